/* A stable answer of an LP backend checked against its own statics
 * system, shared by the backends' differential tests: the forces f (dim
 * components per system contact, normal first) balance every row,
 * |A f - rhs| <= 1e-7, with no pulling contact. Header-only (static
 * inline), as tests/scenes.h. */
#ifndef US_TEST_EQCHECK_H
#define US_TEST_EQCHECK_H

#include <math.h>
#include <stdlib.h>

#include "stability/equilibrium.h"
#include "test.h"

static inline void eqcheck_forces(const us_EqSystem *eq, const double *f) {
  double *y = calloc((size_t)(eq->nbody * eq->nw) + 1, sizeof *y);
  CHECK(y);
  if (!y) return;
  us_eq_mult(eq, f, y);
  double worst = 0.0, least = INFINITY;
  for (int r = 0; r < eq->nbody * eq->nw; r++) worst = fmax(worst, fabs(y[r] - eq->rhs[r]));
  for (int c = 0; c < eq->ncontact; c++) least = fmin(least, f[c * eq->dim]);
  CHECK(worst <= 1e-7);
  CHECK(eq->ncontact == 0 || least >= -1e-9);
  free(y);
}

#endif
