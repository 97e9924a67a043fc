/* unstack check: does the whole structure stand? */
#include "options.h"

#include <stdio.h>
#include <string.h>

static const char help[] =
    "usage: unstack check FILE [options]\n"
    "\n"
    "Test whether the structure in FILE stands (weak stability: contact forces\n"
    "exist that balance gravity on every body, with non-negative normal forces\n"
    "and friction inside the Coulomb cone). The answer carries a certificate\n"
    "(the forces) that is re-checked without the solver.\n"
    "\n"
    "options:\n"
    "  --method M        auto (default), lp (CLP), lpsolve, lcp, lcp-reuse, lp-lcp\n"
    "  --local on|off      exact local tests for lp and auto (default on)\n"
    "  --contact-tol T   contact detection tolerance (default 1e-6 x size)\n"
    "  --forces          print the certificate forces\n"
    "  --time-limit S    stop after S seconds, inside the solver too (undecided)\n"
    "\n"
    "exit: 0 stable, 1 unstable, 2 usage or input error, 3 undecided (a solver\n"
    "limit was hit and no fallback decided, or the certificate failed)\n";

static void print_forces(const us_Structure *s, const us_Forces *f) {
  int dim = s->dim;
  printf(dim == 3 ? "contact forces (a -> b, point, normal force, tangential forces along t1, t2):\n"
                  : "contact forces (a -> b, point, normal force, tangential force):\n");
  for (int k = 0; k < f->ncontact; k++) {
    const us_Contact *c = &s->contacts[f->contact[k]];
    const double *v = f->f + dim * k;
    printf("  %s -> %s at ", c->a < 0 ? "ground" : us_id_text(s->bodies[c->a].id).s,
           us_id_text(s->bodies[c->b].id).s);
    if (dim == 3)
      printf("(%.6g, %.6g, %.6g): fn = %.6g, ft = (%.6g, %.6g)\n", c->p[0], c->p[1], c->p[2],
             v[0], v[1], v[2]);
    else
      printf("(%.6g, %.6g): fn = %.6g, ft = %.6g\n", c->p[0], c->p[1], v[0], v[1]);
  }
}

static int report(const us_Structure *s, const us_StabilityResult *res, int forces) {
  int nmov = us_structure_movable_count(s);
  if (res->verdict == US_STABLE) {
    printf("stable: %d bodies, %d contacts; certificate: force residual %.2e, torque residual "
           "%.2e, cone violation %.2e (relative)\n",
           nmov, s->ncontact, res->check.max_force_residual, res->check.max_torque_residual,
           res->check.max_cone_violation);
    if (res->note[0]) printf("solver: %s\n", res->note);
    if (forces) print_forces(s, &res->forces);
    return CLI_EXIT_OK;
  }
  printf("%s: %d bodies, %d contacts", us_verdict_name(res->verdict), nmov, s->ncontact);
  if (res->unstable_body >= 0) printf("; body '%s' cannot be held",
                                      us_id_text(s->bodies[res->unstable_body].id).s);
  if (res->note[0]) printf(" (%s)", res->note);
  printf("\n");
  return res->verdict == US_UNDECIDED ? CLI_EXIT_UNDECIDED : CLI_EXIT_NO;
}

int cmd_check(int argc, char **argv) {
  CliCommon c;
  cli_common_init(&c);
  const char *file = NULL;
  int forces = 0;
  for (int i = 1; i < argc; i++) {
    int r = cli_common_option("check", argc, argv, &i, &c);
    if (r < 0) return CLI_EXIT_ERR;
    if (r) continue;
    if (cli_is_help(argv[i])) return fputs(help, stdout), CLI_EXIT_OK;
    if (!strcmp(argv[i], "--forces")) forces = 1;
    else if (!strcmp(argv[i], "--time-limit")) {
      const char *v = cli_value("check", argc, argv, &i);
      if (!v || cli_time_limit("check", v, &c)) return CLI_EXIT_ERR;
    }
    else if (argv[i][0] == '-' && argv[i][1]) return cli_fail("check", "unknown option '%s'", argv[i]);
    else if (file) return cli_fail("check", "more than one FILE given");
    else file = argv[i];
  }
  if (!file) return cli_fail("check", "no FILE given (see 'unstack check --help')");
  int load;
  us_Structure *s = cli_load("check", file, &c, c.stab.time_limit, &load);
  if (!s) return load;
  us_Error err;
  us_error_clear(&err);
  us_StabilityResult res;
  memset(&res, 0, sizeof res);
  c.stab.time_limit = cli_time_left(c.stab.time_limit);
  us_Stability *w = us_stability_new(s, &c.stab, &err);
  int code = CLI_EXIT_ERR;
  if (w && us_stability_test_full(w, &res, &err) == US_OK) code = report(s, &res, forces);
  if (code == CLI_EXIT_ERR) cli_error("check", &err);
  us_stability_result_free(&res);
  us_stability_free(w);
  us_structure_free(s);
  return code;
}
