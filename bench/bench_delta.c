/* Benchmark of tests by change (docs/planning.md, "Tests by change"): the
 * mean time of one stability test on walls (2 rows) and pyramids of about
 * 1,000, 10,000 and 100,000 blocks, when the sub-assembly is stated as a
 * whole bitset (us_stability_test) and as a change (us_stability_add,
 * us_stability_test_current), over the same sequence of tests: the
 * structure built bottom-up in its plan's order. Then the planner's search
 * and verify as the library runs them (us_plan, us_verify_steps), and the
 * exponent of the per-test time from 1,000 to 100,000 blocks. Each time is
 * the best of `reps` runs. Timings live here, never in the tests.
 * Usage: bench_delta [quick]   (quick: up to 10,000 blocks, one run);
 * bench_delta profile wall|pyramid SIZE: only the tests by change, five
 * times over, for a profiler (perf record). */
#include "unstack/unstack.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  double bitset, change;     /* seconds per test, best run */
  double search, verify;     /* seconds, best run */
  long tests;
  int ok;
} Row;

/* The build order of s: its plan's removal order reversed. NULL if none. */
static int *build_order(const us_Structure *s, int *n) {
  us_PlanSettings set = us_plan_default_settings();
  us_Plan p;
  if (us_plan(s, &set, &p, NULL) || p.status != US_PLAN_FOUND) return NULL;
  int *b = malloc((size_t)p.nsteps * sizeof(int));
  for (int k = 0; b && k < p.nsteps; k++) b[k] = p.order[p.nsteps - 1 - k];
  *n = p.nsteps;
  us_plan_free(&p);
  return b;
}

/* Seconds per test of the build sequence, by bitset (change 0) or by
 * change (1); every test must be stable (else -1). */
static double per_test(const us_Structure *s, const int *order, int n, int change) {
  us_StabilitySettings set = us_stability_default_settings();
  set.skip_forces = 1;
  us_Stability *w = us_stability_new(s, &set, NULL);
  us_Bitset node;
  if (!w || us_bitset_init(&node, s->nbody)) return -1;
  us_StabilityResult res;
  us_stability_result_init(&res);
  int ok = 1;
  double t0 = us_now();
  for (int k = 0; k < n && ok; k++) {
    us_Status st;
    if (change) {
      us_stability_add(w, order[k], NULL);
      st = us_stability_test_current(w, &res, NULL);
    } else {
      us_bitset_set(&node, order[k]);
      st = us_stability_test(w, &node, &res, NULL);
    }
    ok = st == US_OK && res.verdict == US_STABLE;
  }
  double t = (us_now() - t0) / (n > 0 ? n : 1);
  us_stability_result_free(&res);
  us_bitset_free(&node);
  us_stability_free(w);
  return ok ? t : -1;
}

/* The planner's search time, its tests, and verify's time. */
static void whole(const us_Structure *s, Row *r) {
  us_PlanSettings set = us_plan_default_settings();
  us_Plan p;
  if (us_plan(s, &set, &p, NULL) || p.status != US_PLAN_FOUND) return;
  r->search = fmin(r->search, p.stats.time_search);
  r->tests = p.stats.tests;
  us_StabilitySettings st = us_stability_default_settings();
  us_VerifyReport rep;
  double t0 = us_now();
  int bad = us_verify_steps(s, &st, p.order, p.nsteps, p.group_start, p.ngroups, &rep, NULL);
  r->verify = fmin(r->verify, us_now() - t0);
  r->ok = !bad && rep.ok;
  us_plan_free(&p);
}

static Row measure(const us_Structure *s, int reps) {
  Row r = {INFINITY, INFINITY, INFINITY, INFINITY, 0, 0};
  int n = 0, *order = build_order(s, &n);
  if (!order) return r;
  for (int k = 0; k < reps; k++) {
    double b = per_test(s, order, n, 0), c = per_test(s, order, n, 1);
    if (b >= 0) r.bitset = fmin(r.bitset, b);
    if (c >= 0) r.change = fmin(r.change, c);
    whole(s, &r);
  }
  free(order);
  return r;
}

static us_Structure *scene(int pyramid, int size) {
  us_GenSettings g = us_gen_default_settings();
  if (pyramid) {
    g.n = size;
    return us_gen_pyramid(&g, NULL);
  }
  g.rows = 2;
  g.cols = size;
  return us_gen_wall(&g, NULL);
}

/* Five runs of the tests by change of one scene (for perf). */
static int profile(int pyramid, int size) {
  us_Structure *s = scene(pyramid, size);
  int n = 0, *order = s ? build_order(s, &n) : NULL;
  if (!order) return 1;
  double t0 = us_now();
  for (int k = 0; k < 5; k++) per_test(s, order, n, 1);
  printf("%d blocks: %.3f us per test by change\n", n, (us_now() - t0) / 5 / n * 1e6);
  free(order);
  us_structure_free(s);
  return 0;
}

int main(int argc, char **argv) {
  if (argc > 3 && strcmp(argv[1], "profile") == 0)
    return profile(strcmp(argv[2], "pyramid") == 0, atoi(argv[3]));
  int quick = argc > 1 && strcmp(argv[1], "quick") == 0, reps = quick ? 1 : 3;
  static const int walls[3] = {507, 5007, 50007}, pyrs[3] = {45, 141, 447};
  int nsize = quick ? 2 : 3;
  printf("| scene | blocks | per test, bitset (us) | per test, by change (us) | search (s) | "
         "search per test (us) | verify (s) | verified |\n|---|---|---|---|---|---|---|---|\n");
  for (int fam = 0; fam < 2; fam++) {
    double first[3] = {0}, last[3] = {0};
    int nfirst = 0, nlast = 0;
    for (int k = 0; k < nsize; k++) {
      us_Structure *s = scene(fam, fam ? pyrs[k] : walls[k]);
      if (!s) return 1;
      int n = us_structure_movable_count(s);
      Row r = measure(s, reps);
      printf("| %s | %d | %.3f | %.3f | %.4f | %.3f | %.4f | %s |\n", fam ? "pyramid" : "wall", n,
             r.bitset * 1e6, r.change * 1e6, r.search, r.tests ? r.search / (double)r.tests * 1e6 : 0.0,
             r.verify, r.ok ? "yes" : "NO");
      fflush(stdout);
      double v[3] = {r.bitset, r.change, r.tests ? r.search / (double)r.tests : 0.0};
      if (k == 0) memcpy(first, v, sizeof v), nfirst = n;
      memcpy(last, v, sizeof v), nlast = n;
      us_structure_free(s);
    }
    double span = log((double)nlast / nfirst);
    printf("\n%s: exponent of the per-test time from %d to %d blocks: bitset %.2f, by change %.2f, "
           "search %.2f\n\n", fam ? "pyramid" : "wall", nfirst, nlast, log(last[0] / first[0]) / span,
           log(last[1] / first[1]) / span, log(last[2] / first[2]) / span);
  }
  return 0;
}
