/* LP fallbacks of the LCP backends on the benchmark's workloads (issue 10):
 * plans with lcp-reuse on generated stacks (mu = 0.5), assembled and taken
 * down, must (a) give the plan lp gives (same status, order, stable and
 * unstable counts: a differing verdict would change the path or the
 * counts), (b) leave few tests to the LP and (c) re-seed and skip the
 * friction LCP no more often than measured (issue 23: counts, not times). The bounds are properties
 * measured on fixed seeds, deterministic, with room for round-off; a
 * regression of the solver or of the cone LCP that settles its open cases
 * makes them fail. */
#include "test.h"

typedef struct Load {
  const char *name;
  int kind; /* 0 stacker (rows 15, width 12, seed), 1 pyramid (rows), 2 wall (size x size), 3 column */
  int size;
  unsigned long seed;
  double max_share; /* largest share of tests the LP may decide */
  int max_seeds[2], max_skips[2]; /* lcp-reuse re-seeds, skipped friction LCPs: assemble, dfs */
} Load;

static us_Structure *build(const Load *l) {
  us_GenSettings g = us_gen_default_settings();
  g.friction = 0.5;
  g.seed = l->seed;
  us_Error err;
  switch (l->kind) {
  case 0: g.rows = l->size, g.width = 12; return us_gen_stacker(&g, &err);
  case 1: g.n = l->size; return us_gen_pyramid(&g, &err);
  case 2: g.rows = l->size, g.cols = l->size; return us_gen_wall(&g, &err);
  default: g.n = l->size; return us_gen_column(&g, &err);
  }
}

static int same_plan(const us_Plan *a, const us_Plan *b) {
  if (a->status != b->status || a->nsteps != b->nsteps) return 0;
  if (a->stats.stable != b->stats.stable || a->stats.unstable != b->stats.unstable) return 0;
  for (int i = 0; i < a->nsteps; i++)
    if (a->order[i] != b->order[i]) return 0;
  return 1;
}

/* One workload, one search: lp and lcp-reuse plan it; returns the LP
 * fallbacks of lcp-reuse, its tests, re-seeds and skips, -1 on a
 * disagreement. */
static long run_one(const us_Structure *s, us_Search search, long *tests, long *seeds,
                    long *skips) {
  us_PlanSettings a = us_plan_default_settings();
  a.search = search;
  a.direction = US_DIR_DOWN;
  us_PlanSettings b = a;
  a.stability.method = US_METHOD_LP;
  b.stability.method = US_METHOD_LCP_REUSE;
  us_Plan pa, pb;
  us_Error err;
  if (us_plan(s, &a, &pa, &err)) return -1;
  if (us_plan(s, &b, &pb, &err)) {
    us_plan_free(&pa);
    return -1;
  }
  long fb = same_plan(&pa, &pb) ? pb.stats.stability.lp_fallbacks : -1;
  *tests = pb.stats.tests;
  *seeds = pb.stats.stability.lcp_seeds;
  *skips = pb.stats.stability.lcp_skips;
  us_plan_free(&pa);
  us_plan_free(&pb);
  return fb;
}

static void check_loads(const Load *loads, int n) {
  for (int k = 0; k < n; k++) {
    us_Structure *s = build(&loads[k]);
    CHECK(s);
    for (int srch = 0; srch < 2; srch++) {
      long tests = 0, seeds = 0, skips = 0;
      long fb = run_one(s, srch ? US_SEARCH_DFS : US_SEARCH_ASSEMBLE, &tests, &seeds, &skips);
      fprintf(stderr, "%s %s: %ld of %ld tests to the LP, re-seeded %ld, LCP skipped %ld\n",
              loads[k].name, srch ? "dfs down" : "assemble", fb, tests, seeds, skips);
      if (fb < 0) us_structure_free(s);
      CHECK(fb >= 0); /* same plan as lp */
      if ((double)fb > loads[k].max_share * (double)tests) us_structure_free(s);
      CHECK((double)fb <= loads[k].max_share * (double)tests);
      if (seeds > loads[k].max_seeds[srch] || skips > loads[k].max_skips[srch])
        us_structure_free(s);
      CHECK(seeds <= loads[k].max_seeds[srch]);
      CHECK(skips <= loads[k].max_skips[srch]);
    }
    us_structure_free(s);
  }
}

/* The LP decides no test on these workloads (since the cone LCP's Lemke
 * fallback; before it, stacker seeds 1, 3 and 4 sent 2 % to 17 % of their
 * tests to the LP), and since failed repairs are retried from scratch
 * (issue 23) lcp-reuse re-seeds and skips under 1 % of the tests: none
 * at all but on seed 4 taken down, whose first scratch run (the whole
 * stack) and one retry end degenerate: 2 re-seeds of 203 tests. Before
 * the retry: 3-12 re-seeds and 4-109 skipped tests on seeds 1, 3 and 4. */
static void under_one_percent(void) {
  static const Load loads[] = {
      {"column50", 3, 50, 1, 0.01, {0, 0}, {0, 0}},
      {"pyramid91", 1, 13, 1, 0.01, {0, 0}, {0, 0}},
      {"wall10x10", 2, 10, 1, 0.01, {0, 0}, {0, 0}},
      {"stacker seed 1", 0, 15, 1, 0.01, {0, 0}, {0, 0}},
      {"stacker seed 2", 0, 15, 2, 0.01, {0, 0}, {0, 0}},
      {"stacker seed 3", 0, 15, 3, 0.01, {0, 0}, {0, 0}},
      {"stacker seed 4", 0, 15, 4, 0.01, {0, 2}, {0, 0}},
      {"stacker seed 5", 0, 15, 5, 0.01, {0, 0}, {0, 0}},
  };
#ifdef US_TEST_SANITIZED /* memory errors, not statistics: seeds 1 and 4 (its re-seeds) */
  static const int pick[] = {0, 1, 2, 3, 6};
  Load some[sizeof pick / sizeof pick[0]];
  for (size_t k = 0; k < sizeof pick / sizeof pick[0]; k++) some[k] = loads[pick[k]];
  check_loads(some, (int)(sizeof some / sizeof some[0]));
#else
  check_loads(loads, (int)(sizeof loads / sizeof loads[0]));
#endif
}

US_TEST_MAIN({"under_one_percent", under_one_percent})
