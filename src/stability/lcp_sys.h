/* The LCP operator of a 2D structure, A = J M^-1 J^T (lcp_sys.c): LCP
 * index 2c is the normal of structure contact c, 2c + 1 its friction. Per
 * body, generalized coordinates (x, y, angle * L) with masses
 * (m, m, I / L^2) / m_total, forces in units of the weight W, torques /
 * (W L): the normalization of us_EqSystem. */
#ifndef US_LCP_SYS_H
#define US_LCP_SYS_H

#include "core/core.h"
#include "lcp_ops.h"

typedef struct us_LcpSys {
  const us_Structure *s;
  int nbody, ncontact;
  double *minv;           /* [3 nbody] inverse masses (normalized) */
  double *fext;           /* [3 nbody] external force (normalized), present only */
  unsigned char *present; /* [nbody] movable and in the sub-assembly */
  int *cb;                /* [2 ncontact] the bodies of a contact (-1: fixed/ground) */
  double *w;              /* [12 ncontact]: (index 2c+k, side) -> 3 wrench rows */
  int *adj_start, *adj;   /* contacts of each body */
  /* scratch of lcp_sys.c */
  double *u;              /* [3 nbody] kept zero */
  int *touched;           /* [nbody] */
  unsigned char *bmark;   /* [nbody] */
  unsigned char *cmark;   /* [ncontact] kept zero */
} us_LcpSys;

int us_lcp_sys_init(us_LcpSys *y, const us_Structure *s);
/* The cone operator: for a contact with finite mu > 0, index 2c is the
 * cone edge n + mu t and 2c + 1 the edge n - mu t (both normals of a
 * frictionless LCP: forces >= 0); other contacts as above. */
int us_lcp_sys_init_cone(us_LcpSys *y, const us_Structure *s);
void us_lcp_sys_free(us_LcpSys *y);
us_LcpOps us_lcp_sys_ops(us_LcpSys *y);
/* Per-index wrench on body side `side` of LCP index i (3 values). */
static inline const double *us_lcp_sys_w(const us_LcpSys *y, int i, int side) {
  return y->w + ((size_t)i * 2 + (size_t)side) * 3;
}
/* Net normalized wrench r = E f + F_ext on every present body; returns the
 * largest component magnitude and the body (index) where it occurs, and
 * (energy not NULL) v^T M v = sum r^T M^-1 r with v the accelerations. */
double us_lcp_sys_residual(us_LcpSys *y, const double *f, int *worst_body, double *energy);

#endif
