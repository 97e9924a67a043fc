/* The stability module's surface for the layers above it (the planner,
 * plan verification): workspace controls that are not public API. Only
 * this header of src/stability is theirs; the backend interface
 * (backend.h) stays inside the module and its tests. */
#ifndef US_STABILITY_STABILITY_H
#define US_STABILITY_STABILITY_H

#include "core/core.h"

/* Whether stable results carry their forces (the planner's searches skip
 * them; us_StabilitySettings.skip_forces sets the initial value). */
void us_stability_set_skip_forces(us_Stability *w, int skip);

/* 3D friction cones: refinement rounds of one test at most (default
 * CONE_ROUNDS, 60; 0: none), after which the outer polygons' forces are
 * the claim and the certificate decides (stable or UNDECIDED, never a
 * stable without a passed check). The random3d generator's drop tests use
 * a small budget: an undecided drop is simply discarded. And the most
 * rounds one test of the workspace ran (its tests' counter). */
void us_stability_set_cone_rounds(us_Stability *w, int rounds);
int us_stability_cone_rounds_max(const us_Stability *w);

/* Bilateral joints (on 1) for the workspace's later tests: every contact
 * force component free in sign, no friction cone (the LP's generators
 * +-n, +-t, lp_gen.h); certificates are checked in that mode (residuals
 * only) and mechanisms must keep every contact closed and unslipping.
 * The local tests are skipped. Only the LP methods (lp, lpsolve): -1 for
 * any other, the workspace unchanged. classify's "stands only with
 * equality constraints" (docs/classify.md). */
int us_stability_set_bilateral(us_Stability *w, int on);

/* Can the bodies reg[0..nreg) of `present` stand while every other body
 * of `present` is held still? res->verdict US_UNSTABLE: they cannot, and
 * res->mechanism is their mechanism, checked against the true cones (a
 * proof, whatever the rest does); US_UNDECIDED: not proven. Solved by CLP
 * with the local tests' support LP (local.h) whatever the method, since
 * the proof is the checked mechanism, not the solver's word. Does not
 * count as a test and leaves the reuse state of us_stability_test alone. */
us_Status us_stability_held(us_Stability *w, const us_Bitset *present, const int *reg, int nreg,
                            us_StabilityResult *res, us_Error *err);

/* Start the local tests from `present` standing with forces f (newtons,
 * as in us_StabilityResult.forces; e.g. an earlier structure's forces
 * carried over to this one, which has the same bodies and more), as if a
 * test of `present` had found them: the next test that differs from it by
 * a few bodies is decided on a region around them. The forces are
 * re-checked first (the certificate check, cert_tol); *taken is 1 when
 * they passed and became the base, 0 when not or when the workspace has
 * no local tests (the next test then goes as it would have). */
us_Status us_stability_seed(us_Stability *w, const us_Bitset *present, const us_Forces *f,
                            int *taken, us_Error *err);

/* Whether a test costs what its change costs, not what the set costs, so
 * a caller may state a step as a change of a larger set: the unilateral
 * tests go through the local tests (local.h), in 2D, where a test they
 * hand back solves only the components that changed (3D hands more tests
 * back, and solves the whole set). */
int us_stability_tests_locally(const us_Stability *w);

/* Tests of the tests-by-change bookkeeping (us_stability_add ...): 1 when
 * the current set's count, and the local tests' diff against their base,
 * their count and their memo's absent bodies, all agree with a recount
 * from the bitsets (O(n)); 0 when some does not. */
int us_stability_delta_consistent(const us_Stability *w);

#endif
