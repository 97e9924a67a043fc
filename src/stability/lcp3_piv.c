/* Principal pivoting on the 3D cone LCP (lcp3_piv.h): Lawson and Hanson's
 * active-set method for min 1/2 l^T A l + b^T l over l >= 0, whose KKT
 * conditions are the LCP a = A l + b >= 0, l >= 0, l . a = 0.
 *
 * Algorithm. P is a set of live indices whose Gram block A_PP is positive
 * definite, factorized as R^T R; forces are zero off P and >= 0 on P.
 *   settle: the Newton step dl_P = -A_PP^-1 a_P (a exact: recomputed from
 *     the forces) reaches the minimizer over span P. If it keeps every
 *     force >= 0, take it (then a_P = 0); else go the largest part of it
 *     that keeps them (the ratio test), let the indices whose forces hit
 *     0 leave P (a Givens downdate of R), and settle again;
 *   join: the live index off P with the most negative a joins P (a column
 *     appended to R), unless its pivot is below tol_piv times A_jj: then
 *     it is in the span of P up to round-off (where, exactly, a_j would be
 *     0) and is refused for the rest of the sweep;
 * until no a off P is below -tol_a. Each join then settle strictly lowers
 * the objective in exact arithmetic, so no P repeats and the method ends
 * (Lawson and Hanson 1974, ch. 23); a pivot limit guards round-off. On
 * SOLVED, every live index has l >= 0 and a_P = 0, and a >= -tol_a off P
 * except refused indices still refused after SWEEPS sweeps (round-off);
 * the caller's verdict re-checks a and never trusts SOLVED alone.
 * The matrix class: A symmetric positive semidefinite (a Gram matrix) is
 * what the method needs; it never forms A, only A_PP's entries and a.
 * Reuse: P, R and the forces stay between runs. Indices of removed bodies
 * leave P by downdates (us_lcp3_piv_drop); the other columns of P are
 * unchanged (a body's removal changes A only in the rows of its own
 * contacts), so R stays the factor of the new A_PP and the next run
 * starts from the parent's solution; new indices join with l = 0.
 */
#include "lcp3_piv.h"

#include <math.h>
#include <string.h>

#define MIN_CAP 16
#define SWEEPS 3 /* sweeps that may clear refused indices and go on */

int us_lcp3_piv_init(us_Lcp3Piv *q, int n) {
  memset(q, 0, sizeof *q);
  size_t m = (size_t)(n > 0 ? n : 1);
  q->pos = us_malloc(m * sizeof(int));
  q->live = us_malloc(m * sizeof(int));
  q->skip = us_calloc(m, 1);
  if (!q->pos || !q->live || !q->skip) return -1;
  for (int i = 0; i < n; i++) q->pos[i] = -1;
  return 0;
}

void us_lcp3_piv_free(us_Lcp3Piv *q) {
  void *arrs[] = {q->mem, q->pos, q->live, q->R, q->t1, q->t2, q->skip};
  for (size_t i = 0; i < sizeof arrs / sizeof arrs[0]; i++) us_free(arrs[i]);
  memset(q, 0, sizeof *q);
}

void us_lcp3_piv_reset(us_Lcp3Piv *q, int n) {
  (void)n;
  for (int i = 0; i < q->k; i++) q->pos[q->mem[i]] = -1;
  q->k = 0;
}

/* Room for one more member (R keeps its columns at the new stride). */
static int grow(us_Lcp3Piv *q) {
  if (q->k < q->cap) return 0;
  int cap = q->cap < MIN_CAP ? MIN_CAP : 2 * q->cap;
  size_t c = (size_t)cap;
  double *R = us_calloc(c * c, sizeof(double));
  int *mem = us_realloc(q->mem, c * sizeof(int));
  if (mem) q->mem = mem;
  double *t1 = us_realloc(q->t1, c * sizeof(double));
  if (t1) q->t1 = t1;
  double *t2 = us_realloc(q->t2, c * sizeof(double));
  if (t2) q->t2 = t2;
  if (!R || !mem || !t1 || !t2) {
    us_free(R);
    return -1;
  }
  for (int j = 0; j < q->k; j++)
    memcpy(R + (size_t)j * c, q->R + (size_t)j * (size_t)q->cap, (size_t)(j + 1) * sizeof(double));
  us_free(q->R);
  q->R = R;
  q->cap = cap;
  return 0;
}

static double *col(const us_Lcp3Piv *q, int j) { return q->R + (size_t)j * (size_t)q->cap; }

/* x = (R^T R)^-1 x in place. */
static void solve(const us_Lcp3Piv *q, double *x) {
  for (int i = 0; i < q->k; i++) { /* R^T u = x */
    const double *ci = col(q, i);
    double s = x[i];
    for (int m = 0; m < i; m++) s -= ci[m] * x[m];
    x[i] = s / ci[i];
  }
  for (int i = q->k - 1; i >= 0; i--) { /* R x = u */
    double s = x[i];
    for (int m = i + 1; m < q->k; m++) s -= col(q, m)[i] * x[m];
    x[i] = s / col(q, i)[i];
  }
}

/* Index j joins P: 1, 0 refused (dependent up to round-off), -1 OOM. */
static int join(us_Lcp3Piv *q, us_Lcp *p, int j) {
  if (grow(q)) return -1;
  double *c = col(q, q->k), ajj = p->ops.entry(p->ops.ctx, j, j), d = ajj;
  for (int i = 0; i < q->k; i++) c[i] = p->ops.entry(p->ops.ctx, q->mem[i], j);
  for (int i = 0; i < q->k; i++) { /* R^T y = A_Pj */
    const double *ci = col(q, i);
    double s = c[i];
    for (int m = 0; m < i; m++) s -= ci[m] * c[m];
    c[i] = s / ci[i];
    d -= c[i] * c[i];
  }
  if (!(d > p->set.tol_piv * ajj) || !isfinite(d)) {
    q->skip[j] = 1;
    q->refused++;
    return 0;
  }
  c[q->k] = sqrt(d);
  q->mem[q->k] = j;
  q->pos[j] = q->k++;
  return 1;
}

/* Member at position s leaves P: its column goes, the Hessenberg rest is
 * made triangular again by Givens rotations. */
static void leave(us_Lcp3Piv *q, int s) {
  q->pos[q->mem[s]] = -1;
  for (int c = s + 1; c < q->k; c++) {
    memcpy(col(q, c - 1), col(q, c), (size_t)(c + 1) * sizeof(double));
    q->mem[c - 1] = q->mem[c];
    q->pos[q->mem[c - 1]] = c - 1;
  }
  q->k--;
  for (int i = s; i < q->k; i++) {
    double *ci = col(q, i), a = ci[i], b = ci[i + 1], r = hypot(a, b);
    double cs = r > 0 ? a / r : 1.0, sn = r > 0 ? b / r : 0.0;
    for (int m = i; m < q->k; m++) {
      double *cm = col(q, m), x = cm[i], y = cm[i + 1];
      cm[i] = cs * x + sn * y;
      cm[i + 1] = -sn * x + cs * y;
    }
    ci[i + 1] = 0.0;
  }
}

void us_lcp3_piv_drop(us_Lcp3Piv *q, us_Lcp *p, const int *idx, int k) {
  for (int m = 0; m < k; m++) {
    int i = idx[m];
    if (q->pos[i] >= 0) leave(q, q->pos[i]);
    p->f[i] = p->a[i] = 0.0;
    p->live[i] = 0;
    p->state[i] = US_LCP_OFF;
  }
}

/* The ratio test of the Newton step t1 (members' increments): the
 * fraction of it that keeps every force >= 0, and the first member that
 * blocks it (-1: the whole step). */
static double ratio(const us_Lcp3Piv *q, const us_Lcp *p, int *block) {
  double alpha = 1.0;
  *block = -1;
  for (int i = 0; i < q->k; i++) {
    double l = p->f[q->mem[i]], z = l + q->t1[i];
    if (z > 0) continue;
    double r = l > 0 ? l / (l - z) : 0.0;
    if (r < alpha) alpha = r, *block = i;
  }
  return alpha;
}

/* Settle P (header): 0 or LIMIT, with a fresh on return. `fresh`: the
 * index that just joined (a is still fresh: its force is 0), refused if
 * it leaves at once without progress; -1: recompute a first. */
static us_LcpResult settle(us_Lcp3Piv *q, us_Lcp *p, int fresh, long start, long limit) {
  for (int stale = fresh < 0;; stale = 1) {
    if (stale) p->ops.full(p->ops.ctx, p->f, p->live, p->a);
    if (q->k == 0) return US_LCP_SOLVED;
    for (int i = 0; i < q->k; i++) q->t1[i] = -p->a[q->mem[i]];
    solve(q, q->t1);
    int block;
    double alpha = ratio(q, p, &block);
    for (int i = 0; i < q->k; i++) p->f[q->mem[i]] = US_MAX(0.0, p->f[q->mem[i]] + alpha * q->t1[i]);
    if (block < 0) {
      p->ops.full(p->ops.ctx, p->f, p->live, p->a);
      return US_LCP_SOLVED;
    }
    if (q->mem[block] == fresh && alpha <= 0) q->skip[fresh] = 1;
    p->f[q->mem[block]] = 0.0;
    leave(q, block);
    for (int i = q->k - 1; i >= 0; i--) /* others that reached 0 with it */
      if (p->f[q->mem[i]] <= 0) leave(q, i);
    if (++q->pivots - start > limit) return US_LCP_LIMIT;
  }
}

/* The live index off P with the most negative a below -tol_a, or -1. */
static int most_violated(const us_Lcp3Piv *q, const us_Lcp *p, int *refused) {
  int best = -1;
  double worst = -p->set.tol_a;
  *refused = 0;
  for (int m = 0; m < q->nlive; m++) {
    int i = q->live[m];
    if (q->pos[i] >= 0 || !(p->a[i] < -p->set.tol_a)) continue;
    if (q->skip[i]) {
      *refused = 1;
      continue;
    }
    if (p->a[i] < worst) worst = p->a[i], best = i;
  }
  return best;
}

us_LcpResult us_lcp3_piv_run(us_Lcp3Piv *q, us_Lcp *p, long limit) {
  long start = q->pivots;
  memset(q->skip, 0, (size_t)p->n);
  q->nlive = 0;
  for (int i = 0; i < p->n; i++)
    if (p->live[i]) q->live[q->nlive++] = i;
  us_LcpResult r = settle(q, p, -1, start, limit);
  for (int sweep = 0; r == US_LCP_SOLVED;) {
    int refused, j = most_violated(q, p, &refused);
    if (j < 0 && refused && ++sweep < SWEEPS) { /* refused ones: one more sweep */
      memset(q->skip, 0, (size_t)p->n);
      continue;
    }
    if (j < 0) break;
    int ok = join(q, p, j);
    if (ok < 0) r = US_LCP_NOMEM;
    if (ok <= 0) continue;
    if (++q->pivots - start > limit) r = US_LCP_LIMIT;
    if (r == US_LCP_SOLVED) r = settle(q, p, j, start, limit);
    if (((q->pivots - start) & 63) == 0 && p->set.deadline > 0 && us_now() > p->set.deadline)
      r = US_LCP_LIMIT;
  }
  p->pivots += q->pivots - start;
  return r;
}
