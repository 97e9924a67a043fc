/* Tests of the representative force sets (src/stability/represent.c):
 * every set returned as stable passes the independent certificate check
 * and agrees with the stability test's verdict; on a block resting on two
 * supports the margin and min-norm sets load both supports, whatever the solver's
 * vertex does; a structure that falls gets no set. No force value is
 * asserted beyond such provable properties. */
#include "extrude.h"
#include "scenes.h"
#include "test.h"

/* Sum of the normal forces on contacts between body a (US_GROUND too) and b. */
static double normal_between(const us_Structure *s, const us_Forces *f, int a, int b) {
  double sum = 0.0;
  for (int j = 0; j < f->ncontact; j++) {
    const us_Contact *c = &s->contacts[f->contact[j]];
    if ((c->a == a && c->b == b) || (c->a == b && c->b == a)) sum += f->f[s->dim * j];
  }
  return sum;
}

/* A beam across two piers: piers 0 and 1, beam 2 (symmetric). */
static us_Structure *bridge(int dim) {
  us_Structure *s = us_structure_new(2);
  scene_box(s, "left", 0, 0, 1, 1, 1);
  scene_box(s, "right", 3, 0, 1, 1, 1);
  scene_box(s, "beam", 0, 1, 4, 0.5, 1);
  s = scene_seal(s);
  if (!s || dim == 2) return s;
  us_Structure *e = test_finalized(test_extrude(s, 1.0, 0.0, 0.0, 0.0), "bridge3d");
  us_structure_free(s);
  return e;
}

/* The set of rule `kind` for the full s: stable and certified, the full
 * check passed again here from scratch. */
static int certified_set(const us_Structure *s, us_ForceSet kind, us_StabilityResult *res) {
  us_Bitset p;
  us_Error err;
  if (us_bitset_init(&p, s->nbody)) return 0;
  us_bitset_fill(&p);
  us_Status st = us_stability_forces_representative(s, &p, kind, NULL, res, &err);
  us_CertCheck again = us_certificate_check(s, &p, &res->forces, 1e-6);
  us_bitset_free(&p);
  return st == US_OK && res->verdict == US_STABLE && res->check.ok && again.ok;
}

/* Both rules on the bridge, 2D and 3D (inner friction polygons). */
static void bridge_certified(void) {
  for (int dim = 2; dim <= 3; dim++) {
    us_Structure *s = bridge(dim);
    CHECK(s);
    us_StabilityResult res;
    us_stability_result_init(&res);
    CHECK(certified_set(s, US_FORCESET_MARGIN, &res));
    CHECK(certified_set(s, US_FORCESET_MIN_SUM, &res));
    CHECK(certified_set(s, US_FORCESET_MIN_NORM, &res));
    us_stability_result_free(&res);
    us_structure_free(s);
  }
}

/* Symmetric load: the margin set puts a positive normal force on every
 * contact (and min-norm on both piers), so on both piers (a vertex of the LP may load one pier's outer
 * corner and the other's inner one, but never needs both piers evenly). */
static void margin_loads_both_supports(void) {
  for (int dim = 2; dim <= 3; dim++) {
    us_Structure *s = bridge(dim);
    CHECK(s);
    us_StabilityResult res;
    us_stability_result_init(&res);
    CHECK(certified_set(s, US_FORCESET_MARGIN, &res));
    CHECK(normal_between(s, &res.forces, 0, 2) > 0.0);
    CHECK(normal_between(s, &res.forces, 1, 2) > 0.0);
    for (int j = 0; j < res.forces.ncontact; j++) CHECK(res.forces.f[s->dim * j] > 0.0);
    /* min-norm: the unique minimiser of a strictly convex function keeps
       the mirror symmetry, so the piers share the beam */
    CHECK(certified_set(s, US_FORCESET_MIN_NORM, &res));
    CHECK(normal_between(s, &res.forces, 0, 2) > 0.0);
    CHECK(normal_between(s, &res.forces, 1, 2) > 0.0);
    us_stability_result_free(&res);
    us_structure_free(s);
  }
}

/* Pyramid-like stack of 6 on a 3-2-1 layout: certified with both rules,
 * the same verdict as the stability test. */
static void stack_agrees_with_test(void) {
  us_Structure *s = us_structure_new(2);
  char id[16];
  for (int row = 0, k = 0; row < 3; row++)
    for (int i = 0; i < 3 - row; i++, k++) {
      snprintf(id, sizeof id, "b%d", k);
      scene_box(s, id, 0.5 * row + i, row, 1, 1, 1);
    }
  s = scene_seal(s);
  CHECK(s);
  us_StabilityResult res, test;
  us_stability_result_init(&res);
  us_stability_result_init(&test);
  us_Error err;
  us_Stability *w = us_stability_new(s, NULL, &err);
  CHECK(w);
  CHECK_OK(us_stability_test_full(w, &test, &err), &err);
  CHECK_INT(test.verdict, ==, US_STABLE);
  CHECK(certified_set(s, US_FORCESET_MARGIN, &res));
  CHECK(certified_set(s, US_FORCESET_MIN_SUM, &res));
  CHECK(certified_set(s, US_FORCESET_MIN_NORM, &res));
  us_stability_free(w);
  us_stability_result_free(&res);
  us_stability_result_free(&test);
  us_structure_free(s);
}

/* A block hanging past its support's edge falls: no set, and no claim of
 * stability; a bad rule is a usage error. */
static void falling_gets_no_set(void) {
  us_Structure *s = us_structure_new(2);
  scene_box(s, "base", 0, 0, 1, 1, 1);
  scene_box(s, "over", 0.8, 1, 1, 0.2, 1);
  s = scene_seal(s);
  CHECK(s);
  us_Bitset p;
  CHECK(us_bitset_init(&p, s->nbody) == 0);
  us_bitset_fill(&p);
  us_StabilityResult res;
  us_stability_result_init(&res);
  us_Error err;
  CHECK_OK(us_stability_forces_representative(s, &p, US_FORCESET_MARGIN, NULL, &res, &err), &err);
  CHECK_INT(res.verdict, ==, US_UNDECIDED);
  CHECK(res.note[0] != 0);
  CHECK_INT(us_stability_forces_representative(s, &p, US_FORCESET_SOLVER, NULL, &res, &err), ==,
            US_ERR_USAGE);
  us_stability_result_free(&res);
  us_bitset_free(&p);
  us_structure_free(s);
}

/* Every allocation failing in turn: an error (US_ERR_NOMEM) or the set,
 * never a crash or a leak (the harness checks leaks after each case). */
static void out_of_memory_is_clean(void) {
  us_Structure *s = bridge(2);
  CHECK(s);
  us_Bitset p;
  CHECK(us_bitset_init(&p, s->nbody) == 0);
  us_bitset_fill(&p);
  for (int kind = US_FORCESET_MARGIN; kind <= US_FORCESET_MIN_NORM; kind++) {
    us_Status st = US_ERR_NOMEM;
    int n = 0, other = 0;
    for (; st == US_ERR_NOMEM && n < 1000; n++) {
      us_StabilityResult res;
      us_stability_result_init(&res);
      us_Error err;
      us_alloc_fail_after(n);
      st = us_stability_forces_representative(s, &p, (us_ForceSet)kind, NULL, &res, &err);
      us_alloc_fail_after(-1);
      other += st != US_OK && st != US_ERR_NOMEM;
      if (st == US_OK) CHECK_INT(res.verdict, ==, US_STABLE);
      us_stability_result_free(&res);
    }
    CHECK_INT(other, ==, 0);
    CHECK_INT(st, ==, US_OK);
    CHECK(n > 1);
  }
  us_bitset_free(&p);
  us_structure_free(s);
}

US_TEST_MAIN(T(bridge_certified), T(margin_loads_both_supports), T(stack_agrees_with_test),
             T(falling_gets_no_set), T(out_of_memory_is_clean))
