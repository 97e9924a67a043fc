/* unstack count: the number of connected sub-assemblies containing the
 * ground, an upper bound on the stability tests a disassembly search needs. */
#include "options.h"

#include <stdio.h>
#include <string.h>

static const char head[] =
    "usage: unstack count FILE [options]\n"
    "\n"
    "Count the subsets S of the movable bodies such that S and the ground form a\n"
    "connected part of the contact graph (fixed bodies count as ground; the empty\n"
    "S counts). A search that skips sub-assemblies not connected to the ground and\n"
    "remembers its verdicts tests no other sub-assembly, none twice: the count\n"
    "bounds its number of stability tests. Exact, in decimal (docs/count.md).\n";
static const char tail[] =
    "exit: 0 counted, 1 refused (a limit was reached), 2 usage or input error\n";

typedef struct CountArgs {
  CliCommon common;
  us_CountSettings set;
  const char *file;
  int json;
} CountArgs;

/* -1: help printed (exit 0); else 0 or CLI_EXIT_ERR. By count's option
 * table (optable.h). */
static int parse_args(int argc, char **argv, CountArgs *a) {
  /* One entry per option, in --help's order; optable.h says how to add one. */
  const CliOpt opts[] = {
      CLI_FLAG("--json", &a->json, "print a JSON object (the count as a string)"),
      CLI_REAL("--time-limit", "S", &a->set.time_limit,
               "give up after S seconds (default 10; 0: no limit)", CLI_ATLEAST(0),
               .need = "a number >= 0"),
      CLI_INT("--max-bodies", "N", &a->set.max_bodies,
              "refuse the general algorithm past N bodies connected to the ground (default "
              "10000; trees: up to 1000000)", CLI_RANGE(1, 100000000)),
      CLI_ENUM("--method", "M", &a->set.method,
               "auto (default: tree formula for a tree, else frontier), tree, frontier, contract "
               "(deletion-contraction)",
               .parse = cli_parse_count_method, .word = cli_count_method_word, .what = "method"),
      CLI_OPT_CONTACT_TOL(&a->common),
      CLI_END};
  const CliSpec spec = {"count", head, tail, opts, &a->file, 1, "more than one FILE given"};
  int r = cli_parse(&spec, argc, argv);
  if (!r && !a->file) return cli_fail("count", "no FILE given (see 'unstack count --help')");
  return r;
}

static void print_text(const us_Count *c) {
  if (c->status == US_COUNT_EXACT)
    printf("count: %s connected sub-assemblies containing the ground (", c->value);
  else
    printf("count: refused, %s (", c->note);
  printf("%s", us_count_method_name(c->method)); /* the word --method takes */
  if (c->method == US_COUNT_FRONTIER) printf(", width %d", c->width);
  printf(", %d bodies", c->nbody);
  if (c->nconnected != c->nbody) printf(" (%d connected to the ground)", c->nconnected);
  printf(", %d edges, %.3f s)\n", c->nedge, c->seconds);
}

/* Our notes hold no control characters; quotes and backslashes escaped. */
static void print_json_string(const char *s) {
  putchar('"');
  for (; *s; s++) {
    if (*s == '"' || *s == '\\') putchar('\\');
    putchar(*s);
  }
  putchar('"');
}

static void print_json(const us_Count *c) {
  printf("{\"count\": ");
  if (c->value) print_json_string(c->value);
  else printf("null");
  printf(", \"status\": \"%s\", \"exact\": %s, \"method\": \"%s\", \"tree\": %s",
         us_count_status_name(c->status), c->status == US_COUNT_EXACT ? "true" : "false",
         us_count_method_name(c->method), c->is_tree ? "true" : "false");
  printf(", \"bodies\": %d, \"connected\": %d, \"edges\": %d, \"width\": %d", c->nbody,
         c->nconnected, c->nedge, c->width);
  printf(", \"digits\": %d, \"work\": %ld, \"peak\": %ld, \"seconds\": %.6f, \"note\": ",
         c->value ? (int)strlen(c->value) : 0, c->work, c->peak, c->seconds);
  print_json_string(c->note);
  printf("}\n");
}

int cmd_count(int argc, char **argv) {
  CountArgs a;
  memset(&a, 0, sizeof a);
  cli_common_init(&a.common);
  a.set = us_count_default_settings();
  int r = parse_args(argc, argv, &a);
  if (r) return r < 0 ? CLI_EXIT_OK : r;
  int load;
  us_Structure *s = cli_load("count", a.file, &a.common, a.set.time_limit, &load);
  if (!s) return load;
  us_Error err;
  us_error_clear(&err);
  us_Count c;
  int code = CLI_EXIT_ERR;
  if (us_count_subgraphs(s, &a.set, &c, &err) == US_OK) {
    if (a.json) print_json(&c);
    else print_text(&c);
    code = c.status == US_COUNT_EXACT ? CLI_EXIT_OK : CLI_EXIT_NO;
  } else {
    cli_error("count", &err);
  }
  us_count_free(&c);
  us_structure_free(s);
  return code;
}
