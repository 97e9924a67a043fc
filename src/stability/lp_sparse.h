/* A sparse revised simplex for the local tests' region LPs (lp_sparse.c).
 *
 * Why: a region LP has a few hundred rows, and each of its columns (a
 * cone generator) touches two bodies: six nonzeros. CLP spends most of a
 * region solve on its set-up (a fresh model, scaling, a first
 * factorization: 0.5 ms even for a solve of a few iterations), and the
 * dense tableau of lp_small.c pivots m times at O(m n) each. This solver
 * factorizes only its basis (sparse LU, no fill on a stack's load paths),
 * starts from the basis the same workspace ended with (keyed by contact
 * and cone slot, as CLP's statuses are), and prices in O(nonzeros).
 *
 * Like lp_small.c it never has the last word: a feasible answer's
 * residual is measured from the sparse columns, and the caller re-checks
 * the forces with the certificate check; an infeasible one returns a
 * Farkas ray that us_eq_gen_farkas_body and then the mechanism check
 * verify. Anything it cannot settle cleanly (iteration limit, a singular
 * basis it cannot repair, a ray that fails) comes back US_UNDECIDED and
 * the caller asks the next solver. */
#ifndef US_STABILITY_LP_SPARSE_H
#define US_STABILITY_LP_SPARSE_H

#include "backend.h"

/* Systems up to this many rows go to the sparse solver first: the local
 * tests' regions (at most 1,500 rows, unless a closed one is larger) and
 * their hand-backs' full systems (stability.c). Its LU of a stack's basis
 * has about 3.4 m entries in L and 3 m in U; a 1,539-row closed region
 * took it 20 M instructions where CLP took 750 M. */
#define US_SPARSE_ROWS 6000

static inline int us_sparse_fits_region(const us_EqSystem *e) {
  return e->dim == 2 && e->nbody * e->nw <= US_SPARSE_ROWS;
}

extern const us_Backend us_backend_sparse;

#endif
