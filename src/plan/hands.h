/* Plans with hands: assembly actions with up to H bodies held (hands.c). */
#ifndef US_PLAN_HANDS_H
#define US_PLAN_HANDS_H

#include "core/core.h"

/* The planner for set->hands != 1 (us_plan calls it): status found with
 * out->actions and out->order (the reverse of the placements), none (no
 * plan with set->hands hands: proven), limit or undecided, unstable.
 * set->hands 0: the smallest H, out->hands_lower saying what is proven. */
us_Status us_plan_hands(const us_Structure *s, const us_PlanSettings *set, us_Plan *out,
                        us_Error *err);

#endif
