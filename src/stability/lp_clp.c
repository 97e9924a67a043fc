/* The default stability backend: the statics feasibility LP solved by CLP
 * (COIN-OR) through its C interface, from scratch for every test.
 *
 * Formulation (2D, exact): the cone-edge form of equilibrium.c,
 * G l = rhs with l >= 0 and a zero objective: two non-negative multipliers
 * per frictional contact (one when mu = 0), equality rows only. The
 * sub-assembly stands iff the LP is feasible. Compared with f_n >= 0, f_t
 * free plus two cone rows per contact this halves the rows and makes every
 * solution satisfy the cones up to the bound tolerance.
 *
 * Robustness: the system is already normalized (forces in units of the
 * total weight, torques divided by the structure's scale), CLP scales
 * rows and columns on top, and the primal tolerance is tightened to 1e-9
 * so that accepted solutions pass the certificate check (1e-6) with room.
 * The dual simplex is run without presolve: a zero objective makes the
 * slack basis dual feasible, and on infeasibility its dual ray is a
 * Farkas certificate, from which we name the body with the largest virtual
 * motion (verified against G before use).
 *
 * Memory: the model and the ray belong to CLP (Clp_deleteModel,
 * Clp_freeRay); our column buffers are kept and reused between tests.
 */
#include "stability.h"

#include <coin/Clp_C_Interface.h>
#include <stdio.h>
#include <string.h>

typedef struct ClpWs {
  us_EqGen gen;
  double *bounds;   /* [nrow] row bounds (rhs) */
  double *sol;      /* [ncol] copy of the column solution */
  int cap_row, cap_col;
  int last_body;    /* evidence of the last unstable verdict */
} ClpWs;

static void *clp_create(const us_Structure *s, const us_StabilitySettings *set, us_Error *err) {
  US_UNUSED(set);
  if (s->dim != 2) {
    us_error_set(err, US_ERR_USAGE, "the LP backends support 2D structures only");
    return NULL;
  }
  ClpWs *w = us_calloc(1, sizeof *w);
  if (!w) us_error_set(err, US_ERR_NOMEM, "out of memory creating the CLP workspace");
  if (w) w->last_body = -1;
  return w;
}

static void clp_destroy(void *ws) {
  ClpWs *w = ws;
  if (!w) return;
  us_eq_gen_free(&w->gen);
  us_free(w->bounds);
  us_free(w->sol);
  us_free(w);
}

static int clp_reserve(ClpWs *w, int nrow, int ncol) {
  if (nrow > w->cap_row) {
    double *b = us_realloc(w->bounds, (size_t)nrow * sizeof(double));
    if (!b) return -1;
    w->bounds = b;
    w->cap_row = nrow;
  }
  if (ncol > w->cap_col) {
    double *x = us_realloc(w->sol, (size_t)ncol * sizeof(double));
    if (!x) return -1;
    w->sol = x;
    w->cap_col = ncol;
  }
  return 0;
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
  Clp_setPrimalTolerance(m, 1e-9);
  return m;
}

/* After an infeasible solve: the evidence body from CLP's dual ray. */
static int clp_evidence(Clp_Simplex *m, ClpWs *w, const us_EqSystem *sys) {
  double *ray = Clp_infeasibilityRay(m);
  if (!ray) return -1;
  int body = us_eq_gen_farkas_body(sys, &w->gen, ray);
  Clp_freeRay(m, ray);
  return body;
}

/* No column at all (no active contact can carry load): the bodies stand
 * only if nothing pushes them, i.e. rhs = 0. Solvers disagree on empty
 * models (lp_solve does not run them), so this is decided here. */
static us_Verdict no_columns_verdict(const us_EqSystem *sys) {
  for (int r = 0; r < sys->nbody * sys->nw; r++)
    if (sys->rhs[r] != 0.0) return US_UNSTABLE;
  return US_STABLE;
}

static us_Status clp_solve(void *ws, const us_EqSystem *sys, const int *added, int nadded,
                           const int *removed, int nremoved, int restart, us_Verdict *verdict,
                           double *f, us_StabilityInfo *info, char *note, size_t note_sz,
                           us_Error *err) {
  US_UNUSED(added), US_UNUSED(nadded), US_UNUSED(removed), US_UNUSED(nremoved);
  US_UNUSED(restart), US_UNUSED(info);
  ClpWs *w = ws;
  w->last_body = -1;
  int r = us_eq_generators(sys, &w->gen);
  if (r == -2) return us_error_set(err, US_ERR_USAGE, "the LP backends support 2D only");
  if (r || clp_reserve(w, w->gen.nrow, w->gen.ncol))
    return us_error_set(err, US_ERR_NOMEM, "out of memory building the LP");
  if (w->gen.ncol == 0) {
    *verdict = no_columns_verdict(sys);
    snprintf(note, note_sz, "no active contact");
    return US_OK;
  }
  Clp_Simplex *m = clp_load(w, sys);
  if (!m) return us_error_set(err, US_ERR_NOMEM, "CLP could not create a model");
  Clp_dual(m, 0);
  int status = Clp_status(m);
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

const us_Backend us_backend_clp = {
    .name = "lp",
    .create = clp_create,
    .destroy = clp_destroy,
    .solve = clp_solve,
    .unstable_body = clp_unstable_body,
};
