/* A small program that uses the unstack library directly: build a
 * cantilever held by a counterweight with the builder API, ask whether it
 * stands, plan its unstacking, and re-check the plan.
 *
 *   pier P, a spacer S and a plank L on it (L sticks out to the right and
 *   would tip on its own), a heavy counterweight C on S and L's inner end.
 *   C is the highest body, but the plank has to go first.
 *
 * Build: part of the CMake build (build/example_plan); against an installed
 * unstack with examples/CMakeLists.txt or pkg-config (docs/install.md). */
#include <stdio.h>

#include "unstack/unstack.h"

static int box(us_Structure *s, const char *id, double x0, double y0, double x1, double y1,
               double density, us_Error *err) {
  double v[8] = {x0, y0, x1, y0, x1, y1, x0, y1};
  return us_structure_add_body(
      s,
      &(us_BodyDef){
          .id = id, .nvert = 4, .xy = v, .density = density, .friction = -1},
      err);
}

int main(void) {
  us_Error err;
  us_error_clear(&err);
  us_Structure *s = us_structure_new(2);
  if (!s || box(s, "P", 0, 0, 1, 1, 1, &err) < 0 || box(s, "S", 0, 1, 0.6, 1.2, 1, &err) < 0 ||
      box(s, "L", 0.6, 1, 3.6, 1.2, 1, &err) < 0 || box(s, "C", 0, 1.2, 1, 1.7, 10, &err) < 0 ||
      us_structure_finalize(s, &err) != US_OK) {
    fprintf(stderr, "example: %s\n", err.msg);
    us_structure_free(s);
    return 2;
  }
  printf("%d bodies, %d contacts detected\n", s->nbody, s->ncontact);

  us_PlanSettings set = us_plan_default_settings(); /* DFS, highest first, CLP */
  us_Plan plan;
  if (us_plan(s, &set, &plan, &err) != US_OK) {
    fprintf(stderr, "example: %s\n", err.msg);
    us_structure_free(s);
    return 2;
  }
  printf("plan: %s after %ld tests (%ld unstable)\n", us_plan_status_name(plan.status),
         plan.stats.tests, plan.stats.unstable);
  for (int k = 0; k < plan.nsteps; k++) printf("  %d. remove %s\n", k + 1, s->bodies[plan.order[k]].id);

  us_VerifyReport rep;
  us_StabilitySettings check = us_stability_default_settings();
  check.method = US_METHOD_LPSOLVE; /* re-check with the other LP solver */
  int ok = us_verify_order(s, &check, plan.order, plan.nsteps, &rep, &err) == US_OK && rep.ok;
  printf("re-checked with lp_solve: %s\n", ok ? "valid" : "INVALID");
  us_plan_free(&plan);
  us_structure_free(s);
  return ok ? 0 : 1;
}
