/* The LCP stability backends' private constructor (lcp_backend.c), for
 * tests and benchmarks that vary the solver's settings: a workspace of
 * us_backend_lcp (reuse 0) or us_backend_lcp_reuse (reuse 1) whose solver
 * runs with `lcp` (NULL: us_lcp_default_settings(); settings->max_pivots,
 * when > 0, still overrides lcp->max_pivots). Use it as the create
 * function of a us_Backend that borrows the other functions from
 * us_backend_lcp. */
#ifndef US_LCP_BACKEND_H
#define US_LCP_BACKEND_H

#include "lcp.h"

void *us_lcp_backend_create(const us_Structure *s, const us_StabilitySettings *set,
                            const us_LcpSettings *lcp, int reuse, us_Error *err);

#endif
