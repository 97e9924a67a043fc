/* Convex polyhedra and the small pieces of spatial geometry around them:
 * tangent frames, bounding boxes, the planar convex hull, mass integrals,
 * rotations and boxes.
 *
 * Mass integrals (us_polyhedron_moments): by the divergence theorem the
 * integrals of 1, x and x x^T over the solid are sums over the boundary;
 * with each face split into a fan of triangles (v0, vi, vi+1) they are
 * sums over the tetrahedra (ref, v0, vi, vi+1), signed by the orientation
 * of the triangle (outward counter-clockwise faces give positive volume
 * for every ref, inside or not). For a tetrahedron with edge vectors a, b,
 * c from ref and D = a . (b x c): volume D / 6, first moment
 * D / 24 (a + b + c), second moment D / 120 (a a^T + b b^T + c c^T +
 * s s^T) with s = a + b + c. These are exact polynomial identities, so a
 * box, a rotated box or any convex polyhedron gets its closed-form values
 * up to rounding; ref near the body keeps the rounding small.
 *
 * Planar hull (us_hull2): Andrew's monotone chain on points sorted by
 * (x, y), with a tolerance: a point within tol of the previous hull point
 * is a duplicate, and a middle point within tol of the line through its
 * neighbours (cross product <= tol * chord) is popped, so near-collinear
 * points never become vertices. */
#include "geometry3.h"

#include <math.h>
#include <string.h>

void us_v3_frame(us_Vec3 n, us_Vec3 *t1, us_Vec3 *t2) {
  /* t1 orthogonal to n from its smallest component, t2 = n x t1 */
  double an[3] = {fabs(n.x), fabs(n.y), fabs(n.z)};
  int k = an[0] < an[1] ? (an[0] < an[2] ? 0 : 2) : (an[1] < an[2] ? 1 : 2);
  us_Vec3 a = us_v3(k == 0, k == 1, k == 2);
  *t1 = us_v3_unit(us_v3_cross(a, n));
  *t2 = us_v3_cross(n, *t1);
}

void us_points3_bbox(const double *xyz, int n, double out[6]) {
  for (int d = 0; d < 3; d++) out[d] = INFINITY, out[d + 3] = -INFINITY;
  for (int i = 0; i < n; i++)
    for (int d = 0; d < 3; d++) {
      out[d] = US_MIN(out[d], xyz[3 * i + d]);
      out[d + 3] = US_MAX(out[d + 3], xyz[3 * i + d]);
    }
}

double us_bbox3_diameter(const double bb[6]) {
  if (!(bb[0] <= bb[3])) return 0.0;
  return hypot(hypot(bb[3] - bb[0], bb[4] - bb[1]), bb[5] - bb[2]);
}

void us_body_bbox3(const us_Body *b, double out[6]) {
  for (int d = 0; d < 3; d++) out[d] = INFINITY, out[d + 3] = -INFINITY;
  for (int k = 0; k < b->npart; k++) {
    double bb[6];
    us_points3_bbox(b->parts[k].verts, b->parts[k].nvert, bb);
    for (int d = 0; d < 3; d++) out[d] = US_MIN(out[d], bb[d]), out[d + 3] = US_MAX(out[d + 3], bb[d + 3]);
  }
}

double us_body_diameter(const us_Body *b) {
  double bb[6];
  us_body_bbox3(b, bb);
  return us_bbox3_diameter(bb);
}

/* ------------------------------------------------------------ planar hull */

static int before(const us_Vec2 *p, int a, int b) {
  if (p[a].x != p[b].x) return p[a].x < p[b].x;
  if (p[a].y != p[b].y) return p[a].y < p[b].y;
  return a < b;
}

/* Bottom-up merge sort of ord[0..n) by (x, y, index); buf has room for n. */
static void sort_points(const us_Vec2 *p, int *ord, int *buf, int n) {
  for (int w = 1; w < n; w *= 2) {
    for (int lo = 0; lo < n; lo += 2 * w) {
      int mid = US_MIN(lo + w, n), hi = US_MIN(lo + 2 * w, n), i = lo, j = mid, k = lo;
      while (i < mid || j < hi) buf[k++] = (j >= hi || (i < mid && before(p, ord[i], ord[j]))) ? ord[i++] : ord[j++];
    }
    memcpy(ord, buf, (size_t)n * sizeof *ord);
  }
}

/* Push point c onto the chain h[0..*m) (one direction of the hull). */
static void chain_push(const us_Vec2 *p, int *h, int *m, int floor, int c, double tol) {
  if (*m > floor && us_v2_dist(p[h[*m - 1]], p[c]) <= tol) return;
  while (*m >= floor + 2) {
    us_Vec2 o = p[h[*m - 2]], a = p[h[*m - 1]];
    if (us_orient(o, a, p[c]) > tol * us_v2_dist(o, p[c])) break;
    (*m)--;
  }
  h[(*m)++] = c;
}

int us_hull2(const us_Vec2 *p, int n, double tol, int *idx, int *work) {
  if (n <= 0) return 0;
  int *ord = idx;
  for (int i = 0; i < n; i++) ord[i] = i;
  sort_points(p, ord, work, n);
  memcpy(work, ord, (size_t)n * sizeof *work); /* work: sorted order */
  int far = 0;
  for (int i = 1; i < n; i++) far |= us_v2_dist(p[work[0]], p[work[i]]) > tol;
  if (!far) return idx[0] = work[0], 1;
  int m = 0;
  for (int i = 0; i < n; i++) chain_push(p, idx, &m, 0, work[i], tol);
  int lower = m;
  for (int i = n - 2; i >= 0; i--) chain_push(p, idx, &m, lower - 1, work[i], tol);
  if (m > 1 && idx[m - 1] == idx[0]) m--;
  return m;
}

/* ------------------------------------------------------------- polyhedra */

void us_polyhedron_free(us_Polyhedron *p) {
  if (!p) return;
  us_free(p->verts);
  us_free(p->face_start);
  us_free(p->face_vert);
  us_free(p->planes);
  us_free(p->edges);
  memset(p, 0, sizeof *p);
}

static void *dup_array(const void *src, size_t bytes) {
  void *d = us_malloc(bytes ? bytes : 1);
  if (d && bytes) memcpy(d, src, bytes);
  return d;
}

int us_polyhedron_copy(us_Polyhedron *dst, const us_Polyhedron *src) {
  memset(dst, 0, sizeof *dst);
  *dst = *src;
  int nf = src->nface, nfv = nf > 0 ? src->face_start[nf] : 0;
  dst->verts = dup_array(src->verts, (size_t)src->nvert * 3 * sizeof(double));
  dst->face_start = nf > 0 ? dup_array(src->face_start, (size_t)(nf + 1) * sizeof(int)) : NULL;
  dst->face_vert = nf > 0 ? dup_array(src->face_vert, (size_t)nfv * sizeof(int)) : NULL;
  dst->planes = nf > 0 ? dup_array(src->planes, (size_t)nf * 4 * sizeof(double)) : NULL;
  dst->edges = src->nedge > 0 ? dup_array(src->edges, (size_t)src->nedge * 2 * sizeof(int)) : NULL;
  if (!dst->verts || (nf > 0 && (!dst->face_start || !dst->face_vert || !dst->planes)) ||
      (src->nedge > 0 && !dst->edges)) {
    us_polyhedron_free(dst);
    return -1;
  }
  return 0;
}

/* Add the tetrahedron (ref, ref + a, ref + b, ref + c) to the integrals. */
static void add_tet(us_Vec3 a, us_Vec3 b, us_Vec3 c, double *vol, double m1[3], double m2[9]) {
  double det = us_v3_dot(a, us_v3_cross(b, c));
  us_Vec3 s = us_v3_add(us_v3_add(a, b), c);
  double va[3] = {a.x, a.y, a.z}, vb[3] = {b.x, b.y, b.z}, vc[3] = {c.x, c.y, c.z},
         vs[3] = {s.x, s.y, s.z};
  *vol += det / 6.0;
  for (int i = 0; i < 3; i++) {
    m1[i] += det / 24.0 * vs[i];
    for (int j = 0; j < 3; j++)
      m2[3 * i + j] += det / 120.0 * (va[i] * va[j] + vb[i] * vb[j] + vc[i] * vc[j] + vs[i] * vs[j]);
  }
}

void us_polyhedron_moments(const us_Polyhedron *p, us_Vec3 ref, double *vol, double m1[3],
                           double m2[9]) {
  *vol = 0.0;
  memset(m1, 0, 3 * sizeof *m1);
  memset(m2, 0, 9 * sizeof *m2);
  for (int f = 0; f < p->nface; f++) {
    us_Vec3 a = us_v3_sub(us_face_vertex(p, f, 0), ref);
    for (int k = 1; k + 1 < us_face_size(p, f); k++)
      add_tet(a, us_v3_sub(us_face_vertex(p, f, k), ref), us_v3_sub(us_face_vertex(p, f, k + 1), ref),
              vol, m1, m2);
  }
}

void us_polyhedron_project(const us_Polyhedron *p, us_Vec3 n, double *lo, double *hi) {
  *lo = INFINITY;
  *hi = -INFINITY;
  for (int i = 0; i < p->nvert; i++) {
    double d = us_v3_dot(n, us_v3_at(p->verts, i));
    *lo = US_MIN(*lo, d);
    *hi = US_MAX(*hi, d);
  }
}

/* -------------------------------------------------------- boxes, rotation */

/* Hamilton product r = a b of quaternions [w, x, y, z]. */
static void quat_mul(const double a[4], const double b[4], double r[4]) {
  double w = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
  double x = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
  double y = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
  double z = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
  r[0] = w, r[1] = x, r[2] = y, r[3] = z;
}

void us_quat_from_euler(const double deg[3], double q[4]) {
  const double rad = 3.14159265358979323846 / 360.0; /* half angles */
  double qx[4] = {cos(deg[0] * rad), sin(deg[0] * rad), 0, 0};
  double qy[4] = {cos(deg[1] * rad), 0, sin(deg[1] * rad), 0};
  double qz[4] = {cos(deg[2] * rad), 0, 0, sin(deg[2] * rad)};
  double t[4];
  quat_mul(qz, qy, t);
  quat_mul(t, qx, q);
}

/* Row-major rotation matrix of a quaternion (normalized here). */
static void quat_matrix(const double q[4], double r[9]) {
  double l = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  double w = q[0] / l, x = q[1] / l, y = q[2] / l, z = q[3] / l;
  r[0] = 1 - 2 * (y * y + z * z), r[1] = 2 * (x * y - w * z), r[2] = 2 * (x * z + w * y);
  r[3] = 2 * (x * y + w * z), r[4] = 1 - 2 * (x * x + z * z), r[5] = 2 * (y * z - w * x);
  r[6] = 2 * (x * z - w * y), r[7] = 2 * (y * z + w * x), r[8] = 1 - 2 * (x * x + y * y);
}

void us_box_points(const double center[3], const double size[3], const double q[4],
                   double out[24]) {
  double r[9];
  quat_matrix(q, r);
  for (int k = 0; k < 8; k++) {
    double h[3];
    for (int a = 0; a < 3; a++) h[a] = ((k >> a) & 1 ? 0.5 : -0.5) * size[a];
    for (int i = 0; i < 3; i++)
      out[3 * k + i] = center[i] + (r[3 * i] * h[0] + r[3 * i + 1] * h[1] + r[3 * i + 2] * h[2]);
  }
}
