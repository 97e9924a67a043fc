/* Private interface of the planner: the search context shared by the
 * driver (plan.c), the two graph searches (dfs.c, bfs.c) and the candidate
 * ordering (order.c). */
#ifndef US_SEARCH_H
#define US_SEARCH_H

#include "core/core.h"

/* A node of the disassembly graph is the set of movable bodies present
 * (bits over body indices; fixed bodies' bits stay clear). A move toggles
 * one body: direction down removes a present body, up adds an absent one.
 * The root is the full set (down) or the empty set (up); the goal the
 * other one. Both are stable by the time the search starts: the full set
 * is tested by the driver, the empty set stands trivially. */
typedef struct us_SearchCtx {
  const us_Structure *s;
  const us_PlanSettings *set;
  us_Stability *stab;
  us_StabilityResult res;
  int nmov;             /* movable bodies */
  int *cand;            /* [nmov] bodies in the order moves are tried */
  us_Bitset full;       /* all movable bodies */
  us_Bitset cur;        /* the node being expanded */
  us_BitsetSet dead;    /* nodes known not to lead to the goal */
  int *path;            /* [nmov] moves from the root to cur */
  int npath;
  us_PlanStats *st;
  double t_start;
  int limit;            /* a limit was hit */
} us_SearchCtx;

/* order.c: fill ctx->cand according to set->order and direction. */
int us_plan_order_candidates(us_SearchCtx *ctx);

/* plan.c: test the node `node`; 1 stable, 0 not, -1 error, -2 limit. */
int us_plan_test(us_SearchCtx *ctx, const us_Bitset *node, us_Error *err);
/* 1 when `node` is the goal of the search direction. */
int us_plan_is_goal(const us_SearchCtx *ctx, const us_Bitset *node);
/* 1 when moving body b is a legal move from `node`. */
int us_plan_can_move(const us_SearchCtx *ctx, const us_Bitset *node, int b);
static inline void us_plan_toggle(us_Bitset *node, int b) { node->w[b >> 6] ^= (uint64_t)1 << (b & 63); }

/* dfs.c / bfs.c: search from ctx->cur (the root). On success fill
 * ctx->path / npath with the moves and return US_PLAN_FOUND; otherwise
 * US_PLAN_NONE or US_PLAN_LIMIT. Errors: return -1 with err set. */
int us_plan_dfs(us_SearchCtx *ctx, us_Error *err);
int us_plan_bfs(us_SearchCtx *ctx, us_Error *err);

#endif
