/* Depth-first search of the disassembly graph, iterative (no recursion, so
 * thousands of bodies need no deep C stack), and its randomized variant
 * with restarts.
 *
 * Invariants: ctx->cur is the node at depth ctx->npath and every node on
 * the path from the root is stable; next[d] is the position in ctx->cand
 * of the next move to try at depth d. A node enters `dead` when it is
 * unstable, or when every
 * move from it was tried without reaching the goal; so no node is tested
 * twice and no dead end is expanded twice: every skipped child counts as a
 * revisit. With the memo rule off nothing enters `dead` (the plain search
 * of the source, exponential on dead sub-graphs).
 *
 * Greedy rule: at the first backtrack the search stops guessing and
 * finishes through the rescue (rescue.c): a deep node of its path that
 * greedy assembly rebuilds, or the root's exact order.
 *
 * Undecided tests: a child whose test was undecided is not known stable,
 * so it is rejected like an unstable one (and marked dead); the driver
 * turns a `none` into `undecided` when any test was undecided.
 *
 * Random search (the source's suggestion): the candidate order is shuffled
 * at every restart, and a run is cut after a budget of tests that follows
 * the Luby sequence (1, 1, 2, 1, 1, 2, 4, ...) times the part's size. The
 * dead memo is kept across restarts (deadness does not depend on the
 * order), so the search stays complete: its runs grow without bound.
 * With the greedy rule a run whose budget is used up is not restarted but
 * rescued like a backtrack. */
#include "rescue.h"
#include "rules.h"
#include "searches.h"

#include <string.h>

static int memo_on(const us_SearchCtx *ctx) { return (ctx->set->rules & US_RULE_MEMO) != 0; }

static int known_dead(us_SearchCtx *ctx, const us_Bitset *node) {
  return memo_on(ctx) && us_bitset_set_contains(&ctx->dead, node);
}

static int mark_dead(us_SearchCtx *ctx, const us_Bitset *node, us_Error *err) {
  if (memo_on(ctx) && us_bitset_set_add(&ctx->dead, node) < 0)
    return us_error_set(err, US_ERR_NOMEM, "out of memory in the search"), -1;
  return 0;
}

/* The next legal move at the current depth whose child is not known dead;
 * -1 when exhausted. Advances *next. */
static int next_move(us_SearchCtx *ctx, int *next) {
  while (*next < ctx->ncand) {
    int b = ctx->cand[(*next)++];
    if (!us_plan_can_move(ctx, &ctx->cur, b)) continue;
    us_plan_toggle(&ctx->cur, b);
    int known = known_dead(ctx, &ctx->cur);
    us_plan_toggle(&ctx->cur, b);
    if (!known) return b;
    ctx->st->revisited++;
  }
  return -1;
}

/* Step back to the parent, marking the current node dead. */
static int backtrack(us_SearchCtx *ctx, us_Error *err) {
  if (mark_dead(ctx, &ctx->cur, err)) return -1;
  ctx->st->backtracks++;
  ctx->npath--;
  us_plan_toggle(&ctx->cur, ctx->path[ctx->npath]);
  return 0;
}

static int greedy_applies(const us_SearchCtx *ctx) {
  return (ctx->set->rules & US_RULE_GREEDY) && !ctx->kin && ctx->root_live;
}

/* Stable: 1; unstable: 0; < 0 stop. */
static int child_verdict(us_SearchCtx *ctx, us_Error *err) {
  if (us_plan_is_goal(ctx, &ctx->cur)) return 1;
  return us_plan_node_test(ctx, &ctx->cur, err);
}

/* Try the child reached by moving b: 1 descended, 0 rejected, <0 stop. */
static int try_child(us_SearchCtx *ctx, int b, int *next, us_Error *err) {
  us_plan_toggle(&ctx->cur, b);
  int r = child_verdict(ctx, err);
  if (r < 0) {
    us_plan_toggle(&ctx->cur, b);
    return r;
  }
  if (r == 0) {
    int bad = mark_dead(ctx, &ctx->cur, err);
    us_plan_toggle(&ctx->cur, b);
    return bad ? US_STEP_ERROR : 0;
  }
  ctx->path[ctx->npath++] = b;
  next[ctx->npath] = 0;
  ctx->st->nodes_expanded++;
  if (ctx->npath > ctx->st->max_depth) ctx->st->max_depth = ctx->npath;
  return 1;
}

/* One depth-first run from ctx->cur: FOUND, NONE, or a us_Step (restart:
 * the budget of this run is used up). */
static int dfs_run(us_SearchCtx *ctx, int *next, us_Error *err) {
  ctx->npath = 0;
  next[0] = 0;
  for (;;) {
    if (us_plan_is_goal(ctx, &ctx->cur)) return US_PLAN_FOUND;
    int b = next_move(ctx, &next[ctx->npath]);
    if (b < 0) {
      if (ctx->npath == 0) return US_PLAN_NONE; /* the root is a dead end */
      if (greedy_applies(ctx)) return us_plan_rescue(ctx, 1, err);
      if (backtrack(ctx, err)) return US_STEP_ERROR;
      continue;
    }
    int r = try_child(ctx, b, next, err);
    if (r == US_STEP_RESTART && greedy_applies(ctx)) {
      ctx->budget_end = 0; /* the rescue needs no restart */
      return us_plan_rescue(ctx, 1, err);
    }
    if (r < 0) return r;
  }
}

int us_plan_dfs(us_SearchCtx *ctx, us_Error *err) {
  int *next = us_calloc((size_t)ctx->nmov + 2, sizeof(int));
  if (!next) return us_error_set(err, US_ERR_NOMEM, "out of memory in the search"), US_STEP_ERROR;
  int r = dfs_run(ctx, next, err);
  us_free(next);
  return r == US_STEP_RESTART ? US_STEP_ERROR : r; /* no budget set: never */
}

/* ------------------------------------------------------------- random */

/* Luby's sequence: 1 1 2 1 1 2 4 1 1 2 1 1 2 4 8 ... (i >= 1). */
static long luby(long i) {
  for (;;) {
    long k = 1;
    while ((1L << k) - 1 < i) k++;
    if ((1L << k) - 1 == i) return 1L << (k - 1);
    i -= (1L << (k - 1)) - 1;
  }
}

static void shuffle(us_SearchCtx *ctx) {
  for (int i = ctx->ncand - 1; i > 0; i--) {
    int j = (int)us_rng_below(&ctx->rng, i + 1);
    int t = ctx->cand[i];
    ctx->cand[i] = ctx->cand[j];
    ctx->cand[j] = t;
  }
}

int us_plan_random(us_SearchCtx *ctx, us_Error *err) {
  int *next = us_calloc((size_t)ctx->nmov + 2, sizeof(int));
  if (!next) return us_error_set(err, US_ERR_NOMEM, "out of memory in the search"), US_STEP_ERROR;
  long unit = ctx->ncand > 16 ? ctx->ncand : 16;
  int r = US_STEP_RESTART;
  for (long i = 1; r == US_STEP_RESTART; i++) {
    shuffle(ctx);
    ctx->budget_end = ctx->st->tests + luby(i) * unit;
    r = dfs_run(ctx, next, err);
    if (r == US_STEP_RESTART) {
      us_plan_rewind(ctx, 0);
      ctx->st->restarts++;
    }
  }
  ctx->budget_end = 0;
  us_free(next);
  return r;
}
