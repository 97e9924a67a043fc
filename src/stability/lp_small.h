/* The dense simplex for tiny statics LPs (lp_small.c), used by the local
 * tests below CLP's fixed cost per solve. */
#ifndef US_STABILITY_LP_SMALL_H
#define US_STABILITY_LP_SMALL_H

#include "backend.h"

/* Systems of at most this many rows (3 per body) go to the small solver
 * first. Measured per solve on the local tests of random stacks of 58 to
 * 134 blocks (2026-11-27): the small solver 0.23 ms at 60-75 rows, 0.7 ms
 * at 90, 1.2 ms at 120; CLP 0.5-0.9 ms from 45 to 150 rows. At 60 rows
 * (before) a batch of 400 random stacks of the default size loaded CLP for
 * a third of them; at 90 the 400 take 22 % less CPU, and 43 stacks of 58
 * to 134 blocks 2 % less (at 120: 6 % more, at 105 3 % more). */
#define US_SMALL_ROWS 90
/* Does system e go to the small solver first? 2D only: a 3D region's
 * tableau is as wide as its cone generators (8 and more per contact, ~250
 * contacts for 10 bodies of pyramid3d), and pivoting through it densely
 * cost 10 to 30 times CLP's time (pyramid3d, 385 boxes: plan 3.0 s with
 * it for up to 96 contacts, 0.33 s without). */
static inline int us_small_fits(const us_EqSystem *e) {
  return e->dim == 2 && e->nbody * e->nw <= US_SMALL_ROWS;
}

/* A local test's region LP (local.c) goes to the small solver up to this
 * many rows, more than a whole small system: CLP runs a region warm from
 * the latest statuses, and costs 1-2.5 ms a solve nearly whatever the size
 * from 90 to 360 rows (its model, factorizations and steepest-edge
 * weights), while the dense tableau grows with the size. Timed on the same
 * region LPs (2026-12-02; small / CLP, ms per solve), the 876-block stack
 * (`generate stacker --rows 100 --width 60 --seed 3`): 90-119 rows 0.47 /
 * 1.92, 120-149 0.88 / 1.56, 150-179 1.63 / 1.89, 180-209 2.40 / 2.01;
 * the 632-block one (`--rows 60 --width 60 --seed 1`): 0.41 / 1.06, 0.89 /
 * 1.36, 1.43 / 1.79, 1.95 / 2.42. Plans (user CPU, same orders) at 90 /
 * 165: 876 blocks 1.05-1.11 / 0.82-0.90 s, 5,796 blocks 12.3-12.4 /
 * 10.4-10.6 s, 9,352 blocks 7.9-8.1 / 7.4-7.7 s; batches of small stacks
 * unchanged (their regions are smaller). */
#define US_SMALL_REGION_ROWS 165
static inline int us_small_fits_region(const us_EqSystem *e) {
  return e->dim == 2 && e->nbody * e->nw <= US_SMALL_REGION_ROWS;
}

extern const us_Backend us_backend_small;

#endif
