/* Representative contact forces, the LP part (module clp.so, beside
 * lp_clp.c; represent.c is the host's entry): of the many force sets that hold a stable
 * sub-assembly, one chosen by a stated rule instead of the solver's vertex.
 *
 * Forces are not unique: a structure that stands is held by a convex set
 * of contact forces, and an LP solver returns a vertex of it, which
 * squeezes a lone block at the edge of its friction cone and sends a
 * pyramid's load down a few columns. The rules here (us_ForceSet) are LPs
 * on the statics system in cone-generator form (lp_gen.h: G l = rhs,
 * l >= 0, unit-length generators, forces in units of the total weight),
 * solved with CLP:
 *   min-sum  A: minimise s = sum_j w_j l_j, the total of the generator
 *               weights, w_j = 1 for a contact's pure normal generator and
 *               FRICTION_COST (2) for the friction edges: the least total
 *               force, friction counted twice, so a lone block is not
 *               squeezed sideways when it need not be.
 *   margin   A, then B: maximise t subject to f_n(c) = sum_{j of c} cn_j l_j
 *               >= t for every active contact and sum_j w_j l_j <= 2 s*
 *               (MARGIN_BUDGET: without a budget a self-stress, such as a
 *               block wedged between two others, would raise t without
 *               end), then C: minimise sum_j w_j l_j with every f_n(c) >=
 *               t* (the least total force that keeps the margin).
 *   min-norm minimise sum_j w_j l_j^2 / 2 (a strictly convex QP in l, so
 *               its solution is unique and keeps any symmetry of the
 *               structure: the load spread evenly), by CLP's barrier
 *               without crossover; its point is only as precise as the
 *               barrier's tolerance, and the certificate check decides.
 * In 3D the cones are the inner polygons (lp_gen.h, 8 directions), inside
 * the circular cone, so any solution is admissible for the true cone; a
 * structure that stands only on the circle's rim gets no representative
 * set here (verdict undecided, the caller keeps the solver's).
 *
 * Invariant: a STABLE result carries forces that passed the independent
 * certificate check (certificate.c) at the settings' cert_tol, exactly as
 * a stability test's; anything else is UNDECIDED with a note (the
 * solver's forces stay the caller's to show). This never decides
 * stability: an infeasible LP here is "no representative set", not
 * "unstable" (the inner 3D cones are smaller than the true ones). */
#include "certificate.h"
#include "clp_module.h"
#include "equilibrium.h"
#include "lp_gen.h"

#include <coin/Clp_C_Interface.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* Stage B's budget: the total force may be this many times the least. */
#define MARGIN_BUDGET 2.0
/* Stage C keeps this share of the margin found (room for CLP's tolerance). */
#define MARGIN_KEEP (1.0 - 1e-7)
/* Every contact with friction also gets the pure normal generator (the LP
 * backends add it for wide cones only), so that the objective below can
 * tell pure pressure from friction. */
#define N_COLUMN_MU 0.0
/* The objective's weight of a generator that carries friction (the pure
 * normal weighs 1): friction is used only where equilibrium needs it. */
#define FRICTION_COST 2.0
/* CLP's primal tolerance: well inside the certificate check's 1e-6. */
#define PRIMAL_TOL 1e-10

/* The LP of stages A-C: columns l (ngen) then t; rows G (nrow), one margin
 * row per active contact (f_n - t >= 0), one budget row (sum w l). */
typedef struct RepLp {
  us_EqGen gen;
  int nrow, ncol;   /* of the whole LP */
  int *start, *row;
  double *val, *rlo, *rup, *clo, *cup, *obj;
} RepLp;

static void rep_free(RepLp *p) {
  us_eq_gen_free(&p->gen);
  us_free(p->start), us_free(p->row), us_free(p->val);
  us_free(p->rlo), us_free(p->rup), us_free(p->clo), us_free(p->cup), us_free(p->obj);
}

static int rep_alloc(RepLp *p, size_t nnz) {
  size_t nr = (size_t)p->nrow, nc = (size_t)p->ncol;
  p->start = us_malloc((nc + 1) * sizeof(int));
  p->row = us_malloc(nnz * sizeof(int));
  p->val = us_malloc(nnz * sizeof(double));
  p->rlo = us_malloc(nr * sizeof(double)), p->rup = us_malloc(nr * sizeof(double));
  p->clo = us_malloc(nc * sizeof(double)), p->cup = us_malloc(nc * sizeof(double));
  p->obj = us_calloc(nc, sizeof(double));
  return p->start && p->row && p->val && p->rlo && p->rup && p->clo && p->cup && p->obj ? 0 : -1;
}

/* A generator's weight in the objective and the budget row. */
static double gen_weight(const us_EqGen *g, int j) {
  return us_eq_gen_slot(g, j) == 0 ? 1.0 : FRICTION_COST;
}

/* The columns: each generator's G entries, its cn in its contact's margin
 * row, its weight in the budget row; then t, -1 in every margin row. */
static void rep_columns(RepLp *p, const us_EqSystem *e) {
  const us_EqGen *g = &p->gen;
  int q = 0, margin0 = g->nrow, budget = g->nrow + e->ncontact;
  for (int j = 0; j < g->ncol; j++) {
    p->start[j] = q;
    for (int k = g->start[j]; k < g->start[j + 1]; k++)
      p->row[q] = g->row[k], p->val[q++] = g->val[k];
    p->row[q] = margin0 + g->col_contact[j], p->val[q++] = g->col_coef[3 * j];
    p->row[q] = budget, p->val[q++] = gen_weight(g, j);
    p->clo[j] = 0.0, p->cup[j] = DBL_MAX;
  }
  p->start[g->ncol] = q;
  for (int c = 0; c < e->ncontact; c++) p->row[q] = margin0 + c, p->val[q++] = -1.0;
  p->start[g->ncol + 1] = q;
  p->clo[g->ncol] = p->cup[g->ncol] = 0.0; /* t: fixed at 0 until stage B */
}

/* Rows: equilibrium G l = rhs, margins >= 0, the budget free until stage B. */
static void rep_rows(RepLp *p, const us_EqSystem *e) {
  int nr = p->gen.nrow;
  for (int r = 0; r < nr; r++) p->rlo[r] = p->rup[r] = e->rhs[r];
  for (int r = nr; r < p->nrow; r++) p->rlo[r] = 0.0, p->rup[r] = DBL_MAX;
}

static int rep_build(RepLp *p, const us_EqSystem *e) {
  if (us_eq_generators(e, N_COLUMN_MU, &p->gen)) return -1;
  p->nrow = p->gen.nrow + e->ncontact + 1;
  p->ncol = p->gen.ncol + 1;
  size_t nnz = (size_t)p->gen.start[p->gen.ncol] + 2 * (size_t)p->gen.ncol + (size_t)e->ncontact;
  if (rep_alloc(p, nnz)) return -1;
  rep_columns(p, e);
  rep_rows(p, e);
  return 0;
}

/* One stage: objective sum w l (minimise) or -t; CLP's primal simplex from
 * the last stage's basis. 1 optimal, 0 not. */
static int rep_stage(Clp_Simplex *m, RepLp *p, int maximise_t) {
  int nl = p->gen.ncol;
  for (int j = 0; j < nl; j++)
    p->obj[j] = maximise_t ? 0.0 : gen_weight(&p->gen, j);
  p->obj[nl] = maximise_t ? -1.0 : 0.0;
  Clp_chgObjCoefficients(m, p->obj);
  Clp_chgRowUpper(m, p->rup);
  Clp_chgColumnLower(m, p->clo);
  Clp_chgColumnUpper(m, p->cup);
  Clp_primal(m, 0);
  return Clp_status(m) == 0;
}

/* min-norm: minimise sum_j w_j l_j^2 / 2 (CLP's quadratic objective,
 * diagonal; the barrier: CLP's primal QP took 3.5 s on the 91-block
 * pyramid, the barrier 0.15 s), no linear part. 1 optimal, 0 not, -1 OOM. */
static int rep_min_norm(Clp_Simplex *m, RepLp *p) {
  int nl = p->gen.ncol, ok = -1;
  int *start = us_malloc(((size_t)p->ncol + 1) * sizeof *start);
  int *col = us_malloc(((size_t)p->ncol + 1) * sizeof *col);
  double *val = us_malloc(((size_t)p->ncol + 1) * sizeof *val);
  if (start && col && val) {
    for (int j = 0; j <= p->ncol; j++) start[j] = j < nl ? j : nl;
    for (int j = 0; j < nl; j++) col[j] = j, val[j] = gen_weight(&p->gen, j), p->obj[j] = 0.0;
    p->obj[nl] = 0.0;
    Clp_chgObjCoefficients(m, p->obj);
    Clp_loadQuadraticObjective(m, p->ncol, start, col, val);
    Clp_initialBarrierNoCrossSolve(m);
    ok = Clp_status(m) == 0;
  }
  us_free(start), us_free(col), us_free(val);
  return ok;
}

/* Stages A (and B, C for margin) or the QP on the loaded model; 1 solved,
 * 0 not, -1 out of memory. */
static int rep_solve(Clp_Simplex *m, RepLp *p, us_ForceSet kind) {
  int nl = p->gen.ncol, budget = p->nrow - 1;
  if (kind == US_FORCESET_MIN_NORM) return rep_min_norm(m, p);
  if (!rep_stage(m, p, 0)) return 0;
  if (kind != US_FORCESET_MARGIN) return 1;
  p->rup[budget] = MARGIN_BUDGET * Clp_objectiveValue(m);
  p->cup[nl] = DBL_MAX;
  if (!rep_stage(m, p, 1)) return 0;
  p->clo[nl] = MARGIN_KEEP * Clp_getColSolution(m)[nl];
  p->rup[budget] = DBL_MAX;
  return rep_stage(m, p, 0);
}

/* The LP's generator weights into res->forces (newtons), then the check. */
static us_Status rep_certify(const us_EqSystem *e, const RepLp *p, const double *l,
                             const us_Bitset *present, double tol, us_StabilityResult *res,
                             us_Error *err) {
  if (us_forces_reserve(&res->forces, e->ncontact))
    return us_error_set(err, US_ERR_NOMEM, "out of memory storing contact forces");
  res->forces.ncontact = e->ncontact;
  for (int c = 0; c < e->ncontact; c++) res->forces.contact[c] = e->contact[c];
  us_eq_gen_forces(e, &p->gen, l, res->forces.f);
  for (int j = 0; j < e->ncontact * e->dim; j++) res->forces.f[j] *= e->force_scale;
  /* the check's scratch here, so that no memory failure passes for a failed check */
  double *acc = us_malloc(((size_t)US_CERT_ACC * (size_t)e->s->nbody + 1) * sizeof *acc);
  unsigned char *seen = us_malloc((size_t)e->s->ncontact + 1);
  int have = acc && seen;
  if (have) us_certificate_check_buf(e->s, present, &res->forces, tol, acc, seen, &res->check);
  us_free(acc);
  us_free(seen);
  if (!have) return us_error_set(err, US_ERR_NOMEM, "out of memory checking forces");
  res->verdict = res->check.ok ? US_STABLE : US_UNDECIDED;
  if (!res->check.ok)
    snprintf(res->note, sizeof res->note, "representative forces failed the certificate check "
             "(force %.2g torque %.2g cone %.2g sign %.2g)", res->check.max_force_residual,
             res->check.max_torque_residual, res->check.max_cone_violation,
             res->check.max_sign_violation);
  return US_OK;
}

/* Load, solve and certify the LP of system e (clp_module.h). */
us_Status us_represent_run(const us_EqSystem *e, const us_Bitset *present, us_ForceSet kind,
                           const char *name, double tol, us_StabilityResult *res,
                           us_Error *err) {
  RepLp p;
  memset(&p, 0, sizeof p);
  us_Status st = US_OK;
  Clp_Simplex *m = NULL;
  if (rep_build(&p, e) || !(m = Clp_newModel())) {
    st = us_error_set(err, US_ERR_NOMEM, "out of memory building the force LP");
  } else {
    Clp_setLogLevel(m, 0);
    Clp_loadProblem(m, p.ncol, p.nrow, p.start, p.row, p.val, p.clo, p.cup, p.obj, p.rlo, p.rup);
    Clp_setPrimalTolerance(m, PRIMAL_TOL);
    int solved = rep_solve(m, &p, kind);
    if (solved > 0)
      st = rep_certify(e, &p, Clp_getColSolution(m), present, tol, res, err);
    else if (solved < 0)
      st = us_error_set(err, US_ERR_NOMEM, "out of memory building the force QP");
    else
      snprintf(res->note, sizeof res->note, "no representative forces: the %s LP was not "
               "solved (CLP status %d)%s", name, Clp_status(m),
               e->dim == 3 ? "; 3D uses the inner friction polygons" : "");
  }
  if (m) Clp_deleteModel(m);
  rep_free(&p);
  return st;
}
