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

/* Region LPs never come here: they go to the sparse simplex (lp_sparse.h)
 * whatever their size. Until 2026-12-06 regions of up to 90 rows came
 * here first; once the sparse simplex started from the base forces with
 * superbasic columns (a few pivots per solve), the dense tableau's m
 * pivots cost more: instructions of `unstack plan` -27 % on a 632-block
 * stack, -14 % on 1,076, -32 % on 4,336, and -17 % on a batch of 400
 * small random stacks. Whole systems of up to 90 rows still come here. */

extern const us_Backend us_backend_small;

#endif
