/* The factorized clamped system of the LCP solver: a dense inverse H of the
 * system matrix K over the members, updated in O(k^2) when one member joins
 * or leaves, never recomputed from scratch.
 *
 * Why an inverse and not LDL^T: with friction at its bound the system is
 * not symmetric (a bound row f_t - s mu f_n = 0 next to rows a_i = 0), so a
 * symmetric factorization does not apply; the bordered inverse handles both
 * cases with the same two updates and its growth is bounded because tiny
 * pivots are refused (redundant contacts are deferred by the caller).
 *
 * Append (bordering): K' = [K u; v^T alpha], y = H u, z = H^T v,
 * sigma = alpha - v.y (the Schur complement, the pivot). Then
 * H' = [H + y z^T / sigma, -y / sigma; -z^T / sigma, 1 / sigma].
 * Delete slot s: swap s with the last slot (a symmetric permutation of K,
 * hence of H), then the inverse of the leading block is
 * H_11 - H_1L H_L1 / H_LL (the Schur complement of the last pivot of H).
 * Invariant: H (k x k, leading dimension cap, row-major) is K^-1 for the
 * members mem[0..k) in slot order; pos[] maps an index to its slot.
 */
#include "lcp.h"

#include <math.h>
#include <string.h>

/* Grow H and the member scratch arrays to hold `need` members. */
int us_lcp_inv_reserve(us_Lcp *p, int need) {
  if (need <= p->cap) return 0;
  int cap = US_MAX(need, 2 * p->cap);
  cap = US_MAX(cap, 8);
  double *H = us_malloc((size_t)cap * (size_t)cap * sizeof(double));
  if (!H) return -1;
  for (int i = 0; i < p->k; i++)
    memcpy(H + (size_t)i * (size_t)cap, p->H + (size_t)i * (size_t)p->cap,
           (size_t)p->k * sizeof(double));
  double **vecs[5] = {&p->dfm, &p->r, &p->y, &p->z, &p->e};
  for (int v = 0; v < 5; v++) {
    double *x = us_realloc(*vecs[v], (size_t)cap * sizeof(double));
    if (!x) {
      us_free(H);
      return -1;
    }
    *vecs[v] = x;
  }
  int *mem = us_realloc(p->mem, (size_t)cap * sizeof(int));
  if (!mem) {
    us_free(H);
    return -1;
  }
  p->mem = mem;
  int *nz = us_realloc(p->nz, (size_t)cap * sizeof(int));
  if (!nz) {
    us_free(H);
    return -1;
  }
  p->nz = nz;
  us_free(p->H);
  p->H = H;
  p->cap = cap;
  return 0;
}

/* x = H r. r is usually sparse (contacts couple only through shared
 * bodies): the non-zeros are gathered first, so the cost is O(k nnz). */
void us_lcp_inv_mult(const us_Lcp *p, const double *r, double *x) {
  int nnz = 0;
  for (int j = 0; j < p->k; j++)
    if (r[j] != 0.0) p->nz[nnz++] = j;
  for (int i = 0; i < p->k; i++) {
    const double *h = p->H + (size_t)i * (size_t)p->cap;
    double s = 0.0;
    for (int t = 0; t < nnz; t++) s += h[p->nz[t]] * r[p->nz[t]];
    x[i] = s;
  }
}

/* z = H^T v */
static void inv_mult_t(const us_Lcp *p, const double *v, double *z) {
  for (int j = 0; j < p->k; j++) z[j] = 0.0;
  for (int i = 0; i < p->k; i++) {
    const double *h = p->H + (size_t)i * (size_t)p->cap;
    double vi = v[i];
    if (vi == 0.0) continue;
    for (int j = 0; j < p->k; j++) z[j] += vi * h[j];
  }
}

int us_lcp_inv_append(us_Lcp *p, int idx, const double *u, const double *v, double alpha,
                      double tol) {
  int k = p->k;
  /* u and v may be p->r / p->e: the caller reserved, so they stay put */
  if (k + 1 > p->cap) return -1;
  us_lcp_inv_mult(p, u, p->y);
  inv_mult_t(p, v, p->z);
  double sigma = alpha;
  for (int i = 0; i < k; i++) sigma -= v[i] * p->y[i];
  if (!(fabs(sigma) > tol)) return 1;
  double is = 1.0 / sigma;
  size_t ld = (size_t)p->cap;
  for (int i = 0; i < k; i++) {
    double *h = p->H + (size_t)i * ld;
    double yi = p->y[i] * is;
    for (int j = 0; j < k; j++) h[j] += yi * p->z[j];
    h[k] = -yi;
  }
  double *hk = p->H + (size_t)k * ld;
  for (int j = 0; j < k; j++) hk[j] = -p->z[j] * is;
  hk[k] = is;
  p->mem[k] = idx;
  p->pos[idx] = k;
  p->k = k + 1;
  p->updates++;
  return 0;
}

/* Swap slots s and t (rows and columns of H, entries of mem / pos). */
static void inv_swap(us_Lcp *p, int s, int t) {
  if (s == t) return;
  size_t ld = (size_t)p->cap;
  double *hs = p->H + (size_t)s * ld, *ht = p->H + (size_t)t * ld;
  for (int j = 0; j < p->k; j++) {
    double x = hs[j];
    hs[j] = ht[j];
    ht[j] = x;
  }
  for (int i = 0; i < p->k; i++) {
    double *h = p->H + (size_t)i * ld;
    double x = h[s];
    h[s] = h[t];
    h[t] = x;
  }
  int ms = p->mem[s], mt = p->mem[t];
  p->mem[s] = mt;
  p->mem[t] = ms;
  p->pos[mt] = s;
  p->pos[ms] = t;
}

int us_lcp_inv_delete(us_Lcp *p, int s) {
  int L = p->k - 1;
  inv_swap(p, s, L);
  size_t ld = (size_t)p->cap;
  const double *hl = p->H + (size_t)L * ld;
  int bad = !(fabs(hl[L]) > 1e-300) || !isfinite(hl[L]);
  double ihll = bad ? 0.0 : 1.0 / hl[L];
  for (int i = 0; i < L; i++) {
    double *h = p->H + (size_t)i * ld;
    double c = h[L] * ihll;
    if (c == 0.0) continue;
    for (int j = 0; j < L; j++) h[j] -= c * hl[j];
  }
  p->pos[p->mem[L]] = -1;
  p->k = L;
  p->updates++;
  return bad;
}
