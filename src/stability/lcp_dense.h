/* A dense inverse H = K^-1 (k x k, leading dimension cap), updated by
 * bordering (append) and Schur complement (delete), O(k^2) each
 * (lcp_dense.c): the inverse of the border's Schur complement in the LCP's
 * factorization (lcp_factor.c). */
#ifndef US_LCP_DENSE_H
#define US_LCP_DENSE_H

typedef struct us_DenseInv {
  int k, cap;
  double *H;
  double *y, *z; /* [cap] scratch of this file */
  int *nz;       /* [cap] scratch of this file */
} us_DenseInv;

/* Room for `need` rows. 0 or -1. */
int us_dinv_reserve(us_DenseInv *d, int need);
void us_dinv_free(us_DenseInv *d);
/* Border K with column u, row v, corner alpha. 0, 1 if the pivot is tiny
 * (|sigma| <= tol: nothing changes), -1 OOM. */
int us_dinv_append(us_DenseInv *d, const double *u, const double *v, double alpha, double tol);
/* Delete row and column s (the last one moves into s). 1 if the rest
 * looks singular (the deleted pivot of H at or below `tiny`, or not
 * finite), else 0. */
int us_dinv_delete(us_DenseInv *d, int s, double tiny);
/* x = H r (x and r distinct). */
void us_dinv_mult(const us_DenseInv *d, const double *r, double *x);

#endif
