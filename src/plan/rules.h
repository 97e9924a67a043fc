/* The culling rules of the graph searches (rules.c). */
#ifndef US_PLAN_RULES_H
#define US_PLAN_RULES_H

#include "search.h"

/* The node test of the graph searches, with the ground and union rules
 * when enabled; the return values of us_plan_test. */
int us_plan_node_test(us_SearchCtx *ctx, const us_Bitset *node, us_Error *err);
/* Greedy rule: 1 when `node` (down: the bodies left) can be emptied one
 * body at a time (exact, exact.c), 0 when not known, < 0 as above. When
 * live and seq is not NULL, seq[0..*nseq) is a removal order of it. */
int us_plan_node_live(us_SearchCtx *ctx, const us_Bitset *node, int *seq, int *nseq,
                      us_Error *err);
/* The one-sided check: 1 when greedy assembly finishes from `node` (down:
 * rebuilds it from the ground; up: completes the part from it), and then
 * seq, if not NULL, holds the moves that take `node` to the goal; 0 when
 * it is stuck (which proves nothing), < 0 as above. */
int us_plan_node_greedy(us_SearchCtx *ctx, const us_Bitset *node, int *seq, int *nseq,
                        us_Error *err);

#endif
