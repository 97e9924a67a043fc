/* Broad phase of contact detection: sort and sweep over axis-aligned boxes,
 * one design for both dimensions (boxes have dim axes; 3D bodies are boxed
 * over all their parts).
 *
 * Every polygon body gets its box inflated by its own tolerance (at least
 * the tolerance of any pair it belongs to, which is the smaller of the two
 * bodies' own). The boxes are sorted by
 * their low end along the axis on which the box centres spread most (x for
 * a wide wall, y for a tall column), ties broken by body index so the order
 * is deterministic; a sweep then compares each box only with the following
 * boxes that start before it ends, and keeps the pairs that also overlap on
 * the other axis. Pairs of two fixed bodies are dropped (no contact between
 * them matters). The pair list is finally sorted by (i, j).
 *
 * Boxes of long thin bodies lying at an angle (the voussoirs of an arch of
 * many thin blocks) overlap the boxes of thousands of neighbours they are
 * nowhere near. So a pair whose boxes overlap is kept only if no edge
 * normal of either polygon separates them by more than twice the pair's
 * tolerance (the projections of two polygons on any axis are intervals;
 * a gap between them bounds the distance between the polygons from below,
 * so such a pair can have neither contacts nor overlap). The test is run
 * for polygons of at most SEP_MAX_VERTS vertices together, to keep it
 * cheap; larger pairs go to the narrow phase as they are. In 3D the
 * narrow phase starts with its own separating-axis test (geometry/
 * sat3.c), so box-overlapping pairs go there directly. */
#include "contact.h"

#include "geometry/geometry3.h"

#include <math.h>
#include <stdlib.h>

typedef struct Box {
  double lo[3], hi[3];
  double blo[2], bhi[2]; /* the polygon's own box (2D), without tolerance */
  int body;
  int square;    /* 2D: every edge horizontal or vertical */
  us_Vec2 axis;  /* unit normal of the body's longest edge */
  double alo, ahi; /* the body's own projection on it */
} Box;

/* Order by the low end on one axis, then by body index (a total order, so
 * qsort gives the same result on every run). One comparator per axis keeps
 * qsort free of shared state. */
static int box_cmp_on(const Box *a, const Box *b, int ax) {
  if (a->lo[ax] != b->lo[ax]) return a->lo[ax] < b->lo[ax] ? -1 : 1;
  return (a->body > b->body) - (a->body < b->body);
}
static int box_cmp_x(const void *pa, const void *pb) { return box_cmp_on(pa, pb, 0); }
static int box_cmp_y(const void *pa, const void *pb) { return box_cmp_on(pa, pb, 1); }
static int box_cmp_z(const void *pa, const void *pb) { return box_cmp_on(pa, pb, 2); }

static int pair_cmp(const void *pa, const void *pb) {
  const us_BodyPair *a = pa, *b = pb;
  if (a->i != b->i) return a->i < b->i ? -1 : 1;
  return (a->j > b->j) - (a->j < b->j);
}

static void project(const us_Body *b, us_Vec2 n, double *lo, double *hi);

/* The normal of b's longest edge, tried first: for a long thin block it is
 * the axis that separates it from the parallel blocks beside it. */
static void long_axis(const us_Body *b, Box *x) {
  double best = 0.0;
  for (int e = 0; e < b->nvert; e++) {
    us_Vec2 d = us_v2_sub(us_poly_vertex(b->verts, b->nvert, e + 1),
                          us_poly_vertex(b->verts, b->nvert, e));
    double l = us_v2_norm(d);
    if (l > best) best = l, x->axis = us_v2(d.y / l, -d.x / l);
  }
  project(b, x->axis, &x->alo, &x->ahi);
}

/* Is every edge of b horizontal or vertical? */
static int axis_aligned(const us_Body *b) {
  for (int e = 0; e < b->nvert; e++) {
    us_Vec2 p = us_poly_vertex(b->verts, b->nvert, e), q = us_poly_vertex(b->verts, b->nvert, e + 1);
    if (p.x != q.x && p.y != q.y) return 0;
  }
  return 1;
}

/* Fill boxes of polygon bodies; returns their count. */
static int make_boxes(const us_Structure *s, const double *tol, Box *bx) {
  int n = 0;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    if (b->nvert < 3) continue;
    double bb[4];
    us_poly_bbox(b->verts, b->nvert, bb);
    double t = tol[i];
    bx[n] = (Box){{bb[0] - t, bb[1] - t, 0}, {bb[2] + t, bb[3] + t, 0}, {bb[0], bb[1]},
                  {bb[2], bb[3]}, i, axis_aligned(b), us_v2(0, 0), 0, 0};
    long_axis(b, &bx[n]);
    n++;
  }
  return n;
}

/* Boxes of 3D bodies (over all parts); returns their count. */
static int make_boxes3(const us_Structure *s, const double *tol, Box *bx) {
  int n = 0;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    if (b->npart < 1) continue;
    double bb[6];
    us_body_bbox3(b, bb);
    bx[n] = (Box){{0}, {0}, {0}, {0}, i, 0, us_v2(0, 0), 0, 0};
    for (int d = 0; d < 3; d++) bx[n].lo[d] = bb[d] - tol[i], bx[n].hi[d] = bb[d + 3] + tol[i];
    n++;
  }
  return n;
}

/* The axis (0 = x, 1 = y, 2 = z) along which the box centres spread most
 * (the first of equal spreads). */
static int choose_axis(const Box *bx, int n, int dim) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int k = 0; k < n; k++)
    for (int d = 0; d < dim; d++) {
      double c = 0.5 * (bx[k].lo[d] + bx[k].hi[d]);
      lo[d] = US_MIN(lo[d], c);
      hi[d] = US_MAX(hi[d], c);
    }
  int ax = 0;
  for (int d = 1; n > 0 && d < dim; d++)
    if (hi[d] - lo[d] > hi[ax] - lo[ax]) ax = d;
  return ax;
}

#define SEP_MAX_VERTS 24

/* Interval of polygon b's projections on axis n. */
static void project(const us_Body *b, us_Vec2 n, double *lo, double *hi) {
  *lo = INFINITY;
  *hi = -INFINITY;
  for (int k = 0; k < b->nvert; k++) {
    double d = n.x * b->verts[2 * k] + n.y * b->verts[2 * k + 1];
    *lo = US_MIN(*lo, d);
    *hi = US_MAX(*hi, d);
  }
}

/* Does some edge normal of a separate a and b by more than gap? */
static int normal_separates(const us_Body *a, const us_Body *b, double gap) {
  for (int e = 0; e < a->nvert; e++) {
    us_Vec2 p = us_poly_vertex(a->verts, a->nvert, e), q = us_poly_vertex(a->verts, a->nvert, e + 1);
    us_Vec2 n = us_v2(q.y - p.y, p.x - q.x);
    double len = us_v2_norm(n), alo, ahi, blo, bhi;
    if (!(len > 0)) continue;
    n = us_v2_scale(n, 1.0 / len);
    project(a, n, &alo, &ahi);
    project(b, n, &blo, &bhi);
    if (blo - ahi > gap || alo - bhi > gap) return 1;
  }
  return 0;
}

/* Does the longest-edge axis of x separate the other body by > gap? */
static int long_axis_separates(const Box *x, const us_Body *other, double gap) {
  double lo, hi;
  project(other, x->axis, &lo, &hi);
  return lo - x->ahi > gap || x->alo - hi > gap;
}

/* Two polygons whose edges are all horizontal or vertical: their edge
 * normals are (+-1, 0) and (0, +-1), so the test below is the gap between
 * their boxes on x and y (the normals' rounding aside: either way a pair
 * dropped is more than twice its tolerance apart, where the narrow phase
 * finds neither contact nor overlap, so the contacts are the same). */
static int boxes_apart(const Box *x, const Box *y, double gap) {
  for (int d = 0; d < 2; d++)
    if (y->blo[d] - x->bhi[d] > gap || x->blo[d] - y->bhi[d] > gap) return 1;
  return 0;
}

static int separated(const us_Structure *s, const double *tol, const Box *x, const Box *y) {
  if (s->dim == 3) return 0; /* the narrow phase's own axis test */
  int i = x->body, j = y->body;
  const us_Body *a = &s->bodies[i], *b = &s->bodies[j];
  if (a->nvert + b->nvert > SEP_MAX_VERTS) return 0;
  double gap = 2.0 * US_MIN(tol[i], tol[j]);
  if (x->square && y->square) return boxes_apart(x, y, gap);
  if (long_axis_separates(x, b, gap) || long_axis_separates(y, a, gap)) return 1;
  return normal_separates(a, b, gap) || normal_separates(b, a, gap);
}

static int push_pair(us_BodyPair **pairs, int *np, int *cap, int a, int b) {
  if (US_GROW(*pairs, *cap, *np + 1)) return -1;
  (*pairs)[*np].i = US_MIN(a, b);
  (*pairs)[*np].j = US_MAX(a, b);
  (*np)++;
  return 0;
}

/* Do the boxes overlap on every axis but ax (the sweep's)? */
static int overlap_others(const Box *a, const Box *b, int ax, int dim) {
  for (int d = 0; d < dim; d++)
    if (d != ax && (b->lo[d] > a->hi[d] || a->lo[d] > b->hi[d])) return 0;
  return 1;
}

static int sweep(const us_Structure *s, const double *tol, const Box *bx, int n, int ax,
                 us_BodyPair **pairs, int *np, int *cap) {
  int dim = s->dim == 3 ? 3 : 2;
  for (int k = 0; k < n; k++)
    for (int m = k + 1; m < n && bx[m].lo[ax] <= bx[k].hi[ax]; m++) {
      if (!overlap_others(&bx[k], &bx[m], ax, dim)) continue;
      if (s->bodies[bx[k].body].fixed && s->bodies[bx[m].body].fixed) continue;
      if (separated(s, tol, &bx[k], &bx[m])) continue;
      if (push_pair(pairs, np, cap, bx[k].body, bx[m].body)) return -1;
    }
  return 0;
}

us_Status us_broadphase(const us_Structure *s, const double *tol, us_BodyPair **pairs,
                        int *npairs, us_Error *err) {
  *pairs = NULL;
  *npairs = 0;
  int cap = 0;
  Box *bx = us_malloc((size_t)(s->nbody > 0 ? s->nbody : 1) * sizeof *bx);
  if (!bx || US_GROW(*pairs, cap, 16)) {
    us_free(bx);
    return us_error_set(err, US_ERR_NOMEM, "out of memory in contact detection");
  }
  int dim = s->dim == 3 ? 3 : 2;
  int n = dim == 3 ? make_boxes3(s, tol, bx) : make_boxes(s, tol, bx);
  int ax = choose_axis(bx, n, dim);
  qsort(bx, (size_t)n, sizeof *bx, ax == 2 ? box_cmp_z : ax ? box_cmp_y : box_cmp_x);
  int rc = sweep(s, tol, bx, n, ax, pairs, npairs, &cap);
  us_free(bx);
  if (rc) {
    us_free(*pairs);
    *pairs = NULL;
    *npairs = 0;
    return us_error_set(err, US_ERR_NOMEM, "out of memory in contact detection");
  }
  qsort(*pairs, (size_t)*npairs, sizeof **pairs, pair_cmp);
  return US_OK;
}

us_Status us_broadphase_all(const us_Structure *s, us_BodyPair **pairs, int *npairs,
                            us_Error *err) {
  int cap = 0;
  *pairs = NULL;
  *npairs = 0;
  for (int i = 0; i < s->nbody; i++)
    for (int j = i + 1; j < s->nbody; j++) {
      const us_Body *a = &s->bodies[i], *b = &s->bodies[j];
      int sa = s->dim == 3 ? a->npart > 0 : a->nvert >= 3, sb = s->dim == 3 ? b->npart > 0 : b->nvert >= 3;
      if (!sa || !sb || (a->fixed && b->fixed)) continue;
      if (push_pair(pairs, npairs, &cap, i, j)) {
        us_free(*pairs);
        *pairs = NULL;
        *npairs = 0;
        return us_error_set(err, US_ERR_NOMEM, "out of memory in contact detection");
      }
    }
  return US_OK;
}
