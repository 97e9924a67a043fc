/* The LCP solver of the LCP stability backends: Baraff's contact-force
 * algorithm (1994), i.e. Dantzig's principal pivoting driven one index at a
 * time, with 2D static friction whose bound moves with the normal force.
 *
 * Algorithm. Live indices are in one of the sets of lcp.h. A drive takes
 * one violated index d and moves its force f_d in the direction that
 * brings a_d towards 0 (normals: up from 0 when a_d < 0; frictions:
 * -sign(a_t)), while every member of the clamped system keeps its row
 * satisfied: the members' increments solve K df = -(A_{.,d} dd) with the
 * factorized K (lcp_factor.c). The step is the smallest of
 *   the driven a_d reaching 0 (d joins the system),
 *   the driven friction reaching its bound +-mu f_n (joins as a bound row),
 *   a clamped normal force reaching 0 (C -> NC),
 *   a non-clamped normal acceleration reaching 0 (NC -> C),
 *   a sticking friction reaching its bound (C -> BND),
 *   a friction at its bound whose a_t changes sign (BND -> C);
 * then the sets change and the drive goes on until d is settled. A fade
 * (computation reuse, removed contacts) drives a set of forces to zero
 * along a line with the same ratio test.
 *
 * Forces change only along a step or through set_force, which updates a,
 * so the tracked a stays A f + b up to round-off (snapping a force to 0
 * or clipping a friction onto its cone without it left a stale by up to
 * 0.3 on LP-seeded walls).
 * Invariants between pivots: members satisfy their rows (clamped a_i = 0,
 * bound f_t = s mu f_n), clamped normal forces >= 0, NC normals have
 * f = 0 and a >= 0, a friction whose normal is not clamped has f_t = 0 and
 * state OFF, every friction satisfies |f_t| <= mu f_n. Pending indices may
 * violate their conditions; they keep their force until driven.
 * A run drains the queue, then a final check recomputes a from f,
 * polishes the members (one Newton step) and queues every violated index
 * again, until none is left.
 * Degeneracy: an index whose pivot is tiny when it must join the clamped
 * system (a redundant contact) is deferred (FREE: unwatched, re-checked by
 * the final check); a bound row with a tiny pivot ends the run as
 * DEGENERATE. Zero-length steps: ties go to the driven index, then to the
 * smallest index, and during a zero-length streak an index that changed
 * set may not rejoin at zero length (no cycling); an unbounded drive or an
 * endless streak is DEGENERATE, the pivot limit LIMIT. The caller then
 * settles the question another way (the LP).
 * Infinite friction (mu = +inf): f_t is free, its condition a_t = 0
 * whatever f_n; such an index is queued with the normals, has no bound
 * event, stays when its normal leaves, and mu never multiplies anything
 * for it (inf * 0 = NaN): every use of mu is guarded by `unbounded`.
 * Settings: every limit and tolerance is a field of us_LcpSettings (lcp.h),
 * read from p->set.
 * Sign conventions: a = A f + b; a_t f_t <= 0 (friction opposes sliding).
 */
#include "lcp.h"

#include <math.h>
#include <string.h>

/* ------------------------------------------------------------ life cycle */

us_LcpSettings us_lcp_default_settings(void) {
  us_LcpSettings s;
  memset(&s, 0, sizeof s);
  s.max_pivots = 0;
  s.pivots_per_index = 4;
  s.pivots_base = 1000;
  s.tol_a = 1e-9;
  s.tol_f = 1e-12;
  s.tol_piv = 1e-6;
  s.tol_piv3 = 1e-13;
  s.pivot_floor = 1e-300;
  s.ratio_tol = 1e-11;
  s.zero_step = 1e-14;
  s.tie_window = 1e-13;
  s.refine_rounds = 2;
  s.refine_tol = 1e-12;
  s.zero_streak_per_index = 2;
  s.zero_streak_base = 20;
  s.zero_rebuild_streak = 8;
  s.zero_rebuild_border = 16;
  s.polish_rounds = 3;
  s.polish_tol = 1e-3;
  s.check_tol_f = 1e3;
  s.force_limit = 1e12;
  s.check_passes = 50;
  s.seed_cone_margin = 1e-9;
  s.factor = us_lcp_factor_default_settings();
  s.reuse_pivots = 1000;
  s.reuse_pivots_div = 4;
  s.eq_tol = 1e-9;
  s.unstable_tol = 1e-6;
  s.cone_slack = 1e-12;
  s.energy_slack = 1e-10;
  s.max_backoff = 20;
  s.lemke_max_dim = 800;
  return s;
}

/* Room for `need` members: the factorization's slots and the slot scratch
 * of this file (dfm, r, e). 0 or -1. */
static int reserve_slots(us_Lcp *p, int need) {
  if (us_lcp_fac_reserve(&p->fac, need)) return -1;
  if (p->fac.cap <= p->scap) return 0;
  size_t cap = (size_t)p->fac.cap;
  double **vecs[3] = {&p->dfm, &p->r, &p->e};
  for (int v = 0; v < 3; v++) {
    double *x = us_realloc(*vecs[v], cap * sizeof(double));
    if (!x) return -1;
    *vecs[v] = x;
  }
  p->scap = p->fac.cap;
  return 0;
}

int us_lcp_init(us_Lcp *p, int n, const us_LcpOps *ops) {
  memset(p, 0, sizeof *p);
  p->n = n;
  p->ops = *ops;
  p->set = us_lcp_default_settings();
  size_t m = (size_t)(n > 0 ? n : 1);
  p->kind = us_calloc(m, 1);
  p->partner = us_malloc(m * sizeof(int));
  p->mu = us_calloc(m, sizeof(double));
  p->live = us_calloc(m, 1);
  p->state = us_calloc(m, 1);
  p->bsign = us_calloc(m, 1);
  p->f = us_calloc(m, sizeof(double));
  p->a = us_calloc(m, sizeof(double));
  p->queue = us_malloc(m * sizeof(int));
  p->inq = us_calloc(m, 1);
  p->da = us_calloc(m, sizeof(double));
  p->out = us_malloc(m * sizeof(int));
  p->didx = us_malloc(2 * m * sizeof(int));
  p->dep = us_malloc(m * sizeof(int));
  p->zmark = us_calloc(m, 1);
  p->zlist = us_malloc(m * sizeof(int));
  p->dval = us_malloc(2 * m * sizeof(double));
  if (!p->kind || !p->partner || !p->mu || !p->live || !p->state || !p->bsign || !p->f || !p->a ||
      !p->queue || !p->inq || !p->da || !p->out || !p->didx || !p->dep || !p->dval || !p->zmark ||
      !p->zlist)
    return -1;
  for (int i = 0; i < n; i++) p->partner[i] = -1;
  if (us_lcp_fac_init(&p->fac, n, ops, &p->set.factor)) return -1;
  return reserve_slots(p, 8);
}

void us_lcp_configure(us_Lcp *p, const us_LcpSettings *set) {
  p->set = *set;
  p->fac.set = set->factor;
}

void us_lcp_free(us_Lcp *p) {
  us_lcp_fac_free(&p->fac);
  void *arrs[] = {p->kind, p->partner, p->mu,  p->live, p->state, p->bsign, p->f,
                  p->a,    p->queue,   p->inq, p->da,   p->out,   p->didx,  p->dval,
                  p->dep,  p->dfm,     p->r,   p->e,    p->zmark, p->zlist};
  for (size_t i = 0; i < sizeof arrs / sizeof arrs[0]; i++) us_free(arrs[i]);
  memset(p, 0, sizeof *p);
}

void us_lcp_set_friction(us_Lcp *p, int t, int n, double mu) {
  p->kind[t] = US_LCP_FRICTION;
  p->partner[t] = n;
  p->partner[n] = t;
  p->mu[t] = mu;
}

void us_lcp_reset(us_Lcp *p) {
  for (int i = 0; i < p->n; i++) {
    p->f[i] = p->a[i] = 0.0;
    p->live[i] = p->inq[i] = 0;
    p->state[i] = US_LCP_OFF;
  }
  us_lcp_fac_reset(&p->fac);
  p->qhead = p->qlen = 0;
}

/* A friction with mu = +inf: f_t is free, it never reaches a bound (and
 * mu never multiplies anything for it: inf * 0 would be NaN). */
static int unbounded(const us_Lcp *p, int t) { return isinf(p->mu[t]); }

static void push(us_Lcp *p, int i) {
  p->state[i] = US_LCP_PEND;
  if (p->inq[i]) return;
  p->queue[(p->qhead + p->qlen) % p->n] = i;
  p->qlen++;
  p->inq[i] = 1;
}

static int pop(us_Lcp *p) {
  int i = p->queue[p->qhead];
  p->qhead = (p->qhead + 1) % p->n;
  p->qlen--;
  p->inq[i] = 0;
  return i;
}

void us_lcp_add(us_Lcp *p, const int *idx, int k) {
  for (int j = 0; j < k; j++) {
    int i = idx[j];
    p->live[i] = 1;
    p->f[i] = 0.0;
    p->state[i] = US_LCP_OFF;
  }
  for (int j = 0; j < k; j++)
    if (p->kind[idx[j]] == US_LCP_NORMAL || unbounded(p, idx[j])) push(p, idx[j]);
}

void us_lcp_refresh(us_Lcp *p) { p->ops.full(p->ops.ctx, p->f, p->live, p->a); }

/* --------------------------------------------------------- the system K */

static double entry(const us_Lcp *p, int i, int j) { return p->ops.entry(p->ops.ctx, i, j); }

/* col[s] = (A x)_{mem[s]} for x non-zero at idx[0..nd) (values val): one
 * sparse product instead of k entries. Uses the scratch da / out. */
static void member_column(us_Lcp *p, const int *idx, const double *val, int nd, double *col) {
  int nout = p->ops.apply(p->ops.ctx, idx, val, nd, p->da, p->out);
  for (int s = 0; s < p->fac.k; s++) col[s] = p->da[p->fac.mem[s]];
  for (int j = 0; j < nout; j++) p->da[p->out[j]] = 0.0;
}

/* Change force i outside a step and keep a = A f + b: a += A e_i df for
 * the live indices the product lists (uses the scratch da / out, which is
 * clear between pivots). Without it a snapped or clipped force leaves the
 * tracked a stale, and the final check's fresh a then shows the members'
 * rows off by the jump (measured: up to 0.3 on LP-seeded walls), which
 * the polish can only repair by large moves that turn clamped forces
 * negative. */
static void set_force(us_Lcp *p, int i, double v) {
  double df = v - p->f[i];
  p->f[i] = v;
  if (df == 0.0) return;
  int nout = p->ops.apply(p->ops.ctx, &i, &df, 1, p->da, p->out);
  for (int j = 0; j < nout; j++) {
    int o = p->out[j];
    if (p->live[o]) p->a[o] += p->da[o];
    p->da[o] = 0.0;
  }
}

/* Index i joins as a clamped row (a_i = 0). 0, 1 tiny pivot, -1 OOM. */
static int append_clamp(us_Lcp *p, int i) {
  if (reserve_slots(p, p->fac.k + 1)) return -1;
  double one = 1.0;
  member_column(p, &i, &one, 1, p->e); /* row of K: A_{i, m} = A_{m, i} */
  for (int s = 0; s < p->fac.k; s++)        /* column of K: clamped rows only */
    p->r[s] = p->state[p->fac.mem[s]] == US_LCP_C ? p->e[s] : 0.0;
  double alpha = entry(p, i, i);
  int r = us_lcp_fac_append(&p->fac, i, -1, 0.0, p->r, p->e, alpha,
                            p->set.tol_piv * US_MAX(fabs(alpha), p->set.pivot_floor));
  if (r == 0) p->state[i] = US_LCP_C;
  return r;
}

/* Friction t joins as the bound row f_t - s mu f_n = 0. */
static int append_bound(us_Lcp *p, int t, int sign) {
  if (reserve_slots(p, p->fac.k + 1)) return -1;
  int n = p->partner[t];
  double one = 1.0;
  member_column(p, &t, &one, 1, p->r);
  for (int s = 0; s < p->fac.k; s++) {
    int m = p->fac.mem[s];
    if (p->state[m] != US_LCP_C) p->r[s] = 0.0;
    p->e[s] = m == n ? -(double)sign * p->mu[t] : 0.0;
  }
  int r = us_lcp_fac_append(&p->fac, t, n, -(double)sign * p->mu[t], p->r, p->e, 1.0, p->set.tol_piv);
  if (r == 0) {
    p->state[t] = US_LCP_BND;
    p->bsign[t] = (signed char)sign;
  }
  return r;
}

/* Members a refactorization found (nearly) dependent: deferred, as if
 * refused on arrival (state FREE, keeping their forces). */
static void defer_members(us_Lcp *p, int nd) {
  for (int j = 0; j < nd; j++) {
    p->state[p->dep[j]] = US_LCP_FREE;
    p->deferred++;
  }
}

/* Remove member i from the system. 0, 1 if the rest looked singular (it
 * was refactorized, deferring dependent members), -1 OOM. */
static int remove_member(us_Lcp *p, int i) {
  int nd = 0, r = us_lcp_fac_delete(&p->fac, p->fac.pos[i], p->dep, &nd);
  defer_members(p, nd);
  return r;
}

/* Refactorize the members, deferring dependent ones. 0 or -1 (OOM). */
static int refactorize(us_Lcp *p) {
  int nd = us_lcp_fac_rebuild(&p->fac, p->dep);
  if (nd < 0) return -1;
  defer_members(p, nd);
  return 0;
}

/* --------------------------------------------------------------- a step */

typedef struct Ev {
  double lam;
  int kind, idx, sign;
  const unsigned char *zmark; /* indices with a zero-length event in this streak */
  double zero_step, tie;      /* settings: zero_step, tie_window */
} Ev;

/* Keep the smallest step. Ties (degenerate steps) go to the driven
 * index's own events, then to the smallest index. Against cycling among
 * degenerate indices (f = 0 and a = 0 together, common in walls): during a
 * streak of zero-length steps an index that already changed set may not
 * rejoin the system at zero length, so a streak has at most 2n steps; an
 * index skipped that way may end slightly violated and is then driven
 * again after the final check. */

static int driven_event(int kind) {
  return kind == US_LCP_EV_DONE || kind == US_LCP_EV_ZERO || kind == US_LCP_EV_BOUND ||
         kind == US_LCP_EV_FADED;
}

static void consider(Ev *ev, double lam, int kind, int idx, int sign) {
  if (lam < 0) lam = 0;
  if (lam <= ev->zero_step && idx >= 0 && ev->zmark[idx] &&
      (kind == US_LCP_EV_NC_C || kind == US_LCP_EV_BND_C))
    return;
  int better = lam < ev->lam;
  if (!better && isfinite(ev->lam) && lam <= ev->lam + ev->tie * (1.0 + ev->lam))
    better = !driven_event(ev->kind) && (driven_event(kind) || idx < ev->idx);
  if (better) {
    ev->lam = lam;
    ev->kind = kind;
    ev->idx = idx;
    ev->sign = sign;
  }
}

/* Residual of the members' rows for the increments in dfm / da (res by
 * slot); returns its largest magnitude and sets *scale = max(1, |dfm|). */
static double row_residual(const us_Lcp *p, double *res, double *scale) {
  double err = 0.0, sc = 1.0;
  for (int s = 0; s < p->fac.k; s++) {
    int m = p->fac.mem[s];
    sc = US_MAX(sc, fabs(p->dfm[s]));
    if (p->state[m] == US_LCP_C) {
      res[s] = p->da[m];
    } else {
      int pn = p->fac.pos[p->partner[m]];
      res[s] = p->dfm[s] - p->bsign[m] * p->mu[m] * (pn >= 0 ? p->dfm[pn] : 0.0);
    }
    err = US_MAX(err, fabs(res[s]));
  }
  *scale = sc;
  return err;
}

/* Member increments df = -H (A_{members, D} dD) for the driven set D
 * (didx/dval, nd entries), then da = A (df, dD) for the touched indices.
 * Returns the number of listed indices in p->out. */
static int direction(us_Lcp *p, int nd) {
  member_column(p, p->didx, p->dval, nd, p->r);
  for (int s = 0; s < p->fac.k; s++) p->r[s] = p->state[p->fac.mem[s]] == US_LCP_C ? -p->r[s] : 0.0;
  us_lcp_fac_solve(&p->fac, p->r, p->dfm);
  for (int s = 0; s < p->fac.k; s++) {
    p->didx[nd + s] = p->fac.mem[s];
    p->dval[nd + s] = p->dfm[s];
  }
  int nout = p->ops.apply(p->ops.ctx, p->didx, p->dval, nd + p->fac.k, p->da, p->out);
  for (int round = 0; round < p->set.refine_rounds; round++) { /* iterative refinement */
    double scale, err = row_residual(p, p->e, &scale);
    if (!(err > p->set.refine_tol * scale)) break;
    us_lcp_fac_solve(&p->fac, p->e, p->r);
    for (int s = 0; s < p->fac.k; s++) p->dval[nd + s] = p->dfm[s] -= p->r[s];
    for (int j = 0; j < nout; j++) p->da[p->out[j]] = 0.0;
    nout = p->ops.apply(p->ops.ctx, p->didx, p->dval, nd + p->fac.k, p->da, p->out);
  }
  return nout;
}

static double member_df(const us_Lcp *p, int i) { return p->fac.pos[i] >= 0 ? p->dfm[p->fac.pos[i]] : 0.0; }

/* Ratio test over the members and the listed non-members. */
static void ratio_members(const us_Lcp *p, int nout, double thr_f, double thr_a, Ev *ev) {
  for (int s = 0; s < p->fac.k; s++) {
    int i = p->fac.mem[s];
    double df = p->dfm[s];
    if (p->state[i] == US_LCP_C && p->kind[i] == US_LCP_NORMAL) {
      if (df < -thr_f) consider(ev, p->f[i] / -df, US_LCP_EV_C_NC, i, 0);
    } else if (p->state[i] == US_LCP_C && !unbounded(p, i)) { /* sticking friction: both bounds */
      int n = p->partner[i];
      double dfn = member_df(p, n);
      for (int sg = -1; sg <= 1; sg += 2) {
        double h0 = sg * p->f[i] - p->mu[i] * p->f[n], h1 = sg * df - p->mu[i] * dfn;
        if (h1 > thr_f) consider(ev, -h0 / h1, US_LCP_EV_C_BND, i, sg);
      }
    }
  }
  for (int j = 0; j < nout; j++) {
    int i = p->out[j];
    if (!p->live[i]) continue;
    double da = p->da[i];
    if (p->state[i] == US_LCP_NC && da < -thr_a) consider(ev, p->a[i] / -da, US_LCP_EV_NC_C, i, 0);
    if (p->state[i] == US_LCP_BND && p->bsign[i] * da > thr_a)
      consider(ev, -p->bsign[i] * p->a[i] / (p->bsign[i] * da), US_LCP_EV_BND_C, i, 0);
  }
}

/* The driven index's own events (single drive, direction dir). */
static void ratio_driven(const us_Lcp *p, int d, double dir, double thr_f, double thr_a, Ev *ev) {
  double da = p->da[d];
  if (p->a[d] * dir >= -p->set.tol_a) /* reached 0 already (a tie in the last step) */
    consider(ev, 0.0, US_LCP_EV_DONE, d, 0);
  else if (dir * da > thr_a)
    consider(ev, -p->a[d] / da, US_LCP_EV_DONE, d, 0);
  if (p->kind[d] == US_LCP_NORMAL) {
    if (dir < 0) consider(ev, p->f[d], US_LCP_EV_ZERO, d, 0);
    return;
  }
  if (unbounded(p, d)) return; /* f_t free: no bound to reach */
  int n = p->partner[d];
  double h0 = dir * p->f[d] - p->mu[d] * p->f[n], h1 = 1.0 - p->mu[d] * member_df(p, n);
  if (h1 > thr_f) consider(ev, -h0 / h1, US_LCP_EV_BOUND, d, (int)dir);
}

/* Largest magnitude of the listed da and of the member increments. */
static void scales(const us_Lcp *p, int nout, double *fs, double *as) {
  double f = 1.0, a = 1.0;
  for (int s = 0; s < p->fac.k; s++) f = US_MAX(f, fabs(p->dfm[s]));
  for (int j = 0; j < nout; j++) a = US_MAX(a, fabs(p->da[p->out[j]]));
  *fs = f;
  *as = a;
}

/* Move by lam along the current direction (nd driven entries). */
static void advance(us_Lcp *p, int nd, int nout, double lam) {
  for (int j = 0; j < nd + p->fac.k; j++) p->f[p->didx[j]] += lam * p->dval[j];
  for (int j = 0; j < nout; j++) {
    int i = p->out[j];
    if (p->live[i]) p->a[i] += lam * p->da[i];
  }
}

static void clear_da(us_Lcp *p, int nout) {
  for (int j = 0; j < nout; j++) p->da[p->out[j]] = 0.0;
}

/* ------------------------------------------------------------ the events */

/* A DEGENERATE end, with the reason kept for the caller's note. */
static us_LcpResult degenerate(us_Lcp *p, const char *why) {
  p->why = why;
  return US_LCP_DEGENERATE;
}

/* The friction of a normal that left the system: force 0, no condition. */
static int friction_off(us_Lcp *p, int n) {
  int t = p->partner[n];
  if (t < 0 || !p->live[t] || p->state[t] == US_LCP_DRV || unbounded(p, t)) return 0;
  int bad = 0;
  if (p->fac.pos[t] >= 0) bad = remove_member(p, t);
  p->state[t] = US_LCP_OFF;
  set_force(p, t, 0.0);
  return bad;
}

/* A normal joined the system: its friction (if any) waits for a drive. */
static void friction_on(us_Lcp *p, int n) {
  int t = p->partner[n];
  if (t >= 0 && p->live[t] && p->state[t] == US_LCP_OFF) push(p, t);
}

/* Index i has a_i = 0 and joins the system. A tiny pivot means i is
 * redundant with the system (its row is a combination of the members'):
 * it is deferred instead, keeping its force (a normal without force is
 * simply NC); deferred indices are re-checked at the end of the run. */
static us_LcpResult join_clamp(us_Lcp *p, int i) {
  int r = append_clamp(p, i);
  if (r < 0) return US_LCP_NOMEM;
  if (r == 0) {
    if (p->kind[i] == US_LCP_NORMAL) friction_on(p, i);
    return US_LCP_SOLVED;
  }
  /* deferred, unwatched by ratio tests (an NC one blocking at a = 0
   * would block again at once: a zero-step cycle) */
  p->deferred++;
  p->state[i] = US_LCP_FREE;
  return US_LCP_SOLVED;
}

static us_LcpResult ev_done(us_Lcp *p, int d) { return join_clamp(p, d); }

static us_LcpResult ev_bound(us_Lcp *p, int t, int sign, int was_member) {
  set_force(p, t, sign * p->mu[t] * p->f[p->partner[t]]);
  if (was_member && remove_member(p, t)) return degenerate(p, "singular after a friction left");
  int r = append_bound(p, t, sign);
  return r < 0 ? US_LCP_NOMEM : r > 0 ? degenerate(p, "tiny pivot of a bound row") : US_LCP_SOLVED;
}

static us_LcpResult apply_event(us_Lcp *p, const Ev *ev) {
  int i = ev->idx;
  switch (ev->kind) {
  case US_LCP_EV_DONE: return ev_done(p, i);
  case US_LCP_EV_ZERO:
    set_force(p, i, 0.0);
    p->state[i] = US_LCP_NC;
    return US_LCP_SOLVED;
  case US_LCP_EV_BOUND: return ev_bound(p, i, ev->sign, 0);
  case US_LCP_EV_C_NC:
    set_force(p, i, 0.0);
    if (remove_member(p, i)) return degenerate(p, "singular after a contact left");
    p->state[i] = US_LCP_NC;
    return friction_off(p, i) ? degenerate(p, "singular after a friction left") : US_LCP_SOLVED;
  case US_LCP_EV_NC_C: return join_clamp(p, i);
  case US_LCP_EV_C_BND: return ev_bound(p, i, ev->sign, 1);
  case US_LCP_EV_BND_C:
    if (remove_member(p, i)) return degenerate(p, "singular after a friction left");
    return join_clamp(p, i);
  }
  return US_LCP_SOLVED;
}

/* ------------------------------------------------------------ the drives */

typedef struct Run {
  long pivots, limit;
  int zero_steps;
  int nz; /* indices marked in p->zmark (listed in p->zlist) */
} Run;

/* Mark idx for the current zero-length streak, or clear all marks. */
static void zero_mark(us_Lcp *p, Run *run, int idx, int zero) {
  if (!zero) {
    for (int j = 0; j < run->nz; j++) p->zmark[p->zlist[j]] = 0;
    run->nz = 0;
  } else if (idx >= 0 && !p->zmark[idx]) {
    p->zmark[idx] = 1;
    p->zlist[run->nz++] = idx;
  }
}

/* Refactorize the clamped system from the members (lcp_factor.c): when
 * its border has outgrown its limit, and when a run of zero-length steps
 * suggests lost accuracy. A member that now shows as dependent is
 * deferred like one refused on arrival. 0, or US_LCP_NOMEM. */
static us_LcpResult rebuild(us_Lcp *p) {
  if (refactorize(p)) return US_LCP_NOMEM;
  p->rebuilds++;
  return US_LCP_SOLVED;
}

/* After a change of the system outside a pivot: refactorize if due. */
static us_LcpResult keep_fresh(us_Lcp *p, us_LcpResult r) {
  return r == US_LCP_SOLVED && us_lcp_fac_stale(&p->fac) ? rebuild(p) : r;
}

/* One pivot of a drive of nd driven entries (single: nd == 1, driven
 * direction dir; fade: lam_max bounds the step). */
static us_LcpResult pivot(us_Lcp *p, Run *run, int nd, int single, double dir, double lam_max,
                          double *lam_out) {
  int nout = direction(p, nd);
  double fs, as;
  scales(p, nout, &fs, &as);
  double thr_f = p->set.ratio_tol * fs, thr_a = p->set.ratio_tol * as;
  Ev ev = {INFINITY, -1, -1, 0, p->zmark, p->set.zero_step, p->set.tie_window};
  if (single)
    ratio_driven(p, p->didx[0], dir, thr_f, thr_a, &ev);
  else
    consider(&ev, lam_max, US_LCP_EV_FADED, -1, 0);
  ratio_members(p, nout, thr_f, thr_a, &ev);
  if (!isfinite(ev.lam)) {
    clear_da(p, nout);
    return degenerate(p, "unbounded drive");
  }
  advance(p, nd, nout, ev.lam);
  clear_da(p, nout);
  *lam_out = ev.lam;
  run->zero_steps = ev.lam <= p->set.zero_step ? run->zero_steps + 1 : 0;
  zero_mark(p, run, ev.idx, run->zero_steps > 0);
  us_LcpResult r = ev.kind == US_LCP_EV_FADED ? US_LCP_SOLVED : apply_event(p, &ev);
  p->pivots++;
  if (p->trace) {
    us_LcpStep st = {single ? p->didx[0] : -1, ev.lam, ev.kind, ev.idx, p->f, p->a};
    p->trace(p->trace_ud, &st);
  }
  if (r) return r;
  if (++run->pivots > run->limit) return US_LCP_LIMIT;
  if ((run->pivots & 63) == 0 && p->set.deadline > 0 && us_now() > p->set.deadline)
    return US_LCP_LIMIT;
  if (run->zero_steps > p->set.zero_streak_per_index * p->n + p->set.zero_streak_base) return degenerate(p, "endless zero-length steps");
  if (us_lcp_fac_stale(&p->fac) ||
      (run->zero_steps == p->set.zero_rebuild_streak && p->fac.m > p->set.zero_rebuild_border))
    return rebuild(p);
  return US_LCP_SOLVED;
}

/* Settle an index whose a is already ~0 (no motion needed). */
static us_LcpResult settle_in_place(us_Lcp *p, int d) {
  if (p->kind[d] == US_LCP_NORMAL && p->f[d] <= p->set.tol_f) {
    p->f[d] = 0.0;
    p->state[d] = US_LCP_NC;
    return US_LCP_SOLVED;
  }
  return ev_done(p, d);
}

/* Direction of a drive of d, or 0 if d is settled without moving. */
static double drive_dir(const us_Lcp *p, int d) {
  double a = p->a[d];
  if (p->kind[d] == US_LCP_NORMAL) {
    if (a < -p->set.tol_a) return 1.0;
    return a > p->set.tol_a && p->f[d] > p->set.tol_f ? -1.0 : 0.0;
  }
  return a > p->set.tol_a ? -1.0 : a < -p->set.tol_a ? 1.0 : 0.0;
}

static us_LcpResult drive(us_Lcp *p, Run *run, int d) {
  if (p->kind[d] == US_LCP_FRICTION && !unbounded(p, d) && p->state[p->partner[d]] != US_LCP_C) {
    p->state[d] = US_LCP_OFF; /* unloaded contact: no friction */
    set_force(p, d, 0.0);
    return US_LCP_SOLVED;
  }
  double dir = drive_dir(p, d);
  /* settled without a pivot (the border still grows: refactorize when
   * due, as after a pivot) */
  if (dir == 0.0) return keep_fresh(p, settle_in_place(p, d));
  if (p->kind[d] == US_LCP_FRICTION && !unbounded(p, d) &&
      dir * p->f[d] >= p->mu[d] * p->f[p->partner[d]] - p->set.tol_f)
    return keep_fresh(p, ev_bound(p, d, (int)dir, 0)); /* already at the bound it moves to */
  p->state[d] = US_LCP_DRV;
  while (p->state[d] == US_LCP_DRV) {
    p->didx[0] = d;
    p->dval[0] = dir;
    double lam;
    us_LcpResult r = pivot(p, run, 1, 1, dir, 0.0, &lam);
    if (r) return r;
  }
  return US_LCP_SOLVED;
}

static long run_limit(const us_Lcp *p) {
  return p->set.max_pivots > 0 ? p->set.max_pivots
                              : (long)p->set.pivots_per_index * p->n + p->set.pivots_base;
}

static us_LcpResult fade(us_Lcp *p, Run *run, const int *idx, int k) {
  for (int j = 0; j < k; j++) {
    int i = idx[j];
    if (p->fac.pos[i] >= 0 && remove_member(p, i)) return degenerate(p, "singular after a fade");
    p->state[i] = US_LCP_DRV; /* a stale queue entry is skipped by its state */
  }
  double left = 1.0;
  while (left > 0) {
    int nd = 0;
    for (int j = 0; j < k; j++) {
      p->didx[nd] = idx[j];
      p->dval[nd++] = -p->f[idx[j]] / left; /* reach 0 when left is used up */
    }
    double lam;
    us_LcpResult r = pivot(p, run, nd, 0, 0.0, left, &lam);
    if (r) return r;
    left = lam >= left ? 0.0 : left - lam;
  }
  for (int j = 0; j < k; j++) {
    p->f[idx[j]] = p->a[idx[j]] = 0.0;
    p->live[idx[j]] = 0;
    p->state[idx[j]] = US_LCP_OFF;
  }
  return US_LCP_SOLVED;
}

/* ------------------------------------------------------ the final check */

/* Newton corrections of the members from fresh accelerations (iterative
 * refinement: the rows drift by round-off over many pivots, and a nearly
 * dependent clamped set amplifies it): up to three rounds, each followed
 * by a fresh a; if the rows are still off, the system is refactorized and
 * three more rounds run. A round that does not reduce the drift (a nearly
 * singular K) is undone and ends the polish. 0, or US_LCP_NOMEM. */
static double row_drift(us_Lcp *p) {
  double worst = 0.0;
  for (int s = 0; s < p->fac.k; s++) {
    int m = p->fac.mem[s];
    if (p->state[m] == US_LCP_C)
      p->r[s] = p->a[m];
    else
      p->r[s] = p->f[m] - p->bsign[m] * p->mu[m] * p->f[p->partner[m]];
    worst = US_MAX(worst, fabs(p->r[s]));
  }
  return worst;
}

/* Whether the last polish round (its step in dfm) turned a clamped normal
 * force clearly negative: a nearly singular K moves the members along a
 * near-null direction (a self-stress of nearly dependent contacts) that
 * barely changes the rows but leaves the clamped forces off their sign. */
static int pushed_negative(const us_Lcp *p) {
  for (int s = 0; s < p->fac.k; s++) {
    int m = p->fac.mem[s];
    if (p->state[m] == US_LCP_C && p->kind[m] == US_LCP_NORMAL && p->f[m] < 0 &&
        p->f[m] + p->dfm[s] >= 0 && -p->f[m] > p->set.tol_f)
      return 1;
  }
  return 0;
}

static us_LcpResult polish(us_Lcp *p) {
  double drift = row_drift(p);
  for (int round = 0; round < 2 * p->set.polish_rounds; round++) {
    if (!(drift > p->set.polish_tol * p->set.tol_a)) return US_LCP_SOLVED;
    if (round == p->set.polish_rounds) {
      if (refactorize(p)) return US_LCP_NOMEM;
      p->rebuilds++;
      drift = row_drift(p);
    }
    us_lcp_fac_solve(&p->fac, p->r, p->dfm);
    for (int s = 0; s < p->fac.k; s++) p->f[p->fac.mem[s]] -= p->dfm[s];
    us_lcp_refresh(p);
    double now = row_drift(p);
    if (!(now < drift) || pushed_negative(p)) { /* a nearly singular K: undo, stop */
      for (int s = 0; s < p->fac.k; s++) p->f[p->fac.mem[s]] += p->dfm[s];
      us_lcp_refresh(p);
      return US_LCP_SOLVED;
    }
    drift = now;
  }
  return US_LCP_SOLVED;
}

/* Round-off scale of the final check: a_i carries errors of order
 * eps * sum_j |A_ij f_j| <= eps * n * max A_jj * max |f_j| (PSD), so the
 * tolerances on a and f grow with the largest force and diagonal. */
typedef struct Scale {
  double ta, tf, fmax;
} Scale;


static Scale check_scale(const us_Lcp *p) {
  double fmax = 0.0, dmax = 0.0;
  for (int i = 0; i < p->n; i++)
    if (p->live[i]) fmax = US_MAX(fmax, fabs(p->f[i]));
  for (int s = 0; s < p->fac.k; s++) dmax = US_MAX(dmax, fabs(entry(p, p->fac.mem[s], p->fac.mem[s])));
  Scale sc = {p->set.tol_a * (1.0 + fmax * dmax), p->set.check_tol_f * p->set.tol_f * (1.0 + fmax), fmax};
  return sc;
}

/* Conditions of a friction i with mu = +inf (live) after a run: a_t = 0
 * (f_t is free, there is no cone to leave). */
static us_LcpResult check_unbounded(us_Lcp *p, int i, Scale sc) {
  if (p->state[i] == US_LCP_C)
    return fabs(p->a[i]) > sc.ta ? degenerate(p, "sticking friction off its row") : US_LCP_SOLVED;
  if (fabs(p->a[i]) > sc.ta) push(p, i);
  return US_LCP_SOLVED;
}

/* Conditions of friction i (live) after a run; queue the violated ones. */
static us_LcpResult check_friction(us_Lcp *p, int i, Scale sc) {
  if (unbounded(p, i)) return check_unbounded(p, i, sc);
  int n = p->partner[i];
  double a = p->a[i], lim = p->mu[i] * p->f[n] + sc.tf;
  switch (p->state[i]) {
  case US_LCP_OFF:
    if (p->state[n] == US_LCP_C) push(p, i);
    return US_LCP_SOLVED;
  case US_LCP_C:
    if (fabs(a) > sc.ta) return degenerate(p, "sticking friction off its row");
    if (fabs(p->f[i]) > lim) { /* drifted past its bound: back on it, driven again */
      if (remove_member(p, i)) return degenerate(p, "singular after a friction left");
      set_force(p, i, (p->f[i] > 0 ? 1.0 : -1.0) * p->mu[i] * p->f[n]);
      push(p, i);
    }
    return US_LCP_SOLVED;
  case US_LCP_BND:
    if (p->bsign[i] * a > sc.ta) { /* sliding the wrong way: drive back */
      if (remove_member(p, i)) return degenerate(p, "singular after a friction left");
      push(p, i);
    }
    return US_LCP_SOLVED;
  default: /* FREE or left pending: unwatched while f_n moved */
    if (fabs(p->f[i]) > lim) { /* back onto the cone, then driven again */
      set_force(p, i, (p->f[i] > 0 ? 1.0 : -1.0) * p->mu[i] * p->f[n]);
      push(p, i);
    } else if (fabs(a) > sc.ta) {
      push(p, i);
    }
    return US_LCP_SOLVED;
  }
}

static us_LcpResult check_normal(us_Lcp *p, int i, Scale sc) {
  switch (p->state[i]) {
  case US_LCP_C:
    return p->f[i] < -sc.tf || fabs(p->a[i]) > sc.ta ? degenerate(p, "clamped contact off its row")
                                                      : US_LCP_SOLVED;
  case US_LCP_NC:
    if (p->a[i] < -sc.ta) push(p, i);
    return US_LCP_SOLVED;
  case US_LCP_FREE: /* deferred: without force it is NC, else a must be ~0 */
    if (p->f[i] <= p->set.tol_f && p->a[i] >= -sc.ta) {
      p->f[i] = 0.0;
      p->state[i] = US_LCP_NC;
    } else if (fabs(p->a[i]) > sc.ta) {
      push(p, i);
    }
    return US_LCP_SOLVED;
  default: push(p, i); return US_LCP_SOLVED;
  }
}

/* Fresh a, polish, then every live index against its conditions. */
static us_LcpResult final_check(us_Lcp *p) {
  us_lcp_refresh(p);
  if (polish(p)) return US_LCP_NOMEM;
  Scale sc = check_scale(p);
  if (!(sc.fmax <= p->set.force_limit)) return degenerate(p, "forces ran away");
  for (int i = 0; i < p->n; i++) {
    if (!p->live[i]) continue;
    us_LcpResult r =
        p->kind[i] == US_LCP_NORMAL ? check_normal(p, i, sc) : check_friction(p, i, sc);
    if (r) return r;
  }
  return US_LCP_SOLVED;
}

static us_LcpResult run_queue(us_Lcp *p, Run *run) {
  us_lcp_refresh(p);
  for (int pass = 0; pass < p->set.check_passes; pass++) {
    while (p->qlen > 0) {
      int i = pop(p);
      if (!p->live[i] || p->state[i] != US_LCP_PEND) continue;
      us_LcpResult r = drive(p, run, i);
      if (r) return r;
    }
    us_LcpResult r = final_check(p);
    if (r) return r;
    if (p->qlen == 0) return US_LCP_SOLVED;
  }
  return degenerate(p, "no fixed point after the final checks");
}

/* The seeded state of friction i from its force and its normal's state:
 * off without a clamped normal, sticking inside its cone, else at its
 * bound. With mu = +inf it sticks whatever its normal (f_t is free). */
static void seed_friction(us_Lcp *p, int i) {
  int n = p->partner[i];
  if (unbounded(p, i)) {
    p->state[i] = US_LCP_C;
    return;
  }
  double lim = p->mu[i] * p->f[n];
  if (p->state[n] != US_LCP_C) {
    p->state[i] = US_LCP_OFF;
    p->f[i] = 0.0;
  } else if (fabs(p->f[i]) < lim * (1.0 - p->set.seed_cone_margin)) {
    p->state[i] = US_LCP_C;
  } else {
    p->state[i] = US_LCP_BND;
    p->bsign[i] = (signed char)(p->f[i] < 0 ? -1 : 1);
    p->f[i] = p->bsign[i] * lim;
  }
}

/* Start from given forces f of the live indices, typically a static
 * solution from the LP (then a = 0 everywhere and the forces satisfy every
 * sign and cone condition): positive normals are clamped, frictions inside
 * their cone sticking, on it at their bound; the system is factorized
 * (dependent members deferred) and a run repairs whatever is left. */
us_LcpResult us_lcp_seed(us_Lcp *p) {
  us_lcp_fac_reset(&p->fac);
  p->qhead = p->qlen = 0;
  int count = 0;
  for (int i = 0; i < p->n; i++) {
    p->inq[i] = 0;
    count += p->live[i];
  }
  if (reserve_slots(p, count)) return US_LCP_NOMEM;
  for (int i = 0; i < p->n; i++) { /* normals first: frictions look at them */
    if (!p->live[i] || p->kind[i] != US_LCP_NORMAL) continue;
    p->state[i] = p->f[i] > p->set.tol_f ? US_LCP_C : US_LCP_NC;
    if (p->state[i] == US_LCP_NC) p->f[i] = 0.0;
  }
  for (int i = 0; i < p->n; i++) {
    if (!p->live[i]) continue;
    if (p->kind[i] == US_LCP_FRICTION) seed_friction(p, i);
    if (p->state[i] == US_LCP_C)
      us_lcp_fac_enlist(&p->fac, i, -1, 0.0);
    else if (p->state[i] == US_LCP_BND)
      us_lcp_fac_enlist(&p->fac, i, p->partner[i], -(double)p->bsign[i] * p->mu[i]);
  }
  if (refactorize(p)) return US_LCP_NOMEM;
  return us_lcp_run(p);
}

/* Both entry points leave no zero-streak marks behind, whatever the exit. */
us_LcpResult us_lcp_fade(us_Lcp *p, const int *idx, int k) {
  Run run = {0, run_limit(p), 0, 0};
  us_LcpResult r = fade(p, &run, idx, k);
  zero_mark(p, &run, -1, 0);
  return r;
}

us_LcpResult us_lcp_run(us_Lcp *p) {
  Run run = {0, run_limit(p), 0, 0};
  us_LcpResult r = run_queue(p, &run);
  zero_mark(p, &run, -1, 0);
  return r;
}
