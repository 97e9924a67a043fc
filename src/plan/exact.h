/* Exact buildability with a memo over connected sets (exact.c). */
#ifndef US_PLAN_EXACT_H
#define US_PLAN_EXACT_H

#include "search.h"

/* Steps of at most K bodies. us_exact_solve: 1 when `set` can be emptied
 * through certified-stable sets (its removal order, with step ends marked,
 * in order/step_end when not NULL: capacity nbody), 0 when not known (a
 * proof when no test was undecided, see search.c), or a us_Step. */
typedef struct us_Exact us_Exact;
us_Exact *us_exact_new(int nbody, int K);
void us_exact_free(us_Exact *e);
size_t us_exact_bytes(const us_Exact *e);
int us_exact_solve(us_SearchCtx *ctx, us_Exact *e, const us_Bitset *set, int *order,
                   unsigned char *step_end, int *n, us_Error *err);

#endif
