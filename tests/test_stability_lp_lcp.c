/* Tests of the lp-lcp backend (lp_lcp.c): a hand case, certificates of
 * both verdicts, the size cap's fallback, the deadline, reuse against cold
 * starts, and a differential test against the LP (CLP) on walks over
 * generated walls, pyramids, arches and random piles with mu = 0, 0.5,
 * 1e6 and infinity. */
#include "stability/backend.h"
#include "stability/equilibrium.h"
#include "stability/lp_lcp.h"
#include "piles.h"
#include "scenes.h"
#include "test.h"
#include "walks.h"

#ifdef US_TEST_SANITIZED
#define US_TEST_SHARE 5
#else
#define US_TEST_SHARE 1
#endif

/* ------------------------------------------------------------- helpers */

static us_LpLcpOptions opts; /* options of the custom backends below */

static void *create_custom(const us_Structure *s, const us_StabilitySettings *set, us_Error *err) {
  return us_lp_lcp_create(s, set, &opts, err);
}

/* A workspace on lp-lcp with options (reuse, max_dim). */
static us_Stability *open_lplcp(const us_Structure *s, int reuse, int max_dim) {
  static us_Backend be;
  be = us_backend_lp_lcp;
  be.create = create_custom;
  opts = (us_LpLcpOptions){reuse, max_dim};
  us_StabilitySettings set = us_stability_default_settings();
  set.method = US_METHOD_LP_LCP;
  us_Error err;
  us_Stability *w = us_stability_new_backend(s, &set, &be, &err);
  if (!w) fprintf(stderr, "stability_new: %s\n", err.msg);
  return w;
}

/* A workspace on method m's own backend (us_stability_new). */
static us_Stability *open_method(const us_Structure *s, us_Method m) {
  us_StabilitySettings set = us_stability_default_settings();
  set.method = m;
  us_Error err;
  us_Stability *w = us_stability_new(s, &set, &err);
  if (!w) fprintf(stderr, "stability_new: %s\n", err.msg);
  return w;
}

typedef struct Tally {
  long tests, stable, unstable, own_rays, bad_cert, bad_ray;
  long why[4]; /* CLP fallbacks: over the cap, ray rejected, pivot limit, inaccurate */
} Tally;

static const char *const why_text[4] = {"over the size cap", "ray rejected", "pivot limit",
                                        "inaccurate"};

/* Verdict of `present` on w, with its certificate checked: a stable one
 * must pass the force check, an unstable one that lp-lcp decided by a ray
 * must carry a mechanism that passes. -1 on error. */
static int test_on(us_Stability *w, const us_Bitset *present, Tally *t) {
  us_StabilityResult res;
  us_stability_result_init(&res);
  us_Error err;
  int v = -1;
  if (us_stability_test(w, present, &res, &err) == US_OK)
    v = (int)res.verdict;
  else
    fprintf(stderr, "test: %s\n", err.msg);
  if (t && v == US_STABLE) {
    t->stable++;
    t->bad_cert += !res.check.ok;
  }
  if (t && v == US_UNSTABLE) {
    t->unstable++;
    int own = strstr(res.note, "secondary ray") != NULL;
    t->own_rays += own;
    t->bad_ray += own && !(res.mechanism.nbody > 0 && res.mechanism.ok);
  }
  for (int k = 0; k < 4 && t; k++) t->why[k] += strstr(res.note, why_text[k]) != NULL;
  if (t) t->tests++;
  us_stability_result_free(&res);
  return v;
}

static unsigned long long rng = 0x51ed27a5c3b1f4e9ULL;
static double rnd(void) { return test_rnd(&rng); }

/* A walk of 2 n sub-assemblies tested on lp (ws[0]) and lp-lcp (ws[1]);
 * returns the disagreements. */
static int walk(const us_Structure *s, us_Stability **ws, Tally *t) {
  us_Bitset sub;
  if (us_bitset_init(&sub, s->nbody)) return 1;
  us_bitset_fill(&sub);
  int bad = 0, steps = 2 * s->nbody;
  for (int step = 0; step < steps; step++) {
    int v0 = test_on(ws[0], &sub, NULL), v1 = test_on(ws[1], &sub, t);
    if (v0 < 0 || v0 != v1) {
      fprintf(stderr, "disagreement: lp %d lp-lcp %d (%d of %d bodies, mu %g)\n", v0, v1,
              us_bitset_count(&sub), s->nbody, s->friction);
      bad++;
    }
    walk_step(&sub, s->nbody, step < steps / 2, &rng);
  }
  us_bitset_free(&sub);
  return bad;
}

static us_Structure *generated(int kind, double mu, int size, unsigned long seed) {
  if (kind < 3) return walk_generated(kind, mu, size, seed, 3, 2);
  return pile_random(&rng, 4 + (int)(rnd() * 9)); /* mu: set_mu */
}

/* Every contact of a pile gets coefficient mu (the piles draw their own). */
static void set_mu(us_Structure *s, double mu) {
  for (int c = 0; c < s->ncontact; c++) s->contacts[c].mu = mu;
}

/* ----------------------------------------------------------------- cases */

/* The full structure's verdict on lp-lcp, with its certificate checked
 * (force check when stable, mechanism when unstable by a ray). */
static int full_verdict(const us_Structure *s, Tally *t, char *note, size_t note_sz) {
  us_Stability *w = open_method(s, US_METHOD_LP_LCP);
  if (!w) return -1;
  us_Bitset all;
  if (us_bitset_init(&all, s->nbody)) return us_stability_free(w), -1;
  us_bitset_fill(&all);
  us_StabilityResult res;
  us_stability_result_init(&res);
  us_Error err;
  int v = us_stability_test(w, &all, &res, &err) == US_OK ? (int)res.verdict : -1;
  snprintf(note, note_sz, "%s", res.note);
  if (v == US_STABLE) t->bad_cert += !res.check.ok;
  if (v == US_UNSTABLE) t->bad_ray += !(res.mechanism.nbody > 0 && res.mechanism.ok);
  us_stability_result_free(&res);
  us_bitset_free(&all);
  us_stability_free(w);
  return v;
}

/* A block on the ground stands; on a fixed ledge [0, 1] it stands with
 * its centre above the ledge (x 0.8) and tips with it past the edge
 * (x 1.1): a secondary ray whose Farkas ray and mechanism check. */
static void hand_cases(void) {
  const double x0[3] = {0.0, 0.3, 0.6};
  const int want[3] = {US_STABLE, US_STABLE, US_UNSTABLE};
  for (int k = 0; k < 3; k++) {
    us_Structure *s = us_structure_new(2);
    double ledge[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    if (k) scene_polygon(s, "ledge", 4, ledge, 1);
    scene_box(s, "b", x0[k], k ? 1.0 : 0.0, 1.0, 0.5, 1.0);
    s = scene_seal(s);
    CHECK(s);
    Tally t = {0};
    char note[160];
    int v = full_verdict(s, &t, note, sizeof note);
    printf("hand case %d: %s (%s)\n", k, us_verdict_name((us_Verdict)v), note);
    us_structure_free(s);
    CHECK_INT(v, ==, want[k]);
    CHECK_INT(t.bad_cert + t.bad_ray, ==, 0);
    CHECK(strstr(note, v == US_STABLE ? "lp-lcp: feasible" : "lp-lcp: secondary ray"));
  }
}

/* Friction values of the differential test (1e6: a wide finite cone with
 * its n column; INFINITY: the half-space). */
static const double mus[4] = {0.0, 0.5, 1e6, INFINITY};

/* One structure of the differential test: kind 0 wall, 1 pyramid, 2 arch,
 * 3 random pile. NULL when a draw fails. */
static us_Structure *diff_scene(int kind, int round) {
  double mu = mus[round % 4];
  int size = 2 + round % 4;
  us_Structure *s = generated(kind, mu, size, (unsigned long)round + 1);
  if (s && kind == 3) set_mu(s, mu);
  return s;
}

/* lp-lcp and lp agree on every sub-assembly of walks over generated
 * structures; every certificate checks. */
static void differential(void) {
  Tally t = {0};
  int bad = 0, structures = 0, rounds = 48 / US_TEST_SHARE;
  long fallbacks = 0, reused = 0, pivots = 0;
  for (int kind = 0; kind < 4; kind++)
    for (int round = 0; round < rounds * (kind == 3 ? 3 : 1); round++) {
      us_Structure *s = diff_scene(kind, round);
      if (!s) continue;
      structures++;
      us_Stability *ws[2] = {open_method(s, US_METHOD_LP), open_method(s, US_METHOD_LP_LCP)};
      CHECK(ws[0] && ws[1]);
      bad += walk(s, ws, &t);
      const us_StabilityInfo *in = us_stability_info(ws[1]);
      fallbacks += in->lp_fallbacks, reused += in->reused, pivots += in->pivots;
      us_stability_free(ws[0]);
      us_stability_free(ws[1]);
      us_structure_free(s);
    }
  printf("differential: %d structures, %ld sub-assemblies (stable %ld, unstable %ld, %ld by "
         "lp-lcp's own ray), %ld pivots, %ld warm starts, %ld CLP fallbacks, %d disagreements\n",
         structures, t.tests, t.stable, t.unstable, t.own_rays, pivots, reused, fallbacks, bad);
  printf("fallbacks: over the cap %ld, ray rejected %ld, pivot limit %ld, inaccurate %ld\n",
         t.why[0], t.why[1], t.why[2], t.why[3]);
  CHECK_INT(bad, ==, 0);
  CHECK_INT(t.bad_cert, ==, 0);
  CHECK_INT(t.bad_ray, ==, 0);
  CHECK(t.tests >= 2000 / US_TEST_SHARE);
  CHECK(t.stable > t.tests / 10 && t.unstable > t.tests / 10);
  CHECK(fallbacks * 20 < t.tests); /* lp-lcp decides almost all itself */
}

/* Above the size cap every test goes to CLP (counted), with the same
 * verdicts and certificates. */
static void size_cap_falls_back(void) {
  us_Structure *s = generated(0, 0.5, 4, 1);
  CHECK(s);
  us_Stability *ws[2] = {open_method(s, US_METHOD_LP), open_lplcp(s, 1, 40)};
  CHECK(ws[0] && ws[1]);
  Tally t = {0};
  int bad = walk(s, ws, &t);
  long fb = us_stability_info(ws[1])->lp_fallbacks;
  us_stability_free(ws[0]);
  us_stability_free(ws[1]);
  us_structure_free(s);
  CHECK_INT(bad, ==, 0);
  CHECK_INT(t.bad_cert, ==, 0);
  CHECK(fb > 0);
}

/* A deadline in the past: the backend itself stops undecided with a note
 * that says "time limit" (the front end checks the clock too, before). */
static void deadline_stops(void) {
  us_Structure *s = generated(1, 0.5, 3, 1);
  CHECK(s);
  us_StabilitySettings set = us_stability_default_settings();
  us_Error err;
  us_LpLcpOptions o = {1, 0};
  void *ws = us_lp_lcp_create(s, &set, &o, &err);
  us_EqSystem e;
  us_Bitset all;
  CHECK(ws && us_eq_init(&e, s) == 0 && us_bitset_init(&all, s->nbody) == 0);
  us_bitset_fill(&all);
  CHECK(us_eq_build(&e, &all) == 0);
  us_backend_lp_lcp.set_deadline(ws, us_now() - 1.0);
  double f[4096];
  char note[128] = "";
  us_StabilityInfo info = {0};
  us_BackendOut out = {US_STABLE, f, &info, note, sizeof note};
  us_Status st = us_backend_lp_lcp.solve(ws, &(us_BackendProblem){.sys = &e, .restart = 1}, &out,
                                         &err);
  us_Verdict v = out.verdict;
  us_backend_lp_lcp.destroy(ws);
  us_eq_free(&e);
  us_bitset_free(&all);
  us_structure_free(s);
  CHECK_INT(st, ==, US_OK);
  CHECK_INT(v, ==, US_UNDECIDED);
  CHECK(strstr(note, "time limit"));
}

/* Pivots of a top-down take-down (bodies were added bottom-up) with and
 * without reuse; verdicts equal. */
static int takedown(const us_Structure *s, long piv[2], long *warm) {
  us_Stability *ws[2] = {open_lplcp(s, 0, 0), open_lplcp(s, 1, 0)};
  us_Bitset sub = {0};
  int bad = !ws[0] || !ws[1] || us_bitset_init(&sub, s->nbody) ? -1 : 0;
  if (!bad) us_bitset_fill(&sub);
  for (int i = s->nbody - 1; i >= 0 && !bad; i--) {
    bad += test_on(ws[0], &sub, NULL) != test_on(ws[1], &sub, NULL);
    us_bitset_clear(&sub, i);
  }
  for (int k = 0; k < 2; k++) piv[k] = ws[k] ? us_stability_info(ws[k])->pivots : 0;
  *warm = ws[1] ? us_stability_info(ws[1])->reused : 0;
  us_bitset_free(&sub);
  us_stability_free(ws[0]);
  us_stability_free(ws[1]);
  return bad;
}

/* Reuse saves pivots on a column and a wall taken down from the top. */
static void reuse_saves_pivots(void) {
  us_Structure *sc[3] = {scene_column(12), generated(0, 0.5, 6, 1), generated(0, 0.0, 5, 1)};
  const char *name[3] = {"column 12", "wall 6x6 mu 0.5", "wall 5x5 mu 0"};
  for (int k = 0; k < 3; k++) {
    CHECK(sc[k]);
    long piv[2] = {0, 0}, warm = 0;
    int bad = takedown(sc[k], piv, &warm);
    printf("reuse: %s, %d tests: pivots cold %ld, with reuse %ld (%ld warm starts, setup "
           "pivots included)\n",
           name[k], sc[k]->nbody, piv[0], piv[1], warm);
    CHECK_INT(bad, ==, 0);
    CHECK_INT(warm, ==, sc[k]->nbody - 1);
    CHECK_INT(piv[1], <, piv[0]);
  }
  for (int k = 0; k < 3; k++) us_structure_free(sc[k]);
}

US_TEST_MAIN(T(hand_cases), T(differential), T(size_cap_falls_back), T(deadline_stops),
             T(reuse_saves_pivots))
