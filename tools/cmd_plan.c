/* unstack plan: find a stable unstacking order and write it as a plan file. */
#include "task.h"

#include <stdio.h>
#include <string.h>

static const char head[] =
    "usage: unstack plan FILE [-o PLAN.json] [options]\n"
    "\n"
    "Find an order that takes the structure in FILE apart one body at a time\n"
    "(or a few, --max-group) so that every intermediate structure stands, or\n"
    "prove there is none (docs/planning.md). Prints a one-line summary; writes\n"
    "the plan (docs/format.md) with -o.\n";
static const char tail[] =
    "exit: 0 order found, 1 no order (none, unstable, limit), 2 usage or input\n"
    "error, 3 undecided (no order found, and none or unstable would rest on\n"
    "stability tests that could not be decided)\n";

static void print_stats(FILE *fp, const us_PlanStats *st) {
  fprintf(fp, "statistics:\n  tests %ld (stable %ld, unstable %ld, undecided %ld), revisited %ld, "
         "expanded %ld, max depth %ld\n",
         st->tests, st->stable, st->unstable, st->undecided, st->revisited, st->nodes_expanded,
         st->max_depth);
  fprintf(fp, "  backtracks %ld; rules: ground saved %ld tests, union saved %ld, exact checks %ld, "
         "greedy checks %ld, components %ld\n",
         st->backtracks, st->saved_ground, st->saved_union, st->exact_checks, st->greedy_checks,
         st->components);
  fprintf(fp, "  assembly: retries skipped %ld, sets searched exhaustively %ld, proven unbuildable "
         "by a cut %ld (%ld held tests); restarts %ld\n",
         st->retries_skipped, st->exhaustive, st->cuts, st->held_tests, st->restarts);
  fprintf(fp, "  time: total %.6f s, setup %.6f s, search %.6f s, in solver %.6f s, "
         "certificate checks %.6f s\n",
         st->time_total, st->time_setup, st->time_search, st->time_solve, st->time_check);
  fprintf(fp, "  memo %zu bytes\n", st->memo_bytes);
  cli_print_solver_stats(&st->stability);
  cli_print_local_stats(&st->stability);
}

/* Up to `max` ids of a list, then "and N more". */
static void print_ids(FILE *fp, const us_Structure *s, const int *v, int n, int max) {
  for (int k = 0; k < n && k < max; k++) fprintf(fp, "%s%s",
                                                k ? ", " : "", us_id_text(s->bodies[v[k]].id).s);
  if (n > max) fprintf(fp, " and %d more", n - max);
}

/* Why no answer is proven, and what the greedy reached. */
static void print_undecided(FILE *fp, const us_Structure *s, const us_Plan *p) {
  fprintf(fp, "  %ld stability test%s could not be decided (taken as not standing); the first: %s\n",
         p->stats.undecided, p->stats.undecided == 1 ? "" : "s", p->note);
  if (!p->blocked) return;
  fprintf(fp, "  the greedy placed %d of %d bodies; not reached: ", p->nbuildable,
         p->nbuildable + p->nblocked);
  print_ids(fp, s, p->blocked, p->nblocked, 20);
  fprintf(fp, "\n");
}

/* What is proven about the number of hands. */
static void print_hands(FILE *fp, const us_Structure *s, const us_Plan *p, int asked) {
  if (p->status == US_PLAN_FOUND && asked == 0 && p->hands_lower >= p->hands)
    fprintf(fp, "  %d hand%s: the minimum (proven)\n", p->hands, p->hands == 1 ? "" : "s");
  else if (p->status == US_PLAN_FOUND && asked == 0)
    fprintf(fp, "  %d hands, not proven minimal: %d%s%.0d not proven impossible (budget: "
            "--exact-tests, --time-limit)\n", p->hands, p->hands_lower,
            p->hands - 1 > p->hands_lower ? " to " : "",
            p->hands - 1 > p->hands_lower ? p->hands - 1 : 0);
  else if (p->status == US_PLAN_NONE && p->blocked) {
    fprintf(fp, "  proven: %d hand%s cannot build the part of ", asked, asked == 1 ? "" : "s");
    print_ids(fp, s, p->blocked, p->nblocked, 20);
    fprintf(fp, "\n");
  }
}

static void print_summary(FILE *fp, const us_Structure *s, const us_Plan *p, const CliCommon *c,
                          const char *out) {
  const us_PlanStats *st = &p->stats;
  fprintf(fp, "%s", us_plan_status_name(p->status));
  if (p->status == US_PLAN_FOUND && p->actions)
    fprintf(fp, ": %d actions with %d hand%s", p->nactions, p->hands, p->hands == 1 ? "" : "s");
  else if (p->status == US_PLAN_FOUND && p->ngroups == p->nsteps)
    fprintf(fp, ": %d removals", p->nsteps);
  else if (p->status == US_PLAN_FOUND)
    fprintf(fp, ": %d removals in %d step%s of up to %d bodies", p->nsteps, p->ngroups,
           p->ngroups == 1 ? "" : "s", p->max_group);
  fprintf(fp, ", %ld tests (%ld unstable, %ld revisited), %.3f s [%s, %s", st->tests, st->unstable,
         st->revisited, st->time_total, us_method_name(us_method_resolve(c->stab.method, s)),
         us_search_name(c->plan.search));
  if (c->plan.search != US_SEARCH_ASSEMBLE)
    fprintf(fp, ", %s, %s", us_order_name(c->plan.order), us_direction_name(c->plan.direction));
  if (c->plan.removal != US_REMOVAL_ANY) fprintf(fp, ", removal %s", us_removal_name(c->plan.removal));
  fprintf(fp, "]");
  if (out) fprintf(fp, " -> %s", out);
  fprintf(fp, "\n");
  if (p->status == US_PLAN_LIMIT && p->blocked) {
    fprintf(fp, "  the greedy was stuck with %d of %d bodies placed, and the exact decision was "
           "cut (--exact-tests, --max-tests, --time-limit);\n  not reached by the greedy: ",
           p->nbuildable, p->nbuildable + p->nblocked);
    print_ids(fp, s, p->blocked, p->nblocked, 20);
    fprintf(fp, "\n");
  }
  if (p->status == US_PLAN_UNDECIDED) print_undecided(fp, s, p);
  if (c->plan.hands != 1) print_hands(fp, s, p, c->plan.hands);
  if (p->status == US_PLAN_NONE && p->blocked) {
    fprintf(fp, "  cannot be removed with steps of up to %d bod%s: ", p->max_group > 0 ? p->max_group : 1,
           p->max_group > 1 ? "ies" : "y");
    print_ids(fp, s, p->blocked, p->nblocked, 20);
    fprintf(fp, "\n  a maximal buildable sub-assembly (the greedy's) has %d of %d bodies\n", p->nbuildable,
           p->nbuildable + p->nblocked);
  }
}

/* --print: "K<TAB>id[<TAB>id...]" per step; a none plan's build order. */
static void print_steps(FILE *fp, const us_Structure *s, const us_Plan *p) {
  int build = p->status != US_PLAN_FOUND;
  const int *v = build ? p->buildable : p->order, *start = build ? p->build_start : p->group_start;
  int nsteps = build ? (start ? p->nbuild : 0) : (start ? p->ngroups : p->nsteps);
  if (build && v) fprintf(fp, "build order of the buildable part (the greedy's placements):\n");
  for (int k = 0; v && k < nsteps; k++) {
    fprintf(fp, "%d", k + 1);
    for (int q = start ? start[k] : k; q < (start ? start[k + 1] : k + 1); q++)
      fprintf(fp, "\t%s", us_id_text(s->bodies[v[q]].id).s);
    fputc('\n', fp);
  }
}

/* -o -: the plan through a scratch file, so that an error leaves stdout
 * empty. */
static us_Status write_stdout(const us_Structure *s, const us_Plan *p, const CliCommon *c,
                              us_Error *err) {
  FILE *tmp = tmpfile();
  if (!tmp) return us_error_set(err, US_ERR_IO, "-: cannot open a scratch file");
  us_Status st = us_plan_write_stream(s, p, &c->plan, tmp, "-", err);
  char buf[8192];
  size_t n;
  if (!st) rewind(tmp);
  while (!st && (n = fread(buf, 1, sizeof buf, tmp)) > 0)
    if (fwrite(buf, 1, n, stdout) != n) st = us_error_set(err, US_ERR_IO, "-: write error");
  if (!st && fflush(stdout)) st = us_error_set(err, US_ERR_IO, "-: write error");
  fclose(tmp);
  return st;
}

static us_Status write_plan(const us_Structure *s, const us_Plan *p, const CliCommon *c,
                            const char *out, us_Error *err) {
  if (!out) return US_OK;
  if (!strcmp(out, "-")) return write_stdout(s, p, c, err);
  return us_plan_write(s, p, &c->plan, out, err);
}

/* --max-group K: 'auto' (0) or 1..64. */
static int set_max_group(const char *v, void *dst, const char *cmd) {
  long n;
  if (!strcmp(v, "auto")) return *(int *)dst = 0, 0;
  if (cli_parse_long(v, &n) || n < 1 || n > 64)
    return cli_fail(cmd, "--max-group needs 'auto' or an integer from 1 to 64, got '%s'", v);
  return *(int *)dst = (int)n, 0;
}

/* --hands H: 'auto' (0) or 1..64. */
static int set_hands(const char *v, void *dst, const char *cmd) {
  long n;
  if (!strcmp(v, "auto")) return *(int *)dst = 0, 0;
  if (cli_parse_long(v, &n) || n < 1 || n > 64)
    return cli_fail(cmd, "--hands needs 'auto' or an integer from 1 to 64, got '%s'", v);
  return *(int *)dst = (int)n, 0;
}

static int set_rules(const char *v, void *dst, const char *cmd) {
  if (us_rules_parse(v, dst))
    return cli_fail(cmd, "unknown rules '%s' (all, none, or a comma list of memo, ground, union, "
                    "components, greedy)", v);
  return 0;
}

/* plan's option table (optable.h), shared with batch (task.h). */
void cli_plan_table(CliCommon *c, PlanArgs *a, CliOpt *out) {
  us_PlanSettings *p = &c->plan;
  /* One entry per option, in --help's order; optable.h says how to add one. */
  const CliOpt opts[] = {
      CLI_TEXT("--output", "PLAN", &a->out, "write the plan file (also when no order exists); "
               "'-o -' writes it to stdout (the summary then goes to stderr)", .alias = "-o"),
      CLI_FLAG("--print", &a->print, "list the steps, one per line: the step number and the ids "
               "it removes (a none plan: its build order)"),
      CLI_OPT_METHOD(c),
      CLI_OPT_LOCAL(c),
      CLI_OPT_SEARCH(c),
      CLI_CALL("--max-group", "K", &p->max_group, set_max_group,
               "steps of up to K bodies at once (assemble); 'auto': the smallest K that gives an "
               "order (default 1)"),
      CLI_CALL("--hands", "H", &p->hands, set_hands,
               "build with up to H bodies held still at once (place, grab, release; "
               "docs/planning.md, \"Hands\"); 'auto': the smallest H, proven where the budget "
               "allows (default 1: one body at a time)"),
      CLI_ENUM("--removal", "R", &p->removal,
               "any (default), up (lifted straight up without hitting a body that stays), free "
               "(some translation frees it); up and free need a graph search",
               .parse = cli_parse_removal, .word = cli_removal_word, .what = "removal"),
      CLI_OPT_ORDER(c),
      CLI_OPT_DIRECTION(c),
      CLI_CALL("--rules", "LIST", &p->rules, set_rules,
               "culling rules of the graph searches: all (default), none, or a comma list of "
               "memo, ground, union, components, greedy"),
      CLI_ULONG("--seed", "S", &p->seed, "random search seed (default 1)", CLI_ATLEAST(0)),
      CLI_LONG("--max-tests", "N", &p->max_tests, "stop after N stability tests (status "
               "\"limit\")", CLI_ATLEAST(1)),
      CLI_LONG("--exact-tests", "N", &p->max_exact_tests,
               "tests one exact decision may use where the greedy is stuck (default 100000, 0: "
               "no limit; status \"limit\")", CLI_ATLEAST(0),
               .need = "a non-negative integer (0: no limit)"),
      CLI_OPT_TIME_LIMIT(&p->time_limit, "stop after S seconds (status \"limit\")"),
      CLI_FLAG("--certificates", &p->certificates, "store the contact forces of every step in "
               "the plan"),
      CLI_OPT_STATS(&a->stats, "print the search statistics"),
      CLI_OPT_CONTACT_TOL(c),
      CLI_END};
  _Static_assert(sizeof opts / sizeof opts[0] <= CLI_TABLE_MAX, "CLI_TABLE_MAX too small");
  memcpy(out, opts, sizeof opts);
}

/* The command line, by plan's option table. */
static int parse(int argc, char **argv, CliCommon *c, PlanArgs *a) {
  CliOpt opts[CLI_TABLE_MAX];
  cli_plan_table(c, a, opts);
  const CliSpec spec = {"plan", head, tail, opts, &a->file, 1, "more than one FILE given"};
  int r = cli_parse(&spec, argc, argv);
  if (!r && !a->file) return cli_fail("plan", "no FILE given (see 'unstack plan --help')");
  if (!r && (a->print || a->stats) && a->out && !strcmp(a->out, "-"))
    return cli_fail("plan", "%s and -o - both write to stdout: choose one",
                    a->print ? "--print" : "--stats");
  return r;
}

us_Status cli_plan_run(const us_Structure *s, const CliCommon *c, double time_limit, us_Plan *p,
                       us_Error *err) {
  us_PlanSettings set = c->plan;
  set.stability = c->stab;
  set.time_limit = time_limit;
  return us_plan(s, &set, p, err);
}

int cli_plan_exit(const us_Plan *p) {
  return p->status == US_PLAN_FOUND       ? CLI_EXIT_OK
         : p->status == US_PLAN_UNDECIDED ? CLI_EXIT_UNDECIDED
                                          : CLI_EXIT_NO;
}

/* Which way the search goes, for the progress line. */
static CliProgressMode progress_mode(const us_PlanSettings *p) {
  return p->search != US_SEARCH_ASSEMBLE && p->direction == US_DIR_DOWN
             ? CLI_PROGRESS_REMOVE
             : CLI_PROGRESS_BUILD;
}

int cmd_plan(int argc, char **argv) {
  CliCommon c;
  cli_common_init(&c);
  PlanArgs a = {NULL, NULL, 0, 0};
  int r = parse(argc, argv, &c, &a);
  if (r) return r < 0 ? CLI_EXIT_OK : r;
  int to_stdout = a.out && !strcmp(a.out, "-");
  if (a.out && !to_stdout && cli_check_output("plan", a.out, &a.file, 1)) return CLI_EXIT_ERR;
  int load;
  us_Structure *s = cli_load("plan", a.file, &c, c.plan.time_limit, &load);
  if (!s) return load;
  cli_progress_on("plan", &c, progress_mode(&c.plan), us_structure_movable_count(s));
  us_Error err;
  us_error_clear(&err);
  us_Plan p;
  int code = CLI_EXIT_ERR;
  us_Status pst = cli_plan_run(s, &c, cli_time_left(c.plan.time_limit), &p, &err);
  cli_progress_off(&c);
  if (pst == US_OK) {
    if (write_plan(s, &p, &c, a.out, &err) == US_OK) {
      FILE *info = to_stdout ? stderr : stdout;
      print_summary(info, s, &p, &c, to_stdout ? "stdout" : a.out);
      if (a.stats) print_stats(info, &p.stats);
      if (a.print) print_steps(stdout, s, &p);
      code = cli_plan_exit(&p);
    }
    us_plan_free(&p);
  }
  if (code == CLI_EXIT_ERR) cli_error("plan", &err);
  us_structure_free(s);
  return code;
}
