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
 * A sweep along one axis compares a box with every box overlapping it on
 * that axis: in a square wall of n bricks that is a whole column of
 * courses, n^1.5 in all. So the boxes are first put in a uniform grid
 * over the two axes of largest spread (cells of the mean box size) and
 * compared only within a cell, each pair in the one cell holding the
 * corner (largest low end on both axes) that lies in both boxes. Both
 * ways give the set of pairs whose closed boxes meet and pass the filters
 * below, and the list is sorted, so the result is the same; the sweep
 * remains for boxes the grid would list too often (a few huge bodies).
 * The pairs are sorted by counting on i.
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
#include <string.h>

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

/* The grid: cells of size h from org along axes a[0], a[1]; cell c
 * lists items[start[c] .. start[c+1]) (box positions). */
typedef struct Grid {
  int a[2], nc[2];
  double org[2], h[2];
  int *start, *items;
} Grid;

static int cell_of(const Grid *g, int d, double v) {
  double c = (v - g->org[d]) / g->h[d];
  if (!(c > 0)) return 0;
  return c >= (double)(g->nc[d] - 1) ? g->nc[d] - 1 : (int)c;
}

/* Cells of the grid: mean box size per axis, at most about 2n cells. */
static void grid_shape(Grid *g, const Box *bx, int n) {
  for (int d = 0; d < 2; d++) {
    double lo = INFINITY, hi = -INFINITY, sum = 0.0;
    for (int k = 0; k < n; k++) {
      lo = US_MIN(lo, bx[k].lo[g->a[d]]), hi = US_MAX(hi, bx[k].hi[g->a[d]]);
      sum += bx[k].hi[g->a[d]] - bx[k].lo[g->a[d]];
    }
    double h = sum / n, span = hi - lo;
    g->org[d] = lo;
    g->h[d] = h > 0 ? h : 1.0;
    g->nc[d] = (int)US_MIN(ceil(span / g->h[d]), 2.0 * n + 16);
    if (g->nc[d] < 1) g->nc[d] = 1;
  }
  while ((double)g->nc[0] * g->nc[1] > 2.0 * n + 16) /* coarser until few enough */
    for (int d = 0; d < 2; d++) g->h[d] *= 2, g->nc[d] = (g->nc[d] + 1) / 2;
}

/* Cell ranges of box b: r = {c0, r0, c1, r1}. */
static void grid_range(const Grid *g, const Box *b, int r[4]) {
  r[0] = cell_of(g, 0, b->lo[g->a[0]]), r[1] = cell_of(g, 1, b->lo[g->a[1]]);
  r[2] = cell_of(g, 0, b->hi[g->a[0]]), r[3] = cell_of(g, 1, b->hi[g->a[1]]);
}

/* List every box in the cells it covers: 0, 1 when that would list too
 * many entries (the sweep is used), -1 out of memory. */
static int grid_fill(Grid *g, const Box *bx, int n) {
  long cells = (long)g->nc[0] * g->nc[1], total = 0;
  if (!(g->start = us_calloc((size_t)cells + 1, sizeof *g->start))) return -1;
  for (int k = 0, r[4]; k < n; k++) {
    grid_range(g, &bx[k], r);
    total += (long)(r[2] - r[0] + 1) * (r[3] - r[1] + 1);
    if (total > 8L * n + 1024) return 1;
    for (int y = r[1]; y <= r[3]; y++)
      for (int x = r[0]; x <= r[2]; x++) g->start[(long)y * g->nc[0] + x + 1]++;
  }
  for (long c = 0; c < cells; c++) g->start[c + 1] += g->start[c];
  int *pos = us_malloc((size_t)(cells + 1) * sizeof *pos);
  g->items = us_malloc((size_t)(total > 0 ? total : 1) * sizeof *g->items);
  if (!pos || !g->items) return us_free(pos), -1;
  memcpy(pos, g->start, (size_t)(cells + 1) * sizeof *pos);
  for (int k = 0, r[4]; k < n; k++) {
    grid_range(g, &bx[k], r);
    for (int y = r[1]; y <= r[3]; y++)
      for (int x = r[0]; x <= r[2]; x++) g->items[pos[(long)y * g->nc[0] + x]++] = k;
  }
  us_free(pos);
  return 0;
}

/* Is c the cell of the corner of a and b (their largest low ends)? */
static int home_cell(const Grid *g, const Box *a, const Box *b, long c) {
  int x = cell_of(g, 0, US_MAX(a->lo[g->a[0]], b->lo[g->a[0]]));
  int y = cell_of(g, 1, US_MAX(a->lo[g->a[1]], b->lo[g->a[1]]));
  return (long)y * g->nc[0] + x == c;
}

/* Do the closed boxes meet on every axis? */
static int boxes_meet(const Box *a, const Box *b, int dim) {
  return overlap_others(a, b, -1, dim);
}

/* The pairs of each cell, each in its home cell only. */
static int grid_pairs(const us_Structure *s, const double *tol, const Grid *g, const Box *bx,
                      us_BodyPair **pairs, int *np, int *cap) {
  int dim = s->dim == 3 ? 3 : 2;
  for (long c = 0; c < (long)g->nc[0] * g->nc[1]; c++)
    for (int p = g->start[c]; p < g->start[c + 1]; p++)
      for (int q = p + 1; q < g->start[c + 1]; q++) {
        const Box *x = &bx[g->items[p]], *y = &bx[g->items[q]];
        if (!boxes_meet(x, y, dim) || !home_cell(g, x, y, c)) continue;
        if (s->bodies[x->body].fixed && s->bodies[y->body].fixed) continue;
        if (separated(s, tol, x, y)) continue;
        if (push_pair(pairs, np, cap, x->body, y->body)) return -1;
      }
  return 0;
}

/* The two axes (of dim) along which the box centres spread most. */
static void grid_axes(const Box *bx, int n, int dim, int a[2]) {
  a[0] = 0, a[1] = 1;
  if (dim < 3) return;
  int drop = 0;
  double spread[3];
  for (int d = 0; d < 3; d++) {
    double lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k < n; k++) {
      double c = 0.5 * (bx[k].lo[d] + bx[k].hi[d]);
      lo = US_MIN(lo, c), hi = US_MAX(hi, c);
    }
    spread[d] = n > 0 ? hi - lo : 0.0;
    if (spread[d] < spread[drop]) drop = d;
  }
  a[0] = drop == 0 ? 1 : 0, a[1] = drop == 2 ? 1 : 2;
}

/* Candidate pairs through the grid: 0, 1 (not used: sweep instead), -1. */
static int grid_phase(const us_Structure *s, const double *tol, const Box *bx, int n,
                      us_BodyPair **pairs, int *np, int *cap) {
  Grid g = {{0, 1}, {1, 1}, {0, 0}, {1, 1}, NULL, NULL};
  if (n < 2) return 0;
  grid_axes(bx, n, s->dim == 3 ? 3 : 2, g.a);
  grid_shape(&g, bx, n);
  int rc = grid_fill(&g, bx, n);
  if (rc == 0) rc = grid_pairs(s, tol, &g, bx, pairs, np, cap);
  us_free(g.start);
  us_free(g.items);
  return rc;
}

/* Sort pairs by (i, j): counting on i, then each i's few j in place. */
static int sort_pairs(us_BodyPair *p, int np, int nbody) {
  int *start = us_calloc((size_t)nbody + 1, sizeof *start);
  us_BodyPair *tmp = us_malloc((size_t)(np > 0 ? np : 1) * sizeof *tmp);
  if (!start || !tmp) return us_free(start), us_free(tmp), -1;
  for (int k = 0; k < np; k++) start[p[k].i + 1]++;
  for (int i = 0; i < nbody; i++) start[i + 1] += start[i];
  for (int k = 0; k < np; k++) tmp[start[p[k].i]++] = p[k];
  for (int i = 0, from = 0; i < nbody; from = start[i++]) {
    int m = start[i] - from;
    if (m > 16) qsort(tmp + from, (size_t)m, sizeof *tmp, pair_cmp);
    else
      for (int a = from + 1; a < start[i]; a++)
        for (int b = a; b > from && tmp[b - 1].j > tmp[b].j; b--) {
          us_BodyPair t = tmp[b];
          tmp[b] = tmp[b - 1], tmp[b - 1] = t;
        }
  }
  memcpy(p, tmp, (size_t)np * sizeof *p);
  us_free(start);
  us_free(tmp);
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
  int rc = grid_phase(s, tol, bx, n, pairs, npairs, &cap);
  if (rc == 1) { /* too many entries: the sweep */
    int ax = choose_axis(bx, n, dim);
    *npairs = 0;
    qsort(bx, (size_t)n, sizeof *bx, ax == 2 ? box_cmp_z : ax ? box_cmp_y : box_cmp_x);
    rc = sweep(s, tol, bx, n, ax, pairs, npairs, &cap);
  }
  if (!rc) rc = sort_pairs(*pairs, *npairs, s->nbody);
  us_free(bx);
  if (rc) {
    us_free(*pairs);
    *pairs = NULL;
    *npairs = 0;
    return us_error_set(err, US_ERR_NOMEM, "out of memory in contact detection");
  }
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
