/* Depth-first search of the disassembly graph, iterative (no recursion, so
 * thousands of bodies need no deep C stack).
 *
 * Invariants: ctx->cur is the node at depth ctx->npath and every node on
 * the path from the root is stable; next[d] is the position in ctx->cand
 * of the next move to try at depth d. A node enters `dead` when it is
 * unstable or when every move from it was tried without reaching the goal,
 * so no node is tested twice and no dead end is expanded twice: every
 * skipped child counts as a revisit. */
#include "search.h"

/* The next legal move at the current depth whose child is not known dead;
 * -1 when exhausted. Advances *next. */
static int next_move(us_SearchCtx *ctx, int *next) {
  while (*next < ctx->nmov) {
    int b = ctx->cand[(*next)++];
    if (!us_plan_can_move(ctx, &ctx->cur, b)) continue;
    us_plan_toggle(&ctx->cur, b);
    int known = us_bitset_set_contains(&ctx->dead, &ctx->cur);
    us_plan_toggle(&ctx->cur, b);
    if (!known) return b;
    ctx->st->revisited++;
  }
  return -1;
}

/* Step back to the parent, marking the current node dead. */
static int backtrack(us_SearchCtx *ctx, us_Error *err) {
  if (us_bitset_set_add(&ctx->dead, &ctx->cur) < 0) {
    us_error_set(err, US_ERR_NOMEM, "out of memory in the search");
    return -1;
  }
  ctx->npath--;
  us_plan_toggle(&ctx->cur, ctx->path[ctx->npath]);
  return 0;
}

/* Try the child reached by moving b: 1 descended, 0 rejected, <0 stop. */
static int try_child(us_SearchCtx *ctx, int b, int *next, us_Error *err) {
  us_plan_toggle(&ctx->cur, b);
  int r = us_plan_is_goal(ctx, &ctx->cur) ? 1 : us_plan_test(ctx, &ctx->cur, err);
  if (r < 0) {
    us_plan_toggle(&ctx->cur, b);
    return r;
  }
  if (r == 0) {
    int add = us_bitset_set_add(&ctx->dead, &ctx->cur);
    us_plan_toggle(&ctx->cur, b);
    if (add < 0) return us_error_set(err, US_ERR_NOMEM, "out of memory in the search"), -1;
    return 0;
  }
  ctx->path[ctx->npath++] = b;
  next[ctx->npath] = 0;
  ctx->st->nodes_expanded++;
  if (ctx->npath > ctx->st->max_depth) ctx->st->max_depth = ctx->npath;
  return 1;
}

int us_plan_dfs(us_SearchCtx *ctx, us_Error *err) {
  int *next = us_calloc((size_t)ctx->nmov + 1, sizeof(int));
  if (!next) return us_error_set(err, US_ERR_NOMEM, "out of memory in the search"), -1;
  int status = US_PLAN_NONE;
  ctx->npath = 0;
  for (;;) {
    if (us_plan_is_goal(ctx, &ctx->cur)) {
      status = US_PLAN_FOUND;
      break;
    }
    int b = next_move(ctx, &next[ctx->npath]);
    if (b < 0) {
      if (ctx->npath == 0) break; /* the root is a dead end: none */
      if (backtrack(ctx, err)) {
        status = -1;
        break;
      }
      continue;
    }
    int r = try_child(ctx, b, next, err);
    if (r == -2) status = US_PLAN_LIMIT;
    if (r < 0) {
      if (r == -1) status = -1;
      break;
    }
  }
  us_free(next);
  return status;
}
