/* The statics LP in cone-generator form, shared by the LP backends
 * (lp_clp.c, lp_lpsolve.c, lp_small.c, lp_lcp.c); built by cone.c from an
 * us_EqSystem.
 *
 * G l = rhs, l >= 0, equality rows only (rows as in us_EqSystem). Each
 * active contact contributes unit-length generator columns of its cone,
 * column = cn A(c, n) + ct1 A(c, t1) (+ ct2 A(c, t2)) with (cn, ct1, ct2)
 * the generator's components in the contact frame.
 *
 * 2D (exact): with a = atan(mu), e+- = cos(a) n +- sin(a) t:
 *   mu = 0:           n            (slots 0)
 *   0 < mu <= n_mu:   e+, e-       (slots 1, 2)
 *   n_mu < mu:        n, e+, e-
 * (mu = INFINITY gives e+- = +-t: the half-plane f_n >= 0.)
 *
 * 3D: the circular cone |f_t| <= mu f_n is not polyhedral. mu = 0 gives n
 * and mu = INFINITY n, +-t1, +-t2 (the half-space, exact); for finite
 * mu > 0 each contact has a polygon of directions theta_1 < ... < theta_k
 * (us_ConeSet: 8 uniform ones until refined) and the set's mode picks
 *   INNER: edges at the theta_i on the circular cone (cos a, sin a cos
 *          theta_i, sin a sin theta_i): their hull is inside the cone, so a
 *          feasible LP is a stable certificate for the true cone;
 *   OUTER: edges at the midpoints phi_i of consecutive directions, at the
 *          angle atan(mu / cos(delta_i / 2)) (delta_i the gap): the polygon
 *          whose sides touch the circle at the theta_i, so the cone holds
 *          the circular one and an infeasible LP (its Farkas ray) proves
 *          the true cone infeasible too.
 * plus n for wide cones in both. Refining a contact at a direction theta
 * (us_cone_set_refine) adds a vertex of the inner polygon and a tangent
 * side of the outer one there; stability.c alternates the two LPs and
 * refines where the outer forces leave the circle (docs/cones3d.md).
 *
 * Bilateral joints (e->bilateral, classify's equality constraints): every
 * contact gets +-n, +-t1 (+-t2) instead (slots 0 .. 2 dim - 1), so its
 * force is free in sign and mu plays no part.
 *
 * Slots: a column's key among its contact's columns (0: n), stable
 * between builds, so backends can keep a basis status per (contact, slot);
 * us_eq_gen_slots(dim) bounds them.
 */
#ifndef US_STABILITY_LP_GEN_H
#define US_STABILITY_LP_GEN_H

#include "equilibrium.h"

#define US_CONE_START 8       /* directions of an unrefined 3D polygon */
#define US_CONE_MAX_EDGES 64  /* directions of one contact's polygon at most */

typedef enum us_ConeMode { US_CONE_INNER = 0, US_CONE_OUTER = 1 } us_ConeMode;

/* The 3D polygons, per structure contact (all sub-assemblies share them:
 * a refinement made for one test serves every later test). */
typedef struct us_ConeSet {
  int ncontact;
  us_ConeMode mode;
  int *nang;       /* [ncontact] directions of a refined polygon; 0: unrefined */
  double **ang;    /* [ncontact] sorted directions in [0, 2 pi), NULL: unrefined */
} us_ConeSet;

int us_cone_set_init(us_ConeSet *c, int ncontact); /* 0 or -1 (OOM) */
void us_cone_set_free(us_ConeSet *c);
/* Add direction theta (radians, any value) to contact c's polygon: 1
 * added, 0 not (already within a tiny angle of a direction, or the polygon
 * is full), -1 out of memory. */
int us_cone_set_refine(us_ConeSet *c, int contact, double theta);
/* The largest gap between consecutive directions of contact c's polygon. */
double us_cone_set_gap(const us_ConeSet *c, int contact);

typedef struct us_EqGen {
  int nrow, ncol;
  int *start;              /* [ncol + 1] */
  int *row;                /* [start[ncol]] */
  double *val;
  int *col_contact;        /* [ncol] active-contact index */
  unsigned char *col_slot; /* [ncol] key among the contact's columns */
  double *col_coef;        /* [3 ncol] (cn, ct1, ct2) in the contact frame */
  int *col_blk;            /* [2 ncol] the row blocks of its sides a, b (-1: held) */
  int cap_col, cap_nnz;
} us_EqGen;

/* 0, -1 on OOM. Reuses g's arrays (zero-init is valid). n_column_mu:
 * contacts with mu above it also get the column n. In 3D the polygons are
 * e->cones' (NULL: the inner unrefined ones). */
int us_eq_generators(const us_EqSystem *e, double n_column_mu, us_EqGen *g);
void us_eq_gen_free(us_EqGen *g);
/* Key of column j among the columns of its contact, < us_eq_gen_slots. */
int us_eq_gen_slot(const us_EqGen *g, int j);
int us_eq_gen_slots(int dim);
/* Edge multipliers l (ncol) to components f (dim * ncontact); l < 0 -> 0. */
void us_eq_gen_forces(const us_EqSystem *e, const us_EqGen *g, const double *l, double *f);
/* y (nrow, either sign) a Farkas ray of G l = rhs, l >= 0, with slack
 * `slack` relative to |rhs . y|? Then the body with the largest virtual
 * motion in y, else -1. */
int us_eq_gen_farkas_body(const us_EqSystem *e, const us_EqGen *g, const double *y,
                          double slack);

/* The LP settings with every field <= 0 replaced by its default
 * (us_lp_default_settings; both in lp_settings.c). */
us_LpSettings us_lp_settings_resolve(const us_LpSettings *in);

/* No column at all (no active contact can carry load): the bodies stand
 * only if nothing pushes them, i.e. rhs = 0. */
us_Verdict us_eq_no_columns_verdict(const us_EqSystem *e);

#endif
