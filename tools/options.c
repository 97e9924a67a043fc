/* Option values shared by several subcommands: enum names and the
 * structure-loading options. */
#include "options.h"

#include <stdio.h>
#include <string.h>

static int parse_enum(const char *s, const char *const *names, int n, int *out) {
  for (int i = 0; i < n; i++)
    if (!strcmp(s, names[i])) {
      *out = i;
      return 0;
    }
  return -1;
}

const char *const cli_search_names[] = {"dfs", "bfs"};
const char *const cli_order_names[] = {"highest", "lowest", "input"};
const char *const cli_direction_names[] = {"down", "up"};

/* Returns 1 if argv[*i] was a common option (consumed), 0 if not, -1 on a
 * bad value (message printed). */
int cli_common_option(const char *cmd, int argc, char **argv, int *i, CliCommon *c) {
  const char *a = argv[*i], *v;
  int e;
  if (!strcmp(a, "--method")) {
    if (!(v = cli_value(cmd, argc, argv, i))) return -1;
    us_Method m;
    if (us_method_parse(v, &m))
      return cli_fail(cmd, "unknown method '%s' (lp, lpsolve, lcp, lcp-reuse)", v), -1;
    c->stab.method = m;
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
    if (parse_enum(v, cli_search_names, 2, &e))
      return cli_fail(cmd, "unknown search '%s' (dfs, bfs)", v), -1;
    c->plan.search = (us_Search)e;
    return 1;
  }
  if (!strcmp(a, "--order")) {
    if (!(v = cli_value(cmd, argc, argv, i))) return -1;
    if (parse_enum(v, cli_order_names, 3, &e))
      return cli_fail(cmd, "unknown order '%s' (highest, lowest, input)", v), -1;
    c->plan.order = (us_Order)e;
    return 1;
  }
  if (!strcmp(a, "--direction")) {
    if (!(v = cli_value(cmd, argc, argv, i))) return -1;
    if (parse_enum(v, cli_direction_names, 2, &e))
      return cli_fail(cmd, "unknown direction '%s' (down, up)", v), -1;
    c->plan.direction = (us_Direction)e;
    return 1;
  }
  return 0;
}

void cli_common_init(CliCommon *c) {
  memset(c, 0, sizeof *c);
  c->plan = us_plan_default_settings();
  c->stab = us_stability_default_settings();
}

us_Structure *cli_load(const char *cmd, const char *path, const CliCommon *c) {
  us_Error err;
  us_error_clear(&err);
  us_Structure *s = us_structure_read(path, c->contact_tol, &err);
  if (!s) cli_error(cmd, &err);
  return s;
}
