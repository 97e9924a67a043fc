/* Private interface of the stability layer.
 *
 * The front end (stability.c) owns the workspace: it tracks the last tested
 * sub-assembly, builds the equilibrium system of the next one
 * (equilibrium.c), hands the backend the list of bodies added and removed
 * since its previous call (computation reuse), scales the forces back to
 * newtons and re-checks them without any solver (certificate.c).
 *
 * Units: the system is normalized so that forces are in units of the
 * structure's total weight W and torques in units of W * scale; a backend
 * returns forces in those units and the front end multiplies by W.
 *
 * Sign conventions: for active contact c with normal n from a into b and
 * force components f = (f_n, f_t1[, f_t2]), the force on b is
 * F = f_n n + f_t1 t1 (+ f_t2 t2) at point p, and a receives -F at p.
 * Cones: f_n >= 0, |f_t| <= mu f_n (2D exact; 3D: Euclidean norm).
 */
#ifndef US_STABILITY_H
#define US_STABILITY_H

#include "core/core.h"

/* The equilibrium system of one sub-assembly. Rows: nw per present movable
 * body (force, then torque / scale). Columns: dim per active contact
 * (normal first). Entry (row block of body i, column (c, k)) is the wrench
 * that a unit component k of contact c exerts on body i. Each column has
 * at most 2 * nw non-zeros (the two bodies of the contact). */
typedef struct us_EqSystem {
  const us_Structure *s;
  int dim;             /* 2 or 3 */
  int nw;              /* wrench size: 3 in 2D, 6 in 3D */
  int nbody;           /* present movable bodies */
  int *body;           /* [nbody] body index of each row block */
  int *row_of_body;    /* [s->nbody] row block of a body, or -1 */
  int ncontact;        /* active contacts */
  int *contact;        /* [ncontact] indices into s->contacts */
  /* Column data: for column j = c * dim + k, the row blocks touched
   * (blk[2j], blk[2j+1], -1 for ground or fixed) and the wrenches
   * (w[(2j + side) * nw + r]). */
  int *blk;
  double *w;
  double *rhs;         /* [nbody * nw]: minus the external wrench, normalized:
                          A f = rhs means equilibrium */
  double *mu;          /* [ncontact] */
  double force_scale;  /* W: multiply forces by this to get newtons */
  double length_scale; /* torque rows are divided by this */
  int cap_body, cap_contact;
} us_EqSystem;

int us_eq_init(us_EqSystem *e, const us_Structure *s);
void us_eq_free(us_EqSystem *e);
/* Build the system of sub-assembly `present`. 0 or -1 on OOM. */
int us_eq_build(us_EqSystem *e, const us_Bitset *present);
/* y = A x (y has nbody*nw entries, x ncontact*dim). */
void us_eq_mult(const us_EqSystem *e, const double *x, double *y);

/* A stability backend. The workspace is the backend's own state and may
 * keep the last sub-assembly's solution for reuse. */
typedef struct us_Backend {
  const char *name;
  void *(*create)(const us_Structure *s, const us_StabilitySettings *set, us_Error *err);
  void (*destroy)(void *ws);
  /* Decide the sub-assembly `sys`. added / removed: bodies that changed
   * since this backend's previous solve (restart = 1: no previous state to
   * reuse, e.g. first call). On stable, write dim * ncontact normalized
   * forces to f. */
  us_Status (*solve)(void *ws, const us_EqSystem *sys, const int *added, int nadded,
                     const int *removed, int nremoved, int restart, us_Verdict *verdict,
                     double *f, us_StabilityInfo *info, char *note, size_t note_sz,
                     us_Error *err);
  /* Optional (NULL: unknown). After an unstable verdict: the body the
   * backend's evidence points at (e.g. largest virtual motion in a Farkas
   * ray), else -1. */
  int (*unstable_body)(void *ws);
} us_Backend;

extern const us_Backend us_backend_clp;     /* lp_clp.c */
extern const us_Backend us_backend_lpsolve; /* lp_lpsolve.c */
extern const us_Backend us_backend_lcp;     /* lcp_backend.c (from scratch) */
extern const us_Backend us_backend_lcp_reuse;

/* ---- additions by the LP helper ---- */

/* A workspace on a given backend (tests, benchmarks); us_stability_new picks
 * the backend from set->method. */
us_Stability *us_stability_new_backend(const us_Structure *s, const us_StabilitySettings *set,
                                       const us_Backend *be, us_Error *err);

/* equilibrium.c: is contact c active in `present` (both sides present,
 * ground and fixed bodies always are; at least one side movable)? */
int us_contact_active(const us_Structure *s, const us_Bitset *present, int c);

/* equilibrium.c: the 2D LP in cone-edge form, G l = rhs, l >= 0 (column-
 * major, rows as in us_EqSystem). mu > 0: two columns per contact, (c, +1)
 * = n + mu t and (c, -1) = n - mu t; mu = 0: one column (c, 0) = n. */
typedef struct us_EqGen {
  int nrow, ncol;
  int *start;              /* [ncol + 1] */
  int *row;                /* [start[ncol]] */
  double *val;
  int *col_contact;        /* [ncol] active-contact index */
  signed char *col_sign;   /* [ncol] +1, -1 or 0 */
  int cap_col, cap_nnz;
} us_EqGen;
/* 0, -1 on OOM, -2 if dim != 2. Reuses g's arrays (zero-init is valid). */
int us_eq_generators(const us_EqSystem *e, us_EqGen *g);
void us_eq_gen_free(us_EqGen *g);
/* Edge multipliers l (ncol) to components f (2 * ncontact); l < 0 -> 0. */
void us_eq_gen_forces(const us_EqSystem *e, const us_EqGen *g, const double *l, double *f);
/* y (nrow, either sign) a Farkas ray of G l = rhs, l >= 0? Then the body
 * with the largest virtual motion in y, else -1. */
int us_eq_gen_farkas_body(const us_EqSystem *e, const us_EqGen *g, const double *y);

/* certificate.c: us_certificate_check with caller scratch (acc: 6 * nbody
 * doubles, seen: ncontact bytes), so that it cannot fail on memory.
 * Returns 0, or -1 when the forces are malformed (out->ok = 0). */
int us_certificate_check_buf(const us_Structure *s, const us_Bitset *present,
                             const us_Forces *f, double tol, double *acc, unsigned char *seen,
                             us_CertCheck *out);

#endif
