/* A sparse revised simplex for the region LPs of the local tests.
 *
 * Problem: G l = b, l >= 0 (lp_gen.h: G's columns are cone generators),
 * a feasibility question. Columns 0 .. n-1 are G's; column n + i is row
 * i's artificial e_i, whose only feasible value is 0.
 *
 * Phase 1, composite: the basis may start infeasible (it is the previous
 * solve's), so each iteration prices the sum of infeasibilities of the
 * current basic values, w = sum over basic l_j < 0 of -l_j plus sum over
 * basic artificials of |a_i|: costs c_B = -1, +1 or -1 on those, 0 on the
 * rest. y = B^-T c_B; the entering column is the one with the most
 * negative reduced cost -y . G_j (Dantzig; Bland's lowest index after
 * STALL degenerate steps); the leaving one is the first basic value to
 * reach a bound as the entering one grows (a feasible l_j at 0, an
 * artificial at 0 from either side, an infeasible l_j at 0 from below).
 * Artificials never enter. w = 0: the basic l is feasible. No entering
 * column while w > 0: then y . G_j <= 0 for every column and
 * y . b = c_B . l_B = w > 0, so y is a Farkas ray of the LP.
 *
 * Basis: B = L U after a row permutation (left-looking LU, one basis
 * column at a time; each column's pivot is the smallest row index among
 * the entries within PIV_REL of its largest, so a load path's column
 * pivots on its upper body's rows and the factors keep B's sparsity),
 * then one eta per basis change (product form), refactorized every
 * MAX_ETAS changes. Columns that are (numerically) dependent on the
 * earlier ones are left out and the artificials of the rows left
 * unpivoted complete the basis.
 *
 * Warm start: a 2D hint (the base's forces) gives the first basis
 * (start_basis). Without one, the workspace keeps, per structure contact
 * and cone slot, whether the column was basic when its last solve without
 * a hint ended; the next such solve starts from those columns (a test next
 * to the previous one starts near its answer, as CLP's statuses do in
 * lp_clp.c).
 */
#include "lp_sparse.h"

#include "lp_gen.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FEAS_TOL 1e-11  /* a basic value this far below 0 (artificial: from 0) is infeasible */
#define COST_EPS 1e-12  /* reduced costs above -this are optimal */
#define RATIO_PIV 1e-9  /* ratio-test entries below this are not pivots */
#define RATIO_TIE 1e-12 /* ratios this close are ties */
#define PIV_REL 0.1     /* LU: a pivot within this share of the column's largest */
#define PIV_ABS 1e-9    /* LU: a column whose largest remaining entry is below this is dependent */
#define MAX_ETAS 32     /* basis changes between factorizations */
#define STALL 16        /* degenerate steps in a row before Bland's rule */
#define RESID_TOL 1e-9  /* a feasible claim's max |G l - b| */
#define HINT_SHARE 1e-12 /* a hint's generator share above this: a starting column */

typedef struct SparseWs {
  us_EqGen gen;
  us_LpSettings set;
  int m, n, cap_m, cap_n;
  int *basis;          /* [m] column at each basis position (= LU step) */
  int *where;          /* [n + m] basis position, or -1 */
  double *xb;          /* [m] basic values */
  double *x, *z, *w;   /* [m] dense work: x by row (all zero between uses),
                          z by step (BTRAN), w the phase-1 costs by position */
  double *alpha;       /* [m] the entering column, FTRAN'd */
  int *prow, *pinv;    /* [m] row pivoted at step k; step of row i or -1 */
  double *uinv;        /* [m] 1 / U's diagonal */
  int *lstart, *ustart;  /* [m + 1] */
  int *lidx, *uidx;      /* L: rows; U: steps */
  double *lval, *uval;
  int cap_l, cap_u;
  int *cx;             /* [m] the unpivoted rows of the column being factorized */
  double *cv;          /* [m] ... their nonzero values after elimination */
  int *heap;           /* [m + 2] the steps it reaches; scratch counts */
  unsigned char *mark; /* [m] */
  int *cand;           /* [n + m] candidate basis columns */
  int *sortkey;        /* [2 (n + m)] scratch of their order */
  double *cost;        /* [n + m] scratch: the answer's generator shares */
  double *xn;          /* [n + m] a nonbasic column's value: 0, or > 0 for a
                          superbasic one (a hint's share left out of the
                          basis), which may move either way */
  /* etas: position, and the entering column's nonzeros */
  int neta, *eta_pos, *eta_start, *eta_idx, cap_eta, cap_eidx;
  double *eta_val;
  unsigned char *was_basic; /* [nkey = structure contacts * slots], allocated
                               at the first solve */
  int nslot, nkey;
  int nw;              /* rows per body (the system's wrench size) */
  double *ray;
  int nray, last_body;
} SparseWs;

static void sparse_destroy(void *ws) {
  SparseWs *w = ws;
  if (!w) return;
  us_eq_gen_free(&w->gen);
  void *arrays[] = {w->basis, w->where, w->xb, w->x, w->z, w->w, w->alpha, w->prow, w->pinv,
                    w->uinv, w->lstart, w->ustart, w->lidx, w->uidx, w->lval, w->uval,
                    w->heap, w->mark, w->cand, w->sortkey, w->cost, w->eta_pos, w->eta_start, w->eta_idx,
                    w->eta_val, w->was_basic, w->ray, w->xn, w->cx, w->cv};
  for (size_t k = 0; k < sizeof arrays / sizeof *arrays; k++) us_free(arrays[k]);
  us_free(w);
}

static void *sparse_create(const us_Structure *s, const us_StabilitySettings *set, us_Error *err) {
  SparseWs *w = us_calloc(1, sizeof *w);
  if (!w) {
    us_error_set(err, US_ERR_NOMEM, "out of memory creating the sparse LP workspace");
    return NULL;
  }
  w->set = us_lp_settings_resolve(&set->lp);
  w->nslot = us_eq_gen_slots(s->dim);
  w->nkey = s->ncontact * w->nslot; /* was_basic: at the first solve (most never come) */
  w->last_body = -1;
  return w;
}

/* Work arrays for m rows and n columns; -1 on OOM. */
static int reserve(SparseWs *w, int m, int n) {
  if (m > w->cap_m) {
    int c = 2 * m + 16;
    us_free(w->basis), us_free(w->xb), us_free(w->x), us_free(w->z), us_free(w->w);
    us_free(w->alpha), us_free(w->prow), us_free(w->pinv), us_free(w->uinv);
    us_free(w->lstart), us_free(w->ustart), us_free(w->mark), us_free(w->ray);
    us_free(w->heap), us_free(w->cx), us_free(w->cv);
    w->heap = us_malloc((size_t)(c + 2) * sizeof(int)); /* + 2: order_candidates counts */
    w->cx = us_malloc((size_t)c * sizeof(int));
    w->cv = us_malloc((size_t)c * sizeof(double));
    w->basis = us_malloc((size_t)c * sizeof(int));
    w->xb = us_malloc((size_t)c * sizeof(double));
    w->x = us_calloc((size_t)c, sizeof(double));
    w->z = us_malloc((size_t)c * sizeof(double));
    w->w = us_malloc((size_t)c * sizeof(double));
    w->alpha = us_malloc((size_t)c * sizeof(double));
    w->prow = us_malloc((size_t)c * sizeof(int));
    w->pinv = us_malloc((size_t)c * sizeof(int));
    w->uinv = us_malloc((size_t)c * sizeof(double));
    w->lstart = us_malloc((size_t)(c + 1) * sizeof(int));
    w->ustart = us_malloc((size_t)(c + 1) * sizeof(int));
    w->mark = us_calloc((size_t)c, 1);
    w->ray = us_malloc((size_t)c * sizeof(double));
    w->cap_m = w->basis && w->xb && w->x && w->z && w->w && w->alpha && w->prow && w->pinv &&
                       w->uinv && w->lstart && w->ustart && w->mark && w->ray && w->heap &&
                       w->cx && w->cv
                   ? c
                   : 0;
    if (!w->cap_m) return -1;
  }
  if (n + m > w->cap_n) {
    int c = 2 * (n + m) + 16;
    us_free(w->where), us_free(w->cand), us_free(w->sortkey), us_free(w->cost), us_free(w->xn);
    w->where = us_malloc((size_t)c * sizeof(int));
    w->cand = us_malloc((size_t)c * sizeof(int));
    w->sortkey = us_malloc(2 * (size_t)c * sizeof(int));
    w->cost = us_malloc((size_t)c * sizeof(double));
    w->xn = us_malloc((size_t)c * sizeof(double));
    w->cap_n = w->where && w->cand && w->sortkey && w->cost && w->xn ? c : 0;
    if (!w->cap_n) return -1;
  }
  return 0;
}

/* ------------------------------------------------------------ columns */

/* Column j's nonzeros: G's, or the artificial e_(j - n). */
static int column(const SparseWs *w, int j, const int **row, const double **val, int *art_row) {
  static const double one = 1.0;
  if (j < w->n) {
    int a = w->gen.start[j];
    *row = w->gen.row + a, *val = w->gen.val + a;
    return w->gen.start[j + 1] - a;
  }
  *art_row = j - w->n;
  *row = art_row, *val = &one;
  return 1;
}

static int key_of(const SparseWs *w, const us_EqSystem *e, int j) {
  return e->contact[w->gen.col_contact[j]] * w->nslot + w->gen.col_slot[j];
}

/* ----------------------------------------------------------------- LU */

/* A sparse vector store (index and value arrays) grown to hold need
 * entries; -1 on OOM (the arrays stay valid). */
static int grow_store(int **idx, double **val, int *cap, int need) {
  if (need <= *cap) return 0;
  int c = 2 * need + 64;
  int *i = us_realloc(*idx, (size_t)c * sizeof(int));
  if (i) *idx = i;
  double *v = us_realloc(*val, (size_t)c * sizeof(double));
  if (v) *val = v;
  if (!i || !v) return -1;
  *cap = c;
  return 0;
}

static int grow_lu(SparseWs *w, int nl, int nu) {
  return grow_store(&w->lidx, &w->lval, &w->cap_l, nl) ||
                 grow_store(&w->uidx, &w->uval, &w->cap_u, nu)
             ? -1
             : 0;
}

/* The steps a column reaches, in decreasing order (the L solve takes the
 * smallest, from the end): insertion, as a column reaches few steps (4 on
 * average on stacker stacks), where a heap's sifting cost more. */
static void steps_push(int *h, int *n, int v) {
  int i = (*n)++;
  while (i > 0 && h[i - 1] < v) h[i] = h[i - 1], i--;
  h[i] = v;
}

/* Row r of the column being factorized becomes nonzero: a pivoted row's
 * step joins the steps to visit, an unpivoted row the pivot candidates. */
static void reach(SparseWs *w, int r, int *nh, int *nx) {
  w->mark[r] = 1;
  if (w->pinv[r] >= 0) steps_push(w->heap, nh, w->pinv[r]);
  else w->cx[(*nx)++] = r;
}

/* Factor column j as step k: 1 taken, 0 dependent (nothing kept), -1 OOM.
 * The column's rows split as they are reached (reach): pivoted rows are
 * steps of the L solve, which visits only those (smallest first: L's
 * column s only holds rows pivoted after s) and clears each as it goes
 * (no later L column holds it); unpivoted rows are the pivot candidates
 * (w->cx), cleared with their values kept (w->cv) in one pass at the end;
 * the pivot and L's column come from those. */
static int factor_column(SparseWs *w, int j, int k) {
  int ul = w->ustart[k], ll = w->lstart[k];
  /* room first: U's column k has at most k entries, L's at most m - 1 */
  if (grow_lu(w, ll + w->m, ul + k + 1)) return -1;
  const int *row;
  const double *val;
  int ar, nz = column(w, j, &row, &val, &ar), nh = 0, nx = 0, *heap = w->heap;
  for (int q = 0; q < nz; q++) {
    int r = row[q];
    if (!w->mark[r]) reach(w, r, &nh, &nx);
    w->x[r] += val[q];
  }
  while (nh > 0) {
    int s = heap[--nh], r0 = w->prow[s];
    double v = w->x[r0];
    w->x[r0] = 0.0, w->mark[r0] = 0;
    if (v == 0.0) continue;
    w->uidx[ul] = s, w->uval[ul++] = v;
    for (int q = w->lstart[s]; q < w->lstart[s + 1]; q++) {
      int r = w->lidx[q];
      if (!w->mark[r]) reach(w, r, &nh, &nx);
      w->x[r] -= w->lval[q] * v;
    }
  }
  double big = 0.0;
  int n = 0;
  for (int q = 0; q < nx; q++) {
    int r = w->cx[q];
    double v = w->x[r];
    w->x[r] = 0.0, w->mark[r] = 0;
    if (v == 0.0) continue;
    w->cx[n] = r, w->cv[n++] = v;
    big = US_MAX(big, fabs(v));
  }
  int p = -1;
  if (big > PIV_ABS)
    for (int q = 0; q < n; q++)
      if (fabs(w->cv[q]) >= PIV_REL * big && (p < 0 || w->cx[q] < w->cx[p])) p = q;
  if (p < 0) return 0;
  double piv = w->cv[p];
  w->ustart[k + 1] = ul;
  w->prow[k] = w->cx[p], w->pinv[w->cx[p]] = k, w->uinv[k] = 1.0 / piv;
  for (int q = 0; q < n; q++)
    if (q != p) w->lidx[ll] = w->cx[q], w->lval[ll++] = w->cv[q] * w->uinv[k];
  w->lstart[k + 1] = ll;
  return 1;
}

/* Factorize a basis from the candidate columns w->cand[0 .. nc) (in the
 * order given), completed by artificials: 0, or -1 OOM. */
static int factorize(SparseWs *w, int nc) {
  int m = w->m, k = 0;
  for (int i = 0; i < m; i++) w->pinv[i] = -1;
  for (int j = 0; j < w->n + m; j++) w->where[j] = -1;
  w->lstart[0] = w->ustart[0] = 0;
  w->neta = 0;
  for (int q = 0; q < nc && k < m; q++) {
    int r = factor_column(w, w->cand[q], k);
    if (r < 0) return -1;
    if (r) w->basis[k] = w->cand[q], w->where[w->cand[q]] = k, k++;
  }
  for (int i = 0; i < m && k < m; i++) {
    if (w->pinv[i] >= 0) continue;
    int r = factor_column(w, w->n + i, k); /* e_i on an unpivoted row: always taken */
    if (r < 0) return -1;
    w->basis[k] = w->n + i, w->where[w->n + i] = k, k++;
  }
  return 0;
}

/* Candidate order: by the smallest row each column touches (the region's
 * bodies are numbered from the change down, so upper bodies first). */
static int first_row(const SparseWs *w, int j) {
  const int *row;
  const double *val;
  int ar, nz = column(w, j, &row, &val, &ar), lo = w->m;
  for (int q = 0; q < nz; q++) lo = US_MIN(lo, row[q]);
  return lo;
}

/* Candidates w->cand[0 .. nc), given in increasing column order, into
 * the order of their first rows (ties in column order): a counting sort,
 * O(nc + m) (qsort of the same keys was 3 % of a stack's plan). */
static void order_candidates(SparseWs *w, int nc) {
  int m = w->m, *cnt = w->heap, *first = w->sortkey, *out = w->sortkey + nc;
  for (int i = 0; i <= m + 1; i++) cnt[i] = 0; /* first_row is m for an empty column */
  for (int q = 0; q < nc; q++) cnt[(first[q] = first_row(w, w->cand[q])) + 1]++;
  for (int i = 0; i < m; i++) cnt[i + 1] += cnt[i];
  for (int q = 0; q < nc; q++) out[cnt[first[q]]++] = w->cand[q];
  memcpy(w->cand, out, (size_t)nc * sizeof(int));
}

/* ------------------------------------------------------ FTRAN / BTRAN */

/* out (by position) = B^-1 x, x by row in w->x (cleared on return): the
 * L solve in step order, the U solve backwards, then the etas in order. */
static void solve_x(SparseWs *w, double *out) {
  int m = w->m;
  double *x = w->x;
  for (int s = 0; s < m; s++) {
    double v = x[w->prow[s]];
    if (v == 0.0) continue;
    for (int q = w->lstart[s]; q < w->lstart[s + 1]; q++) x[w->lidx[q]] -= w->lval[q] * v;
  }
  for (int k = m - 1; k >= 0; k--) {
    double v = x[w->prow[k]] * w->uinv[k];
    out[k] = v;
    if (v == 0.0) continue;
    for (int q = w->ustart[k]; q < w->ustart[k + 1]; q++) x[w->prow[w->uidx[q]]] -= w->uval[q] * v;
  }
  memset(x, 0, (size_t)m * sizeof(double));
  for (int t = 0; t < w->neta; t++) {
    int r = w->eta_pos[t];
    double zr = out[r] * w->eta_val[w->eta_start[t]]; /* 1 / the pivot entry, stored first */
    if (zr != 0.0)
      for (int q = w->eta_start[t] + 1; q < w->eta_start[t + 1]; q++) out[w->eta_idx[q]] -= w->eta_val[q] * zr;
    out[r] = zr;
  }
}

/* alpha (by position) = B^-1 column j. */
static void ftran(SparseWs *w, int j, double *out) {
  const int *row;
  const double *val;
  int ar, nz = column(w, j, &row, &val, &ar);
  for (int q = 0; q < nz; q++) w->x[row[q]] += val[q];
  solve_x(w, out);
}

/* The basic values (by position) = B^-1 (rhs - N x_N): the superbasic
 * columns' values taken off the right-hand side. */
static void ftran_rhs(SparseWs *w, const double *rhs, double *out) {
  memcpy(w->x, rhs, (size_t)w->m * sizeof(double));
  for (int j = 0; j < w->n; j++)
    if (w->xn[j] != 0.0)
      for (int q = w->gen.start[j]; q < w->gen.start[j + 1]; q++)
        w->x[w->gen.row[q]] -= w->gen.val[q] * w->xn[j];
  solve_x(w, out);
}

/* y (by row) = B^-T c (c by position; overwritten). */
static void btran(SparseWs *w, double *c, double *y) {
  int m = w->m;
  for (int t = w->neta - 1; t >= 0; t--) {
    double v = c[w->eta_pos[t]];
    for (int q = w->eta_start[t] + 1; q < w->eta_start[t + 1]; q++) v -= w->eta_val[q] * c[w->eta_idx[q]];
    c[w->eta_pos[t]] = v * w->eta_val[w->eta_start[t]];
  }
  double *v = w->z;
  for (int k = 0; k < m; k++) {
    double s = c[k];
    for (int q = w->ustart[k]; q < w->ustart[k + 1]; q++) s -= w->uval[q] * v[w->uidx[q]];
    v[k] = s * w->uinv[k];
  }
  for (int s = m - 1; s >= 0; s--) {
    double t = v[s];
    for (int q = w->lstart[s]; q < w->lstart[s + 1]; q++) t -= w->lval[q] * y[w->lidx[q]];
    y[w->prow[s]] = t;
  }
}

/* Record the basis change at position r (alpha: the entering column). */
static int push_eta(SparseWs *w, int r, const double *alpha) {
  int m = w->m, nz = 1;
  for (int i = 0; i < m; i++) nz += i != r && alpha[i] != 0.0;
  if (w->neta + 2 > w->cap_eta) {
    int c = 2 * w->neta + 16;
    int *p = us_realloc(w->eta_pos, (size_t)c * sizeof(int));
    if (p) w->eta_pos = p;
    int *s = us_realloc(w->eta_start, (size_t)(c + 1) * sizeof(int));
    if (s) w->eta_start = s;
    if (!p || !s) return -1;
    w->cap_eta = c;
  }
  if (w->neta == 0) w->eta_start[0] = 0;
  int a = w->eta_start[w->neta];
  if (grow_store(&w->eta_idx, &w->eta_val, &w->cap_eidx, a + nz)) return -1;
  w->eta_idx[a] = r, w->eta_val[a++] = 1.0 / alpha[r];
  for (int i = 0; i < m; i++)
    if (i != r && alpha[i] != 0.0) w->eta_idx[a] = i, w->eta_val[a++] = alpha[i];
  w->eta_pos[w->neta++] = r;
  w->eta_start[w->neta] = a;
  return 0;
}

/* ------------------------------------------------------------ simplex */

/* Phase-1 costs of the basic values into c; returns the infeasibility w. */
static double phase1_costs(const SparseWs *w, double *c) {
  double inf = 0.0;
  for (int k = 0; k < w->m; k++) {
    double v = w->xb[k];
    int art = w->basis[k] >= w->n;
    c[k] = v < -FEAS_TOL ? -1.0 : art && v > FEAS_TOL ? 1.0 : 0.0;
    inf += c[k] * v;
  }
  return inf;
}

/* The entering column for duals y: the largest gain |d_j| of a column at
 * 0 with d_j < 0 (it rises) or a superbasic one with d_j != 0 (it moves
 * against d_j), or the lowest index with a gain (bland); -1 when none.
 * *dir: +1 the column rises, -1 it falls. */
static int price(const SparseWs *w, const double *y, int bland, int *dir) {
  int pc = -1, nw = w->nw, nb = w->m / nw;
  double most = COST_EPS;
  unsigned char *nzb = w->mark; /* all 0 between uses: the row blocks where y != 0 */
  for (int b = 0; b < nb; b++)
    for (int r = 0; r < nw; r++)
      if (y[b * nw + r] != 0.0) {
        nzb[b] = 1;
        break;
      }
  const int *blk = w->gen.col_blk;
  for (int j = 0; j < w->n; j++) {
    if (w->where[j] >= 0) continue;
    /* a column touches at most two bodies' row blocks (its sides') */
    int b0 = blk[2 * j], b1 = blk[2 * j + 1];
    if (!(b0 >= 0 && nzb[b0]) && !(b1 >= 0 && nzb[b1])) continue;
    double d = 0.0;
    for (int q = w->gen.start[j]; q < w->gen.start[j + 1]; q++) d -= y[w->gen.row[q]] * w->gen.val[q];
    double gain = w->xn[j] > 0.0 ? fabs(d) : -d;
    if (gain > most) {
      pc = j, *dir = d < 0.0 ? 1 : -1;
      if (bland) break;
      most = gain;
    }
  }
  memset(nzb, 0, (size_t)nb);
  return pc;
}

/* The leaving position for the entering column (alpha, moving in
 * direction dir: the basic values change by -dir * step * alpha), its
 * step in *theta; -1 if no basic value reaches a bound. */
static int leaving(const SparseWs *w, const double *alpha, double dir, double *theta) {
  int r = -1, rart = 0;
  double best = INFINITY, rpiv = 0.0;
  for (int k = 0; k < w->m; k++) {
    double a = dir * alpha[k], v = w->xb[k], num;
    if (fabs(a) <= RATIO_PIV) continue;
    int art = w->basis[k] >= w->n;
    if (v < -FEAS_TOL) { /* infeasible below 0: a bound when it rises to 0 */
      if (a > 0) continue;
      num = v;
    } else if (art && v > FEAS_TOL) {
      if (a < 0) continue;
      num = v;
    } else if (art) {
      num = 0.0; /* an artificial at 0 may not move */
    } else {
      if (a < 0) continue;
      num = US_MAX(v, 0.0);
    }
    /* num / a >= 0; divide only when it may beat best (|a| > 0) */
    if (fabs(num) > (best + RATIO_TIE) * fabs(a)) continue;
    double t = num / a;
    int better = t < best - RATIO_TIE ||
                 (t <= best + RATIO_TIE && (art > rart || (art == rart && fabs(a) > rpiv)));
    if (better) best = US_MIN(t, best), r = k, rart = art, rpiv = fabs(a);
  }
  *theta = best;
  return r;
}

/* The current basis's structural columns as candidates, then refactorize
 * and recompute the basic values. */
static int refactor(SparseWs *w, const us_EqSystem *sys) {
  int nc = 0;
  for (int j = 0; j < w->n; j++) /* in column order, as order_candidates wants */
    if (w->where[j] >= 0) w->cand[nc++] = j;
  order_candidates(w, nc);
  if (factorize(w, nc)) return -1;
  ftran_rhs(w, sys->rhs, w->xb);
  return 0;
}

enum { RUN_FEASIBLE = 0, RUN_INFEASIBLE = 1, RUN_LIMIT = 2, RUN_OOM = -1 };

static int run(SparseWs *w, const us_EqSystem *sys) {
  int limit = 4 * w->m + 200, stall = 0;
  for (int it = 0; it < limit; it++) {
    double inf = phase1_costs(w, w->w);
    if (inf <= 0.0) return RUN_FEASIBLE;
    btran(w, w->w, w->ray);
    int dir = 1;
    int pc = price(w, w->ray, stall >= STALL, &dir);
    if (pc < 0) return RUN_INFEASIBLE;
    ftran(w, pc, w->alpha);
    double theta, sd = (double)dir;
    int r = leaving(w, w->alpha, sd, &theta);
    if (dir < 0 && !(theta < w->xn[pc])) { /* it falls to 0 first: a bound flip */
      theta = w->xn[pc];
      for (int k = 0; k < w->m; k++) w->xb[k] += theta * w->alpha[k];
      w->xn[pc] = 0.0;
      stall = 0;
      continue;
    }
    if (r < 0) return RUN_LIMIT;
    for (int k = 0; k < w->m; k++) w->xb[k] -= sd * theta * w->alpha[k];
    w->xb[r] = w->xn[pc] + sd * theta;
    w->xn[pc] = 0.0;
    w->where[w->basis[r]] = -1;
    w->basis[r] = pc, w->where[pc] = r;
    stall = theta == 0.0 ? stall + 1 : 0;
    if (w->neta + 1 >= MAX_ETAS) {
      if (refactor(w, sys)) return RUN_OOM;
    } else if (push_eta(w, r, w->alpha)) {
      return RUN_OOM;
    }
  }
  return RUN_LIMIT;
}

/* max |G l - b| of the basic solution, l into w->cost (clamped at 0). */
static double residual(SparseWs *w, const us_EqSystem *sys) {
  double *l = w->cost, *r = w->x;
  for (int j = 0; j < w->n; j++)
    if (w->where[j] < 0) l[j] = w->xn[j];
  for (int k = 0; k < w->m; k++)
    if (w->basis[k] < w->n) l[w->basis[k]] = US_MAX(w->xb[k], 0.0);
  for (int i = 0; i < w->m; i++) r[i] = -sys->rhs[i];
  for (int j = 0; j < w->n; j++)
    for (int q = w->gen.start[j]; q < w->gen.start[j + 1] && l[j] != 0.0; q++)
      r[w->gen.row[q]] += w->gen.val[q] * l[j];
  double worst = 0.0;
  for (int i = 0; i < w->m; i++) worst = US_MAX(worst, fabs(r[i])), r[i] = 0.0;
  return worst;
}

/* Keep which columns ended basic, for the next solve's start. */
static void save_statuses(SparseWs *w, const us_EqSystem *sys) {
  for (int j = 0; j < w->n; j++) w->was_basic[key_of(w, sys, j)] = w->where[j] >= 0 || w->xn[j] > 0.0;
}

/* Column j's share of the hint's force on its contact (2D): > 0 when the
 * force uses that generator. */
static double hint_share(const SparseWs *w, const us_EqSystem *sys, int j, const double *hint) {
  int ci = w->gen.col_contact[j];
  const double *f = hint + 2 * (size_t)sys->contact[ci];
  double cn = w->gen.col_coef[3 * (size_t)j], ct = w->gen.col_coef[3 * (size_t)j + 1];
  double mu = sys->mu[ci];
  if (mu == 0) return f[0];
  if (isinf(mu)) return ct == 0 ? f[0] : ct * f[1];
  if (ct == 0) return 0.0; /* the normal beside the edges: the edges take it */
  return 0.5 * (f[0] / cn + f[1] / ct);
}

/* The first basis: the hint's columns (2D), else the columns basic when
 * the last solve ended. Hint columns left out of the basis (a force inside
 * its cone takes both edges, so a hint that is no vertex has more columns
 * than rows) stay at their shares as superbasic columns: the start is
 * the hint itself, off balance only where the change is. */
static int start_basis(SparseWs *w, const us_EqSystem *sys, const double *hint) {
  int nc = 0, use_hint = hint && sys->dim == 2, pair[2] = {-2, -2}, in_pair = 0;
  for (int j = 0; j < w->n + w->m; j++) w->xn[j] = 0.0;
  for (int j = 0; j < w->n; j++) {
    double h = use_hint ? hint_share(w, sys, j, hint) : 0.0;
    if (!(use_hint ? h > HINT_SHARE : w->was_basic[key_of(w, sys, j)])) continue;
    if (!use_hint) {
      w->cand[nc++] = j;
      continue;
    }
    /* the columns of the contacts between two bodies span at most nw
       dimensions (both bodies' wrenches are the force at the same points),
       so a pair's hint columns past the first nw are dependent: they stay
       superbasic without a factorization's attempt (40 of 206 candidates
       on regions of 174 rows) */
    const us_Contact *k = &sys->s->contacts[sys->contact[w->gen.col_contact[j]]];
    if (k->a != pair[0] || k->b != pair[1]) pair[0] = k->a, pair[1] = k->b, in_pair = 0;
    w->xn[j] = h;
    if (in_pair++ < sys->nw) w->cand[nc++] = j;
  }
  order_candidates(w, nc);
  if (factorize(w, nc)) return -1;
  for (int k = 0; k < w->m; k++) w->xn[w->basis[k]] = 0.0;
  ftran_rhs(w, sys->rhs, w->xb);
  return 0;
}

static us_Status sparse_solve(void *ws, const us_BackendProblem *pb, us_BackendOut *out,
                              us_Error *err) {
  const us_EqSystem *sys = pb->sys;
  SparseWs *w = ws;
  w->nray = 0;
  w->last_body = -1;
  out->verdict = US_UNDECIDED;
  if (us_eq_generators(sys, w->set.n_column_mu, &w->gen))
    return us_error_set(err, US_ERR_NOMEM, "out of memory building the LP");
  w->m = w->gen.nrow, w->n = w->gen.ncol, w->nw = sys->nw;
  if (w->n == 0) {
    out->verdict = us_eq_no_columns_verdict(sys);
    snprintf(out->note, out->note_sz, "no active contact");
    return US_OK;
  }
  if (!w->was_basic) w->was_basic = us_calloc((size_t)w->nkey + 1, 1);
  if (!w->was_basic || reserve(w, w->m, w->n) || start_basis(w, sys, pb->hint))
    return us_error_set(err, US_ERR_NOMEM, "out of memory in the sparse LP");
  int r = run(w, sys);
  if (r == RUN_OOM) return us_error_set(err, US_ERR_NOMEM, "out of memory in the sparse LP");
  if (r == RUN_LIMIT) {
    snprintf(out->note, out->note_sz, "sparse LP: iteration limit");
    return US_OK;
  }
  if (!(pb->hint && sys->dim == 2)) save_statuses(w, sys); /* a 2D hint is the start */
  if (r == RUN_FEASIBLE) {
    if (residual(w, sys) > RESID_TOL) {
      snprintf(out->note, out->note_sz, "sparse LP: inaccurate");
      return US_OK;
    }
    us_eq_gen_forces(sys, &w->gen, w->cost, out->f);
    out->verdict = US_STABLE;
    snprintf(out->note, out->note_sz, "sparse LP: feasible");
    return US_OK;
  }
  if (pb->no_ray) { /* infeasible as far as phase 1 saw: not proven, no ray
                       kept; where it stopped (basic values clamped at 0) in
                       out->f, a grown region's start (local.c) */
    residual(w, sys);
    us_eq_gen_forces(sys, &w->gen, w->cost, out->f);
    out->verdict = US_UNSTABLE;
    snprintf(out->note, out->note_sz, "sparse LP: infeasible (no ray asked)");
    return US_OK;
  }
  w->last_body = us_eq_gen_farkas_body(sys, &w->gen, w->ray, w->set.farkas_slack);
  if (w->last_body < 0) {
    snprintf(out->note, out->note_sz, "sparse LP: infeasible, ray rejected");
    return US_OK;
  }
  w->nray = w->m;
  out->verdict = US_UNSTABLE;
  snprintf(out->note, out->note_sz, "sparse LP: infeasible (Farkas ray checked)");
  return US_OK;
}

static int sparse_unstable_body(void *ws) { return ((SparseWs *)ws)->last_body; }

static int sparse_farkas_ray(void *ws, const double **y) {
  SparseWs *w = ws;
  *y = w->nray ? w->ray : NULL;
  return w->nray;
}

const us_Backend us_backend_sparse = {
    .method = US_METHOD_LP,
    .create = sparse_create,
    .destroy = sparse_destroy,
    .solve = sparse_solve,
    .unstable_body = sparse_unstable_body,
    .farkas_ray = sparse_farkas_ray,
};
