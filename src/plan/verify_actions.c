/* Verification of action plans (plans with hands, docs/planning.md,
 * "Hands"): first the sequence (never more than H held, each body placed
 * once, grabs of placed bodies not held, releases of held bodies, all
 * placed and none held at the end: a mistake is an input error naming the
 * action's index), then after every release a fresh stability test of the
 * placed bodies with the held ones fixed (a copy of the structure whose
 * held bodies are `fixed`, us_hands_fixed_copy), each verdict carrying its
 * re-checked certificate. As in verify.c, the first release after which
 * the placed bodies fall is reported; an undecided test before it makes
 * the answer undecided, never valid. */
#include "hands.h"
#include "hook.h"

#include <stdio.h>
#include <string.h>

static const char *id_of(const us_Structure *s, int b) { return us_id_text(s->bodies[b].id).s; }

/* One action's bookkeeping: the sets after it, or an input error. */
static us_Status step(const us_Structure *s, int H, const us_Action *a, int k, us_Bitset *P,
                      us_Bitset *F, int *nheld, us_Error *err) {
  int b = a->body;
  if (b < 0 || b >= s->nbody || s->bodies[b].fixed)
    return us_error_set(err, US_ERR_INPUT, "action %d: no movable body with index %d", k, b);
  if (a->verb == US_ACTION_PLACE && us_bitset_get(P, b))
    return us_error_set(err, US_ERR_INPUT, "action %d: body '%s' is placed twice", k, id_of(s, b));
  if (a->verb == US_ACTION_GRAB && (!us_bitset_get(P, b) || us_bitset_get(F, b)))
    return us_error_set(err, US_ERR_INPUT, "action %d: body '%s' is %s", k, id_of(s, b),
                        us_bitset_get(P, b) ? "already held" : "grabbed before it is placed");
  if (a->verb == US_ACTION_RELEASE && !us_bitset_get(F, b))
    return us_error_set(err, US_ERR_INPUT, "action %d: body '%s' is released but not held", k,
                        id_of(s, b));
  if ((unsigned)a->verb > US_ACTION_RELEASE)
    return us_error_set(err, US_ERR_INPUT, "action %d: unknown verb", k);
  if (a->verb == US_ACTION_RELEASE) us_bitset_clear(F, b), (*nheld)--;
  else us_bitset_set(P, b), us_bitset_set(F, b), (*nheld)++;
  if (*nheld > H)
    return us_error_set(err, US_ERR_INPUT, "action %d: %d bodies held, more than the plan's %d "
                        "hands", k, *nheld, H);
  return US_OK;
}

/* The whole sequence, without stability. */
static us_Status check_sequence(const us_Structure *s, int H, const us_Action *a, int n,
                                us_Bitset *P, us_Bitset *F, us_Error *err) {
  int nheld = 0;
  for (int k = 0; k < n; k++) {
    us_Status st = step(s, H, &a[k], k, P, F, &nheld, err);
    if (st) return st;
  }
  for (int i = 0; i < s->nbody; i++)
    if (!s->bodies[i].fixed && !us_bitset_get(P, i))
      return us_error_set(err, US_ERR_INPUT, "the actions never place body '%s'", id_of(s, i));
  if (nheld > 0)
    return us_error_set(err, US_ERR_INPUT, "%d bod%s still held after the last action", nheld,
                        nheld == 1 ? "y is" : "ies are");
  return US_OK;
}

/* Do the bodies of P stand with those of F fixed? A fresh workspace. */
static us_Status test_held(const us_Structure *s, const us_StabilitySettings *set,
                           const us_Bitset *P, const us_Bitset *F, us_StabilityResult *res,
                           us_Error *err) {
  us_Structure copy;
  us_Body *bodies;
  if (us_hands_fixed_copy(s, F, &copy, &bodies))
    return us_error_set(err, US_ERR_NOMEM, "out of memory (verify)");
  us_Stability *w = us_stability_new(&copy, set, err);
  us_Status st = w ? us_plan_stability_test(w, P, res, err) : (err->code ? err->code : US_ERR_NOMEM);
  us_stability_free(w);
  us_free(bodies);
  return st;
}

static void note_test(us_VerifyReport *rep, const us_StabilityResult *res) {
  rep->steps_checked++;
  if (res->check.max_force_residual > rep->max_force_residual)
    rep->max_force_residual = res->check.max_force_residual;
  if (res->check.max_torque_residual > rep->max_torque_residual)
    rep->max_torque_residual = res->check.max_torque_residual;
}

/* Replay with a test after every release; fills rep. */
static us_Status replay(const us_Structure *s, const us_StabilitySettings *set,
                        const us_Action *a, int n, us_Bitset *P, us_Bitset *F,
                        us_VerifyReport *rep, us_Error *err) {
  us_StabilityResult res;
  us_stability_result_init(&res);
  us_Status st = US_OK;
  int nheld = 0;
  for (int k = 0; k < n && !st && rep->failed_step < 0; k++) {
    st = step(s, 64, &a[k], k, P, F, &nheld, err);
    if (st || a[k].verb != US_ACTION_RELEASE) continue;
    st = test_held(s, set, P, F, &res, err);
    if (st) break;
    note_test(rep, &res);
    if (res.verdict == US_UNSTABLE) {
      rep->failed_step = k;
      rep->remaining = us_bitset_count(P);
      rep->unstable_body = res.unstable_body;
    } else if (res.verdict == US_UNDECIDED && rep->undecided_step < 0) {
      rep->undecided_step = k;
      snprintf(rep->note, sizeof rep->note, "%s", res.note[0] ? res.note : "no reason given");
    }
  }
  us_stability_result_free(&res);
  rep->undecided = !st && rep->failed_step < 0 && rep->undecided_step >= 0;
  rep->ok = !st && rep->failed_step < 0 && !rep->undecided;
  return st;
}

us_Status us_verify_actions(const us_Structure *s, const us_StabilitySettings *set, int hands,
                            const us_Action *actions, int n, us_VerifyReport *rep,
                            us_Error *err) {
  us_Error local;
  if (!err) err = &local;
  us_error_clear(err);
  if (!s || !rep || (n > 0 && !actions))
    return us_error_set(err, US_ERR_USAGE, "us_verify_actions: NULL argument");
  memset(rep, 0, sizeof *rep);
  rep->failed_step = rep->undecided_step = rep->unstable_body = -1;
  if (hands < 1 || hands > 64)
    return us_error_set(err, US_ERR_INPUT, "hands must be 1 to 64, got %d", hands);
  us_Bitset P = {0}, F = {0};
  us_Status st = us_bitset_init(&P, s->nbody) || us_bitset_init(&F, s->nbody)
                     ? us_error_set(err, US_ERR_NOMEM, "out of memory (verify)")
                     : check_sequence(s, hands, actions, n, &P, &F, err);
  if (!st) {
    memset(P.w, 0, (size_t)P.nwords * sizeof(uint64_t));
    memset(F.w, 0, (size_t)F.nwords * sizeof(uint64_t));
    st = replay(s, set, actions, n, &P, &F, rep, err);
  }
  us_bitset_free(&P);
  us_bitset_free(&F);
  return st;
}
