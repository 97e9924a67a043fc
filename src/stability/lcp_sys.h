/* The LCP operator of a structure, A = J M^-1 J^T (lcp_sys.c), with the
 * dimension as a parameter: nw generalized coordinates per body (2D: x, y,
 * angle * L; 3D: x, y, z, rotation * L) and K LCP indices per contact,
 * index K c + slot. 2D (K = 2): slot 0 the normal of structure contact c,
 * 1 its friction (or, for the cone operator, the cone's two edges). 3D
 * (lcp3_sys.c, K = us_eq_gen_slots(3)): slot s is the cone generator
 * column of that slot in us_eq_generators (lp_gen.h), loaded per test, so
 * every 3D index is a normal of a frictionless LCP. Masses (m, m, I / L^2)
 * / m_total (3D: the rotational block m_total L^2 I^-1 from the inertia
 * tensor), forces in units of the weight W, torques / (W L): the
 * normalization of us_EqSystem. */
#ifndef US_LCP_SYS_H
#define US_LCP_SYS_H

#include "core/core.h"
#include "lcp_ops.h"

typedef struct us_LcpSys {
  const us_Structure *s;
  int nbody, ncontact;
  int nw;                 /* rows per body: 3 (2D) or 6 (3D) */
  int K;                  /* LCP indices per contact: index K c + slot */
  double *minv;           /* [nw nbody] inverse masses (normalized; 3D: the
                             translational three, the rotation in rinv) */
  double *rinv;           /* 3D: [9 nbody] rotational inverse inertia */
  double *fext;           /* [nw nbody] external force (normalized), present only */
  unsigned char *present; /* [nbody] movable and in the sub-assembly */
  int *cb;                /* [2 ncontact] the bodies of a contact (-1: fixed/ground) */
  double *w;              /* [2 nw K ncontact]: (index, side) -> nw wrench rows */
  unsigned char *slots;   /* [K ncontact] the slots in use of each contact */
  int *nslot;             /* [ncontact] how many */
  int *adj_start, *adj;   /* contacts of each body */
  /* scratch of lcp_sys.c */
  double *u;              /* [nw nbody] kept zero */
  int *touched;           /* [nbody] */
  unsigned char *bmark;   /* [nbody] */
  unsigned char *cmark;   /* [ncontact] kept zero */
} us_LcpSys;

/* The movable bodies' total mass (1 when there is none): masses are
 * divided by it, so gravity alone gives each free body acceleration 1. */
double us_lcp_sys_movable_mass(const us_Structure *s);
int us_lcp_sys_init(us_LcpSys *y, const us_Structure *s);
/* The cone operator: for a contact with finite mu > 0, index 2c is the
 * cone edge n + mu t and 2c + 1 the edge n - mu t (both normals of a
 * frictionless LCP: forces >= 0); other contacts as above. */
int us_lcp_sys_init_cone(us_LcpSys *y, const us_Structure *s);
/* The arrays of an operator with nw rows per body and K indices per
 * contact, the contacts' bodies (cb) filled; then the caller fills w and
 * the masses and links the adjacency (us_lcp_sys_link). 0 or -1 (OOM). */
int us_lcp_sys_alloc(us_LcpSys *y, const us_Structure *s, int nw, int K);
int us_lcp_sys_link(us_LcpSys *y);
void us_lcp_sys_free(us_LcpSys *y);
us_LcpOps us_lcp_sys_ops(us_LcpSys *y);
/* Per-index wrench on body side `side` of LCP index i (nw values). */
static inline double *us_lcp_sys_w(const us_LcpSys *y, int i, int side) {
  return y->w + ((size_t)i * 2 + (size_t)side) * (size_t)y->nw;
}
/* Net normalized wrench r = E f + F_ext on every present body; returns the
 * largest component magnitude and the body (index) where it occurs, and
 * (energy not NULL) v^T M v = sum r^T M^-1 r with v the accelerations. */
double us_lcp_sys_residual(us_LcpSys *y, const double *f, int *worst_body, double *energy);
/* The accelerations v = M^-1 (E f + F_ext) of every present body b into
 * v[nw b ..] (v holds nw nbody; others untouched): 3D Farkas rays. */
void us_lcp_sys_velocity(us_LcpSys *y, const double *f, double *v);

/* 3D (lcp3_sys.c): the operator of a 3D structure, every index a cone
 * generator (loaded per test by us_lcp3_sys_load). 0 or -1 (OOM). */
int us_lcp3_sys_init(us_LcpSys *y, const us_Structure *s);
/* The generator columns g of system e (us_eq_generators) into the
 * operator: contact e->contact[ci]'s slots and wrenches. changed[c] (per
 * structure contact) is set to 1 where they differ from before. */
struct us_EqSystem;
struct us_EqGen;
void us_lcp3_sys_load(us_LcpSys *y, const struct us_EqSystem *e, const struct us_EqGen *g,
                      unsigned char *changed);

#endif
