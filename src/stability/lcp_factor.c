/* The clamped system of the LCP solver, kept factorized as a block LU:
 * a sparse LU of a base matrix K0 (SuiteSparse's KLU) plus a small border
 * whose Schur complement is a dense inverse (lcp_dense.c). Memory follows
 * the non-zeros of the members' rows (contacts couple only through shared
 * bodies) plus n0 x (border size), not k^2.
 *
 * The system. Members are the clamped indices (row a_i = 0, i.e. the row
 * A_{i,members}) and the frictions at their bound (row f_t - s mu f_n = 0);
 * the unknowns are the members' forces. Slots 0..k-1 order the members
 * (mem, pos), as the solver sees them. This file owns the member list and
 * each member's row; the solver says which row a member brings when it
 * joins, and gets back the members a refactorization found dependent.
 *
 * Block LU (Gill, Murray, Saunders and Wright's bordering, as in block-LU
 * updates of the simplex basis). At a refactorization the members become
 * the base: K0 = K, factorized sparsely, border empty. Later changes border
 * it, never refactorizing per pivot:
 *   an index joins: an ADD item, border column u (its column of K over the
 *     base rows), row v (its row over the base columns), corner entries;
 *   a base member leaves: a DEL item, column e_i (a free slack absorbs row
 *     i) and row e_i^T (forces x_i = 0), so K0 still serves;
 *   an ADD item leaves: its row and column leave the border.
 * The augmented matrix G = [K0 U; V^T D] is K up to those slacks, and with
 * Y = K0^-1 U (a dense column y_b per item) the Schur complement is
 * S = D - V^T Y, kept as the dense inverse S^-1 (bordering and Schur
 * deletion). A solve K x = r is then one sparse solve with K0, O(n0 m) for
 * the border and O(m^2) with S^-1. The Schur pivot of an append equals the
 * pivot of K itself (alpha - v^T K^-1 u), so tiny-pivot refusals mean what
 * they meant with a dense inverse.
 * When the border grows past `border_limit` items (or the changes since
 * the last refactorization past update_per_member * k + update_base) the
 * members are refactorized;
 * while the base is empty every member is an ADD item and S^-1 = K^-1
 * (small problems never refactorize).
 * Invariants: bpos[i] >= 0 (base slot) or ipos[i] >= 0 (border item) for
 * each member i, never both; a base slot whose member left is `gone` and
 * has a DEL item; the dense inverse has one row per item, in item order.
 */
#include "lcp_factor.h"

#include "core/core.h"

#include <math.h>
#include <string.h>
#include <suitesparse/klu.h>
#include <threads.h>

typedef struct Klu {
  klu_common c;
  klu_symbolic *sym;
  klu_numeric *num;
} Klu;

/* SuiteSparse allocates through our funnel (leak checks, OOM tests). Its
 * allocator is SuiteSparse's one global: set once, whatever the threads
 * (writing it at every factor's set-up was a data race). */
static void set_klu_allocator(void) {
  SuiteSparse_config.malloc_func = us_malloc;
  SuiteSparse_config.calloc_func = us_calloc;
  SuiteSparse_config.realloc_func = us_realloc;
  SuiteSparse_config.free_func = us_free;
}

static once_flag klu_once = ONCE_FLAG_INIT;

static void klu_allocator(void) { call_once(&klu_once, set_klu_allocator); }

/* ------------------------------------------------------------ life cycle */

us_LcpFactorSettings us_lcp_factor_default_settings(void) {
  us_LcpFactorSettings s = {64, 4, 64, 1e-9, 1e-300};
  return s;
}

int us_lcp_fac_init(us_LcpFactor *F, int n, const us_LcpOps *ops, const us_LcpFactorSettings *set) {
  memset(F, 0, sizeof *F);
  klu_allocator();
  F->n = n;
  F->ops = *ops;
  F->set = set ? *set : us_lcp_factor_default_settings();
  size_t m = (size_t)(n > 0 ? n : 1);
  F->pos = us_malloc(m * sizeof(int));
  F->row = us_calloc(m, 1);
  F->bcoef = us_calloc(m, sizeof(double));
  F->bnorm = us_malloc(m * sizeof(int));
  F->bound_of = us_malloc(m * sizeof(int));
  F->bpos = us_malloc(m * sizeof(int));
  F->ipos = us_malloc(m * sizeof(int));
  F->col = us_calloc(m, sizeof(double));
  F->out = us_malloc(m * sizeof(int));
  Klu *K = us_calloc(1, sizeof *K);
  F->klu = K;
  if (!F->pos || !F->row || !F->bcoef || !F->bnorm || !F->bound_of || !F->bpos || !F->ipos || !F->col ||
      !F->out || !K)
    return -1;
  for (int i = 0; i < n; i++) F->pos[i] = F->bound_of[i] = F->bpos[i] = F->ipos[i] = -1;
  klu_defaults(&K->c);
  return us_lcp_fac_reserve(F, 8);
}

static void free_base(us_LcpFactor *F) {
  Klu *K = F->klu;
  if (K) {
    if (K->num) klu_free_numeric(&K->num, &K->c);
    if (K->sym) klu_free_symbolic(&K->sym, &K->c);
  }
  us_free(F->bidx);
  us_free(F->gone);
  us_free(F->x0);
  F->bidx = NULL;
  F->gone = NULL;
  F->x0 = NULL;
  F->n0 = 0;
}

static void free_item(us_LcpFactor *F, int b) {
  us_free(F->y[b]);
  us_free(F->vi[b]);
  us_free(F->vx[b]);
  F->y[b] = NULL;
  F->vi[b] = NULL;
  F->vx[b] = NULL;
  F->vn[b] = 0;
}

/* Empty the border and the base; the members stay (slots unchanged). */
static void clear(us_LcpFactor *F) {
  for (int b = 0; b < F->m; b++) {
    if (F->item[b] >= 0) F->ipos[F->item[b]] = -1;
    free_item(F, b);
  }
  for (int j = 0; j < F->n0; j++)
    if (!F->gone[j]) F->bpos[F->bidx[j]] = -1;
  F->m = 0;
  F->S.k = 0;
  F->updates = 0;
  free_base(F);
}

void us_lcp_fac_free(us_LcpFactor *F) {
  if (F->bpos && F->ipos) clear(F);
  void *arrs[] = {F->klu, F->mem, F->pos,  F->row, F->bcoef, F->bnorm, F->bound_of, F->bpos, F->ipos,
                  F->item, F->y,  F->vi,   F->vx,  F->vn,    F->w,        F->uc,   F->vr,
                  F->col,  F->out};
  for (size_t i = 0; i < sizeof arrs / sizeof arrs[0]; i++) us_free(arrs[i]);
  us_dinv_free(&F->S);
  memset(F, 0, sizeof *F);
}

/* The row of member idx (bound_normal < 0: clamped). */
static void set_row(us_LcpFactor *F, int idx, int bound_normal, double coef) {
  F->row[idx] = bound_normal < 0 ? US_LCP_ROW_CLAMP : US_LCP_ROW_BOUND;
  if (bound_normal < 0) return;
  F->bcoef[idx] = coef;
  F->bnorm[idx] = bound_normal;
  F->bound_of[bound_normal] = idx;
}

/* Index c is no longer a member: forget its row. */
static void unset_row(us_LcpFactor *F, int c) {
  if (F->row[c] == US_LCP_ROW_BOUND) F->bound_of[F->bnorm[c]] = -1;
  F->row[c] = US_LCP_ROW_NONE;
  F->pos[c] = -1;
}

void us_lcp_fac_reset(us_LcpFactor *F) {
  clear(F);
  for (int s = 0; s < F->k; s++) unset_row(F, F->mem[s]);
  F->k = 0;
}

int us_lcp_fac_reserve(us_LcpFactor *F, int need) {
  if (need <= F->cap) return 0;
  int cap = US_MAX(US_MAX(need, 2 * F->cap), 8);
  int *mem = us_realloc(F->mem, (size_t)cap * sizeof(int));
  if (!mem) return -1;
  F->mem = mem;
  F->cap = cap;
  return 0;
}

/* Room for one more border item. */
static int reserve_item(us_LcpFactor *F) {
  if (F->m < F->mcap) return 0;
  int cap = US_MAX(2 * F->mcap, 16);
  void **arrs[7] = {(void **)&F->item, (void **)&F->y, (void **)&F->vi, (void **)&F->vx,
                    (void **)&F->vn, (void **)&F->w, (void **)&F->uc};
  size_t sz[7] = {sizeof(int),    sizeof(double *), sizeof(int *), sizeof(double *),
                  sizeof(int),    sizeof(double),   sizeof(double)};
  for (int a = 0; a < 7; a++) {
    void *x = us_realloc(*arrs[a], (size_t)cap * sz[a]);
    if (!x) return -1;
    *arrs[a] = x;
  }
  double *vr = us_realloc(F->vr, (size_t)cap * sizeof(double));
  if (!vr) return -1;
  F->vr = vr;
  for (int b = F->mcap; b < cap; b++) {
    F->y[b] = NULL;
    F->vi[b] = NULL;
    F->vx[b] = NULL;
    F->vn[b] = 0;
  }
  F->mcap = cap;
  return us_dinv_reserve(&F->S, cap);
}

/* ------------------------------------------------------------ base solves */

/* x (n0) := K0^-1 x. 0, or -1 if KLU failed. */
static int base_solve(us_LcpFactor *F, double *x) {
  if (F->n0 == 0) return 0;
  Klu *K = F->klu;
  return klu_solve(K->sym, K->num, F->n0, 1, x, &K->c) ? 0 : -1;
}

/* A fresh n0-vector K0^-1 (sum over the given base entries), or NULL
 * (n0 == 0 gives NULL too: nothing to store). *fail on OOM. */
static double *base_column(us_LcpFactor *F, const int *idx, const double *val, int nnz,
                           int *fail) {
  *fail = 0;
  if (F->n0 == 0) return NULL;
  double *y = us_calloc((size_t)F->n0, sizeof(double));
  if (!y) {
    *fail = 1;
    return NULL;
  }
  for (int t = 0; t < nnz; t++) y[idx[t]] += val[t];
  if (base_solve(F, y)) {
    us_free(y);
    *fail = 1;
    return NULL;
  }
  return y;
}

static double sparse_dot(const int *vi, const double *vx, int vn, const double *x) {
  double s = 0.0;
  for (int t = 0; t < vn; t++) s += vx[t] * x[vi[t]];
  return s;
}

/* v_b^T x for border item b over the base (x has n0 entries). */
static double item_row_dot(const us_LcpFactor *F, int b, const double *x) {
  if (F->item[b] < 0) return x[-1 - F->item[b]];
  return sparse_dot(F->vi[b], F->vx[b], F->vn[b], x);
}

/* ---------------------------------------------------------------- solves */

void us_lcp_fac_solve(us_LcpFactor *F, const double *r, double *x) {
  double *x0 = F->x0;
  if (F->n0 > 0) {
    memset(x0, 0, (size_t)F->n0 * sizeof(double));
    for (int s = 0; s < F->k; s++) {
      int c = F->mem[s];
      if (F->bpos[c] >= 0) x0[F->bpos[c]] = r[s];
    }
    (void)base_solve(F, x0); /* cannot fail once factorized */
  }
  for (int b = 0; b < F->m; b++) {
    double rb = F->item[b] >= 0 ? r[F->pos[F->item[b]]] : 0.0;
    F->w[b] = rb - (F->n0 > 0 ? item_row_dot(F, b, x0) : 0.0);
  }
  us_dinv_mult(&F->S, F->w, F->uc);
  for (int b = 0; b < F->m; b++) {
    double xb = F->uc[b];
    const double *y = F->y[b];
    if (xb != 0.0 && y)
      for (int j = 0; j < F->n0; j++) x0[j] -= xb * y[j];
  }
  for (int s = 0; s < F->k; s++) {
    int c = F->mem[s];
    x[s] = F->bpos[c] >= 0 ? x0[F->bpos[c]] : F->uc[F->ipos[c]];
  }
}

/* --------------------------------------------------------------- updates */

/* Border entries of a new item q with base column y_q and base row
 * (qi, qx, qn) (NULL qi: the DEL row e_{qdel}); du / dv give the corner
 * entries D(b, q) / D(q, b) of ADD items (NULL: zero). */
static void border_entries(us_LcpFactor *F, const double *yq, const int *qi, const double *qx, int qn,
                           int qdel, const double *du, const double *dv) {
  for (int b = 0; b < F->m; b++) {
    int add = F->item[b] >= 0, sb = add ? F->pos[F->item[b]] : -1;
    double vb_yq = yq ? item_row_dot(F, b, yq) : 0.0;
    double vq_yb = 0.0;
    if (F->y[b]) vq_yb = qi ? sparse_dot(qi, qx, qn, F->y[b]) : F->y[b][qdel];
    F->uc[b] = (add && du ? du[sb] : 0.0) - vb_yq;
    F->vr[b] = (add && dv ? dv[sb] : 0.0) - vq_yb;
  }
}

/* Push the prepared item (uc / vr hold its border entries). */
static int push_item(us_LcpFactor *F, int code, double *yq, int *qi, double *qx, int qn,
                     double alpha, double tol) {
  int r = us_dinv_append(&F->S, F->uc, F->vr, alpha, tol);
  if (r) {
    us_free(yq);
    us_free(qi);
    us_free(qx);
    return r;
  }
  int b = F->m++;
  F->item[b] = code;
  F->y[b] = yq;
  F->vi[b] = qi;
  F->vx[b] = qx;
  F->vn[b] = qn;
  if (code >= 0) F->ipos[code] = b;
  F->updates++;
  return 0;
}

int us_lcp_fac_append(us_LcpFactor *F, int idx, int bound_normal, double coef, const double *u,
                      const double *v, double alpha, double tol) {
  if (us_lcp_fac_reserve(F, F->k + 1) || reserve_item(F)) return -1;
  /* base parts of u (dense solve) and v (kept sparse) */
  int nu = 0, nv = 0;
  int *qi = NULL;
  double *qx = NULL;
  if (F->n0 > 0) {
    qi = us_malloc((size_t)F->k * 2 * sizeof(int));
    qx = us_malloc((size_t)F->k * 2 * sizeof(double));
    if (!qi || !qx) {
      us_free(qi);
      us_free(qx);
      return -1;
    }
    for (int s = 0; s < F->k; s++) { /* u entries first, at the back half */
      int j = F->bpos[F->mem[s]];
      if (j < 0) continue;
      if (u[s] != 0.0) {
        qi[F->k + nu] = j;
        qx[F->k + nu++] = u[s];
      }
      if (v[s] != 0.0) {
        qi[nv] = j;
        qx[nv++] = v[s];
      }
    }
  }
  int fail;
  double *yq = base_column(F, qi ? qi + F->k : NULL, qx ? qx + F->k : NULL, nu, &fail);
  if (fail) {
    us_free(qi);
    us_free(qx);
    return -1;
  }
  if (qi) { /* keep only the row part (a shrink cannot fail) */
    int *ti = us_realloc(qi, (size_t)US_MAX(nv, 1) * sizeof(int));
    if (ti) qi = ti;
    double *tx = us_realloc(qx, (size_t)US_MAX(nv, 1) * sizeof(double));
    if (tx) qx = tx;
  }
  border_entries(F, yq, qi, qx, nv, -1, u, v);
  double a = alpha - (yq ? sparse_dot(qi, qx, nv, yq) : 0.0);
  int r = push_item(F, idx, yq, qi, qx, nv, a, tol);
  if (r) return r;
  us_lcp_fac_enlist(F, idx, bound_normal, coef);
  return 0;
}

void us_lcp_fac_enlist(us_LcpFactor *F, int idx, int bound_normal, double coef) {
  F->mem[F->k] = idx;
  F->pos[idx] = F->k++;
  set_row(F, idx, bound_normal, coef);
}

/* Drop slot s from the slot list (the last member moves into s). */
static void drop_slot(us_LcpFactor *F, int s) {
  int L = F->k - 1, c = F->mem[s];
  F->mem[s] = F->mem[L];
  F->pos[F->mem[s]] = s;
  unset_row(F, c);
  F->k = L;
}

/* A base member leaves: a DEL item. 0, 1 singular, -1 OOM. */
static int delete_base(us_LcpFactor *F, int c) {
  if (reserve_item(F)) return -1;
  int i = F->bpos[c], fail;
  double one = 1.0;
  double *yq = base_column(F, &i, &one, 1, &fail);
  if (fail) return -1;
  border_entries(F, yq, NULL, NULL, 0, i, NULL, NULL);
  int r = push_item(F, -1 - i, yq, NULL, NULL, 0, -yq[i], F->set.singular_pivot);
  if (r) return r;
  F->gone[i] = 1;
  F->bpos[c] = -1;
  return 0;
}

/* An ADD item leaves the border. 0, or 1 if the rest looks singular. */
static int delete_item(us_LcpFactor *F, int b) {
  int L = F->m - 1, bad = us_dinv_delete(&F->S, b, F->set.singular_pivot);
  F->ipos[F->item[b]] = -1;
  free_item(F, b);
  if (b != L) {
    F->item[b] = F->item[L];
    F->y[b] = F->y[L];
    F->vi[b] = F->vi[L];
    F->vx[b] = F->vx[L];
    F->vn[b] = F->vn[L];
    F->y[L] = NULL;
    F->vi[L] = NULL;
    F->vx[L] = NULL;
    F->vn[L] = 0;
    if (F->item[b] >= 0) F->ipos[F->item[b]] = b;
  }
  F->m = L;
  F->updates++;
  return bad;
}

int us_lcp_fac_delete(us_LcpFactor *F, int s, int *dep, int *ndep) {
  int c = F->mem[s], r;
  *ndep = 0;
  if (F->bpos[c] >= 0) {
    r = delete_base(F, c);
    if (r < 0) return -1;
    if (r > 0) clear(F); /* refused: rebuilt below */
  } else {
    r = delete_item(F, F->ipos[c]);
  }
  drop_slot(F, s);
  if (r > 0) { /* the rest looks singular: refactorize it from the members */
    *ndep = us_lcp_fac_rebuild(F, dep);
    return *ndep < 0 ? -1 : 1;
  }
  return r;
}

/* ------------------------------------------------------ refactorization */

/* Column j of K (member c in slot j) into (ri, rx); returns the count.
 * Clamped rows come from A's column through the operator, bound rows
 * from their definition (1 at the friction, coef at its normal). */
static int k_column(us_LcpFactor *F, int c, int *ri, double *rx) {
  double one = 1.0;
  int nout = F->ops.apply(F->ops.ctx, &c, &one, 1, F->col, F->out), n = 0;
  for (int t = 0; t < nout; t++) {
    int i = F->out[t];
    if (F->pos[i] >= 0 && F->row[i] == US_LCP_ROW_CLAMP && F->col[i] != 0.0) {
      ri[n] = F->pos[i];
      rx[n++] = F->col[i];
    }
    F->col[i] = 0.0;
  }
  if (F->row[c] == US_LCP_ROW_BOUND) {
    ri[n] = F->pos[c];
    rx[n++] = 1.0;
  }
  int t = F->bound_of[c];
  if (t >= 0) {
    ri[n] = F->pos[t];
    rx[n++] = F->bcoef[t];
  }
  for (int a = 1; a < n; a++) /* insertion sort by row: columns are short */
    for (int b = a; b > 0 && ri[b - 1] > ri[b]; b--) {
      int ti = ri[b];
      ri[b] = ri[b - 1];
      ri[b - 1] = ti;
      double tx = rx[b];
      rx[b] = rx[b - 1];
      rx[b - 1] = tx;
    }
  return n;
}

/* K over the members in compressed columns. 0 or -1 (OOM). */
static int assemble(us_LcpFactor *F, int **Ap, int **Ai, double **Ax) {
  int k = F->k, cap = 8 * k + 8, nnz = 0;
  *Ap = us_malloc((size_t)(k + 1) * sizeof(int));
  *Ai = us_malloc((size_t)cap * sizeof(int));
  *Ax = us_malloc((size_t)cap * sizeof(double));
  if (!*Ap || !*Ai || !*Ax) return -1;
  (*Ap)[0] = 0;
  for (int j = 0; j < k; j++) {
    int need = nnz + F->n + 2; /* a column lists at most n + 2 rows */
    if (need > cap) {
      cap = US_MAX(2 * cap, need);
      int *ai = us_realloc(*Ai, (size_t)cap * sizeof(int));
      if (ai) *Ai = ai;
      double *ax = us_realloc(*Ax, (size_t)cap * sizeof(double));
      if (ax) *Ax = ax;
      if (!ai || !ax) return -1;
    }
    nnz += k_column(F, F->mem[j], *Ai + nnz, *Ax + nnz);
    (*Ap)[j + 1] = nnz;
  }
  return 0;
}

/* Members whose pivot in the fresh factorization is tiny (|U_jj| of the
 * row-scaled matrix <= tol; KLU keeps its column order, so U_jj belongs to
 * column Q[j]): (nearly) dependent on the others, as a tiny Schur pivot
 * would have shown on arrival. Their member indices go to out[]. */
static int tiny_pivots(us_LcpFactor *F, Klu *K, double tol, int *out) {
  const double *ud = K->num->Udiag;
  int n = 0;
  for (int j = 0; j < F->k; j++)
    if (!(fabs(ud[j]) > tol)) out[n++] = F->mem[K->sym->Q[j]];
  return n;
}

/* Factorize K over the members as the new base. 0, -1 OOM, or the number
 * of members found (nearly) dependent, listed in bad[] (nothing kept). */
static int factor(us_LcpFactor *F, int *bad) {
  Klu *K = F->klu;
  int k = F->k, *Ap = NULL, *Ai = NULL, r = -1;
  double *Ax = NULL;
  clear(F);
  if (k == 0) return 0;
  F->bidx = us_malloc((size_t)k * sizeof(int));
  F->gone = us_calloc((size_t)k, 1);
  F->x0 = us_malloc((size_t)k * sizeof(double));
  if (!F->bidx || !F->gone || !F->x0 || assemble(F, &Ap, &Ai, &Ax)) goto done;
  K->sym = klu_analyze(k, Ap, Ai, &K->c);
  if (K->sym) K->num = klu_factor(Ap, Ai, Ax, K->sym, &K->c);
  if (!K->num) {
    if (K->c.status == KLU_SINGULAR) {
      int j = K->c.singular_col >= 0 && K->c.singular_col < k ? K->c.singular_col : k - 1;
      bad[0] = F->mem[j];
      r = 1;
    }
    goto done;
  }
  r = tiny_pivots(F, K, F->set.tiny_lu_pivot, bad);
  if (r) goto done;
  F->n0 = k;
  for (int j = 0; j < k; j++) {
    F->bidx[j] = F->mem[j];
    F->bpos[F->mem[j]] = j;
  }
  F->refactors++;
done:
  us_free(Ap);
  us_free(Ai);
  us_free(Ax);
  if (r) free_base(F);
  return r;
}

int us_lcp_fac_rebuild(us_LcpFactor *F, int *dep) {
  int total = 0;
  for (;;) {
    int nbad = factor(F, dep + total);
    if (nbad < 0) return -1;
    if (nbad == 0) return total;
    /* (nearly) dependent members leave, as if refused on arrival */
    for (int j = 0; j < nbad; j++) drop_slot(F, F->pos[dep[total + j]]);
    total += nbad;
  }
}

int us_lcp_fac_stale(const us_LcpFactor *F) {
  return F->m > F->set.border_limit ||
         F->updates > (long)F->set.update_per_member * F->k + F->set.update_base;
}

/* Bytes held by the factorization (for benchmarks and memory reports):
 * the LU entries (value and index) with the off-diagonal blocks, the
 * border columns Y and rows, and the dense inverse of the border. */
double us_lcp_fac_bytes(const us_LcpFactor *F, long *lu_nnz) {
  const Klu *K = F->klu;
  long nnz = 0;
  if (K && K->num) nnz = (long)K->num->lnz + K->num->unz + K->num->nzoff;
  if (lu_nnz) *lu_nnz = nnz;
  double bytes = 12.0 * (double)nnz + 13.0 * F->n0;
  for (int b = 0; b < F->m; b++) bytes += 8.0 * (F->y[b] ? F->n0 : 0) + 12.0 * F->vn[b];
  return bytes + 8.0 * F->S.cap * F->S.cap;
}
