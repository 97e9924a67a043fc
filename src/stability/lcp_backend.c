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
 *     although a static one exists; the gray zone between the thresholds;
 *     a pivot limit or a degenerate run) the LP decides: the CLP backend,
 *     created lazily inside this workspace, counted in info->lp_fallbacks.
 * Reuse: the workspace keeps forces, index sets and the factorized clamped
 * system. Removed bodies: their contacts' rows leave the factorization and
 * their forces are faded to zero along a line while every other index
 * keeps its conditions (pivoting where one would break), which repairs the
 * solution locally. Added bodies: their contacts join with zero force and
 * only they are driven. Old contacts keep their forces in both cases.
 * After a failed run the state is dropped; a stable LP verdict re-seeds it.
 * Back-off (lcp-reuse only): where the LCP keeps failing (large degenerate
 * walls: long runs of zero-length exchanges), the tests go straight to the
 * LP instead of paying for failing runs. After the j-th failed run in a
 * row, the next 2^(j-1) - 1 tests skip the LCP (an isolated failure costs
 * nothing: the next test reuses again); once a scratch solve of the
 * workspace has failed, a test that cannot reuse goes to the LP too
 * (a scratch run would fail again, at the full pivot limit). Skipped tests
 * are counted in info->lcp_skips; verdicts never depend on the policy.
 * The thresholds above (1e-9 W, 1e-6 W, the reuse pivot limit, the
 * back-off cap) are fields of us_LcpSettings (lcp.h), defaults unless a
 * workspace is made by us_lcp_backend_create with others. A contact with
 * mu = +inf is never clipped into a cone, and its dual cone is the ray
 * a_t = 0, a_n >= 0.
 */
#include "lcp_backend.h"

#include "lcp.h"
#include "lcp_sys.h"
#include "backend.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct LcpWs {
  const us_Structure *s;
  us_StabilitySettings set;
  us_LcpSettings lset; /* limits and tolerances (lcp.h) */
  int reuse; /* the reuse backend */
  int valid; /* lcp holds the solution of the last sub-assembly */
  us_LcpSys sys;
  us_Lcp lcp;
  int *idx;   /* [2 ncontact + 1] */
  unsigned char *cmark; /* [ncontact + 1] contacts listed, kept zero */
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
  if (w->lpws) us_backend_clp.set_deadline(w->lpws, deadline);
}

static void lcp_destroy(void *ws) {
  LcpWs *w = ws;
  if (!w) return;
  us_lcp_free(&w->lcp);
  us_lcp_sys_free(&w->sys);
  if (w->lpws) us_backend_clp.destroy(w->lpws);
  us_free(w->idx);
  us_free(w->cmark);
  us_free(w);
}

static int lcp_setup(LcpWs *w, const us_Structure *s) {
  if (us_lcp_sys_init(&w->sys, s)) return -1;
  us_LcpOps ops = us_lcp_sys_ops(&w->sys);
  if (us_lcp_init(&w->lcp, 2 * s->ncontact, &ops)) return -1;
  us_lcp_configure(&w->lcp, &w->lset);
  for (int c = 0; c < s->ncontact; c++)
    if (s->contacts[c].mu > 0) us_lcp_set_friction(&w->lcp, 2 * c + 1, 2 * c, s->contacts[c].mu);
  w->idx = us_malloc((size_t)(2 * s->ncontact + 1) * sizeof(int));
  w->cmark = us_calloc((size_t)s->ncontact + 1, 1);
  return w->idx && w->cmark ? 0 : -1;
}

void *us_lcp_backend_create(const us_Structure *s, const us_StabilitySettings *set,
                            const us_LcpSettings *lcp, int reuse, us_Error *err) {
  if (s->dim != 2) {
    us_error_set(err, US_ERR_USAGE, "the LCP backends support 2D structures only");
    return NULL;
  }
  LcpWs *w = us_calloc(1, sizeof *w);
  if (w) {
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

/* Present flags and external forces of the bodies of sys. */
static void load_bodies(LcpWs *w, const us_EqSystem *sys) {
  for (int r = 0; r < sys->nbody; r++) {
    int b = sys->body[r];
    w->sys.present[b] = 1;
    for (int k = 0; k < 3; k++) w->sys.fext[3 * (size_t)b + (size_t)k] = -sys->rhs[3 * r + k];
  }
}

/* The LCP indices of structure contact c. */
static int contact_indices(const LcpWs *w, int c, int *out) {
  out[0] = 2 * c;
  if (w->lcp.kind[2 * c + 1] != US_LCP_FRICTION) return 1;
  out[1] = 2 * c + 1;
  return 2;
}

static void start_scratch(LcpWs *w, const us_EqSystem *sys) {
  us_lcp_reset(&w->lcp);
  memset(w->sys.present, 0, (size_t)w->sys.nbody);
  load_bodies(w, sys);
  int k = 0;
  for (int ci = 0; ci < sys->ncontact; ci++) k += contact_indices(w, sys->contact[ci], w->idx + k);
  us_lcp_add(&w->lcp, w->idx, k);
}

/* Removed bodies leave; their live contacts are faded out. */
static us_LcpResult remove_bodies(LcpWs *w, const int *removed, int nremoved) {
  us_LcpSys *y = &w->sys;
  int k = 0;
  for (int j = 0; j < nremoved; j++) {
    int b = removed[j];
    y->present[b] = 0;
    for (int q = y->adj_start[b]; q < y->adj_start[b + 1]; q++) {
      int c = y->adj[q];
      if (!w->lcp.live[2 * c] || w->cmark[c]) continue;
      w->cmark[c] = 1;
      k += contact_indices(w, c, w->idx + k);
    }
  }
  for (int j = 0; j < k; j++) w->cmark[w->idx[j] >> 1] = 0;
  return k ? us_lcp_fade(&w->lcp, w->idx, k) : US_LCP_SOLVED;
}

/* Added bodies arrive; contacts of sys that are not live join with f = 0.
 * Returns -1 if the live set then differs from sys (restart instead). */
static int add_bodies(LcpWs *w, const us_EqSystem *sys) {
  load_bodies(w, sys);
  int k = 0, live = 0;
  for (int ci = 0; ci < sys->ncontact; ci++) {
    int c = sys->contact[ci];
    if (!w->lcp.live[2 * c]) k += contact_indices(w, c, w->idx + k);
  }
  us_lcp_add(&w->lcp, w->idx, k);
  for (int c = 0; c < w->sys.ncontact; c++) live += w->lcp.live[2 * c];
  int present = 0;
  for (int b = 0; b < w->sys.nbody; b++) present += w->sys.present[b];
  return live == sys->ncontact && present == sys->nbody ? 0 : -1;
}

/* Set up the LCP of sys, reusing the last state if allowed. 1 if reused,
 * 0 if started from scratch. */
static int prepare(LcpWs *w, const us_EqSystem *sys, const int *removed, int nremoved,
                   int restart) {
  if (w->reuse && w->valid && !restart) {
    if (remove_bodies(w, removed, nremoved) == US_LCP_SOLVED && add_bodies(w, sys) == 0) return 1;
  }
  start_scratch(w, sys);
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

/* Whether this test goes straight to the LP (consumes one skipped test). */
static int skip_lcp(LcpWs *w, int restart) {
  if (!w->reuse) return 0;
  if (w->skip > 0) {
    w->skip--;
    w->valid = 0; /* the state no longer follows the sub-assemblies */
    return 1;
  }
  return w->scratch_failed && (!w->valid || restart);
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
  us_Status st = us_backend_clp.solve(w->lpws, sys, NULL, 0, NULL, 0, 1, verdict, f, info, sub,
                                      sizeof sub, err);
  if (st) return st;
  info->lp_fallbacks++;
  if (*verdict == US_UNSTABLE && us_backend_clp.unstable_body)
    w->last_body = us_backend_clp.unstable_body(w->lpws);
  const char *seeded = "";
  if (w->reuse && !w->valid && w->skip == 0 && *verdict == US_STABLE) {
    /* reuse goes on from the LP's forces (the live set made that of sys:
     * a skipped test or a failed fade leaves another) */
    start_scratch(w, sys);
    read_forces(w, sys, f);
    us_LcpResult r = us_lcp_seed(&w->lcp);
    if (r == US_LCP_NOMEM) return us_error_set(err, US_ERR_NOMEM, "out of memory in the LCP");
    w->valid = r == US_LCP_SOLVED;
    if (!w->valid) record_failure(w);
    info->lcp_seeds += w->valid;
    seeded = w->valid ? "; LCP re-seeded from it" : "";
  }
  snprintf(note, note_sz, "LCP %s; LP: %s%s", why, sub, seeded);
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
 * not pass and goes to the LP. */
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
  return fallback(w, sys, verdict, f, info, why, note, note_sz, err);
}

static us_Status lcp_solve(void *ws, const us_EqSystem *sys, const int *added, int nadded,
                           const int *removed, int nremoved, int restart, us_Verdict *verdict,
                           double *f, us_StabilityInfo *info, char *note, size_t note_sz,
                           us_Error *err) {
  US_UNUSED(added), US_UNUSED(nadded);
  LcpWs *w = ws;
  w->last_body = -1;
  if (sys->dim != 2) return us_error_set(err, US_ERR_USAGE, "the LCP backends support 2D only");
  if (skip_lcp(w, restart)) {
    info->lcp_skips++;
    char why[64];
    snprintf(why, sizeof why, "skipped after %d failed run%s", w->fails, w->fails == 1 ? "" : "s");
    return fallback(w, sys, verdict, f, info, why, note, note_sz, err);
  }
  long piv0 = w->lcp.pivots;
  int can_reuse = w->reuse && w->valid && !restart;
  /* a repair after a one-body change needs tens of pivots; one that runs
   * long (the fade of the removed contacts, then the run) is cut short
   * sooner than a scratch solve (the LP settles it and reseeds the LCP) */
  int auto_limit = w->lset.max_pivots <= 0;
  if (auto_limit)
    w->lcp.set.max_pivots = can_reuse ? w->lset.reuse_pivots + w->lcp.n / w->lset.reuse_pivots_div : 0;
  int reused = prepare(w, sys, removed, nremoved, restart);
  if (can_reuse && !reused && w->scratch_failed) { /* the fade failed: no scratch run */
    info->pivots += w->lcp.pivots - piv0;
    w->valid = 0;
    record_failure(w);
    return fallback(w, sys, verdict, f, info, "repair failed", note, note_sz, err);
  }
  if (auto_limit && !reused) w->lcp.set.max_pivots = 0;
  us_LcpResult r = us_lcp_run(&w->lcp);
  info->pivots += w->lcp.pivots - piv0;
  info->reused += reused;
  w->valid = r == US_LCP_SOLVED;
  if (r == US_LCP_NOMEM) return us_error_set(err, US_ERR_NOMEM, "out of memory in the LCP");
  if (r == US_LCP_SOLVED) w->fails = 0;
  if (r != US_LCP_SOLVED) {
    w->scratch_failed |= !reused;
    record_failure(w);
    char why[96];
    snprintf(why, sizeof why, "%s%s%s", result_name(r), r == US_LCP_DEGENERATE ? ": " : "",
             r == US_LCP_DEGENERATE && w->lcp.why ? w->lcp.why : "");
    return fallback(w, sys, verdict, f, info, why, note, note_sz, err);
  }
  return decide(w, sys, verdict, f, info, note, note_sz, err);
}

static int lcp_unstable_body(void *ws) { return ((LcpWs *)ws)->last_body; }

const us_Backend us_backend_lcp = {
    .method = US_METHOD_LCP,
    .create = create_scratch,
    .destroy = lcp_destroy,
    .solve = lcp_solve,
    .unstable_body = lcp_unstable_body,
    .set_deadline = lcp_set_deadline,
};
const us_Backend us_backend_lcp_reuse = {
    .method = US_METHOD_LCP_REUSE,
    .create = create_reuse,
    .destroy = lcp_destroy,
    .solve = lcp_solve,
    .unstable_body = lcp_unstable_body,
    .set_deadline = lcp_set_deadline,
};
