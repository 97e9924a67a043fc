/* The LCP stability backends: the sub-assembly stands iff the contact LCP
 * (Baraff 1994) has a solution with zero body accelerations; us_backend_lcp
 * solves every test from scratch, us_backend_lcp_reuse starts from the
 * previous sub-assembly's solution.
 *
 * Algorithm of one test: map the sub-assembly onto the structure-wide LCP
 * of lcp_sys.c (index 2c normal, 2c + 1 friction of structure contact c,
 * live when the contact is active), solve it (lcp.c), and decide:
 *   - net wrench of every body ~ 0 (|E f + F| <= 1e-9 W): STABLE, with
 *     these forces (the front end re-checks them);
 *   - frictionless (every active mu = 0): the body accelerations of a
 *     PSD LCP are unique, so a clear non-zero wrench (>= 1e-6 W) is
 *     UNSTABLE, exactly;
 *   - with friction, the same when the contact accelerations prove that
 *     no static solution exists (dual_cone_proof: toppling, lifting off);
 *   - otherwise (friction: the LCP may have found a sliding solution
 *     although a static one exists, or a true sliding one that the dual
 *     cone does not prove; a pivot limit or a degenerate run) the cone
 *     LCP decides: the same structure with every friction cone replaced by
 *     its two edges (lcp_sys.c, us_lcp_sys_init_cone), a frictionless,
 *     hence PSD, LCP: the KKT system of min |E l + F|^2 over l >= 0 in the
 *     M^-1 norm. Its net wrench is zero iff a static solution exists; a
 *     clearly non-zero one comes with accelerations in every dual cone,
 *     so the dual-cone proof below holds for it by construction;
 *   - where that fails too (gray zone, pivot limit, degenerate run) the LP
 *     decides: the CLP backend, created lazily inside this workspace,
 *     counted in info->lp_fallbacks.
 * Reuse: the workspace keeps forces, index sets and the factorized clamped
 * system. Removed bodies: their contacts' rows leave the factorization and
 * their forces are faded to zero along a line while every other index
 * keeps its conditions (pivoting where one would break), which repairs the
 * solution locally. Added bodies: their contacts join with zero force and
 * only they are driven. Old contacts keep their forces in both cases.
 * After a failed run the state is dropped; a stable verdict of the cone
 * LCP or the LP re-seeds it. The cone LCP keeps its own state (lcp-reuse)
 * and follows the sub-assemblies lazily: when it is next needed, the
 * bodies it has and the test lacks leave (faded), the test's new contacts
 * join.
 * A repair that fails (degenerate, limit) is first retried from scratch
 * on the same test under the reuse pivot limit (info->lcp_retries): the
 * path from zero forces usually avoids the nearly dependent set the
 * repair ran into (docs/lcp.md, "Re-seeds and skips").
 * Back-off (lcp-reuse only): where the LCP keeps failing (large degenerate
 * walls: long runs of zero-length exchanges), the tests go straight to the
 * LP instead of paying for failing runs. After the j-th failed run in a
 * row, the next 2^(j-1) - 1 tests skip the LCP (an isolated failure costs
 * nothing: the next test reuses again); once a scratch solve of the
 * workspace has failed, a test that cannot reuse skips it too (a scratch
 * run would fail again, at the full pivot limit). Skipped tests (counted
 * in info->lcp_skips) go to the cone LCP, then the LP; verdicts never
 * depend on the policy.
 * The thresholds above (1e-9 W, 1e-6 W, the reuse pivot limit, the
 * back-off cap) are fields of us_LcpSettings (lcp.h), defaults unless a
 * workspace is made by us_lcp_backend_create with others. A contact with
 * mu = +inf is never clipped into a cone, and its dual cone is the ray
 * a_t = 0, a_n >= 0.
 */
#include "lcp_backend.h"

#include "lcp.h"
#include "lcp3_piv.h"
#include "lcp_lemke.h"
#include "lcp_sys.h"
#include "backend.h"
#include "lp_gen.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* The cone LCP of the workspace (created on first use). */
typedef struct Cone {
  us_LcpSys sys;
  us_Lcp lcp;
  int ready;  /* sys and lcp set up */
  int valid;  /* lcp holds the solution of the last sub-assembly it saw */
  int failed; /* scratch solves that failed in a row (lcp-reuse) */
  long wait;  /* requests left before the next scratch attempt */
  us_LcpLemke lemke; /* where the Dantzig run fails (lcp_lemke.c) */
  us_Lcp3Piv piv;    /* 3D: the principal pivoting (lcp3_piv.c) */
} Cone;

typedef struct LcpWs {
  const us_Structure *s;
  us_StabilitySettings set;
  us_LcpSettings lset; /* limits and tolerances (lcp.h) */
  int reuse; /* the reuse backend */
  int valid; /* lcp holds the solution of the last sub-assembly */
  us_LcpSys sys;
  us_Lcp lcp;
  Cone cones[2]; /* 2D: [0]; 3D: the inner and the outer polygons' LCPs */
  Cone *kc;      /* the cone LCP of the current test */
  us_EqGen gen;  /* 3D: the test's cone generators (lp_gen.h) */
  double *lcol, *ray; /* 3D: [gen.ncol] multipliers, [rows] Farkas ray */
  int cap_lcol, cap_ray, nray;
  unsigned char *changed; /* 3D: [ncontact + 1] contacts whose columns changed, kept zero */
  int by_lp;  /* the LP decided the last test */
  double farkas_slack; /* the LP settings' (3D rays are checked as the LP's) */
  int *idx;   /* [K ncontact + 1] */
  int *gone;  /* [nbody + 1] bodies the cone LCP has and the test lacks */
  unsigned char *cmark; /* [ncontact + 1] contacts listed, kept zero */
  unsigned char *bmark; /* [nbody + 1] bodies of the test, kept zero */
  void *lpws; /* CLP workspace, created on the first fallback */
  int last_body;
  int fails;          /* failed LCP runs (or seeds) in a row, lcp-reuse */
  long skip;          /* tests left that go straight to the LP (back-off) */
  int scratch_failed; /* a scratch solve failed: restarts go to the LP */
} LcpWs;

/* Deadline (backend.h): runs stop as at their pivot limit, and the LP
 * that then decides stops undecided. */
static void lcp_set_deadline(void *ws, double deadline) {
  LcpWs *w = ws;
  w->lset.deadline = deadline;
  w->lcp.set.deadline = deadline;
  for (int m = 0; m < 2; m++) w->cones[m].lcp.set.deadline = deadline;
  if (w->lpws) us_backend_clp.set_deadline(w->lpws, deadline);
}

static void lcp_destroy(void *ws) {
  LcpWs *w = ws;
  if (!w) return;
  us_lcp_free(&w->lcp);
  us_lcp_sys_free(&w->sys);
  for (int m = 0; m < 2; m++) {
    us_lcp_free(&w->cones[m].lcp);
    us_lcp_sys_free(&w->cones[m].sys);
    us_lcp_lemke_free(&w->cones[m].lemke);
    us_lcp3_piv_free(&w->cones[m].piv);
  }
  us_eq_gen_free(&w->gen);
  us_free(w->lcol);
  us_free(w->ray);
  us_free(w->changed);
  if (w->lpws) us_backend_clp.destroy(w->lpws);
  us_free(w->idx);
  us_free(w->gone);
  us_free(w->cmark);
  us_free(w->bmark);
  us_free(w);
}

/* Index arrays of the workspace, then (2D) the friction LCP. 0 or -1. */
static int lcp_setup(LcpWs *w, const us_Structure *s) {
  size_t K = (size_t)(s->dim == 3 ? us_eq_gen_slots(3) : 2);
  w->idx = us_malloc((K * (size_t)s->ncontact + 1) * sizeof(int));
  w->cmark = us_calloc((size_t)s->ncontact + 1, 1);
  w->changed = us_calloc((size_t)s->ncontact + 1, 1);
  w->gone = us_malloc(((size_t)s->nbody + 1) * sizeof(int));
  w->bmark = us_calloc((size_t)s->nbody + 1, 1);
  if (!w->idx || !w->cmark || !w->changed || !w->gone || !w->bmark) return -1;
  if (s->dim == 3) { /* no friction LCP: the cone LCP is the LCP */
    w->ray = us_malloc((12 * (size_t)s->nbody + 1) * sizeof(double));
    return w->ray ? 0 : -1;
  }
  if (us_lcp_sys_init(&w->sys, s)) return -1;
  us_LcpOps ops = us_lcp_sys_ops(&w->sys);
  if (us_lcp_init(&w->lcp, 2 * s->ncontact, &ops)) return -1;
  us_lcp_configure(&w->lcp, &w->lset);
  for (int c = 0; c < s->ncontact; c++)
    if (s->contacts[c].mu > 0) us_lcp_set_friction(&w->lcp, 2 * c + 1, 2 * c, s->contacts[c].mu);
  return 0;
}

/* The cone LCP, set up on first use (2D: mu = +inf contacts keep a free
 * friction: their cone is a half-space with one edge direction; 3D: every
 * index a cone generator, the half-space's four included). 0 or -1. */
static int cone_setup(LcpWs *w) {
  Cone *k = w->kc;
  if (k->ready) return 0;
  us_LcpOps ops;
  int d3 = w->s->dim == 3;
  if ((d3 ? us_lcp3_sys_init(&k->sys, w->s) : us_lcp_sys_init_cone(&k->sys, w->s)) == 0) {
    ops = us_lcp_sys_ops(&k->sys);
    if (us_lcp_init(&k->lcp, k->sys.K * w->s->ncontact, &ops) == 0 &&
        (!d3 || us_lcp3_piv_init(&k->piv, k->sys.K * w->s->ncontact) == 0)) {
      us_lcp_configure(&k->lcp, &w->lset);
      if (d3) k->lcp.set.tol_piv = w->lset.tol_piv3;
      for (int c = 0; c < w->s->ncontact && !d3; c++)
        if (isinf(w->s->contacts[c].mu)) us_lcp_set_friction(&k->lcp, 2 * c + 1, 2 * c, INFINITY);
      k->ready = 1;
      return 0;
    }
  }
  us_lcp_free(&k->lcp);
  us_lcp_sys_free(&k->sys);
  us_lcp3_piv_free(&k->piv);
  return -1;
}

void *us_lcp_backend_create(const us_Structure *s, const us_StabilitySettings *set,
                            const us_LcpSettings *lcp, int reuse, us_Error *err) {
  LcpWs *w = us_calloc(1, sizeof *w);
  if (w) {
    w->kc = &w->cones[0];
    w->farkas_slack = us_lp_settings_resolve(&set->lp).farkas_slack;
    w->s = s;
    w->set = *set;
    w->lset = lcp ? *lcp : us_lcp_default_settings();
    if (set->max_pivots > 0) w->lset.max_pivots = set->max_pivots; /* the user's limit */
    w->reuse = reuse;
    w->last_body = -1;
  }
  if (!w || lcp_setup(w, s)) {
    lcp_destroy(w);
    us_error_set(err, US_ERR_NOMEM, "out of memory creating the LCP workspace");
    return NULL;
  }
  return w;
}

static void *create_scratch(const us_Structure *s, const us_StabilitySettings *set, us_Error *err) {
  return us_lcp_backend_create(s, set, NULL, 0, err);
}

static void *create_reuse(const us_Structure *s, const us_StabilitySettings *set, us_Error *err) {
  return us_lcp_backend_create(s, set, NULL, 1, err);
}

/* ------------------------------------------------------ mapping the test */

/* Is structure contact c live in p (operator y)? */
static int contact_live(const us_LcpSys *y, const us_Lcp *p, int c) {
  return y->nslot[c] > 0 && p->live[y->K * c + y->slots[(size_t)y->K * (size_t)c]];
}

/* Present flags and external forces of the bodies of sys in operator y. */
static void load_bodies(us_LcpSys *y, const us_EqSystem *sys) {
  size_t nw = (size_t)y->nw;
  for (int r = 0; r < sys->nbody; r++) {
    int b = sys->body[r];
    y->present[b] = 1;
    for (size_t k = 0; k < nw; k++) y->fext[nw * (size_t)b + k] = -sys->rhs[nw * (size_t)r + k];
  }
}

/* The LCP indices of structure contact c in operator y: 3D, its cone
 * generators (the slots last loaded); 2D, the normal, and the friction
 * (the friction LCP) or the cone's second edge (the cone LCP) when mu > 0. */
static int contact_indices(const LcpWs *w, const us_LcpSys *y, int c, int *out) {
  if (y->nw == 6) {
    const unsigned char *sl = y->slots + (size_t)y->K * (size_t)c;
    for (int m = 0; m < y->nslot[c]; m++) out[m] = y->K * c + sl[m];
    return y->nslot[c];
  }
  out[0] = 2 * c;
  if (!(w->s->contacts[c].mu > 0)) return 1;
  out[1] = 2 * c + 1;
  return 2;
}

static void start_scratch(LcpWs *w, us_LcpSys *y, us_Lcp *p, const us_EqSystem *sys) {
  us_lcp_reset(p);
  memset(y->present, 0, (size_t)y->nbody);
  load_bodies(y, sys);
  int k = 0;
  for (int ci = 0; ci < sys->ncontact; ci++) k += contact_indices(w, y, sys->contact[ci], w->idx + k);
  us_lcp_add(p, w->idx, k);
}

/* Removed bodies leave; their live contacts are faded out. */
static us_LcpResult remove_bodies(LcpWs *w, us_LcpSys *y, us_Lcp *p, const int *removed,
                                  int nremoved) {
  int k = 0;
  for (int j = 0; j < nremoved; j++) {
    int b = removed[j];
    y->present[b] = 0;
    for (int q = y->adj_start[b]; q < y->adj_start[b + 1]; q++) {
      int c = y->adj[q];
      if (!contact_live(y, p, c) || w->cmark[c]) continue;
      w->cmark[c] = 1;
      k += contact_indices(w, y, c, w->idx + k);
    }
  }
  for (int j = 0; j < k; j++) w->cmark[w->idx[j] / y->K] = 0;
  return k ? us_lcp_fade(p, w->idx, k) : US_LCP_SOLVED;
}

/* Added bodies arrive; contacts of sys that are not live join with f = 0.
 * Returns -1 if the live set then differs from sys (restart instead). */
static int add_bodies(LcpWs *w, us_LcpSys *y, us_Lcp *p, const us_EqSystem *sys) {
  load_bodies(y, sys);
  int k = 0, live = 0;
  for (int ci = 0; ci < sys->ncontact; ci++) {
    int c = sys->contact[ci];
    if (!contact_live(y, p, c)) k += contact_indices(w, y, c, w->idx + k);
  }
  us_lcp_add(p, w->idx, k);
  for (int c = 0; c < y->ncontact; c++) live += contact_live(y, p, c);
  int present = 0;
  for (int b = 0; b < y->nbody; b++) present += y->present[b];
  return live == sys->ncontact && present == sys->nbody ? 0 : -1;
}

/* Set up the LCP of sys, reusing the last state if allowed. 1 if reused,
 * 0 if started from scratch. */
static int prepare(LcpWs *w, const us_EqSystem *sys, const int *removed, int nremoved,
                   int restart) {
  if (w->reuse && w->valid && !restart) {
    if (remove_bodies(w, &w->sys, &w->lcp, removed, nremoved) == US_LCP_SOLVED &&
        add_bodies(w, &w->sys, &w->lcp, sys) == 0)
      return 1;
  }
  start_scratch(w, &w->sys, &w->lcp, sys);
  return 0;
}

/* --------------------------------------------------------------- verdict */

/* Clip round-off: normal forces >= 0, frictions inside their cones (a
 * friction with mu = +inf is free: nothing to clip, and inf * 0 must not
 * turn it into NaN). */
static void clip_forces(LcpWs *w, const us_EqSystem *sys) {
  double *f = w->lcp.f;
  for (int ci = 0; ci < sys->ncontact; ci++) {
    int c = sys->contact[ci];
    if (f[2 * c] < 0) f[2 * c] = 0.0;
    if (w->lcp.kind[2 * c + 1] != US_LCP_FRICTION) f[2 * c + 1] = 0.0;
    if (isinf(sys->mu[ci])) continue;
    double lim = sys->mu[ci] * f[2 * c];
    f[2 * c + 1] = US_MAX(-lim, US_MIN(lim, f[2 * c + 1]));
  }
}

static void write_forces(const LcpWs *w, const us_EqSystem *sys, double *f) {
  for (int ci = 0; ci < sys->ncontact; ci++) {
    int c = sys->contact[ci];
    f[2 * ci] = w->lcp.f[2 * c];
    f[2 * ci + 1] = w->lcp.f[2 * c + 1];
  }
}

/* The inverse: the LCP's forces from the system's (e.g. the LP's). */
static void read_forces(LcpWs *w, const us_EqSystem *sys, const double *f) {
  for (int ci = 0; ci < sys->ncontact; ci++) {
    int c = sys->contact[ci];
    w->lcp.f[2 * c] = f[2 * ci];
    if (w->lcp.kind[2 * c + 1] == US_LCP_FRICTION) w->lcp.f[2 * c + 1] = f[2 * ci + 1];
  }
}

/* Cone edge forces l (cone LCP indices) <-> contact forces (f_n, f_t):
 * f_n = l0 + l1, f_t = mu (l0 - l1) for a finite mu > 0; else the same. */
static void cone_to_forces(LcpWs *w, const us_EqSystem *sys, double *f) {
  const double *l = w->kc->lcp.f;
  if (sys->dim == 3) { /* 3D: through the generators (lp_gen.h) */
    for (int j = 0; j < w->gen.ncol; j++)
      w->lcol[j] = l[w->kc->sys.K * sys->contact[w->gen.col_contact[j]] + us_eq_gen_slot(&w->gen, j)];
    us_eq_gen_forces(sys, &w->gen, w->lcol, f);
    return;
  }
  for (int ci = 0; ci < sys->ncontact; ci++) {
    int c = sys->contact[ci];
    double mu = sys->mu[ci], l0 = l[2 * c], l1 = mu > 0 ? l[2 * c + 1] : 0.0;
    int edges = mu > 0 && !isinf(mu);
    f[2 * ci] = edges ? l0 + l1 : l0;
    f[2 * ci + 1] = edges ? mu * (l0 - l1) : l1;
  }
}

static void cone_from_forces(LcpWs *w, const us_EqSystem *sys, const double *f) {
  double *l = w->kc->lcp.f;
  for (int ci = 0; ci < sys->ncontact; ci++) {
    int c = sys->contact[ci];
    double mu = sys->mu[ci], fn = f[2 * ci], ft = f[2 * ci + 1];
    if (mu > 0 && !isinf(mu)) {
      l[2 * c] = US_MAX(0.0, 0.5 * (fn + ft / mu));
      l[2 * c + 1] = US_MAX(0.0, 0.5 * (fn - ft / mu));
    } else {
      l[2 * c] = fn;
      if (mu > 0) l[2 * c + 1] = ft;
    }
  }
}

static int frictionless(const us_EqSystem *sys) {
  for (int ci = 0; ci < sys->ncontact; ci++)
    if (sys->mu[ci] > 0) return 0;
  return 1;
}

/* Back-off after a failed run or seed (lcp-reuse): the next 2^(j-1) - 1
 * tests skip the LCP, j the number of failures in a row. */
static void record_failure(LcpWs *w) {
  if (!w->reuse) return;
  w->fails = US_MIN(w->fails + 1, w->lset.max_backoff);
  w->skip = (1L << (w->fails - 1)) - 1;
}

/* Whether this test skips the friction LCP (consumes one skipped test). */
static int skip_lcp(LcpWs *w, int restart) {
  if (!w->reuse) return 0;
  if (w->skip > 0) {
    w->skip--;
    w->valid = 0; /* the state no longer follows the sub-assemblies */
    return 1;
  }
  return w->scratch_failed && (!w->valid || restart);
}

/* Static forces f of sys (the LP's or the cone LCP's) re-seed the
 * friction LCP, whose state was dropped (lcp-reuse, not while backing
 * off), and the cone LCP if it has no state. Returns 1 if the friction
 * LCP was re-seeded, 0 if not, -1 out of memory. */
static int reseed(LcpWs *w, const us_EqSystem *sys, const double *f) {
  if (!w->reuse || sys->dim == 3) return 0; /* 3D: no friction LCP; the LP's
                                                forces name no cone edges */
  if (w->kc->ready && !w->kc->valid) {
    start_scratch(w, &w->kc->sys, &w->kc->lcp, sys);
    cone_from_forces(w, sys, f);
    us_LcpResult r = us_lcp_seed(&w->kc->lcp);
    if (r == US_LCP_NOMEM) return -1;
    w->kc->valid = r == US_LCP_SOLVED;
  }
  if (w->valid || w->skip > 0) return 0;
  start_scratch(w, &w->sys, &w->lcp, sys);
  read_forces(w, sys, f);
  us_LcpResult r = us_lcp_seed(&w->lcp);
  if (r == US_LCP_NOMEM) return -1;
  w->valid = r == US_LCP_SOLVED;
  if (!w->valid) record_failure(w);
  return w->valid;
}

/* The LP decides (CLP backend, lazily created). */
static us_Status fallback(LcpWs *w, const us_EqSystem *sys, us_Verdict *verdict, double *f,
                          us_StabilityInfo *info, const char *why, char *note, size_t note_sz,
                          us_Error *err) {
  if (!w->lpws) {
    w->lpws = us_backend_clp.create(w->s, &w->set, err);
    if (!w->lpws) return err ? err->code : US_ERR_NOMEM;
    us_backend_clp.set_deadline(w->lpws, w->lset.deadline);
  }
  char sub[96] = "";
  us_BackendOut out = {*verdict, f, info, sub, sizeof sub};
  us_Status st = us_backend_clp.solve(w->lpws, &(us_BackendProblem){.sys = sys, .restart = 1}, &out,
                                      err);
  *verdict = out.verdict;
  if (st) return st;
  info->lp_fallbacks++;
  w->by_lp = 1;
  if (*verdict == US_UNSTABLE && us_backend_clp.unstable_body)
    w->last_body = us_backend_clp.unstable_body(w->lpws);
  int seeded = *verdict == US_STABLE ? reseed(w, sys, f) : 0;
  if (seeded < 0) return us_error_set(err, US_ERR_NOMEM, "out of memory in the LCP");
  info->lcp_seeds += seeded;
  snprintf(note, note_sz, "LCP %s; LP: %s%s", why, sub, seeded ? "; LCP re-seeded from it" : "");
  return US_OK;
}

static const char *result_name(us_LcpResult r) {
  switch (r) {
  case US_LCP_SOLVED: return "solved";
  case US_LCP_LIMIT: return "hit the pivot limit";
  case US_LCP_DEGENERATE: return "degenerate";
  case US_LCP_NOMEM: return "out of memory";
  }
  return "?";
}

/* Exact instability with friction (the LCP solution need not be unique):
 * let f* be any static solution (J^T f* + F = 0, f* in the cones). With
 * a = A f + b = J v and v = M^-1 J^T (f - f*),
 *   v^T M v = (f - f*)^T a = f^T a - sum_c f*_c^T a_c.
 * If every contact's a_c lies in the dual cone (a_n >= mu |a_t|), each
 * f*_c^T a_c >= 0, so v^T M v <= f^T a (which is <= 0 for an LCP
 * solution: f_n a_n = 0, f_t a_t <= 0). A clearly positive v^T M v above
 * f^T a therefore proves that no static solution exists. (Self-stresses
 * s with J^T s = 0 add s^T J v = 0, so the round-off slack on the dual
 * cone test is not multiplied by arbitrarily large internal forces.)
 * This covers toppling and lifting off; sliding (a_n = 0, a_t != 0) does
 * not pass and goes to the cone LCP. */
/* a_c in the dual cone of contact c's cone, up to the slack: a_n >= mu
 * |a_t|; with mu = +inf (the cone is the half-space f_n >= 0) the dual
 * cone is the ray a_t = 0, a_n >= 0. */
static int in_dual_cone(double an, double at, double mu, double slack) {
  if (isinf(mu)) return fabs(at) <= slack && an >= -slack;
  return !(an < mu * fabs(at) - slack);
}

static int dual_cone_proof(LcpWs *w, const us_EqSystem *sys, double energy) {
  us_Lcp *p = &w->lcp;
  us_lcp_refresh(p);
  double fa = 0.0;
  for (int ci = 0; ci < sys->ncontact; ci++) {
    int c = sys->contact[ci];
    double an = p->a[2 * c], at = 0.0;
    fa += p->f[2 * c] * an;
    if (p->kind[2 * c + 1] == US_LCP_FRICTION) {
      at = p->a[2 * c + 1];
      fa += p->f[2 * c + 1] * at;
    }
    if (!in_dual_cone(an, at, sys->mu[ci], w->lset.cone_slack)) return 0;
  }
  return energy > US_MAX(fa, 0.0) + w->lset.energy_slack;
}

/* The same proof in the cone LCP's own indices: a contact's acceleration
 * is in its dual cone iff it does not move against either edge (a_e >= 0
 * for both edges; a_t = 0 for a free friction, mu = +inf), and f^T a is
 * sum l_e a_e. */
static int cone_dual_proof(LcpWs *w, const us_EqSystem *sys, double energy) {
  us_Lcp *p = &w->kc->lcp;
  double fa = 0.0, fmax = 0.0, dmax = 0.0;
  for (int i = 0; i < p->n; i++) {
    if (!p->live[i]) continue;
    fmax = US_MAX(fmax, fabs(p->f[i]));
    dmax = US_MAX(dmax, p->ops.entry(p->ops.ctx, i, i));
  }
  double slack = w->lset.cone_slack * (1.0 + fmax * dmax);
  us_lcp_refresh(p);
  for (int ci = 0; ci < sys->ncontact; ci++) {
    int nidx = contact_indices(w, &w->kc->sys, sys->contact[ci], w->idx);
    for (int m = 0; m < nidx; m++) {
      int i = w->idx[m];
      fa += p->f[i] * p->a[i];
      int ok = p->kind[i] == US_LCP_FRICTION ? fabs(p->a[i]) <= slack : p->a[i] >= -slack;
      if (!ok) return 0;
    }
  }
  return energy > US_MAX(fa, 0.0) + w->lset.energy_slack;
}

/* Automatic pivot limit of a run of p: a reused run is cut short sooner
 * than a scratch solve (a repair after a one-body change needs tens). */
static void set_limit(const LcpWs *w, us_Lcp *p, int reusing) {
  if (w->lset.max_pivots <= 0)
    p->set.max_pivots = reusing ? w->lset.reuse_pivots + p->n / w->lset.reuse_pivots_div : 0;
}

/* Solve the cone LCP of sys (reusing its last state where it has one).
 * 1 solved, 0 not, -1 out of memory. */
static int cone_solve(LcpWs *w, const us_EqSystem *sys, us_StabilityInfo *info) {
  Cone *k = w->kc;
  if (w->reuse && !k->valid && k->wait > 0) { /* back-off: its scratch solves fail */
    k->wait--;
    return 0;
  }
  if (cone_setup(w)) return -1;
  long piv0 = k->lcp.pivots;
  int reused = 0;
  set_limit(w, &k->lcp, w->reuse && k->valid);
  if (w->reuse && k->valid) {
    int ngone = 0;
    for (int r = 0; r < sys->nbody; r++) w->bmark[sys->body[r]] = 1;
    for (int b = 0; b < k->sys.nbody; b++)
      if (k->sys.present[b] && !w->bmark[b]) w->gone[ngone++] = b;
    for (int r = 0; r < sys->nbody; r++) w->bmark[sys->body[r]] = 0;
    reused = remove_bodies(w, &k->sys, &k->lcp, w->gone, ngone) == US_LCP_SOLVED &&
             add_bodies(w, &k->sys, &k->lcp, sys) == 0;
  }
  if (!reused) { /* a scratch solve gets the reuse limit too: on a large
                     wall it would cost more than the LP it saves */
    set_limit(w, &k->lcp, w->reuse);
    start_scratch(w, &k->sys, &k->lcp, sys);
  }
  us_LcpResult r = us_lcp_run(&k->lcp);
  info->pivots += k->lcp.pivots - piv0;
  k->valid = r == US_LCP_SOLVED;
  if (!reused) { /* after the j-th failed scratch solve in a row, 2^j - 1 requests wait */
    k->failed = k->valid ? 0 : US_MIN(k->failed + 1, w->lset.max_backoff);
    k->wait = k->valid ? 0 : (1L << k->failed) - 1;
  }
  return r == US_LCP_NOMEM ? -1 : k->valid;
}

/* 3D: live indices idx[0..k) of the cone LCP, f = 0 (lcp3_piv.c drives
 * them; the Dantzig queue is not used). */
static void make_live(us_Lcp *p, const int *idx, int k) {
  for (int m = 0; m < k; m++) {
    p->live[idx[m]] = 1;
    p->f[idx[m]] = 0.0;
    p->state[idx[m]] = US_LCP_NC;
  }
}

/* 3D reuse: the contacts of the bodies the cone LCP has and the test
 * lacks leave P and the LCP, the test's new contacts join with l = 0.
 * 1 if the live set then matches the test, 0 if not (start afresh). */
static int follow3(LcpWs *w, const us_EqSystem *sys) {
  Cone *k = w->kc;
  us_LcpSys *y = &k->sys;
  int ngone = 0, n = 0, live = 0;
  for (int r = 0; r < sys->nbody; r++) w->bmark[sys->body[r]] = 1;
  for (int b = 0; b < y->nbody; b++)
    if (y->present[b] && !w->bmark[b]) w->gone[ngone++] = b;
  for (int r = 0; r < sys->nbody; r++) w->bmark[sys->body[r]] = 0;
  for (int j = 0; j < ngone; j++) {
    int b = w->gone[j];
    y->present[b] = 0;
    for (int q = y->adj_start[b]; q < y->adj_start[b + 1]; q++)
      if (contact_live(y, &k->lcp, y->adj[q])) {
        n = contact_indices(w, y, y->adj[q], w->idx);
        us_lcp3_piv_drop(&k->piv, &k->lcp, w->idx, n);
      }
  }
  load_bodies(y, sys);
  for (int ci = 0; ci < sys->ncontact; ci++) {
    int c = sys->contact[ci];
    if (contact_live(y, &k->lcp, c)) continue;
    n = contact_indices(w, y, c, w->idx);
    make_live(&k->lcp, w->idx, n);
  }
  for (int c = 0; c < y->ncontact; c++) live += contact_live(y, &k->lcp, c);
  return live == sys->ncontact;
}

/* 3D: solve the cone LCP of sys by principal pivoting (lcp3_piv.c), from
 * the last sub-assembly's passive set where it has one (lcp-reuse). 1
 * solved, 0 not, -1 out of memory. */
static int cone_solve3(LcpWs *w, const us_EqSystem *sys, us_StabilityInfo *info) {
  Cone *k = w->kc;
  if (cone_setup(w)) return -1;
  long piv0 = k->lcp.pivots;
  int reused = w->reuse && k->valid && follow3(w, sys);
  if (!reused) {
    us_lcp_reset(&k->lcp);
    us_lcp3_piv_reset(&k->piv, k->lcp.n);
    memset(k->sys.present, 0, (size_t)k->sys.nbody);
    load_bodies(&k->sys, sys);
    int n = 0;
    for (int ci = 0; ci < sys->ncontact; ci++) n += contact_indices(w, &k->sys, sys->contact[ci], w->idx + n);
    make_live(&k->lcp, w->idx, n);
  }
  int live = 0;
  for (int ci = 0; ci < sys->ncontact; ci++) live += k->sys.nslot[sys->contact[ci]];
  long limit = w->lset.max_pivots > 0 ? w->lset.max_pivots
                                      : w->lset.pivots_per_index * (long)live + w->lset.pivots_base;
  us_LcpResult r = us_lcp3_piv_run(&k->piv, &k->lcp, limit);
  info->pivots += k->lcp.pivots - piv0;
  info->reused += reused;
  k->valid = r == US_LCP_SOLVED;
  return r == US_LCP_NOMEM ? -1 : k->valid;
}

/* Edge forces >= 0 (round-off), then the cone LCP's net wrench: its
 * largest component, the body, and the energy v^T M v. */
static double cone_residual(LcpWs *w, int *worst, double *energy) {
  us_Lcp *p = &w->kc->lcp;
  for (int i = 0; i < p->n; i++)
    if (p->live[i] && p->kind[i] == US_LCP_NORMAL && p->f[i] < 0) p->f[i] = 0.0;
  return us_lcp_sys_residual(&w->kc->sys, p->f, worst, energy);
}

/* The proof failed on a_e >= -tol_a, which the Dantzig run accepts (times
 * the scale): run once more with the proof's round-off slack. 1 ran to a
 * solution (*res etc. fresh), 0 not, -1 out of memory. */
static int cone_rerun(LcpWs *w, us_StabilityInfo *info, double *res, int *worst, double *energy) {
  us_Lcp *p = &w->kc->lcp;
  double tol = p->set.tol_a;
  long piv0 = p->pivots;
  p->set.tol_a = w->lset.cone_slack;
  us_LcpResult rr = us_lcp_run(p);
  p->set.tol_a = tol;
  info->pivots += p->pivots - piv0;
  if (rr == US_LCP_NOMEM) return -1;
  w->kc->valid = rr == US_LCP_SOLVED;
  if (rr != US_LCP_SOLVED) return 0;
  *res = cone_residual(w, worst, energy);
  return 1;
}

/* The same for 3D: the pivoting goes on from its passive set until no a
 * is below the proof's slack (its own stop is a >= -tol_a). */
static int cone_rerun3(LcpWs *w, us_StabilityInfo *info, double *res, int *worst, double *energy) {
  us_Lcp *p = &w->kc->lcp;
  double tol = p->set.tol_a, fmax = 0.0, dmax = 0.0;
  for (int i = 0; i < p->n; i++) {
    if (!p->live[i]) continue;
    fmax = US_MAX(fmax, fabs(p->f[i]));
    dmax = US_MAX(dmax, p->ops.entry(p->ops.ctx, i, i));
  }
  long piv0 = p->pivots;
  p->set.tol_a = 0.5 * w->lset.cone_slack * (1.0 + fmax * dmax);
  us_LcpResult rr = us_lcp3_piv_run(&w->kc->piv, p, w->lset.pivots_base);
  p->set.tol_a = tol;
  info->pivots += p->pivots - piv0;
  if (rr == US_LCP_NOMEM) return -1;
  w->kc->valid = rr == US_LCP_SOLVED;
  if (rr != US_LCP_SOLVED) return 0;
  *res = cone_residual(w, worst, energy);
  return 1;
}

/* 3D: the accelerations v = M^-1 (G l - rhs) of the cone LCP's solution
 * as a Farkas ray of G l = rhs, l >= 0 (docs/lcp.md, "3D"): G^T v = a >= 0
 * is every generator's acceleration and rhs . v = f^T a - v^T M v < 0.
 * Checked without the solver (us_eq_gen_farkas_body) and kept for the
 * front end's mechanism (farkas_ray). The body it points at, or -1. */
static int cone_ray(LcpWs *w, const us_EqSystem *sys) {
  size_t nw = (size_t)sys->nw;
  double *vel = w->ray + nw * (size_t)sys->nbody;
  us_lcp_sys_velocity(&w->kc->sys, w->kc->lcp.f, vel);
  for (int r = 0; r < sys->nbody; r++)
    memcpy(w->ray + nw * (size_t)r, vel + nw * (size_t)sys->body[r], nw * sizeof(double));
  int body = us_eq_gen_farkas_body(sys, &w->gen, w->ray, w->farkas_slack);
  w->nray = body >= 0 ? sys->nbody * sys->nw : 0;
  return body;
}

/* The verdict of the cone LCP's forces (its Dantzig run's, rerun allowed,
 * or Lemke's): 1 decided (verdict, forces f), 0 not, -1 out of memory.
 * Stable: its net wrench is ~0; unstable: a clear net wrench with the
 * dual-cone proof (which a solution of this PSD LCP satisfies up to
 * round-off). `by` names the solver in the note. */
static int cone_verdict(LcpWs *w, const us_EqSystem *sys, us_Verdict *verdict, double *f,
                        us_StabilityInfo *info, int rerun, const char *by, const char *why,
                        char *note, size_t note_sz) {
  int worst = -1;
  double energy = 0.0, res = cone_residual(w, &worst, &energy);
  if (res <= w->lset.eq_tol) {
    *verdict = US_STABLE;
    cone_to_forces(w, sys, f);
    int seeded = reseed(w, sys, f);
    if (seeded < 0) return -1;
    info->lcp_seeds += seeded;
    snprintf(note, note_sz, "LCP %s; %s: equilibrium (residual %.1e)%s", why, by, res,
             seeded ? "; LCP re-seeded from it" : "");
    return 1;
  }
  if (rerun && res >= w->lset.unstable_tol && !cone_dual_proof(w, sys, energy)) {
    int r = sys->dim == 3 ? cone_rerun3(w, info, &res, &worst, &energy)
                          : cone_rerun(w, info, &res, &worst, &energy);
    if (r <= 0) return r;
  }
  if (!(res >= w->lset.unstable_tol && cone_dual_proof(w, sys, energy))) return 0;
  if (sys->dim == 3 && cone_ray(w, sys) < 0) return 0;
  *verdict = US_UNSTABLE;
  w->last_body = worst;
  snprintf(note, note_sz, "LCP %s; %s: bodies accelerate (net wrench %.2g W on '%s')", why, by,
           res, us_id_text(w->s->bodies[worst].id).s);
  return 1;
}

/* The cone LCP by Lemke (lcp_lemke.c) where its Dantzig run failed or
 * left the verdict open: from the start on the test's live set, then the
 * same verdict. The cone LCP's state no longer follows its forces: it is
 * dropped (a stable verdict re-seeds it). 1, 0 or -1 as cone_verdict. */
static int cone_lemke_decide(LcpWs *w, const us_EqSystem *sys, us_Verdict *verdict, double *f,
                             us_StabilityInfo *info, const char *why, char *note,
                             size_t note_sz) {
  Cone *k = w->kc;
  if (cone_setup(w)) return -1;
  start_scratch(w, &k->sys, &k->lcp, sys);
  k->valid = 0;
  us_LcpLemkeEnd e = us_lcp_lemke(&k->lemke, &k->lcp, w->lset.lemke_max_dim, &info->pivots);
  if (e == US_LCP_LEMKE_NOMEM) return -1;
  if (e == US_LCP_LEMKE_TOO_BIG || e == US_LCP_LEMKE_NOT_PSD) return 0;
  int r = e == US_LCP_LEMKE_SOLVED
              ? cone_verdict(w, sys, verdict, f, info, 0, "cone LCP by Lemke", why, note, note_sz)
              : 0;
  if (r >= 0) *(r ? &info->cone_lemke : &info->cone_lemke_failed) += 1;
  return r;
}

/* The cone LCP decides: its Dantzig run (reused where it can be), then
 * Lemke where that fails. 1 decided, 0 not (the LP will), -1 out of
 * memory. */
static int cone_decide(LcpWs *w, const us_EqSystem *sys, us_Verdict *verdict, double *f,
                       us_StabilityInfo *info, const char *why, char *note, size_t note_sz) {
  int r = sys->dim == 3 ? cone_solve3(w, sys, info) : cone_solve(w, sys, info);
  if (r > 0) r = cone_verdict(w, sys, verdict, f, info, 1, "cone LCP", why, note, note_sz);
  if (r != 0) return r;
  return cone_lemke_decide(w, sys, verdict, f, info, why, note, note_sz);
}

/* Settle a test the friction LCP did not decide: the cone LCP, then the LP. */
static us_Status settle(LcpWs *w, const us_EqSystem *sys, us_Verdict *verdict, double *f,
                        us_StabilityInfo *info, const char *why, char *note, size_t note_sz,
                        us_Error *err) {
  int r = cone_decide(w, sys, verdict, f, info, why, note, note_sz);
  if (r < 0) return us_error_set(err, US_ERR_NOMEM, "out of memory in the LCP");
  return r ? US_OK : fallback(w, sys, verdict, f, info, why, note, note_sz, err);
}

static us_Status decide(LcpWs *w, const us_EqSystem *sys, us_Verdict *verdict, double *f,
                        us_StabilityInfo *info, char *note, size_t note_sz, us_Error *err) {
  clip_forces(w, sys);
  int worst = -1;
  double energy = 0.0;
  double res = us_lcp_sys_residual(&w->sys, w->lcp.f, &worst, &energy);
  if (res <= w->lset.eq_tol) {
    *verdict = US_STABLE;
    write_forces(w, sys, f);
    snprintf(note, note_sz, "LCP: equilibrium (residual %.1e)", res);
    return US_OK;
  }
  int fl = frictionless(sys);
  if (res >= w->lset.unstable_tol && (fl || dual_cone_proof(w, sys, energy))) {
    *verdict = US_UNSTABLE;
    w->last_body = worst;
    snprintf(note, note_sz, "LCP: bodies accelerate (net wrench %.2g W on '%s'%s)", res,
             us_id_text(w->s->bodies[worst].id).s, fl ? "" : ", dual-cone proof");
    return US_OK;
  }
  char why[64];
  snprintf(why, sizeof why, "%s (net wrench %.2g W)",
           fl ? "residual in the gray zone" : "sliding solution", res);
  return settle(w, sys, verdict, f, info, why, note, note_sz, err);
}

/* 3D: the columns of the cone LCP of this test's polygons (the front
 * end's inner or outer ones) into its operator; a live contact whose
 * columns changed (a refinement) drops the LCP's state. */
static void load3(LcpWs *w, const us_EqSystem *sys) {
  Cone *k = w->kc;
  us_lcp3_sys_load(&k->sys, sys, &w->gen, w->changed);
  for (int ci = 0; ci < sys->ncontact; ci++) {
    int c = sys->contact[ci];
    if (!w->changed[c]) continue;
    w->changed[c] = 0;
    for (int i = k->sys.K * c; i < k->sys.K * (c + 1) && k->valid; i++)
      if (k->lcp.live[i]) k->valid = 0;
  }
}

/* 3D: the cone LCP on the test's generators (no friction LCP: docs/lcp.md,
 * "3D"), reused where it can be, then Lemke, then the LP (settle). */
static us_Status solve3(LcpWs *w, const us_EqSystem *sys, us_Verdict *verdict, double *f,
                        us_StabilityInfo *info, char *note, size_t note_sz, us_Error *err) {
  int outer = sys->cones && sys->cones->mode == US_CONE_OUTER;
  w->kc = &w->cones[outer];
  if (us_eq_generators(sys, DBL_MAX, &w->gen) || US_GROW(w->lcol, w->cap_lcol, w->gen.ncol + 1))
    return us_error_set(err, US_ERR_NOMEM, "out of memory building the 3D LCP");
  if (w->gen.ncol == 0) {
    *verdict = us_eq_no_columns_verdict(sys);
    snprintf(note, note_sz, "no active contact");
    return US_OK;
  }
  if (cone_setup(w)) return us_error_set(err, US_ERR_NOMEM, "out of memory in the LCP");
  load3(w, sys);
  return settle(w, sys, verdict, f, info, outer ? "3D, outer cones" : "3D, inner cones", note,
                note_sz, err);
}

static us_Status lcp_solve(void *ws, const us_BackendProblem *pb, us_BackendOut *out,
                           us_Error *err) {
  /* the problem and the output under the names the body reads */
  const us_EqSystem *sys = pb->sys;
  const int *removed = pb->removed;
  int nremoved = pb->nremoved, restart = pb->restart;
  us_Verdict *verdict = &out->verdict;
  double *f = out->f;
  us_StabilityInfo *info = out->info;
  char *note = out->note;
  size_t note_sz = out->note_sz;
  LcpWs *w = ws;
  w->last_body = -1;
  w->nray = w->by_lp = 0;
  if (sys->dim == 3) return solve3(w, sys, verdict, f, info, note, note_sz, err);
  if (skip_lcp(w, restart)) {
    info->lcp_skips++;
    char why[64];
    snprintf(why, sizeof why, "skipped after %d failed run%s", w->fails, w->fails == 1 ? "" : "s");
    return settle(w, sys, verdict, f, info, why, note, note_sz, err);
  }
  long piv0 = w->lcp.pivots;
  int can_reuse = w->reuse && w->valid && !restart;
  set_limit(w, &w->lcp, can_reuse);
  int reused = prepare(w, sys, removed, nremoved, restart);
  if (can_reuse && !reused && w->scratch_failed) { /* the fade failed: no scratch run */
    info->pivots += w->lcp.pivots - piv0;
    w->valid = 0;
    record_failure(w);
    return settle(w, sys, verdict, f, info, "repair failed", note, note_sz, err);
  }
  if (!reused) set_limit(w, &w->lcp, 0);
  us_LcpResult r = us_lcp_run(&w->lcp);
  int retried = reused && (r == US_LCP_DEGENERATE || r == US_LCP_LIMIT);
  if (retried) { /* a failed repair: this test from scratch, under the reuse limit */
    start_scratch(w, &w->sys, &w->lcp, sys);
    reused = 0;
    r = us_lcp_run(&w->lcp);
    info->lcp_retries++;
  }
  info->pivots += w->lcp.pivots - piv0;
  info->reused += reused;
  w->valid = r == US_LCP_SOLVED;
  if (r == US_LCP_NOMEM) return us_error_set(err, US_ERR_NOMEM, "out of memory in the LCP");
  if (r == US_LCP_SOLVED) w->fails = 0;
  if (r != US_LCP_SOLVED) {
    w->scratch_failed |= !reused && !retried; /* a limited retry proves nothing */
    record_failure(w);
    char why[96];
    snprintf(why, sizeof why, "%s%s%s", result_name(r), r == US_LCP_DEGENERATE ? ": " : "",
             r == US_LCP_DEGENERATE && w->lcp.why ? w->lcp.why : "");
    return settle(w, sys, verdict, f, info, why, note, note_sz, err);
  }
  return decide(w, sys, verdict, f, info, note, note_sz, err);
}

static int lcp_unstable_body(void *ws) { return ((LcpWs *)ws)->last_body; }

/* 3D only (2D keeps its verdicts without a mechanism): the cone LCP's
 * checked ray, or the LP's where the LP decided. */
static int lcp_farkas_ray(void *ws, const double **y) {
  LcpWs *w = ws;
  *y = NULL;
  if (w->s->dim != 3) return 0;
  if (w->by_lp) return w->lpws ? us_backend_clp.farkas_ray(w->lpws, y) : 0;
  *y = w->nray ? w->ray : NULL;
  return w->nray;
}

const us_Backend us_backend_lcp = {
    .method = US_METHOD_LCP,
    .create = create_scratch,
    .destroy = lcp_destroy,
    .solve = lcp_solve,
    .unstable_body = lcp_unstable_body,
    .farkas_ray = lcp_farkas_ray,
    .set_deadline = lcp_set_deadline,
};
const us_Backend us_backend_lcp_reuse = {
    .method = US_METHOD_LCP_REUSE,
    .create = create_reuse,
    .destroy = lcp_destroy,
    .solve = lcp_solve,
    .unstable_body = lcp_unstable_body,
    .farkas_ray = lcp_farkas_ray,
    .set_deadline = lcp_set_deadline,
};
