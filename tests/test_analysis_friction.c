/* Tests of the critical friction (src/analysis/friction.c) against hand
 * statics: a slab leaning on a wall (friction at both ends, exact formula
 * for the slab's corners and centre, and the thin-ladder formula), a block
 * on a ramp (tan alpha), a column (0), two slabs leaning on each other (a
 * moment balance), overhanging and floating blocks (no mu works), a box
 * pinched between walls (0, not attained), the decoupling of separate
 * parts (the larger of their values), agreement of the backends, the
 * threshold on random piles with tilted joints (stable 1e-6 above,
 * unstable 1e-6 below, each side tested on a structure built with that
 * coefficient), undecided verdicts, argument errors and out-of-memory
 * paths. */
#include "scenes.h"
#include "test.h"

#define PI 3.14159265358979323846

/* ----------------------------------------------------------------- scenes */

/* A rectangular slab L x t, its long side at angle theta to the ground,
 * its lower corner P0 at the origin and its upper corner P1 = L (c, s)
 * against the vertical face x = L c of a fixed wall. */
static us_Structure *ladder(double theta, double len, double thick, double mu) {
  double c = cos(theta), s = sin(theta);
  double slab[8] = {0, 0, len * c, len * s, len * c - thick * s, len * s + thick * c,
                    -thick * s, thick * c};
  double x = len * c, wall[8] = {x, 0, x + 1, 0, x + 1, len * s + 1, x, len * s + 1};
  us_Structure *st = us_structure_new(2);
  st->friction = mu;
  scene_polygon(st, "wall", 4, wall, 1);
  scene_polygon(st, "slab", 4, slab, 0);
  return scene_seal(st);
}

/* Hand statics of the ladder. Ground contact at P0: normal N_g up,
 * friction F_g towards the wall; wall contact at P1: normal N_w away from
 * the wall, friction F_w up. Equilibrium: F_g = N_w, N_g + F_w = W, and
 * moments about P0: L c F_w + L s N_w = W g_x, where g_x = (L c - t s) / 2
 * is the centre's abscissa. At the threshold both frictions are at their
 * bounds (F_g = mu N_g, F_w = mu N_w; with mu below cot theta a smaller F_w
 * only needs more N_w), so N_g = W / (1 + mu^2), N_w = mu N_g and
 * mu (mu c + s) = a (1 + mu^2), a = g_x / L: the root in (0, 1) of
 * (c - a) mu^2 + s mu - a = 0. For t = 0, a = c / 2 and this is
 * tan theta = (1 - mu^2) / (2 mu). */
static double ladder_mu(double theta, double len, double thick) {
  double c = cos(theta), s = sin(theta);
  double a = (len * c - thick * s) / (2 * len), q = c - a;
  return (-s + sqrt(s * s + 4 * a * q)) / (2 * q);
}

/* A fixed wedge of slope alpha and a b x b block on it, its lower edge on
 * the slope from distance d to d + b along it. */
static us_Structure *ramp(double x0, double alpha, double mu, us_Structure *into) {
  double c = cos(alpha), s = sin(alpha), d = 1.5, b = 0.5, run = 4.0;
  double wedge[6] = {x0, 0, x0 + run, 0, x0 + run, run * s / c};
  double blk[8] = {x0 + d * c,         d * s,         x0 + (d + b) * c,
                   (d + b) * s,         x0 + (d + b) * c - b * s,
                   (d + b) * s + b * c, x0 + d * c - b * s, d * s + b * c};
  us_Structure *st = into ? into : us_structure_new(2);
  st->friction = mu;
  scene_polygon(st, "wedge", 3, wedge, 1);
  scene_polygon(st, "block", 4, blk, 0);
  return into ? st : scene_seal(st);
}

/* Hand statics of the inverted V. The forces that hold it at a given mu
 * form a convex set mapped onto itself by the mirror, so if it stands it
 * stands with mirror-symmetric forces, and those carry no shear on the
 * joint (the mirror turns the shear the left slab gets into the opposite
 * of what the right one gets). The left slab (area 0.55, centre x
 * c_x = 1.84 / 3.3 by the shoelace formula) then takes the joint's push
 * P1 + P2 (at heights 1.5, 2) to the left, ground normals N1, N2 at x = 0,
 * 0.4 summing to W and ground friction P1 + P2 <= mu W. Moments about the
 * origin: 0.4 N2 + 1.5 P1 + 2 P2 = W c_x, so the smallest push is
 * (c_x - 0.4) W / 2 (N2 = W, P1 = 0): mu* = (c_x - 0.4) / 2 = 13 / 165. */
#define LEANING_MU (13.0 / 165.0)

/* A box on a base box with its centre beyond the base's edge, and a box
 * floating off to the side. */
static us_Structure *overhang(void) {
  us_Structure *s = us_structure_new(2);
  scene_box(s, "base", 0, 0, 1, 1, 1);
  scene_box(s, "over", 0.8, 1, 1, 0.5, 1);
  scene_box(s, "float", 5, 1, 1, 1, 1);
  return scene_seal(s);
}

/* A pile of blocks with tilted joints: joint k is the line
 * y = y_k + m_k x (joint 0 is the ground), block i lies between joints i
 * and i + 1 over x in [x0_i, x1_i] with vertical sides. Joints are at least
 * 0.3 apart over |x| <= 2, so only neighbours touch, along the overlap of
 * their spans. Deterministic in `seed`; every contact gets mu. */
static us_Structure *pile(unsigned long long seed, double mu) {
  unsigned long long r = seed * 2654435761ull + 1;
  us_Structure *s = us_structure_new(2);
  s->friction = mu;
  int n = 2 + (int)(test_rnd(&r) * 4);
  double y = 0, m = 0, x0 = -0.5, x1 = 0.5;
  char id[16];
  for (int i = 0; i < n; i++) {
    double m2 = (test_rnd(&r) - 0.5) * 1.0;
    double y2 = y + 0.3 + 0.3 * test_rnd(&r) + fabs(m2 - m) * 2.0;
    double xy[8] = {x0, y + m * x0, x1, y + m * x1, x1, y2 + m2 * x1, x0, y2 + m2 * x0};
    snprintf(id, sizeof id, "p%d", i);
    us_structure_add_body(s,
                          &(us_BodyDef){.id = id,
                                        .nvert = 4,
                                        .xy = xy,
                                        .density = 0.5 + 1.5 * test_rnd(&r),
                                        .friction = -1},
                          NULL);
    double w = 0.6 + 0.8 * test_rnd(&r), lo = fmax(x0 - w + 0.2, -2.0);
    double a = lo + (fmin(x1 - 0.2, 2.0 - w) - lo) * test_rnd(&r);
    x0 = a, x1 = a + w, y = y2, m = m2;
  }
  return scene_seal(s);
}

/* ---------------------------------------------------------------- helpers */

/* Critical friction with default settings; -1 on error, else the value
 * (INFINITY when it does not stand). The certificate must pass. */
static double mu_of(const us_Structure *s, const us_Bitset *present, us_Method m) {
  us_StabilitySettings set = us_stability_default_settings();
  set.method = m;
  us_FrictionResult r;
  us_Error err;
  if (us_critical_friction(s, present, &set, 0, 0, &r, &err) != US_OK) {
    fprintf(stderr, "critical friction: %s\n", err.msg);
    return -1;
  }
  double mu = r.mu_critical;
  if (r.stands && (!r.check.ok || r.mu_high - r.mu_low > 1e-7 || r.mu_critical != r.mu_high)) {
    fprintf(stderr, "bad result: check %d, bracket %.12g %.12g\n", r.check.ok, r.mu_low,
            r.mu_high);
    mu = -1;
  }
  us_friction_result_free(&r);
  return mu;
}

/* Verdict of the whole structure (default settings); -1 on error. */
static int verdict(const us_Structure *s) {
  us_Error err;
  us_Stability *w = us_stability_new(s, NULL, &err);
  if (!w) return -1;
  us_StabilityResult res = {0};
  int v = us_stability_test_full(w, &res, &err) == US_OK ? (int)res.verdict : -1;
  us_stability_result_free(&res);
  us_stability_free(w);
  return v;
}

/* ------------------------------------------------------------------ cases */

static void ladder_exact(void) {
  const double deg[] = {45, 55, 60, 70, 80};
  for (int k = 0; k < 5; k++) {
    double th = deg[k] * PI / 180;
    us_Structure *s = ladder(th, 2.0, 0.1, 0.3);
    CHECK(s);
    CHECK_INT(s->ncontact, ==, 2);
    double mu = mu_of(s, NULL, US_METHOD_LP);
    CHECK_NEAR(mu, ladder_mu(th, 2.0, 0.1), 1e-6);
    us_structure_free(s);
  }
}

/* A slab 1e-4 of its length thick follows the thin-ladder formula
 * tan theta = (1 - mu^2) / (2 mu), i.e. mu = (1 - sin theta) / cos theta. */
static void ladder_thin(void) {
  const double deg[] = {40, 60, 75};
  for (int k = 0; k < 3; k++) {
    double th = deg[k] * PI / 180;
    us_Structure *s = ladder(th, 2.0, 2e-4, 0.3);
    CHECK(s);
    double mu = mu_of(s, NULL, US_METHOD_LP);
    CHECK_NEAR(mu, (1 - sin(th)) / cos(th), 1e-4);
    us_structure_free(s);
  }
}

/* The structure's own coefficients play no part, and stay as they were. */
static void own_friction_ignored(void) {
  double th = 60 * PI / 180, want = ladder_mu(th, 2.0, 0.1);
  const double own[] = {0.0, 0.05, 5.0};
  for (int k = 0; k < 3; k++) {
    us_Structure *s = ladder(th, 2.0, 0.1, own[k]);
    CHECK(s);
    CHECK_NEAR(mu_of(s, NULL, US_METHOD_LP), want, 1e-6);
    for (int c = 0; c < s->ncontact; c++) CHECK_NEAR(s->contacts[c].mu, own[k], 0);
    us_structure_free(s);
  }
}

static void ramp_tan_alpha(void) {
  const double deg[] = {5, 15, 25, 35, 42};
  for (int k = 0; k < 5; k++) {
    double al = deg[k] * PI / 180;
    us_Structure *s = ramp(0, al, 0.5, NULL);
    CHECK(s);
    CHECK_INT(s->ncontact, ==, 2);
    CHECK_NEAR(mu_of(s, NULL, US_METHOD_LP), tan(al), 1e-6);
    us_structure_free(s);
  }
}

static void column_needs_none(void) {
  us_Structure *s = scene_column(4);
  CHECK(s);
  us_FrictionResult r;
  us_Error err;
  CHECK_OK(us_critical_friction(s, NULL, NULL, 0, 0, &r, &err), &err);
  CHECK_INT(r.stands_frictionless, ==, 1);
  CHECK_INT(r.stands, ==, 1);
  CHECK_INT(r.probes, ==, 1);
  CHECK_NEAR(r.mu_critical, 0, 0);
  CHECK_INT(r.check.ok, ==, 1);
  CHECK_INT(r.forces.ncontact, ==, s->ncontact);
  us_friction_result_free(&r);
  us_structure_free(s);
}

static void leaning_pair(void) {
  us_Structure *s = scene_leaning(0.5);
  CHECK(s);
  CHECK_NEAR(mu_of(s, NULL, US_METHOD_LP), LEANING_MU, 1e-6);
  /* 2 end probes, 5 geometric ones from [0, 1e3] down to [0.042, 0.087],
     then halving that to 1e-7 (19): 26 when run by hand on the verdicts */
  us_FrictionResult r;
  us_Error err;
  CHECK_OK(us_critical_friction(s, NULL, NULL, 0, 0, &r, &err), &err);
  CHECK_INT(r.probes, ==, 26);
  CHECK_INT(r.undecided, ==, 0);
  us_friction_result_free(&r);
  us_Bitset left = {0};
  CHECK(us_bitset_init(&left, s->nbody) == 0);
  us_bitset_set(&left, 0); /* alone its centre is beyond its foot */
  CHECK(isinf(mu_of(s, &left, US_METHOD_LP)));
  us_bitset_free(&left);
  us_structure_free(s);
}

static void no_mu_holds_an_overhang(void) {
  us_Structure *s = overhang();
  CHECK(s);
  us_FrictionResult r;
  us_Error err;
  CHECK_OK(us_critical_friction(s, NULL, NULL, 0, 0, &r, &err), &err);
  CHECK_INT(r.stands, ==, 0);
  CHECK_INT(r.stands_frictionless, ==, 0);
  CHECK_INT(r.probes, ==, 2);
  CHECK_NEAR(r.mu_low, 1e3, 0);
  CHECK(isinf(r.mu_high) && isinf(r.mu_critical));
  CHECK_INT(r.forces.ncontact, ==, 0);
  us_friction_result_free(&r);
  us_Bitset p = {0}; /* the base alone stands without friction */
  CHECK(us_bitset_init(&p, s->nbody) == 0);
  us_bitset_set(&p, 0);
  CHECK_NEAR(mu_of(s, &p, US_METHOD_LP), 0, 0);
  us_bitset_set(&p, 2); /* the floating box never does */
  CHECK(isinf(mu_of(s, &p, US_METHOD_LP)));
  us_bitset_free(&p);
  us_structure_free(s);
}

/* A box pinched between two fixed vertical walls, off the ground. Without
 * friction nothing holds it up; with any mu > 0 a squeeze N >= W / (2 mu)
 * does (weak stability bounds no force). So mu* = 0 is an infimum that is
 * not attained: the answer is within tol of 0 but it does not stand at 0. */
static void pinched_between_walls(void) {
  us_Structure *s = us_structure_new(2);
  double wl[8] = {0, 0, 1, 0, 1, 3, 0, 3}, wr[8] = {2, 0, 3, 0, 3, 3, 2, 3};
  scene_polygon(s, "left", 4, wl, 1);
  scene_polygon(s, "right", 4, wr, 1);
  scene_box(s, "box", 1, 1, 1, 1, 1);
  s = scene_seal(s);
  CHECK(s);
  us_FrictionResult r;
  us_Error err;
  CHECK_OK(us_critical_friction(s, NULL, NULL, 0, 0, &r, &err), &err);
  CHECK_INT(r.stands_frictionless, ==, 0);
  CHECK_INT(r.stands, ==, 1);
  CHECK_NEAR(r.mu_low, 0, 0);
  CHECK(r.mu_critical > 0 && r.mu_critical <= 1e-7);
  CHECK_INT(r.check.ok, ==, 1);
  us_friction_result_free(&r);
  us_structure_free(s);
}

/* Parts that touch only through supports stand apart: the whole needs the
 * larger of the two values. */
static void separate_parts(void) {
  double th = 45 * PI / 180, al = 15 * PI / 180;
  us_Structure *s = ramp(10, al, 0.5, us_structure_new(2));
  double c = cos(th), sn = sin(th);
  double slab[8] = {0, 0, 2 * c, 2 * sn, 2 * c - 0.1 * sn, 2 * sn + 0.1 * c, -0.1 * sn, 0.1 * c};
  double wall[8] = {2 * c, 0, 2 * c + 1, 0, 2 * c + 1, 3, 2 * c, 3};
  scene_polygon(s, "wall", 4, wall, 1);
  scene_polygon(s, "slab", 4, slab, 0);
  s = scene_seal(s);
  CHECK(s);
  double mu_l = ladder_mu(th, 2.0, 0.1), mu_r = tan(al);
  CHECK(mu_l > mu_r + 0.01);
  us_Bitset p = {0};
  CHECK(us_bitset_init(&p, s->nbody) == 0);
  us_bitset_set(&p, 1); /* the block */
  CHECK_NEAR(mu_of(s, &p, US_METHOD_LP), mu_r, 1e-6);
  us_bitset_clear(&p, 1);
  us_bitset_set(&p, 3); /* the slab */
  CHECK_NEAR(mu_of(s, &p, US_METHOD_LP), mu_l, 1e-6);
  CHECK_NEAR(mu_of(s, NULL, US_METHOD_LP), mu_l, 1e-6);
  us_bitset_free(&p);
  us_structure_free(s);
}

static void backends_agree(void) {
  us_Structure *sc[3] = {scene_leaning(0.5), ladder(50 * PI / 180, 2.0, 0.1, 0.5),
                         ramp(0, 30 * PI / 180, 0.5, NULL)};
  double want[3] = {LEANING_MU, ladder_mu(50 * PI / 180, 2.0, 0.1), tan(30 * PI / 180)};
  for (int k = 0; k < 3; k++) CHECK(sc[k]);
  for (int m = 0; m < US_METHOD_COUNT; m++)
    for (int k = 0; k < 3; k++) {
      double mu = mu_of(sc[k], NULL, (us_Method)m);
      if (fabs(mu - want[k]) > 1e-6)
        fprintf(stderr, "method %s, scene %d\n", us_method_name((us_Method)m), k);
      CHECK_NEAR(mu, want[k], 1e-6);
    }
  for (int k = 0; k < 3; k++) us_structure_free(sc[k]);
}

/* The threshold on random piles: a pile built with coefficient
 * mu_c + 1e-6 stands, one built with mu_c - 1e-6 does not. */
static void threshold_on_piles(void) {
  int positive = 0, zero = 0, never = 0;
  for (unsigned long long seed = 1; seed <= 60; seed++) {
    us_Structure *s = pile(seed, 0.5);
    CHECK(s);
    double mu = mu_of(s, NULL, US_METHOD_LP);
    us_structure_free(s);
    CHECK(mu >= 0);
    if (isinf(mu)) {
      never++;
      continue;
    }
    s = pile(seed, mu + 1e-6);
    CHECK(s);
    CHECK_INT(verdict(s), ==, US_STABLE);
    us_structure_free(s);
    if (mu == 0) {
      zero++;
      continue;
    }
    positive++;
    s = pile(seed, fmax(mu - 1e-6, 0));
    CHECK(s);
    CHECK_INT(verdict(s), ==, US_UNSTABLE);
    us_structure_free(s);
  }
  printf("  piles: %d need friction, %d stand without, %d never\n", positive, zero, never);
  CHECK(positive >= 15);
  CHECK(never >= 1);
}

/* tol and mu_max: a coarse tolerance brackets tan alpha from above, a
 * bound below it gives "does not stand"; probes follow the bisection. */
static void tolerance_and_bound(void) {
  double al = 30 * PI / 180;
  us_Structure *s = ramp(0, al, 0.5, NULL);
  CHECK(s);
  us_FrictionResult r;
  us_Error err;
  CHECK_OK(us_critical_friction(s, NULL, NULL, 1e-3, 10, &r, &err), &err);
  CHECK_INT(r.stands, ==, 1);
  CHECK(r.mu_low < tan(al) && tan(al) <= r.mu_high + 1e-9 && r.mu_high - r.mu_low <= 1e-3);
  /* at most 2 end probes, log2 log2 of the span and log2 of the bracket */
  CHECK(r.probes <= 2 + 5 + 13);
  us_friction_result_free(&r);
  CHECK_OK(us_critical_friction(s, NULL, NULL, 0, 0.5, &r, &err), &err);
  CHECK_INT(r.stands, ==, 0);
  CHECK_NEAR(r.mu_low, 0.5, 0);
  us_friction_result_free(&r);
  us_structure_free(s);
}

/* An undecided verdict never counts as standing: with a certificate
 * tolerance no rounding error meets (1e-300), every stable claim of the LP
 * is rejected, so the ramp "does not stand" and says why. */
static void undecided_is_not_standing(void) {
  us_Structure *s = ramp(0, 30 * PI / 180, 0.5, NULL);
  CHECK(s);
  us_StabilitySettings set = us_stability_default_settings();
  set.cert_tol = 1e-300;
  us_FrictionResult r;
  us_Error err;
  CHECK_OK(us_critical_friction(s, NULL, &set, 0, 0, &r, &err), &err);
  CHECK_INT(r.stands, ==, 0);
  CHECK_INT(r.probes, ==, 2);
  CHECK_INT(r.undecided, ==, 1); /* mu = 0 is a clean "unstable" */
  us_friction_result_free(&r);
  us_structure_free(s);
}

static void bad_arguments(void) {
  us_Structure *s = scene_column(2);
  CHECK(s);
  us_FrictionResult r;
  us_Error err;
  us_Bitset p = {0};
  CHECK(us_bitset_init(&p, s->nbody + 1) == 0);
  CHECK_INT(us_critical_friction(NULL, NULL, NULL, 0, 0, &r, &err), ==, US_ERR_USAGE);
  CHECK_INT(us_critical_friction(s, NULL, NULL, 0, 0, NULL, &err), ==, US_ERR_USAGE);
  CHECK_INT(us_critical_friction(s, &p, NULL, 0, 0, &r, &err), ==, US_ERR_USAGE);
  CHECK_INT(us_critical_friction(s, NULL, NULL, NAN, 0, &r, NULL), ==, US_ERR_USAGE);
  CHECK_INT(us_critical_friction(s, NULL, NULL, 0, INFINITY, &r, NULL), ==, US_ERR_USAGE);
  us_StabilitySettings set = us_stability_default_settings();
  set.cert_tol = -1;
  CHECK_INT(us_critical_friction(s, NULL, &set, 0, 0, &r, NULL), ==, US_ERR_USAGE);
  CHECK_OK(us_critical_friction(s, NULL, NULL, 0, 0, &r, NULL), &err);
  CHECK_INT(r.stands_frictionless, ==, 1);
  us_friction_result_free(&r);
  us_bitset_free(&p);
  us_structure_free(s);
  s = us_structure_new(2);
  scene_box(s, "b", 0, 0, 1, 1, 1);
  CHECK_INT(us_critical_friction(s, NULL, NULL, 0, 0, &r, &err), ==, US_ERR_USAGE);
  us_structure_free(s);
}

/* Every failing allocation gives US_ERR_NOMEM and leaks nothing; the run
 * that gets all its memory gives the hand value. */
static void out_of_memory(void) {
  double th = 60 * PI / 180;
  us_Structure *s = ladder(th, 2.0, 0.1, 0.5);
  CHECK(s);
  int succeeded = 0;
  for (long n = 0; n < 5000 && !succeeded; n++) {
    long live0 = us_alloc_live();
    us_FrictionResult r;
    us_Error err;
    us_alloc_fail_after(n);
    us_Status st = us_critical_friction(s, NULL, NULL, 1e-4, 2, &r, &err);
    us_alloc_fail_after(-1);
    CHECK(st == US_OK || st == US_ERR_NOMEM);
    if (st == US_OK) {
      CHECK_NEAR(r.mu_critical, ladder_mu(th, 2.0, 0.1), 1e-4);
      CHECK_INT(r.check.ok, ==, 1);
      succeeded = 1;
    } else {
      CHECK_INT(r.forces.ncontact, ==, 0);
    }
    us_friction_result_free(&r);
    CHECK_INT(us_alloc_live(), ==, live0);
  }
  CHECK(succeeded);
  us_structure_free(s);
}

US_TEST_MAIN(T(ladder_exact), T(ladder_thin), T(own_friction_ignored), T(ramp_tan_alpha),
             T(column_needs_none), T(leaning_pair), T(no_mu_holds_an_overhang), T(pinched_between_walls),
             T(separate_parts), T(backends_agree), T(threshold_on_piles),
             T(tolerance_and_bound), T(undecided_is_not_standing), T(bad_arguments),
             T(out_of_memory))
