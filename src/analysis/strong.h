/* Strong stability (strong*.c): the homogenized contact-dynamics model that
 * the exhaustive mode search (strong_enum.c, lp_solve) and the MIP
 * (strong_mip.c, module cbc) both solve, and the module's entry point.
 *
 * Variables, in this order (nv in all):
 *   u[nu]             body accelerations, normalized: (ax, ay) / |g| and
 *                     alpha L / |g| per present movable body (L the length
 *                     scale of the equilibrium system), free;
 *   per contact c, 6: f_n >= 0, f_t free, g+ = mu f_n - f_t >= 0,
 *                     g- = mu f_n + f_t >= 0, a_n >= 0, a_t free
 *                     (forces in units of the weight W, accelerations as u);
 *   s >= 0            the scale of gravity (homogenization).
 * Rows: M u - A f + s rhs = 0 (Newton-Euler, nu rows); s + sum f_n = 1 (the
 * normalization); a_n = (A^T u)_n, a_t = (A^T u)_t; the two cone rows
 * (mu above 1e6 is refused); the hull cuts of strong_model.c (rows
 * rlo <= row <= rhi: equalities, or at most rhi).
 * Objective: maximise F^T u with F = -rhs, the gravity power.
 * Every row but the normalization is homogeneous, so a solution of the
 * dynamics with gravity (s = 1) scales into this box, and back by 1 / s.
 *
 * 3D (dim 3, strong_model.c): u holds (a, alpha L) / |g| per body (6), and
 * per contact the SV3_* variables below: f_n, a_n, f_t and a_t in the
 * contact's (t[0], t[1]) frame, and the polygonal cone of US_STRONG_EDGES
 * directions w_j (angle 2 pi j / d on the tangent circle): f_n = g +
 * sum lin_j + sum lout_j, f_t = sum lin_j mu w_j + sum lout_j mu' m_j
 * (m_j the mid directions, mu' = mu / cos(pi / d): the circumscribed
 * polygon), a_t = sum beta_j w_j (every variable >= 0 but the f_t, a_t).
 * The modes are bounds on these (us_strong_mode_bounds): separates, sticks,
 * and one slide per direction (mode 2 + k). The inner model (outer = 0)
 * slides exactly along w_k with friction -mu f_n w_k: its solutions are
 * motions of the circular cone. The outer model slides anywhere in the
 * sector (w_k, w_k+1) with friction in the triangle around the arc of the
 * opposite directions: every motion of the circular cone is one of its
 * solutions. */
#ifndef US_ANALYSIS_STRONG_H
#define US_ANALYSIS_STRONG_H

#include "stability/equilibrium.h"
#include "unstack/analysis.h"

#define US_STRONG_VARS_PER_CONTACT 6
enum { SV_FN, SV_FT, SV_GP, SV_GM, SV_AN, SV_AT };
#define US_STRONG_EDGES 8 /* 3D: directions of the polygonal cones (even) */
enum { SV3_FN, SV3_AN, SV3_FT1, SV3_FT2, SV3_AT1, SV3_AT2, SV3_G, SV3_LIN,
       SV3_LOUT = SV3_LIN + US_STRONG_EDGES, SV3_BETA = SV3_LOUT + US_STRONG_EDGES,
       SV3_COUNT = SV3_BETA + US_STRONG_EDGES };

typedef struct us_StrongModel {
  us_EqSystem e;     /* built for the sub-assembly */
  int nu, nc, nv;    /* accelerations, contacts, variables */
  int dim, vpc;      /* 2 or 3; variables per contact */
  int outer;         /* 3D: 1 the outer cone model, 0 the inner one */
  int nrow;          /* rows of the CSR below */
  int *row_start;    /* [nrow + 1] */
  int *col;          /* [nnz] */
  double *val;       /* [nnz] */
  double *rlo, *rhi; /* [nrow] row bounds (equalities: lo = hi) */
  double *lo, *hi;   /* [nv] variable bounds, the relaxation of every mode */
  double *obj;       /* [nv] gravity power */
  double *mdiag;     /* [nu] (3D: the rotational entries unused) */
  double *mrot;      /* 3D: [nbody * 9] normalized inertia tensors, and */
  double *mrinv;     /* their inverses */
  double *bound;     /* [nv] |x_j| <= bound[j] for every normalized solution */
  int nnz, cap;
} us_StrongModel;

static inline int us_sv(const us_StrongModel *m, int c, int k) {
  return m->nu + m->vpc * c + k;
}

/* Build the model of sub-assembly present (strong_model.c); 0, -1 on OOM,
 * 1 when a body has no inertia or a contact a mu above 1e6 (refused: why). */
int us_strong_model_build(us_StrongModel *m, const us_Structure *s, const us_Bitset *present,
                          char *why, size_t why_size);
/* The same in 3D with the inner (outer = 0) or outer polygonal cones. */
int us_strong_model_build3(us_StrongModel *m, const us_Structure *s, const us_Bitset *present,
                           int outer, char *why, size_t why_size);
/* The modes the search tries at contact c into modes[] (at most 2 +
 * US_STRONG_EDGES), in 3D the one closest to the solution x (may be NULL)
 * first; their number. */
int us_strong_modes(const us_StrongModel *m, int c, const double *x, int *modes);
/* Tighten the big-M magnitudes (us_strong_tighten, a quarter of the time
 * left before deadline) and add the hull cuts; 0, or -1 on OOM. */
int us_strong_model_tighten(us_StrongModel *m, double deadline);
void us_strong_model_free(us_StrongModel *m);

/* Write the bounds of contact c's variables in mode k (the relaxation for
 * k < 0) into the full arrays lo[nv], hi[nv]. */
void us_strong_mode_bounds(const us_StrongModel *m, int c, int k, double *lo, double *hi);
/* The mode a normalized solution x shows at contact c, or -1 when x is not
 * complementary there (within tol). */
int us_strong_mode_of(const us_StrongModel *m, const double *x, int c, double tol);

/* Fill the witness of out from the normalized solution x (strong.c). */
int us_strong_witness(const us_StrongModel *m, const double *x, us_StrongResult *out);

/* Tighten the magnitudes bound[] of the contacts' a_n, a_t (the big-M
 * values) to their extent over the relaxation (strong_lp.c, two LPs
 * each; margin 1e-6 relative + 1e-9; stops at deadline, the bounds left
 * are valid, only looser): 0, or -1 on OOM. */
int us_strong_tighten(us_StrongModel *m, double deadline);

/* Re-solve a witness x (gravity power `power`) in its own mode pattern for
 * the largest gravity scale s, so that dividing by s amplifies rounding
 * least (strong_enum.c): 1 x replaced, 0 kept (x not complementary within
 * 1e-7, or the LP failed), -1 on OOM. */
int us_strong_polish(const us_StrongModel *m, double *x, double power);

/* The exhaustive mode search (strong_enum.c): decides into out->strong,
 * nodes, power, bound; the witness solution into x[nv] when no. */
us_Status us_strong_enumerate(const us_StrongModel *m, const us_StrongSettings *set,
                              double deadline, double *x, us_StrongResult *out, us_Error *err);

/* Module cbc.so (src/module/cbc.c): the MIP. */
typedef struct us_CbcModule {
  us_Status (*solve)(const us_StrongModel *m, const us_StrongSettings *set, double deadline,
                     double *x, us_StrongResult *out, us_Error *err);
} us_CbcModule;
us_Status us_strong_mip(const us_StrongModel *m, const us_StrongSettings *set, double deadline,
                        double *x, us_StrongResult *out, us_Error *err);
/* The module's entry points, loading it on first use; NULL with the
 * loader's error. */
const us_CbcModule *us_cbc_module_api(us_Error *err);

#endif
