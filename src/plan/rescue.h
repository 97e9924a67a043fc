/* The greedy rule's rescue of a graph search (rescue.c). */
#ifndef US_PLAN_RESCUE_H
#define US_PLAN_RESCUE_H

#include "search.h"

/* A deep node on the current path (ctx->path[0..npath), ending at
 * ctx->cur; the root is live) that greedy assembly rebuilds, by binary
 * search (top_dead: the last node is known dead and is not checked), then
 * its removal order to the goal (the root's exact order when no node below
 * it passes). US_PLAN_FOUND or < 0. */
int us_plan_rescue(us_SearchCtx *ctx, int top_dead, us_Error *err);
/* Rewind the path to depth d (ctx->cur follows). */
void us_plan_rewind(us_SearchCtx *ctx, int d);

#endif
