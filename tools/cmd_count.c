/* unstack count: the number of connected sub-assemblies containing the
 * ground, an upper bound on the stability tests a disassembly search needs. */
#include "options.h"

#include <stdio.h>
#include <string.h>

static const char help[] =
    "usage: unstack count FILE [options]\n"
    "\n"
    "Count the subsets S of the movable bodies such that S and the ground form a\n"
    "connected part of the contact graph (fixed bodies count as ground; the empty\n"
    "S counts). A search that skips sub-assemblies not connected to the ground and\n"
    "remembers its verdicts tests no other sub-assembly, none twice: the count\n"
    "bounds its number of stability tests. Exact, in decimal (docs/count.md).\n"
    "\n"
    "options:\n"
    "  --json            print a JSON object (the count as a string)\n"
    "  --time-limit S    give up after S seconds (default 10; 0: no limit)\n"
    "  --max-bodies N    refuse the general algorithm past N bodies connected to\n"
    "                    the ground (default 10000; trees: up to 1000000)\n"
    "  --method M        auto (default: tree formula for a tree, else frontier),\n"
    "                    tree, frontier, contract (deletion-contraction)\n"
    "  --contact-tol T   contact detection tolerance (default 1e-6 x size)\n"
    "\n"
    "exit: 0 counted, 1 refused (a limit was reached), 2 usage or input error\n";

typedef struct CountArgs {
  CliCommon common;
  us_CountSettings set;
  const char *file;
  int json;
} CountArgs;

/* One option of count's own; 0 done, CLI_EXIT_ERR on a bad value. */
static int own_option(int argc, char **argv, int *i, CountArgs *a) {
  const char *name = argv[*i], *v;
  long n;
  if (!strcmp(name, "--json")) return a->json = 1, 0;
  if (!(v = cli_value("count", argc, argv, i))) return CLI_EXIT_ERR;
  if (!strcmp(name, "--time-limit")) {
    if (cli_parse_double(v, &a->set.time_limit) || a->set.time_limit < 0)
      return cli_fail("count", "--time-limit needs a number >= 0, got '%s'", v);
  } else if (!strcmp(name, "--max-bodies")) {
    if (cli_parse_long(v, &n) || n < 1 || n > 100000000)
      return cli_fail("count", "--max-bodies needs a positive integer, got '%s'", v);
    a->set.max_bodies = (int)n;
  } else if (us_count_method_parse(v, &a->set.method)) { /* --method */
    return cli_unknown("count", "method", v, cli_count_method_word);
  }
  return 0;
}

static int is_own(const char *a) {
  return !strcmp(a, "--json") || !strcmp(a, "--time-limit") || !strcmp(a, "--max-bodies") ||
         !strcmp(a, "--method");
}

/* -1: help printed (exit 0); else 0 or CLI_EXIT_ERR. */
static int parse_args(int argc, char **argv, CountArgs *a) {
  for (int i = 1; i < argc; i++) {
    const char *s = argv[i];
    if (cli_is_help(s)) return fputs(help, stdout), -1;
    if (is_own(s)) {
      if (own_option(argc, argv, &i, a)) return CLI_EXIT_ERR;
    } else if (!strcmp(s, "--contact-tol")) {
      if (cli_common_option("count", argc, argv, &i, &a->common) < 0) return CLI_EXIT_ERR;
    } else if (s[0] == '-' && s[1]) {
      return cli_fail("count", "unknown option '%s'", s);
    } else if (a->file) {
      return cli_fail("count", "more than one FILE given");
    } else {
      a->file = s;
    }
  }
  if (!a->file) return cli_fail("count", "no FILE given (see 'unstack count --help')");
  return 0;
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
