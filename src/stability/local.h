/* Exact local stability tests (local.c; the argument is in docs/local.md).
 *
 * The workspace keeps a base: the last sub-assembly B proven stable, with
 * its checked forces. A test of S that differs from B by a few bodies is
 * decided on a region R of bodies around the change:
 *   - stable, if forces exist on R's contacts that hold R while every
 *     other force keeps its base value (the "fixed" LP; the merged forces
 *     are then a certificate for all of S, re-checked on R's bodies);
 *   - unstable, if R cannot stand even when the rest of S is held still
 *     (the "support" LP; its Farkas ray is a mechanism of R, checked);
 *   - else R grows (supporters under the change first, then rings of
 *     neighbours, at least doubling), and past a share of S the test goes
 *     to the full system (us_LOCAL_GLOBAL).
 */
#ifndef US_STABILITY_LOCAL_H
#define US_STABILITY_LOCAL_H

#include "backend.h"

typedef struct us_Local us_Local;

enum { US_LOCAL_STABLE = 1, US_LOCAL_UNSTABLE = 2, US_LOCAL_GLOBAL = 3 };

struct us_ConeSet;

/* A local tester on structure s whose small LPs are solved by backend be
 * (an LP backend with Farkas rays: CLP). 3D: cones are the polygonal
 * friction cones shared with the full system (lp_gen.h); the fixed LP
 * uses the inner polygons (feasible: stable for the circular cones), the
 * support LP the outer ones (infeasible: unstable for them); their
 * refinements, made by the full system, serve the local LPs too. NULL on
 * OOM or a backend error (err set). */
us_Local *us_local_new(const us_Structure *s, const us_StabilitySettings *set,
                       const us_Backend *be, struct us_ConeSet *cones, us_Error *err);
void us_local_free(us_Local *L);

/* Decide `cur` (movable bits of the sub-assembly) locally. Returns
 * US_LOCAL_STABLE (the base becomes cur, res->check holds the local
 * re-check), US_LOCAL_UNSTABLE (res->unstable_body and res->note set;
 * res->check holds the mechanism check), US_LOCAL_GLOBAL (the caller must
 * test the full system), or -1 on error (err set). info: statistics. */
int us_local_test(us_Local *L, const us_Bitset *cur, us_StabilityResult *res,
                  us_StabilityInfo *info, us_Error *err);

/* The base's forces (pending plumb loads pushed in first) as a full
 * system's starting point, indexed by structure contact (dim each): NULL
 * without a base, when the last test changed too many of its bodies (the
 * base is no start then), or when the pending loads could not be pushed
 * (OOM). */
const double *us_local_hint(us_Local *L);
/* After a test that returned US_LOCAL_GLOBAL with only bodies added (no
 * removed body touches cur): *part is the union K of the components of
 * cur that hold a changed body, and the result its size; else -1. The
 * other components of cur are components of the base, unchanged and held
 * by its forces, so cur stands iff K does: the caller may solve K's
 * system alone, then hand it to us_local_set_base with cur (the base keeps
 * its forces off K's contacts). */
int us_local_changed_part(const us_Local *L, const us_Bitset **part);

/* After a full-system stable verdict of cur with normalized forces f of the
 * system e (of cur, or of the part above): the base becomes cur with those
 * forces on e's contacts. */
void us_local_set_base(us_Local *L, const us_Bitset *cur, const us_EqSystem *e,
                       const double *f);

/* The base becomes cur with forces f (newtons per structure contact, as
 * us_local_forces gives them; other contacts 0), checked by the caller:
 * a certificate found elsewhere, e.g. on an earlier structure with the
 * same bodies and contacts. */
void us_local_seed_base(us_Local *L, const us_Bitset *cur, const us_Forces *f);

/* Body i of the caller's current set cur has just flipped (present or
 * absent): the diff against the base, the count and the plumb memo's
 * absent bodies follow, in O(1). Every change of cur between tests must
 * be told so (stability.c, toggle_body). us_local_sync: start from cur as
 * it is (a tester made after cur was filled; O(n / 64)). */
void us_local_toggle(us_Local *L, const us_Bitset *cur, int i);
void us_local_sync(us_Local *L, const us_Bitset *cur);
/* 1 when that bookkeeping agrees with a recount from cur (tests). */
int us_local_delta_consistent(const us_Local *L, const us_Bitset *cur);

/* Forget the base (after an error). */
void us_local_forget(us_Local *L);

/* The base's forces on the active contacts of cur (newtons) into f. 0 or
 * -1 on OOM. */
int us_local_forces(us_Local *L, const us_Bitset *cur, us_Forces *f);

/* A Farkas ray y (ny = e->nw * e->nbody values) of system e as a mechanism
 * (unchecked, oriented so that gravity drives it). 0 or -1 on OOM. */
int us_mechanism_from_ray(us_Mechanism *m, const us_EqSystem *e, const double *y, int ny);

/* Can the bodies reg[0..nreg) of `present` stand while every other body
 * of `present` is held still (the support LP alone, outer cone polygons
 * in 3D)? 1 they cannot: res->verdict is US_UNSTABLE and res->mechanism a
 * mechanism of theirs, checked against the true cones (a proof: no
 * motion of the rest can help them). 0 not proven, -1 error (err set).
 * The base is untouched. */
int us_local_held(us_Local *L, const us_Bitset *present, const int *reg, int nreg,
                  us_StabilityResult *res, us_StabilityInfo *info, us_Error *err);

/* The deadline of the small LPs (us_stability_set_deadline). */
void us_local_set_deadline(us_Local *L, double deadline);

#endif
