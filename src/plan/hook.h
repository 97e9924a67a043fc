/* The one stability test of the planner, plan verification and
 * classification (hook.c), with a test-only hook on its verdicts.
 *
 * The hook exists so that tests can make chosen tests undecided (or
 * unstable) deterministically, whatever the backends do: an undecided
 * verdict is rare and depends on the solvers, but the planner must handle
 * it soundly (never a found plan through it, never a proof of `none` or
 * `unstable` resting on it). It may only weaken verdicts: a hook that
 * turns an undecided or unstable verdict into stable would let a test
 * claim a certificate that was never checked, so such a change is ignored.
 * The hook belongs to the calling thread (thread-local): tests set it,
 * run, and clear it (fn NULL), and the planners of other threads never
 * see it. Library users never need it. */
#ifndef US_PLAN_HOOK_H
#define US_PLAN_HOOK_H

#include "core/core.h"

/* Called after every stability test of the planner with the node tested
 * and its result; may set res->verdict to US_UNSTABLE or US_UNDECIDED (and
 * res->note to a reason). */
typedef void (*us_PlanTestHook)(void *user, const us_Bitset *node, us_StabilityResult *res);
void us_plan_set_test_hook(us_PlanTestHook fn, void *user);

/* us_stability_test, then the hook when one is set. */
us_Status us_plan_stability_test(us_Stability *w, const us_Bitset *node, us_StabilityResult *res,
                                 us_Error *err);

/* The same for the workspace's current set (us_stability_test_current);
 * the hook sees that set as its node. */
us_Status us_plan_stability_test_current(us_Stability *w, us_StabilityResult *res, us_Error *err);

/* Can bodies reg[0..nreg) of `present` stand with the rest of `present`
 * held still (us_stability_held)? US_UNSTABLE in res is a proof that they
 * cannot (a checked mechanism); then the hook, as above. */
us_Status us_plan_held_test(us_Stability *w, const us_Bitset *present, const int *reg, int nreg,
                            us_StabilityResult *res, us_Error *err);

#endif
