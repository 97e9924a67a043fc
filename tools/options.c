/* Option values shared by several subcommands: enum names and the
 * structure-loading options. */
#include "options.h"

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

int cli_unknown(const char *cmd, const char *what, const char *value, CliWord word) {
  char list[200] = "";
  size_t len = 0;
  for (int i = 0; i < 32 && strcmp(word(i), "unknown") && len < sizeof list; i++)
    len += (size_t)snprintf(list + len, sizeof list - len, "%s%s", i ? ", " : "", word(i));
  return cli_fail(cmd, "unknown %s '%s' (%s)", what, value, list);
}

/* Returns 1 if argv[*i] was a common option (consumed), 0 if not, -1 on a
 * bad value (message printed). */
int cli_common_option(const char *cmd, int argc, char **argv, int *i, CliCommon *c) {
  const char *a = argv[*i], *v;
  if (!strcmp(a, "--method")) {
    if (!(v = cli_value(cmd, argc, argv, i))) return -1;
    us_Method m;
    if (us_method_parse(v, &m))
      return cli_unknown(cmd, "method", v, cli_method_word), -1;
    c->stab.method = m;
    return 1;
  }
  if (!strcmp(a, "--local")) {
    if (!(v = cli_value(cmd, argc, argv, i))) return -1;
    if (strcmp(v, "on") && strcmp(v, "off"))
      return cli_fail(cmd, "--local takes on or off (got '%s')", v), -1;
    c->stab.local = strcmp(v, "on") ? -1 : 1;
    return 1;
  }
  if (!strcmp(a, "--contact-tol")) {
    if (!(v = cli_value(cmd, argc, argv, i))) return -1;
    if (cli_parse_double(v, &c->contact_tol) || c->contact_tol <= 0)
      return cli_fail(cmd, "--contact-tol needs a positive number, got '%s'", v), -1;
    return 1;
  }
  if (!strcmp(a, "--search")) {
    if (!(v = cli_value(cmd, argc, argv, i))) return -1;
    if (us_search_parse(v, &c->plan.search))
      return cli_unknown(cmd, "search", v, cli_search_word), -1;
    return 1;
  }
  if (!strcmp(a, "--order")) {
    if (!(v = cli_value(cmd, argc, argv, i))) return -1;
    if (us_order_parse(v, &c->plan.order))
      return cli_unknown(cmd, "order", v, cli_order_word), -1;
    return 1;
  }
  if (!strcmp(a, "--direction")) {
    if (!(v = cli_value(cmd, argc, argv, i))) return -1;
    if (us_direction_parse(v, &c->plan.direction))
      return cli_unknown(cmd, "direction", v, cli_direction_word), -1;
    return 1;
  }
  return 0;
}

void cli_common_init(CliCommon *c) {
  memset(c, 0, sizeof *c);
  c->plan = us_plan_default_settings();
  c->stab = us_stability_default_settings();
}

us_Structure *cli_load(const char *cmd, const char *path, const CliCommon *c, double time_limit,
                       int *code) {
  us_Error err;
  us_error_clear(&err);
  us_LoadSettings set = us_load_default_settings();
  set.contact_tol = c->contact_tol;
  set.deadline = cli_deadline(time_limit);
  us_Structure *s = us_structure_read_with(path, &set, &err);
  *code = s ? CLI_EXIT_OK : CLI_EXIT_ERR;
  if (!s && err.code == US_ERR_TIME_LIMIT) { /* an outcome: nothing decided */
    printf("undecided: loading was cut by the time limit (--time-limit %g): %s\n", time_limit,
           err.msg);
    *code = CLI_EXIT_UNDECIDED;
  }
  else if (!s) cli_error(cmd, &err);
  return s;
}

void cli_print_local_stats(const us_StabilityInfo *in) {
  long settled = in->local_stable + in->local_unstable;
  if (settled + in->local_global == 0) return;
  printf("  local tests: %ld stable (%ld by plumb lines), %ld unstable, %ld on the full system; "
         "%ld region LPs, mean region %.1f bodies\n",
         in->local_stable, in->local_plumb, in->local_unstable, in->local_global, in->local_lps,
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

static void print_progress(const us_Progress *p, void *user) {
  const char *cmd = user;
  double rate = p->elapsed > 0 ? (double)p->tests / p->elapsed : 0.0;
  fprintf(stderr, "\r%s: %ld tests, %d bodies, %.0f tests/s, %.0f s", cmd, p->tests, p->bodies,
          rate, p->elapsed);
  if (p->time_left >= 0) fprintf(stderr, ", %.0f s left", p->time_left);
  fprintf(stderr, "\033[K");
  fflush(stderr);
}

void cli_progress_on(const char *cmd, CliCommon *c) {
  if (!isatty(STDERR_FILENO)) return; /* silent unless a person watches */
  c->stab.progress = print_progress;
  c->stab.progress_user = (void *)cmd;
}

void cli_progress_off(const CliCommon *c) {
  if (c->stab.progress) fprintf(stderr, "\r\033[K");
}

static double clock_start = -1.0;

void cli_clock_start(void) { clock_start = us_now(); }

double cli_deadline(double limit) {
  return limit > 0 && clock_start >= 0 ? clock_start + limit : 0.0;
}

double cli_time_left(double limit) {
  if (!(limit > 0) || clock_start < 0) return limit;
  return fmax(limit - (us_now() - clock_start), 1e-3);
}

int cli_time_limit(const char *cmd, const char *v, CliCommon *c) {
  if (cli_parse_double(v, &c->stab.time_limit) || c->stab.time_limit <= 0)
    return cli_fail(cmd, "--time-limit needs a positive number of seconds, got '%s'", v), -1;
  return 0;
}
