/* The exhaustive contact-mode search for strong stability: the reference
 * decision, with lp_solve (independent of CBC, which solves the MIP).
 *
 * Every solution of the dynamics at rest shows, at each contact, one of
 * four modes (separates, sticks, slides +t, slides -t; us_ContactMode; 3D:
 * one slide per cone direction, us_strong_modes), and
 * in a fixed mode pattern the conditions are linear: the solutions of one
 * pattern are a polyhedron, given in strong.h's variables by bounds only.
 * So the union over patterns is the solution set, and strong stability
 * fails iff the largest gravity power F^T u over some pattern is positive
 * (any solution has u^T M u = s F^T u + sum_c f_t a_t, and sliding friction
 * opposes the slip, f_t a_t <= 0: u != 0 forces F^T u > 0).
 *
 * Search: depth first over partial patterns. A node leaves the unassigned
 * contacts in the relaxation (every mode's conditions but complementarity),
 * a superset of its patterns' solutions, so an LP optimum <= tol (or an
 * infeasible LP) settles the whole subtree. Otherwise, if the optimum is
 * complementary everywhere it is the witness; else the node branches on
 * the first unassigned contact where it is not. The answer "yes" is the
 * search exhausted with no optimum above tol: every pattern was covered.
 * Any LP without a clean status, the node budget or the clock gives
 * undecided, never yes. */
#include "strong_lp.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct Search {
  const us_StrongModel *m;
  lprec *lp;
  int *mode;          /* [nc] assigned mode or -1 */
  double *lo, *hi;    /* [nv] working bounds */
  double *x;          /* [nv] the LP's solution */
  double tol, deadline;
  long nodes, max_nodes;
  int found, undecided;
  double power;       /* largest optimum seen; the witness's once found */
  char note[160];
} Search;

/* The node's bounds, within the certified magnitudes (strong_model.c), so
 * that no LP is unbounded. */
static void load_bounds(Search *q) {
  const us_StrongModel *m = q->m;
  for (int j = 0; j < m->nv; j++) {
    double b = 1.01 * m->bound[j] + 1e-9;
    set_bounds(q->lp, j + 1, fmax(q->lo[j], -b), fmin(q->hi[j], b));
  }
}

/* Solve the node's LP: 1 optimum in q->x and *obj, 0 infeasible, -1 no
 * clean status (undecided). */
static int node_lp(Search *q, double *obj) {
  load_bounds(q);
  q->nodes++;
  /* one LP of a large 3D model can outlast the deadline: lp_solve's own
     limit (whole seconds), a timeout being undecided */
  if (q->deadline > 0) set_timeout(q->lp, (long)ceil(fmax(q->deadline - us_now(), 0)) + 1);
  int rc = solve(q->lp);
  if (rc == INFEASIBLE) return 0;
  if (rc != OPTIMAL && rc != PRESOLVED) {
    snprintf(q->note, sizeof q->note, "lp_solve returned status %d in the mode search", rc);
    return -1;
  }
  *obj = get_working_objective(q->lp);
  return get_variables(q->lp, q->x) ? 1 : -1;
}

/* The first unassigned contact where x is not complementary, or -1. */
static int branch_contact(const Search *q) {
  for (int c = 0; c < q->m->nc; c++)
    if (q->mode[c] < 0 && us_strong_mode_of(q->m, q->x, c, 1e-9) < 0) return c;
  return -1;
}

static void dfs(Search *q) {
  if (q->found || q->undecided) return;
  if (q->nodes >= q->max_nodes || us_past(q->deadline)) {
    q->undecided = 1;
    snprintf(q->note, sizeof q->note, "mode search stopped at its budget (%ld LPs)", q->nodes);
    return;
  }
  double obj = 0;
  int rc = node_lp(q, &obj);
  if (rc < 0) q->undecided = 1;
  if (rc <= 0) return;
  q->power = fmax(q->power, obj);
  if (obj <= q->tol) return;
  int c = branch_contact(q);
  if (c < 0) {
    q->found = 1; /* complementary everywhere with power above tol */
    q->power = obj;
    return;
  }
  int modes[2 + US_STRONG_EDGES];
  int nmode = us_strong_modes(q->m, c, q->x, modes);
  for (int i = 0; i < nmode && !q->found && !q->undecided; i++) {
    int k = modes[i];
    q->mode[c] = k;
    us_strong_mode_bounds(q->m, c, k, q->lo, q->hi);
    dfs(q);
  }
  if (!q->found) {
    q->mode[c] = -1;
    us_strong_mode_bounds(q->m, c, -1, q->lo, q->hi);
  }
}

int us_strong_polish(const us_StrongModel *m, double *x, double power) {
  int *mode = us_malloc((size_t)(m->nc > 0 ? m->nc : 1) * sizeof(int));
  double *lo = us_malloc((size_t)m->nv * sizeof(double));
  double *hi = us_malloc((size_t)m->nv * sizeof(double));
  double *obj = us_calloc((size_t)m->nv + 1, sizeof(double));
  lprec *lp = mode && lo && hi && obj ? us_strong_lp_new(m) : NULL;
  int rc = lp ? 1 : -1;
  for (int c = 0; lp && c < m->nc; c++) {
    mode[c] = us_strong_mode_of(m, x, c, 1e-7);
    if (mode[c] < 0) rc = 0;
  }
  if (rc == 1) {
    /* the pattern's polyhedron, gravity power at least half the found one,
       the largest gravity scale s */
    memcpy(lo, m->lo, (size_t)m->nv * sizeof(double));
    memcpy(hi, m->hi, (size_t)m->nv * sizeof(double));
    for (int c = 0; c < m->nc; c++) us_strong_mode_bounds(m, c, mode[c], lo, hi);
    for (int j = 0; j < m->nv; j++) {
      double b = 1.01 * m->bound[j] + 1e-9;
      set_bounds(lp, j + 1, fmax(lo[j], -b), fmin(hi[j], b));
    }
    int *colno = us_malloc((size_t)m->nu * sizeof(int));
    for (int j = 0; colno && j < m->nu; j++) colno[j] = j + 1;
    if (colno) add_constraintex(lp, m->nu, m->obj, colno, GE, 0.5 * power);
    us_free(colno);
    obj[m->nv] = 1;
    set_obj_fn(lp, obj);
    int st = colno ? solve(lp) : -1;
    rc = (st == OPTIMAL || st == PRESOLVED) && get_variables(lp, x) ? 1 : 0;
  }
  if (lp) delete_lp(lp);
  us_free(mode);
  us_free(lo);
  us_free(hi);
  us_free(obj);
  return rc;
}

us_Status us_strong_enumerate(const us_StrongModel *m, const us_StrongSettings *set,
                              double deadline, double *x, us_StrongResult *out, us_Error *err) {
  Search q = {.m = m, .tol = set->tol, .deadline = deadline, .max_nodes = set->max_nodes};
  size_t nv = (size_t)m->nv, nc = (size_t)(m->nc > 0 ? m->nc : 1);
  q.mode = us_malloc(nc * sizeof(int));
  q.lo = us_malloc(nv * sizeof(double));
  q.hi = us_malloc(nv * sizeof(double));
  q.x = x;
  q.lp = q.mode && q.lo && q.hi ? us_strong_lp_new(m) : NULL;
  us_Status st = US_OK;
  if (!q.lp) {
    st = US_ERR_NOMEM;
    us_error_set(err, st, "out of memory building the strong-stability LP");
  } else {
    for (size_t c = 0; c < nc; c++) q.mode[c] = -1;
    memcpy(q.lo, m->lo, nv * sizeof(double));
    memcpy(q.hi, m->hi, nv * sizeof(double));
    dfs(&q);
    out->strong = q.found ? 0 : q.undecided ? -1 : 1;
    out->nodes = q.nodes;
    out->power = q.power;
    out->bound = q.found || q.undecided ? INFINITY : fmin(q.power, set->tol);
    if (q.undecided) snprintf(out->note, sizeof out->note, "%s", q.note);
    delete_lp(q.lp);
  }
  us_free(q.mode);
  us_free(q.lo);
  us_free(q.hi);
  return st;
}
