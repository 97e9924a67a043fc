/* Separating-axis test of two convex polyhedra.
 *
 * Two convex polyhedra are disjoint iff their projections on some line are
 * disjoint, and it suffices to try the face normals of both and the cross
 * products of one edge direction of each (the normals of the faces of
 * their Minkowski difference). So the largest projection gap over those
 * axes is positive exactly when they are apart, and when they overlap its
 * negative is the penetration depth: the Minkowski difference's face
 * nearest the origin is among those axes. Parallel edge directions are
 * dropped (their cross product has no direction; the face normals cover
 * them), so two blocks with parallel edges cost 3 + 3 + 9 axes. Face
 * normals are tried first and the test stops at the first gap above the
 * caller's threshold, so separated pairs are usually decided by a face. */
#include "geometry3.h"

#include <math.h>

#define EDGE_PARALLEL_SIN 1e-9

double us_axis_gap(const us_Polyhedron *a, const us_Polyhedron *b, us_Vec3 u, us_Vec3 *oriented) {
  double alo, ahi, blo, bhi;
  us_polyhedron_project(a, u, &alo, &ahi);
  us_polyhedron_project(b, u, &blo, &bhi);
  double plus = blo - ahi, minus = alo - bhi;
  *oriented = plus >= minus ? u : us_v3_scale(u, -1.0);
  return US_MAX(plus, minus);
}

/* Keep u as the best axis if its gap beats *best. */
static void try_axis(const us_Polyhedron *a, const us_Polyhedron *b, us_Vec3 u, double *best,
                     us_Vec3 *axis) {
  us_Vec3 o;
  double g = us_axis_gap(a, b, u, &o);
  if (g > *best) *best = g, *axis = o;
}

static us_Vec3 edge_dir(const us_Polyhedron *p, int e) {
  return us_v3_unit(us_v3_sub(us_v3_at(p->verts, p->edges[2 * e + 1]), us_v3_at(p->verts, p->edges[2 * e])));
}

/* The distinct edge directions of p (parallel ones once) in dir[], at most
 * MAX_DIRS; beyond that every edge's (correct, only slower). */
#define MAX_DIRS 96
static int edge_dirs(const us_Polyhedron *p, us_Vec3 *dir) {
  int n = 0;
  for (int e = 0; e < p->nedge && n < MAX_DIRS; e++) {
    us_Vec3 d = edge_dir(p, e);
    int k = 0;
    while (k < n && us_v3_norm(us_v3_cross(d, dir[k])) > EDGE_PARALLEL_SIN) k++;
    if (k == n) dir[n++] = d;
  }
  return n;
}

/* Direction k of p: from the list, or edge k's beyond it. */
static us_Vec3 dir_at(const us_Polyhedron *p, const us_Vec3 *dir, int n, int k) {
  return n < MAX_DIRS ? dir[k] : edge_dir(p, k);
}

static double face_axes(const us_Polyhedron *a, const us_Polyhedron *b, const us_Polyhedron *owner,
                        double stop, double best, us_Vec3 *axis) {
  for (int f = 0; f < owner->nface && best <= stop; f++) try_axis(a, b, us_face_normal(owner, f), &best, axis);
  return best;
}

double us_convex_separation(const us_Polyhedron *a, const us_Polyhedron *b, double stop,
                            us_Vec3 *axis) {
  us_Vec3 ax = us_v3(0, 0, 1);
  double best = face_axes(a, b, a, stop, -INFINITY, &ax);
  best = face_axes(a, b, b, stop, best, &ax);
  best = us_edge_separation(a, b, stop, best, &ax);
  if (axis) *axis = ax;
  return best;
}

double us_edge_separation(const us_Polyhedron *a, const us_Polyhedron *b, double stop, double best,
                          us_Vec3 *axis) {
  us_Vec3 ax = *axis, da[MAX_DIRS], db[MAX_DIRS];
  int na = best <= stop ? edge_dirs(a, da) : 0, nb = best <= stop ? edge_dirs(b, db) : 0;
  int ma = na < MAX_DIRS ? na : a->nedge, mb = nb < MAX_DIRS ? nb : b->nedge;
  for (int e = 0; e < ma && best <= stop; e++)
    for (int k = 0; k < mb && best <= stop; k++) {
      us_Vec3 c = us_v3_cross(dir_at(a, da, na, e), dir_at(b, db, nb, k));
      if (us_v3_norm(c) > EDGE_PARALLEL_SIN) try_axis(a, b, us_v3_unit(c), &best, &ax);
    }
  *axis = ax;
  return best;
}
