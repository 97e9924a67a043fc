/* The planner's stability test with the test-only verdict hook (hook.h):
 * the backend's verdict first, then the hook, which may only weaken it
 * (stable -> unstable or undecided; unstable -> undecided). */
#include "hook.h"

#include "stability/stability.h"

/* per thread: a test's hook never sees another thread's planner */
static _Thread_local us_PlanTestHook hook_fn;
static _Thread_local void *hook_user;

void us_plan_set_test_hook(us_PlanTestHook fn, void *user) {
  hook_fn = fn;
  hook_user = fn ? user : NULL;
}

/* Verdicts ordered by strength: stable, then unstable, then undecided. */
static int strength(us_Verdict v) { return v == US_STABLE ? 2 : v == US_UNSTABLE ? 1 : 0; }

/* The hook on a result of status st, which it may only weaken. */
static us_Status hooked(us_Status st, const us_Bitset *node, us_StabilityResult *res) {
  if (st || !hook_fn) return st;
  us_Verdict before = res->verdict;
  hook_fn(hook_user, node, res);
  if (strength(res->verdict) > strength(before)) res->verdict = before;
  return US_OK;
}

us_Status us_plan_stability_test(us_Stability *w, const us_Bitset *node, us_StabilityResult *res,
                                 us_Error *err) {
  return hooked(us_stability_test(w, node, res, err), node, res);
}

us_Status us_plan_stability_test_current(us_Stability *w, us_StabilityResult *res, us_Error *err) {
  us_Status st = us_stability_test_current(w, res, err);
  return hooked(st, us_stability_current(w), res);
}

us_Status us_plan_held_test(us_Stability *w, const us_Bitset *present, const int *reg, int nreg,
                            us_StabilityResult *res, us_Error *err) {
  return hooked(us_stability_held(w, present, reg, nreg, res, err), present, res);
}
