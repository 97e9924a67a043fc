/* The operator interface of the LCP solver: the solver, its factorization
 * and the operators (lcp_sys.c for a structure, tests' dense matrices)
 * meet here. A is reached only through these callbacks (an entry on
 * demand, a sparse product, a full recomputation of a = A f + b), so an
 * operator can keep A implicit. */
#ifndef US_LCP_OPS_H
#define US_LCP_OPS_H

typedef struct us_LcpOps {
  void *ctx;
  /* A_ij */
  double (*entry)(void *ctx, int i, int j);
  /* y = A x for x non-zero only at idx[0..k) (values x[0..k)): writes y[i]
   * for every index i it lists in out[] (returns the count; out holds n).
   * Unlisted indices have y_i = 0. May list non-live indices. */
  int (*apply)(void *ctx, const int *idx, const double *x, int k, double *y, int *out);
  /* a = A f + b for every index with live[i] != 0 (others untouched). */
  void (*full)(void *ctx, const double *f, const unsigned char *live, double *a);
} us_LcpOps;

#endif
