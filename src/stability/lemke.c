/* Lemke's method (complementary pivoting with an artificial variable z0
 * and covering vector e) on a dense tableau, with a lexicographic ratio
 * test.
 *
 * The LCP: w = M z + q >= 0, z >= 0, w . z = 0. The start adds z0 >= 0:
 * w = M z + q + e z0, every w basic. If q >= 0 the start solves it; else
 * z0 enters at the row of the most negative q_i (the almost complementary
 * basis is then feasible), and each following pivot brings in the
 * complement of the variable that just left, the leaving row chosen by
 * the least ratio qb_i / -t[i][s]. The run ends when z0 leaves (a
 * solution) or when no row blocks the entering column (a secondary ray).
 *
 * Termination. Ties of the ratio test go to z0 first, then to the
 * lexicographic minimum of the rows' coefficients of the start's basic
 * variables (the columns of B^-1) divided by the pivot. That is the
 * ratio test of the perturbed problem q + (eps, eps^2, ..., eps^dim) for
 * a small enough eps > 0, which is nondegenerate: every almost
 * complementary feasible basis then has exactly two neighbours on the
 * path (the two ways its missing pair can re-enter), the start has one
 * (the primary ray), so the path cannot return to a basis it visited and,
 * the bases being finite, ends: z0 leaves or a secondary ray (Cottle,
 * Pang & Stone, The Linear Complementarity Problem, 4.4 and 4.9). What a
 * ray means depends on M: when M is copositive-plus (skew-symmetric and
 * symmetric positive semidefinite matrices are), a secondary ray proves
 * that the LCP has no feasible point (Theorem 4.4.13 there), so a
 * feasible LCP with such an M always ends SOLVED in exact arithmetic. Each user says what a ray
 * proves for its M (lp_lcp.c, lcp_lemke.c) and checks it.
 *
 * Invariants between pivots: exactly one of w_i, z_i is basic for every i
 * but one pair (both nonbasic) while z0 is basic; qb >= 0 up to round-off
 * once z0 is in. A pivot updates the other rows only in the pivot row's
 * non-zero columns (the tableaux of both users start sparse).
 */
#include "lemke.h"

#include <math.h>
#include <string.h>

#define PIVOT_EPS 1e-9    /* |entries| at most this never pivot */
#define FEAS_EPS 1e-11    /* basic values above -this count as >= 0 */
#define RATIO_TIE 1e-11   /* ratios this close are ties */
#define LEX_TIE 1e-12     /* lexicographic entries this close are equal */
#define DEADLINE_EVERY 64 /* pivots between looks at the clock */
#define PIVOTS_PER_DIM 20 /* default pivot limit: 20 dim + 200 */
#define PIVOT_BASE 200

int us_lemke_reserve(us_Lemke *k, int dim) {
  long cells = (long)dim * (long)(dim + 1);
  if (cells > 1L << 28) return -1;
  k->dim = dim;
  return US_GROW(k->t, k->cap_t, (int)cells) || US_GROW(k->qb, k->cap_q, dim) ||
                 US_GROW(k->rowvar, k->cap_rv, dim) || US_GROW(k->colvar, k->cap_cv, dim + 1) ||
                 US_GROW(k->pos, k->cap_pos, 2 * dim + 1) || US_GROW(k->ref, k->cap_ref, dim) ||
                 US_GROW(k->nz, k->cap_nz, dim + 1) || US_GROW(k->ties, k->cap_ties, dim)
             ? -1
             : 0;
}

void us_lemke_free(us_Lemke *k) {
  double *d[] = {k->t, k->qb};
  int *i[] = {k->rowvar, k->colvar, k->pos, k->ref, k->nz, k->ties};
  for (size_t j = 0; j < sizeof d / sizeof d[0]; j++) us_free(d[j]);
  for (size_t j = 0; j < sizeof i / sizeof i[0]; j++) us_free(i[j]);
  memset(k, 0, sizeof *k);
}

void us_lemke_clear(us_Lemke *k) {
  int dim = k->dim;
  memset(k->t, 0, (size_t)dim * (size_t)(dim + 1) * sizeof(double));
  memset(k->qb, 0, (size_t)dim * sizeof(double));
  for (int i = 0; i < dim; i++) {
    us_lemke_row(k, i)[dim] = 1.0;
    k->rowvar[i] = k->pos[i] = i;
    k->colvar[i] = dim + i;
    k->pos[dim + i] = -(i + 1);
  }
  k->colvar[dim] = 2 * dim;
  k->pos[2 * dim] = -(dim + 1);
}

void us_lemke_pivot(us_Lemke *k, int r, int s) {
  int width = k->dim + 1, nnz = 0;
  double *pr = us_lemke_row(k, r), p = pr[s];
  for (int j = 0; j < width; j++) {
    if (pr[j] == 0.0) continue;
    pr[j] = -pr[j] / p;
    k->nz[nnz++] = j;
  }
  pr[s] = 1.0 / p;
  k->qb[r] = -k->qb[r] / p;
  for (int i = 0; i < k->dim; i++) {
    double *ri = us_lemke_row(k, i), f = ri[s];
    if (i == r || f == 0.0) continue;
    ri[s] = 0.0;
    for (int q = 0; q < nnz; q++) ri[k->nz[q]] += f * pr[k->nz[q]];
    k->qb[i] += f * k->qb[r];
  }
  int leave = k->rowvar[r], enter = k->colvar[s];
  k->rowvar[r] = enter;
  k->colvar[s] = leave;
  k->pos[enter] = r;
  k->pos[leave] = -(s + 1);
  k->pivots++;
}

us_LemkeEnd us_lemke_limits(const us_Lemke *k) {
  if (k->pivots >= k->limit) return US_LEMKE_LIMIT;
  if (k->deadline > 0 && k->pivots % DEADLINE_EVERY == 0 && us_now() >= k->deadline)
    return US_LEMKE_TIME;
  return US_LEMKE_GO;
}

static int complement(const us_Lemke *k, int v) { return v < k->dim ? v + k->dim : v - k->dim; }

/* Row i's coefficient of the q-th reference variable (full-tableau sign:
 * the variable's column of B^-1). */
static double lex_coef(const us_Lemke *k, int i, int q) {
  int p = k->pos[k->ref[q]];
  if (p >= 0) return p == i ? 1.0 : 0.0;
  return -us_lemke_row(k, i)[-p - 1];
}

/* Row i's divisor in the lexicographic test (column s; s < 0: the
 * covering vector, 1). */
static double lex_div(const us_Lemke *k, int i, int s) {
  return s < 0 ? 1.0 : -us_lemke_row(k, i)[s];
}

/* Among the tied rows ties[0 .. nt), the lexicographic minimum of the
 * reference coefficients divided by each row's pivot. */
static int lex_min(us_Lemke *k, int nt, int s) {
  for (int q = 0; q < k->dim && nt > 1; q++) {
    double best = INFINITY;
    for (int j = 0; j < nt; j++)
      best = US_MIN(best, lex_coef(k, k->ties[j], q) / lex_div(k, k->ties[j], s));
    int keep = 0;
    for (int j = 0; j < nt; j++) {
      int i = k->ties[j];
      if (lex_coef(k, i, q) / lex_div(k, i, s) <= best + LEX_TIE) k->ties[keep++] = i;
    }
    nt = keep;
  }
  return nt > 0 ? k->ties[0] : -1;
}

/* Lemke's first step: z0 enters at the most negative basic value; -1 if
 * none is negative (the start is a solution). */
static int first_row(us_Lemke *k) {
  double best = -FEAS_EPS;
  for (int i = 0; i < k->dim; i++) best = US_MIN(best, k->qb[i]);
  if (best >= -FEAS_EPS) return -1;
  int nt = 0;
  for (int i = 0; i < k->dim; i++)
    if (k->qb[i] <= best + RATIO_TIE) k->ties[nt++] = i;
  return lex_min(k, nt, -1);
}

/* The leaving row for entering column s: least ratio, z0 first among ties,
 * then the lexicographic rule; -1 if nothing blocks (a ray). */
static int ratio_row(us_Lemke *k, int s) {
  double best = INFINITY;
  for (int i = 0; i < k->dim; i++) {
    double a = -us_lemke_row(k, i)[s];
    if (a > PIVOT_EPS) best = US_MIN(best, US_MAX(k->qb[i], 0.0) / a);
  }
  if (!isfinite(best)) return -1;
  int nt = 0;
  for (int i = 0; i < k->dim; i++) {
    double a = -us_lemke_row(k, i)[s];
    if (a <= PIVOT_EPS || US_MAX(k->qb[i], 0.0) / a > best + RATIO_TIE) continue;
    if (k->rowvar[i] == 2 * k->dim) return i;
    k->ties[nt++] = i;
  }
  return lex_min(k, nt, s);
}

/* Every basic value finite: non-finite data (a NaN compares false in
 * every ratio test) must not reach the pivoting. */
static int values_finite(const us_Lemke *k) {
  for (int i = 0; i < k->dim; i++)
    if (!isfinite(k->qb[i])) return 0;
  return 1;
}

us_LemkeEnd us_lemke_run(us_Lemke *k, int *ray_col) {
  int dim = k->dim, z0 = 2 * dim;
  if (!values_finite(k)) return US_LEMKE_NONFINITE;
  for (int i = 0; i < dim; i++) k->ref[i] = k->rowvar[i];
  int r = first_row(k);
  if (r < 0) return US_LEMKE_SOLVED;
  int s = -k->pos[z0] - 1;
  for (int i = 0; i < dim; i++) us_lemke_row(k, i)[s] = 1.0;
  int leave = k->rowvar[r];
  us_lemke_pivot(k, r, s);
  while (leave != z0) {
    us_LemkeEnd e = us_lemke_limits(k);
    if (e != US_LEMKE_GO) return e;
    s = -k->pos[complement(k, leave)] - 1;
    r = ratio_row(k, s);
    if (r < 0) {
      *ray_col = s;
      return US_LEMKE_RAY;
    }
    leave = k->rowvar[r];
    us_lemke_pivot(k, r, s);
  }
  return values_finite(k) ? US_LEMKE_SOLVED : US_LEMKE_NONFINITE;
}

long us_lemke_default_limit(int dim) { return (long)PIVOTS_PER_DIM * dim + PIVOT_BASE; }

double us_lemke_value(const us_Lemke *k, int v) {
  int p = k->pos[v];
  return p >= 0 ? k->qb[p] : 0.0;
}

double us_lemke_ray_dir(const us_Lemke *k, int v, int s) {
  int p = k->pos[v];
  if (p >= 0) return us_lemke_row(k, p)[s];
  return k->colvar[s] == v ? 1.0 : 0.0;
}
