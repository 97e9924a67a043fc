/* unstack check: does the whole structure stand? */
#include "task.h"

#include <stdio.h>
#include <string.h>

static const char head[] =
    "usage: unstack check FILE [options]\n"
    "\n"
    "Test whether the structure in FILE stands (weak stability: contact forces\n"
    "exist that balance gravity on every body, with non-negative normal forces\n"
    "and friction in the Coulomb cone). The answer carries a certificate\n"
    "(the forces) that is re-checked without the solver.\n";
static const char tail[] =
    "exit: 0 stable, 1 unstable, 2 usage or input error, 3 undecided (a solver\n"
    "limit was hit and no fallback decided, or the certificate failed)\n";

/* check's option table (optable.h), shared with batch (task.h). */
void cli_check_table(CliCommon *c, CheckArgs *a, CliOpt *out) {
  /* One entry per option, in --help's order; optable.h says how to add one. */
  const CliOpt opts[] = {
      CLI_OPT_METHOD(c),
      CLI_OPT_LOCAL(c),
      CLI_OPT_CONTACT_TOL(c),
      CLI_FLAG("--forces", &a->forces, "print the certificate forces"),
      CLI_OPT_TIME_LIMIT(&c->stab.time_limit, "stop after S seconds, inside the solver too "
                         "(undecided)"),
      CLI_OPT_STATS(&a->stats, "print the test's statistics: time, solver, local tests"),
      CLI_END};
  _Static_assert(sizeof opts / sizeof opts[0] <= CLI_TABLE_MAX, "CLI_TABLE_MAX too small");
  memcpy(out, opts, sizeof opts);
}

/* The command line, by check's option table. */
static int parse(int argc, char **argv, CliCommon *c, CheckArgs *a) {
  CliOpt opts[CLI_TABLE_MAX];
  cli_check_table(c, a, opts);
  const CliSpec spec = {"check", head, tail, opts, &a->file, 1, "more than one FILE given"};
  int r = cli_parse(&spec, argc, argv);
  if (!r && !a->file) return cli_fail("check", "no FILE given (see 'unstack check --help')");
  return r;
}

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

us_Status cli_check_run(const us_Structure *s, const CliCommon *c, double time_limit,
                        CliCheckOutcome *out, us_Error *err) {
  us_StabilitySettings set = c->stab;
  set.time_limit = time_limit;
  memset(out, 0, sizeof *out);
  double t0 = us_now();
  us_Stability *w = us_stability_new(s, &set, err);
  double t1 = us_now();
  us_Status st = w ? us_stability_test_full(w, &out->res, err) : err->code;
  if (w) out->info = *us_stability_info(w);
  out->t_setup = t1 - t0, out->t_test = us_now() - t1;
  if (st) us_stability_result_free(&out->res);
  us_stability_free(w);
  return st;
}

int cli_check_exit(us_Verdict v) {
  return v == US_STABLE ? CLI_EXIT_OK : v == US_UNDECIDED ? CLI_EXIT_UNDECIDED : CLI_EXIT_NO;
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
    return cli_check_exit(res->verdict);
  }
  printf("%s: %d bodies, %d contacts", us_verdict_name(res->verdict), nmov, s->ncontact);
  if (res->unstable_body >= 0) printf("; body '%s' cannot be held",
                                      us_id_text(s->bodies[res->unstable_body].id).s);
  if (res->note[0]) printf(" (%s)", res->note);
  printf("\n");
  return cli_check_exit(res->verdict);
}

/* --stats: what the test cost and how it was decided. */
static void print_stats(const us_StabilityInfo *in, const char *method, double t_setup,
                        double t_test) {
  printf("statistics:\n  tests %ld, method %s; time: command %.6f s (reading included), setup "
         "%.6f s, test %.6f s, in solver %.6f s, certificate checks %.6f s\n",
         in->tests, method, cli_elapsed(), t_setup, t_test, in->solve_time, in->check_time);
  cli_print_solver_stats(in);
  cli_print_local_stats(in);
}

int cmd_check(int argc, char **argv) {
  CliCommon c;
  cli_common_init(&c);
  CheckArgs a = {NULL, 0, 0};
  int r = parse(argc, argv, &c, &a);
  if (r) return r < 0 ? CLI_EXIT_OK : r;
  int load;
  us_Structure *s = cli_load("check", a.file, &c, c.stab.time_limit, &load);
  if (!s) return load;
  us_Error err;
  us_error_clear(&err);
  CliCheckOutcome o;
  int code = CLI_EXIT_ERR;
  if (cli_check_run(s, &c, cli_time_left(c.stab.time_limit), &o, &err) == US_OK) {
    code = report(s, &o.res, a.forces);
    if (a.stats)
      print_stats(&o.info, us_method_name(us_method_resolve(c.stab.method, s)), o.t_setup,
                  o.t_test);
    us_stability_result_free(&o.res);
  }
  if (code == CLI_EXIT_ERR) cli_error("check", &err);
  us_structure_free(s);
  return code;
}
