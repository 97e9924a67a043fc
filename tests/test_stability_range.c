/* Tests of the stability layer over the whole range of values a user can
 * write: friction coefficients from 0 to 1e300 and INFINITY, masses,
 * densities and gravity near the ends of the double range, and a result
 * that was never zeroed before its init. Every case states its expected
 * verdict from hand statics; all four methods (lp, lpsolve, lcp,
 * lcp-reuse) must give it, and every STABLE verdict must carry a passing
 * certificate (the front end only returns STABLE so; checked again). */
#include "scenes.h"
#include "test.h"

#define NMETHOD 4

/* Every method gives `want` on s (which is freed). 0, or -1 on mismatch. */
static int all_methods(us_Structure *s, int want, const char *what, double x) {
  int bad = !s;
  for (int m = 0; s && m < NMETHOD; m++) {
    int v = scene_verdict(s, (us_Method)m, NULL);
    if (v != want) {
      fprintf(stderr, "%s (%g): %s gives %d, expected %d\n", what, x,
              us_method_name((us_Method)m), v, want);
      bad = 1;
    }
  }
  us_structure_free(s);
  return bad ? -1 : 0;
}

/* ---------------------------------------------------------------- scenes */

/* A pyramid of `rows` rows of unit boxes (bottom row `rows` boxes). */
static us_Structure *pyramid(int rows, double mu) {
  us_Structure *s = us_structure_new(2);
  s->friction = mu;
  char id[32];
  for (int r = 0; r < rows; r++)
    for (int k = 0; k < rows - r; k++) {
      snprintf(id, sizeof id, "p%d_%d", r, k);
      scene_box(s, id, 0.5 * r + k, r, 1, 1, 1);
    }
  return scene_seal(s);
}

/* A column of two boxes under gravity g (2 components). */
static us_Structure *column2(double mu, double gx, double gy) {
  us_Structure *s = us_structure_new(2);
  s->friction = mu;
  s->gravity[0] = gx, s->gravity[1] = gy;
  scene_box(s, "b1", 0, 0, 1, 0.5, 1);
  scene_box(s, "b2", 0, 0.5, 1, 0.5, 1);
  return scene_seal(s);
}

/* The plank L on pier P without counterweight: its centre (x = 2.5) is
 * beyond the pier's edge (x = 1), so it tips whatever the friction. */
static us_Structure *bare_cantilever(double mu) {
  us_Structure *s = us_structure_new(2);
  s->friction = mu;
  scene_box(s, "P", 0, 0, 1, 1, 1);
  scene_box(s, "L", 0.5, 1, 4, 0.2, 1);
  return scene_seal(s);
}

/* A flat box (2 x 0.5) resting on a fixed incline of angle a (degrees):
 * it slides iff mu < tan a, and tips only beyond tan a = 4. */
static us_Structure *on_incline(double a_deg, double mu) {
  us_Structure *s = us_structure_new(2);
  s->friction = mu;
  s->ground = 0;
  double a = a_deg * 3.14159265358979323846 / 180.0, c = cos(a), sn = sin(a);
  double wedge[6] = {0, 0, 4 * c, 0, 4 * c, 4 * sn};
  us_structure_add_polygon(s, "slope", 3, wedge, 1, 0, 1, -1, NULL);
  /* the box's base from 1.0 to 3.0 along the slope, height 0.5 off it */
  double u[2] = {c, sn}, v[2] = {-sn, c}, xy[8];
  double loc[4][2] = {{1, 0}, {3, 0}, {3, 0.5}, {1, 0.5}};
  for (int k = 0; k < 4; k++) {
    xy[2 * k] = loc[k][0] * u[0] + loc[k][1] * v[0];
    xy[2 * k + 1] = loc[k][0] * u[1] + loc[k][1] * v[1];
  }
  us_structure_add_polygon(s, "box", 4, xy, 1, 0, 0, -1, NULL);
  return scene_seal(s);
}

/* A point body held by one explicit contact at its centre whose normal is
 * horizontal (a peg in a vertical wall): gravity is purely tangential, so
 * it hangs iff the cone holds f_n = 0, |f_t| = m g: only mu = INFINITY. */
static us_Structure *peg(double mu) {
  us_Structure *s = us_structure_new(2);
  s->ground = 0;
  double c[2] = {1, 1}, nx[2] = {1, 0};
  int w = us_structure_add_point_body(s, "wall", 1, c, 1, NULL);
  int b = us_structure_add_point_body(s, "peg", 1, c, 0, NULL);
  us_structure_add_contact(s, w, b, c, nx, mu, NULL);
  s->explicit_contacts = 1;
  return scene_seal(s);
}

/* ----------------------------------------------------------------- cases */

static const double mus[] = {0,    1e-3,  0.05,  0.5,   1,     2,     10,    1e3,
                             1e6,  1e8,   1e10,  1e20,  1e50,  1e100, 1e200, 1e300};
#define NMU (int)(sizeof mus / sizeof mus[0])

/* Friction from 0 to 1e300 and INFINITY on four scenes, four methods. */
static void friction_range(void) {
  int bad = 0;
  for (int k = 0; k <= NMU; k++) {
    double mu = k < NMU ? mus[k] : INFINITY;
    bad |= all_methods(pyramid(4, mu), US_STABLE, "pyramid", mu);
    /* gravity [-1, -9.81]: slides iff mu < 1 / 9.81 */
    bad |= all_methods(column2(mu, -1, -9.81), mu < 0.102 ? US_UNSTABLE : US_STABLE,
                       "tilted column", mu);
    /* leaning slabs: mu* = 13/165 = 0.0788 (docs/classify.md) */
    bad |= all_methods(scene_leaning(mu), mu < 0.0788 ? US_UNSTABLE : US_STABLE, "leaning", mu);
    bad |= all_methods(bare_cantilever(mu), US_UNSTABLE, "bare cantilever", mu);
  }
  CHECK(!bad);
}

/* Infinite friction holds what no finite mu holds (the peg), and what a
 * given finite mu does not (a steep incline); it does not stop tipping. */
static void infinite_friction(void) {
  int bad = 0;
  /* finite mu needs f_n = m g / mu where equilibrium wants f_n = 0: a
   * residual of 1 / mu of the weight, which only exceeds the certificate
   * tolerance (1e-6) and the LP's (1e-9) while mu stays well below 1e6; at
   * larger mu the peg holds within tolerance (not tested) */
  for (int k = 0; mus[k] <= 1e3; k++)
    bad |= all_methods(peg(mus[k]), US_UNSTABLE, "peg", mus[k]);
  bad |= all_methods(peg(INFINITY), US_STABLE, "peg", INFINITY);
  /* 60 degrees: needs mu >= tan 60 = 1.732 */
  bad |= all_methods(on_incline(60, 1.7), US_UNSTABLE, "incline 60", 1.7);
  bad |= all_methods(on_incline(60, 1.8), US_STABLE, "incline 60", 1.8);
  bad |= all_methods(on_incline(60, INFINITY), US_STABLE, "incline 60", INFINITY);
  /* 80 degrees: tan 80 = 5.67 > 4, so the box tips whatever mu */
  bad |= all_methods(on_incline(80, INFINITY), US_UNSTABLE, "incline 80", INFINITY);
  bad |= all_methods(bare_cantilever(INFINITY), US_UNSTABLE, "bare cantilever", INFINITY);
  CHECK(!bad);
}

/* Tilted column with explicit masses / densities on each box. */
static us_Structure *column_masses(double m1, double m2, double d1, double gx, double gy) {
  us_Structure *s = us_structure_new(2);
  s->gravity[0] = gx, s->gravity[1] = gy;
  double a[8] = {0, 0, 1, 0, 1, 0.5, 0, 0.5}, b[8] = {0, 0.5, 1, 0.5, 1, 1, 0, 1};
  us_structure_add_polygon(s, "b1", 4, a, d1, m1, 0, -1, NULL);
  us_structure_add_polygon(s, "b2", 4, b, 1, m2, 0, -1, NULL);
  return s;
}

/* Extreme masses and gravity that can be represented give the verdict of
 * the same structure at ordinary values. */
static void extreme_values_decided(void) {
  int bad = 0;
  /* default friction 0.5; upright column stands, 45-degree gravity slides */
  bad |= all_methods(scene_seal(column_masses(1e-310, 1, 0, 0, -9.81)), US_STABLE, "m 1e-310", 0);
  bad |= all_methods(scene_seal(column_masses(1e-310, 1e-310, 0, 0, -1e10)), US_STABLE,
                     "m 1e-310, g 1e10", 0);
  bad |= all_methods(scene_seal(column_masses(1e200, 1, 0, 0, -9.81)), US_STABLE, "m 1e200", 0);
  bad |= all_methods(scene_seal(column_masses(1e200, 1e200, 0, -1, -1)), US_UNSTABLE,
                     "m 1e200, 45 deg", 0);
  bad |= all_methods(scene_seal(column_masses(0, 0, 1e300, 0, -9.81)), US_STABLE, "d 1e300", 0);
  bad |= all_methods(scene_seal(column_masses(0, 0, 1, 1e308, -1e308)), US_UNSTABLE,
                     "g [1e308, -1e308]", 0);
  bad |= all_methods(scene_seal(column_masses(0, 0, 1, 1e307, -1e308)), US_STABLE,
                     "g [1e307, -1e308]", 0);
  bad |= all_methods(scene_seal(column_masses(0, 0, 1, 0, -1e308)), US_STABLE, "g -1e308", 0);
  CHECK(!bad);
}

/* What cannot be represented is rejected at finalize, naming the cause. */
static void extreme_values_rejected(void) {
  us_Structure *s = column_masses(0, 0, 1e308, 0, -9.81); /* 0.5 * 1e308 * 9.81 = inf */
  CHECK(scene_fails_with(s, "total weight", "overflows"));
  us_structure_free(s);
  s = us_structure_new(2);
  double big[8] = {0, 0, 2, 0, 2, 2, 0, 2}; /* area 4: density 1e308 * 4 overflows */
  us_structure_add_polygon(s, "b", 4, big, 1e308, 0, 0, -1, NULL);
  CHECK(scene_fails_with(s, "body 'b'", "overflows"));
  us_structure_free(s);
  s = column_masses(1e308, 1e308, 0, 0, -1e-300); /* M = inf */
  CHECK(scene_fails_with(s, "total mass", "overflows"));
  us_structure_free(s);
  s = column_masses(1e-310, 1e-310, 0, 0, -9.81); /* W subnormal */
  CHECK(scene_fails_with(s, "total weight", "smallest normal"));
  us_structure_free(s);
}

/* A nearly weightless body floating beside a heavy one is not held. */
static void floating_light_body(void) {
  us_Structure *s = us_structure_new(2);
  scene_box(s, "heavy", 0, 0, 1, 1, 1);
  double xy[8] = {3, 2, 4, 2, 4, 3, 3, 3};
  us_structure_add_polygon(s, "light", 4, xy, 1, 1e-300, 0, -1, NULL);
  CHECK(!all_methods(scene_seal(s), US_UNSTABLE, "floating 1e-300", 0));
}

/* A result full of garbage bytes is usable after init (ASan: no wild
 * store), and stays usable for a second test. */
static void result_init_garbage(void) {
  us_Structure *s = scene_column(3);
  CHECK(s);
  us_Error err;
  us_Stability *w = us_stability_new(s, NULL, &err);
  CHECK(w);
  us_StabilityResult res;
  memset(&res, 0xA5, sizeof res);
  us_stability_result_init(&res);
  CHECK_INT(res.forces.cap, ==, 0);
  CHECK_INT(res.unstable_body, ==, -1);
  CHECK_OK(us_stability_test_full(w, &res, &err), &err);
  CHECK_INT(res.verdict, ==, US_STABLE);
  CHECK(res.check.ok);
  CHECK_OK(us_stability_test_full(w, &res, &err), &err);
  CHECK_INT(res.verdict, ==, US_STABLE);
  us_stability_result_free(&res);
  us_stability_result_init(&res); /* after free: init again is fine */
  us_stability_result_free(&res);
  us_stability_free(w);
  us_structure_free(s);
}

/* The LP's named settings change how it works, not what it answers. */
static void lp_settings_vary(void) {
  us_Structure *s = scene_leaning(0.2);
  CHECK(s);
  double ncol[] = {1e-9, 1.0, 1e9};
  for (int k = 0; k < 3; k++)
    for (int m = 0; m < 2; m++) {
      us_StabilitySettings set = us_stability_default_settings();
      set.method = (us_Method)m;
      set.lp.n_column_mu = ncol[k];
      set.lp.primal_tol = 1e-10;
      us_Error err;
      us_Stability *w = us_stability_new(s, &set, &err);
      CHECK(w);
      us_StabilityResult res;
      us_stability_result_init(&res);
      us_Status st = us_stability_test_full(w, &res, &err);
      us_Verdict v = res.verdict;
      int ok = res.check.ok;
      us_stability_result_free(&res);
      us_stability_free(w);
      CHECK_OK(st, &err);
      CHECK_INT(v, ==, US_STABLE);
      CHECK(ok);
    }
  us_structure_free(s);
}

US_TEST_MAIN(T(friction_range), T(infinite_friction), T(extreme_values_decided),
             T(extreme_values_rejected), T(floating_light_body), T(result_init_garbage),
             T(lp_settings_vary))
