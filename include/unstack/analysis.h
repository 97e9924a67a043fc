/* unstack analysis: counting sub-assemblies and classifying structures.
 * Part of the public API; included by unstack/unstack.h. */
#ifndef UNSTACK_ANALYSIS_H
#define UNSTACK_ANALYSIS_H

#include "unstack/unstack.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ count */
/* (src/plan/count.c) */

/* ------------------------------------------------------------- classify */
/* (src/plan/classify.c, src/plan/friction.c) */

#ifdef __cplusplus
}
#endif
#endif
