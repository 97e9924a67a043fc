/* A raw dense LCP a = A f + b behind the solver's us_LcpOps, shared by the
 * LCP tests (the source's worked example, siconos comparisons). Header-only
 * (static functions) so each test program stays self-contained. */
#ifndef US_TEST_LCP_DENSE_H
#define US_TEST_LCP_DENSE_H

#include "stability/lcp.h"

typedef struct Dense {
  int n;
  const double *A, *b; /* row-major n x n, n */
} Dense;

static inline double d_entry(void *ctx, int i, int j) {
  const Dense *d = ctx;
  return d->A[i * d->n + j];
}

static inline int d_apply(void *ctx, const int *idx, const double *x, int k, double *y, int *out) {
  const Dense *d = ctx;
  for (int i = 0; i < d->n; i++) {
    y[i] = 0.0;
    for (int j = 0; j < k; j++) y[i] += d->A[i * d->n + idx[j]] * x[j];
    out[i] = i;
  }
  return d->n;
}

static inline void d_full(void *ctx, const double *f, const unsigned char *live, double *a) {
  const Dense *d = ctx;
  for (int i = 0; i < d->n; i++) {
    if (!live[i]) continue;
    a[i] = d->b[i];
    for (int j = 0; j < d->n; j++) a[i] += d->A[i * d->n + j] * f[j];
  }
}

/* The ops of a dense problem (d must outlive them). */
static inline us_LcpOps dense_ops(Dense *d) {
  us_LcpOps ops = {d, d_entry, d_apply, d_full};
  return ops;
}

#endif
