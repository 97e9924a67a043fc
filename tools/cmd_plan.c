/* unstack plan: find a stable unstacking order and write it as a plan file. */
#include "options.h"

#include <stdio.h>
#include <string.h>

static const char help[] =
    "usage: unstack plan FILE [-o PLAN.json] [options]\n"
    "\n"
    "Search the disassembly graph of the structure in FILE for an order that\n"
    "removes one body at a time so that every intermediate structure stands.\n"
    "Prints a one-line summary; writes the plan (docs/format.md) with -o.\n"
    "\n"
    "options:\n"
    "  -o, --output PLAN   write the plan file (also when no order exists)\n"
    "  --method M          auto (default), lp (CLP), lpsolve, lcp, lcp-reuse, lp-lcp\n"
    "  --local on|off        exact local tests for lp and auto (default on)\n"
    "  --search S          assemble (default): greedy assembly from the ground,\n"
    "                      complete by the union theorem (at most n(n+1)/2 tests;\n"
    "                      'none' is a proof); dfs, bfs: the source's searches of\n"
    "                      the disassembly graph; random: DFS with random order\n"
    "                      and restarts (--seed)\n"
    "  --max-group K       steps of up to K bodies at once (assemble); 'auto': the\n"
    "                      smallest K that gives an order (default 1)\n"
    "  --removal R         any (default), up (lifted straight up without hitting\n"
    "                      a body that stays), free (some translation frees it);\n"
    "                      up and free need a graph search\n"
    "  --order O           graph searches: highest (default), lowest, input\n"
    "  --direction D       graph searches: down (disassembly, default) or up\n"
    "                      (assembly; the plan is its reverse)\n"
    "  --rules LIST        culling rules of the graph searches: all (default),\n"
    "                      none, or a comma list of memo, ground, union,\n"
    "                      components, greedy\n"
    "  --seed S            random search seed (default 1)\n"
    "  --max-tests N       stop after N stability tests (status \"limit\")\n"
    "  --exact-tests N     tests one exact decision may use where the greedy is\n"
    "                      stuck (default 100000, 0: no limit; status \"limit\")\n"
    "  --time-limit SEC    stop after SEC seconds (status \"limit\")\n"
    "  --certificates      store the contact forces of every step in the plan\n"
    "  --stats             print the search statistics\n"
    "  --contact-tol T     contact detection tolerance (default 1e-6 x size)\n"
    "\n"
    "exit: 0 order found, 1 no order (none, unstable, limit), 2 usage or input\n"
    "error, 3 undecided (no order found, and none or unstable would rest on\n"
    "stability tests that could not be decided)\n";

static void print_stats(const us_PlanStats *st) {
  printf("statistics:\n  tests %ld (stable %ld, unstable %ld, undecided %ld), revisited %ld, "
         "expanded %ld, max depth %ld\n",
         st->tests, st->stable, st->unstable, st->undecided, st->revisited, st->nodes_expanded,
         st->max_depth);
  printf("  backtracks %ld; rules: ground saved %ld tests, union saved %ld, exact checks %ld, "
         "greedy checks %ld, components %ld\n",
         st->backtracks, st->saved_ground, st->saved_union, st->exact_checks, st->greedy_checks,
         st->components);
  printf("  assembly: retries skipped %ld, sets searched exhaustively %ld, proven unbuildable "
         "by a cut %ld (%ld held tests); restarts %ld\n",
         st->retries_skipped, st->exhaustive, st->cuts, st->held_tests, st->restarts);
  printf("  time: total %.6f s, setup %.6f s, search %.6f s, in solver %.6f s, "
         "certificate checks %.6f s\n",
         st->time_total, st->time_setup, st->time_search, st->time_solve, st->time_check);
  printf("  memo %zu bytes; LCP pivots %ld, LP fallbacks %ld (re-seeded %ld, LCP skipped %ld), "
         "reused %ld; cone Lemke settled %ld, failed %ld\n",
         st->memo_bytes, st->stability.pivots, st->stability.lp_fallbacks,
         st->stability.lcp_seeds, st->stability.lcp_skips, st->stability.reused,
         st->stability.cone_lemke, st->stability.cone_lemke_failed);
  cli_print_local_stats(&st->stability);
}

/* Up to `max` ids of a list, then "and N more". */
static void print_ids(const us_Structure *s, const int *v, int n, int max) {
  for (int k = 0; k < n && k < max; k++) printf("%s%s",
                                                k ? ", " : "", us_id_text(s->bodies[v[k]].id).s);
  if (n > max) printf(" and %d more", n - max);
}

/* Why no answer is proven, and what the greedy reached. */
static void print_undecided(const us_Structure *s, const us_Plan *p) {
  printf("  %ld stability test%s could not be decided (taken as not standing); the first: %s\n",
         p->stats.undecided, p->stats.undecided == 1 ? "" : "s", p->note);
  if (!p->blocked) return;
  printf("  the greedy placed %d of %d bodies; not reached: ", p->nbuildable,
         p->nbuildable + p->nblocked);
  print_ids(s, p->blocked, p->nblocked, 20);
  printf("\n");
}

static void print_summary(const us_Structure *s, const us_Plan *p, const CliCommon *c,
                          const char *out) {
  const us_PlanStats *st = &p->stats;
  printf("%s", us_plan_status_name(p->status));
  if (p->status == US_PLAN_FOUND && p->ngroups == p->nsteps)
    printf(": %d removals", p->nsteps);
  else if (p->status == US_PLAN_FOUND)
    printf(": %d removals in %d step%s of up to %d bodies", p->nsteps, p->ngroups,
           p->ngroups == 1 ? "" : "s", p->max_group);
  printf(", %ld tests (%ld unstable, %ld revisited), %.3f s [%s, %s", st->tests, st->unstable,
         st->revisited, st->time_total, us_method_name(us_method_resolve(c->stab.method, s)),
         us_search_name(c->plan.search));
  if (c->plan.search != US_SEARCH_ASSEMBLE)
    printf(", %s, %s", us_order_name(c->plan.order), us_direction_name(c->plan.direction));
  if (c->plan.removal != US_REMOVAL_ANY) printf(", removal %s", us_removal_name(c->plan.removal));
  printf("]");
  if (out) printf(" -> %s", out);
  printf("\n");
  if (p->status == US_PLAN_LIMIT && p->blocked) {
    printf("  the greedy was stuck with %d of %d bodies placed, and the exact decision was "
           "cut (--exact-tests, --max-tests, --time-limit);\n  not reached by the greedy: ",
           p->nbuildable, p->nbuildable + p->nblocked);
    print_ids(s, p->blocked, p->nblocked, 20);
    printf("\n");
  }
  if (p->status == US_PLAN_UNDECIDED) print_undecided(s, p);
  if (p->status == US_PLAN_NONE && p->blocked) {
    printf("  cannot be removed with steps of up to %d bod%s: ", p->max_group > 0 ? p->max_group : 1,
           p->max_group > 1 ? "ies" : "y");
    print_ids(s, p->blocked, p->nblocked, 20);
    printf("\n  a maximal buildable sub-assembly (the greedy's) has %d of %d bodies\n", p->nbuildable,
           p->nbuildable + p->nblocked);
  }
}

typedef struct {
  const char *file, *out;
  int stats;
} PlanArgs;

static int parse(int argc, char **argv, CliCommon *c, PlanArgs *a) {
  for (int i = 1; i < argc; i++) {
    int r = cli_common_option("plan", argc, argv, &i, c);
    const char *v;
    long n;
    if (r < 0) return CLI_EXIT_ERR;
    if (r) continue;
    if (cli_is_help(argv[i])) return fputs(help, stdout), -1;
    if (!strcmp(argv[i], "-o") || !strcmp(argv[i], "--output")) {
      if (!(a->out = cli_value("plan", argc, argv, &i))) return CLI_EXIT_ERR;
    } else if (!strcmp(argv[i], "--max-tests")) {
      if (!(v = cli_value("plan", argc, argv, &i))) return CLI_EXIT_ERR;
      if (cli_parse_long(v, &n) || n <= 0)
        return cli_fail("plan", "--max-tests needs a positive integer, got '%s'", v);
      c->plan.max_tests = n;
    } else if (!strcmp(argv[i], "--time-limit")) {
      if (!(v = cli_value("plan", argc, argv, &i))) return CLI_EXIT_ERR;
      if (cli_parse_double(v, &c->plan.time_limit) || c->plan.time_limit <= 0)
        return cli_fail("plan", "--time-limit needs a positive number of seconds, got '%s'", v);
    } else if (!strcmp(argv[i], "--max-group")) {
      if (!(v = cli_value("plan", argc, argv, &i))) return CLI_EXIT_ERR;
      if (!strcmp(v, "auto")) c->plan.max_group = 0;
      else if (cli_parse_long(v, &n) || n < 1 || n > 64)
        return cli_fail("plan", "--max-group needs 'auto' or an integer from 1 to 64, got '%s'", v);
      else c->plan.max_group = (int)n;
    } else if (!strcmp(argv[i], "--removal")) {
      if (!(v = cli_value("plan", argc, argv, &i))) return CLI_EXIT_ERR;
      if (us_removal_parse(v, &c->plan.removal))
        return cli_unknown("plan", "removal", v, cli_removal_word);
    } else if (!strcmp(argv[i], "--rules")) {
      if (!(v = cli_value("plan", argc, argv, &i))) return CLI_EXIT_ERR;
      if (us_rules_parse(v, &c->plan.rules))
        return cli_fail("plan", "unknown rules '%s' (all, none, or a comma list of memo, "
                        "ground, union, components, greedy)", v);
    } else if (!strcmp(argv[i], "--seed")) {
      if (!(v = cli_value("plan", argc, argv, &i))) return CLI_EXIT_ERR;
      if (cli_parse_long(v, &n) || n < 0)
        return cli_fail("plan", "--seed needs a non-negative integer, got '%s'", v);
      c->plan.seed = (unsigned long)n;
    } else if (!strcmp(argv[i], "--exact-tests")) {
      if (!(v = cli_value("plan", argc, argv, &i))) return CLI_EXIT_ERR;
      if (cli_parse_long(v, &n) || n < 0)
        return cli_fail("plan", "--exact-tests needs a non-negative integer (0: no limit), got '%s'", v);
      c->plan.max_exact_tests = n;
    } else if (!strcmp(argv[i], "--certificates")) {
      c->plan.certificates = 1;
    } else if (!strcmp(argv[i], "--stats")) {
      a->stats = 1;
    } else if (argv[i][0] == '-' && argv[i][1]) {
      return cli_fail("plan", "unknown option '%s'", argv[i]);
    } else if (a->file) {
      return cli_fail("plan", "more than one FILE given");
    } else {
      a->file = argv[i];
    }
  }
  if (!a->file) return cli_fail("plan", "no FILE given (see 'unstack plan --help')");
  return 0;
}

int cmd_plan(int argc, char **argv) {
  CliCommon c;
  cli_common_init(&c);
  PlanArgs a = {NULL, NULL, 0};
  int r = parse(argc, argv, &c, &a);
  if (r) return r < 0 ? CLI_EXIT_OK : r;
  cli_progress_on("plan", &c);
  c.plan.stability = c.stab;
  if (a.out && cli_check_output("plan", a.out, &a.file, 1)) return CLI_EXIT_ERR;
  int load;
  us_Structure *s = cli_load("plan", a.file, &c, c.plan.time_limit, &load);
  if (!s) return load;
  us_Error err;
  us_error_clear(&err);
  us_Plan p;
  int code = CLI_EXIT_ERR;
  c.plan.time_limit = cli_time_left(c.plan.time_limit);
  us_Status pst = us_plan(s, &c.plan, &p, &err);
  cli_progress_off(&c);
  if (pst == US_OK) {
    if (!a.out || us_plan_write(s, &p, &c.plan, a.out, &err) == US_OK) {
      print_summary(s, &p, &c, a.out);
      if (a.stats) print_stats(&p.stats);
      code = p.status == US_PLAN_FOUND       ? CLI_EXIT_OK
             : p.status == US_PLAN_UNDECIDED ? CLI_EXIT_UNDECIDED
                                             : CLI_EXIT_NO;
    }
    us_plan_free(&p);
  }
  if (code == CLI_EXIT_ERR) cli_error("plan", &err);
  us_structure_free(s);
  return code;
}
