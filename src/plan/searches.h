/* The graph searches (dfs.c, bfs.c). */
#ifndef US_PLAN_SEARCHES_H
#define US_PLAN_SEARCHES_H

#include "search.h"

/* Search from ctx->cur (the root). On success fill ctx->path / npath with
 * the moves and return US_PLAN_FOUND; otherwise US_PLAN_NONE (no path
 * through certified-stable nodes), US_PLAN_LIMIT (bfs) or a us_Step
 * (US_STEP_LIMIT, US_STEP_ERROR with err set). */
int us_plan_dfs(us_SearchCtx *ctx, us_Error *err);
int us_plan_random(us_SearchCtx *ctx, us_Error *err);
int us_plan_bfs(us_SearchCtx *ctx, us_Error *err);

#endif
