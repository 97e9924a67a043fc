/* Differential tests of the sparse revised simplex (lp_sparse.c) against
 * lp_solve, an independent solver, on the same statics systems: every
 * verdict the sparse solver gives must be lp_solve's. The systems are
 * whole sub-assemblies of source-style stacker stacks (cantilevers,
 * counterweights, leaning blocks), up to several hundred rows, solved one
 * after another by one workspace (so every solve but the first starts
 * from the statuses the previous one left), and half of them again with
 * the previous stable answer's forces as the hint, as the local tests
 * pass the base forces. A stable answer's forces must balance every body
 * with no pulling contact; an unstable one must come with a Farkas ray
 * and a body. Both verdicts, large systems and warm starts must occur, so
 * the test cannot pass empty, and the solver must leave few systems to
 * the next one. */
#include "stability/backend.h"
#include "stability/equilibrium.h"
#include "stability/lp_sparse.h"
#include "eqcheck.h"
#include "test.h"

typedef struct Tally {
  int decided[2]; /* stable, unstable */
  int big;        /* decided systems of more than 300 rows */
  int hinted;     /* decided with a hint */
  int undecided;
} Tally;

typedef struct Solvers {
  void *sparse, *lps;
  double *hint; /* [structure contacts * 2]: the last stable answer, or NULL */
} Solvers;

/* The forces f of system eq into the structure-indexed hint. */
static void keep_hint(Solvers *v, const us_Structure *s, const us_EqSystem *eq, const double *f) {
  memset(v->hint, 0, (size_t)s->ncontact * 2 * sizeof(double));
  for (int c = 0; c < eq->ncontact; c++)
    for (int k = 0; k < 2; k++) v->hint[2 * (size_t)eq->contact[c] + (size_t)k] = f[2 * c + k];
}

static void compare(const us_Structure *s, const us_Bitset *p, Solvers *v, int hinted, Tally *t) {
  us_EqSystem eq;
  CHECK(us_eq_init(&eq, s) == 0);
  CHECK(us_eq_build(&eq, p) == 0);
  int nf = eq.ncontact * eq.dim + 1;
  double *f = calloc((size_t)nf, sizeof *f), *g = calloc((size_t)nf, sizeof *g);
  char note[128], note2[128];
  us_StabilityInfo info = {0};
  us_Error err;
  const us_BackendProblem pb = {.sys = &eq, .hint = hinted ? v->hint : NULL};
  const us_BackendProblem pl = {.sys = &eq, .restart = 1};
  us_BackendOut a = {US_UNDECIDED, f, &info, note, sizeof note};
  us_BackendOut b = {US_UNDECIDED, g, &info, note2, sizeof note2};
  CHECK(f && g);
  if (f && g) {
    CHECK_OK(us_backend_sparse.solve(v->sparse, &pb, &a, &err), &err);
    CHECK_OK(us_backend_lpsolve.solve(v->lps, &pl, &b, &err), &err);
    if (a.verdict == US_UNDECIDED) {
      t->undecided++;
    } else {
      CHECK_INT(a.verdict, ==, b.verdict);
      t->decided[a.verdict == US_UNSTABLE]++;
      t->big += eq.nbody * eq.nw > 300;
      t->hinted += hinted;
      if (a.verdict == US_STABLE) {
        eqcheck_forces(&eq, f);
        keep_hint(v, s, &eq, f);
      } else {
        const double *y = NULL;
        CHECK_INT(us_backend_sparse.farkas_ray(v->sparse, &y), ==, eq.nbody * eq.nw);
        CHECK(y != NULL);
        CHECK(us_backend_sparse.unstable_body(v->sparse) >= 0);
      }
    }
  }
  free(f), free(g);
  us_eq_free(&eq);
}

/* Sub-assemblies of s: every prefix of the bodies in generation order
 * (bottom up: mostly standing), each prefix less one body (often not);
 * every other one also with the hint. */
static void sweep(const us_Structure *s, Tally *t) {
  us_StabilitySettings set = us_stability_default_settings();
  us_Error err;
  Solvers v = {us_backend_sparse.create(s, &set, &err), us_backend_lpsolve.create(s, &set, &err),
               calloc((size_t)s->ncontact * 2 + 1, sizeof(double))};
  us_Bitset p;
  CHECK(v.sparse && v.lps && v.hint && us_bitset_init(&p, s->nbody) == 0);
  unsigned long long rnd = 4242;
  int stride = 2 + s->nbody / 40; /* about 40 prefixes of each stack */
  for (int k = 1; v.sparse && v.lps && v.hint && k <= s->nbody; k += stride) {
    for (int b = 0; b < s->nbody; b++)
      if (b < k || s->bodies[b].fixed) us_bitset_set(&p, b);
      else us_bitset_clear(&p, b);
    compare(s, &p, &v, 0, t);
    if (k % 2 == 1) compare(s, &p, &v, 1, t);
    int drop = (int)(test_rnd(&rnd) * k);
    if (s->bodies[drop].fixed) continue;
    us_bitset_clear(&p, drop);
    compare(s, &p, &v, k % 4 < 2, t);
  }
  us_bitset_free(&p);
  if (v.sparse) us_backend_sparse.destroy(v.sparse);
  if (v.lps) us_backend_lpsolve.destroy(v.lps);
  free(v.hint);
}

/* Stacker stacks of 14 rows 12 blocks wide (about 80 bodies) and 30 rows
 * 20 wide (about 220 bodies: systems of up to 660-odd rows), friction 0.5
 * and 0.3. */
static void agrees_with_lpsolve(void) {
  Tally t = {{0, 0}, 0, 0, 0};
  for (unsigned long seed = 1; seed <= 3; seed++) {
    us_GenSettings g = us_gen_default_settings();
    g.rows = seed < 3 ? 14 : 30, g.width = seed < 3 ? 12 : 20, g.seed = seed;
    g.friction = seed % 2 ? 0.5 : 0.3;
    us_Error err;
    us_Structure *s = us_gen_stacker(&g, &err);
    CHECK(s);
    if (s) sweep(s, &t);
    us_structure_free(s);
  }
  printf("  sparse: %d stable, %d unstable (%d of more than 300 rows, %d with a hint), "
         "%d left undecided\n",
         t.decided[0], t.decided[1], t.big, t.hinted, t.undecided);
  CHECK(t.decided[0] > 0 && t.decided[1] > 0 && t.big > 0 && t.hinted > 0);
  CHECK(t.undecided * 50 <= t.decided[0] + t.decided[1]); /* it settles them itself */
}

/* A system with no active contact: the verdict follows the right-hand
 * side alone (a body with weight and nothing under it falls). */
static void no_contact(void) {
  us_Structure *s = us_structure_new(2);
  CHECK(s);
  if (!s) return;
  double sq[] = {0, 5, 1, 5, 1, 6, 0, 6};
  us_Error err;
  CHECK(us_structure_add_polygon(s, "floating", 4, sq, 0, 0, 0, 0.5, &err) == 0);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  us_StabilitySettings set = us_stability_default_settings();
  void *w = us_backend_sparse.create(s, &set, &err);
  us_Bitset p;
  us_EqSystem eq;
  CHECK(w && us_bitset_init(&p, s->nbody) == 0 && us_eq_init(&eq, s) == 0);
  us_bitset_fill(&p);
  CHECK(us_eq_build(&eq, &p) == 0);
  double f[3];
  char note[64];
  us_StabilityInfo info = {0};
  const us_BackendProblem pb = {.sys = &eq};
  us_BackendOut out = {US_UNDECIDED, f, &info, note, sizeof note};
  CHECK_OK(us_backend_sparse.solve(w, &pb, &out, &err), &err);
  CHECK_INT(out.verdict, ==, US_UNSTABLE);
  us_eq_free(&eq);
  us_bitset_free(&p);
  us_backend_sparse.destroy(w);
  us_structure_free(s);
}

US_TEST_MAIN(T(agrees_with_lpsolve), T(no_contact))
