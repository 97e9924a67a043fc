/* Critical friction: the smallest Coulomb coefficient mu which, put on
 * every contact alike, lets a sub-assembly stand.
 *
 * Statement. For a sub-assembly X let F(mu) be the set of contact forces
 * with f_n >= 0 and |f_t| <= mu f_n at every active contact that balance
 * gravity on every body of X; X stands at mu iff F(mu) is not empty. The
 * cones grow with mu, so F(mu) is contained in F(mu') for mu <= mu':
 * standing is monotone in mu, and mu* = inf { mu : F(mu) not empty } is a
 * threshold (below it X falls, above it X stands).
 *
 * Why bisection and not one LP: minimising mu over (mu, f) is not an LP
 * (mu multiplies f_n in the cone rows, in any variables: with the cone
 * edges of the LP backends f = l1 (n + mu t) + l2 (n - mu t) the product
 * moves into the columns). It is a quasi-convex problem, each level set
 * F(mu) being a polyhedron, and the stability backends answer exactly the
 * level-set question with a certificate. So the search is a bisection on
 * verdicts, each probe a stability test of a private copy of the structure
 * whose contacts all carry the probe's mu.
 *
 * Algorithm: probe mu = 0 (stands: the answer is 0), then mu_max (falls:
 * no coefficient up to mu_max works). Otherwise the bracket lo = 0 (falls)
 * < hi = mu_max (stands) is narrowed until hi - lo <= tol: at the
 * geometric mean of max(lo, tol) and hi while hi is more than 4 times that
 * (so the magnitude of mu* is found in O(log log(mu_max / tol)) probes),
 * then at the arithmetic mean. The answer is hi, the smallest probe that
 * stood; its forces are re-checked with the certificate check against the
 * copy with every mu = hi. Default settings (tol 1e-7, mu_max 1e3): 23 to
 * 30 probes for answers between 0.01 and 1 (plain halving: 36).
 *
 * Time: the settings' time_limit bounds the whole search (each probe gets
 * what is left). Past it the bisection stops with the bracket as it is
 * (timed_out; a probe cut by it counts as not standing but is not an
 * undecided test): hi, when some probe stood, is a certified upper bound,
 * and no other conclusion holds.
 *
 * Invariants: hi always stood with a certificate that passed (a stable
 * verdict of the stability front end), lo never did; an UNDECIDED verdict
 * counts as not standing (and is counted), so the answer never rests on an
 * unchecked claim. mu* lies in (lo, hi], hence |hi - mu*| <= tol at the
 * end, up to the backend's acceptance: a certificate passes with cone
 * violations below cert_tol * W, so a backend that solves loosely
 * (lp_solve) may land a little below mu*. mu* need not be attained (a box
 * pinched between two walls stands for every mu > 0, not at 0).
 *
 * The copy (the "view") is a struct copy of the structure that shares its
 * bodies and internal part (id index, finalized) read-only and owns its
 * contacts array. It is never
 * handed to us_structure_free. One stability workspace per probe: a
 * backend may keep per-contact data from its creation (the LCP keeps the
 * coefficients), so a workspace must not outlive a change of mu.
 */
#include "core/core.h"
#include "stability/certificate.h" /* us_certificate_check_buf */

#include <math.h>
#include <string.h>

#define US_FRICTION_TOL 1e-7    /* default absolute tolerance on mu */
#define US_FRICTION_MU_MAX 1e3  /* default largest coefficient tried */
#define US_FRICTION_GEOMETRIC 4 /* geometric steps while hi > this * max(lo, tol) */

typedef struct FrictionCtx {
  us_Structure view;             /* the structure with its own contacts */
  const us_StabilitySettings *set;
  us_Bitset present;             /* the sub-assembly tested */
  us_StabilityResult res;        /* reused by every probe */
  double *acc;                   /* certificate scratch: US_CERT_ACC * nbody */
  unsigned char *seen;           /* certificate scratch: ncontact */
  double t_end;                  /* us_now() when set->time_limit runs out; 0: none */
} FrictionCtx;

/* --------------------------------------------------------------- result */

void us_friction_result_free(us_FrictionResult *r) {
  if (!r) return;
  us_forces_free(&r->forces);
  memset(r, 0, sizeof *r);
}

static void result_reset(us_FrictionResult *r) {
  memset(r, 0, sizeof *r);
  r->mu_critical = r->mu_high = INFINITY;
  r->check.worst_body = r->check.worst_contact = -1;
}

/* dst = src (dst's arrays grow as needed). 0 or -1 on OOM. */
static int forces_copy(us_Forces *dst, const us_Forces *src, int dim) {
  int n = src->ncontact;
  if (n > dst->cap) {
    int *c = us_realloc(dst->contact, (size_t)n * sizeof(int));
    if (!c) return -1;
    dst->contact = c;
    double *f = us_realloc(dst->f, (size_t)n * 3 * sizeof(double));
    if (!f) return -1;
    dst->f = f;
    dst->cap = n;
  }
  dst->ncontact = n;
  if (n > 0) {
    memcpy(dst->contact, src->contact, (size_t)n * sizeof(int));
    memcpy(dst->f, src->f, (size_t)n * (size_t)dim * sizeof(double));
  }
  return 0;
}

/* ---------------------------------------------------------------- setup */

static us_Status check_args(const us_Structure *s, const us_Bitset *present, double tol,
                            double mu_max, const us_FrictionResult *out, us_Error *err) {
  if (!s || !out) return us_error_set(err, US_ERR_USAGE, "us_critical_friction: NULL argument");
  if (!us_structure_is_finalized(s))
    return us_error_set(err, US_ERR_USAGE, "us_critical_friction: the structure is not finalized");
  if (present && (present->nbits != s->nbody || !present->w))
    return us_error_set(err, US_ERR_USAGE, "us_critical_friction: sub-assembly has %d bits, "
                        "the structure %d bodies", present->nbits, s->nbody);
  if (!isfinite(tol) || !isfinite(mu_max))
    return us_error_set(err, US_ERR_USAGE, "us_critical_friction: tol (%g) and mu_max (%g) "
                        "must be finite", tol, mu_max);
  return US_OK;
}

static void ctx_free(FrictionCtx *x) {
  us_free(x->view.contacts);
  us_bitset_free(&x->present);
  us_stability_result_free(&x->res);
  us_free(x->acc);
  us_free(x->seen);
}

/* The view, the sub-assembly and the scratch. 0 or -1 on OOM. */
static int ctx_init(FrictionCtx *x, const us_Structure *s, const us_Bitset *present) {
  size_t nc = (size_t)US_MAX(s->ncontact, 1), nb = (size_t)US_MAX(s->nbody, 1);
  x->view = *s;
  x->view.contacts = us_malloc(nc * sizeof(us_Contact));
  x->acc = us_malloc(US_CERT_ACC * nb * sizeof(double));
  x->seen = us_malloc(nc);
  if (!x->view.contacts || !x->acc || !x->seen) return -1;
  if (s->ncontact > 0)
    memcpy(x->view.contacts, s->contacts, (size_t)s->ncontact * sizeof(us_Contact));
  return present ? us_bitset_copy(&x->present, present) : us_structure_movable_set(s, &x->present);
}

static void set_mu(us_Structure *view, double mu) {
  for (int c = 0; c < view->ncontact; c++) view->contacts[c].mu = mu;
}

/* --------------------------------------------------------------- probes */

/* One stability test with every mu = `mu`; *stands = 1 when it stood (its
 * forces are then kept in out->forces). */
static us_Status probe(FrictionCtx *x, double mu, us_FrictionResult *out, int *stands,
                       us_Error *err) {
  set_mu(&x->view, mu);
  us_error_clear(err);
  us_StabilitySettings set = *x->set;
  if (x->t_end > 0) set.time_limit = US_MAX(x->t_end - us_now(), 1e-9); /* what is left */
  us_Stability *w = us_stability_new(&x->view, &set, err);
  if (!w) return err->code != US_OK ? err->code : US_ERR_SOLVER;
  us_Status st = us_stability_test(w, &x->present, &x->res, err);
  us_stability_free(w);
  if (st) return st;
  out->probes++;
  if (x->res.verdict == US_UNDECIDED && x->t_end > 0 && us_now() >= x->t_end)
    out->timed_out = 1; /* cut by the time limit: not a solver's failure */
  else
    out->undecided += x->res.verdict == US_UNDECIDED;
  *stands = x->res.verdict == US_STABLE;
  if (*stands && forces_copy(&out->forces, &x->res.forces, x->view.dim))
    return us_error_set(err, US_ERR_NOMEM, "out of memory keeping contact forces");
  return US_OK;
}

/* The next probe inside (lo, hi); see the file head. */
static double midpoint(double lo, double hi, double tol) {
  double base = US_MAX(lo, tol);
  if (hi > US_FRICTION_GEOMETRIC * base) return sqrt(base * hi);
  return lo + 0.5 * (hi - lo);
}

/* Narrow out->mu_low (falls) < out->mu_high (stands) to tol. */
static us_Status bisect(FrictionCtx *x, double tol, us_FrictionResult *out, us_Error *err) {
  while (out->mu_high - out->mu_low > tol) {
    if (x->t_end > 0 && us_now() >= x->t_end) {
      out->timed_out = 1;
      break;
    }
    double mid = midpoint(out->mu_low, out->mu_high, tol);
    if (!(mid > out->mu_low && mid < out->mu_high)) break; /* below rounding */
    int stands = 0;
    us_Status st = probe(x, mid, out, &stands, err);
    if (st) return st;
    if (stands)
      out->mu_high = mid;
    else
      out->mu_low = mid;
  }
  return US_OK;
}

/* The kept forces against the view with every mu = mu_high. */
static void recheck(FrictionCtx *x, us_FrictionResult *out) {
  set_mu(&x->view, out->mu_high);
  us_certificate_check_buf(&x->view, &x->present, &out->forces, x->set->cert_tol, x->acc,
                           x->seen, &out->check);
}

/* The driver's search once the context is set up. */
static us_Status search(FrictionCtx *x, double tol, double mu_max, us_FrictionResult *out,
                        us_Error *err) {
  int stands = 0;
  us_Status st = probe(x, 0.0, out, &stands, err);
  if (st || out->timed_out) return st;
  out->mu_low = 0.0;
  if (stands) {
    out->stands_frictionless = out->stands = 1;
    out->mu_high = 0.0;
  } else {
    if ((st = probe(x, mu_max, out, &stands, err)) || out->timed_out) return st;
    if (!stands) {
      out->mu_low = mu_max;
      return US_OK;
    }
    out->stands = 1;
    out->mu_high = mu_max;
    if ((st = bisect(x, tol, out, err))) return st;
  }
  out->mu_critical = out->mu_high;
  recheck(x, out);
  return US_OK;
}

us_Status us_critical_friction(const us_Structure *s, const us_Bitset *present,
                               const us_StabilitySettings *set, double tol, double mu_max,
                               us_FrictionResult *out, us_Error *err) {
  us_Error local;
  if (!err) err = &local;
  if (out) result_reset(out);
  us_Status st = check_args(s, present, tol, mu_max, out, err);
  if (st) return st;
  us_StabilitySettings def = us_stability_default_settings();
  FrictionCtx x;
  memset(&x, 0, sizeof x);
  x.set = set ? set : &def;
  if (x.set->time_limit > 0 && isfinite(x.set->time_limit)) x.t_end = us_now() + x.set->time_limit;
  if (ctx_init(&x, s, present)) {
    ctx_free(&x);
    return us_error_set(err, US_ERR_NOMEM, "out of memory setting up the critical friction");
  }
  st = search(&x, tol > 0 ? tol : US_FRICTION_TOL, mu_max > 0 ? mu_max : US_FRICTION_MU_MAX,
              out, err);
  ctx_free(&x);
  if (st) {
    us_friction_result_free(out);
    result_reset(out);
  }
  return st;
}
