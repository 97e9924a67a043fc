/* lp_solve's view of the strong-stability model (strong_lp.c). */
#ifndef US_ANALYSIS_STRONG_LP_H
#define US_ANALYSIS_STRONG_LP_H

#include "strong.h"

#include <lp_lib.h>

/* The model's rows and objective (maximised) as a new lprec, variables at
 * lp_solve's default bounds; NULL on OOM. lp_solve may rewrite the arrays
 * it is given, so it gets copies. */
lprec *us_strong_lp_new(const us_StrongModel *m);

#endif
