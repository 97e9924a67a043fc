/* Spatial geometry for unstack: 3-vectors, convex hulls of point sets,
 * convex polyhedra (us_Polyhedron, public), their mass properties, boxes
 * and rotations, and the planar convex hull both the 3D hull's faces and
 * the contact patches use. Pure functions, value types in and out, every
 * tolerance an argument (a length, normally us_geom_tol of the bodies
 * involved), as in geometry.h. */
#ifndef US_GEOMETRY3_H
#define US_GEOMETRY3_H

#include "geometry.h"

typedef struct us_Vec3 {
  double x, y, z;
} us_Vec3;

static inline us_Vec3 us_v3(double x, double y, double z) {
  us_Vec3 v = {x, y, z};
  return v;
}
/* Point i of a flat array of 3*n coordinates. */
static inline us_Vec3 us_v3_at(const double *xyz, int i) {
  return us_v3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
}
static inline us_Vec3 us_v3_add(us_Vec3 a, us_Vec3 b) { return us_v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline us_Vec3 us_v3_sub(us_Vec3 a, us_Vec3 b) { return us_v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline us_Vec3 us_v3_scale(us_Vec3 a, double k) { return us_v3(a.x * k, a.y * k, a.z * k); }
static inline double us_v3_dot(us_Vec3 a, us_Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline us_Vec3 us_v3_cross(us_Vec3 a, us_Vec3 b) {
  return us_v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double us_v3_norm(us_Vec3 a) { return sqrt(us_v3_dot(a, a)); }
static inline double us_v3_dist(us_Vec3 a, us_Vec3 b) { return us_v3_norm(us_v3_sub(a, b)); }
/* a / |a|, or (0, 0, 0) when |a| is 0. */
static inline us_Vec3 us_v3_unit(us_Vec3 a) {
  double l = us_v3_norm(a);
  return l > 0 ? us_v3_scale(a, 1.0 / l) : us_v3(0, 0, 0);
}

/* An orthonormal tangent pair (t1, t2) with t1 x t2 = n for a unit n (the
 * frame us_contact_frame gives contacts). */
void us_v3_frame(us_Vec3 n, us_Vec3 *t1, us_Vec3 *t2);

/* Axis-aligned box of 3*n coordinates: {xmin, ymin, zmin, xmax, ymax, zmax}
 * (an empty box for n < 1). */
void us_points3_bbox(const double *xyz, int n, double out[6]);
/* Diagonal of such a box (0 for n < 1; inf on overflow). */
double us_bbox3_diameter(const double bb[6]);

/* Box of a 3D body's parts (an empty box without parts) and its diagonal:
 * the body's size, which its own tolerance follows. */
void us_body_bbox3(const us_Body *b, double out[6]);
double us_body_diameter(const us_Body *b);

/* ------------------------------------------------------------ planar hull */

/* Convex hull of n planar points with a length tolerance: writes the
 * indices of the hull's vertices, counter-clockwise, to idx (room for
 * n + 1) and returns their count: 1 when all points lie within tol of the first
 * one, 2 (the extreme points) when they lie within tol of a line, else
 * >= 3. Points within tol of a hull edge's line (collinear) are left out.
 * work needs room for n indices. */
int us_hull2(const us_Vec2 *p, int n, double tol, int *idx, int *work);

/* ------------------------------------------------------------- polyhedra */

typedef enum us_HullStatus {
  US_HULL_OK = 0,
  US_HULL_FLAT,   /* fewer than 4 points off one plane (within tol) */
  US_HULL_FAIL,   /* numerical trouble (a non-simple horizon) */
  US_HULL_NOMEM,
  US_HULL_TIMEOUT /* the deadline passed (us_hull3_until) */
} us_HullStatus;

/* The convex hull of n points (3*n coordinates) with length tolerance tol
 * (points within tol of the hull of the others are dropped; facets whose
 * vertices lie within tol of a common plane are one face). On US_HULL_OK
 * *out owns new arrays (free with us_polyhedron_free) and its vertices are
 * input points, bit for bit; on failure *out is empty. */
us_HullStatus us_hull3(const double *xyz, int n, double tol, us_Polyhedron *out);
/* The same, stopped with US_HULL_TIMEOUT once us_now() passes deadline
 * (read every 1024 points; 0: no deadline). */
us_HullStatus us_hull3_until(const double *xyz, int n, double tol, double deadline,
                             us_Polyhedron *out);
void us_polyhedron_free(us_Polyhedron *p);
/* A deep copy (0, or -1 when out of memory: dst empty). */
int us_polyhedron_copy(us_Polyhedron *dst, const us_Polyhedron *src);

/* Face f: its vertex count, vertex k of it, its outward normal and d. */
static inline int us_face_size(const us_Polyhedron *p, int f) {
  return p->face_start[f + 1] - p->face_start[f];
}
static inline us_Vec3 us_face_vertex(const us_Polyhedron *p, int f, int k) {
  return us_v3_at(p->verts, p->face_vert[p->face_start[f] + k]);
}
static inline us_Vec3 us_face_normal(const us_Polyhedron *p, int f) {
  return us_v3(p->planes[4 * f], p->planes[4 * f + 1], p->planes[4 * f + 2]);
}

/* Integrals over the solid, about the point ref: volume, first moment
 * m1 = int (x - ref) dV and second moment m2 = int (x - ref)(x - ref)^T dV
 * (row-major 3x3), by the divergence theorem over the faces' fans
 * (exact for any closed polyhedron with outward faces). */
void us_polyhedron_moments(const us_Polyhedron *p, us_Vec3 ref, double *vol, double m1[3],
                           double m2[9]);
/* Range of n . x over the vertices. */
void us_polyhedron_project(const us_Polyhedron *p, us_Vec3 n, double *lo, double *hi);

/* Gap between the projections of a and b on the line of unit vector u,
 * taken in the orientation (u or -u, in *oriented) where b lies further
 * along than a: > 0 a gap, < 0 an overlap of the projections. */
double us_axis_gap(const us_Polyhedron *a, const us_Polyhedron *b, us_Vec3 u, us_Vec3 *oriented);
/* Separating-axis test of two convex polyhedra: the largest axis gap over
 * the face normals of both and the cross products of their edge
 * directions (edge pairs within 1e-9 rad of parallel skipped). For convex
 * polyhedra this is exact: > 0 is their distance along the best axis (a
 * lower bound of their distance), <= 0 minus their penetration depth (the
 * shortest translation that separates them). Stops at the first axis with
 * a gap > stop. *axis (may be NULL): the axis, oriented from a to b. */
double us_convex_separation(const us_Polyhedron *a, const us_Polyhedron *b, double stop,
                            us_Vec3 *axis);
/* The edge-pair half of that test: starting from best (the face axes'
 * result, axis holding its axis), the largest gap over the edge cross
 * products, stopping above stop. */
double us_edge_separation(const us_Polyhedron *a, const us_Polyhedron *b, double stop, double best,
                          us_Vec3 *axis);

/* -------------------------------------------------------- boxes, rotation */

/* Unit quaternion [w, x, y, z] of Euler angles in degrees, intrinsic z-y-x:
 * a turn of rz about z, then ry about the new y, then rx about the new x,
 * so that R = Rz(rz) Ry(ry) Rx(rx). */
void us_quat_from_euler(const double deg[3], double q[4]);
/* The 8 corners of a box (24 coordinates): centre + R (+-sx/2, +-sy/2,
 * +-sz/2), corner k taking the + sign on axis a when bit a of k is set; R
 * the rotation of quaternion q = [w, x, y, z] (normalized here; must not
 * be zero). */
void us_box_points(const double center[3], const double size[3], const double q[4],
                   double out[24]);

#endif
