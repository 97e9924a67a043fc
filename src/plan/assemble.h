/* Greedy assembly from the ground (assemble.c). */
#ifndef US_PLAN_ASSEMBLE_H
#define US_PLAN_ASSEMBLE_H

#include "search.h"

/* Builds from the empty set inside `within` (movable bodies), adding any
 * body or group of at most max_group (>= 1) bodies that keeps the set
 * standing (certified stable), lowest first. Fills the placement sequence
 * and its steps. Returns 1 when all of `within` was built, 0 when stuck
 * (built = a maximal buildable sub-assembly reached greedily; being stuck
 * proves nothing by itself, see exact.c), or a us_Step (error: err set). */
typedef struct us_Assembly {
  us_Bitset built;
  int *seq, nseq;       /* bodies in placement order */
  int *gstart, ngroups; /* [ngroups + 1] step offsets into seq */
  int max_group;        /* largest step used, or the bound when stuck */
} us_Assembly;
int us_assemble(us_SearchCtx *ctx, const us_Bitset *within, int max_group, us_Assembly *out,
                us_Error *err);
/* The same from a standing set `start` ⊆ within already in place (its
 * bodies are not in the sequence). */
int us_assemble_from(us_SearchCtx *ctx, const us_Bitset *within, const us_Bitset *start,
                     int max_group, us_Assembly *out, us_Error *err);
void us_assembly_free(us_Assembly *a);

#endif
