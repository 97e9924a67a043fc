/* Tests of src/plan: the disassembly search and plan verification.
 *
 * The reference is independent of the search: for small structures every
 * subset is tested once and a dynamic programme over subsets decides
 * whether a stable path to the empty set exists; DFS, BFS and both
 * directions must agree with it, and every order they return must pass
 * us_verify_order. */
#include "plan/hook.h"
#include "scenes.h"
#include "test.h"

/* Sanitizer builds look for memory errors, not statistics (CMakeLists.txt):
 * the random differential test runs a fifth of its cases there, and the
 * tall column is 70 bodies (still two bitset words). Every code path the
 * full runs reach is reached by these too: found, none and unstable occur
 * among the piles (checked), with every search and direction. */
#ifdef US_TEST_SANITIZED
#define PLAN_TRIALS 80
#define TALL_COLUMN 70
#else
#define PLAN_TRIALS 400
#define TALL_COLUMN 150
#endif

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
  us_Structure *s = scene_column(TALL_COLUMN);
  CHECK(s);
  us_Plan p;
  CHECK_INT(plan_status(s, US_SEARCH_DFS, US_DIR_DOWN, &p), ==, US_PLAN_FOUND);
  CHECK_INT(p.nsteps, ==, TALL_COLUMN);
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

static unsigned long long rng_state = 12345;
static double rnd(void) { return test_lcg(&rng_state); }

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
  for (int trial = 0; trial < PLAN_TRIALS; trial++) {
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
  CHECK(tried >= PLAN_TRIALS / 2);
  CHECK(counts[2] > 0 && counts[1] > 0 && counts[0] > 0);
}

/* ---- undecided tests (through the planner's test-only hook, hook.h) ---- */

/* Hook state: the tests numbered from .. to - 1 (counting from 0) are
 * undecided; with pair >= 0 the configuration "exactly one of the bodies
 * pair, pair2 present" that a search meets first is undecided,
 * consistently, and the other is not. */
typedef struct {
  long seen, from, to;
  int pair, pair2, bad;
} HookState;

static void undecide(us_StabilityResult *res, const char *why) {
  res->verdict = US_UNDECIDED;
  snprintf(res->note, sizeof res->note, "%s", why);
}

static void hook(void *user, const us_Bitset *node, us_StabilityResult *res) {
  HookState *h = user;
  long k = h->seen++;
  if (k >= h->from && k < h->to) undecide(res, "test hook: budget");
  if (h->pair < 0) return;
  int a = us_bitset_get(node, h->pair), b = us_bitset_get(node, h->pair2);
  if (a == b) return;
  if (h->bad < 0) h->bad = a;
  if (a == h->bad) undecide(res, "test hook: pair");
}

static HookState hook_on(long from, long to, int pair, int pair2) {
  HookState h = {0, from, to, pair, pair2, -1};
  return h;
}

/* Two stacks of two boxes side by side, all touching: a | b below, d | e
 * on them. Every order of single bodies leaves d or e alone on the bottom
 * row at some point, so the pair hook leaves one way: through the
 * configuration the search did not meet first. */
static us_Structure *two_stacks(void) {
  us_Structure *s = us_structure_new(2);
  scene_box(s, "a", 0, 0, 1, 0.5, 1);
  scene_box(s, "b", 1, 0, 1, 0.5, 1);
  scene_box(s, "d", 0, 0.5, 1, 0.5, 1);
  scene_box(s, "e", 1, 0.5, 1, 0.5, 1);
  return scene_seal(s);
}

static us_PlanSettings search_mode(int mode) {
  us_PlanSettings set = us_plan_default_settings();
  static const us_Search searches[] = {US_SEARCH_ASSEMBLE, US_SEARCH_ASSEMBLE, US_SEARCH_DFS,
                                       US_SEARCH_DFS, US_SEARCH_BFS, US_SEARCH_RANDOM,
                                       US_SEARCH_DFS};
  set.search = searches[mode];
  if (mode == 1) set.max_group = 0;
  if (mode == 3) set.direction = US_DIR_UP;
  if (mode == 6) set.rules = US_RULE_MEMO; /* the plain search of the source */
  return set;
}
#define NMODES 7

/* A verdict the tests could not decide is reported as undecided by every
 * search, never as unstable or none; the first reason is kept. */
static void undecided_is_not_unstable_or_none(void) {
  us_Structure *unstable = scene_leaning(0.0), *none = scene_leaning(0.5);
  CHECK(unstable && none);
  for (int mode = 0; mode < NMODES; mode++) {
    us_PlanSettings set = search_mode(mode);
    us_Plan p;
    us_Error err;
    /* the first test undecided: the full structure's own (the assembly
       search tests it last: after each slab alone, when it is stuck) */
    HookState h = hook_on(0, 1, -1, -1);
    us_plan_set_test_hook(hook, &h);
    us_Status st = us_plan(unstable, &set, &p, &err);
    us_plan_set_test_hook(NULL, NULL);
    CHECK_OK(st, &err);
    CHECK_INT(p.status, ==, US_PLAN_UNDECIDED);
    CHECK_INT(p.stats.undecided, ==, 1);
    CHECK_INT(p.stats.tests, ==, set.search == US_SEARCH_ASSEMBLE ? 3 : 1);
    CHECK(strstr(p.note, "test hook: budget") != NULL);
    CHECK(p.order == NULL && p.nsteps == 0);
    us_plan_free(&p);
    /* none, but one test on the way undecided (then memoised as dead);
       automatic K finds the pair as one step */
    us_PlanStatus none_status = set.max_group == 0 ? US_PLAN_FOUND : US_PLAN_NONE;
    h = hook_on(1, 2, -1, -1);
    us_plan_set_test_hook(hook, &h);
    st = us_plan(none, &set, &p, &err);
    us_plan_set_test_hook(NULL, NULL);
    CHECK_OK(st, &err);
    CHECK_INT(p.status, ==, none_status == US_PLAN_NONE ? US_PLAN_UNDECIDED : US_PLAN_FOUND);
    CHECK_INT(p.stats.undecided, ==, 1);
    us_plan_free(&p);
    /* without the hook: the proofs */
    CHECK_OK(us_plan(unstable, &set, &p, &err), &err);
    CHECK_INT(p.status, ==, US_PLAN_UNSTABLE);
    CHECK_INT(p.stats.undecided, ==, 0);
    us_plan_free(&p);
    CHECK_OK(us_plan(none, &set, &p, &err), &err);
    CHECK_INT(p.status, ==, none_status);
    us_plan_free(&p);
  }
  us_structure_free(unstable);
  us_structure_free(none);
}

/* The index of body `id` in order, or -1. */
static int position(const us_Structure *s, const us_Plan *p, const char *id) {
  int b = us_structure_find_body(s, id);
  for (int k = 0; k < p->nsteps; k++)
    if (p->order[k] == b) return k;
  return -1;
}

/* A plan exists past an undecided node: every search finds it through
 * certified-stable nodes only (verify, with the same hook, re-tests every
 * step and finds them stable), and an order through the undecided node is
 * reported as undecided at that step by verify. */
static void found_past_undecided_nodes(void) {
  us_Structure *s = two_stacks();
  CHECK(s);
  int d = us_structure_find_body(s, "d"), e = us_structure_find_body(s, "e");
  us_StabilitySettings stab = us_stability_default_settings();
  for (int mode = 0; mode < NMODES; mode++) {
    us_PlanSettings set = search_mode(mode);
    set.certificates = mode == 0;
    HookState h = hook_on(0, 0, d, e);
    us_plan_set_test_hook(hook, &h);
    us_Plan p;
    us_Error err;
    us_Status st = us_plan(s, &set, &p, &err);
    us_VerifyReport rep;
    us_Status vst = st ? st : us_verify_steps(s, &stab, p.order, p.nsteps, p.group_start,
                                              p.ngroups, &rep, &err);
    us_plan_set_test_hook(NULL, NULL);
    CHECK_OK(st, &err);
    CHECK_OK(vst, &err);
    if (p.status != US_PLAN_FOUND) fprintf(stderr, "mode %d: %s\n", mode, us_plan_status_name(p.status));
    CHECK_INT(p.status, ==, US_PLAN_FOUND);
    CHECK(p.stats.undecided >= 1); /* the search met the undecided node */
    CHECK(h.bad >= 0);
    CHECK(rep.ok && !rep.undecided);
    /* the order took the other way: the top body the hook does not let
       stand alone goes first */
    int pd = position(s, &p, "d"), pe = position(s, &p, "e");
    CHECK(pd >= 0 && pe >= 0);
    CHECK(h.bad == 1 ? pd < pe : pe < pd);
    us_plan_free(&p);
  }
  us_structure_free(s);
}

/* verify: an undecided step is neither valid nor invalid; a later step
 * that falls still proves the order invalid. */
static void verify_reports_undecided_steps(void) {
  us_Structure *s = scene_column(3);
  CHECK(s);
  us_StabilitySettings stab = us_stability_default_settings();
  int good[3] = {2, 1, 0}, bad[3] = {0, 2, 1};
  us_VerifyReport rep;
  us_Error err;
  /* verify tests the remainders from the last one up (test 0: after step
     3, test 3: the full structure) */
  /* the full structure and the first remainder are decided, the rest not */
  HookState h = hook_on(0, 2, -1, -1);
  us_plan_set_test_hook(hook, &h);
  us_Status st = us_verify_order(s, &stab, good, 3, &rep, &err);
  us_plan_set_test_hook(NULL, NULL);
  CHECK_OK(st, &err);
  CHECK(!rep.ok && rep.undecided && !rep.full_unstable && !rep.incomplete);
  CHECK_INT(rep.failed_step, ==, -1);
  CHECK_INT(rep.undecided_step, ==, 1);
  CHECK(strstr(rep.note, "test hook") != NULL);
  CHECK_INT(rep.steps_checked, ==, 4);
  /* the full structure undecided, then removing the bottom: a proof */
  h = hook_on(3, 4, -1, -1);
  us_plan_set_test_hook(hook, &h);
  st = us_verify_order(s, &stab, bad, 3, &rep, &err);
  us_plan_set_test_hook(NULL, NULL);
  CHECK_OK(st, &err);
  CHECK(!rep.ok && !rep.undecided && !rep.full_unstable);
  CHECK_INT(rep.failed_step, ==, 0);
  /* the full structure undecided and nothing falls */
  h = hook_on(3, 4, -1, -1);
  us_plan_set_test_hook(hook, &h);
  st = us_verify_order(s, &stab, good, 3, &rep, NULL);
  us_plan_set_test_hook(NULL, NULL);
  CHECK_OK(st, &err);
  CHECK(rep.undecided && rep.undecided_step == -1 && !rep.full_unstable);
  /* an incomplete order is invalid whatever was undecided (two removals:
     the full structure is test 2) */
  h = hook_on(2, 3, -1, -1);
  us_plan_set_test_hook(hook, &h);
  st = us_verify_order(s, &stab, good, 2, &rep, NULL);
  us_plan_set_test_hook(NULL, NULL);
  CHECK_OK(st, &err);
  CHECK(!rep.ok && !rep.undecided && rep.incomplete);
  us_structure_free(s);
}

/* The status words: one table (src/plan/names.c), "undecided" included. */
static void status_words(void) {
  static const char *const words[] = {"found", "none", "unstable", "limit", "undecided"};
  for (int k = 0; k < 5; k++) {
    us_PlanStatus st;
    CHECK_INT(us_plan_status_parse(words[k], &st), ==, 0);
    CHECK_INT(st, ==, k);
    CHECK(!strcmp(us_plan_status_name(st), words[k]));
  }
  us_PlanStatus st;
  CHECK_INT(us_plan_status_parse("stable", &st), ==, -1);
  CHECK(!strcmp(us_plan_status_name((us_PlanStatus)5), "unknown"));
}

/* Fail the n-th allocation of one plan for every n until it succeeds:
 * every failure is out of memory (or a backend's report of it) with a
 * message, nothing leaked (the harness checks), and the same with a NULL
 * error pointer (odd n). Returns the number of failing runs, or -1. */
static long plan_oom_sweep(const us_Structure *s, const us_PlanSettings *set, us_PlanStatus want) {
  for (long n = 0; n < 100000; n++) {
    us_Plan p;
    us_Error err;
    us_error_clear(&err);
    us_alloc_fail_after(n);
    us_Status st = us_plan(s, set, &p, n & 1 ? NULL : &err);
    us_alloc_fail_after(-1);
    if (st == US_OK) {
      int ok = p.status == want;
      us_plan_free(&p);
      return ok && n > 0 ? n : -1;
    }
    if (st != US_ERR_NOMEM && st != US_ERR_SOLVER) return -1;
    if (!(n & 1) && (err.code != st || !err.msg[0])) return -1;
    if (p.order || p.blocked || p.certs) return -1; /* emptied */
  }
  return -1;
}

/* The sweep over every search mode, on a structure whose plan needs a
 * backtrack (the rescue) and on one with none (the stuck set named). */
static void out_of_memory_is_clean(void) {
  us_Structure *scenes[2] = {scene_cantilever(), scene_leaning(0.5)};
  CHECK(scenes[0] && scenes[1]);
  for (int k = 0; k < 2; k++)
    for (int mode = 0; mode < NMODES; mode++) {
      us_PlanSettings set = search_mode(mode);
      set.certificates = k == 0;
      us_PlanStatus want = k == 0 || set.max_group == 0 ? US_PLAN_FOUND : US_PLAN_NONE;
      long runs = plan_oom_sweep(scenes[k], &set, want);
      if (runs < 0) fprintf(stderr, "scene %d mode %d: sweep failed\n", k, mode);
      CHECK(runs > 0);
    }
  us_structure_free(scenes[0]);
  us_structure_free(scenes[1]);
}

/* The same for verify (in steps), with and without an error pointer. */
static void verify_out_of_memory_is_clean(void) {
  us_Structure *s = scene_cantilever();
  CHECK(s);
  us_StabilitySettings stab = us_stability_default_settings();
  int C = us_structure_find_body(s, "C"), L = us_structure_find_body(s, "L");
  int S = us_structure_find_body(s, "S"), P = us_structure_find_body(s, "P");
  int order[4] = {L, C, S, P}, gs[4] = {0, 1, 3, 4};
  long n = 0;
  for (;; n++) {
    us_VerifyReport rep;
    us_Error err;
    us_error_clear(&err);
    us_alloc_fail_after(n);
    us_Status st = us_verify_steps(s, &stab, order, 4, gs, 3, &rep, n & 1 ? NULL : &err);
    us_alloc_fail_after(-1);
    if (st == US_OK) {
      CHECK(rep.ok && rep.steps_checked == 4);
      break;
    }
    CHECK(st == US_ERR_NOMEM || st == US_ERR_SOLVER);
    if (!(n & 1)) CHECK(err.code == st && err.msg[0]);
  }
  CHECK(n > 0);
  us_structure_free(s);
}

/* Every entry point of the planner takes a NULL error pointer, also on
 * bad arguments. */
static void null_error_pointer(void) {
  us_Structure *s = scene_column(3);
  CHECK(s);
  us_PlanSettings set = us_plan_default_settings();
  us_Plan p;
  CHECK_INT(us_plan(NULL, &set, &p, NULL), ==, US_ERR_USAGE);
  CHECK_INT(us_plan(s, NULL, &p, NULL), ==, US_ERR_USAGE);
  CHECK_INT(us_plan(s, &set, NULL, NULL), ==, US_ERR_USAGE);
  set.max_group = 99;
  CHECK_INT(us_plan(s, &set, &p, NULL), ==, US_ERR_USAGE);
  set = us_plan_default_settings();
  CHECK_INT(us_plan(s, &set, &p, NULL), ==, US_OK);
  CHECK_INT(p.status, ==, US_PLAN_FOUND);
  us_plan_free(&p);
  us_StabilitySettings stab = us_stability_default_settings();
  us_VerifyReport rep;
  int order[3] = {2, 1, 0}, twice[2] = {1, 1}, step = 0;
  CHECK_INT(us_verify_order(s, &stab, order, 3, &rep, NULL), ==, US_OK);
  CHECK(rep.ok);
  CHECK_INT(us_verify_order(s, &stab, twice, 2, &rep, NULL), ==, US_ERR_INPUT);
  CHECK_INT(us_verify_order(NULL, &stab, order, 3, &rep, NULL), ==, US_ERR_USAGE);
  CHECK_INT(us_verify_removals(s, US_REMOVAL_UP, order, 3, &step, &step, NULL), ==, US_OK);
  CHECK_INT(us_verify_removals(s, US_REMOVAL_UP, twice, 2, &step, &step, NULL), ==, US_ERR_INPUT);
  CHECK_INT(us_verify_removals(s, US_REMOVAL_UP, order, 3, NULL, &step, NULL), ==, US_ERR_USAGE);
  us_structure_free(s);
}

/* A time limit holds inside the solvers: a plan that runs out ends in
 * limit (not undecided), a stability test undecided with the reason, a
 * verification undecided with the reason; with room, nothing changes. */
static void time_limits_inside_solvers(void) {
  us_Structure *s = scene_column(40);
  CHECK(s);
  us_PlanSettings set = us_plan_default_settings();
  set.search = US_SEARCH_DFS;
  set.time_limit = 1e-9;
  us_Plan p;
  us_Error err;
  CHECK_OK(us_plan(s, &set, &p, &err), &err);
  CHECK_INT(p.status, ==, US_PLAN_LIMIT);
  CHECK_INT(p.stats.undecided, ==, 0);
  us_plan_free(&p);
  us_StabilitySettings stab = us_stability_default_settings();
  stab.time_limit = 1e-9;
  us_Stability *w = us_stability_new(s, &stab, &err);
  CHECK(w);
  us_StabilityResult res;
  us_stability_result_init(&res);
  CHECK_OK(us_stability_test_full(w, &res, &err), &err);
  CHECK_INT(res.verdict, ==, US_UNDECIDED);
  CHECK(strstr(res.note, "time limit") != NULL);
  CHECK_INT(us_stability_info(w)->timed_out, ==, 1);
  us_stability_free(w);
  us_stability_result_free(&res);
  int order[40];
  for (int k = 0; k < 40; k++) order[k] = 39 - k;
  us_VerifyReport rep;
  CHECK_OK(us_verify_order(s, &stab, order, 40, &rep, &err), &err);
  CHECK(rep.undecided && !rep.ok && rep.failed_step == -1);
  CHECK(strstr(rep.note, "time limit") != NULL);
  stab.time_limit = 60;
  CHECK_OK(us_verify_order(s, &stab, order, 40, &rep, &err), &err);
  CHECK(rep.ok);
  us_structure_free(s);
}

typedef struct Seen {
  long calls, last_tests;
  int bad;
} Seen;

static void on_progress(const us_Progress *p, void *user) {
  Seen *seen = user;
  seen->calls++;
  if (p->tests < seen->last_tests || p->bodies < 0 || p->elapsed < 0) seen->bad = 1;
  seen->last_tests = p->tests;
}

/* The progress callback runs during a plan (the first test reports at
 * once) with counts that only grow. */
static void progress_is_reported(void) {
  us_Structure *s = scene_column(30);
  CHECK(s);
  us_PlanSettings set = us_plan_default_settings();
  Seen seen = {0, 0, 0};
  set.stability.progress = on_progress;
  set.stability.progress_user = &seen;
  us_Plan p;
  us_Error err;
  CHECK_OK(us_plan(s, &set, &p, &err), &err);
  CHECK_INT(p.status, ==, US_PLAN_FOUND);
  CHECK(seen.calls >= 1 && !seen.bad && seen.last_tests >= 1);
  us_plan_free(&p);
  us_structure_free(s);
}

US_TEST_MAIN(T(column_top_down), T(column_of_150), T(cantilever_needs_backtracking),
             T(leaning_slabs_have_no_order), T(limits_stop_the_search), T(certificates_per_step),
             T(verify_names_the_failing_step), T(agrees_with_exhaustive_reference),
             T(undecided_is_not_unstable_or_none), T(found_past_undecided_nodes),
             T(verify_reports_undecided_steps), T(status_words), T(out_of_memory_is_clean),
             T(verify_out_of_memory_is_clean), T(null_error_pointer),
             T(time_limits_inside_solvers), T(progress_is_reported))
