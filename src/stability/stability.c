/* The stability front end: the public workspace API that decides whether a
 * sub-assembly stands, whatever backend does the work.
 *
 * Algorithm of one test: keep only the movable bits of `present` (fixed
 * bodies always stand), compare them with the last sub-assembly the backend
 * solved to list the bodies added and removed (word-wise XOR, so the cost is
 * O(words + changes)), build the equilibrium system, call the backend, scale
 * its normalized forces by the total weight W back to newtons, and re-check
 * them with the independent certificate check.
 *
 * Tests by change: the workspace's current set `cur` changes one body at a
 * time (toggle_body), and every change is told to the local tests at once
 * (us_local_toggle), which keep their diff against their base as a list;
 * so a test that the local tests decide costs O(change), not O(n / 64).
 * A whole bitset (us_stability_test) becomes the current set by toggling
 * the bits that differ, the same path. Only a full-system solve (O(n)
 * anyway) still compares bitsets word by word.
 *
 * Boundary band (docs/planning.md, "The boundary band"): a stable claim
 * whose certificate's worst measure exceeds US_BAND_CERT, or an unstable
 * one whose mechanism's margin is below US_BAND_MECH (both relative to the
 * bodies involved, certificate.h), is within tolerance of tipping; such a
 * test gets the verdict of one fixed referee, a scratch CLP solve of the
 * whole sub-assembly, so that no verdict depends on the method.
 *
 * Invariants: a STABLE verdict is only ever returned with a certificate
 * that passed at settings.cert_tol; a backend claim that fails the check
 * becomes UNDECIDED (the rejected forces stay in res->forces for
 * diagnosis). An empty sub-assembly (no movable body) is stable with no
 * forces and never reaches the backend. After a backend error the
 * workspace forgets its last sub-assembly, so the next call restarts the
 * backend. us_StabilityResult arrays are reused across calls: a result
 * must be initialized (us_stability_result_init, or zeroed) before its
 * first test, and every field is rewritten by each test.
 */
#include "backend.h"
#include "certificate.h"
#include "local.h"
#include "lp_small.h"
#include "lp_gen.h"
#include "lp_sparse.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define CONE_ROUNDS 60 /* 3D cone refinement rounds of one test at most (default) */

struct us_Stability {
  const us_Structure *s;
  us_StabilitySettings set;
  const us_Backend *be;
  void *bws;               /* backend state */
  us_EqSystem eq;
  us_Bitset movable;       /* mask of movable bodies */
  us_Bitset cur;           /* movable bits of the current sub-assembly */
  const us_Bitset *sys;    /* what the full system solves: &cur, or the
                              local tests' changed part (decide) */
  int ncur;                /* its number of bodies */
  us_Bitset last;          /* ... of the last one the backend solved */
  int have_last;
  int *added, *removed;    /* [nbody] */
  double *f;               /* normalized forces from the backend */
  int cap_f;
  double *acc;             /* certificate scratch: US_CERT_ACC * nbody */
  unsigned char *held;     /* [nbody] row blocks touched by some contact */
  unsigned char *seen;     /* certificate scratch: ncontact */
  us_StabilityInfo info;
  double deadline;         /* us_now() time; 0: none */
  us_Local *local;         /* exact local tests, or NULL */
  int local_held_only;     /* local made for us_stability_held alone: not a test's path */
  void *small;             /* with local tests: the dense simplex for tiny systems */
  void *sparse;            /* with local tests in 2D: the sparse simplex for the
                              full system of a hand-back, from the base's forces */
  const us_Backend *used_be; /* the backend that decided the last full system */
  void *used_ws;
  double t_created, t_progress; /* us_now() at creation, at the last progress call */
  void *ref;               /* the boundary band's referee: a CLP workspace, lazily */
  int refereeing;          /* run_backend serves the referee (scratch, no state kept) */
  us_ConeSet cones;        /* 3D: the polygonal friction cones (lp_gen.h) */
  int bilateral;           /* bilateral joints (us_stability_set_bilateral) */
  int cone_rounds;         /* 3D: refinement rounds of one test at most */
  int cone_rounds_max;     /* 3D: the most rounds one test ran */
};

/* ------------------------------------------------------------ small API */

static const char *const method_names[US_METHOD_COUNT + 1] = {"lp", "lpsolve", "lcp",
                                                              "lcp-reuse", "lp-lcp", "auto"};

const char *us_method_name(us_Method m) {
  if ((int)m < 0 || m > US_METHOD_AUTO) return "unknown";
  return method_names[m];
}

us_Method us_method_resolve(us_Method m, const us_Structure *s) {
  US_UNUSED(s);
  return m == US_METHOD_AUTO ? US_METHOD_LP : m;
}

int us_method_parse(const char *name, us_Method *out) {
  if (!name) return -1;
  for (int m = 0; m <= US_METHOD_AUTO; m++) {
    if (strcmp(name, method_names[m]) == 0) {
      if (out) *out = (us_Method)m;
      return 0;
    }
  }
  return -1;
}

const char *us_verdict_name(us_Verdict v) {
  switch (v) {
  case US_STABLE: return "stable";
  case US_UNSTABLE: return "unstable";
  case US_UNDECIDED: return "undecided";
  }
  return "unknown";
}

#define CERT_TOL 1e-6

us_StabilitySettings us_stability_default_settings(void) {
  us_StabilitySettings s;
  memset(&s, 0, sizeof s);
  s.method = US_METHOD_AUTO;
  s.cert_tol = CERT_TOL;
  s.max_pivots = 0;
  s.verbose = 0;
  s.lp = us_lp_default_settings();
  return s;
}

void us_forces_free(us_Forces *f) {
  if (!f) return;
  us_free(f->contact);
  us_free(f->f);
  memset(f, 0, sizeof *f);
}

void us_stability_result_init(us_StabilityResult *r) {
  if (!r) return;
  memset(r, 0, sizeof *r);
  r->verdict = US_UNDECIDED;
  r->check.worst_body = r->check.worst_contact = -1;
  r->unstable_body = -1;
}

void us_stability_result_free(us_StabilityResult *r) {
  if (!r) return;
  us_forces_free(&r->forces);
  us_mechanism_free(&r->mechanism);
  memset(r, 0, sizeof *r);
}

int us_active_contacts(const us_Structure *s, const us_Bitset *present, int *idx) {
  int n = 0;
  for (int c = 0; c < s->ncontact; c++)
    if (us_contact_active(s, present, c)) idx[n++] = c;
  return n;
}

const us_StabilityInfo *us_stability_info(const us_Stability *w) { return &w->info; }

void us_stability_set_skip_forces(us_Stability *w, int skip) {
  if (w) w->set.skip_forces = skip != 0;
}

void us_stability_set_cone_rounds(us_Stability *w, int rounds) {
  if (w) w->cone_rounds = rounds > 0 ? rounds : 0;
}

int us_stability_cone_rounds_max(const us_Stability *w) {
  return w ? w->cone_rounds_max : 0;
}

int us_stability_set_bilateral(us_Stability *w, int on) {
  if (!w) return -1;
  if (on && w->be != &us_backend_clp && w->be != &us_backend_lpsolve) return -1;
  w->bilateral = w->eq.bilateral = on != 0;
  w->have_last = 0; /* the backend's columns change meaning */
  if (w->local) us_local_forget(w->local); /* its base forces were of the other mode */
  return 0;
}

void us_stability_set_deadline(us_Stability *w, double deadline) {
  if (!w) return;
  w->deadline = deadline > 0 ? deadline : 0;
  if (w->be->set_deadline) w->be->set_deadline(w->bws, w->deadline);
  if (w->local) us_local_set_deadline(w->local, w->deadline);
}

/* ------------------------------------------------------------ workspace */

static const us_Backend *backend_of(us_Method m) {
  switch (m) {
  case US_METHOD_LP: return &us_backend_clp;
  case US_METHOD_LPSOLVE: return &us_backend_lpsolve;
  case US_METHOD_LCP: return &us_backend_lcp;
  case US_METHOD_LCP_REUSE: return &us_backend_lcp_reuse;
  case US_METHOD_LP_LCP: return &us_backend_lp_lcp;
  default: return NULL;
  }
}

void us_stability_free(us_Stability *w) {
  if (!w) return;
  if (w->bws) w->be->destroy(w->bws);
  if (w->ref) us_backend_clp.destroy(w->ref);
  us_local_free(w->local);
  if (w->small) us_backend_small.destroy(w->small);
  if (w->sparse) us_backend_sparse.destroy(w->sparse);
  us_eq_free(&w->eq);
  us_cone_set_free(&w->cones);
  us_bitset_free(&w->movable);
  us_bitset_free(&w->cur);
  us_bitset_free(&w->last);
  us_free(w->added);
  us_free(w->removed);
  us_free(w->f);
  us_free(w->acc);
  us_free(w->seen);
  us_free(w->held);
  us_free(w);
}

static us_Status check_settings(const us_Structure *s, const us_StabilitySettings *set,
                                us_Error *err) {
  if (!s || !us_structure_is_finalized(s))
    return us_error_set(err, US_ERR_USAGE, "stability: the structure is not finalized");
  if (!(set->cert_tol > 0) || !isfinite(set->cert_tol))
    return us_error_set(err, US_ERR_USAGE, "stability: cert_tol must be positive (got %g)",
                        set->cert_tol);
  return US_OK;
}

/* Every array of the workspace except the backend's. 0 or -1 on OOM. */
static int alloc_arrays(us_Stability *w) {
  const us_Structure *s = w->s;
  size_t nb = (size_t)(s->nbody > 0 ? s->nbody : 1);
  size_t nc = (size_t)(s->ncontact > 0 ? s->ncontact : 1);
  if (us_eq_init(&w->eq, s) || us_structure_movable_set(s, &w->movable) ||
      us_bitset_init(&w->cur, s->nbody) || us_bitset_init(&w->last, s->nbody))
    return -1;
  w->added = us_malloc(nb * sizeof(int));
  w->removed = us_malloc(nb * sizeof(int));
  w->acc = us_malloc(US_CERT_ACC * nb * sizeof(double));
  w->seen = us_malloc(nc);
  w->held = us_malloc(nb);
  if (s->dim == 3) {
    if (us_cone_set_init(&w->cones, s->ncontact)) return -1;
    w->eq.cones = &w->cones;
  }
  return !w->added || !w->removed || !w->acc || !w->seen || !w->held ? -1 : 0;
}

us_Stability *us_stability_new_backend(const us_Structure *s, const us_StabilitySettings *set,
                                       const us_Backend *be, us_Error *err) {
  us_StabilitySettings def = us_stability_default_settings();
  if (!set) set = &def;
  if (check_settings(s, set, err)) return NULL;
  if (!be) {
    us_error_set(err, US_ERR_USAGE, "stability: no backend for method %d", (int)set->method);
    return NULL;
  }
  us_Stability *w = us_calloc(1, sizeof *w);
  if (!w) {
    us_error_set(err, US_ERR_NOMEM, "out of memory creating a stability workspace");
    return NULL;
  }
  w->s = s;
  w->set = *set;
  w->be = be;
  w->cone_rounds = CONE_ROUNDS;
  if (alloc_arrays(w)) {
    us_stability_free(w);
    us_error_set(err, US_ERR_NOMEM, "out of memory creating a stability workspace");
    return NULL;
  }
  w->bws = be->create(s, set, err);
  if (!w->bws) {
    us_stability_free(w);
    return NULL;
  }
  w->sys = &w->cur;
  w->t_created = us_now();
  w->t_progress = 0.0; /* the first test reports at once */
  /* local tests: the CLP backend itself (never a test's stand-in) */
  if (be->local_tests && set->local >= 0) {
    w->local = us_local_new(s, set, be, s->dim == 3 ? &w->cones : NULL, err);
    w->small = w->local ? us_backend_small.create(s, set, err) : NULL;
    w->sparse = w->local && s->dim == 2 ? us_backend_sparse.create(s, set, err) : NULL;
    if (!w->local || !w->small || (s->dim == 2 && !w->sparse)) {
      us_stability_free(w);
      return NULL;
    }
  }
  if (set->time_limit > 0 && isfinite(set->time_limit))
    us_stability_set_deadline(w, w->t_created + set->time_limit);
  return w;
}

us_Stability *us_stability_new(const us_Structure *s, const us_StabilitySettings *set,
                               us_Error *err) {
  us_StabilitySettings def = us_stability_default_settings();
  if (!set) set = &def;
  if ((int)set->method < 0 || set->method > US_METHOD_AUTO) {
    us_error_set(err, US_ERR_USAGE, "stability: unknown method %d", (int)set->method);
    return NULL;
  }
  if (!s || !us_structure_is_finalized(s)) {
    us_error_set(err, US_ERR_USAGE, "stability: the structure is not finalized");
    return NULL;
  }
  us_StabilitySettings r = *set;
  r.method = us_method_resolve(set->method, s);
  return us_stability_new_backend(s, &r, backend_of(r.method), err);
}

/* ----------------------------------------------------------------- test */

/* Bodies in the system solved (sys) but not in last (added) and the
 * reverse (removed). */
static void diff_last(us_Stability *w, int *nadded, int *nremoved) {
  *nadded = *nremoved = 0;
  for (int k = 0; k < w->cur.nwords; k++) {
    uint64_t x = w->sys->w[k] ^ w->last.w[k];
    while (x) {
      int bit = __builtin_ctzll(x);
      x &= x - 1;
      int i = k * 64 + bit;
      if (us_bitset_get(w->sys, i))
        w->added[(*nadded)++] = i;
      else
        w->removed[(*nremoved)++] = i;
    }
  }
}

/* ------------------------------------------------------------- changes */

/* Flip body i (movable) in the current set; the local tests hear of it. */
static void toggle_body(us_Stability *w, int i) {
  w->cur.w[i >> 6] ^= (uint64_t)1 << (i & 63);
  w->ncur += us_bitset_get(&w->cur, i) ? 1 : -1;
  if (w->local) us_local_toggle(w->local, &w->cur, i);
}

/* The movable bits of present become the current set: the bits that
 * differ are toggled, in increasing order. */
static void set_cur(us_Stability *w, const us_Bitset *present) {
  for (int k = 0; k < w->cur.nwords; k++) {
    uint64_t x = (present->w[k] & w->movable.w[k]) ^ w->cur.w[k];
    while (x) {
      toggle_body(w, k * 64 + __builtin_ctzll(x));
      x &= x - 1;
    }
  }
}

/* Body `body` present (on) or absent: checked, then toggled if needed. */
static us_Status change(us_Stability *w, int body, int on, us_Error *err) {
  us_Error local;
  if (!err) err = &local;
  const char *what = on ? "add" : "remove";
  if (!w) return us_error_set(err, US_ERR_USAGE, "us_stability_%s: NULL workspace", what);
  if (body < 0 || body >= w->s->nbody)
    return us_error_set(err, US_ERR_USAGE, "us_stability_%s: no body with index %d (%d bodies)",
                        what, body, w->s->nbody);
  if (us_bitset_get(&w->movable, body) && us_bitset_get(&w->cur, body) != on) toggle_body(w, body);
  return US_OK;
}

us_Status us_stability_add(us_Stability *w, int body, us_Error *err) {
  return change(w, body, 1, err);
}

us_Status us_stability_remove(us_Stability *w, int body, us_Error *err) {
  return change(w, body, 0, err);
}

us_Status us_stability_set_current(us_Stability *w, const us_Bitset *present, us_Error *err) {
  us_Error local;
  if (!err) err = &local;
  if (!w || !present)
    return us_error_set(err, US_ERR_USAGE, "us_stability_set_current: NULL argument");
  if (present->nbits != w->s->nbody || !present->w)
    return us_error_set(err, US_ERR_USAGE, "us_stability_set_current: sub-assembly has %d bits, "
                        "the structure %d bodies", present->nbits, w->s->nbody);
  set_cur(w, present);
  return US_OK;
}

const us_Bitset *us_stability_current(const us_Stability *w) { return w ? &w->cur : NULL; }

int us_stability_current_count(const us_Stability *w) { return w ? w->ncur : 0; }

/* Do this workspace's tests go through the local tests (unilateral)? */
static int local_on(const us_Stability *w) {
  return w->local && !w->local_held_only && !w->bilateral;
}

int us_stability_tests_locally(const us_Stability *w) {
  return local_on(w) && w->s->dim == 2; /* 2D: a hand-back solves the changed part */
}

int us_stability_delta_consistent(const us_Stability *w) {
  if (us_bitset_count(&w->cur) != w->ncur) return 0;
  return !w->local || us_local_delta_consistent(w->local, &w->cur);
}

static void reset_result(us_StabilityResult *res) {
  res->verdict = US_UNDECIDED;
  res->forces.ncontact = 0;
  memset(&res->check, 0, sizeof res->check);
  res->check.worst_body = res->check.worst_contact = -1;
  res->unstable_body = -1;
  res->mechanism.nbody = 0;
  res->mechanism.ok = 0;
  res->mechanism.worst_power = INFINITY;
  res->note[0] = '\0';
}

/* Run the backend on w->eq; on success remember cur as its last state. */
static us_Status run_backend(us_Stability *w, us_StabilityResult *res, us_Error *err) {
  int nadd = 0, nrem = 0, restart = !w->have_last;
  if (!restart) diff_last(w, &nadd, &nrem);
  int need = w->eq.ncontact * w->eq.dim + 1;
  if (US_GROW(w->f, w->cap_f, need))
    return us_error_set(err, US_ERR_NOMEM, "out of memory testing stability");
  memset(w->f, 0, (size_t)need * sizeof(double));
  double t0 = us_now();
  w->used_be = w->be;
  w->used_ws = w->bws;
  if (w->small && !w->refereeing && us_small_fits(&w->eq)) { /* tiny: the dense simplex first */
    us_BackendOut out = {US_UNDECIDED, w->f, &w->info, res->note, sizeof res->note};
    us_Status st = us_backend_small.solve(w->small, &(us_BackendProblem){.sys = &w->eq, .restart = 1},
                                          &out, err);
    res->verdict = out.verdict;
    if (st || res->verdict != US_UNDECIDED) {
      w->info.solve_time += us_now() - t0;
      w->used_be = &us_backend_small;
      w->used_ws = w->small;
      return st;
    }
  }
  if (w->refereeing) { /* a scratch solve; the method's own state stays */
    us_BackendOut out = {US_UNDECIDED, w->f, &w->info, res->note, sizeof res->note};
    us_Status st = us_backend_clp.solve(w->ref, &(us_BackendProblem){.sys = &w->eq, .restart = 1},
                                        &out, err);
    res->verdict = out.verdict;
    w->info.solve_time += us_now() - t0;
    w->used_be = &us_backend_clp;
    w->used_ws = w->ref;
    return st;
  }
  /* a hand-back of the local tests (2D): the sparse simplex from the base's
     forces, off balance only where the test changed the base (a few
     pivots where CLP builds and factorizes the whole model: on an 827-block
     stacker stack its two hand-backs cost 190 ms with CLP; docs/local.md).
     The backend's state stays that of w->last, so it may go on from there */
  const double *hint = w->sparse ? us_local_hint(w->local) : NULL;
  if (hint && us_sparse_fits_region(&w->eq)) {
    us_BackendOut out = {US_UNDECIDED, w->f, &w->info, res->note, sizeof res->note};
    us_Status st = us_backend_sparse.solve(w->sparse, &(us_BackendProblem){.sys = &w->eq, .hint = hint},
                                           &out, err);
    res->verdict = out.verdict;
    if (st || res->verdict != US_UNDECIDED) {
      w->info.solve_time += us_now() - t0;
      w->info.local_global_sparse++;
      w->used_be = &us_backend_sparse;
      w->used_ws = w->sparse;
      return st;
    }
    memset(w->f, 0, (size_t)need * sizeof(double));
  }
  w->have_last = 0; /* until the backend succeeds, its state is unknown */
  us_BackendProblem pb = {&w->eq, w->added, nadd, w->removed, nrem, restart, NULL, 0};
  us_BackendOut out = {US_UNDECIDED, w->f, &w->info, res->note, sizeof res->note};
  us_Status st = w->be->solve(w->bws, &pb, &out, err);
  res->verdict = out.verdict;
  w->info.solve_time += us_now() - t0;
  if (st) return st;
  memcpy(w->last.w, w->sys->w, (size_t)w->cur.nwords * sizeof(uint64_t));
  w->have_last = 1;
  return US_OK;
}

/* 3D: the circular friction cones between polygons (lp_gen.h). The inner
 * polygons' LP first: feasible is a stable claim (its forces lie in the
 * circular cones). Else the outer polygons' LP: infeasible is unstable
 * (its Farkas ray holds for the circular cones, which lie inside). Else
 * its forces leave some circles: each such contact gets the direction of
 * its tangential force (a vertex of the inner polygon, a tangent side of
 * the outer one), and the two LPs run again. When no direction can be
 * added (every violating polygon full, or the violation within
 * CONE_SLACK, or w->cone_rounds rounds done) the outer forces are the
 * claim: the certificate check
 * tests the circular cones, so a claim it rejects is UNDECIDED, never
 * stable. Directions stay for later tests. */
#define CONE_SLACK 1e-9   /* relative excess |f_t| - mu f_n left unrefined */

/* Add the directions of the outer forces that leave their circles: the
 * number added, or -1 (OOM). */
static int refine_cones(us_Stability *w) {
  const us_EqSystem *e = &w->eq;
  int added = 0;
  for (int c = 0; c < e->ncontact; c++) {
    double mu = e->mu[c];
    if (!(mu > 0) || isinf(mu)) continue; /* exact cones */
    const double *f = w->f + 3 * (size_t)c;
    double ft = hypot(f[1], f[2]);
    if (!(ft > mu * f[0] + CONE_SLACK * hypot(f[0], ft))) continue;
    int r = us_cone_set_refine(&w->cones, e->contact[c], atan2(f[2], f[1]));
    if (r < 0) return -1;
    added += r;
  }
  w->info.cone3_refined += added;
  return added;
}

static us_Status run_cones(us_Stability *w, us_StabilityResult *res, us_Error *err) {
  int counted = 0;
  for (int round = 0;; round++) {
    w->cones.mode = US_CONE_INNER;
    us_Status st = run_backend(w, res, err);
    if (st || res->verdict != US_UNSTABLE) return st; /* stable, or no verdict */
    if (!counted) w->info.cone3_outer++, counted = 1;
    w->cones.mode = US_CONE_OUTER;
    st = run_backend(w, res, err);
    w->cones.mode = US_CONE_INNER;
    if (st || res->verdict != US_STABLE) return st; /* unstable (exact), or no verdict */
    int added = round < w->cone_rounds ? refine_cones(w) : 0;
    if (added > 0 && round + 1 > w->cone_rounds_max) w->cone_rounds_max = round + 1;
    if (added < 0) return us_error_set(err, US_ERR_NOMEM, "out of memory refining friction cones");
    if (added == 0) {
      w->info.cone3_open++;
      snprintf(res->note, sizeof res->note,
               "friction cones: outer polygons feasible after %d refinements, inner not: "
               "the outer forces are the claim",
               round);
      return US_OK;
    }
  }
}

/* Forces of a stable claim into res (newtons), then the certificate. */
/* A stable claim whose certificate failed the check: undecided, saying so. */
static void certificate_failed(us_StabilityResult *res, const char *who) {
  res->verdict = US_UNDECIDED;
  snprintf(res->note, sizeof res->note,
           "%s claimed stable, certificate failed (force %.2g torque %.2g cone %.2g sign %.2g)",
           who, res->check.max_force_residual, res->check.max_torque_residual,
           res->check.max_cone_violation, res->check.max_sign_violation);
}

static us_Status certify(us_Stability *w, us_StabilityResult *res, us_Error *err) {
  const us_EqSystem *e = &w->eq;
  int dim = w->s->dim;
  if (us_forces_reserve(&res->forces, e->ncontact))
    return us_error_set(err, US_ERR_NOMEM, "out of memory storing contact forces");
  res->forces.ncontact = e->ncontact;
  for (int c = 0; c < e->ncontact; c++) res->forces.contact[c] = e->contact[c];
  for (int j = 0; j < e->ncontact * dim; j++) res->forces.f[j] = w->f[j] * e->force_scale;
  double t0 = us_now();
  us_certificate_check_mode(w->s, w->sys, &res->forces, w->set.cert_tol, w->bilateral, w->acc,
                            w->seen, &res->check);
  w->info.check_time += us_now() - t0;
  if (!res->check.ok) certificate_failed(res, us_method_name(w->be->method));
  return US_OK;
}

/* A present body that no active contact touches falls as soon as it has
 * weight, however small: decided exactly here, before any solver whose
 * tolerance could absorb a tiny weight. Returns the body, or -1. */
static int unheld_body(us_Stability *w) {
  const us_EqSystem *e = &w->eq;
  memset(w->held, 0, (size_t)e->nbody);
  for (size_t j = 0; j < 2 * (size_t)e->ncontact * (size_t)e->dim; j++)
    if (e->blk[j] >= 0) w->held[e->blk[j]] = 1;
  for (int r = 0; r < e->nbody; r++) {
    if (w->held[r]) continue;
    for (int k = 0; k < e->nw; k++)
      if (e->rhs[(size_t)r * (size_t)e->nw + (size_t)k] != 0.0) return e->body[r];
  }
  return -1;
}

/* The local tests first (local.h): 1 decided (res set), 0 the full system
 * is needed, or an error. */
static int decide_local(us_Stability *w, us_StabilityResult *res, us_Error *err) {
  double t0 = us_now();
  int r = us_local_test(w->local, &w->cur, res, &w->info, err);
  w->info.solve_time += us_now() - t0;
  if (r < 0) {
    us_local_forget(w->local);
    return -1;
  }
  if (r == US_LOCAL_GLOBAL) return 0;
  if (r == US_LOCAL_STABLE && !w->set.skip_forces) {
    if (us_local_forces(w->local, &w->cur, &res->forces))
      return us_error_set(err, US_ERR_NOMEM, "out of memory storing contact forces"), -1;
    /* forces handed out: the full check over them, as for a full solve
       (the local tests checked only what changed) */
    t0 = us_now();
    us_certificate_check_buf(w->s, &w->cur, &res->forces, w->set.cert_tol, w->acc, w->seen,
                             &res->check);
    w->info.check_time += us_now() - t0;
    if (!res->check.ok) {
      certificate_failed(res, "local tests");
      us_local_forget(w->local);
    }
  }
  return 1;
}

/* After a full-system unstable verdict: the backend's Farkas ray, if it
 * has one, as a checked mechanism of all bodies. */
static us_Status global_mechanism(us_Stability *w, us_StabilityResult *res, us_Error *err) {
  const double *y = NULL;
  int ny = w->used_be->farkas_ray ? w->used_be->farkas_ray(w->used_ws, &y) : 0;
  if (!ny || !y) return US_OK;
  if (us_mechanism_from_ray(&res->mechanism, &w->eq, y, ny))
    return us_error_set(err, US_ERR_NOMEM, "out of memory storing a mechanism");
  us_mechanism_check_mode(w->s, &w->cur, &res->mechanism, w->set.cert_tol, w->bilateral);
  return US_OK;
}

/* Bilateral joints: the mechanism of a loose body (touching nothing), a
 * fall along gravity, as a ray of w->eq (row block r), checked. */
static us_Status loose_mechanism(us_Stability *w, int r, us_StabilityResult *res,
                                 us_Error *err) {
  const us_EqSystem *e = &w->eq;
  size_t n = (size_t)e->nbody * (size_t)e->nw;
  double *y = us_calloc(n, sizeof(double));
  if (!y) return us_error_set(err, US_ERR_NOMEM, "out of memory storing a mechanism");
  for (int k = 0; k < e->nw; k++) /* rhs is minus gravity's wrench */
    y[(size_t)r * (size_t)e->nw + (size_t)k] = -e->rhs[(size_t)r * (size_t)e->nw + (size_t)k];
  int bad = us_mechanism_from_ray(&res->mechanism, e, y, (int)n);
  us_free(y);
  if (bad) return us_error_set(err, US_ERR_NOMEM, "out of memory storing a mechanism");
  us_mechanism_check_mode(w->s, &w->cur, &res->mechanism, w->set.cert_tol, w->bilateral);
  return US_OK;
}

static us_Status decide(us_Stability *w, us_StabilityResult *res, us_Error *err) {
  if (w->ncur == 0) { /* nothing can fall */
    res->verdict = US_STABLE;
    snprintf(res->note, sizeof res->note, "no movable body present");
    w->eq.ncontact = 0;
    return certify(w, res, err);
  }
  w->sys = &w->cur;
  if (local_on(w)) {
    int r = decide_local(w, res, err);
    if (r) return r < 0 ? (err->code ? err->code : US_ERR_NOMEM) : US_OK;
    /* 2D, no forces handed out: the full system of the changed components
       alone (local.h; a planner's assembly step by change on a structure
       of many components). The certificate then covers them, the base's
       forces the rest. */
    const us_Bitset *part;
    int np = us_local_changed_part(w->local, &part);
    if (us_stability_tests_locally(w) && w->set.skip_forces && np > 0 && np < w->ncur) {
      w->sys = part;
      w->info.local_global_part++;
    }
  }
  if (us_eq_build(&w->eq, w->sys))
    return us_error_set(err, US_ERR_NOMEM, "out of memory building the equilibrium system");
  int loose = unheld_body(w);
  if (loose >= 0) {
    res->verdict = US_UNSTABLE;
    res->unstable_body = loose;
    snprintf(res->note, sizeof res->note, "a body with weight touches nothing");
    return w->bilateral ? loose_mechanism(w, w->eq.row_of_body[loose], res, err) : US_OK;
  }
  int cones = w->s->dim == 3 && !w->bilateral; /* joints have no cones */
  us_Status st = cones ? run_cones(w, res, err) : run_backend(w, res, err);
  if (st) return st;
  if (res->verdict == US_STABLE) {
    st = certify(w, res, err);
    if (!st && local_on(w) && res->verdict == US_STABLE)
      us_local_set_base(w->local, &w->cur, &w->eq, w->f);
    return st;
  }
  if (res->verdict == US_UNSTABLE && w->used_be->unstable_body)
    res->unstable_body = w->used_be->unstable_body(w->used_ws);
  if (res->verdict == US_UNSTABLE) return global_mechanism(w, res, err);
  return US_OK;
}

static int past_deadline(const us_Stability *w) {
  return w->deadline > 0 && us_now() >= w->deadline;
}

/* ------------------------------------------------------- boundary band */

/* The worst of a certificate's four measures (certificate.c). */
static double worst_measure(const us_CertCheck *c) {
  return US_MAX(US_MAX(c->max_force_residual, c->max_torque_residual),
                US_MAX(c->max_cone_violation, c->max_sign_violation));
}

/* Is a verdict's evidence in the boundary band (file head)? */
static int in_band(const us_Stability *w, const us_StabilityResult *res) {
  if (res->verdict == US_STABLE) return worst_measure(&res->check) > US_BAND_CERT;
  if (res->verdict != US_UNSTABLE || res->mechanism.nbody == 0) return 0;
  return !res->mechanism.ok || us_mechanism_margin(w->s, &res->mechanism) < US_BAND_MECH;
}

/* The referee decides a sub-assembly in the band: a scratch CLP solve of
 * the whole system (3D: with the cone refinement), certificate and ray
 * checked as for any method. */
static us_Status referee(us_Stability *w, us_StabilityResult *res, us_Error *err) {
  if (!w->ref) {
    w->ref = us_backend_clp.create(w->s, &w->set, err);
    if (!w->ref) return err->code ? err->code : US_ERR_NOMEM;
  }
  us_backend_clp.set_deadline(w->ref, w->deadline);
  w->sys = &w->cur;
  if (us_eq_build(&w->eq, &w->cur))
    return us_error_set(err, US_ERR_NOMEM, "out of memory building the equilibrium system");
  char was[64];
  snprintf(was, sizeof was, "%s %s", us_method_name(w->be->method), us_verdict_name(res->verdict));
  reset_result(res);
  w->info.band_referee++;
  w->refereeing = 1;
  int cones = w->s->dim == 3 && !w->bilateral;
  us_Status st = cones ? run_cones(w, res, err) : run_backend(w, res, err);
  w->refereeing = 0;
  if (!st && res->verdict == US_STABLE) st = certify(w, res, err);
  if (!st && res->verdict == US_UNSTABLE) st = global_mechanism(w, res, err);
  if (st) return st;
  char note[sizeof res->note];
  int n = snprintf(note, sizeof note, "within tolerance of tipping (%s); referee: ", was);
  if (n > 0 && (size_t)n < sizeof note)
    memcpy(note + n, res->note, US_MIN(strlen(res->note) + 1, sizeof note - (size_t)n));
  note[sizeof note - 1] = '\0';
  memcpy(res->note, note, sizeof note);
  return US_OK;
}

static void report_progress(us_Stability *w) {
  if (!w->set.progress) return;
  double now = us_now();
  if (now - w->t_progress < 0.25) return;
  w->t_progress = now;
  us_Progress p = {w->info.tests, w->ncur, now - w->t_created,
                   w->deadline > 0 ? US_MAX(w->deadline - now, 0.0) : -1.0};
  w->set.progress(&p, w->set.progress_user);
}

/* Test the current set (the two entry points' common part). */
static us_Status test_cur(us_Stability *w, us_StabilityResult *res, us_Error *err) {
  reset_result(res);
  us_Status st = past_deadline(w) ? US_OK : decide(w, res, err);
  if (!st && in_band(w, res)) st = referee(w, res, err);
  if (st) {
    reset_result(res);
    return st;
  }
  if (res->verdict == US_UNDECIDED && past_deadline(w)) {
    w->info.timed_out++;
    snprintf(res->note, sizeof res->note, "time limit");
  }
  w->info.tests++;
  report_progress(w);
  if (w->set.verbose > 1)
    fprintf(stderr, "stability: %d bodies: %s (%s)\n", w->ncur,
            us_verdict_name(res->verdict), res->note);
  return US_OK;
}

us_Status us_stability_test(us_Stability *w, const us_Bitset *present, us_StabilityResult *res,
                            us_Error *err) {
  us_Error local;
  if (!err) err = &local;
  if (!w || !present || !res)
    return us_error_set(err, US_ERR_USAGE, "us_stability_test: NULL argument");
  if (present->nbits != w->s->nbody || !present->w)
    return us_error_set(err, US_ERR_USAGE, "us_stability_test: sub-assembly has %d bits, "
                        "the structure %d bodies", present->nbits, w->s->nbody);
  set_cur(w, present);
  return test_cur(w, res, err);
}

us_Status us_stability_test_current(us_Stability *w, us_StabilityResult *res, us_Error *err) {
  us_Error local;
  if (!err) err = &local;
  if (!w || !res) return us_error_set(err, US_ERR_USAGE, "us_stability_test_current: NULL argument");
  return test_cur(w, res, err);
}

us_Status us_stability_seed(us_Stability *w, const us_Bitset *present, const us_Forces *f,
                            int *taken, us_Error *err) {
  us_Error local;
  if (!err) err = &local;
  *taken = 0;
  if (!w || !present || !f) return us_error_set(err, US_ERR_USAGE, "us_stability_seed: NULL argument");
  if (present->nbits != w->s->nbody || !present->w)
    return us_error_set(err, US_ERR_USAGE, "us_stability_seed: sub-assembly has %d bits, "
                        "the structure %d bodies", present->nbits, w->s->nbody);
  if (!w->local || w->local_held_only) return US_OK;
  for (int j = 0; j < f->ncontact; j++)
    if (f->contact[j] < 0 || f->contact[j] >= w->s->ncontact)
      return us_error_set(err, US_ERR_USAGE, "us_stability_seed: contact %d out of range", f->contact[j]);
  set_cur(w, present);
  /* the forces must be a certificate of present here, whatever their origin */
  us_CertCheck check;
  us_certificate_check_buf(w->s, &w->cur, f, w->set.cert_tol, w->acc, w->seen, &check);
  if (!check.ok) return US_OK;
  us_local_seed_base(w->local, &w->cur, f);
  *taken = 1;
  return US_OK;
}

us_Status us_stability_held(us_Stability *w, const us_Bitset *present, const int *reg, int nreg,
                            us_StabilityResult *res, us_Error *err) {
  reset_result(res);
  if (!w->local) { /* other methods: a CLP tester of their own, for these LPs only */
    us_StabilitySettings set = w->set;
    set.method = US_METHOD_LP;
    w->local = us_local_new(w->s, &set, &us_backend_clp, w->s->dim == 3 ? &w->cones : NULL, err);
    if (!w->local) return err->code ? err->code : US_ERR_NOMEM;
    w->local_held_only = 1;
    us_local_set_deadline(w->local, w->deadline);
    us_local_sync(w->local, &w->cur); /* it starts from the current set */
  }
  set_cur(w, present);
  double t0 = us_now();
  int r = past_deadline(w) ? 0 : us_local_held(w->local, &w->cur, reg, nreg, res, &w->info, err);
  w->info.solve_time += us_now() - t0;
  if (r < 0) return err->code ? err->code : US_ERR_NOMEM;
  if (r == 0) {
    res->verdict = US_UNDECIDED;
    snprintf(res->note, sizeof res->note, "%s", past_deadline(w) ? "time limit" : "may stand held");
  }
  return US_OK;
}

us_Status us_stability_test_full(us_Stability *w, us_StabilityResult *res, us_Error *err) {
  return us_stability_test(w, &w->movable, res, err);
}
