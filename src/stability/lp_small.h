/* The dense simplex for tiny statics LPs (lp_small.c), used by the local
 * tests below CLP's fixed cost per solve. */
#ifndef US_STABILITY_LP_SMALL_H
#define US_STABILITY_LP_SMALL_H

#include "backend.h"

/* Systems of at most this many rows (3 per body) go to the small solver
 * first: measured faster than CLP up to here on the local tests of walls
 * and pyramids. */
#define US_SMALL_ROWS 60

extern const us_Backend us_backend_small;

#endif
