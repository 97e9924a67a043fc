/* Points and segments: orientation, distances, segment intersection and
 * point-in-polygon.
 *
 * Orientation signs are exact for the given doubles (no tolerance), so
 * us_segment_intersect is a predicate of the input; tolerant questions
 * ("closer than tol") are answered with distances instead. Point in
 * polygon uses the crossing rule with half-open edges, which counts each
 * crossing once even through vertices and works for non-convex polygons. */
#include "geometry.h"

#include <math.h>

double us_point_segment_dist(us_Vec2 p, us_Vec2 a, us_Vec2 b, double *t) {
  us_Vec2 d = us_v2_sub(b, a);
  double l2 = us_v2_dot(d, d);
  double s = l2 > 0 ? us_v2_dot(us_v2_sub(p, a), d) / l2 : 0.0;
  s = s < 0 ? 0 : (s > 1 ? 1 : s);
  if (t) *t = s;
  return us_v2_dist(p, us_v2_add(a, us_v2_scale(d, s)));
}

static int sign_of(double v) { return (v > 0) - (v < 0); }

/* 1 if q (known collinear with [a, b]) lies within the box of [a, b]. */
static int on_segment_box(us_Vec2 a, us_Vec2 b, us_Vec2 q) {
  return q.x >= US_MIN(a.x, b.x) && q.x <= US_MAX(a.x, b.x) && q.y >= US_MIN(a.y, b.y) &&
         q.y <= US_MAX(a.y, b.y);
}

us_SegHit us_segment_intersect(us_Vec2 a0, us_Vec2 a1, us_Vec2 b0, us_Vec2 b1, double *ta,
                               double *tb) {
  double o1 = us_orient(a0, a1, b0), o2 = us_orient(a0, a1, b1);
  double o3 = us_orient(b0, b1, a0), o4 = us_orient(b0, b1, a1);
  int s1 = sign_of(o1), s2 = sign_of(o2), s3 = sign_of(o3), s4 = sign_of(o4);
  if (s1 * s2 < 0 && s3 * s4 < 0) {
    if (ta) *ta = o3 / (o3 - o4);
    if (tb) *tb = o1 / (o1 - o2);
    return US_SEG_PROPER;
  }
  if ((s1 == 0 && on_segment_box(a0, a1, b0)) || (s2 == 0 && on_segment_box(a0, a1, b1)) ||
      (s3 == 0 && on_segment_box(b0, b1, a0)) || (s4 == 0 && on_segment_box(b0, b1, a1)))
    return US_SEG_TOUCH;
  return US_SEG_NONE;
}

double us_segment_segment_dist(us_Vec2 a0, us_Vec2 a1, us_Vec2 b0, us_Vec2 b1) {
  if (us_segment_intersect(a0, a1, b0, b1, NULL, NULL) != US_SEG_NONE) return 0.0;
  double d = us_point_segment_dist(a0, b0, b1, NULL);
  d = US_MIN(d, us_point_segment_dist(a1, b0, b1, NULL));
  d = US_MIN(d, us_point_segment_dist(b0, a0, a1, NULL));
  return US_MIN(d, us_point_segment_dist(b1, a0, a1, NULL));
}

int us_point_in_polygon(us_Vec2 p, const double *xy, int n) {
  int inside = 0;
  for (int i = 0, j = n - 1; i < n; j = i++) {
    double xi = xy[2 * i], yi = xy[2 * i + 1], xj = xy[2 * j], yj = xy[2 * j + 1];
    /* half-open rule: the edge counts if it straddles the horizontal line */
    if ((yi > p.y) != (yj > p.y)) {
      double x = xi + (p.y - yi) * (xj - xi) / (yj - yi);
      if (p.x < x) inside = !inside;
    }
  }
  return inside;
}

double us_point_boundary_dist(us_Vec2 p, const double *xy, int n, int *edge) {
  double best = INFINITY;
  int be = -1;
  for (int i = 0; i < n; i++) {
    double d =
        us_point_segment_dist(p, us_poly_vertex(xy, n, i), us_poly_vertex(xy, n, i + 1), NULL);
    if (d < best) {
      best = d;
      be = i;
    }
  }
  if (edge) *edge = be;
  return best;
}

double us_point_polygon_depth(us_Vec2 p, const double *xy, int n) {
  double d = us_point_boundary_dist(p, xy, n, NULL);
  return us_point_in_polygon(p, xy, n) ? d : -d;
}
