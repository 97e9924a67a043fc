/* The model of strong stability as an lp_solve LP (strong_lp.h), and the
 * tightening of its big-M magnitudes by LPs over the relaxation: the layer
 * below both the model (strong_model.c, which tightens) and the mode
 * search (strong_enum.c). */
#include "strong_lp.h"

#include <math.h>
#include <string.h>

lprec *us_strong_lp_new(const us_StrongModel *m) {
  lprec *lp = make_lp(0, m->nv);
  if (!lp) return NULL;
  set_verbose(lp, 1);
  set_add_rowmode(lp, TRUE);
  int ok = 1;
  /* lp_solve may rewrite the arrays it is given: pass copies */
  int *colno = us_malloc((size_t)m->nv * sizeof(int));
  double *row = us_malloc((size_t)m->nv * sizeof(double));
  ok = colno && row;
  for (int r = 0; ok && r < m->nrow; r++) {
    int a = m->row_start[r], n = m->row_start[r + 1] - a;
    for (int k = 0; k < n; k++) colno[k] = m->col[a + k] + 1, row[k] = m->val[a + k];
    int eq = m->rlo[r] == m->rhi[r];
    ok = add_constraintex(lp, n, row, colno, eq ? EQ : LE, m->rhi[r]);
  }
  us_free(colno);
  us_free(row);
  set_add_rowmode(lp, FALSE);
  double *obj = us_calloc((size_t)m->nv + 1, sizeof(double));
  ok = ok && obj;
  if (ok) memcpy(obj + 1, m->obj, (size_t)m->nv * sizeof(double));
  ok = ok && set_obj_fn(lp, obj);
  us_free(obj);
  set_maxim(lp);
  if (!ok) delete_lp(lp);
  return ok ? lp : NULL;
}

/* The largest |x_j| over the relaxation (both directions), or -1 when an
 * LP has no clean optimum (the bound is then kept). */
static double extent(lprec *lp, const us_StrongModel *m, int j, double *obj) {
  double best = 0;
  for (int sg = -1; sg <= 1; sg += 2) {
    memset(obj, 0, ((size_t)m->nv + 1) * sizeof(double));
    obj[j + 1] = sg;
    set_obj_fn(lp, obj);
    int rc = solve(lp);
    if (rc == INFEASIBLE) return 0;
    if (rc != OPTIMAL && rc != PRESOLVED) return -1;
    best = fmax(best, get_working_objective(lp));
  }
  return best;
}

int us_strong_tighten(us_StrongModel *m, double deadline) {
  lprec *lp = us_strong_lp_new(m);
  double *obj = us_calloc((size_t)m->nv + 1, sizeof(double));
  if (!lp || !obj) {
    if (lp) delete_lp(lp);
    us_free(obj);
    return -1;
  }
  for (int j = 0; j < m->nv; j++) {
    double b = 1.01 * m->bound[j] + 1e-9;
    set_bounds(lp, j + 1, fmax(m->lo[j], -b), fmin(m->hi[j], b));
  }
  /* the big-M magnitudes only; past the deadline the rest stay as they are */
  static const int ks[] = {SV_AN, SV_AT};
  for (int c = 0; c < m->nc && !us_past(deadline); c++)
    for (int k = 0; k < 2; k++) {
      int j = us_sv(m, c, ks[k]);
      double e = extent(lp, m, j, obj);
      if (e >= 0) m->bound[j] = fmin(m->bound[j], e * (1 + 1e-6) + 1e-9);
    }
  delete_lp(lp);
  us_free(obj);
  return 0;
}

