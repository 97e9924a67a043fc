/* The helpers every search shares (search.h): the goal test, the legal
 * moves, and one stability test of a node with the limits and statistics.
 *
 * A test's verdict is one of three: certified stable (a certificate that
 * passed the independent check), unstable, or undecided (a solver limit,
 * or a certificate that failed). The searches only need "certified stable
 * or not", so an undecided node is simply not known stable: it never
 * enters a found plan, and it is never taken for a proof either, because
 * it is counted in st->undecided and the driver (plan.c) downgrades a
 * `none` or `unstable` that may rest on it to `undecided`. The first
 * undecided test's reason is kept in ctx->note. */
#include "search.h"
#include "hook.h"

#include <stdio.h>

int us_plan_is_goal(const us_SearchCtx *ctx, const us_Bitset *node) {
  if (ctx->set->direction == US_DIR_UP) return us_bitset_equal(node, &ctx->part);
  for (int i = 0; i < node->nwords; i++)
    if (node->w[i]) return 0;
  return 1;
}

int us_plan_can_move(const us_SearchCtx *ctx, const us_Bitset *node, int b) {
  int down = ctx->set->direction == US_DIR_DOWN;
  if (us_bitset_get(node, b) != down) return 0;
  /* placing b is removing it, reversed: the same question */
  return !ctx->kin || us_kinematics_can_remove(ctx->kin, node, b);
}

int us_plan_limit_reached(const us_SearchCtx *ctx) {
  const us_PlanSettings *set = ctx->set;
  if (set->max_tests > 0 && ctx->st->tests >= set->max_tests) return 1;
  return set->time_limit > 0 && us_now() - ctx->t_start >= set->time_limit;
}

static void count_verdict(us_SearchCtx *ctx) {
  us_PlanStats *st = ctx->st;
  st->tests++;
  switch (ctx->res.verdict) {
  case US_STABLE: st->stable++; break;
  case US_UNSTABLE: st->unstable++; break;
  default:
    if (st->undecided++ == 0 && ctx->note)
      snprintf(ctx->note, ctx->note_sz, "%s", ctx->res.note[0] ? ctx->res.note : "no reason given");
    break;
  }
}

/* One test of node, or of the workspace's current set when node is NULL. */
static int test_node(us_SearchCtx *ctx, const us_Bitset *node, us_Error *err) {
  if (us_plan_limit_reached(ctx)) return US_STEP_LIMIT;
  if (ctx->exact_end > 0 && ctx->st->tests >= ctx->exact_end) return US_STEP_LIMIT;
  if (ctx->budget_end > 0 && ctx->st->tests >= ctx->budget_end) return US_STEP_RESTART;
  long timed_out = us_stability_info(ctx->stab)->timed_out;
  us_Status st = node ? us_plan_stability_test(ctx->stab, node, &ctx->res, err)
                      : us_plan_stability_test_current(ctx->stab, &ctx->res, err);
  if (st) return US_STEP_ERROR;
  /* stopped by the deadline inside a solve: the limit, not an undecided test */
  if (us_stability_info(ctx->stab)->timed_out > timed_out) return US_STEP_LIMIT;
  count_verdict(ctx);
  return ctx->res.verdict == US_STABLE;
}

int us_plan_test(us_SearchCtx *ctx, const us_Bitset *node, us_Error *err) {
  return test_node(ctx, node, err);
}

int us_plan_test_current(us_SearchCtx *ctx, us_Error *err) { return test_node(ctx, NULL, err); }
