/* A dense inverse updated by bordering (append) and Schur complement
 * (delete), O(k^2) each: the small border block of the LCP's clamped system
 * (lcp_factor.c) lives here.
 *
 * Why an inverse and not LDL^T: with friction at its bound the clamped
 * system is not symmetric (a bound row f_t - s mu f_n = 0 next to rows
 * a_i = 0), so a symmetric factorization does not apply; the bordered
 * inverse handles both cases with the same two updates, and its growth is
 * bounded because tiny pivots are refused.
 *
 * Append: K' = [K u; v^T alpha], y = H u, z = H^T v, sigma = alpha - v.y
 * (the Schur complement, the pivot). Then
 * H' = [H + y z^T / sigma, -y / sigma; -z^T / sigma, 1 / sigma].
 * Delete slot s: swap s with the last slot (a symmetric permutation of K,
 * hence of H), then the inverse of the leading block is
 * H_11 - H_1L H_L1 / H_LL (the Schur complement of the last pivot of H).
 * Invariant: H (k x k, leading dimension cap, row-major) is K^-1.
 */
#include "lcp_dense.h"

#include "core/core.h"

#include <math.h>
#include <string.h>

int us_dinv_reserve(us_DenseInv *d, int need) {
  if (need <= d->cap) return 0;
  int cap = US_MAX(US_MAX(need, 2 * d->cap), 8);
  double *H = us_malloc((size_t)cap * (size_t)cap * sizeof(double));
  double *y = us_realloc(d->y, (size_t)cap * sizeof(double));
  if (y) d->y = y;
  double *z = us_realloc(d->z, (size_t)cap * sizeof(double));
  if (z) d->z = z;
  int *nz = us_realloc(d->nz, (size_t)cap * sizeof(int));
  if (nz) d->nz = nz;
  if (!H || !y || !z || !nz) {
    us_free(H);
    return -1;
  }
  for (int i = 0; i < d->k; i++)
    memcpy(H + (size_t)i * (size_t)cap, d->H + (size_t)i * (size_t)d->cap,
           (size_t)d->k * sizeof(double));
  us_free(d->H);
  d->H = H;
  d->cap = cap;
  return 0;
}

void us_dinv_free(us_DenseInv *d) {
  us_free(d->H);
  us_free(d->y);
  us_free(d->z);
  us_free(d->nz);
  memset(d, 0, sizeof *d);
}

/* x = H r. r is often sparse: its non-zeros are gathered first, so the
 * cost is O(k nnz). x and r must not overlap. */
void us_dinv_mult(const us_DenseInv *d, const double *r, double *x) {
  int nnz = 0;
  for (int j = 0; j < d->k; j++)
    if (r[j] != 0.0) d->nz[nnz++] = j;
  for (int i = 0; i < d->k; i++) {
    const double *h = d->H + (size_t)i * (size_t)d->cap;
    double s = 0.0;
    for (int t = 0; t < nnz; t++) s += h[d->nz[t]] * r[d->nz[t]];
    x[i] = s;
  }
}

/* z = H^T v */
static void mult_t(const us_DenseInv *d, const double *v, double *z) {
  for (int j = 0; j < d->k; j++) z[j] = 0.0;
  for (int i = 0; i < d->k; i++) {
    const double *h = d->H + (size_t)i * (size_t)d->cap;
    double vi = v[i];
    if (vi == 0.0) continue;
    for (int j = 0; j < d->k; j++) z[j] += vi * h[j];
  }
}

int us_dinv_append(us_DenseInv *d, const double *u, const double *v, double alpha, double tol) {
  int k = d->k;
  if (us_dinv_reserve(d, k + 1)) return -1;
  us_dinv_mult(d, u, d->y);
  mult_t(d, v, d->z);
  double sigma = alpha;
  for (int i = 0; i < k; i++) sigma -= v[i] * d->y[i];
  if (!(fabs(sigma) > tol)) return 1;
  double is = 1.0 / sigma;
  size_t ld = (size_t)d->cap;
  for (int i = 0; i < k; i++) {
    double *h = d->H + (size_t)i * ld;
    double yi = d->y[i] * is;
    for (int j = 0; j < k; j++) h[j] += yi * d->z[j];
    h[k] = -yi;
  }
  double *hk = d->H + (size_t)k * ld;
  for (int j = 0; j < k; j++) hk[j] = -d->z[j] * is;
  hk[k] = is;
  d->k = k + 1;
  return 0;
}

/* Swap slots s and t (rows and columns of H). */
static void swap_slots(us_DenseInv *d, int s, int t) {
  if (s == t) return;
  size_t ld = (size_t)d->cap;
  double *hs = d->H + (size_t)s * ld, *ht = d->H + (size_t)t * ld;
  for (int j = 0; j < d->k; j++) {
    double x = hs[j];
    hs[j] = ht[j];
    ht[j] = x;
  }
  for (int i = 0; i < d->k; i++) {
    double *h = d->H + (size_t)i * ld;
    double x = h[s];
    h[s] = h[t];
    h[t] = x;
  }
}

int us_dinv_delete(us_DenseInv *d, int s, double tiny) {
  int L = d->k - 1;
  swap_slots(d, s, L);
  size_t ld = (size_t)d->cap;
  const double *hl = d->H + (size_t)L * ld;
  int bad = !(fabs(hl[L]) > tiny) || !isfinite(hl[L]);
  double ihll = bad ? 0.0 : 1.0 / hl[L];
  for (int i = 0; i < L; i++) {
    double *h = d->H + (size_t)i * ld;
    double c = h[L] * ihll;
    if (c == 0.0) continue;
    for (int j = 0; j < L; j++) h[j] -= c * hl[j];
  }
  d->k = L;
  return bad;
}
