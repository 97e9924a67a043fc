/* Tests of the two LP backends on many random structures:
 *  - random columns of boxes against the exact statics of a column (each
 *    sub-stack's centre of mass must lie over its support interval),
 *    skipping cases within 1e-6 of a boundary;
 *  - random stacks of rows of boxes (gaps, touching neighbours, random mu
 *    in {0, 0.3, 0.7}) and random sub-assemblies: CLP and lp_solve agree,
 *    and every stable verdict carries a passing certificate;
 *  - random leaning pairs (friction decides);
 *  - a 1,000-brick running-bond wall: verdicts and the time per test,
 *    cold and after removing one brick (printed; US_LP_BENCH=N sets the
 *    number of one-brick steps timed). */
#include "stability/backend.h"
#include "stability/certificate.h"
#include "stability/lp_gen.h"
#include "scenes.h"
#include "test.h"

static unsigned long long rng_state = 2024;
static double rnd(void) { return test_lcg(&rng_state); }
static double uniform(double a, double b) { return a + (b - a) * rnd(); }

/* Verdicts of both backends on one workspace each. */
typedef struct Pair {
  us_Stability *w[2];
  us_StabilityResult r[2];
} Pair;

static int pair_open(Pair *p, const us_Structure *s) {
  memset(p, 0, sizeof *p);
  us_Error err;
  for (int m = 0; m < 2; m++) {
    us_StabilitySettings set = us_stability_default_settings();
    set.method = m ? US_METHOD_LPSOLVE : US_METHOD_LP;
    p->w[m] = us_stability_new(s, &set, &err);
    if (!p->w[m]) return -1;
  }
  return 0;
}

static void pair_close(Pair *p) {
  for (int m = 0; m < 2; m++) {
    us_stability_free(p->w[m]);
    us_stability_result_free(&p->r[m]);
  }
}

/* Both verdicts; -1 on error, -2 if they differ, -3 if stable without an
 * ok certificate, else the common verdict. */
static int pair_test(Pair *p, const us_Bitset *present) {
  us_Error err;
  for (int m = 0; m < 2; m++)
    if (us_stability_test(p->w[m], present, &p->r[m], &err) != US_OK) {
      fprintf(stderr, "test: %s\n", err.msg);
      return -1;
    }
  if (p->r[0].verdict != p->r[1].verdict) {
    fprintf(stderr, "disagree: clp %s (%s), lp_solve %s (%s)\n",
            us_verdict_name(p->r[0].verdict), p->r[0].note, us_verdict_name(p->r[1].verdict),
            p->r[1].note);
    return -2;
  }
  for (int m = 0; m < 2; m++)
    if (p->r[m].verdict == US_STABLE && !p->r[m].check.ok) return -3;
  return (int)p->r[0].verdict;
}

/* ------------------------------------------------------- column oracle */

#define COL_MAX 8

/* Exact answer for a column: sub-stack k..n-1 must have its centre of
 * mass over [lo_k, hi_k], the overlap with the block below (ground: the
 * bottom face). Returns the verdict, or -1 when a margin is below eps. */
static int column_oracle(int n, const double *x, const double *w, const double *h, double eps) {
  int stable = 1;
  for (int k = n - 1; k >= 0; k--) {
    double m = 0, mx = 0;
    for (int i = k; i < n; i++) {
      m += w[i] * h[i];
      mx += w[i] * h[i] * (x[i] + 0.5 * w[i]);
    }
    double cx = mx / m;
    double lo = k ? US_MAX(x[k - 1], x[k]) : x[0];
    double hi = k ? US_MIN(x[k - 1] + w[k - 1], x[k] + w[k]) : x[0] + w[0];
    double margin = US_MIN(cx - lo, hi - cx);
    if (fabs(margin) < eps) return -1;
    if (margin < 0) stable = 0;
  }
  return stable ? US_STABLE : US_UNSTABLE;
}

static void random_columns(void) {
  int counts[2] = {0, 0}, tried = 0;
  while (counts[0] + counts[1] < 200 && tried < 1000) {
    tried++;
    int n = 2 + (int)(rnd() * 5);
    double x[COL_MAX], w[COL_MAX], h[COL_MAX], y = 0;
    us_Structure *s = us_structure_new(2);
    s->friction = rnd() < 0.5 ? 0.0 : 0.7;
    for (int i = 0; i < n; i++) {
      w[i] = uniform(0.4, 1.6);
      h[i] = uniform(0.2, 1.0);
      /* overlap with the block below at least 0.05 */
      x[i] = i ? uniform(x[i - 1] - w[i] + 0.05, x[i - 1] + w[i - 1] - 0.05) : 0.0;
      scene_box_auto(s, x[i], y, w[i], h[i]);
      y += h[i];
    }
    us_Error err;
    CHECK_OK(us_structure_finalize(s, &err), &err);
    int want = column_oracle(n, x, w, h, 1e-6);
    if (want >= 0) {
      Pair p;
      CHECK(pair_open(&p, s) == 0);
      us_Bitset all;
      CHECK(us_bitset_init(&all, n) == 0);
      us_bitset_fill(&all);
      int got = pair_test(&p, &all);
      us_bitset_free(&all);
      pair_close(&p);
      CHECK_INT(got, ==, want);
      counts[want]++;
    }
    us_structure_free(s);
  }
  CHECK(counts[0] > 30 && counts[1] > 30); /* both outcomes well sampled */
}

/* ------------------------------------------------- random row stacks */

/* Rows of 1-3 boxes, each row on top of the previous one's height, with
 * random gaps (some zero: touching neighbours). */
static us_Structure *random_rows(void) {
  us_Structure *s = us_structure_new(2);
  static const double mus[3] = {0.0, 0.3, 0.7};
  s->friction = mus[(int)(rnd() * 3)];
  scene_random_rows(s, rnd, 0.6);
  return scene_seal(s);
}

static void backends_agree_rows(void) {
  int counts[3] = {0, 0, 0};
  for (int t = 0; t < 300; t++) {
    us_Structure *s = random_rows();
    CHECK(s);
    Pair p;
    CHECK(pair_open(&p, s) == 0);
    us_Bitset sub;
    CHECK(us_bitset_init(&sub, s->nbody) == 0);
    for (int k = 0; k < 3; k++) {
      us_bitset_fill(&sub);
      if (k > 0)
        for (int i = 0; i < s->nbody; i++)
          if (rnd() < 0.3) us_bitset_clear(&sub, i);
      int v = pair_test(&p, &sub);
      if (v < 0) fprintf(stderr, "structure %d, subset %d\n", t, k);
      CHECK(v >= 0);
      counts[v]++;
    }
    us_bitset_free(&sub);
    pair_close(&p);
    us_structure_free(s);
  }
  CHECK(counts[US_STABLE] > 50 && counts[US_UNSTABLE] > 50);
  CHECK_INT(counts[US_UNDECIDED], ==, 0);
}

/* Two slabs leaning on each other (see test_stability.c: inverted_v) with
 * random feet, apex and friction: friction decides; the backends agree. */
static void backends_agree_leaning(void) {
  int counts[3] = {0, 0, 0};
  for (int t = 0; t < 150; t++) {
    us_Structure *s = us_structure_new(2);
    s->friction = uniform(0.0, 0.4);
    double foot = uniform(0.1, 0.5), top = uniform(1.0, 3.0), ext = uniform(0.2, 0.6);
    double l[8] = {0, 0, foot, 0, 1, top, 1, top + ext};
    double r[8] = {2 - foot, 0, 2, 0, 1, top + ext, 1, top};
    us_Error err;
    CHECK(scene_polygon(s, "left", 4, l, 0) == 0);
    CHECK(us_structure_add_body(s,
                                &(us_BodyDef){.id = "right",
                                              .nvert = 4,
                                              .xy = r,
                                              .density = uniform(0.5, 2),
                                              .friction = -1},
                                &err) == 1);
    CHECK_OK(us_structure_finalize(s, &err), &err);
    Pair p;
    CHECK(pair_open(&p, s) == 0);
    us_Bitset all;
    CHECK(us_bitset_init(&all, 2) == 0);
    us_bitset_fill(&all);
    int v = pair_test(&p, &all);
    CHECK(v >= 0);
    counts[v]++;
    us_bitset_free(&all);
    pair_close(&p);
    us_structure_free(s);
  }
  CHECK(counts[US_STABLE] > 10 && counts[US_UNSTABLE] > 10);
}

/* -------------------------------------------------- 1,000-brick wall */

/* rows x cols running bond (odd rows shifted by half a brick), 2 x 1. */
static us_Structure *wall(int rows, int cols) {
  us_Structure *s = us_structure_new(2);
  for (int r = 0; r < rows; r++)
    for (int c = 0; c < cols; c++) scene_box_auto(s, c * 2.0 + (r % 2), r * 1.0, 2.0, 1.0);
  us_Error err;
  if (us_structure_finalize(s, &err) != US_OK) {
    us_structure_free(s);
    return NULL;
  }
  return s;
}

static void wall_1000(void) {
  int rows = 10, cols = 100;
  us_Structure *s = wall(rows, cols);
  CHECK(s);
  const char *env = getenv("US_LP_BENCH");
  int reps = env ? atoi(env) : 3;
  if (reps < 1) reps = 1;
  us_Bitset p;
  CHECK(us_bitset_init(&p, s->nbody) == 0);
  for (int m = 0; m < 2; m++) {
    us_StabilitySettings set = us_stability_default_settings();
    set.method = m ? US_METHOD_LPSOLVE : US_METHOD_LP;
    us_Error err;
    us_Stability *w = us_stability_new(s, &set, &err);
    CHECK(w);
    us_StabilityResult res = {0};
    us_bitset_fill(&p);
    double t0 = us_now();
    CHECK_OK(us_stability_test(w, &p, &res, &err), &err);
    double t_cold = us_now() - t0;
    CHECK_INT(res.verdict, ==, US_STABLE);
    /* planner-like: remove top-row bricks one at a time (each rests fully
     * on two bricks below, so every remainder stands) */
    t0 = us_now();
    for (int k = 0; k < reps; k++) {
      us_bitset_clear(&p, (rows - 1) * cols + (k * 37) % cols);
      CHECK_OK(us_stability_test(w, &p, &res, &err), &err);
      CHECK_INT(res.verdict, ==, US_STABLE);
    }
    double t_step = (us_now() - t0) / reps;
    /* without the bottom row nothing touches the ground: it all falls
     * (a few missing bottom bricks would not do: the bond arches over) */
    us_bitset_fill(&p);
    for (int c = 0; c < cols; c++) us_bitset_clear(&p, c);
    t0 = us_now();
    CHECK_OK(us_stability_test(w, &p, &res, &err), &err);
    double t_unst = us_now() - t0;
    CHECK_INT(res.verdict, ==, US_UNSTABLE);
    const us_StabilityInfo *info = us_stability_info(w);
    printf("  %-8s wall %dx%d, %d contacts: full wall %.1f ms, one brick less %.1f ms "
           "(mean of %d), no bottom row (unstable) %.1f ms; certificate checks %.2f ms in all; "
           "%ld reused\n",
           us_method_name(set.method), rows, cols, s->ncontact, 1e3 * t_cold, 1e3 * t_step, reps,
           1e3 * t_unst, 1e3 * info->check_time, info->reused);
    us_stability_result_free(&res);
    us_stability_free(w);
  }
  us_bitset_free(&p);
  us_structure_free(s);
}

US_TEST_MAIN(T(random_columns), T(backends_agree_rows), T(backends_agree_leaning), T(wall_1000))
