/* Area, orientation, centroid, polar moment and bounding box of simple
 * polygons.
 *
 * All integrals use the shoelace decomposition into triangles (origin, v_i,
 * v_{i+1}). To avoid cancellation for polygons far from the origin, the
 * coordinates are first shifted by vertex 0 (the results are translation
 * invariant or shifted back). Signed area > 0 means counter-clockwise; the
 * centroid and the polar moment are computed with the signed area and come
 * out the same for either orientation. */
#include "geometry.h"

#include <math.h>

double us_geom_tol(double size) {
  return size > 0 && isfinite(size) ? US_GEOM_TOL_REL * size : 0.0;
}

double us_poly_diameter(const double *xy, int n) {
  if (n < 1) return 0.0;
  double bb[4];
  us_poly_bbox(xy, n, bb);
  return hypot(bb[2] - bb[0], bb[3] - bb[1]);
}

double us_poly_signed_area(const double *xy, int n) {
  if (n < 3) return 0.0;
  us_Vec2 o = us_poly_vertex(xy, n, 0);
  double a2 = 0.0;
  for (int i = 1; i + 1 < n; i++)
    a2 += us_orient(o, us_poly_vertex(xy, n, i), us_poly_vertex(xy, n, i + 1));
  return 0.5 * a2;
}

int us_poly_make_ccw(double *xy, int n) {
  if (n < 3 || us_poly_signed_area(xy, n) >= 0) return 0;
  /* reverse vertices 1..n-1 so that vertex 0 keeps its index */
  for (int i = 1, j = n - 1; i < j; i++, j--) {
    double x = xy[2 * i], y = xy[2 * i + 1];
    xy[2 * i] = xy[2 * j];
    xy[2 * i + 1] = xy[2 * j + 1];
    xy[2 * j] = x;
    xy[2 * j + 1] = y;
  }
  return 1;
}

/* Vertex mean: the fallback centre of degenerate polygons. */
static us_Vec2 vertex_mean(const double *xy, int n) {
  us_Vec2 m = {0, 0};
  for (int i = 0; i < n; i++) m = us_v2_add(m, us_poly_vertex(xy, n, i));
  return n > 0 ? us_v2_scale(m, 1.0 / n) : m;
}

us_Vec2 us_poly_centroid(const double *xy, int n) {
  if (n < 3) return vertex_mean(xy, n);
  us_Vec2 o = us_poly_vertex(xy, n, 0);
  double a2 = 0.0, cx = 0.0, cy = 0.0;
  for (int i = 0; i < n; i++) {
    us_Vec2 p = us_v2_sub(us_poly_vertex(xy, n, i), o);
    us_Vec2 q = us_v2_sub(us_poly_vertex(xy, n, i + 1), o);
    double c = us_v2_cross(p, q);
    a2 += c;
    cx += (p.x + q.x) * c;
    cy += (p.y + q.y) * c;
  }
  if (a2 == 0.0) return vertex_mean(xy, n);
  return us_v2(o.x + cx / (3.0 * a2), o.y + cy / (3.0 * a2));
}

double us_poly_polar_moment(const double *xy, int n) {
  if (n < 3) return 0.0;
  us_Vec2 o = us_poly_vertex(xy, n, 0);
  double a2 = 0.0, j12 = 0.0;
  for (int i = 0; i < n; i++) {
    us_Vec2 p = us_v2_sub(us_poly_vertex(xy, n, i), o);
    us_Vec2 q = us_v2_sub(us_poly_vertex(xy, n, i + 1), o);
    double c = us_v2_cross(p, q);
    a2 += c;
    /* triangle (0, p, q): integral of x^2 + y^2 is c/12 * (p.p + p.q + q.q) */
    j12 += c * (us_v2_dot(p, p) + us_v2_dot(p, q) + us_v2_dot(q, q));
  }
  if (a2 == 0.0) return 0.0;
  double area = 0.5 * a2;
  double jo = j12 / 12.0;                            /* about vertex 0 */
  us_Vec2 c = us_v2_sub(us_poly_centroid(xy, n), o); /* relative to vertex 0 */
  double jc = jo - area * us_v2_dot(c, c);           /* parallel-axis theorem */
  return fabs(jc);
}

void us_poly_bbox(const double *xy, int n, double out[4]) {
  out[0] = out[1] = INFINITY;
  out[2] = out[3] = -INFINITY;
  for (int i = 0; i < n; i++) {
    out[0] = US_MIN(out[0], xy[2 * i]);
    out[1] = US_MIN(out[1], xy[2 * i + 1]);
    out[2] = US_MAX(out[2], xy[2 * i]);
    out[3] = US_MAX(out[3], xy[2 * i + 1]);
  }
}
