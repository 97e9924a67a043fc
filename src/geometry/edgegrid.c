/* Edge index of one polygon: which edges come near a box, and is a point
 * inside, without looking at every edge.
 *
 * A uniform grid over the polygon's bounding box (padded by `pad`) with
 * about one cell per edge, cells shaped like the box (a long flat comb gets
 * a long row of cells). Each edge is listed in every cell its bounding box
 * (padded by `pad`) overlaps, in compressed rows (start[c] .. start[c+1]
 * into items), edges in increasing order within a cell. Invariant: every
 * edge whose padded box meets a query box is listed in a cell the query
 * box meets, so a query returns a superset of the edges within `pad` of
 * the box; callers apply their exact tests to it. A query returns each edge
 * once (a stamp per edge), in increasing order.
 *
 * Point in polygon: a point farther than the tolerance from every edge is
 * strictly inside or outside, and any ray decides it by the parity of its
 * crossings. The ray goes straight to the nearest side of the box and only
 * the cells it passes through are read (an edge crossing the ray is listed
 * in the cell where it crosses), so the cost is the cells and edges met on
 * the way rather than the whole polygon.
 *
 * Small polygons (at most US_EDGE_GRID_MIN edges) and grids that would list
 * too many cells per edge (long diagonal edges) keep no grid: queries then
 * filter all edges by box, and inside uses the full crossing rule, so the
 * answers are the same either way (pad = inf keeps no grid and every
 * query returns every edge: the reference for tests). Cost: building O(n + listed entries);
 * a query O(cells met + edges listed there). */
#include "geometry.h"

#include <stdlib.h>
#include <string.h>

/* The padded box of edge e (0 <= e < n). */
static void edge_box(const us_EdgeGrid *g, int e, double b[4]) {
  const double *p = g->xy + 2 * e, *q = g->xy + 2 * (e + 1 < g->n ? e + 1 : 0);
  b[0] = US_MIN(p[0], q[0]) - g->pad;
  b[1] = US_MIN(p[1], q[1]) - g->pad;
  b[2] = US_MAX(p[0], q[0]) + g->pad;
  b[3] = US_MAX(p[1], q[1]) + g->pad;
}

static int cell_of(double v, double lo, double h, int m) {
  double c = (v - lo) / h;
  if (!(c > 0)) return 0;
  return c >= (double)(m - 1) ? m - 1 : (int)c;
}

/* Cell ranges [c0, c1] x [r0, r1] met by a box. */
static void cell_range(const us_EdgeGrid *g, const double b[4], int r[4]) {
  r[0] = cell_of(b[0], g->lo[0], g->h[0], g->nx);
  r[1] = cell_of(b[1], g->lo[1], g->h[1], g->ny);
  r[2] = cell_of(b[2], g->lo[0], g->h[0], g->nx);
  r[3] = cell_of(b[3], g->lo[1], g->h[1], g->ny);
}

/* Grid shape: about n square-ish cells over the padded box. */
static void shape(us_EdgeGrid *g) {
  double bb[4];
  us_poly_bbox(g->xy, g->n, bb);
  double w = bb[2] - bb[0] + 2 * g->pad, hgt = bb[3] - bb[1] + 2 * g->pad;
  double h = sqrt(w * hgt / g->n);
  if (!(h > 0)) h = US_MAX(w, hgt) / g->n;
  g->nx = (int)US_MIN((double)g->n, US_MAX(1.0, ceil(w / h)));
  g->ny = (int)US_MIN((double)g->n, US_MAX(1.0, ceil(hgt / h)));
  g->lo[0] = bb[0] - g->pad;
  g->lo[1] = bb[1] - g->pad;
  g->h[0] = w > 0 ? w / g->nx : 1.0;
  g->h[1] = hgt > 0 ? hgt / g->ny : 1.0;
}

/* Entries per cell into start (counts, then prefix sums); total or -1
 * when the grid would list too many entries. */
static long count_entries(us_EdgeGrid *g) {
  long total = 0, cap = 16L * g->n + 4096;
  for (int e = 0; e < g->n; e++) {
    double b[4];
    int r[4];
    edge_box(g, e, b);
    cell_range(g, b, r);
    total += (long)(r[2] - r[0] + 1) * (r[3] - r[1] + 1);
    if (total > cap) return -1;
    for (int y = r[1]; y <= r[3]; y++)
      for (int x = r[0]; x <= r[2]; x++) g->start[y * g->nx + x + 1]++;
  }
  for (int c = 0; c < g->nx * g->ny; c++) g->start[c + 1] += g->start[c];
  return total;
}

static void fill_entries(us_EdgeGrid *g, int *pos) {
  memcpy(pos, g->start, (size_t)(g->nx * g->ny) * sizeof *pos);
  for (int e = 0; e < g->n; e++) {
    double b[4];
    int r[4];
    edge_box(g, e, b);
    cell_range(g, b, r);
    for (int y = r[1]; y <= r[3]; y++)
      for (int x = r[0]; x <= r[2]; x++) g->items[pos[y * g->nx + x]++] = e;
  }
}

/* Build the cells; 0, 1 when no grid is kept (too many entries), -1 OOM. */
static int build(us_EdgeGrid *g) {
  shape(g);
  int cells = g->nx * g->ny;
  g->start = us_calloc((size_t)cells + 1, sizeof *g->start);
  if (!g->start) return -1;
  long total = count_entries(g);
  if (total < 0) {
    us_free(g->start);
    g->start = NULL;
    return 1;
  }
  int *pos = us_malloc((size_t)cells * sizeof *pos);
  g->items = us_malloc((size_t)(total > 0 ? total : 1) * sizeof *g->items);
  if (!pos || !g->items) {
    us_free(pos);
    return -1;
  }
  fill_entries(g, pos);
  us_free(pos);
  return 0;
}

int us_edge_grid_init(us_EdgeGrid *g, const double *xy, int n, double pad) {
  memset(g, 0, sizeof *g);
  g->xy = xy;
  g->n = n;
  g->pad = pad;
  if (n <= US_EDGE_GRID_MIN) { /* scanned whole, nothing to allocate */
    g->out = g->small;
    return 0;
  }
  g->stamp = us_calloc((size_t)n, sizeof *g->stamp);
  g->out = us_malloc((size_t)n * sizeof *g->out);
  if (!g->stamp || !g->out || (isfinite(pad) && build(g) < 0)) {
    us_edge_grid_free(g);
    return -1;
  }
  return 0;
}

void us_edge_grid_free(us_EdgeGrid *g) {
  us_free(g->start);
  us_free(g->items);
  us_free(g->stamp);
  if (g->out != g->small) us_free(g->out);
  memset(g, 0, sizeof *g);
}

static int boxes_meet(const double a[4], const double b[4]) {
  return a[0] <= b[2] && b[0] <= a[2] && a[1] <= b[3] && b[1] <= a[3];
}

static int int_cmp(const void *pa, const void *pb) {
  int a = *(const int *)pa, b = *(const int *)pb;
  return (a > b) - (a < b);
}

/* Add edge e to the result once (stamp) if its padded box meets b. */
static void take(us_EdgeGrid *g, int e, const double b[4]) {
  if (g->stamp[e] == g->qid) return;
  g->stamp[e] = g->qid;
  double eb[4];
  edge_box(g, e, eb);
  if (boxes_meet(eb, b)) g->out[g->nout++] = e;
}

int us_edge_grid_query(us_EdgeGrid *g, const double box[4]) {
  g->nout = 0;
  if (!g->start) {
    double eb[4];
    for (int e = 0; e < g->n; e++) {
      edge_box(g, e, eb);
      if (boxes_meet(eb, box)) g->out[g->nout++] = e;
    }
    return g->nout;
  }
  g->qid++;
  int r[4];
  cell_range(g, box, r);
  for (int y = r[1]; y <= r[3]; y++)
    for (int x = r[0]; x <= r[2]; x++) {
      int c = y * g->nx + x;
      for (int k = g->start[c]; k < g->start[c + 1]; k++) take(g, g->items[k], box);
    }
  qsort(g->out, (size_t)g->nout, sizeof *g->out, int_cmp);
  return g->nout;
}

/* Does edge e cross the ray from q along axis `ax` (0 x, 1 y) in the
 * direction `sg` (+1 or -1)? Half-open rule on the other coordinate. */
static int crosses_ray(const us_EdgeGrid *g, int e, us_Vec2 q, int ax, double sg) {
  us_Vec2 a = us_poly_vertex(g->xy, g->n, e), b = us_poly_vertex(g->xy, g->n, e + 1);
  double au = ax ? a.y : a.x, bu = ax ? b.y : b.x, aw = ax ? a.x : a.y, bw = ax ? b.x : b.y;
  double qu = ax ? q.y : q.x, qw = ax ? q.x : q.y;
  if ((aw > qw) == (bw > qw)) return 0;
  double u = au + (qw - aw) * (bu - au) / (bw - aw);
  return sg * (u - qu) > 0;
}

int us_edge_grid_inside(us_EdgeGrid *g, us_Vec2 q) {
  if (!g->start) return us_point_in_polygon(q, g->xy, g->n);
  double hi[2] = {g->lo[0] + g->h[0] * g->nx, g->lo[1] + g->h[1] * g->ny};
  double d[4] = {q.x - g->lo[0], hi[0] - q.x, q.y - g->lo[1], hi[1] - q.y};
  int side = 0;
  for (int k = 1; k < 4; k++)
    if (d[k] < d[side]) side = k;
  if (!(d[side] >= 0)) return 0; /* outside the box */
  /* the cells from q's to the border along the ray, as a box query */
  double box[4] = {q.x, q.y, q.x, q.y};
  box[side == 0 ? 0 : side == 1 ? 2 : side == 2 ? 1 : 3] =
      side == 0 ? g->lo[0] : side == 1 ? hi[0] : side == 2 ? g->lo[1] : hi[1];
  int m = us_edge_grid_query(g, box), odd = 0, ax = side / 2;
  double sg = side % 2 ? 1.0 : -1.0;
  for (int k = 0; k < m; k++) odd ^= crosses_ray(g, g->out[k], q, ax, sg);
  return odd;
}
