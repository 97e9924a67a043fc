/* Simple-polygon test with a length tolerance.
 *
 * A polygon is simple when no two vertices coincide (within tol), adjacent
 * edges meet only at their shared vertex (no spike folding an edge back
 * onto its neighbour) and non-adjacent edges stay more than tol apart.
 * Vertices and edges are sorted by the low end of their range along the
 * axis on which the polygon is longer (x for a wide comb, y for a tall one)
 * and swept, so only pairs whose ranges overlap (inflated by tol) are
 * compared: close to linear for ordinary shapes (a 100,000-vertex comb
 * either way up), n^2 / 2 in the worst case (every edge spanning the
 * polygon's length). Defects are reported with the smaller index first. */
#include "geometry.h"

#include <math.h>
#include <stdlib.h>

typedef struct Span {
  double lo, hi; /* range along the sweep axis */
  int idx;       /* vertex or edge index */
} Span;

static int span_cmp(const void *pa, const void *pb) {
  const Span *a = pa, *b = pb;
  if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
  return (a->idx > b->idx) - (a->idx < b->idx);
}

/* Sort spans (a total order: ties by index); a few by insertion, the
 * same order qsort gives. */
static void sort_spans(Span *sp, int n) {
  if (n > 16) {
    qsort(sp, (size_t)n, sizeof *sp, span_cmp);
    return;
  }
  for (int a = 1; a < n; a++)
    for (int b = a; b > 0 && span_cmp(&sp[b - 1], &sp[b]) > 0; b--) {
      Span t = sp[b];
      sp[b] = sp[b - 1], sp[b - 1] = t;
    }
}

static void set_pair(int *i, int *j, int a, int b) {
  if (i) *i = US_MIN(a, b);
  if (j) *j = US_MAX(a, b);
}

static us_PolyDefect check_vertices(const double *xy, int n, int ax, double tol, Span *sp, int *i,
                                    int *j) {
  for (int k = 0; k < n; k++) sp[k] = (Span){xy[2 * k + ax], xy[2 * k + ax], k};
  sort_spans(sp, n);
  for (int a = 0; a < n; a++)
    for (int b = a + 1; b < n && sp[b].lo <= sp[a].hi + tol; b++) {
      us_Vec2 p = us_poly_vertex(xy, n, sp[a].idx), q = us_poly_vertex(xy, n, sp[b].idx);
      if (us_v2_dist(p, q) <= tol) {
        set_pair(i, j, sp[a].idx, sp[b].idx);
        return US_POLY_REPEATED_VERTEX;
      }
    }
  return US_POLY_SIMPLE;
}

/* Adjacent edges e (v_e -> v_e+1) and f = e+1: fold if the far end of one
 * comes within tol of the other. */
static int edges_fold(const double *xy, int n, int e, double tol) {
  us_Vec2 a = us_poly_vertex(xy, n, e), b = us_poly_vertex(xy, n, e + 1);
  us_Vec2 c = us_poly_vertex(xy, n, e + 2);
  return us_point_segment_dist(a, b, c, NULL) <= tol || us_point_segment_dist(c, a, b, NULL) <= tol;
}

static us_PolyDefect edge_pair(const double *xy, int n, int e, int f, double tol, int *i, int *j) {
  set_pair(i, j, e, f);
  if ((e + 1) % n == f) return edges_fold(xy, n, e, tol) ? US_POLY_EDGES_FOLD : US_POLY_SIMPLE;
  if ((f + 1) % n == e) return edges_fold(xy, n, f, tol) ? US_POLY_EDGES_FOLD : US_POLY_SIMPLE;
  double d = us_segment_segment_dist(us_poly_vertex(xy, n, e), us_poly_vertex(xy, n, e + 1),
                                     us_poly_vertex(xy, n, f), us_poly_vertex(xy, n, f + 1));
  return d <= tol ? US_POLY_EDGES_CROSS : US_POLY_SIMPLE;
}

static us_PolyDefect check_edges(const double *xy, int n, int ax, double tol, Span *sp, int *i,
                                 int *j) {
  for (int k = 0; k < n; k++) {
    double x0 = xy[2 * k + ax], x1 = xy[2 * ((k + 1) % n) + ax];
    sp[k] = (Span){US_MIN(x0, x1), US_MAX(x0, x1), k};
  }
  sort_spans(sp, n);
  for (int a = 0; a < n; a++)
    for (int b = a + 1; b < n && sp[b].lo <= sp[a].hi + tol; b++) {
      us_PolyDefect d = edge_pair(xy, n, sp[a].idx, sp[b].idx, tol, i, j);
      if (d != US_POLY_SIMPLE) return d;
    }
  return US_POLY_SIMPLE;
}

us_PolyDefect us_poly_check_simple(const double *xy, int n, double tol, int *i, int *j) {
  if (n < 3) return US_POLY_SIMPLE; /* callers reject n < 3 themselves */
  Span small[16]; /* blocks: no allocation */
  Span *sp = n <= 16 ? small : us_malloc((size_t)n * sizeof *sp);
  if (!sp) return US_POLY_NOMEM;
  double bb[4];
  us_poly_bbox(xy, n, bb);
  int ax = bb[3] - bb[1] > bb[2] - bb[0]; /* sweep along the longer side */
  us_PolyDefect d = check_vertices(xy, n, ax, tol, sp, i, j);
  if (d == US_POLY_SIMPLE) d = check_edges(xy, n, ax, tol, sp, i, j);
  if (sp != small) us_free(sp);
  return d;
}
