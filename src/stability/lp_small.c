/* A dense simplex for the tiny statics LPs of the local tests.
 *
 * Why: the local tests (local.c) solve many LPs of a few bodies each. CLP
 * decides them exactly but costs about 0.1 ms a solve whatever the size
 * (a model is created, scaled and factorized each time): on the 91-block
 * pyramid that fixed cost was the whole plan's time. For systems of at
 * most US_SMALL_ROWS rows this backend does the same job in a dense
 * tableau, and it never has the last word: a feasible answer is re-checked
 * by the certificate check, an infeasible one by the Farkas ray's own
 * check (us_eq_gen_farkas_body) and then the mechanism check; anything it
 * cannot settle cleanly (too many pivots, a ray that fails) comes back
 * US_UNDECIDED and the caller asks CLP.
 *
 * Algorithm: phase 1 of the primal simplex on G l + a = b (rows with
 * b_i < 0 negated first, so the artificials a = b >= 0 are a feasible
 * start), minimizing the sum of the artificials: entering the most
 * negative reduced cost (Dantzig), or the lowest index with a negative
 * one (Bland) once the objective stalls, leaving the largest pivot
 * among the ratio-test ties (for accuracy; a pivot limit stands in for
 * Bland's guarantee against cycling), or the largest artificial among
 * them if its pivot is at least ART_PREFER of that one (each artificial
 * must leave, so this saves pivots: 3 % of them on random stacks; about
 * half the pivots are degenerate, ties at ratio 0). The tableau is kept
 * by columns: a pivot changes only the columns with a nonzero in the
 * pivot row, each by a multiple of the pivot column (contiguous: SIMD).
 * A feasible answer's residual
 * |G l - b| is measured from the sparse columns before it is claimed.
 * Optimum 0: l is feasible. Optimum > 0: the duals y of the final basis
 * (c_B B^-1, solved from the basis's columns) satisfy
 * y . G_j <= 0 for every column and y . b > 0, a Farkas ray. The
 * artificial columns are not stored: an artificial that leaves never
 * comes back (the usual phase-1 rule), so the tableau is only
 * (m + 1) x (n + 1) doubles, reused between solves, and the duals are
 * solved from the final basis instead (B^T y = c_B, dense, pivoted).
 */
#include "lp_small.h"

#include "lp_gen.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define PIVOT_EPS 1e-11   /* entries below this are not pivots */
#define COST_EPS 1e-12    /* reduced costs above -this are optimal */
#define FEAS_TOL 1e-10    /* phase-1 optimum at most this: feasible */
#define RATIO_TIE 1e-12   /* ratios this close are ties */
#define ART_PREFER 0.1    /* ties: an artificial leaves if its pivot is this share of the largest */
#define RESID_TOL 1e-9    /* a feasible claim's max |G l - b| (b is at most 1) */

/* pivot() in two versions, AVX2 and baseline, the processor's chosen once
 * at load (an ifunc; no FMA, so the arithmetic is the plain loop's): 2-5 %
 * of a batch of small random stacks. GCC on x86-64 only, and not under the
 * sanitizers, which instrument the resolver although it runs before their
 * runtime is up (ThreadSanitizer crashed at load). */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_THREAD__) && !defined(__SANITIZE_ADDRESS__)
#define PIVOT_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define PIVOT_CLONES
#endif

typedef struct SmallWs {
  us_EqGen gen;
  us_LpSettings set;
  double *t;         /* tableau, column-major (T): n + 1 columns of m + 1 (the cost row last) */
  int *basis;        /* [m] basic column of each row (n + i: row i's artificial) */
  int *nz;           /* [n + 1] the pivot row's nonzero columns */
  double *cost;      /* [n + 1] row m of the tableau again, contiguous for pricing */
  double *ratio;     /* [m] the ratio test's ratios */
  double *sol, *ray; /* [n], [m] */
  double *bt;        /* [m (m + 1)] B^T and c_B for the duals */
  int cap_t, cap_b, cap_nz, cap_cost, cap_ratio, cap_s, cap_r, cap_bt;
  int nray, last_body;
} SmallWs;

static void small_destroy(void *ws) {
  SmallWs *w = ws;
  if (!w) return;
  us_eq_gen_free(&w->gen);
  us_free(w->t);
  us_free(w->basis);
  us_free(w->nz);
  us_free(w->cost);
  us_free(w->ratio);
  us_free(w->sol);
  us_free(w->ray);
  us_free(w->bt);
  us_free(w);
}

static void *small_create(const us_Structure *s, const us_StabilitySettings *set, us_Error *err) {
  US_UNUSED(s);
  SmallWs *w = us_calloc(1, sizeof *w);
  if (!w) {
    us_error_set(err, US_ERR_NOMEM, "out of memory creating the small LP workspace");
    return NULL;
  }
  w->set = us_lp_settings_resolve(&set->lp);
  w->last_body = -1;
  return w;
}

/* Entry (i, j) of the tableau: column-major, so that a column (the
 * entering one, the right-hand side) is contiguous. */
#define T(w, m, i, j) ((w)->t[(size_t)(j) * (size_t)((m) + 1) + (size_t)(i)])

/* The phase-1 tableau of G l + a = b with b >= 0 row by row (w->ray[i]
 * records the sign of row i); row m holds the reduced costs of phase 1
 * and, in column n, minus the objective. */
static void fill_tableau(SmallWs *w, const us_EqSystem *sys, int m, int n) {
  const us_EqGen *g = &w->gen;
  memset(w->t, 0, (size_t)(m + 1) * (size_t)(n + 1) * sizeof(double));
  for (int i = 0; i < m; i++) {
    w->ray[i] = sys->rhs[i] < 0 ? -1.0 : 1.0;
    T(w, m, i, n) = w->ray[i] * sys->rhs[i];
    w->basis[i] = n + i;
  }
  for (int j = 0; j < n; j++) { /* a column and its phase-1 cost, minus its sum */
    double c = 0.0;
    for (int k = g->start[j]; k < g->start[j + 1]; k++)
      c -= T(w, m, g->row[k], j) = w->ray[g->row[k]] * g->val[k];
    T(w, m, m, j) = w->cost[j] = c;
  }
  double c = 0.0;
  for (int i = 0; i < m; i++) c -= T(w, m, i, n);
  T(w, m, m, n) = w->cost[n] = c;
}

/* Pivot on (pr, pc). Only the columns with a nonzero in the pivot row
 * change (a body's row meets only its own contacts' columns until fill-in
 * spreads it; 31 % of them on average on random stacks), each by a
 * multiple of the pivot column, contiguous; the others would only have
 * exact zeros subtracted. They are listed first without branches (which
 * entries are zero is unpredictable). Compiled for AVX2 too where the
 * processor has it (PIVOT_CLONES). */
PIVOT_CLONES
static void pivot(SmallWs *w, int m, int n, int pr, int pc) {
  double *piv = &T(w, m, 0, pc), p = piv[pr];
  int *nz = w->nz, nnz = 0, len = m + 1;
  for (int j = 0; j <= n; j++) nz[nnz] = j, nnz += (T(w, m, pr, j) != 0.0) & (j != pc);
  for (int k = 0; k < nnz; k++) {
    double *restrict col = &T(w, m, 0, nz[k]), q = col[pr] / p;
    for (int i = 0; i < len; i++) col[i] -= q * piv[i];
    col[pr] = q;
    w->cost[nz[k]] = col[m];
  }
  memset(piv, 0, (size_t)len * sizeof(double));
  piv[pr] = 1.0;
  w->cost[pc] = 0.0;
  w->basis[pr] = pc;
}

/* The leaving row for entering column pc: the least ratio, and among
 * rows within round-off of it the largest pivot (a small pivot would
 * amplify the tableau's errors), or an artificial nearly as large; -1
 * if none. The ratios are computed once (infinite where the entry is no
 * pivot) and then compared. */
static int leaving_row(SmallWs *w, int m, int n, int pc) {
  const double *col = &T(w, m, 0, pc), *rhs = &T(w, m, 0, n);
  double best = INFINITY, *ratio = w->ratio;
  for (int i = 0; i < m; i++) { /* selects, not branches: a non-pivot is INF / 1 */
    int ok = col[i] > PIVOT_EPS;
    double num = ok ? US_MAX(rhs[i], 0.0) : INFINITY, den = ok ? col[i] : 1.0;
    ratio[i] = num / den;
    best = US_MIN(best, ratio[i]);
  }
  if (!isfinite(best)) return -1;
  int pr = -1, art = -1;
  double big = 0.0, abig = 0.0;
  for (int i = 0; i < m; i++) {
    if (ratio[i] > best + RATIO_TIE) continue;
    if (col[i] > big) big = col[i], pr = i;
    if (w->basis[i] >= n && col[i] > abig) abig = col[i], art = i; /* n + i: an artificial */
  }
  return art >= 0 && abig >= ART_PREFER * big ? art : pr;
}

/* The entering column: the most negative reduced cost (Dantzig: few
 * pivots), or the lowest index with a negative one (Bland: no cycling)
 * once pivots stall; -1 when optimal. */
static int entering_column(const double *cost, int n, int bland) {
  int pc = -1;
  double most = -COST_EPS;
  for (int j = 0; j < n; j++)
    if (cost[j] < most) {
      pc = j;
      if (bland) break;
      most = cost[j];
    }
  return pc;
}

/* Pivots until optimal: 0, or -1 past the pivot limit (then CLP decides).
 * After STALL_PIVOTS degenerate pivots in a row (the objective did not
 * move) the entering rule turns to Bland's for the rest of the solve. */
#define STALL_PIVOTS 16
static int run_simplex(SmallWs *w, int m, int n) {
  int limit = 20 * (m + n), stall = 0;
  for (int it = 0; it < limit; it++) {
    int pc = entering_column(w->cost, n, stall >= STALL_PIVOTS);
    if (pc < 0) return 0;
    int pr = leaving_row(w, m, n, pc);
    if (pr < 0) return -1; /* phase 1 is bounded below: only round-off gets here */
    double before = T(w, m, m, n);
    pivot(w, m, n, pr, pc);
    stall = T(w, m, m, n) == before ? stall + 1 : 0;
  }
  return -1;
}

/* max |G l - b| of a claimed solution, from the sparse columns. */
static double residual(SmallWs *w, const us_EqSystem *sys, int m, int n) {
  double *r = w->ray; /* scratch: the ray is not used on this path */
  for (int i = 0; i < m; i++) r[i] = -sys->rhs[i];
  for (int j = 0; j < n; j++) {
    double x = US_MAX(w->sol[j], 0.0);
    for (int k = w->gen.start[j]; k < w->gen.start[j + 1]; k++) r[w->gen.row[k]] += w->gen.val[k] * x;
  }
  double worst = 0.0;
  for (int i = 0; i < m; i++) worst = US_MAX(worst, fabs(r[i]));
  return worst;
}

static int small_reserve(SmallWs *w, int m, int n) {
  long cells = (long)(m + 1) * (long)(n + 1), bcells = (long)m * (long)(m + 1) + 1;
  if (cells > 1L << 28 || bcells > 1L << 28) return -1;
  return US_GROW(w->t, w->cap_t, (int)cells) || US_GROW(w->basis, w->cap_b, m + 1) ||
                 US_GROW(w->nz, w->cap_nz, n + 1) || US_GROW(w->cost, w->cap_cost, n + 1) ||
                 US_GROW(w->ratio, w->cap_ratio, m + 1) ||
                 US_GROW(w->sol, w->cap_s, US_MAX(n, m) + 1) || US_GROW(w->ray, w->cap_r, m + 1) ||
                 US_GROW(w->bt, w->cap_bt, (int)bcells)
             ? -1
             : 0;
}

/* B^T y = c_B for the final basis, in bt's [m x (m + 1)] augmented rows:
 * row k is basic column k of the (row-negated) system, right-hand side 1
 * for an artificial, 0 for a force column. */
static void fill_dual_system(SmallWs *w, int m, int n) {
  double *bt = w->bt;
  memset(bt, 0, (size_t)m * (size_t)(m + 1) * sizeof(double));
  for (int k = 0; k < m; k++) {
    double *row = bt + (size_t)k * (size_t)(m + 1);
    int j = w->basis[k];
    if (j >= n) {
      row[j - n] = 1.0, row[m] = 1.0;
      continue;
    }
    for (int q = w->gen.start[j]; q < w->gen.start[j + 1]; q++)
      row[w->gen.row[q]] = w->ray[w->gen.row[q]] * w->gen.val[q];
  }
}

/* Gaussian elimination with partial pivoting on bt, y into the last
 * column's rows in order; -1 if the basis looks singular (round-off). */
static int solve_dual_system(double *bt, int m, double *y) {
  int width = m + 1;
  for (int c = 0; c < m; c++) {
    int best = c;
    for (int r = c + 1; r < m; r++)
      if (fabs(bt[(size_t)r * (size_t)width + (size_t)c]) > fabs(bt[(size_t)best * (size_t)width + (size_t)c]))
        best = r;
    double *pr = bt + (size_t)best * (size_t)width, *rc = bt + (size_t)c * (size_t)width;
    if (fabs(pr[c]) <= PIVOT_EPS) return -1;
    if (best != c)
      for (int j = 0; j < width; j++) {
        double tmp = pr[j];
        pr[j] = rc[j], rc[j] = tmp;
      }
    for (int r = c + 1; r < m; r++) {
      double *row = bt + (size_t)r * (size_t)width, f = row[c] / rc[c];
      if (f == 0.0) continue;
      for (int j = c; j < width; j++) row[j] -= f * rc[j];
    }
  }
  for (int c = m - 1; c >= 0; c--) { /* back substitution */
    const double *rc = bt + (size_t)c * (size_t)width;
    double v = rc[m];
    for (int j = c + 1; j < m; j++) v -= rc[j] * y[j];
    y[c] = v / rc[c];
  }
  return 0;
}

/* Optimum > 0: the Farkas ray into w->ray (original row signs; on entry
 * w->ray holds the row signs); -1 if the duals cannot be solved. */
static int read_ray(SmallWs *w, int m, int n) {
  fill_dual_system(w, m, n);
  double *y = w->sol; /* scratch (m of them reserved): no solution on this path */
  if (solve_dual_system(w->bt, m, y)) return -1;
  for (int i = 0; i < m; i++) w->ray[i] *= y[i];
  w->nray = m;
  return 0;
}

static us_Status small_solve(void *ws, const us_BackendProblem *pb, us_BackendOut *out,
                             us_Error *err) {
  /* the problem and the output under the names the body reads */
  const us_EqSystem *sys = pb->sys;
  us_Verdict *verdict = &out->verdict;
  double *f = out->f;
  char *note = out->note;
  size_t note_sz = out->note_sz;
  SmallWs *w = ws;
  w->nray = 0;
  w->last_body = -1;
  int r = us_eq_generators(sys, w->set.n_column_mu, &w->gen);
  int m = w->gen.nrow, n = w->gen.ncol;
  if (r || small_reserve(w, m, n)) return us_error_set(err, US_ERR_NOMEM, "out of memory building the LP");
  if (n == 0) {
    *verdict = us_eq_no_columns_verdict(sys);
    snprintf(note, note_sz, "no active contact");
    return US_OK;
  }
  fill_tableau(w, sys, m, n);
  *verdict = US_UNDECIDED;
  if (run_simplex(w, m, n)) {
    snprintf(note, note_sz, "small LP: pivot limit");
    return US_OK;
  }
  double infeas = -T(w, m, m, n);
  if (infeas <= FEAS_TOL) {
    memset(w->sol, 0, (size_t)n * sizeof(double));
    for (int i = 0; i < m; i++)
      if (w->basis[i] < n) w->sol[w->basis[i]] = T(w, m, i, n);
    if (residual(w, sys, m, n) > RESID_TOL) { /* round-off: let CLP decide */
      snprintf(note, note_sz, "small LP: inaccurate");
      return US_OK;
    }
    us_eq_gen_forces(sys, &w->gen, w->sol, f);
    *verdict = US_STABLE;
    snprintf(note, note_sz, "small LP: feasible");
    return US_OK;
  }
  if (read_ray(w, m, n) == 0)
    w->last_body = us_eq_gen_farkas_body(sys, &w->gen, w->ray, w->set.farkas_slack);
  if (w->last_body < 0) { /* the ray does not hold up: let CLP decide */
    w->nray = 0;
    snprintf(note, note_sz, "small LP: infeasible, ray rejected");
    return US_OK;
  }
  *verdict = US_UNSTABLE;
  snprintf(note, note_sz, "small LP: infeasible (Farkas ray checked)");
  return US_OK;
}

static int small_unstable_body(void *ws) { return ((SmallWs *)ws)->last_body; }

static int small_farkas_ray(void *ws, const double **y) {
  SmallWs *w = ws;
  *y = w->nray ? w->ray : NULL;
  return w->nray;
}

const us_Backend us_backend_small = {
    .method = US_METHOD_LP,
    .create = small_create,
    .destroy = small_destroy,
    .solve = small_solve,
    .unstable_body = small_unstable_body,
    .farkas_ray = small_farkas_ray,
};
