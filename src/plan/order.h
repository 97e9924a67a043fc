/* Candidate ordering of the graph searches (order.c). */
#ifndef US_PLAN_ORDER_H
#define US_PLAN_ORDER_H

#include "search.h"

/* Fill ctx->cand with the bodies of ctx->part according to set->order and
 * direction; 0, or -1 on OOM. */
int us_plan_order_candidates(us_SearchCtx *ctx);
/* Sort bodies[0..n) highest first (top of the geometry, then the centre,
 * then the index); 0, or -1 on OOM. */
int us_plan_sort_highest(const us_Structure *s, int *bodies, int n);

#endif
