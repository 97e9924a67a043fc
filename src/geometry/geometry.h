/* Planar geometry for unstack: pure functions on points, segments and simple
 * polygons (convex or not), with value types in and out and no global state.
 *
 * Polygons are flat arrays xy[2*n] (x0, y0, x1, y1, ...), closed implicitly
 * (edge i joins vertex i to vertex (i+1) % n). Counter-clockwise polygons
 * have positive signed area; the outward normal of a CCW edge with direction
 * (dx, dy) is (dy, -dx) / |d|. Every comparison that needs a tolerance takes
 * it as an argument: a length, normally us_geom_tol(size) of the bodies
 * involved (a pair's own size), so that results do not depend on the units
 * nor on anything far away. */
#ifndef US_GEOMETRY_H
#define US_GEOMETRY_H

#include "core/core.h"

#include <math.h>

/* Default length tolerance: relative to the size (bounding-box diagonal)
 * of the bodies involved, with no absolute floor, so that a structure and
 * its copy scaled by any power of ten get the same answers. */
#define US_GEOM_TOL_REL 1e-6

typedef struct us_Vec2 {
  double x, y;
} us_Vec2;

static inline us_Vec2 us_v2(double x, double y) {
  us_Vec2 v = {x, y};
  return v;
}
static inline us_Vec2 us_v2_sub(us_Vec2 a, us_Vec2 b) { return us_v2(a.x - b.x, a.y - b.y); }
static inline us_Vec2 us_v2_add(us_Vec2 a, us_Vec2 b) { return us_v2(a.x + b.x, a.y + b.y); }
static inline us_Vec2 us_v2_scale(us_Vec2 a, double k) { return us_v2(a.x * k, a.y * k); }
static inline double us_v2_dot(us_Vec2 a, us_Vec2 b) { return a.x * b.x + a.y * b.y; }
static inline double us_v2_cross(us_Vec2 a, us_Vec2 b) { return a.x * b.y - a.y * b.x; }
/* sqrt of the sum of squares rather than hypot: several times faster, and
 * coordinates of real structures are far from overflowing when squared.
 * These small helpers are inline because the libraries are built as
 * position-independent code, where calls to global functions are not
 * inlined even within one file. */
static inline double us_v2_norm(us_Vec2 a) { return sqrt(a.x * a.x + a.y * a.y); }
static inline double us_v2_dist(us_Vec2 a, us_Vec2 b) { return us_v2_norm(us_v2_sub(a, b)); }
/* Twice the signed area of triangle (o, a, b): > 0 when o, a, b turn left. */
static inline double us_orient(us_Vec2 o, us_Vec2 a, us_Vec2 b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}
/* Vertex i of a flat polygon array (i taken modulo n). Callers step one
 * or two past either end, which a compare wraps without the two integer
 * divisions of the general case (this is the innermost call of contact
 * detection). */
static inline us_Vec2 us_poly_vertex(const double *xy, int n, int i) {
  int k = i >= 0 && i < n ? i : i >= n && i < 2 * n ? i - n : i < 0 && i >= -n ? i + n
                                                           : ((i % n) + n) % n;
  return us_v2(xy[2 * k], xy[2 * k + 1]);
}

/* The default tolerance for a body (or pair) of the given size: size *
 * US_GEOM_TOL_REL; 0 when size is not positive and finite. */
double us_geom_tol(double size);
/* Bounding-box diagonal of a polygon (0 for n < 1; may be inf on overflow). */
double us_poly_diameter(const double *xy, int n);

/* Signed area (> 0 counter-clockwise). n >= 3 for a meaningful value. */
double us_poly_signed_area(const double *xy, int n);
/* Reverse the vertex order in place if clockwise; returns 1 if reversed.
 * Vertex 0 stays vertex 0. */
int us_poly_make_ccw(double *xy, int n);
/* Area centroid (either orientation); the vertex mean if the area is 0. */
us_Vec2 us_poly_centroid(const double *xy, int n);
/* Polar moment of inertia about the centroid for density 1 (>= 0, either
 * orientation): integral of |r - c|^2 dA. */
double us_poly_polar_moment(const double *xy, int n);
/* Axis-aligned bounding box: out = {xmin, ymin, xmax, ymax}. */
void us_poly_bbox(const double *xy, int n, double out[4]);

/* Distance from p to segment [a, b]; *t (if not NULL) gets the parameter
 * of the closest point in [0, 1]. */
double us_point_segment_dist(us_Vec2 p, us_Vec2 a, us_Vec2 b, double *t);
/* Smallest distance between two segments. */
double us_segment_segment_dist(us_Vec2 a0, us_Vec2 a1, us_Vec2 b0, us_Vec2 b1);

/* Segment intersection with exact sign tests (no tolerance):
 * US_SEG_PROPER when the segments cross at one point interior to both,
 * US_SEG_TOUCH when they share points otherwise (an endpoint on the other
 * segment, or collinear overlap), US_SEG_NONE when disjoint. On PROPER,
 * *ta and *tb (if not NULL) get the crossing parameters along a and b. */
typedef enum us_SegHit { US_SEG_NONE = 0, US_SEG_PROPER, US_SEG_TOUCH } us_SegHit;
us_SegHit us_segment_intersect(us_Vec2 a0, us_Vec2 a1, us_Vec2 b0, us_Vec2 b1, double *ta,
                               double *tb);

/* Point in polygon by the crossing rule (any simple polygon, either
 * orientation): 1 inside, 0 outside; points on the boundary may go either
 * way, so callers that care use us_point_polygon_depth with a tolerance. */
int us_point_in_polygon(us_Vec2 p, const double *xy, int n);
/* Distance from p to the polygon's boundary, and the closest edge. */
double us_point_boundary_dist(us_Vec2 p, const double *xy, int n, int *edge);
/* Signed depth: + distance to the boundary when inside, - when outside. */
double us_point_polygon_depth(us_Vec2 p, const double *xy, int n);

/* Simple-polygon test with a length tolerance: no two vertices within tol,
 * adjacent edges do not fold back onto each other, non-adjacent edges stay
 * more than tol apart. Edges are swept in order of their left end, so
 * typical polygons of hundreds of vertices cost far less than n^2 tests. */
typedef enum us_PolyDefect {
  US_POLY_SIMPLE = 0,
  US_POLY_REPEATED_VERTEX, /* vertices *i and *j coincide */
  US_POLY_EDGES_CROSS,     /* edges *i and *j cross or touch */
  US_POLY_EDGES_FOLD,      /* adjacent edges *i and *j overlap (a spike) */
  US_POLY_NOMEM
} us_PolyDefect;
us_PolyDefect us_poly_check_simple(const double *xy, int n, double tol, int *i, int *j);

/* Edge index of one polygon (edgegrid.c): the edges whose bounding boxes,
 * padded by `pad`, meet a query box, and point in polygon, at a cost that
 * follows the edges near the query instead of all n. Polygons of at most
 * US_EDGE_GRID_MIN edges are scanned whole. The polygon array must outlive
 * the index. Not thread-safe (queries write the result buffer). */
#define US_EDGE_GRID_MIN 32
typedef struct us_EdgeGrid {
  const double *xy;
  int n;
  double pad;
  double lo[2], h[2]; /* grid origin and cell sizes */
  int nx, ny;
  int *start, *items; /* cell c lists items[start[c] .. start[c+1]); NULL: no grid */
  int *stamp, qid;    /* per-edge mark of the last query that took it */
  int *out, nout;     /* result of the last query, increasing edge indices */
  int small[US_EDGE_GRID_MIN]; /* out for small polygons (no allocation) */
} us_EdgeGrid;
/* 0, or -1 when out of memory (nothing to free then). */
int us_edge_grid_init(us_EdgeGrid *g, const double *xy, int n, double pad);
void us_edge_grid_free(us_EdgeGrid *g);
/* Edges whose padded boxes meet box {xmin, ymin, xmax, ymax}: their count,
 * indices in g->out, increasing. */
int us_edge_grid_query(us_EdgeGrid *g, const double box[4]);
/* Point in polygon for a point not within pad of the boundary (1 inside). */
int us_edge_grid_inside(us_EdgeGrid *g, us_Vec2 q);

#endif
