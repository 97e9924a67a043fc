/* The 2D statics LP in cone-edge form, shared by the LP backends
 * (lp_clp.c, lp_lpsolve.c); built by equilibrium.c from an us_EqSystem.
 *
 * G l = rhs, l >= 0, equality rows only (rows as in us_EqSystem). Each
 * active contact contributes unit-length generator columns of its cone:
 *   mu = 0:           n                     (col_sign 0)
 *   0 < mu <= n_mu:   e+, e-                (col_sign +1, -1)
 *   n_mu < mu:        n, e+, e-
 * with e+- = cos(a) n +- sin(a) t, a = atan(mu) (so mu = INFINITY gives
 * e+- = +-t: the half-space f_n >= 0). The edges have unit length
 * whatever mu, so no column entry grows with mu; the extra column n of a
 * wide cone (settings n_column_mu) lets the LP carry a normal force
 * without two nearly opposite edges cancelling each other.
 */
#ifndef US_STABILITY_LP_GEN_H
#define US_STABILITY_LP_GEN_H

#include "equilibrium.h"

typedef struct us_EqGen {
  int nrow, ncol;
  int *start;              /* [ncol + 1] */
  int *row;                /* [start[ncol]] */
  double *val;
  int *col_contact;        /* [ncol] active-contact index */
  signed char *col_sign;   /* [ncol] +1 (e+), -1 (e-) or 0 (n) */
  int cap_col, cap_nnz;
} us_EqGen;

/* 0, -1 on OOM, -2 if dim != 2. Reuses g's arrays (zero-init is valid).
 * n_column_mu: contacts with mu above it also get the column n. */
int us_eq_generators(const us_EqSystem *e, double n_column_mu, us_EqGen *g);
void us_eq_gen_free(us_EqGen *g);
/* Key of column j among the (at most 3) columns of its contact: 0, 1, 2. */
int us_eq_gen_slot(const us_EqGen *g, int j);
/* Edge multipliers l (ncol) to components f (2 * ncontact); l < 0 -> 0. */
void us_eq_gen_forces(const us_EqSystem *e, const us_EqGen *g, const double *l, double *f);
/* y (nrow, either sign) a Farkas ray of G l = rhs, l >= 0, with slack
 * `slack` relative to |rhs . y|? Then the body with the largest virtual
 * motion in y, else -1. */
int us_eq_gen_farkas_body(const us_EqSystem *e, const us_EqGen *g, const double *y,
                          double slack);

/* The LP settings with every field <= 0 replaced by its default
 * (us_lp_default_settings, stability.c). */
us_LpSettings us_lp_settings_resolve(const us_LpSettings *in);

/* No column at all (no active contact can carry load): the bodies stand
 * only if nothing pushes them, i.e. rhs = 0. */
us_Verdict us_eq_no_columns_verdict(const us_EqSystem *e);

#endif
