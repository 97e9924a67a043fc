/* The greedy rule's rescue of a graph search (rules.c has the rule):
 * when a search has to backtrack (or its queue grows too wide), stop
 * guessing. The root is live (decided exactly by the driver), so the path
 * can always be finished from it; a binary search over the path's depths
 * with greedy-assembly checks (one-sided: a node the greedy rebuilds is
 * live, one it cannot is merely unknown) finds a deep node to finish from
 * in log2(depth) checks, and the greedy's order (or the root's exact
 * order) finishes the path. Every node of the finished path was tested
 * certified stable by the greedy or the exact decision.
 *
 * Invariant of the binary search: the node at depth lo is live (the root,
 * or one the greedy rebuilt), the one at hi is not known to be. */
#include "rescue.h"
#include "rules.h"

/* Rewind the path to depth d. */
void us_plan_rewind(us_SearchCtx *ctx, int d) {
  while (ctx->npath > d) us_plan_toggle(&ctx->cur, ctx->path[--ctx->npath]);
}

/* The node at depth d of the current path, into ctx->scratch. */
static void node_at(us_SearchCtx *ctx, int d) {
  us_bitset_copy(&ctx->scratch, &ctx->cur);
  for (int k = ctx->npath - 1; k >= d; k--) us_plan_toggle(&ctx->scratch, ctx->path[k]);
}

/* The moves from the root to the goal by the exact decision (the root is
 * live): its removal order, or reversed going up. */
static int root_moves(us_SearchCtx *ctx, int *seq, int *nseq, us_Error *err) {
  int r = us_plan_node_live(ctx, &ctx->part, seq, nseq, err);
  if (r == 1 && ctx->set->direction == US_DIR_UP)
    for (int i = 0, j = *nseq - 1; i < j; i++, j--) {
      int t = seq[i];
      seq[i] = seq[j];
      seq[j] = t;
    }
  return r;
}

int us_plan_rescue(us_SearchCtx *ctx, int top_dead, us_Error *err) {
  int lo = 0, hi = top_dead ? ctx->npath : ctx->npath + 1; /* lo passes, hi unknown */
  int *seq = us_malloc(((size_t)ctx->s->nbody + 1) * sizeof(int)), nseq = 0, r = 0;
  if (!seq) return us_error_set(err, US_ERR_NOMEM, "out of memory in the search"), US_STEP_ERROR;
  while (hi - lo > 1 && r >= 0) {
    int mid = lo + (hi - lo) / 2;
    node_at(ctx, mid);
    r = us_plan_node_greedy(ctx, &ctx->scratch, NULL, NULL, err);
    if (r == 1) lo = mid;
    if (r == 0) hi = mid;
  }
  node_at(ctx, lo);
  if (r >= 0 && lo > 0) r = us_plan_node_greedy(ctx, &ctx->scratch, seq, &nseq, err);
  /* a verdict that changed on the re-run (an undecided test): the root */
  if (r == 0 && lo > 0) lo = 0;
  if (r >= 0 && lo == 0) r = root_moves(ctx, seq, &nseq, err);
  if (r == 0) us_error_set(err, US_ERR_SOLVER, "live root check not reproducible"), r = US_STEP_ERROR;
  if (r == 1) {
    us_plan_rewind(ctx, lo);
    for (int k = 0; k < nseq; k++) {
      ctx->path[ctx->npath++] = seq[k];
      us_plan_toggle(&ctx->cur, seq[k]);
    }
    r = US_PLAN_FOUND;
  }
  us_free(seq);
  return r;
}
