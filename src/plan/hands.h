/* Plans with hands: assembly actions with up to H bodies held (hands.c). */
#ifndef US_PLAN_HANDS_H
#define US_PLAN_HANDS_H

#include "core/core.h"

/* The planner for set->hands != 1 (us_plan calls it): status found with
 * out->actions and out->order (the reverse of the placements), none (no
 * plan with set->hands hands: proven), limit or undecided, unstable.
 * set->hands 0: the smallest H, out->hands_lower saying what is proven;
 * `one` is today's plan for H = 1 (us_plan's answer, which plan.c makes
 * first, so that this file never calls back into plan.c), NULL otherwise. */
us_Status us_plan_hands(const us_Structure *s, const us_PlanSettings *set, const us_Plan *one,
                        us_Plan *out, us_Error *err);

/* The same for hands 0 (auto) when the caller has proven that no
 * one-at-a-time order exists (classify's sequence class): H = 1 is not
 * searched again. Out as us_plan's (memset by the caller's us_plan is not
 * done here: out must be zeroed). */
us_Status us_plan_hands_after_none(const us_Structure *s, const us_PlanSettings *set,
                                   us_Plan *out, us_Error *err);

/* Tests: set->hands (1 to 64) decided by the exact search alone (no
 * constructive plan first, H = 1 not handed to today's planner). */
us_Status us_plan_hands_exact(const us_Structure *s, const us_PlanSettings *set, us_Plan *out,
                              us_Error *err);

/* A shallow copy of s whose bodies in F are fixed (held): the same
 * geometry, contacts and ids; *bodies is its own body array (us_free it;
 * the copy is valid while s is). 0, or -1 on OOM. */
int us_hands_fixed_copy(const us_Structure *s, const us_Bitset *F, us_Structure *copy,
                        us_Body **bodies);

#endif
