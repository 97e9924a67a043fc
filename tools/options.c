/* Option values shared by several subcommands: enum names and the
 * structure-loading options. */
#include "options.h"

#include <stdio.h>
#include <string.h>

/* Returns 1 if argv[*i] was a common option (consumed), 0 if not, -1 on a
 * bad value (message printed). */
int cli_common_option(const char *cmd, int argc, char **argv, int *i, CliCommon *c) {
  const char *a = argv[*i], *v;
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
    if (us_search_parse(v, &c->plan.search))
      return cli_fail(cmd, "unknown search '%s' (assemble, dfs, bfs, random)", v), -1;
    return 1;
  }
  if (!strcmp(a, "--order")) {
    if (!(v = cli_value(cmd, argc, argv, i))) return -1;
    if (us_order_parse(v, &c->plan.order))
      return cli_fail(cmd, "unknown order '%s' (highest, lowest, input)", v), -1;
    return 1;
  }
  if (!strcmp(a, "--direction")) {
    if (!(v = cli_value(cmd, argc, argv, i))) return -1;
    if (us_direction_parse(v, &c->plan.direction))
      return cli_fail(cmd, "unknown direction '%s' (down, up)", v), -1;
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
