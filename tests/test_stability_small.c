/* Differential tests of the small dense simplex (lp_small.c) against
 * lp_solve, an independent solver, on the same statics systems: every
 * verdict the small solver gives must be lp_solve's, on sub-assemblies of
 * random walls up to US_SMALL_ROWS rows (both verdicts and systems of
 * more than 60 rows must occur, so the test cannot pass empty), and it
 * must leave few to CLP. A stable answer's forces must balance every body
 * (A f = rhs) with no pulling contact. */
#include "stability/backend.h"
#include "stability/equilibrium.h"
#include "stability/lp_small.h"
#include "scenes.h"
#include "eqcheck.h"
#include "test.h"

/* Counts of a sweep, to show what it covered. */
typedef struct Tally {
  int decided[2];  /* stable, unstable by the small solver */
  int big;         /* decided systems of more than 60 rows */
  int undecided;   /* left to the caller (CLP in the library) */
} Tally;

/* Small and lp_solve on sub-assembly p of s. */
static void compare(const us_Structure *s, const us_Bitset *p, void *small, void *lps, Tally *t) {
  us_EqSystem eq;
  CHECK(us_eq_init(&eq, s) == 0);
  CHECK(us_eq_build(&eq, p) == 0);
  if (!us_small_fits(&eq)) return us_eq_free(&eq);
  int nf = eq.ncontact * eq.dim + 1;
  double *f = calloc((size_t)nf, sizeof *f), *g = calloc((size_t)nf, sizeof *g);
  char note[128], note2[128];
  us_StabilityInfo info = {0};
  us_Error err;
  const us_BackendProblem pb = {.sys = &eq, .restart = 1};
  us_BackendOut a = {US_UNDECIDED, f, &info, note, sizeof note};
  us_BackendOut b = {US_UNDECIDED, g, &info, note2, sizeof note2};
  CHECK(f && g);
  if (f && g) {
    CHECK_OK(us_backend_small.solve(small, &pb, &a, &err), &err);
    CHECK_OK(us_backend_lpsolve.solve(lps, &pb, &b, &err), &err);
    if (a.verdict == US_UNDECIDED) {
      t->undecided++;
    } else {
      CHECK_INT(a.verdict, ==, b.verdict);
      t->decided[a.verdict == US_UNSTABLE]++;
      t->big += eq.nbody * eq.nw > 60;
      if (a.verdict == US_STABLE) eqcheck_forces(&eq, f);
      if (a.verdict == US_UNSTABLE) CHECK(us_backend_small.unstable_body(small) >= 0);
    }
  }
  free(f), free(g);
  us_eq_free(&eq);
}

/* Sub-assemblies of s: every prefix of the bodies in generation order
 * (bottom up: mostly standing), each prefix less one body (often not),
 * and the whole. */
static void sweep(const us_Structure *s, Tally *t) {
  us_StabilitySettings set = us_stability_default_settings();
  us_Error err;
  void *small = us_backend_small.create(s, &set, &err);
  void *lps = us_backend_lpsolve.create(s, &set, &err);
  us_Bitset p;
  CHECK(small && lps && us_bitset_init(&p, s->nbody) == 0);
  unsigned long long rnd = 12345;
  for (int k = 1; small && lps && k <= s->nbody; k++) {
    for (int b = 0; b < s->nbody; b++)
      if (b < k || s->bodies[b].fixed) us_bitset_set(&p, b);
      else us_bitset_clear(&p, b);
    compare(s, &p, small, lps, t);
    int drop = (int)(test_rnd(&rnd) * k);
    if (s->bodies[drop].fixed) continue;
    us_bitset_clear(&p, drop);
    compare(s, &p, small, lps, t);
  }
  us_bitset_free(&p);
  if (small) us_backend_small.destroy(small);
  if (lps) us_backend_lpsolve.destroy(lps);
}

/* A wall of `rows` courses of unit blocks 0.5 high over `width`, each
 * course shifted by a random quarter block, friction mu: the batch's
 * random stacks in kind (overhanging ends make some prefixes fall). */
static us_Structure *random_wall(unsigned long long seed, int rows, int width, double mu) {
  us_Structure *s = us_structure_new(2);
  if (s) s->friction = mu;
  for (int r = 0; s && r < rows; r++) {
    double x = -0.25 * (double)(int)(test_rnd(&seed) * 4.0);
    for (; x < width - 0.5; x += 1.0) scene_box_auto(s, x, 0.5 * r, 1.0, 0.5);
  }
  return s ? scene_seal(s) : NULL;
}

/* Walls of 28 to 40 blocks (up to 120 rows: the prefixes cross
 * US_SMALL_ROWS) with friction 0.6 (the default) and 0.2. */
static void agrees_with_lpsolve(void) {
  Tally t = {{0, 0}, 0, 0};
  for (unsigned long long seed = 1; seed <= 8; seed++) {
    us_Structure *s = random_wall(seed * 7919, 8 + (int)(seed % 3), 4, seed % 2 ? 0.2 : 0.6);
    CHECK(s);
    if (s) sweep(s, &t);
    us_structure_free(s);
  }
  printf("  small: %d stable, %d unstable (%d of more than 60 rows), %d left undecided\n",
         t.decided[0], t.decided[1], t.big, t.undecided);
  CHECK(t.decided[0] > 0 && t.decided[1] > 0 && t.big > 0);
  /* and it settles them itself (round-off, pivot limits or a ray that
     fails its check would leave them to CLP) */
  CHECK(20 * t.undecided <= t.decided[0] + t.decided[1]);
}

US_TEST_MAIN(T(agrees_with_lpsolve))
