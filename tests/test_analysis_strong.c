/* Tests of strong stability with friction (src/analysis/strong*.c) against
 * hand-derived answers, the frictionless theorem (strong = weak), a
 * differential test of the MIP (CBC) against the exhaustive mode search
 * (lp_solve) on sub-assemblies of random piles, the independent witness
 * check (untampered witnesses pass, tampered ones fail), argument errors
 * and out-of-memory paths. No timing is asserted. */
#include "analysis/strong.h"
#include "piles.h"
#include "scenes.h"
#include "test.h"

#include "unstack/analysis.h"

/* ----------------------------------------------------------------- scenes */

/* A unit box between two fixed walls (x in [0, 1] and [2, 3], y in [0, 3]),
 * its bottom at y0: off the ground (y0 = 1) it is pinched, at y0 = 0 it
 * also rests on the ground. */
static us_Structure *pinched(double y0, double mu) {
  us_Structure *s = us_structure_new(2);
  double wl[8] = {0, 0, 1, 0, 1, 3, 0, 3}, wr[8] = {2, 0, 3, 0, 3, 3, 2, 3};
  s->friction = mu;
  scene_polygon(s, "left", 4, wl, 1);
  scene_polygon(s, "right", 4, wr, 1);
  scene_box(s, "box", 1, y0, 1, 1, 1);
  return scene_seal(s);
}

/* A unit box on the ground under gravity tilted to slope tan(theta) = t:
 * g = 9.81 (t, -1) / |(t, -1)|, the ground playing the inclined plane. */
static us_Structure *slope(double t, double mu) {
  us_Structure *s = us_structure_new(2);
  double n = hypot(t, 1.0);
  s->friction = mu;
  s->gravity[0] = 9.81 * t / n;
  s->gravity[1] = -9.81 / n;
  scene_box(s, "box", 0, 0, 1, 1, 1);
  return scene_seal(s);
}

/* Decide with one method; the verdict, or -2 on error. */
static int strong_of(const us_Structure *s, us_StrongMethod m, us_StrongResult *r) {
  us_StrongSettings set = us_strong_default_settings();
  set.method = m;
  us_Error err;
  if (us_strong_stability(s, NULL, &set, r, &err) != US_OK) {
    fprintf(stderr, "strong: %s\n", err.msg);
    return -2;
  }
  return r->strong;
}

/* Both methods agree on `want`; a "no" of a standing structure carries a
 * witness that passes the check. */
static int both_say(const us_Structure *s, int want) {
  us_StrongMethod ms[2] = {US_STRONG_ENUM, US_STRONG_MIP};
  for (int k = 0; k < 2; k++) {
    us_StrongResult r;
    int v = strong_of(s, ms[k], &r);
    int ok = v == want && (v != 0 || !r.has_witness || us_strong_check(s, NULL, &r, 1e-5, NULL, 0));
    if (!ok) fprintf(stderr, "method %d: strong %d (want %d): %s\n", k, v, want, r.note);
    us_strong_result_free(&r);
    if (!ok) return 0;
  }
  return 1;
}

/* ------------------------------------------------------- hand-derived cases */

/* Pinched off the ground (mu 0.5): weakly stable (a squeeze N >= W / 2 mu
 * holds it, tests/test_analysis_friction.c). Not strongly: free fall with
 * no force at either wall is a solution of the dynamics (a_n = 0, f = 0,
 * slip with f_t = 0 = mu f_n), so "no", and the witness moves the box
 * down with gravity doing work. */
static void pinched_weak_not_strong(void) {
  us_Structure *s = pinched(1, 0.5);
  CHECK(s);
  CHECK_INT(scene_verdict(s, US_METHOD_LP, NULL), ==, US_STABLE);
  CHECK(both_say(s, 0));
  us_StrongResult r;
  CHECK_INT(strong_of(s, US_STRONG_ENUM, &r), ==, 0);
  CHECK(r.has_witness);
  CHECK_INT(r.nbody, ==, 1);
  CHECK(r.accel[1] < 0);
  us_strong_result_free(&r);
  us_structure_free(s);
}

/* The box pinched between two movable piers 2 x 3 on the ground (density
 * 1, mu 0.5), off the ground at y 1..2. Weakly stable: a squeeze N = W_box
 * / (2 mu) = W_box per side holds the box; each pier (weight 6 W_box) takes
 * the push N at height 1..2, whose moment (at most 2 W_box) is far below
 * its own about its outer foot (6 W_box x 1), and its ground friction can
 * reach mu (6 + 1/2) W_box > N. Not strongly: the box in free fall with no
 * force on either side, the piers at rest on the ground, is a solution. */
static void pinched_between_piers(void) {
  us_Structure *s = us_structure_new(2);
  s->friction = 0.5;
  scene_box(s, "pierL", 0, 0, 2, 3, 1);
  scene_box(s, "pierR", 3, 0, 2, 3, 1);
  scene_box(s, "box", 2, 1, 1, 1, 1);
  s = scene_seal(s);
  CHECK(s);
  CHECK_INT(scene_verdict(s, US_METHOD_LP, NULL), ==, US_STABLE);
  CHECK(both_say(s, 0));
  us_structure_free(s);
}

/* The same box resting on the ground between the walls: the ground stops
 * any descent, the walls any sideways motion, and a rotation about either
 * bottom corner drives the opposite top corner into its wall; every
 * admissible motion raises the centre, so gravity cannot drive one: weak
 * and strong both yes, at any mu (0.5 and 0). */
static void pinched_on_ground_strong(void) {
  for (int k = 0; k < 2; k++) {
    us_Structure *s = pinched(0, k ? 0.0 : 0.5);
    CHECK(s);
    CHECK_INT(scene_verdict(s, US_METHOD_LP, NULL), ==, US_STABLE);
    CHECK(both_say(s, 1));
    us_structure_free(s);
  }
}

/* A box on a slope tan(theta) = t with mu = 0.5 (centre over the base for
 * t < 1, so no tipping). Closed and sliding down-slope, the normal force is
 * W cos(theta) and the net force along the slope W (sin - mu cos): below
 * the limit (t = 0.3) it opposes the slip, so no sliding solution; the box
 * sticks: weak and strong yes. At the limit (t = mu exactly in the data)
 * the sliding solution exists but its acceleration is zero: strong yes
 * (the solutions differ in their forces only). Above (t = 0.7) it slides:
 * weak no, strong no with the sliding witness. */
static void slope_below_at_above(void) {
  double t[3] = {0.3, 0.5, 0.7};
  int want[3] = {1, 1, 0};
  for (int k = 0; k < 3; k++) {
    us_Structure *s = slope(t[k], 0.5);
    CHECK(s);
    CHECK_INT(scene_verdict(s, US_METHOD_LP, NULL), ==, want[k] ? US_STABLE : US_UNSTABLE);
    CHECK(both_say(s, want[k]));
    us_structure_free(s);
  }
}

/* Without friction the two coincide (Gauss's principle, docs/classify.md):
 * a column stands, strong yes; the pinched box falls, strong no. */
static void frictionless_agree(void) {
  us_Structure *s = scene_column(4);
  CHECK(s);
  for (int c = 0; c < s->ncontact; c++) s->contacts[c].mu = 0;
  CHECK(both_say(s, 1));
  us_structure_free(s);
  s = pinched(1, 0.0);
  CHECK(s);
  CHECK_INT(scene_verdict(s, US_METHOD_LP, NULL), ==, US_UNSTABLE);
  CHECK(both_say(s, 0));
  us_structure_free(s);
}

/* ---------------------------------------------------- the witness check */

static void tampered_witness_rejected(void) {
  us_Structure *s = pinched(1, 0.5);
  CHECK(s);
  us_StrongResult r;
  CHECK_INT(strong_of(s, US_STRONG_ENUM, &r), ==, 0);
  char why[128];
  CHECK(us_strong_check(s, NULL, &r, 1e-6, why, sizeof why));
  /* a wrong acceleration: Newton fails */
  double ay = r.accel[1];
  r.accel[1] = 0.9 * ay;
  CHECK(!us_strong_check(s, NULL, &r, 1e-6, why, sizeof why));
  r.accel[1] = ay;
  /* at rest: no motion */
  double a[3];
  memcpy(a, r.accel, sizeof a);
  memset(r.accel, 0, sizeof a);
  CHECK(!us_strong_check(s, NULL, &r, 1e-6, why, sizeof why));
  memcpy(r.accel, a, sizeof a);
  /* a squeeze with friction holding the box while it still falls: the
     forces are inside the cones but the friction no longer matches the
     acceleration (Newton), and friction along the slip is refused */
  for (int k = 0; k < r.ncontact; k++) r.force[2 * k] = 5.0;
  CHECK(!us_strong_check(s, NULL, &r, 1e-6, why, sizeof why));
  for (int k = 0; k < r.ncontact; k++) r.force[2 * k] = 0, r.force[2 * k + 1] = 0;
  CHECK(us_strong_check(s, NULL, &r, 1e-6, why, sizeof why));
  /* a contact pulling */
  r.force[0] = -1.0;
  CHECK(!us_strong_check(s, NULL, &r, 1e-6, why, sizeof why));
  r.force[0] = 0;
  /* a body that is not movable */
  int b = r.body[0];
  r.body[0] = 0; /* the left wall, fixed */
  CHECK(!us_strong_check(s, NULL, &r, 1e-6, why, sizeof why));
  r.body[0] = b;
  CHECK(us_strong_check(s, NULL, &r, 1e-6, why, sizeof why));
  us_strong_result_free(&r);
  us_structure_free(s);
}

/* The slope above its limit: the sliding witness passes; the same motion
 * with the friction turned along the slip, or with the box pushed into the
 * ground, does not. */
static void sliding_witness_friction_sign(void) {
  us_Structure *s = slope(0.7, 0.5);
  CHECK(s);
  us_StrongResult r;
  CHECK_INT(strong_of(s, US_STRONG_ENUM, &r), ==, 0);
  char why[128];
  CHECK(us_strong_check(s, NULL, &r, 1e-6, why, sizeof why));
  for (int k = 0; k < r.ncontact; k++) r.force[2 * k + 1] = -r.force[2 * k + 1];
  CHECK(!us_strong_check(s, NULL, &r, 1e-6, why, sizeof why));
  for (int k = 0; k < r.ncontact; k++) r.force[2 * k + 1] = -r.force[2 * k + 1];
  r.accel[1] -= 1.0;
  CHECK(!us_strong_check(s, NULL, &r, 1e-6, why, sizeof why));
  us_strong_result_free(&r);
  us_structure_free(s);
}

/* ------------------------------------------------- differential tests */

/* The raw search of one method on sub-assembly `present` (no weak test):
 * 1, 0 or -1; a "no" is checked. -2 on error. */
static int raw(const us_Structure *s, const us_Bitset *present, us_StrongMethod m, long *nodes) {
  us_StrongModel md;
  char why[128];
  if (us_strong_model_build(&md, s, present, why, sizeof why) || us_strong_model_tighten(&md, 0)) {
    us_strong_model_free(&md);
    return -2;
  }
  double *x = us_calloc((size_t)md.nv, sizeof(double));
  us_StrongSettings set = us_strong_default_settings();
  us_StrongResult r = {0};
  us_Error err;
  us_Status st = US_ERR_NOMEM;
  if (x && m == US_STRONG_ENUM) st = us_strong_enumerate(&md, &set, 0, x, &r, &err);
  const us_CbcModule *api = m == US_STRONG_MIP ? us_cbc_module_api(&err) : NULL;
  if (x && api) st = api->solve(&md, &set, 0, x, &r, &err);
  int v = st == US_OK ? r.strong : -2;
  if (v == 0 && (us_strong_polish(&md, x, r.power) < 0 || us_strong_witness(&md, x, &r) || !us_strong_check(s, present, &r, 1e-5, why, sizeof why))) {
    fprintf(stderr, "method %d: witness rejected: %s\n", (int)m, why);
    v = -3;
  }
  if (v == -1) fprintf(stderr, "undecided (%d contacts): %s\n", md.nc, r.note);
  *nodes += r.nodes;
  us_strong_result_free(&r);
  us_free(x);
  us_strong_model_free(&md);
  return v;
}

/* Random sub-assemblies (about half the bodies) of random piles at mu:
 * the MIP and the exhaustive search give the same answer on every one,
 * every "no" passes the check, and where the LP says the sub-assembly
 * does not stand both say no. Counts the cases where weak and strong
 * differ (stands, yet a motion exists). */
#ifdef US_TEST_SANITIZED
enum { MIP_PILES = 16 }; /* the sanitizers look for memory errors: a quarter of the
                            piles (30 took 61 s of the suite's 795 s of CPU) */
#else
enum { MIP_PILES = 60 };
#endif

static void mip_matches_enumeration_at(double mu, unsigned long long rng) {
  int cases = 0, differ = 0, yes = 0;
  long nodes_e = 0, nodes_m = 0;
  double t_e = 0, t_m = 0;
  for (int it = 0; it < MIP_PILES; it++) {
    us_Structure *s = pile_random(&rng, 4 + it % 3);
    if (!s) continue;
    for (int c = 0; c < s->ncontact; c++) s->contacts[c].mu = mu;
    us_Bitset present;
    CHECK(us_bitset_init(&present, s->nbody) == 0);
    for (int rep = 0; rep < 2; rep++) {
      for (int i = 0; i < s->nbody; i++) {
        if (pile_rnd(&rng) < 0.5 && !s->bodies[i].fixed) us_bitset_set(&present, i);
        else present.w[i >> 6] &= ~((uint64_t)1 << (i & 63));
      }
      double t0 = us_now();
      int e = raw(s, &present, US_STRONG_ENUM, &nodes_e);
      double t1 = us_now();
      int m = raw(s, &present, US_STRONG_MIP, &nodes_m);
      t_e += t1 - t0, t_m += us_now() - t1;
      if (e != m) fprintf(stderr, "pile %d rep %d: enumeration %d, MIP %d\n", it, rep, e, m);
      CHECK_INT(e, ==, m);
      CHECK(e == 0 || e == 1);
      int weak = scene_verdict(s, US_METHOD_LP, &present);
      if (weak == US_UNSTABLE) CHECK_INT(e, ==, 0);
      differ += weak == US_STABLE && e == 0;
      yes += e == 1;
      cases++;
    }
    us_bitset_free(&present);
    us_structure_free(s);
  }
  fprintf(stderr, "%d sub-assemblies: %d strongly stable, %d weakly but not strongly; "
          "LPs %ld in %.2f s, MIP nodes %ld in %.2f s (not asserted)\n", cases, yes, differ,
          nodes_e, t_e, nodes_m, t_m);
  CHECK(cases >= 5 * MIP_PILES / 3); /* two sub-assemblies a pile, a few piles fail to generate */
  CHECK(yes > 0);
}

/* 120 sub-assemblies each (two ctest cases, so that they run in parallel) */
static void mip_matches_enumeration_mu03(void) { mip_matches_enumeration_at(0.3, 20261126); }
static void mip_matches_enumeration_mu06(void) { mip_matches_enumeration_at(0.6, 20261127); }

/* Frictionless sub-assemblies: strong = weak on every one (the theorem). */
static void frictionless_strong_equals_weak(void) {
  unsigned long long rng = 7;
  long nodes = 0;
  int cases = 0;
  for (int it = 0; it < 40; it++) {
    us_Structure *s = pile_random(&rng, 4 + it % 3);
    if (!s) continue;
    for (int c = 0; c < s->ncontact; c++) s->contacts[c].mu = 0;
    us_Bitset present;
    CHECK(us_bitset_init(&present, s->nbody) == 0);
    for (int i = 0; i < s->nbody; i++)
      if (pile_rnd(&rng) < 0.7 && !s->bodies[i].fixed) us_bitset_set(&present, i);
    int weak = scene_verdict(s, US_METHOD_LP, &present);
    int e = raw(s, &present, US_STRONG_ENUM, &nodes);
    CHECK_INT(e, ==, weak == US_STABLE ? 1 : 0);
    cases++;
    us_bitset_free(&present);
    us_structure_free(s);
  }
  CHECK(cases >= 30);
}

/* ---------------------------------------------------- errors and memory */

static void bad_arguments(void) {
  us_StrongResult r;
  us_Error err;
  CHECK_INT(us_strong_stability(NULL, NULL, NULL, &r, &err), ==, US_ERR_USAGE);
  us_Structure *s = pinched(1, 0.5);
  CHECK(s);
  us_StrongSettings set = us_strong_default_settings();
  set.tol = 0;
  CHECK_INT(us_strong_stability(s, NULL, &set, &r, &err), ==, US_ERR_USAGE);
  us_structure_free(s);
}

/* Every allocation failing in turn: an error or a full answer, never a
 * crash or a leak (the harness checks leaks after the case). */
static void out_of_memory(void) {
  us_Structure *s = pinched(1, 0.5);
  CHECK(s);
  us_StrongSettings set = us_strong_default_settings();
  set.method = US_STRONG_ENUM;
  int done = 0;
  for (int n = 0; n < 400 && !done; n++) {
    us_StrongResult r;
    us_Error err;
    us_alloc_fail_after(n);
    us_Status st = us_strong_stability(s, NULL, &set, &r, &err);
    us_alloc_fail_after(-1);
    if (st == US_OK) done = r.strong == 0, us_strong_result_free(&r);
    else CHECK(st == US_ERR_NOMEM || st == US_ERR_SOLVER);
  }
  CHECK(done);
  us_structure_free(s);
}

US_TEST_MAIN(T(pinched_weak_not_strong), T(pinched_between_piers), T(pinched_on_ground_strong), T(slope_below_at_above),
             T(frictionless_agree), T(tampered_witness_rejected),
             T(sliding_witness_friction_sign), T(mip_matches_enumeration_mu03), T(mip_matches_enumeration_mu06),
             T(frictionless_strong_equals_weak), T(bad_arguments), T(out_of_memory))
