/* Tests by change (us_stability_add / remove / set_current /
 * test_current; src/stability/stability.c, local.c; docs/planning.md,
 * "Tests by change").
 *
 * Stating a test as the change since the last one must give the verdict a
 * whole bitset gives: random sequences of adds and removes (mostly along
 * a plan's build order, with removals of random present bodies, re-adds
 * and jumps to far-away sets) over walls, pyramids, an arch with loose
 * blocks, the stacker's random stacks (cantilevers: regions, levers, the
 * full system) and 3D structures are tested three ways: a workspace told
 * the changes, a workspace given the bitset, and a fresh workspace without
 * local tests (the full LP, no memory at all). The first two must agree
 * exactly (same verdict and note), all three on every verdict (none is
 * undecided on these scenes);
 * every stable verdict's forces pass the independent certificate check
 * on the set, every unstable one's mechanism (when it has one) the
 * mechanism check; after every test the bookkeeping of the change (the
 * set's count, the local tests' diff against their base, the plumb memo's
 * absent bodies) agrees with a recount from the bitsets. */
#include "scenes.h"
#include "stability/stability.h" /* us_stability_delta_consistent */
#include "test.h"
#include "walks.h"

#ifdef US_TEST_SANITIZED
#define OPS 120
#else
#define OPS 400
#endif

typedef struct Tally {
  long tests, stable, unstable, mech, undecided;
} Tally;

/* The build order of s (its plan's removal order reversed) into order;
 * its length, or -1. */
static int build_order(const us_Structure *s, int *order) {
  us_PlanSettings set = us_plan_default_settings();
  us_Plan p;
  if (us_plan(s, &set, &p, NULL)) return -1;
  int n = p.status == US_PLAN_FOUND ? p.nsteps : 0;
  for (int k = 0; k < n; k++) order[k] = p.order[n - 1 - k];
  us_plan_free(&p);
  return n;
}

/* The verdict of node on a fresh workspace without local tests. */
static us_Verdict fresh_verdict(const us_Structure *s, const us_Bitset *node) {
  us_StabilitySettings set = local_settings(0);
  us_Stability *w = us_stability_new(s, &set, NULL);
  us_StabilityResult r;
  us_stability_result_init(&r);
  us_Verdict v = w && us_stability_test(w, node, &r, NULL) == US_OK ? r.verdict : US_UNDECIDED;
  us_stability_result_free(&r);
  us_stability_free(w);
  return v;
}

/* The certificate of a result on node re-checked without the solver: 1
 * holds (or no certificate to check: undecided, or unstable without a
 * mechanism), 0 not. */
static int certified(const us_Structure *s, const us_Bitset *node, us_StabilityResult *r) {
  if (r->verdict == US_STABLE) return us_certificate_check(s, node, &r->forces, 1e-6).ok;
  if (r->verdict == US_UNSTABLE && r->mechanism.nbody > 0)
    return us_mechanism_check(s, node, &r->mechanism, 1e-6);
  return 1;
}

/* Test node three ways (file head); 0 or -1 (reported). */
static int compare(const us_Structure *s, us_Stability *byc, us_Stability *byb,
                   const us_Bitset *node, us_StabilityResult *rc, us_StabilityResult *rb,
                   Tally *t, const char *name, int op) {
  us_Error err;
  if (us_stability_test_current(byc, rc, &err) || us_stability_test(byb, node, rb, &err)) {
    fprintf(stderr, "%s op %d: %s\n", name, op, err.msg);
    return -1;
  }
  t->tests++;
  t->stable += rc->verdict == US_STABLE;
  t->unstable += rc->verdict == US_UNSTABLE;
  t->mech += rc->verdict == US_UNSTABLE && rc->mechanism.nbody > 0;
  t->undecided += rc->verdict == US_UNDECIDED;
  us_Verdict ref = fresh_verdict(s, node);
  int bad = rc->verdict != rb->verdict || strcmp(rc->note, rb->note) != 0 ||
            (rc->verdict != US_UNDECIDED && ref != US_UNDECIDED && rc->verdict != ref) ||
            !certified(s, node, rc) || !us_bitset_equal(us_stability_current(byc), node) ||
            us_stability_current_count(byc) != us_bitset_count(node) ||
            !us_stability_delta_consistent(byc) || !us_stability_delta_consistent(byb);
  if (bad)
    fprintf(stderr, "%s op %d (%d bodies): by change %s (%s), by bitset %s (%s), fresh %s\n", name,
            op, us_bitset_count(node), us_verdict_name(rc->verdict), rc->note,
            us_verdict_name(rb->verdict), rb->note, us_verdict_name(ref));
  return bad ? -1 : 0;
}

/* Toggle body i in node and tell the change to w. */
static void change(us_Stability *w, us_Bitset *node, int i, int on) {
  if (on) {
    us_bitset_set(node, i);
    us_stability_add(w, i, NULL);
  } else {
    us_bitset_clear(node, i);
    us_stability_remove(w, i, NULL);
  }
}

/* A random present (on = 1) or absent movable body of node, or -1. */
static int pick(const us_Structure *s, const us_Bitset *node, int on, unsigned long long *rng) {
  int n = s->nbody, i = (int)(test_rnd(rng) * n);
  for (int k = 0; k < n; k++, i = (i + 1) % n)
    if (!s->bodies[i].fixed && us_bitset_get(node, i) == on) return i;
  return -1;
}

/* One op of the sequence: the next body of the build order (most often),
 * a random present body out, a random absent body in, or, rarely, a jump
 * to the first k bodies of the order (a whole set, by set_current). */
static void step(const us_Structure *s, us_Stability *w, us_Bitset *node, const int *order,
                 int norder, int *next, unsigned long long *rng) {
  double u = test_rnd(rng);
  if (u < 0.03 && norder > 0) {
    int k = (int)(test_rnd(rng) * norder);
    memset(node->w, 0, (size_t)node->nwords * sizeof(uint64_t));
    for (int q = 0; q < k; q++) us_bitset_set(node, order[q]);
    us_stability_set_current(w, node, NULL);
    *next = k;
    return;
  }
  if (u < 0.65 && *next < norder) {
    change(w, node, order[(*next)++], 1);
    return;
  }
  int on = u < 0.85, i = pick(s, node, on, rng);
  if (i >= 0) change(w, node, i, !on);
}

/* A sequence of OPS ops on s (freed here); 0 or -1. */
static int run_sequence(us_Structure *s, const char *name, unsigned long long seed, Tally *t) {
  if (!s) return fprintf(stderr, "%s: not generated\n", name), -1;
  us_StabilitySettings set = local_settings(1);
  us_Stability *byc = us_stability_new(s, &set, NULL), *byb = us_stability_new(s, &set, NULL);
  int *order = malloc(((size_t)s->nbody + 1) * sizeof(int));
  us_Bitset node;
  int bad = !byc || !byb || !order || us_bitset_init(&node, s->nbody);
  int norder = bad ? -1 : build_order(s, order), next = 0;
  us_StabilityResult rc, rb;
  us_stability_result_init(&rc);
  us_stability_result_init(&rb);
  bad = bad || norder < 0;
  for (int op = 0; op < OPS && !bad; op++) {
    step(s, byc, &node, order, norder, &next, &seed);
    bad = compare(s, byc, byb, &node, &rc, &rb, t, name, op) != 0;
  }
  us_stability_result_free(&rc);
  us_stability_result_free(&rb);
  us_bitset_free(&node);
  free(order);
  us_stability_free(byc);
  us_stability_free(byb);
  us_structure_free(s);
  return bad ? -1 : 0;
}

/* 2D: walls, pyramids, an arch with loose blocks, stacker stacks, with
 * and without friction. */
static void same_verdicts_2d(void) {
  Tally t = {0};
  for (int mu = 0; mu < 2; mu++) {
    double f = mu ? 0.6 : 0.0;
    CHECK_INT(run_sequence(walk_generated(0, f, 6, 1, 0, 0), "wall", 11 + (unsigned)mu, &t), ==, 0);
    CHECK_INT(run_sequence(walk_generated(1, f, 8, 1, 0, 0), "pyramid", 21 + (unsigned)mu, &t), ==, 0);
    CHECK_INT(run_sequence(walk_generated(2, f, 7, 1, 0, 8), "arch", 31 + (unsigned)mu, &t), ==, 0);
    for (unsigned long seed = 1; seed <= 3; seed++)
      CHECK_INT(run_sequence(walk_generated(3, f, 10, seed, 0, 0), "stacker", 41 + seed, &t), ==, 0);
  }
  /* both verdicts and mechanisms must really occur */
  CHECK_INT(t.stable, >, t.tests / 10);
  CHECK_INT(t.unstable, >, t.tests / 10);
  CHECK_INT(t.mech, >, 0);
  CHECK_INT(t.undecided, ==, 0); /* none on these scenes: a stale base would show here */
}

/* 3D: a pyramid of boxes and a wall. */
static void same_verdicts_3d(void) {
  Tally t = {0};
  us_GenSettings g = us_gen_default_settings();
  g.n = 4;
  CHECK_INT(run_sequence(us_gen_pyramid3d(&g, NULL), "pyramid3d", 51, &t), ==, 0);
  g = us_gen_default_settings();
  g.rows = 4, g.cols = 5;
  CHECK_INT(run_sequence(us_gen_wall3d(&g, NULL), "wall3d", 52, &t), ==, 0);
  CHECK_INT(t.stable, >, t.tests / 10);
  CHECK_INT(t.unstable, >, 0);
  CHECK_INT(t.undecided, ==, 0);
}

/* The set itself: adds and removes are idempotent, fixed bodies stay out
 * of it, an index out of range is a usage error that changes nothing,
 * and the bitset API and set_current leave the same set. */
static void set_bookkeeping(void) {
  us_Structure *s = scene_column(5);
  CHECK(s != NULL);
  us_Error err;
  us_Stability *w = us_stability_new(s, NULL, &err);
  CHECK(w != NULL);
  CHECK_INT(us_stability_current_count(w), ==, 0);
  CHECK_OK(us_stability_add(w, 2, &err), &err);
  CHECK_OK(us_stability_add(w, 2, &err), &err);
  CHECK_OK(us_stability_add(w, 0, &err), &err);
  CHECK_INT(us_stability_current_count(w), ==, 2);
  CHECK_INT(us_stability_add(w, 5, &err), ==, US_ERR_USAGE);
  CHECK_INT(us_stability_remove(w, -1, &err), ==, US_ERR_USAGE);
  CHECK_INT(us_stability_current_count(w), ==, 2);
  CHECK_OK(us_stability_remove(w, 1, &err), &err); /* absent: no change */
  CHECK_INT(us_stability_current_count(w), ==, 2);
  us_StabilityResult r;
  us_stability_result_init(&r);
  CHECK_OK(us_stability_test_current(w, &r, &err), &err);
  CHECK_INT(r.verdict, ==, US_UNSTABLE); /* c2 floats over the gap of c1 */
  CHECK_OK(us_stability_add(w, 1, &err), &err);
  CHECK_OK(us_stability_test_current(w, &r, &err), &err);
  CHECK_INT(r.verdict, ==, US_STABLE);
  us_Bitset b;
  CHECK_INT(us_bitset_init(&b, s->nbody), ==, 0);
  us_bitset_set(&b, 4);
  CHECK_OK(us_stability_test(w, &b, &r, &err), &err);
  CHECK(us_bitset_equal(us_stability_current(w), &b));
  CHECK_INT(us_stability_current_count(w), ==, 1);
  CHECK_INT(r.verdict, ==, US_UNSTABLE);
  us_bitset_set(&b, 0);
  CHECK_OK(us_stability_set_current(w, &b, &err), &err);
  CHECK_INT(us_stability_current_count(w), ==, 2);
  CHECK(us_stability_delta_consistent(w));
  us_bitset_free(&b);
  us_stability_result_free(&r);
  us_stability_free(w);
  us_structure_free(s);
}

/* A fixed body: add and remove leave it out of the current set. */
static void fixed_body(void) {
  us_Structure *s = us_structure_new(2);
  CHECK(s != NULL);
  double lo[8] = {0, 0, 1, 0, 1, 1, 0, 1}, hi[8] = {0, 1, 1, 1, 1, 2, 0, 2};
  int a = scene_polygon(s, "pier", 4, lo, 1), b = scene_polygon(s, "top", 4, hi, 0);
  CHECK(a >= 0 && b >= 0);
  s = scene_seal(s);
  CHECK(s != NULL);
  us_Stability *w = us_stability_new(s, NULL, NULL);
  CHECK(w != NULL);
  CHECK_OK(us_stability_add(w, a, NULL), &(us_Error){0});
  CHECK_INT(us_stability_current_count(w), ==, 0);
  CHECK_OK(us_stability_add(w, b, NULL), &(us_Error){0});
  CHECK_INT(us_stability_current_count(w), ==, 1);
  us_StabilityResult r;
  us_stability_result_init(&r);
  CHECK_OK(us_stability_test_current(w, &r, NULL), &(us_Error){0});
  CHECK_INT(r.verdict, ==, US_STABLE);
  CHECK(us_certificate_check(s, us_stability_current(w), &r.forces, 1e-6).ok);
  us_stability_result_free(&r);
  us_stability_free(w);
  us_structure_free(s);
}

/* The component of C ∪ {b} that holds b (bodies joined by contacts) into
 * w; its size. queue: scratch of nbody ints. */
static int component_of(const us_Structure *s, const us_Bitset *c, int b, us_Bitset *w,
                        int *queue) {
  memset(w->w, 0, (size_t)w->nwords * sizeof(uint64_t));
  us_bitset_set(w, b);
  int n = 0, head = 0;
  queue[n++] = b;
  while (head < n) {
    int u = queue[head++];
    for (int k = 0; k < s->ncontact; k++) {
      const us_Contact *ct = &s->contacts[k];
      int v = ct->a == u ? ct->b : ct->b == u ? ct->a : -1;
      if (v < 0 || us_bitset_get(w, v) || !us_bitset_get(c, v)) continue;
      us_bitset_set(w, v);
      queue[n++] = v;
    }
  }
  return n;
}

/* The assembly's tests by component (assemble.c: C ∪ {b} is tested
 * through the component W that holds b, as a bitset): the base keeps
 * B ∪ S while B \ S touches nothing of S, so it gathers the other
 * components, and a later test whose body bridges to them must see them
 * touch S again. Along the build order of stacks of several towers, each
 * body's W and, before it, the W of a random absent body (often one that
 * cannot stand yet) are tested on one workspace: verdicts as a fresh one
 * without local tests, certificates checked, the bookkeeping recounted. */
static void by_component(void) {
  long tests = 0, split = 0, bridged = 0, stable = 0, unstable = 0;
#ifdef US_TEST_SANITIZED
  const unsigned long nseed = 1;
#else
  const unsigned long nseed = 3;
#endif
  for (int mu = 0; mu < 2; mu++)
    for (unsigned long seed = 1; seed <= nseed; seed++) {
      us_GenSettings g = us_gen_default_settings();
      g.friction = mu ? 0.6 : 0.0;
      g.seed = seed;
      g.rows = 6;
      g.width = 40;
      us_Structure *s = us_gen_stacker(&g, NULL);
      CHECK(s != NULL);
      us_StabilitySettings set = local_settings(1);
      us_Stability *w = us_stability_new(s, &set, NULL);
      int n = s->nbody, *order = malloc((size_t)n * sizeof(int)),
          *queue = malloc((size_t)n * sizeof(int));
      us_Bitset c, node;
      CHECK(w && order && queue && !us_bitset_init(&c, n) && !us_bitset_init(&node, n));
      int norder = build_order(s, order);
      CHECK_INT(norder, ==, n);
      unsigned long long rng = 7 + seed;
      us_StabilityResult r;
      us_stability_result_init(&r);
      int prev = -1; /* the size of C's component of the previous body */
      for (int q = 0; q < norder; q++) {
        for (int k = 0; k < 2; k++) {
          int b = k ? order[q] : pick(s, &c, 0, &rng);
          if (b < 0 || (k == 0 && b == order[q])) continue;
          int size = component_of(s, &c, b, &node, queue);
          split += size < us_bitset_count(&c) + 1;
          bridged += k && prev >= 0 && size > prev + 1;
          us_Error err;
          CHECK_OK(us_stability_test(w, &node, &r, &err), &err);
          us_Verdict ref = fresh_verdict(s, &node);
          if (r.verdict != ref || !certified(s, &node, &r) || !us_stability_delta_consistent(w))
            fprintf(stderr, "stacker seed %lu mu %d step %d body %d (%d bodies): %s (%s), fresh %s\n",
                    seed, mu, q, b, size, us_verdict_name(r.verdict), r.note, us_verdict_name(ref));
          CHECK_INT(r.verdict, ==, ref);
          CHECK(certified(s, &node, &r));
          CHECK(us_stability_delta_consistent(w));
          tests++;
          stable += r.verdict == US_STABLE;
          unstable += r.verdict == US_UNSTABLE;
          if (k) prev = size;
        }
        us_bitset_set(&c, order[q]);
      }
      us_stability_result_free(&r);
      us_bitset_free(&c);
      us_bitset_free(&node);
      free(order);
      free(queue);
      us_stability_free(w);
      us_structure_free(s);
    }
  /* the case must occur: tests on one component of several, and bodies
     that join components the base kept */
  CHECK_INT(split, >, tests / 4);
  CHECK_INT(bridged, >, 0);
  CHECK_INT(stable, >, tests / 4);
  CHECK_INT(unstable, >, tests / 20);
}

US_TEST_MAIN(T(same_verdicts_2d), T(same_verdicts_3d), T(by_component), T(set_bookkeeping), T(fixed_body))
