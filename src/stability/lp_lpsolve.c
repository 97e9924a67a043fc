/* The reference stability backend: the same statics feasibility LP as
 * lp_clp.c, solved by lp_solve 5.5, from scratch for every test.
 *
 * Formulation: the cone-generator form of lp_gen.h (G l = rhs, l >= 0,
 * zero objective; exact in 2D; unit generators whatever mu, so mu up to
 * 1e300 or INFINITY leaves every entry of G of the wrenches' size).
 * lp_solve's default bounds are exactly l in [0, inf), so no variable needs
 * set_unbounded. The model is built column by column (add_columnex, which
 * suits our column-major G) after sizing it once with resize_lp; rows are
 * then made equalities with their right-hand sides. lp_solve's default
 * scaling runs first (it is measurably faster on ordinary structures); when
 * it ends in a numerical failure the model is solved again unscaled: the
 * system is normalized already (lp_gen.h), and the geometric scaling is
 * what turned the unit cone edges of very wide cones (mu >= 1e8, entries
 * down to 1 / mu) into numerical failures.
 *
 * Cycling: lp_solve's default simplex (dual phase 1, then primal) can loop
 * forever on degenerate systems (a 5-body structure found by fuzzing,
 * tests/fuzz/corpus/pipeline/crash-lpsolve-cycle.json). Every solve has a
 * time limit growing with the model (2 s + 10 ms per column, far above
 * the normal time); a run that hits it is retried once with the primal
 * simplex, and a second time-out is UNDECIDED, never a verdict. A
 * SUBOPTIMAL answer is a feasible point (the objective is zero), so it is
 * a stable claim like OPTIMAL, re-checked by the certificate.
 *
 * Memory: the lprec and everything it returns belong to lp_solve
 * (delete_lp); solutions are copied out with get_variables into our own
 * buffer. lp_solve reports OOM as NOMEMORY (or a NULL lprec).
 */
#include "backend.h"
#include "lp_gen.h"

#include <lp_lib.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct LpsWs {
  us_LpSettings set;
  us_EqGen gen;
  double *col;      /* [2 * 6] one column: two bodies' wrench rows at most */
  int *rowno;
  double *sol;      /* [ncol] */
  int cap_col;
  double deadline; /* us_now() time; 0: none */
} LpsWs;

static void *lps_create(const us_Structure *s, const us_StabilitySettings *set, us_Error *err) {
  US_UNUSED(s);
  LpsWs *w = us_calloc(1, sizeof *w);
  if (w) w->set = us_lp_settings_resolve(&set->lp);
  if (w) w->col = us_malloc(12 * sizeof(double));
  if (w) w->rowno = us_malloc(12 * sizeof(int));
  if (!w || !w->col || !w->rowno) {
    if (w) us_free(w->col), us_free(w->rowno);
    us_free(w);
    us_error_set(err, US_ERR_NOMEM, "out of memory creating the lp_solve workspace");
    return NULL;
  }
  return w;
}

static void lps_destroy(void *ws) {
  LpsWs *w = ws;
  if (!w) return;
  us_eq_gen_free(&w->gen);
  us_free(w->col);
  us_free(w->rowno);
  us_free(w->sol);
  us_free(w);
}

/* Build the lprec of G l = rhs. NULL when lp_solve runs out of memory. */
static lprec *lps_load(LpsWs *w, const us_EqSystem *sys, int scaled) {
  const us_EqGen *g = &w->gen;
  lprec *lp = make_lp(g->nrow, 0);
  if (!lp) return NULL;
  set_verbose(lp, NEUTRAL);
  if (!scaled) set_scaling(lp, SCALE_NONE);
  if (!resize_lp(lp, g->nrow, g->ncol)) goto fail;
  for (int j = 0; j < g->ncol; j++) {
    int n = 0;
    for (int k = g->start[j]; k < g->start[j + 1]; k++, n++) {
      w->rowno[n] = g->row[k] + 1; /* lp_solve rows are 1-based, 0 = objective */
      w->col[n] = g->val[k];
    }
    if (!add_columnex(lp, n, w->col, w->rowno)) goto fail;
  }
  for (int r = 0; r < g->nrow; r++)
    if (!set_constr_type(lp, r + 1, EQ) || !set_rh(lp, r + 1, sys->rhs[r])) goto fail;
  return lp;
fail:
  delete_lp(lp);
  return NULL;
}

/* lp_solve's time limit in whole seconds: its own (see Cycling above),
 * cut to what is left before the deadline (at least 1 s: 0 means none). */
static long lps_timeout(const LpsWs *w, int ncol) {
  long limit = 2 + ncol / 100;
  if (w->deadline > 0) limit = US_MIN(limit, US_MAX(1L, (long)ceil(w->deadline - us_now())));
  return limit;
}

/* solve() with the time limit and the primal retry (see Cycling above). */
static int lps_run(const LpsWs *w, lprec *lp, int ncol) {
  set_timeout(lp, lps_timeout(w, ncol));
  int ret = solve(lp);
  if (ret != TIMEOUT || (w->deadline > 0 && us_now() >= w->deadline)) return ret;
  set_simplextype(lp, SIMPLEX_PRIMAL_PRIMAL);
  default_basis(lp);
  set_timeout(lp, lps_timeout(w, ncol));
  return solve(lp);
}

static void lps_set_deadline(void *ws, double deadline) { ((LpsWs *)ws)->deadline = deadline; }

static us_Status lps_solve(void *ws, const us_BackendProblem *pb, us_BackendOut *out,
                           us_Error *err) {
  /* the problem and the output under the names the body reads */
  const us_EqSystem *sys = pb->sys;
  us_Verdict *verdict = &out->verdict;
  double *f = out->f;
  char *note = out->note;
  size_t note_sz = out->note_sz;
  LpsWs *w = ws;
  if (us_eq_generators(sys, w->set.n_column_mu, &w->gen) || US_GROW(w->sol, w->cap_col, w->gen.ncol + 1))
    return us_error_set(err, US_ERR_NOMEM, "out of memory building the LP");
  if (w->gen.ncol == 0) {
    /* lp_solve does not run empty models: decided here */
    *verdict = us_eq_no_columns_verdict(sys);
    snprintf(note, note_sz, "no active contact");
    return US_OK;
  }
  if (w->deadline > 0 && us_now() >= w->deadline) {
    *verdict = US_UNDECIDED;
    snprintf(note, note_sz, "lp_solve: time limit");
    return US_OK;
  }
  lprec *lp = lps_load(w, sys, 1);
  if (!lp) return us_error_set(err, US_ERR_NOMEM, "lp_solve could not build the model");
  int ret = lps_run(w, lp, w->gen.ncol);
  if (ret == NUMFAILURE) { /* once more without lp_solve's scaling */
    delete_lp(lp);
    lp = lps_load(w, sys, 0);
    if (!lp) return us_error_set(err, US_ERR_NOMEM, "lp_solve could not build the model");
    ret = lps_run(w, lp, w->gen.ncol);
  }
  us_Status st = US_OK;
  if (ret == OPTIMAL || ret == SUBOPTIMAL) {
    get_variables(lp, w->sol);
    us_eq_gen_forces(sys, &w->gen, w->sol, f);
    *verdict = US_STABLE;
    snprintf(note, note_sz, "lp_solve: feasible");
  } else if (ret == INFEASIBLE) {
    *verdict = US_UNSTABLE;
    snprintf(note, note_sz, "lp_solve: infeasible");
  } else if (ret == TIMEOUT) {
    *verdict = US_UNDECIDED;
    snprintf(note, note_sz, w->deadline > 0 && us_now() >= w->deadline
                                ? "lp_solve: time limit"
                                : "lp_solve: no answer within its time limit (cycling)");
  } else if (ret == NOMEMORY) {
    st = us_error_set(err, US_ERR_NOMEM, "lp_solve ran out of memory");
  } else {
    st = us_error_set(err, US_ERR_SOLVER, "lp_solve stopped with status %d", ret);
  }
  delete_lp(lp);
  return st;
}

const us_Backend us_backend_lpsolve = {
    .method = US_METHOD_LPSOLVE,
    .create = lps_create,
    .destroy = lps_destroy,
    .solve = lps_solve,
    .unstable_body = NULL,
    .set_deadline = lps_set_deadline,
};
