/* What several subcommands share: enum words and parsers for the option
 * tables, structure loading, the statistics lines of --stats, the progress
 * line and the command's clock. */
#include "task.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

/* Enum words come from the library's name tables only (us_*_name), so each
 * word is spelled once in the repository; the words of enum value i, until
 * the table says "unknown". */
const char *cli_method_word(int i) { return us_method_name((us_Method)i); }
const char *cli_search_word(int i) { return us_search_name((us_Search)i); }
const char *cli_order_word(int i) { return us_order_name((us_Order)i); }
const char *cli_direction_word(int i) { return us_direction_name((us_Direction)i); }
const char *cli_removal_word(int i) { return us_removal_name((us_Removal)i); }
const char *cli_count_method_word(int i) { return us_count_method_name((us_CountMethod)i); }

/* Enum values for the option tables: the library's parsers, typed. */
int cli_parse_method(const char *v, void *dst) { return us_method_parse(v, dst); }
int cli_parse_search(const char *v, void *dst) { return us_search_parse(v, dst); }
int cli_parse_order(const char *v, void *dst) { return us_order_parse(v, dst); }
int cli_parse_direction(const char *v, void *dst) { return us_direction_parse(v, dst); }
int cli_parse_removal(const char *v, void *dst) { return us_removal_parse(v, dst); }
int cli_parse_count_method(const char *v, void *dst) { return us_count_method_parse(v, dst); }

int cli_set_local(const char *v, void *dst, const char *cmd) {
  if (strcmp(v, "on") && strcmp(v, "off"))
    return cli_fail(cmd, "--local takes on or off (got '%s')", v);
  *(int *)dst = strcmp(v, "on") ? -1 : 1;
  return 0;
}

void cli_common_init(CliCommon *c) {
  memset(c, 0, sizeof *c);
  c->plan = us_plan_default_settings();
  c->stab = us_stability_default_settings();
}

us_Structure *cli_load_quiet(const char *path, const CliCommon *c, double deadline, us_Error *err) {
  us_LoadSettings set = us_load_default_settings();
  set.contact_tol = c->contact_tol;
  set.deadline = deadline;
  return us_structure_read_with(path, &set, err);
}

us_Structure *cli_load(const char *cmd, const char *path, const CliCommon *c, double time_limit,
                       int *code) {
  us_Error err;
  us_error_clear(&err);
  us_Structure *s = cli_load_quiet(path, c, cli_deadline(time_limit), &err);
  *code = s ? CLI_EXIT_OK : CLI_EXIT_ERR;
  if (!s && err.code == US_ERR_TIME_LIMIT) { /* an outcome: nothing decided */
    printf("undecided: loading was cut by the time limit (--time-limit %g): %s\n", time_limit,
           err.msg);
    *code = CLI_EXIT_UNDECIDED;
  }
  else if (!s) cli_error(cmd, &err);
  return s;
}

void cli_print_solver_stats(const us_StabilityInfo *in) {
  printf("  LCP pivots %ld, LP fallbacks %ld (re-seeded %ld, LCP skipped %ld), reused %ld "
         "(%ld failed repairs retried from scratch); cone Lemke settled %ld, failed %ld\n",
         in->pivots, in->lp_fallbacks, in->lcp_seeds, in->lcp_skips, in->reused, in->lcp_retries,
         in->cone_lemke,
         in->cone_lemke_failed);
  if (in->cone3_outer || in->cone3_refined || in->cone3_open)
    printf("  3D cones: outer-polygon LPs %ld, directions added %ld, claims left to the "
           "certificate %ld\n", in->cone3_outer, in->cone3_refined, in->cone3_open);
  if (in->timed_out) printf("  tests stopped by the time limit: %ld\n", in->timed_out);
}

void cli_print_local_stats(const us_StabilityInfo *in) {
  long settled = in->local_stable + in->local_unstable;
  if (settled + in->local_global == 0) return;
  printf("  local tests: %ld stable (%ld by plumb lines, %ld by levers), %ld unstable, %ld on the "
         "full system (%ld by the sparse simplex); %ld region LPs, mean region %.1f bodies\n",
         in->local_stable, in->local_plumb, in->local_lever, in->local_unstable, in->local_global,
         in->local_global_sparse, in->local_lps,
         settled ? (double)in->local_region_bodies / (double)settled : 0.0);
  printf("  settled by region size:");
  for (int k = 0; k < US_LOCAL_BUCKETS; k++)
    if (in->local_settled[k])
      printf(" %d-%d: %.1f%%", k ? 1 << k : 0, (1 << (k + 1)) - 1,
             100.0 * (double)in->local_settled[k] / (double)(settled + in->local_global));
  if (in->local_global)
    printf(" full: %.1f%%", 100.0 * (double)in->local_global / (double)(settled + in->local_global));
  printf("\n");
}

/* ------------------------------------------------------------ progress */

/* "plan: 45/91 bodies reached (49%), 1234 tests, 120 tests/s, 3 s, 7 s left".
 * The bodies of the sub-assembly just tested go up and down as a search
 * backtracks (and the assembly tests only the component a body joins); the
 * line shows the furthest reached so far, which only grows: the largest
 * sub-assembly tested while building up, the most bodies gone while taking
 * apart, the steps checked by verify. */
void cli_progress_line(char *buf, size_t n, const CliProgress *pr, const us_Progress *p) {
  size_t len = 0;
  int total = pr->total > 0 ? pr->total : 1;
  const char *what = pr->mode == CLI_PROGRESS_STEPS    ? "steps checked"
                     : pr->mode == CLI_PROGRESS_REMOVE ? "bodies removed"
                                                       : "bodies reached";
  double rate = p->elapsed > 0 ? (double)p->tests / p->elapsed : 0.0;
  len += (size_t)snprintf(buf, n, "%s: %d/%d %s (%.0f%%), %ld tests, %.0f tests/s, %.0f s", pr->cmd,
                          pr->reached, pr->total, what, 100.0 * pr->reached / total, p->tests,
                          rate, p->elapsed);
  if (p->time_left >= 0 && len < n) snprintf(buf + len, n - len, ", %.0f s left", p->time_left);
}

/* How far the job got, from one report: monotone whatever the search does. */
static int reached(const CliProgress *pr, const us_Progress *p) {
  int r = pr->mode == CLI_PROGRESS_STEPS    ? (int)p->tests /* one test per step's state */
          : pr->mode == CLI_PROGRESS_REMOVE ? pr->total - p->bodies
          : p->tests > 1                    ? p->bodies
                                            : 0; /* the first test is the full structure's */
  if (r > pr->total) r = pr->total;
  return r > pr->reached ? r : pr->reached;
}

static void print_progress(const us_Progress *p, void *user) {
  CliProgress *pr = user;
  char line[256];
  pr->reached = reached(pr, p);
  cli_progress_line(line, sizeof line, pr, p);
  fprintf(stderr, "\r%s\033[K", line);
  fflush(stderr);
}

void cli_progress_on(const char *cmd, CliCommon *c, CliProgressMode mode, int total) {
  if (!isatty(STDERR_FILENO)) return; /* silent unless a person watches */
  c->progress = (CliProgress){cmd, mode, total, 0};
  c->stab.progress = print_progress;
  c->stab.progress_user = &c->progress;
}

void cli_progress_off(const CliCommon *c) {
  if (c->stab.progress) fprintf(stderr, "\r\033[K");
}

static double clock_start = -1.0;

void cli_clock_start(void) { clock_start = us_now(); }

double cli_elapsed(void) { return clock_start < 0 ? 0.0 : us_now() - clock_start; }

double cli_deadline(double limit) {
  return limit > 0 && clock_start >= 0 ? clock_start + limit : 0.0;
}

double cli_time_left(double limit) {
  if (!(limit > 0) || clock_start < 0) return limit;
  return fmax(limit - (us_now() - clock_start), 1e-3);
}
