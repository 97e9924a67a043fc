/* Tests of src/geometry: areas, centroids and polar moments against hand
 * formulas (rectangles, an L shape composed of two rectangles), orientation,
 * distances, segment intersection, point in a non-convex polygon and the
 * simple-polygon test. */
#include "geometry/geometry.h"
#include "test.h"

/* Rectangle [x0, x0 + w] x [y0, y0 + h], counter-clockwise. */
static void rect(double *xy, double x0, double y0, double w, double h) {
  double v[8] = {x0, y0, x0 + w, y0, x0 + w, y0 + h, x0, y0 + h};
  memcpy(xy, v, sizeof v);
}

static void rectangle_props(void) {
  double xy[8];
  double w = 3.0, h = 0.5, x0 = -1.25, y0 = 2.0;
  rect(xy, x0, y0, w, h);
  CHECK_NEAR(us_poly_signed_area(xy, 4), w * h, 1e-12);
  us_Vec2 c = us_poly_centroid(xy, 4);
  CHECK_NEAR(c.x, x0 + w / 2, 1e-12);
  CHECK_NEAR(c.y, y0 + h / 2, 1e-12);
  /* polar moment of a rectangle about its centre: A (w^2 + h^2) / 12 */
  CHECK_NEAR(us_poly_polar_moment(xy, 4), w * h * (w * w + h * h) / 12.0, 1e-12);
}

/* Far from the origin the shifted formulas keep their accuracy. */
static void rectangle_far_away(void) {
  double xy[8];
  rect(xy, 1e7, 1e7, 2.0, 1.0);
  CHECK_NEAR(us_poly_signed_area(xy, 4), 2.0, 1e-9);
  us_Vec2 c = us_poly_centroid(xy, 4);
  CHECK_NEAR(c.x, 1e7 + 1.0, 1e-7);
  CHECK_NEAR(c.y, 1e7 + 0.5, 1e-7);
  CHECK_NEAR(us_poly_polar_moment(xy, 4), 2.0 * (4.0 + 1.0) / 12.0, 1e-6);
}

/* L shape = [0,3]x[0,1] + [0,1]x[1,3]; combine the two rectangles by hand
 * (parallel-axis theorem) and compare with the polygon formulas. */
static void l_shape_props(void) {
  double L[12] = {0, 0, 3, 0, 3, 1, 1, 1, 1, 3, 0, 3};
  double a1 = 3.0, c1x = 1.5, c1y = 0.5, j1 = a1 * (9.0 + 1.0) / 12.0;
  double a2 = 2.0, c2x = 0.5, c2y = 2.0, j2 = a2 * (1.0 + 4.0) / 12.0;
  double a = a1 + a2, cx = (a1 * c1x + a2 * c2x) / a, cy = (a1 * c1y + a2 * c2y) / a;
  double j = j1 + a1 * ((c1x - cx) * (c1x - cx) + (c1y - cy) * (c1y - cy)) + j2 +
             a2 * ((c2x - cx) * (c2x - cx) + (c2y - cy) * (c2y - cy));
  CHECK_NEAR(us_poly_signed_area(L, 6), a, 1e-12);
  us_Vec2 c = us_poly_centroid(L, 6);
  CHECK_NEAR(c.x, cx, 1e-12);
  CHECK_NEAR(c.y, cy, 1e-12);
  CHECK_NEAR(us_poly_polar_moment(L, 6), j, 1e-12);
}

static void orientation(void) {
  double cw[12] = {0, 0, 0, 3, 1, 3, 1, 1, 3, 1, 3, 0}; /* the L shape, clockwise */
  CHECK(us_poly_signed_area(cw, 6) < 0);
  double j_cw = us_poly_polar_moment(cw, 6);
  us_Vec2 c_cw = us_poly_centroid(cw, 6);
  CHECK_INT(us_poly_make_ccw(cw, 6), ==, 1);
  CHECK(us_poly_signed_area(cw, 6) > 0);
  CHECK_NEAR(cw[0], 0.0, 0);
  CHECK_NEAR(cw[1], 0.0, 0); /* vertex 0 kept */
  CHECK_NEAR(cw[2], 3.0, 0);
  CHECK_NEAR(cw[3], 0.0, 0); /* next vertex now goes along the bottom */
  CHECK_INT(us_poly_make_ccw(cw, 6), ==, 0);
  /* centroid and moment do not depend on the orientation */
  CHECK_NEAR(us_poly_polar_moment(cw, 6), j_cw, 1e-12);
  us_Vec2 c = us_poly_centroid(cw, 6);
  CHECK_NEAR(c.x, c_cw.x, 1e-12);
  CHECK_NEAR(c.y, c_cw.y, 1e-12);
}

static void distances(void) {
  double t;
  CHECK_NEAR(us_point_segment_dist(us_v2(1, 2), us_v2(0, 0), us_v2(2, 0), &t), 2.0, 1e-15);
  CHECK_NEAR(t, 0.5, 1e-15);
  CHECK_NEAR(us_point_segment_dist(us_v2(-3, 4), us_v2(0, 0), us_v2(2, 0), &t), 5.0, 1e-15);
  CHECK_NEAR(t, 0.0, 0);
  CHECK_NEAR(us_point_segment_dist(us_v2(5, 4), us_v2(0, 0), us_v2(2, 0), &t), 5.0, 1e-15);
  CHECK_NEAR(t, 1.0, 0);
  CHECK_NEAR(us_segment_segment_dist(us_v2(0, 0), us_v2(1, 0), us_v2(0, 1), us_v2(1, 2)), 1.0,
             1e-15);
  CHECK_NEAR(us_segment_segment_dist(us_v2(0, 0), us_v2(2, 2), us_v2(0, 2), us_v2(2, 0)), 0.0, 0);
}

static void segment_intersection(void) {
  double ta, tb;
  CHECK(us_segment_intersect(us_v2(0, 0), us_v2(4, 0), us_v2(1, -1), us_v2(1, 3), &ta, &tb) ==
        US_SEG_PROPER);
  CHECK_NEAR(ta, 0.25, 1e-15);
  CHECK_NEAR(tb, 0.25, 1e-15);
  /* endpoint on the other segment, collinear overlap, disjoint, parallel */
  CHECK(us_segment_intersect(us_v2(0, 0), us_v2(4, 0), us_v2(2, 0), us_v2(2, 3), NULL, NULL) ==
        US_SEG_TOUCH);
  CHECK(us_segment_intersect(us_v2(0, 0), us_v2(4, 0), us_v2(3, 0), us_v2(6, 0), NULL, NULL) ==
        US_SEG_TOUCH);
  CHECK(us_segment_intersect(us_v2(0, 0), us_v2(4, 0), us_v2(5, 0), us_v2(6, 0), NULL, NULL) ==
        US_SEG_NONE);
  CHECK(us_segment_intersect(us_v2(0, 0), us_v2(4, 0), us_v2(0, 1), us_v2(4, 1), NULL, NULL) ==
        US_SEG_NONE);
  CHECK(us_segment_intersect(us_v2(0, 0), us_v2(4, 0), us_v2(5, -1), us_v2(5, 1), NULL, NULL) ==
        US_SEG_NONE);
}

/* A U shape (non-convex): the notch is outside, the arms are inside; rays
 * from some test points pass exactly through vertices. */
static void point_in_nonconvex(void) {
  double U[16] = {0, 0, 3, 0, 3, 3, 2, 3, 2, 1, 1, 1, 1, 3, 0, 3};
  CHECK_INT(us_point_in_polygon(us_v2(1.5, 2), U, 8), ==, 0);   /* notch */
  CHECK_INT(us_point_in_polygon(us_v2(0.5, 2), U, 8), ==, 1);   /* left arm */
  CHECK_INT(us_point_in_polygon(us_v2(2.5, 2), U, 8), ==, 1);   /* right arm */
  CHECK_INT(us_point_in_polygon(us_v2(1.5, 0.5), U, 8), ==, 1); /* base */
  CHECK_INT(us_point_in_polygon(us_v2(0.5, 1), U, 8), ==, 1);   /* ray through two vertices */
  CHECK_INT(us_point_in_polygon(us_v2(-1, 3), U, 8), ==, 0);    /* ray along the top */
  CHECK_INT(us_point_in_polygon(us_v2(4, 1), U, 8), ==, 0);
  CHECK_NEAR(us_point_polygon_depth(us_v2(0.5, 2), U, 8), 0.5, 1e-15);
  CHECK_NEAR(us_point_polygon_depth(us_v2(1.5, 2), U, 8), -0.5, 1e-15);
  int e = -1;
  CHECK_NEAR(us_point_boundary_dist(us_v2(1.5, 1.25), U, 8, &e), 0.25, 1e-15);
  CHECK_INT(e, ==, 4); /* the notch floor (2,1)-(1,1) */
}

static void simple_polygons(void) {
  int i = -1, j = -1;
  double bow[8] = {0, 0, 1, 1, 1, 0, 0, 1};
  CHECK(us_poly_check_simple(bow, 4, 1e-9, &i, &j) == US_POLY_EDGES_CROSS);
  CHECK_INT(i, ==, 0);
  CHECK_INT(j, ==, 2);
  double U[16] = {0, 0, 3, 0, 3, 3, 2, 3, 2, 1, 1, 1, 1, 3, 0, 3};
  CHECK(us_poly_check_simple(U, 8, 1e-9, &i, &j) == US_POLY_SIMPLE);
  double rep[10] = {0, 0, 2, 0, 1, 1, 2, 2, 1, 1}; /* vertex 2 == vertex 4 */
  CHECK(us_poly_check_simple(rep, 5, 1e-9, &i, &j) == US_POLY_REPEATED_VERTEX);
  CHECK_INT(i, ==, 2);
  CHECK_INT(j, ==, 4);
  /* edge 3 runs back along edge 2; its end also touches edge 1, so either
   * defect may be reported first */
  double spike[10] = {0, 0, 2, 0, 2, 1, 3, 1, 0, 1};
  us_PolyDefect d = us_poly_check_simple(spike, 5, 1e-9, &i, &j);
  CHECK(d == US_POLY_EDGES_FOLD || d == US_POLY_EDGES_CROSS);
  double flat[6] = {0, 0, 2, 0, 1, 0}; /* a triangle folded flat */
  CHECK(us_poly_check_simple(flat, 3, 1e-9, &i, &j) == US_POLY_EDGES_FOLD);
  /* two non-adjacent edges touching at a point (an hourglass pinch) */
  double pinch[12] = {0, 0, 2, 0, 1, 1, 2, 2, 0, 2, 1, 1.0 + 1e-12};
  CHECK(us_poly_check_simple(pinch, 6, 1e-9, &i, &j) != US_POLY_SIMPLE);
  /* the same pinch opened wider than the tolerance is simple */
  pinch[11] = 1.0 + 1e-3;
  pinch[5] = 1.0 - 1e-3;
  CHECK(us_poly_check_simple(pinch, 6, 1e-9, &i, &j) == US_POLY_SIMPLE);
}

/* A 400-gon star (non-convex) is simple; moving one vertex across the
 * polygon makes it self-intersecting. */
static void simple_large(void) {
  enum { N = 400 };
  double xy[2 * N];
  for (int k = 0; k < N; k++) {
    double a = 2.0 * 3.14159265358979323846 * k / N, r = (k % 2) ? 1.0 : 0.8;
    xy[2 * k] = r * cos(a);
    xy[2 * k + 1] = r * sin(a);
  }
  int i, j;
  CHECK(us_poly_check_simple(xy, N, 1e-9, &i, &j) == US_POLY_SIMPLE);
  CHECK(us_poly_signed_area(xy, N) > 0);
  xy[2 * 10] = -0.95;
  xy[2 * 10 + 1] = 0.01;
  CHECK(us_poly_check_simple(xy, N, 1e-9, &i, &j) == US_POLY_EDGES_CROSS);
  CHECK(i == 9 || i == 10 || j == 9 || j == 10);
}

static void tolerance_scales(void) {
  CHECK_NEAR(us_geom_tol(100.0), 100.0 * US_GEOM_TOL_REL, 1e-18);
  /* no absolute floor: a body 1e-9 across gets 1e-15 */
  CHECK_NEAR(us_geom_tol(1e-9), 1e-9 * US_GEOM_TOL_REL, 1e-30);
  CHECK(us_geom_tol(1e-300) > 0);
  CHECK(us_geom_tol(0.0) == 0 && us_geom_tol(INFINITY) == 0);
}

US_TEST_MAIN(T(rectangle_props), T(rectangle_far_away), T(l_shape_props), T(orientation),
             T(distances), T(segment_intersection), T(point_in_nonconvex), T(simple_polygons),
             T(simple_large), T(tolerance_scales))
