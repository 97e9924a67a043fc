/* The lp-lcp stability backend's private constructor (lp_lcp.c), for
 * tests and benchmarks that compare warm and cold starts or move the size
 * cap: a workspace of us_backend_lp_lcp with the given options. Use it as
 * the create function of a us_Backend that borrows the other functions
 * from us_backend_lp_lcp. */
#ifndef US_STABILITY_LP_LCP_H
#define US_STABILITY_LP_LCP_H

#include "backend.h"

/* Systems whose LCP has more than this many complementary pairs
 * (generator columns + rows + 1) go to CLP: the dense tableau is
 * dim x (dim + 1) doubles and a pivot touches all of it. */
#define US_LP_LCP_MAX_DIM 900

typedef struct us_LpLcpOptions {
  int reuse;   /* 1: start from the previous sub-assembly's basis */
  int max_dim; /* the size cap; <= 0: US_LP_LCP_MAX_DIM */
} us_LpLcpOptions;

void *us_lp_lcp_create(const us_Structure *s, const us_StabilitySettings *set,
                       const us_LpLcpOptions *opt, us_Error *err);

#endif
