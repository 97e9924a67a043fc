/* The MIP of strong stability, solved by CBC (module cbc.so): one
 * mixed-integer program over the contact-mode pattern that maximises the
 * gravity power of strong.h's homogenized model.
 *
 * Binaries per contact c: z (separates), p (slides +t), q (slides -t);
 * z = p = q = 0 is "closed and sticking". With the certified magnitudes
 * B[] of strong_model.c (every normalized solution satisfies
 * |x_j| <= B_j), the complementarity conditions become
 *   a_n <= B_an z,  f_n <= 1 - z            (separates or closed)
 *   a_t <= B_at (p + z),  -a_t <= B_at (q + z)   (slip only when sliding,
 *                                             or free when separated)
 *   g- <= 2 mu (1 - p),  g+ <= 2 mu (1 - q),  p + q <= 1
 * and every solution of the dynamics, normalized, is feasible for some
 * binaries: the big-M values cut nothing off, so the MIP's optimum is the
 * largest gravity power over all patterns. (Separated, f = 0 makes g+- = 0
 * and p, q play no part.) B is enlarged by a factor 1.01 plus 1e-9 against
 * rounding. "yes" needs CBC's proven bound (its best possible objective)
 * at most tol; "no" needs a solution above tol, which the driver turns
 * into a witness and checks without CBC; anything else is undecided. */
#include "strong.h"

#include <Cbc_C_Interface.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static double big(const us_StrongModel *m, int j) { return 1.01 * m->bound[j] + 1e-9; }

/* The model's continuous columns and rows. */
static void load_lp(Cbc_Model *cbc, const us_StrongModel *m) {
  for (int j = 0; j < m->nv; j++)
    Cbc_addCol(cbc, "", fmax(m->lo[j], -big(m, j)), fmin(m->hi[j], big(m, j)), m->obj[j], 0, 0,
               NULL, NULL);
  for (int r = 0; r < m->nrow; r++) {
    int a = m->row_start[r];
    int eq = m->rlo[r] == m->rhi[r];
    Cbc_addRow(cbc, "", m->row_start[r + 1] - a, m->col + a, m->val + a, eq ? 'E' : 'L',
               m->rhi[r]);
  }
}

/* Row sum_k v_k x_{j_k} <= rhs. */
static void le(Cbc_Model *cbc, int n, int *j, double *v, double rhs) {
  Cbc_addRow(cbc, "", n, j, v, 'L', rhs);
}

/* The binaries and big-M rows of contact c (file head). */
static void contact_rows(Cbc_Model *cbc, const us_StrongModel *m, int c) {
  int z = Cbc_getNumCols(cbc), p = z + 1, q = z + 2;
  for (int k = 0; k < 3; k++) {
    Cbc_addCol(cbc, "", 0, 1, 0, 1, 0, NULL, NULL);
  }
  int an = us_sv(m, c, SV_AN), at = us_sv(m, c, SV_AT), fn = us_sv(m, c, SV_FN);
  int gp = us_sv(m, c, SV_GP), gm = us_sv(m, c, SV_GM);
  double ban = big(m, an), bat = big(m, at), bg = big(m, gp);
  le(cbc, 2, (int[]){an, z}, (double[]){1, -ban}, 0);
  le(cbc, 2, (int[]){fn, z}, (double[]){1, 1}, 1);
  le(cbc, 3, (int[]){at, p, z}, (double[]){1, -bat, -bat}, 0);
  le(cbc, 3, (int[]){at, q, z}, (double[]){-1, -bat, -bat}, 0);
  le(cbc, 2, (int[]){gm, p}, (double[]){1, bg}, bg);
  le(cbc, 2, (int[]){gp, q}, (double[]){1, bg}, bg);
  le(cbc, 2, (int[]){p, q}, (double[]){1, 1}, 1);
}

static Cbc_Model *build(const us_StrongModel *m, const us_StrongSettings *set, double deadline) {
  Cbc_Model *cbc = Cbc_newModel();
  if (!cbc) return NULL;
  Cbc_setLogLevel(cbc, 0);
  load_lp(cbc, m);
  for (int c = 0; c < m->nc; c++) contact_rows(cbc, m, c);
  Cbc_setObjSense(cbc, -1);
  Cbc_setAllowableGap(cbc, 0.1 * set->tol);
  Cbc_setAllowableFractionGap(cbc, 0);
  /* small models: CBC's cut rounds and heuristics cost more than the
     branching they save (measured on the differential test's piles) */
  Cbc_setParameter(cbc, "cuts", "off");
  Cbc_setParameter(cbc, "heuristicsOnOff", "off");
  Cbc_setParameter(cbc, "preprocess", "off");
  Cbc_setMaximumNodes(cbc, set->max_nodes > 2000000000L ? 2000000000 : (int)set->max_nodes);
  /* the deadline is wall-clock time, CBC counts CPU seconds by default */
  Cbc_setParameter(cbc, "timeMode", "elapsed");
  if (deadline > 0) Cbc_setMaximumSeconds(cbc, fmax(deadline - us_now(), 0.01));
  return cbc;
}

/* CBC's best solution: its incumbent, or for a model without binaries (no
 * contact) the LP's optimum, which CBC does not store as an incumbent. */
static const double *best(Cbc_Model *cbc) {
  if (Cbc_getNumIntegers(cbc) == 0) return Cbc_isProvenOptimal(cbc) ? Cbc_getColSolution(cbc) : NULL;
  return Cbc_bestSolution(cbc);
}

/* The answer from CBC's status, bound and best solution. */
static void read_answer(Cbc_Model *cbc, const us_StrongModel *m, const us_StrongSettings *set,
                        double *x, us_StrongResult *out) {
  const double *sol = best(cbc);
  double obj = sol ? Cbc_getObjValue(cbc) : -INFINITY;
  int infeasible = Cbc_isProvenInfeasible(cbc);
  double bound = infeasible ? -INFINITY
                 : Cbc_getNumIntegers(cbc) == 0 ? obj : Cbc_getBestPossibleObjValue(cbc);
  out->nodes = Cbc_getNodeCount(cbc);
  out->power = sol ? fmax(obj, 0) : 0;
  out->bound = bound;
  if (sol && obj > set->tol) {
    memcpy(x, sol, (size_t)m->nv * sizeof(double));
    out->strong = 0;
  } else if (infeasible || (Cbc_isProvenOptimal(cbc) && bound <= set->tol)) {
    out->strong = 1;
  } else {
    out->strong = -1;
    snprintf(out->note, sizeof out->note, "CBC stopped (status %d/%d) with bound %.3g > tol",
             Cbc_status(cbc), Cbc_secondaryStatus(cbc), bound);
  }
}

us_Status us_strong_mip(const us_StrongModel *m, const us_StrongSettings *set, double deadline,
                        double *x, us_StrongResult *out, us_Error *err) {
  Cbc_Model *cbc = build(m, set, deadline);
  if (!cbc) {
    us_error_set(err, US_ERR_NOMEM, "out of memory building the strong-stability MIP");
    return US_ERR_NOMEM;
  }
  Cbc_solve(cbc);
  read_answer(cbc, m, set, x, out);
  Cbc_deleteModel(cbc);
  return US_OK;
}
