/* The hands fields of plan files: "hands", "hands_lower", "actions"
 * (plan_actions.c; docs/format.md). */
#ifndef US_IO_PLAN_ACTIONS_H
#define US_IO_PLAN_ACTIONS_H

#include "io.h"

/* Write `"hands": H, "hands_lower": L, "actions": [...]` lines (each
 * ending ",\n") when p has actions; nothing otherwise. */
void us_plan_write_actions(us_JsonOut *o, const us_Structure *s, const us_Plan *p);
/* Read them from root into out (absent: hands 0, no actions). Every id
 * must name a movable body and every verb be place, grab or release
 * (else US_ERR_INPUT naming actions[k]); the sequence itself is checked
 * by us_verify_actions. */
us_Status us_plan_read_actions(const us_IoCtx *c, const us_Structure *s, json_t *root,
                               us_PlanFile *out);

#endif
