/* Principal pivoting for the 3D cone LCP (lcp3_piv.c): the LCP
 *   a = A l + b >= 0,  l >= 0,  l . a = 0,  A = G^T M^-1 G (PSD)
 * of an us_Lcp whose live indices are all normals (cone generators), as
 * the active-set method of Lawson and Hanson: a passive set P of indices
 * with a_P = 0 whose Gram block A_PP is kept factorized (dense Cholesky,
 * updated one index at a time), so that a later run starts from the
 * previous sub-assembly's P and factor (computation reuse). */
#ifndef US_STABILITY_LCP3_PIV_H
#define US_STABILITY_LCP3_PIV_H

#include "lcp.h"

typedef struct us_Lcp3Piv {
  int k, cap;          /* members of P, room in R */
  int *mem;            /* [cap] LCP index of each member, in factor order */
  int *pos;            /* [n] position in P, or -1 */
  double *R;           /* [cap * cap] upper triangular, column j at R + j cap:
                          R^T R = A_PP */
  double *t1, *t2;     /* [cap] scratch */
  unsigned char *skip; /* [n] refused in this sweep (dependent on P) */
  int *live, nlive;    /* [n] the live indices of the current run */
  long pivots;         /* additions and removals, total */
  long refused;        /* additions refused as dependent (round-off), total */
} us_Lcp3Piv;

int us_lcp3_piv_init(us_Lcp3Piv *q, int n);
void us_lcp3_piv_free(us_Lcp3Piv *q);
/* Empty P (the LCP's forces are the caller's). */
void us_lcp3_piv_reset(us_Lcp3Piv *q, int n);
/* Indices idx[0..k) leave P and the LCP: f = 0, not live. Their columns
 * must not have changed since they joined. */
void us_lcp3_piv_drop(us_Lcp3Piv *q, us_Lcp *p, const int *idx, int k);
/* Solve from the current P and forces (l >= 0, zero off P): SOLVED, LIMIT
 * (more than `limit` pivots, or p->set.deadline passed) or NOMEM. */
us_LcpResult us_lcp3_piv_run(us_Lcp3Piv *q, us_Lcp *p, long limit);

#endif
