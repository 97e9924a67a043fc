/* Exact local stability tests (src/stability/local.c, docs/local.md).
 *
 * The local tests must give the verdict of the full system every time:
 * the differential cases walk sequences of sub-assemblies (one or a few
 * bodies added or removed per step, as the searches and verify do) of
 * walls, pyramids, arches, the stacker's random stacks, random piles with
 * counterweights, leaning pairs and arches, at mu = 0 and mu > 0, and test
 * each with two workspaces: local tests on (down to one body) and off.
 * The verdicts must agree; every stable verdict carries a certificate the
 * check accepted, every locally proven unstable verdict a mechanism the
 * independent check accepts, and most tests must really be settled
 * locally (else the test would prove nothing about them). */
#include "piles.h"
#include "scenes.h"
#include "test.h"
#include "walks.h"

static void flip(us_Bitset *b, int i) { b->w[i >> 6] ^= (uint64_t)1 << (i & 63); }

#ifdef US_TEST_SANITIZED
#define WALK_STEPS 120
#define NPILES 40
#else
#define WALK_STEPS 700
#define NPILES 400
#endif

typedef struct Tally {
  long tests, stable, unstable, local, mech, plumb, lever;
} Tally;

/* Test `node` with both workspaces: 0 if the verdicts agree and the
 * certificates hold, else -1 (reported). */
static int compare(us_Stability *loc, us_Stability *glob, const us_Structure *s,
                   const us_Bitset *node, us_StabilityResult *rl, us_StabilityResult *rg,
                   Tally *t) {
  us_Error err;
  long before = us_stability_info(loc)->local_stable + us_stability_info(loc)->local_unstable;
  long plumbed = us_stability_info(loc)->local_plumb;
  long levered = us_stability_info(loc)->local_lever;
  if (us_stability_test(loc, node, rl, &err) || us_stability_test(glob, node, rg, &err)) {
    fprintf(stderr, "test error: %s\n", err.msg);
    return -1;
  }
  long after = us_stability_info(loc)->local_stable + us_stability_info(loc)->local_unstable;
  int was_local = after > before;
  t->tests++;
  t->local += was_local;
  t->plumb += us_stability_info(loc)->local_plumb - plumbed;
  t->lever += us_stability_info(loc)->local_lever - levered;
  if (rl->verdict != rg->verdict || rl->verdict == US_UNDECIDED) {
    fprintf(stderr, "%d bodies: local %s (%s), full %s (%s)\n", us_bitset_count(node),
            us_verdict_name(rl->verdict), rl->note, us_verdict_name(rg->verdict), rg->note);
    return -1;
  }
  if (rl->verdict == US_STABLE) {
    t->stable++;
    if (!rl->check.ok) return fprintf(stderr, "stable without a passing check\n"), -1;
    if (rl->forces.ncontact > 0) {
      us_CertCheck c = us_certificate_check(s, node, &rl->forces, 1e-6);
      if (!c.ok) return fprintf(stderr, "merged forces fail the full check\n"), -1;
    }
  } else {
    t->unstable++;
    if (was_local) {
      if (!rl->mechanism.ok || rl->mechanism.nbody == 0)
        return fprintf(stderr, "local unstable without a mechanism\n"), -1;
      us_Mechanism m = rl->mechanism; /* re-check it from the public API */
      if (!us_mechanism_check(s, node, &m, 1e-6)) return fprintf(stderr, "mechanism rejected\n"), -1;
      t->mech++;
    }
  }
  return 0;
}

/* The two workspaces of a differential walk (local tests on, off) and
 * their results. */
typedef struct Pair {
  us_Stability *loc, *glob;
  us_StabilityResult rl, rg;
} Pair;

static int pair_open(const us_Structure *s, Pair *p) {
  us_StabilitySettings sl = local_settings(1), sg = local_settings(0);
  us_Error err;
  p->loc = us_stability_new(s, &sl, &err);
  p->glob = us_stability_new(s, &sg, &err);
  us_stability_result_init(&p->rl);
  us_stability_result_init(&p->rg);
  return p->loc && p->glob ? 0 : -1;
}

static void pair_close(Pair *p) {
  us_stability_result_free(&p->rl);
  us_stability_result_free(&p->rg);
  us_stability_free(p->loc);
  us_stability_free(p->glob);
}

static int pair_compare(Pair *p, const us_Structure *s, const us_Bitset *node, Tally *t) {
  return compare(p->loc, p->glob, s, node, &p->rl, &p->rg, t);
}

/* An absent body that touches a present one or the ground, or -1. */
static int touching_absent(const us_Structure *s, const us_Bitset *node, unsigned long long *rng) {
  for (int tries = 0; tries < 16 && s->ncontact > 0; tries++) {
    const us_Contact *k = &s->contacts[(int)(pile_rnd(rng) * s->ncontact)];
    int a_in = k->a < 0 || s->bodies[k->a].fixed || us_bitset_get(node, k->a);
    int b_in = s->bodies[k->b].fixed || us_bitset_get(node, k->b);
    if (a_in && !b_in) return k->b;
    if (b_in && !a_in) return k->a;
  }
  return -1;
}

/* One move: add a touching absent body or remove a present one; the body
 * moved (toggle it again to undo), or -1. */
static int move(const us_Structure *s, us_Bitset *node, unsigned long long *rng) {
  int b = -1;
  if (pile_rnd(rng) < 0.5) b = touching_absent(s, node, rng);
  for (int tries = 0; b < 0 && tries < 16; tries++) {
    int c = (int)(pile_rnd(rng) * s->nbody);
    if (!s->bodies[c].fixed && us_bitset_get(node, c)) b = c;
  }
  if (b >= 0) flip(node, b);
  return b;
}

/* Random walk from `node` (the full structure), as the searches move: one
 * body (sometimes two) added or removed per step; after a test that fell
 * the last move is mostly undone, so the walk stays near the boundary
 * between standing and falling. */
static int walk(const us_Structure *s, us_Bitset *node, int steps, unsigned long long *rng,
                Tally *t) {
  Pair p;
  int bad = pair_open(s, &p), last[2] = {-1, -1};
  for (int k = 0; k < steps && !bad; k++) {
    bad = pair_compare(&p, s, node, t) != 0;
    if (p.rl.verdict != US_STABLE && pile_rnd(rng) < 0.6) {
      for (int m = 0; m < 2; m++)
        if (last[m] >= 0) flip(node, last[m]);
    }
    last[0] = move(s, node, rng);
    last[1] = pile_rnd(rng) < 0.1 ? move(s, node, rng) : -1;
  }
  pair_close(&p);
  return bad ? -1 : 0;
}

static int walk_structure(us_Structure *s, int steps, unsigned long long seed, Tally *t) {
  if (!s) return -1;
  us_Bitset node = {0};
  int r = us_structure_movable_set(s, &node);
  unsigned long long rng = seed;
  if (!r) r = walk(s, &node, steps, &rng, t);
  us_bitset_free(&node);
  us_structure_free(s);
  return r;
}

/* Removal orders top-down and bottom-up builds: one body per step. */
static int removal_walk(us_Structure *s, Tally *t) {
  if (!s) return -1;
  Pair p;
  us_Bitset node = {0};
  int bad = pair_open(s, &p) || us_bitset_init(&node, s->nbody);
  /* build bottom-up in index order (generators number bottom-up), then
     take down in the same order (the lowest first: it falls) */
  for (int i = 0; i < s->nbody && !bad; i++) {
    if (s->bodies[i].fixed) continue;
    us_bitset_set(&node, i);
    bad = pair_compare(&p, s, &node, t) != 0;
  }
  for (int i = 0; i < s->nbody && !bad; i++) {
    us_bitset_clear(&node, i);
    bad = pair_compare(&p, s, &node, t) != 0;
  }
  us_bitset_free(&node);
  pair_close(&p);
  us_structure_free(s);
  return bad ? -1 : 0;
}

static us_Structure *gen(int kind, double mu, int size, unsigned long seed) {
  return walk_generated(kind, mu, size, seed, 0, 6);
}

static void report(const char *what, const Tally *t) {
  fprintf(stderr, "%s: %ld sub-assemblies (%ld stable, %ld unstable), %ld settled locally, "
                  "%ld by plumb lines, %ld by levers, %ld mechanisms checked\n",
          what, t->tests, t->stable, t->unstable, t->local, t->plumb, t->lever, t->mech);
}

/* ------------------------------------------------------------------ cases */

static void generators_agree(void) {
  Tally t = {0};
  static const double mus[] = {0.0, 0.5};
  for (int kind = 0; kind < 4; kind++)
    for (int m = 0; m < 2; m++) {
      int size = kind == 2 ? 9 : kind == 1 ? 8 : 6;
      if (kind == 2 && mus[m] == 0.0) continue; /* an arch needs friction */
      CHECK_INT(removal_walk(gen(kind, mus[m], size, 7u + (unsigned)kind), &t), ==, 0);
      CHECK_INT(walk_structure(gen(kind, mus[m], size, 11u + (unsigned)m), WALK_STEPS,
                               0x1234u + (unsigned)(kind * 7 + m), &t), ==, 0);
    }
  report("generators", &t);
  CHECK(t.stable > t.tests / 10 && t.unstable > t.tests / 10);
  CHECK(t.local > t.tests / 2); /* most tests must really be local */
  CHECK(t.mech > 0);
  CHECK(t.plumb > t.stable / 10); /* the plumb lines took part in the agreement */
}

static void random_piles_agree(void) {
  Tally t = {0};
  unsigned long long rng = 0x51ed2701u;
  int piles = 0;
  for (int k = 0; k < NPILES; k++) {
    us_Structure *s = pile_random(&rng, 4 + k % 9);
    if (!s) continue;
    piles++;
    unsigned long long seed = rng ^ (unsigned long long)k;
    CHECK_INT(walk_structure(s, 25, seed, &t), ==, 0);
  }
  report("piles", &t);
  CHECK(piles > NPILES * 3 / 4);
  CHECK(t.stable > t.tests / 10 && t.unstable > t.tests / 10);
  CHECK(t.local > t.tests / 3);
  CHECK(t.mech > 0);
}

/* A long plank on a pier near its left end, held by a column of k blocks
 * standing on its far left end; a block set on its far right end. The
 * change (the right block) is many contacts away from the top of the
 * column, whose weight decides: the regions must grow to the column. */
static us_Structure *lever(int k, double right_density) {
  us_Structure *s = us_structure_new(2);
  s->friction = 0.6;
  scene_box(s, "pier", 2.5, 0, 1, 1, 1);
  scene_box(s, "plank", 0, 1, 8, 0.2, 1);
  char id[16];
  for (int i = 0; i < k; i++) {
    snprintf(id, sizeof id, "w%d", i);
    scene_box(s, id, 0, 1.2 + 0.25 * i, 0.5, 0.25, 0.3);
  }
  scene_box(s, "load", 7.5, 1.2, 0.5, 0.5, right_density);
  return scene_seal(s);
}

static void global_instability_decided(void) {
  Tally t = {0};
  int stood = 0, fell = 0;
  for (int k = 8; k <= 28; k += 4) {
    for (int d = 1; d <= 13; d += 2) {
      us_Structure *s = lever(k, 0.2 * d);
      CHECK(s);
      Pair pr;
      CHECK_INT(pair_open(s, &pr), ==, 0);
      us_Bitset node = {0};
      CHECK_INT(us_structure_movable_set(s, &node), ==, 0);
      int load = s->nbody - 1;
      us_bitset_clear(&node, load);
      int r = pair_compare(&pr, s, &node, &t); /* without the load: the base */
      us_bitset_set(&node, load);
      if (!r) r = pair_compare(&pr, s, &node, &t);
      if (!r && pr.rl.verdict == US_STABLE) stood++;
      if (!r && pr.rl.verdict == US_UNSTABLE) fell++;
      us_bitset_free(&node);
      pair_close(&pr);
      us_structure_free(s);
      CHECK_INT(r, ==, 0);
    }
  }
  report("lever", &t);
  CHECK(stood > 0 && fell > 0); /* both sides of the balance were met */
}

/* The mechanism check rejects what is not a mechanism. */
static void mechanism_check_rejects(void) {
  /* a block on a pier overhanging to the right: it tips */
  us_Structure *s = us_structure_new(2);
  scene_box(s, "pier", 0, 0, 1, 1, 1);
  scene_box(s, "top", 0.6, 1, 2, 0.3, 1);
  s = scene_seal(s);
  CHECK(s);
  us_StabilitySettings set = local_settings(1);
  us_Error err;
  us_Stability *w = us_stability_new(s, &set, &err);
  CHECK(w);
  us_Bitset node = {0};
  CHECK_INT(us_structure_movable_set(s, &node), ==, 0);
  us_StabilityResult res;
  us_stability_result_init(&res);
  CHECK_OK(us_stability_test(w, &node, &res, &err), &err);
  CHECK_INT(res.verdict, ==, US_UNSTABLE);
  CHECK(res.mechanism.ok && res.mechanism.nbody == 2);
  us_Mechanism m = res.mechanism;
  CHECK(us_mechanism_check(s, &node, &m, 1e-9));
  /* reversed: gravity would do negative work */
  double v[6];
  memcpy(v, m.v, sizeof v);
  for (int k = 0; k < 6; k++) m.v[k] = -v[k];
  CHECK(!us_mechanism_check(s, &node, &m, 1e-9));
  /* straight down through the pier: the contacts resist */
  memset(m.v, 0, sizeof v);
  m.v[4] = -1.0; /* the top body (slot 1) moves down */
  if (m.body[1] != 1) m.v[1] = -1.0, m.v[4] = 0.0;
  CHECK(!us_mechanism_check(s, &node, &m, 1e-9));
  /* a body that is not present */
  us_bitset_clear(&node, 1);
  memcpy(m.v, v, sizeof v);
  CHECK(!us_mechanism_check(s, &node, &m, 1e-9));
  memcpy(res.mechanism.v, v, sizeof v);
  us_bitset_free(&node);
  us_stability_result_free(&res);
  us_stability_free(w);
  us_structure_free(s);
}

/* The planner's pattern on the stacker's stacks: build in the reverse of
 * a plan's removal order (found with local tests off), and before each
 * placement also try the next few bodies of the order on their own, as the
 * greedy assembly does (a cantilever before its counterweight falls; one
 * after it is held only through the counterweight's load path, level 1b
 * of the regions). Every test through both workspaces. */
static int assembly_replay(us_Structure *s, Tally *t) {
  us_PlanSettings ps = us_plan_default_settings();
  ps.stability.local = -1;
  us_Plan plan;
  us_Error err;
  if (!s || us_plan(s, &ps, &plan, &err)) return -1;
  Pair p;
  us_Bitset node = {0};
  int bad = plan.status != US_PLAN_FOUND || pair_open(s, &p) || us_bitset_init(&node, s->nbody);
  for (int k = plan.nsteps - 1; k >= 0 && !bad; k--) {
    for (int j = k - 1; j >= 0 && j >= k - 3 && !bad; j--) { /* ahead of time */
      flip(&node, plan.order[j]);
      bad = pair_compare(&p, s, &node, t) != 0;
      flip(&node, plan.order[j]);
    }
    flip(&node, plan.order[k]);
    if (!bad) bad = pair_compare(&p, s, &node, t) != 0;
  }
  us_bitset_free(&node);
  pair_close(&p);
  us_plan_free(&plan);
  us_structure_free(s);
  return bad ? -1 : 0;
}

static void stacker_assembly_agrees(void) {
  Tally t = {0};
  static const double mus[] = {0.0, 0.5};
  for (int m = 0; m < 2; m++)
    for (unsigned long seed = 1; seed <= 3; seed++)
      CHECK_INT(assembly_replay(walk_generated(3, mus[m], 14, seed, 0, 6), &t), ==, 0);
  report("stacker assembly", &t);
  CHECK(t.stable > t.tests / 4 && t.unstable > 0);
  CHECK(t.local > t.tests / 2);
  CHECK(t.mech > 0);
  CHECK(t.lever > 0); /* the levers took part in the agreement */
}

/* Hand-backs from a base (2D): many bodies added to a standing base at
 * once send the test to the full system, which the sparse simplex decides
 * from the base's forces (stability.c, us_local_hint); the verdicts are
 * the full system's of a workspace without local tests, stable ones with
 * a certificate and unstable ones with a Farkas ray the checks accept. */
static void hand_backs_start_from_the_base(void) {
  Tally t = {0};
  long sparse = 0;
  static const int kinds[] = {0, 1, 3}, sizes[] = {8, 12, 20};
  for (int q = 0; q < 3; q++)
    for (int m = 0; m < 2; m++) {
      us_Structure *s = gen(kinds[q], m ? 0.5 : 0.0, sizes[q], 5u + (unsigned)q);
      CHECK(s);
      Pair p;
      us_Bitset node = {0};
      CHECK_INT(pair_open(s, &p) || us_bitset_init(&node, s->nbody), ==, 0);
      unsigned long long rng = 77u + (unsigned)(10 * q + m);
      int bad = 0;
      for (int round = 0; round < 6 && !bad; round++) {
        /* the base: the lower bodies (generators number bottom-up) */
        memset(node.w, 0, (size_t)node.nwords * sizeof(uint64_t));
        for (int i = 0; i < s->nbody / 3; i++) us_bitset_set(&node, i);
        bad = pair_compare(&p, s, &node, &t) != 0;
        /* then most of the rest at once; a few left out may make it fall */
        for (int i = s->nbody / 3; i < s->nbody && !bad; i++)
          if (pile_rnd(&rng) < 0.9) us_bitset_set(&node, i);
        if (!bad) bad = pair_compare(&p, s, &node, &t) != 0;
      }
      sparse += us_stability_info(p.loc)->local_global_sparse;
      CHECK_INT(us_stability_info(p.glob)->local_global_sparse, ==, 0);
      us_bitset_free(&node);
      pair_close(&p);
      us_structure_free(s);
      CHECK_INT(bad, ==, 0);
    }
  report("hand-backs from a base", &t);
  fprintf(stderr, "hand-backs decided by the sparse simplex: %ld\n", sparse);
  CHECK(t.stable > 0 && t.unstable > 0);
  CHECK(sparse >= 12); /* the path under test decided hand-backs */
}

/* Local tests off, on, and the planner: the same plans. */
static void plans_agree(void) {
  for (int kind = 0; kind < 4; kind++) {
    us_Structure *s = gen(kind, 0.5, kind == 2 ? 7 : 7, 3);
    CHECK(s);
    us_PlanSettings a = us_plan_default_settings(), b = a;
    a.stability.local = 1;
    a.stability.local_min_bodies = 1;
    b.stability.local = -1;
    us_Plan pa, pb;
    us_Error err;
    CHECK_OK(us_plan(s, &a, &pa, &err), &err);
    CHECK_OK(us_plan(s, &b, &pb, &err), &err);
    CHECK_INT(pa.status, ==, pb.status);
    CHECK(pa.stats.stability.local_stable + pa.stats.stability.local_unstable > 0);
    CHECK_INT(pb.stats.stability.local_stable + pb.stats.stability.local_unstable, ==, 0);
    us_plan_free(&pa);
    us_plan_free(&pb);
    us_structure_free(s);
  }
}

US_TEST_MAIN({"generators_agree", generators_agree}, {"random_piles_agree", random_piles_agree},
             {"global_instability_decided", global_instability_decided},
             {"mechanism_check_rejects", mechanism_check_rejects}, {"plans_agree", plans_agree},
             {"stacker_assembly_agrees", stacker_assembly_agrees},
             {"hand_backs_start_from_the_base", hand_backs_start_from_the_base})
