/* The default stability backend: the statics feasibility LP solved by CLP
 * (COIN-OR) through its C interface, from scratch for every test.
 *
 * Formulation (2D, exact): the cone-generator form of lp_gen.h,
 * G l = rhs with l >= 0 and a zero objective: unit-length generators of
 * every contact's cone (n alone when mu = 0, the two edges, plus n for
 * wide cones; mu = INFINITY gives n, +t, -t), equality rows only. The
 * sub-assembly stands iff the LP is feasible. Compared with f_n >= 0, f_t
 * free plus two cone rows per contact this halves the rows and makes every
 * solution satisfy the cones up to the bound tolerance.
 *
 * Robustness: the system is already normalized (forces in units of the
 * total weight, gravity rows of size m_i / M <= 1, torques divided by the
 * structure's scale, generator columns of unit length whatever mu), CLP
 * scales rows and columns on top, and the primal tolerance is tightened
 * (us_LpSettings.primal_tol, 1e-9) so that accepted solutions pass the
 * certificate check (1e-6) with room.
 * The dual simplex is run without presolve: a zero objective makes the
 * slack basis dual feasible, and on infeasibility its dual ray is a
 * Farkas certificate, from which we name the body with the largest virtual
 * motion (verified against G before use).
 *
 * Reuse: CLP's basis status of every column (keyed by structure contact
 * and generator) and row (keyed by body and wrench component) is kept
 * after each solve; every later model starts from the latest status of
 * each of its columns and rows, whichever solve left it (columns never
 * seen at their bound, rows never seen basic), so a planner that moves
 * between components, or a region system of the local tests, finds the
 * statuses it left there. With a zero objective every basis is dual
 * feasible, so the dual simplex is valid from any start: reuse changes the
 * pivot count, never the verdict (CLP repairs a basis of the wrong size).
 *
 * Memory: the model and the ray belong to CLP (Clp_deleteModel,
 * Clp_freeRay); our column buffers are kept and reused between tests.
 */
#include "backend.h"
#include "lp_gen.h"

#include <coin/Clp_C_Interface.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

/* A barrier point must hold every row to this, relative to the row's own
 * scale |rhs_r| + sum_j |G_rj| l_j (the certificate check asks 1e-6 of
 * each body; near-infeasible systems end "optimal" well above it). */
#define CLP_BARRIER_REL 1e-9

/* A warm-started feasible claim must hold every row to this (relative as
 * above; the certificate check asks 1e-6 of each body): from some starts
 * CLP has called a system optimal after 0 iterations with a body's rows
 * not met at all (a 3,052-block wall, 56 of 5,353 tests). */
#define CLP_WARM_REL 1e-7

/* Cold solves of systems with at least this many rows (3 per body) use the
 * barrier first (clp_cold_big); below, the dual simplex is faster (a
 * 990-block wall: dual 0.70 s, barrier 0.15 s; a 91-block pyramid: both
 * in a few ms). */
#define CLP_BARRIER_ROWS 1500

/* CLP's barrier does not stop at Clp_setMaximumSeconds (a 10,050-block
 * wall's check with --time-limit 2 ran 10 s), the dual simplex does. With
 * a deadline the barrier runs only when the time left is at least this
 * many seconds per row (the wall's 30,150 rows took 5.4 s: 1.8e-4 s per
 * row; twice that for margin); else the dual simplex runs and stops at
 * the deadline. */
#define CLP_BARRIER_SEC_PER_ROW 4e-4

typedef struct ClpWs {
  us_EqGen gen;
  double *bounds;   /* [nrow] row bounds (rhs) */
  double *sol;      /* [max(ncol, 2 nrow)] copy of the column solution */
  int cap_row, cap_col;
  us_LpSettings set;
  int last_body;    /* evidence of the last unstable verdict */
  /* basis of the previous solve, valid where *_stamp == stamp */
  unsigned char *col_st, *row_st; /* [slots * s->ncontact], [nw * s->nbody] */
  int *col_stamp, *row_stamp;
  int stamp;
  unsigned char *st; /* [ncol + nrow] status handed to CLP */
  int cap_st;
  double *ray;       /* the last infeasible solve's checked Farkas ray */
  int cap_ray, nray; /* nray = 0: none */
  double deadline;   /* us_now() time; 0: none */
  double wall0, cpu0; /* us_now() and clock() seconds at creation */
  int nw;             /* rows per body: 3 (2D) or 6 (3D) */
} ClpWs;

static void clp_destroy(void *ws) {
  ClpWs *w = ws;
  if (!w) return;
  us_eq_gen_free(&w->gen);
  us_free(w->bounds);
  us_free(w->sol);
  us_free(w->col_st);
  us_free(w->row_st);
  us_free(w->col_stamp);
  us_free(w->row_stamp);
  us_free(w->st);
  us_free(w->ray);
  us_free(w);
}

static void *clp_create(const us_Structure *s, const us_StabilitySettings *set, us_Error *err) {
  ClpWs *w = us_calloc(1, sizeof *w);
  size_t nc = (size_t)us_eq_gen_slots(s->dim) * (size_t)(s->ncontact > 0 ? s->ncontact : 1);
  size_t nr = (size_t)(s->dim == 3 ? 6 : 3) * (size_t)(s->nbody > 0 ? s->nbody : 1);
  if (w) {
    w->set = us_lp_settings_resolve(&set->lp);
    w->last_body = -1;
    w->nw = s->dim == 3 ? 6 : 3;
    w->wall0 = us_now();
    w->cpu0 = (double)clock() / CLOCKS_PER_SEC;
    w->stamp = 1;
    w->col_st = us_malloc(nc);
    w->row_st = us_malloc(nr);
    w->col_stamp = us_calloc(nc, sizeof(int));
    w->row_stamp = us_calloc(nr, sizeof(int));
  }
  if (!w || !w->col_st || !w->row_st || !w->col_stamp || !w->row_stamp) {
    clp_destroy(w);
    us_error_set(err, US_ERR_NOMEM, "out of memory creating the CLP workspace");
    return NULL;
  }
  return w;
}

static int clp_reserve(ClpWs *w, int nrow, int ncol) {
  if (nrow > w->cap_row) {
    double *b = us_realloc(w->bounds, (size_t)nrow * sizeof(double));
    if (!b) return -1;
    w->bounds = b;
    w->cap_row = nrow;
  }
  int nsol = US_MAX(ncol, 2 * nrow); /* also the barrier check's scratch */
  if (nsol > w->cap_col) {
    double *x = us_realloc(w->sol, (size_t)nsol * sizeof(double));
    if (!x) return -1;
    w->sol = x;
    w->cap_col = nsol;
  }
  return US_GROW(w->st, w->cap_st, nrow + ncol);
}

/* Keys of column j and row r of the current system in the basis maps. */
static size_t col_key(const us_EqSystem *sys, const us_EqGen *g, int j) {
  return (size_t)us_eq_gen_slots(sys->dim) * (size_t)sys->contact[g->col_contact[j]] +
         (size_t)us_eq_gen_slot(g, j);
}

static size_t row_key(const us_EqSystem *sys, int r) {
  return (size_t)sys->nw * (size_t)sys->body[r / sys->nw] + (size_t)(r % sys->nw);
}

/* Start from the latest status of each column and row, whatever solve
 * left it (the previous one's for what it shared with this system, older
 * ones' for the rest: a planner that tests one component, then another,
 * comes back to statuses of the first). CLP status codes: 1 basic, 3 at
 * lower bound. Returns 1 if any status was reused. */
static int warm_start(Clp_Simplex *m, ClpWs *w, const us_EqSystem *sys) {
  const us_EqGen *g = &w->gen;
  int reused = 0;
  for (int j = 0; j < g->ncol; j++) {
    size_t k = col_key(sys, g, j);
    int ok = w->col_stamp[k] > 0;
    w->st[j] = ok ? w->col_st[k] : 3;
    reused |= ok;
  }
  for (int r = 0; r < g->nrow; r++) {
    size_t k = row_key(sys, r);
    int ok = w->row_stamp[k] > 0;
    w->st[g->ncol + r] = ok ? w->row_st[k] : 1;
    reused |= ok;
  }
  Clp_copyinStatus(m, w->st);
  return reused;
}

/* Remember the final basis for the next solve. */
static void save_basis(Clp_Simplex *m, ClpWs *w, const us_EqSystem *sys) {
  const us_EqGen *g = &w->gen;
  const unsigned char *st = Clp_statusArray(m);
  w->stamp++;
  if (!st) return;
  for (int j = 0; j < g->ncol; j++) {
    size_t k = col_key(sys, g, j);
    w->col_st[k] = st[j] & 7;
    w->col_stamp[k] = w->stamp;
  }
  for (int r = 0; r < g->nrow; r++) {
    size_t k = row_key(sys, r);
    w->row_st[k] = st[g->ncol + r] & 7;
    w->row_stamp[k] = w->stamp;
  }
}

#define CLP_CLOCK_RETRIES 4 /* runs continued after CLP's own clock stopped them early */

/* CLP's time limit counts the process's CPU seconds; the deadline is wall
 * time. On a loaded machine the process gets a share of a core, so the
 * wall time left is scaled by the share measured since the workspace was
 * created (1 until 50 ms have passed; at least 0.05). */
static double clp_seconds_left(const ClpWs *w) {
  double now = us_now(), wall = now - w->wall0;
  double cpu = (double)clock() / CLOCKS_PER_SEC - w->cpu0;
  double share = wall > 0.05 && cpu > 0 ? US_MIN(US_MAX(cpu / wall, 0.05), 1.0) : 1.0;
  return US_MAX((w->deadline - now) * share, 1e-3);
}

/* Load G l = rhs, 0 <= l into a fresh model. */
static Clp_Simplex *clp_load(ClpWs *w, const us_EqSystem *sys) {
  Clp_Simplex *m = Clp_newModel();
  if (!m) return NULL;
  Clp_setLogLevel(m, 0);
  const us_EqGen *g = &w->gen;
  memcpy(w->bounds, sys->rhs, (size_t)g->nrow * sizeof(double));
  /* NULL column bounds / objective: l in [0, inf), objective zero */
  Clp_loadProblem(m, g->ncol, g->nrow, g->start, g->row, g->val, NULL, NULL, NULL, w->bounds,
                  w->bounds);
  Clp_setPrimalTolerance(m, w->set.primal_tol);
  /* 3D: no CLP scaling (the system is normalized): scaled warm runs on a
   * tower of 100 boxes were accepted 32 times in 100 (the rest imprecise,
   * solved again), unscaled 98 times: the plan 3.9 s -> 0.9 s */
  if (w->nw == 6) Clp_scaling(m, 0);
  if (w->deadline > 0) Clp_setMaximumSeconds(m, clp_seconds_left(w));
  return m;
}

/* After an infeasible solve: the evidence body from CLP's dual ray. */
static int clp_evidence(Clp_Simplex *m, ClpWs *w, const us_EqSystem *sys) {
  double *ray = Clp_infeasibilityRay(m);
  if (!ray) return -1;
  int body = us_eq_gen_farkas_body(sys, &w->gen, ray, w->set.farkas_slack);
  if (body >= 0 && !US_GROW(w->ray, w->cap_ray, w->gen.nrow)) {
    memcpy(w->ray, ray, (size_t)w->gen.nrow * sizeof(double));
    w->nray = w->gen.nrow;
  }
  Clp_freeRay(m, ray);
  return body;
}

/* Does the infeasible run's ray pass the Farkas check? A warm run whose
 * ray does not is repeated cold (seen once in 3,134 3D unstable verdicts:
 * the lcp backend's own LP, warm from its previous sub-assembly, left an
 * unstable verdict without a mechanism where a cold run has one). */
static int ray_usable(Clp_Simplex *m, ClpWs *w, const us_EqSystem *sys) {
  double *ray = Clp_infeasibilityRay(m);
  if (!ray) return 0;
  int body = us_eq_gen_farkas_body(sys, &w->gen, ray, w->set.farkas_slack);
  Clp_freeRay(m, ray);
  return body >= 0;
}

/* A cold solve of a big system: CLP's barrier without crossover (an
 * interior point: on the 10,000-block wall 5.4 s, where the dual simplex
 * from the slack basis took 4 minutes and the barrier with crossover 3).
 * Accepted only when CLP calls it optimal with no visible infeasibility;
 * otherwise (infeasible systems included: the barrier proves nothing) the
 * model is reloaded and the dual simplex decides. The front end re-checks
 * any forces it yields. NULL if CLP cannot create a model. */
/* Does l >= 0 satisfy G l = rhs row by row to `rel` of each row's own
 * scale (sum_j |G_rj| l_j) plus its body's weight share (the sum of the
 * body's |rhs|, as the certificate check measures a body)? Uses w->bounds
 * (the rhs) and w->sol as scratch for the row sums. */
static int precise(ClpWs *w, const double *l, double rel) {
  const us_EqGen *g = &w->gen;
  double *res = w->sol, *scale = w->sol + g->nrow;
  for (int r = 0; r < g->nrow; r++) res[r] = -w->bounds[r], scale[r] = 0.0;
  for (int j = 0; j < g->ncol; j++) {
    if (!(l[j] >= 0.0) || !isfinite(l[j])) return 0;
    for (int q = g->start[j]; q < g->start[j + 1]; q++) {
      res[g->row[q]] += g->val[q] * l[j];
      scale[g->row[q]] += fabs(g->val[q]) * l[j];
    }
  }
  int nw = w->nw;
  for (int b = 0; b < g->nrow / nw; b++) {
    double share = 0.0; /* the body's weight share: the rows' own floor */
    for (int k = 0; k < nw; k++) share += fabs(w->bounds[b * nw + k]);
    for (int k = 0; k < nw; k++) {
      int r = b * nw + k;
      if (!(fabs(res[r]) <= rel * (scale[r] + share))) return 0;
    }
  }
  return 1;
}

static Clp_Simplex *clp_cold_big(ClpWs *w, const us_EqSystem *sys) {
  Clp_Simplex *m = clp_load(w, sys);
  if (!m) return NULL;
  Clp_initialBarrierNoCrossSolve(m);
  if (Clp_status(m) == 0 && Clp_sumPrimalInfeasibilities(m) <= w->set.warm_accept &&
      precise(w, Clp_getColSolution(m), CLP_BARRIER_REL))
    return m;
  Clp_deleteModel(m);
  m = clp_load(w, sys);
  if (m) Clp_dual(m, 0);
  return m;
}

/* Load and solve with the dual simplex from the latest statuses
 * (warm_start); a big system with no known status goes to the barrier
 * first (clp_cold_big). A warm run that stops without a verdict, or with
 * visible infeasibility left, is repeated cold. (Until 2026-11 a solve
 * started cold when more than 8 + nbody / 16 bodies had changed since the
 * previous one: the planner's assembly search, which tests one component
 * and then another, paid a cold solve, or a barrier of up to 0.1 s, for
 * most tests of a 2,000-block stacker stack: 23 s, now 7.4 s.) A cold
 * run that CLP calls optimal is checked too (precise): on a 3D pyramid of
 * boxes (53 bodies, 8,736 cone edges) CLP's scaled dual simplex returned
 * "optimal" with a row off by 0.0064 of the total weight; such a run is
 * repeated without CLP's scaling (the system is normalized already). NULL
 * if CLP cannot create a model. */
static Clp_Simplex *clp_run(ClpWs *w, const us_EqSystem *sys, int region,
                            us_StabilityInfo *info) {
  Clp_Simplex *m = clp_load(w, sys);
  if (!m) return NULL;
  int reused = warm_start(m, w, sys);
  int barrier_fits = w->deadline <= 0 ||
                     w->deadline - us_now() >= CLP_BARRIER_SEC_PER_ROW * (double)w->gen.nrow;
  if (!reused && !region && w->gen.nrow >= CLP_BARRIER_ROWS && barrier_fits) {
    Clp_deleteModel(m);
    return clp_cold_big(w, sys);
  }
  if (reused) {
    Clp_dual(m, 0);
    int status = Clp_status(m);
    if ((status == 0 && Clp_sumPrimalInfeasibilities(m) <= w->set.warm_accept &&
         precise(w, Clp_getColSolution(m), CLP_WARM_REL)) ||
        (status == 1 && ray_usable(m, w, sys))) {
      info->reused++;
      return m;
    }
    Clp_deleteModel(m);
    m = clp_load(w, sys);
    if (!m) return NULL;
  }
  Clp_dual(m, 0);
  if (Clp_status(m) == 0 && !precise(w, Clp_getColSolution(m), CLP_WARM_REL)) {
    Clp_deleteModel(m); /* CLP's scaling misled it: once more unscaled */
    m = clp_load(w, sys);
    if (!m) return NULL;
    Clp_scaling(m, 0);
    Clp_dual(m, 0);
  }
  return m;
}

static us_Status clp_solve(void *ws, const us_BackendProblem *pb, us_BackendOut *out,
                           us_Error *err) {
  /* the problem and the output under the names the body reads */
  const us_EqSystem *sys = pb->sys;
  us_Verdict *verdict = &out->verdict;
  double *f = out->f;
  us_StabilityInfo *info = out->info;
  char *note = out->note;
  size_t note_sz = out->note_sz;
  ClpWs *w = ws;
  w->last_body = -1;
  w->nray = 0;
  if (us_eq_generators(sys, w->set.n_column_mu, &w->gen) ||
      clp_reserve(w, w->gen.nrow, w->gen.ncol))
    return us_error_set(err, US_ERR_NOMEM, "out of memory building the LP");
  if (w->gen.ncol == 0) {
    /* solvers disagree on empty models: decided here */
    *verdict = us_eq_no_columns_verdict(sys);
    snprintf(note, note_sz, "no active contact");
    return US_OK;
  }
  int region = !pb->added && !pb->removed; /* a region system (backend.h) */
  if (w->deadline > 0 && us_now() >= w->deadline) {
    snprintf(note, note_sz, "CLP: time limit");
    *verdict = US_UNDECIDED;
    return US_OK;
  }
  /* the statuses are keyed: no list of changes needed */
  Clp_Simplex *m = clp_run(w, sys, region, info);
  if (!m) return us_error_set(err, US_ERR_NOMEM, "CLP could not create a model");
  /* CLP's clock (CPU seconds, scaled by the share measured so far) may
     stop it before the wall deadline when the machine's load changes:
     it goes on with the wall time left, unscaled */
  for (int k = 0; k < CLP_CLOCK_RETRIES && Clp_status(m) == 3 && Clp_secondaryStatus(m) == 9 &&
                  w->deadline > 0 && us_now() < w->deadline;
       k++) {
    Clp_setMaximumSeconds(m, US_MAX(w->deadline - us_now(), 1e-3));
    Clp_dual(m, 0);
  }
  int status = Clp_status(m);
  if (status != 0 && status != 1 && w->deadline > 0 && us_now() >= w->deadline) {
    Clp_deleteModel(m); /* stopped by the deadline: no verdict, no error */
    w->stamp++;
    snprintf(note, note_sz, "CLP: time limit");
    *verdict = US_UNDECIDED;
    return US_OK;
  }
  if (status == 0 || status == 1) save_basis(m, w, sys);
  else w->stamp++; /* forget the basis */
  us_Status st = US_OK;
  if (status == 0) {
    memcpy(w->sol, Clp_getColSolution(m), (size_t)w->gen.ncol * sizeof(double));
    us_eq_gen_forces(sys, &w->gen, w->sol, f);
    *verdict = US_STABLE;
    snprintf(note, note_sz, "CLP: feasible after %d iterations", Clp_numberIterations(m));
  } else if (status == 1) {
    *verdict = US_UNSTABLE;
    w->last_body = clp_evidence(m, w, sys);
    snprintf(note, note_sz, "CLP: primal infeasible (%s)",
             w->last_body >= 0 ? "Farkas ray checked" : "no usable ray");
  } else {
    st = us_error_set(err, US_ERR_SOLVER, "CLP stopped with status %d (secondary %d)", status,
                      Clp_secondaryStatus(m));
  }
  Clp_deleteModel(m);
  return st;
}

static int clp_unstable_body(void *ws) { return ((ClpWs *)ws)->last_body; }

static void clp_set_deadline(void *ws, double deadline) { ((ClpWs *)ws)->deadline = deadline; }

static int clp_farkas_ray(void *ws, const double **y) {
  ClpWs *w = ws;
  *y = w->nray ? w->ray : NULL;
  return w->nray;
}

const us_Backend us_backend_clp = {
    .method = US_METHOD_LP,
    .local_tests = 1,
    .create = clp_create,
    .destroy = clp_destroy,
    .solve = clp_solve,
    .unstable_body = clp_unstable_body,
    .farkas_ray = clp_farkas_ray,
    .set_deadline = clp_set_deadline,
};
