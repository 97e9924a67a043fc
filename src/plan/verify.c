/* Plan verification: re-test the full structure and the remainder after
 * every removal with a fresh stability workspace, each verdict carrying its
 * re-checked certificate. The remainders are tested from the last one up
 * (each adds one step: local tests, no from-scratch solve of the whole).
 * The first removal after which the remainder does not stand is reported;
 * an order that leaves bodies in place is incomplete. A test that cannot
 * be decided (us_Verdict US_UNDECIDED) is neither: the first one in
 * removal order is noted, and a remainder that falls after it still
 * proves the order invalid; when none falls the answer is undecided,
 * never "valid" and never "does not stand". Input mistakes
 * in the order (unknown, fixed or repeated bodies) are errors, not
 * outcomes. Every entry point accepts a NULL error pointer. */
#include "core/core.h"
#include "contact/kinematics.h"
#include "hook.h"
#include "stability/stability.h"

#include <stdio.h>
#include <string.h>

static us_Status check_order(const us_Structure *s, const int *order, int n, us_Bitset *seen,
                             us_Error *err) {
  for (int k = 0; k < n; k++) {
    int b = order[k];
    if (b < 0 || b >= s->nbody)
      return us_error_set(err, US_ERR_INPUT, "step %d: no body with index %d", k + 1, b);
    if (s->bodies[b].fixed)
      return us_error_set(err, US_ERR_INPUT, "step %d: body '%s' is fixed and cannot be removed",
                          k + 1, us_id_text(s->bodies[b].id).s);
    if (us_bitset_get(seen, b))
      return us_error_set(err, US_ERR_INPUT, "step %d: body '%s' is removed twice", k + 1,
                          us_id_text(s->bodies[b].id).s);
    us_bitset_set(seen, b);
  }
  return US_OK;
}

static void note_step(us_VerifyReport *rep, const us_StabilityResult *res) {
  rep->steps_checked++;
  if (res->check.max_force_residual > rep->max_force_residual)
    rep->max_force_residual = res->check.max_force_residual;
  if (res->check.max_torque_residual > rep->max_torque_residual)
    rep->max_torque_residual = res->check.max_torque_residual;
}

/* Step k's bodies (k >= 0) back into the workspace's current set; their
 * number. */
static int put_back(us_Stability *w, const int *order, const int *gs, int k) {
  int q0 = gs ? gs[k] : k, q1 = gs ? gs[k + 1] : k + 1;
  for (int q = q0; q < q1; q++) us_stability_add(w, order[q], NULL);
  return q1 - q0;
}

/* Test every remainder, from the last one up to the full structure (each
 * test adds one step to the previous one, stated as that change (tests by
 * change), so the stability workspace's local tests apply, the full
 * structure is never solved from scratch, and a step costs what its
 * bodies cost, not the structure's size). The answer is the one of a walk
 * down the order: the first step (smallest k) after which the remainder
 * falls, else the first undecided test, else valid. node: the full
 * structure on entry. */
static us_Status walk(us_Stability *w, us_Bitset *node, const int *order, const int *gs,
                      int nsteps, us_VerifyReport *rep, us_StabilityResult *res, us_Error *err) {
  for (int k = 0; k < nsteps; k++)
    for (int q = gs ? gs[k] : k; q < (gs ? gs[k + 1] : k + 1); q++) us_bitset_clear(node, order[q]);
  int left = us_bitset_count(node), failed = nsteps, undecided = nsteps, now = left;
  us_Status set = us_stability_set_current(w, node, err);
  if (set) return set;
  for (int k = nsteps - 1; k >= -1; k--) {
    if (k < nsteps - 1) now += put_back(w, order, gs, k + 1);
    long timed_out = us_stability_info(w)->timed_out;
    us_Status st = us_plan_stability_test_current(w, res, err);
    if (st) return st;
    if (us_stability_info(w)->timed_out > timed_out) { /* the time limit: no answer */
      rep->undecided = 1;
      rep->undecided_step = k;
      rep->failed_step = -1;
      rep->full_unstable = rep->incomplete = rep->ok = 0;
      snprintf(rep->note, sizeof rep->note, "time limit (%d of %d remainders tested)",
               nsteps - 1 - k, nsteps + 1);
      return US_OK;
    }
    note_step(rep, res);
    if (res->verdict == US_UNDECIDED) {
      undecided = k;
      snprintf(rep->note, sizeof rep->note, "%s", res->note[0] ? res->note : "no reason given");
    }
    if (res->verdict == US_UNSTABLE) {
      failed = k;
      rep->remaining = now;
      rep->unstable_body = res->unstable_body;
    }
  }
  if (failed < nsteps) {
    rep->full_unstable = failed < 0;
    rep->failed_step = failed < 0 ? -1 : failed;
  } else {
    rep->remaining = left;
    rep->incomplete = left > 0;
  }
  /* an undecided test matters only before the first fall, in removal order */
  int und = undecided < failed && undecided < nsteps;
  if (und) rep->undecided_step = undecided;
  else rep->note[0] = '\0';
  rep->undecided = und && failed == nsteps && !rep->incomplete;
  rep->ok = failed == nsteps && !rep->incomplete && !und;
  return US_OK;
}

/* Step offsets must run from 0 to n, increasing. */
static us_Status check_steps(const int *gs, int ngroups, int n, us_Error *err) {
  if (!gs) return US_OK;
  if (ngroups < 0 || gs[0] != 0 || gs[ngroups] != n)
    return us_error_set(err, US_ERR_INPUT, "plan steps do not cover the order");
  for (int k = 0; k < ngroups; k++)
    if (gs[k + 1] <= gs[k])
      return us_error_set(err, US_ERR_INPUT, "plan step %d is empty", k + 1);
  return US_OK;
}

us_Status us_verify_order(const us_Structure *s, const us_StabilitySettings *set, const int *order,
                          int n, us_VerifyReport *rep, us_Error *err) {
  return us_verify_steps(s, set, order, n, NULL, n, rep, err);
}

us_Status us_verify_steps(const us_Structure *s, const us_StabilitySettings *set, const int *order,
                          int n, const int *group_start, int ngroups, us_VerifyReport *rep,
                          us_Error *err) {
  us_Error local;
  if (!err) err = &local;
  us_error_clear(err);
  if (!s || !set || !rep || (n > 0 && !order))
    return us_error_set(err, US_ERR_USAGE, "us_verify_steps: NULL argument");
  memset(rep, 0, sizeof *rep);
  rep->failed_step = -1;
  rep->unstable_body = -1;
  us_Bitset seen = {0}, node = {0};
  if (us_bitset_init(&seen, s->nbody) || us_structure_movable_set(s, &node)) {
    us_bitset_free(&seen);
    return us_error_set(err, US_ERR_NOMEM, "out of memory");
  }
  us_Status st = check_order(s, order, n, &seen, err);
  if (!st) st = check_steps(group_start, ngroups, n, err);
  us_Stability *w = st ? NULL : us_stability_new(s, set, err);
  if (!st && !w) st = err->code ? err->code : US_ERR_NOMEM;
  if (w) us_stability_set_skip_forces(w, 1); /* verdicts and checks only */
  us_StabilityResult res;
  memset(&res, 0, sizeof res);
  if (!st) st = walk(w, &node, order, group_start, group_start ? ngroups : n, rep, &res, err);
  us_stability_result_free(&res);
  us_stability_free(w);
  us_bitset_free(&seen);
  us_bitset_free(&node);
  return st;
}

/* Kinematics of an order: before each removal, may the body leave (lifted
 * straight up, or along some free direction) past the bodies still there? */
us_Status us_verify_removals(const us_Structure *s, us_Removal removal, const int *order, int n,
                             int *failed_step, int *blocker, us_Error *err) {
  us_Error local;
  if (!err) err = &local;
  us_error_clear(err);
  if (!s || !failed_step || !blocker || (n > 0 && !order))
    return us_error_set(err, US_ERR_USAGE, "us_verify_removals: NULL argument");
  *failed_step = -1;
  *blocker = -1;
  if (removal == US_REMOVAL_ANY) return US_OK;
  us_Bitset node = {0};
  if (us_bitset_init(&node, s->nbody)) return us_error_set(err, US_ERR_NOMEM, "out of memory");
  us_Status st = check_order(s, order, n, &node, err);
  us_bitset_free(&node);
  if (st) return st;
  us_Kinematics *k = us_kinematics_new(s, removal, err);
  if (!k || us_structure_movable_set(s, &node)) {
    us_kinematics_free(k);
    return k || !err->code ? us_error_set(err, US_ERR_NOMEM, "out of memory") : err->code;
  }
  for (int q = 0; q < n && *failed_step < 0; q++) {
    if (!us_kinematics_can_remove(k, &node, order[q])) {
      *failed_step = q;
      *blocker = us_kinematics_blocker(k, &node, order[q]);
    }
    us_bitset_clear(&node, order[q]);
  }
  us_bitset_free(&node);
  us_kinematics_free(k);
  return US_OK;
}
