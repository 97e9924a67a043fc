/* Tests of src/plan: the disassembly search and plan verification.
 *
 * The reference is independent of the search: for small structures every
 * subset is tested once and a dynamic programme over subsets decides
 * whether a stable path to the empty set exists; DFS, BFS and both
 * directions must agree with it, and every order they return must pass
 * us_verify_order. */
#include "scenes.h"
#include "test.h"

static us_Bitset all_movable(const us_Structure *s) {
  us_Bitset b = {0};
  us_structure_movable_set(s, &b);
  return b;
}

static us_PlanStatus plan_status(const us_Structure *s, us_Search search, us_Direction dir,
                                 us_Plan *p) {
  us_PlanSettings set = us_plan_default_settings();
  set.search = search;
  set.direction = dir;
  us_Error err;
  if (us_plan(s, &set, p, &err) != US_OK) {
    fprintf(stderr, "plan: %s\n", err.msg);
    return (us_PlanStatus)-1;
  }
  return p->status;
}

static int order_valid(const us_Structure *s, const us_Plan *p) {
  us_StabilitySettings st = us_stability_default_settings();
  us_VerifyReport rep;
  us_Error err;
  if (us_verify_order(s, &st, p->order, p->nsteps, &rep, &err) != US_OK) return 0;
  return rep.ok;
}

static void column_top_down(void) {
  us_Structure *s = scene_column(5);
  CHECK(s);
  us_Plan p;
  CHECK_INT(plan_status(s, US_SEARCH_DFS, US_DIR_DOWN, &p), ==, US_PLAN_FOUND);
  CHECK_INT(p.nsteps, ==, 5);
  for (int k = 0; k < 5; k++) CHECK_INT(p.order[k], ==, 4 - k);
  CHECK_INT(p.stats.unstable, ==, 0);
  CHECK(order_valid(s, &p));
  us_plan_free(&p);
  us_structure_free(s);
}

/* More than 64 bodies: the bitsets span several words. */
static void column_of_150(void) {
  us_Structure *s = scene_column(150);
  CHECK(s);
  us_Plan p;
  CHECK_INT(plan_status(s, US_SEARCH_DFS, US_DIR_DOWN, &p), ==, US_PLAN_FOUND);
  CHECK_INT(p.nsteps, ==, 150);
  CHECK(order_valid(s, &p));
  us_plan_free(&p);
  us_structure_free(s);
}

static void cantilever_needs_backtracking(void) {
  us_Structure *s = scene_cantilever();
  CHECK(s);
  us_Plan p;
  CHECK_INT(plan_status(s, US_SEARCH_DFS, US_DIR_DOWN, &p), ==, US_PLAN_FOUND);
  CHECK(p.stats.unstable > 0); /* the greedy first move failed */
  CHECK_INT(p.order[0], ==, us_structure_find_body(s, "L"));
  CHECK(order_valid(s, &p));
  us_plan_free(&p);
  us_structure_free(s);
}

static void leaning_slabs_have_no_order(void) {
  us_Structure *s = scene_leaning(0.5);
  CHECK(s);
  us_Plan p;
  CHECK_INT(plan_status(s, US_SEARCH_DFS, US_DIR_DOWN, &p), ==, US_PLAN_NONE);
  us_plan_free(&p);
  CHECK_INT(plan_status(s, US_SEARCH_BFS, US_DIR_DOWN, &p), ==, US_PLAN_NONE);
  us_plan_free(&p);
  us_structure_free(s);
  s = scene_leaning(0.0);
  CHECK(s);
  CHECK_INT(plan_status(s, US_SEARCH_DFS, US_DIR_DOWN, &p), ==, US_PLAN_UNSTABLE);
  us_plan_free(&p);
  us_structure_free(s);
}

static void limits_stop_the_search(void) {
  us_Structure *s = scene_column(20);
  CHECK(s);
  us_PlanSettings set = us_plan_default_settings();
  set.max_tests = 5;
  us_Plan p;
  us_Error err;
  CHECK_OK(us_plan(s, &set, &p, &err), &err);
  CHECK_INT(p.status, ==, US_PLAN_LIMIT);
  CHECK(p.stats.tests <= 5);
  us_plan_free(&p);
  us_structure_free(s);
}

static void certificates_per_step(void) {
  us_Structure *s = scene_cantilever();
  CHECK(s);
  us_PlanSettings set = us_plan_default_settings();
  set.certificates = 1;
  us_Plan p;
  us_Error err;
  CHECK_OK(us_plan(s, &set, &p, &err), &err);
  CHECK_INT(p.status, ==, US_PLAN_FOUND);
  CHECK(p.certs != NULL);
  us_Bitset node = all_movable(s);
  for (int k = 0; k <= p.nsteps; k++) {
    if (k > 0) us_bitset_clear(&node, p.order[k - 1]);
    us_CertCheck c = us_certificate_check(s, &node, &p.certs[k], 1e-6);
    CHECK(c.ok);
  }
  CHECK_INT(p.certs[p.nsteps].ncontact, ==, 0);
  us_bitset_free(&node);
  us_plan_free(&p);
  us_structure_free(s);
}

static void verify_names_the_failing_step(void) {
  us_Structure *s = scene_cantilever();
  CHECK(s);
  us_StabilitySettings st = us_stability_default_settings();
  int C = us_structure_find_body(s, "C"), L = us_structure_find_body(s, "L");
  int S = us_structure_find_body(s, "S"), P = us_structure_find_body(s, "P");
  int bad[4] = {C, L, S, P}, good[4] = {L, C, S, P};
  us_VerifyReport rep;
  us_Error err;
  CHECK_OK(us_verify_order(s, &st, bad, 4, &rep, &err), &err);
  CHECK(!rep.ok);
  CHECK_INT(rep.failed_step, ==, 0);
  CHECK_OK(us_verify_order(s, &st, good, 4, &rep, &err), &err);
  CHECK(rep.ok);
  CHECK_OK(us_verify_order(s, &st, good, 3, &rep, &err), &err);
  CHECK(!rep.ok && rep.incomplete && rep.remaining == 1);
  int dup[2] = {L, L};
  CHECK_INT(us_verify_order(s, &st, dup, 2, &rep, &err), ==, US_ERR_INPUT);
  us_structure_free(s);
}

/* ---- reference: dynamic programme over all subsets ---- */

typedef struct {
  int n;              /* movable bodies (all bodies movable here) */
  signed char *stable;
  signed char *reach; /* subset can be emptied through stable subsets */
} Ref;

static int ref_reach(Ref *r, unsigned m) {
  if (r->reach[m] >= 0) return r->reach[m];
  int ok = 0;
  if (m == 0) ok = 1;
  else if (r->stable[m])
    for (int b = 0; b < r->n && !ok; b++)
      if (m & (1u << b)) ok = ref_reach(r, m & ~(1u << b));
  r->reach[m] = (signed char)ok;
  return ok;
}

static int reference_found(const us_Structure *s) {
  int n = s->nbody;
  unsigned N = 1u << n;
  Ref r = {n, us_malloc(N), us_malloc(N)};
  us_StabilitySettings set = us_stability_default_settings();
  us_Stability *w = us_stability_new(s, &set, NULL);
  us_StabilityResult res;
  memset(&res, 0, sizeof res);
  us_Bitset b;
  us_bitset_init(&b, n);
  for (unsigned m = 0; m < N; m++) {
    b.w[0] = m;
    us_stability_test(w, &b, &res, NULL);
    r.stable[m] = res.verdict == US_STABLE;
    r.reach[m] = -1;
  }
  int found = r.stable[N - 1] ? ref_reach(&r, N - 1) : -1;
  us_bitset_free(&b);
  us_stability_result_free(&res);
  us_stability_free(w);
  us_free(r.stable);
  us_free(r.reach);
  return found; /* -1 full unstable, 0 none, 1 found */
}

static unsigned long rng_state = 12345;
static double rnd(void) {
  rng_state = rng_state * 6364136223846793005UL + 1442695040888963407UL;
  return (double)(rng_state >> 11) / 9007199254740992.0;
}

/* Random piles: boxes of random widths dropped at random offsets onto the
 * exact skyline of the boxes below (not necessarily stable, and sometimes
 * bridging two stacks): a mix of found, none and unstable. */
static us_Structure *random_pile(int n) {
  us_Structure *s = us_structure_new(2);
  s->friction = rnd() < 0.3 ? 0.0 : 0.6;
  SceneSkyline sky = {0};
  char id[16];
  for (int i = 0; i < n; i++) {
    double w = 0.5 + 1.2 * rnd();
    double x0 = 2.0 * rnd();
    double y = scene_landing(&sky, x0, w);
    double h = 0.2 + 0.3 * rnd();
    scene_skyline_add(&sky, x0, w, y + h);
    snprintf(id, sizeof id, "r%d", i);
    scene_box(s, id, x0, y, w, h, rnd() < 0.2 ? 5.0 : 1.0);
  }
  us_Error err;
  if (us_structure_finalize(s, &err) != US_OK) {
    us_structure_free(s);
    return NULL;
  }
  return s;
}

static void agrees_with_exhaustive_reference(void) {
  int counts[3] = {0, 0, 0}, tried = 0;
  for (int trial = 0; trial < 400; trial++) {
    us_Structure *s = random_pile(3 + trial % 6);
    if (!s) continue; /* overlapping draw: skip */
    tried++;
    int ref = reference_found(s);
    us_PlanStatus want = ref < 0 ? US_PLAN_UNSTABLE : ref ? US_PLAN_FOUND : US_PLAN_NONE;
    counts[ref + 1]++;
    for (int k = 0; k < 4; k++) {
      us_Plan p;
      us_PlanStatus got = plan_status(s, k & 1 ? US_SEARCH_BFS : US_SEARCH_DFS,
                                      k & 2 ? US_DIR_UP : US_DIR_DOWN, &p);
      if (got != want) fprintf(stderr, "trial %d variant %d: %d vs %d\n", trial, k, got, want);
      CHECK_INT(got, ==, want);
      if (got == US_PLAN_FOUND) CHECK(order_valid(s, &p));
      us_plan_free(&p);
    }
    us_structure_free(s);
  }
  printf("reference: %d structures: %d unstable, %d none, %d found\n", tried, counts[0],
         counts[1], counts[2]);
  CHECK(tried >= 200);
  CHECK(counts[2] > 0 && counts[1] > 0 && counts[0] > 0);
}

static void out_of_memory_is_clean(void) {
  us_Structure *s = scene_cantilever();
  CHECK(s);
  us_PlanSettings set = us_plan_default_settings();
  set.certificates = 1;
  for (long n = 0; n < 400; n += 7) {
    us_Plan p;
    us_Error err;
    us_alloc_fail_after(n);
    us_Status st = us_plan(s, &set, &p, &err);
    us_alloc_fail_after(-1);
    if (st == US_OK) {
      us_plan_free(&p);
      break;
    }
    CHECK(st == US_ERR_NOMEM || st == US_ERR_SOLVER);
  }
  us_structure_free(s);
}

US_TEST_MAIN(T(column_top_down), T(column_of_150), T(cantilever_needs_backtracking),
             T(leaning_slabs_have_no_order), T(limits_stop_the_search), T(certificates_per_step),
             T(verify_names_the_failing_step), T(agrees_with_exhaustive_reference),
             T(out_of_memory_is_clean))
