/* The equilibrium system of one sub-assembly (equilibrium.c).
 *
 * Units: the system is normalized so that nothing in it depends on the
 * size of the user's numbers. Body i's gravity row is -(m_i / M) g^ with
 * M the total movable mass and g^ the unit gravity direction, so forces
 * are in units of the total weight W = M |g| and every entry of the
 * right-hand side is at most 1 in magnitude; torques are divided by the
 * structure's scale L. A backend returns forces in these units and the
 * front end multiplies them by W (newtons).
 *
 * Sign conventions: for active contact c with normal n from a into b and
 * force components f = (f_n, f_t1[, f_t2]), the force on b is
 * F = f_n n + f_t1 t1 (+ f_t2 t2) at point p, and a receives -F at p.
 * Cones: f_n >= 0, |f_t| <= mu f_n (2D exact; 3D: Euclidean norm); mu =
 * INFINITY is the half-space f_n >= 0 with f_t free.
 */
#ifndef US_STABILITY_EQUILIBRIUM_H
#define US_STABILITY_EQUILIBRIUM_H

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
  double *mu;          /* [ncontact], INFINITY allowed */
  double force_scale;  /* W: multiply forces by this to get newtons */
  double mass_total;   /* M: body i's gravity row is -(m_i / M) gdir */
  double gdir[3];      /* unit gravity direction (0 without gravity) */
  double length_scale; /* torque rows are divided by this */
  const struct us_ConeSet *cones; /* 3D: the LP backends' polygonal cones
                                     (lp_gen.h); NULL: the inner ones */
  int bilateral;       /* 1: bilateral joints (a contact's whole force is
                          free in sign: +-n, +-t generators); set by the
                          caller after us_eq_init, kept by the builds */
  int cap_body, cap_contact;
  int *inc_start, *inc; /* the structure's contacts by body (us_eq_build's
                           own, built at its first call) */
} us_EqSystem;

int us_eq_init(us_EqSystem *e, const us_Structure *s);
void us_eq_free(us_EqSystem *e);
/* Build the system of sub-assembly `present`. 0 or -1 on OOM. */
int us_eq_build(us_EqSystem *e, const us_Bitset *present);
/* y = A x (y has nbody*nw entries, x ncontact*dim). */
void us_eq_mult(const us_EqSystem *e, const double *x, double *y);

/* A region R of a sub-assembly for the local tests (local.c): its bodies
 * (present and movable), a mark per body, the contacts of every body
 * (inc[inc_start[i] .. inc_start[i + 1]) lists each contact touching body
 * i) and the treatment of the contacts between R and the rest. */
typedef struct us_EqRegion {
  const int *reg;                /* [nreg] bodies of R */
  int nreg;
  const unsigned char *in_r;     /* [s->nbody] 1 on R */
  const int *inc_start, *inc;    /* body -> contacts */
  int fixed_boundary;            /* 1: boundary forces fixed (the "stable"
                                    test); 0: the rest is a support (the
                                    "unstable" test) */
} us_EqRegion;

/* The system of region R inside sub-assembly `present`: rows R's bodies;
 * columns the active contacts with a side in R. With fixed_boundary, a
 * contact between R and a present movable body outside R is no column:
 * its force, fbase[c * dim ...] (normalized), moves to the right-hand
 * side. Without, the outside side of such a contact is held like the
 * ground. Cost O(|R| + contacts of R). 0 or -1 on OOM. */
int us_eq_build_region(us_EqSystem *e, const us_Bitset *present, const us_EqRegion *g,
                       const double *fbase);

/* Is contact c active in `present` (both sides present, ground and fixed
 * bodies always are; at least one side movable)? */
int us_contact_active(const us_Structure *s, const us_Bitset *present, int c);

#endif
