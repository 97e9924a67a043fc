/* The lp-lcp stability backend: the statics LP of lp_gen.h written as a
 * linear complementarity problem and solved by our own Lemke method on a
 * dense tableau, warm-started from the previous sub-assembly's basis.
 *
 * The LCP. The sub-assembly stands iff some l >= 0 has G l = b (G: the
 * m x n cone-generator matrix, b = sys->rhs). The same set is
 *   { x >= 0 : A x >= c },  A = [G; -1^T G],  c = (b, -1^T b)
 * (G x >= b row by row and a sum of those slacks <= 0 forces every slack
 * to 0): m + 1 inequality rows instead of the 2m of [G; -G]. The KKT
 * conditions of "min 0 s.t. A x >= c, x >= 0" are the LCP
 *   w = M z + q >= 0,  z >= 0,  w . z = 0,
 *   z = (x, y),  M = [[0, -A^T], [A, 0]],  q = (0, -c),
 * of dim = n + m + 1 complementary pairs. Its solutions are the primal-
 * dual optimal pairs of that LP; every feasible x is optimal for the zero
 * objective (with y = 0), so the LCP is solvable iff the LP is feasible,
 * and the x of any solution is feasible. M is skew-symmetric: z^T M z = 0 for
 * every z, so M is positive semidefinite, hence copositive-plus.
 *
 * Lemke's method (lemke.c: covering vector e, lexicographic ratio test,
 * so no basis repeats and the path is finite) therefore ends either with
 * z0 leaving (a solution: the x part is feasible, STABLE) or on a
 * secondary ray (z*, w*, z0*) + t (z^h, w^h, z0^h). On the ray z^h >= 0,
 * z^h != 0 and complementarity gives z^h . w^h = 0 = z^h^T M z^h +
 * z0^h e . z^h, so z0^h = 0 and w^h = M z^h >= 0; with M^T = -M, and
 * w* . z^h = 0,
 *   q . z^h = w* . z^h + z*^T w^h - z0* e . z^h = -z0* e . z^h < 0.
 * Writing z^h = (x^h, y1^h, y0^h): A^T y^h <= 0 and c . y^h > 0, i.e.
 *   u = y1^h - y0^h 1  has  G^T u <= 0  and  b . u > 0,
 * a Farkas ray of G l = b, l >= 0 (UNSTABLE). Every ray is re-checked by
 * us_eq_gen_farkas_body before it is claimed; a ray that fails, a
 * solution whose residual |G x - b| is above 1e-9, the pivot limit, and
 * systems above the size cap (us_LpLcpOptions.max_dim) go to CLP, created
 * lazily in this workspace and counted in info->lp_fallbacks. The front
 * end re-checks stable forces (certificate.h) and the ray's mechanism.
 *
 * Tableau (lemke.h): pairs x_j = j, y_k = n + k (the sum row's y0 last),
 * variables w_i = i, z_i = dim + i, z0 = 2 dim.
 *
 * Reuse. After each run the basic members of z are remembered by
 * identity, not position: x by (structure contact, cone slot), y by (body,
 * wrench component), y0 on its own. The next system starts from the
 * initial tableau (all w basic) and brings back remembered pairs (x_j,
 * y_k) by two pivots each (x_j for w_y_k, then y_k for w_x_j), choosing
 * the largest |pivot| first, as an LU with full pivoting of the
 * remembered block of A; the second pivot equals minus the first because
 * the skew diagonal is 0, so it never fails. Pairs whose pivot is below
 * 1e-7 (a removed body's contacts, rows now unmatched) stay out. The
 * result is a complementary basis whose principal pivot transform M' is
 * again skew-symmetric, so Lemke runs from it on (q', M') with covering
 * vector e in the new coordinates and the argument above holds unchanged
 * (q' . z'^h = q . z^h: for skew M the sum over pairs of w z' + z w' does
 * not depend on which member of a pair is called w). If the start is
 * already feasible Lemke makes no pivot. A warm run that fails (see
 * below) is repeated cold before CLP is asked. Setup pivots count in
 * info->pivots like Lemke's; info->reused counts warm starts.
 *
 * The dimension is a parameter: a body has nw = 3 (2D) or 6 (3D) wrench
 * rows and a contact up to us_eq_gen_slots(dim) column slots, which size
 * the remembered keys. In 3D the front end alternates the inner and outer
 * polygonal cones (docs/cones3d.md) and calls this backend on each, so a
 * basis is remembered per mode; after a refinement a remembered (contact,
 * slot) may name another edge than last time: the warm start is then a
 * worse guess, never a wrong one (any complementary start of the skew LCP
 * keeps the argument above).
 */
#include "lp_lcp.h"

#include "lemke.h"
#include "lp_gen.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define SETUP_EPS 1e-7     /* a warm start's pair needs a pivot above this */
#define RESID_TOL 1e-9     /* a feasible claim's max |G x - b| (b is at most 1) */

typedef struct LpLcpWs {
  const us_Structure *s;
  us_StabilitySettings set;
  us_LpSettings lp;
  us_LpLcpOptions opt;
  us_EqGen gen;
  int n, m, dim;              /* columns and rows of G; pairs n + m + 1 */
  us_Lemke lk;                /* the tableau and Lemke's state */
  int *xl, *yl;               /* scratch of the warm start: [n], [m + 1] */
  double *x, *ray;            /* [n] solution, [m] Farkas ray */
  int cap_xl, cap_yl, cap_x, cap_ray;
  double deadline;
  int nslot, nw;         /* column slots per contact, wrench rows per body */
  int *xstamp, *ystamp; /* remembered bases, one per cone mode (2D: [0]):
                           [2 (nslot ncontact + 1)], [2 (nw nbody + 1)] */
  int stamp[2], have_basis[2];
  int md;               /* the current system's cone mode (3D: 1 outer) */
  int nray, last_body;
  void *clp;     /* CLP workspace, created on the first fallback */
  int by_clp;    /* CLP decided the last test */
  int clp_chain; /* CLP's previous solve was the previous sub-assembly */
} LpLcpWs;

/* ------------------------------------------------------------ workspace */

static void lplcp_destroy(void *ws) {
  LpLcpWs *w = ws;
  if (!w) return;
  us_eq_gen_free(&w->gen);
  us_lemke_free(&w->lk);
  double *d[] = {w->x, w->ray};
  int *i[] = {w->xl, w->yl, w->xstamp, w->ystamp};
  for (size_t k = 0; k < sizeof d / sizeof d[0]; k++) us_free(d[k]);
  for (size_t k = 0; k < sizeof i / sizeof i[0]; k++) us_free(i[k]);
  if (w->clp) us_backend_clp.destroy(w->clp);
  us_free(w);
}

void *us_lp_lcp_create(const us_Structure *s, const us_StabilitySettings *set,
                       const us_LpLcpOptions *opt, us_Error *err) {
  LpLcpWs *w = us_calloc(1, sizeof *w);
  if (w) {
    w->s = s;
    w->set = *set;
    w->lp = us_lp_settings_resolve(&set->lp);
    w->opt = *opt;
    if (w->opt.max_dim <= 0) w->opt.max_dim = US_LP_LCP_MAX_DIM;
    w->last_body = -1;
    w->nslot = us_eq_gen_slots(s->dim);
    w->nw = s->dim == 2 ? 3 : 6;
    w->xstamp = us_calloc(2 * ((size_t)w->nslot * (size_t)s->ncontact + 1), sizeof(int));
    w->ystamp = us_calloc(2 * ((size_t)w->nw * (size_t)s->nbody + 1), sizeof(int));
  }
  if (!w || !w->xstamp || !w->ystamp) {
    lplcp_destroy(w);
    us_error_set(err, US_ERR_NOMEM, "out of memory creating the lp-lcp workspace");
    return NULL;
  }
  return w;
}

static void *lplcp_create(const us_Structure *s, const us_StabilitySettings *set, us_Error *err) {
  us_LpLcpOptions opt = {1, 0};
  return us_lp_lcp_create(s, set, &opt, err);
}

/* Room for a system of n columns and m rows. 0 or -1 (OOM). */
static int lplcp_reserve(LpLcpWs *w, int n, int m) {
  return us_lemke_reserve(&w->lk, n + m + 1) || US_GROW(w->xl, w->cap_xl, n + 1) ||
                 US_GROW(w->yl, w->cap_yl, m + 1) || US_GROW(w->x, w->cap_x, n + 1) ||
                 US_GROW(w->ray, w->cap_ray, m + 1)
             ? -1
             : 0;
}

static void lplcp_set_deadline(void *ws, double deadline) {
  LpLcpWs *w = ws;
  w->deadline = deadline;
  w->lk.deadline = deadline;
  if (w->clp) us_backend_clp.set_deadline(w->clp, deadline);
}

/* -------------------------------------------------------------- tableau */

static double *row_at(const LpLcpWs *w, int r) { return us_lemke_row(&w->lk, r); }

/* Column j of G into the tableau: row x_j holds -A^T's entries (y1, y0),
 * the rows of y hold A's (the sum row: minus the column's sum). */
static void fill_column(LpLcpWs *w, int j) {
  const us_EqGen *g = &w->gen;
  double sum = 0.0, *xr = row_at(w, j);
  for (int k = g->start[j]; k < g->start[j + 1]; k++) {
    xr[w->n + g->row[k]] = -g->val[k];
    row_at(w, w->n + g->row[k])[j] = g->val[k];
    sum += g->val[k];
  }
  xr[w->n + w->m] = sum;
  row_at(w, w->n + w->m)[j] = -sum;
}

/* The starting tableau w = M z + q + e z0: every w basic. */
static void fill_tableau(LpLcpWs *w, const us_EqSystem *sys) {
  us_lemke_clear(&w->lk);
  for (int j = 0; j < w->n; j++) fill_column(w, j);
  double bsum = 0.0;
  for (int r = 0; r < w->m; r++) {
    w->lk.qb[w->n + r] = -sys->rhs[r];
    bsum += sys->rhs[r];
  }
  w->lk.qb[w->n + w->m] = bsum;
}

/* ---------------------------------------------------------------- reuse */

static int x_key(const LpLcpWs *w, const us_EqSystem *sys, int j) {
  int base = w->md * (w->nslot * w->s->ncontact + 1);
  return base + w->nslot * sys->contact[w->gen.col_contact[j]] + us_eq_gen_slot(&w->gen, j);
}

static int y_key(const LpLcpWs *w, const us_EqSystem *sys, int k) {
  int base = w->md * (w->nw * w->s->nbody + 1);
  return base + (k == w->m ? w->nw * w->s->nbody : w->nw * sys->body[k / w->nw] + k % w->nw);
}

/* Remember the basic members of z by identity. */
static void save_basis(LpLcpWs *w, const us_EqSystem *sys) {
  int st = ++w->stamp[w->md];
  for (int j = 0; j < w->n; j++)
    if (w->lk.pos[w->dim + j] >= 0) w->xstamp[x_key(w, sys, j)] = st;
  for (int k = 0; k <= w->m; k++)
    if (w->lk.pos[w->dim + w->n + k] >= 0) w->ystamp[y_key(w, sys, k)] = st;
  w->have_basis[w->md] = 1;
}

/* The remembered x (into cand) and y (into ties) of this system. */
static void remembered(LpLcpWs *w, const us_EqSystem *sys, int *nx, int *ny) {
  *nx = *ny = 0;
  for (int j = 0; j < w->n; j++)
    if (w->xstamp[x_key(w, sys, j)] == w->stamp[w->md]) w->xl[(*nx)++] = j;
  for (int k = 0; k <= w->m; k++)
    if (w->ystamp[y_key(w, sys, k)] == w->stamp[w->md]) w->yl[(*ny)++] = k;
}

/* The remembered pair (cand[bx], ties[by]) with the largest pivot above
 * SETUP_EPS; 0 if none. */
static int best_pair(const LpLcpWs *w, int nx, int ny, int *bx, int *by) {
  double best = SETUP_EPS;
  *bx = *by = -1;
  for (int a = 0; a < ny; a++) {
    const double *row = row_at(w, w->lk.pos[w->n + w->yl[a]]); /* w_y_k is still basic */
    for (int b = 0; b < nx; b++) {
      double v = fabs(row[-w->lk.pos[w->dim + w->xl[b]] - 1]); /* x_j is still nonbasic */
      if (v > best) best = v, *bx = b, *by = a;
    }
  }
  return *bx >= 0;
}

/* Bring the remembered pairs back (file head). *pairs: how many. */
static us_LemkeEnd warm_setup(LpLcpWs *w, const us_EqSystem *sys, int *pairs) {
  int nx, ny, bx, by;
  remembered(w, sys, &nx, &ny);
  *pairs = 0;
  while (best_pair(w, nx, ny, &bx, &by)) {
    us_LemkeEnd e = us_lemke_limits(&w->lk);
    if (e != US_LEMKE_GO) return e;
    int j = w->xl[bx], k = w->yl[by];
    us_lemke_pivot(&w->lk, w->lk.pos[w->n + k], -w->lk.pos[w->dim + j] - 1);                 /* x_j for w_y_k */
    us_lemke_pivot(&w->lk, w->lk.pos[j], -w->lk.pos[w->dim + w->n + k] - 1);                 /* y_k for w_x_j */
    w->xl[bx] = w->xl[--nx];
    w->yl[by] = w->yl[--ny];
    (*pairs)++;
  }
  return US_LEMKE_GO;
}

/* ------------------------------------------------------------- verdicts */

/* The x part of the basic solution into w->x; returns max |G x - b|. */
static double read_solution(LpLcpWs *w, const us_EqSystem *sys) {
  for (int j = 0; j < w->n; j++) w->x[j] = US_MAX(us_lemke_value(&w->lk, w->dim + j), 0.0);
  double *r = w->ray; /* scratch: no ray on this path */
  for (int i = 0; i < w->m; i++) r[i] = -sys->rhs[i];
  for (int j = 0; j < w->n; j++)
    for (int k = w->gen.start[j]; k < w->gen.start[j + 1]; k++)
      r[w->gen.row[k]] += w->gen.val[k] * w->x[j];
  double worst = 0.0;
  for (int i = 0; i < w->m; i++) worst = US_MAX(worst, fabs(r[i]));
  return worst;
}

/* u = y1^h - y0^h 1 into w->ray (file head). */
static void read_ray(LpLcpWs *w, int s) {
  int y = w->dim + w->n;
  double y0 = us_lemke_ray_dir(&w->lk, y + w->m, s);
  for (int k = 0; k < w->m; k++) w->ray[k] = us_lemke_ray_dir(&w->lk, y + k, s) - y0;
}

/* CLP decides (created lazily); chained to its own previous solve when
 * that was the previous sub-assembly, so its basis reuse still works. */
static us_Status clp_decide(LpLcpWs *w, const us_EqSystem *sys, const int *added, int nadded,
                            const int *removed, int nremoved, int chain, us_Verdict *verdict,
                            double *f, us_StabilityInfo *info, const char *why, char *note,
                            size_t note_sz, us_Error *err) {
  static const int none = -1; /* non-NULL lists: a sub-assembly, not a region system */
  if (!w->clp) {
    w->clp = us_backend_clp.create(w->s, &w->set, err);
    if (!w->clp) return err ? err->code : US_ERR_NOMEM;
    us_backend_clp.set_deadline(w->clp, w->deadline);
  }
  char sub[96] = "";
  us_BackendProblem pb = {sys, chain && added ? added : &none, chain ? nadded : 0,
                          chain && removed ? removed : &none, chain ? nremoved : 0, !chain, NULL, 0};
  us_BackendOut out = {*verdict, f, info, sub, sizeof sub};
  us_Status st = us_backend_clp.solve(w->clp, &pb, &out, err);
  *verdict = out.verdict;
  if (st) return st;
  info->lp_fallbacks++;
  w->by_clp = w->clp_chain = 1;
  snprintf(note, note_sz, "lp-lcp %s; LP: %s", why, sub);
  return US_OK;
}

/* A solution: STABLE if its residual is small, else CLP decides. */
static int accept_solution(LpLcpWs *w, const us_EqSystem *sys, us_Verdict *verdict, double *f,
                           char *note, size_t note_sz, long piv, int pairs) {
  double res = read_solution(w, sys);
  if (res > RESID_TOL) return 0;
  us_eq_gen_forces(sys, &w->gen, w->x, f);
  *verdict = US_STABLE;
  save_basis(w, sys);
  snprintf(note, note_sz, "lp-lcp: feasible after %ld pivots (%s, residual %.1e)", piv,
           pairs ? "warm" : "cold", res);
  return 1;
}

/* A secondary ray: UNSTABLE if its Farkas ray checks, else CLP decides. */
static int accept_ray(LpLcpWs *w, const us_EqSystem *sys, int s, us_Verdict *verdict, char *note,
                      size_t note_sz, long piv, int pairs) {
  read_ray(w, s);
  w->last_body = us_eq_gen_farkas_body(sys, &w->gen, w->ray, w->lp.farkas_slack);
  if (w->last_body < 0) return 0;
  w->nray = w->m;
  *verdict = US_UNSTABLE;
  save_basis(w, sys);
  snprintf(note, note_sz, "lp-lcp: secondary ray after %ld pivots (%s, Farkas ray checked)", piv,
           pairs ? "warm" : "cold");
  return 1;
}

/* Tableau, warm start when allowed, Lemke. */
static us_LemkeEnd run(LpLcpWs *w, const us_EqSystem *sys, int restart, int *pairs,
                       int *ray_col) {
  fill_tableau(w, sys);
  *pairs = 0;
  if (w->opt.reuse && w->have_basis[w->md] && !restart) {
    us_LemkeEnd e = warm_setup(w, sys, pairs);
    if (e != US_LEMKE_GO) return e;
  }
  return us_lemke_run(&w->lk, ray_col);
}

/* One run (cold, or warm when allowed) and its verdict: 1 decided or
 * stopped by the deadline, 0 not (*why says why; *warm: it was warm). */
static int try_run(LpLcpWs *w, const us_EqSystem *sys, int cold, us_Verdict *verdict, double *f,
                   us_StabilityInfo *info, char *note, size_t note_sz, const char **why,
                   int *warm) {
  long piv0 = w->lk.pivots;
  w->lk.limit = piv0 + (w->set.max_pivots > 0 ? w->set.max_pivots
                                           : us_lemke_default_limit(w->dim));
  int pairs = 0, ray_col = -1;
  us_LemkeEnd e = run(w, sys, cold, &pairs, &ray_col);
  long piv = w->lk.pivots - piv0;
  info->pivots += piv;
  info->reused += pairs > 0;
  *warm = pairs > 0;
  if (e == US_LEMKE_TIME) {
    snprintf(note, note_sz, "lp-lcp: time limit");
    return 1;
  }
  if (e == US_LEMKE_SOLVED && accept_solution(w, sys, verdict, f, note, note_sz, piv, pairs)) return 1;
  if (e == US_LEMKE_RAY && accept_ray(w, sys, ray_col, verdict, note, note_sz, piv, pairs)) return 1;
  *why = e == US_LEMKE_LIMIT       ? "hit the pivot limit"
         : e == US_LEMKE_RAY       ? "ray rejected"
         : e == US_LEMKE_NONFINITE ? "non-finite values"
                                   : "solution inaccurate";
  return 0;
}

static us_Status lplcp_solve(void *ws, const us_BackendProblem *pb, us_BackendOut *out,
                             us_Error *err) {
  /* the problem and the output under the names the body reads */
  const us_EqSystem *sys = pb->sys;
  const int *added = pb->added, *removed = pb->removed;
  int nadded = pb->nadded, nremoved = pb->nremoved, restart = pb->restart;
  us_Verdict *verdict = &out->verdict;
  double *f = out->f;
  us_StabilityInfo *info = out->info;
  char *note = out->note;
  size_t note_sz = out->note_sz;
  LpLcpWs *w = ws;
  int chain = w->clp_chain && !restart;
  w->nray = w->by_clp = w->clp_chain = 0;
  w->md = sys->cones && sys->cones->mode == US_CONE_OUTER; /* a basis per cone mode */
  w->last_body = -1;
  *verdict = US_UNDECIDED;
  if (us_eq_generators(sys, w->lp.n_column_mu, &w->gen)) return us_error_set(err, US_ERR_NOMEM, "out of memory building the LP");
  w->n = w->gen.ncol, w->m = w->gen.nrow, w->dim = w->n + w->m + 1;
  if (w->n == 0) {
    *verdict = us_eq_no_columns_verdict(sys);
    snprintf(note, note_sz, "no active contact");
    return US_OK;
  }
  if (w->deadline > 0 && us_now() >= w->deadline) {
    snprintf(note, note_sz, "lp-lcp: time limit");
    return US_OK;
  }
  if (w->dim > w->opt.max_dim)
    return clp_decide(w, sys, added, nadded, removed, nremoved, chain, verdict, f, info,
                      "over the size cap", note, note_sz, err);
  if (lplcp_reserve(w, w->n, w->m))
    return us_error_set(err, US_ERR_NOMEM, "out of memory building the lp-lcp tableau");
  const char *why = "";
  int warm = 0;
  if (try_run(w, sys, restart, verdict, f, info, note, note_sz, &why, &warm)) return US_OK;
  if (warm && try_run(w, sys, 1, verdict, f, info, note, note_sz, &why, &warm)) return US_OK;
  w->have_basis[w->md] = 0; /* a failed run's basis is no start */
  return clp_decide(w, sys, added, nadded, removed, nremoved, chain, verdict, f, info, why, note,
                    note_sz, err);
}

static int lplcp_unstable_body(void *ws) {
  LpLcpWs *w = ws;
  return w->by_clp ? us_backend_clp.unstable_body(w->clp) : w->last_body;
}

static int lplcp_farkas_ray(void *ws, const double **y) {
  LpLcpWs *w = ws;
  if (w->by_clp) return us_backend_clp.farkas_ray(w->clp, y);
  *y = w->nray ? w->ray : NULL;
  return w->nray;
}

const us_Backend us_backend_lp_lcp = {
    .method = US_METHOD_LP_LCP,
    .create = lplcp_create,
    .destroy = lplcp_destroy,
    .solve = lplcp_solve,
    .unstable_body = lplcp_unstable_body,
    .set_deadline = lplcp_set_deadline,
    .farkas_ray = lplcp_farkas_ray,
};
