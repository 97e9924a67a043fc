/* Interpenetration check of one pair of bodies, beyond the tolerance.
 *
 * Two simple polygons overlap by more than tol when some point of one's
 * boundary lies inside the other deeper than tol, or when they share a
 * boundary stretch with both interiors on the same side. The boundary test
 * samples: (1) every vertex, and (2) every edge cut at the places where it
 * meets the other polygon's boundary (proper crossings and the other's
 * vertices within tol of it), testing the midpoint of each piece. A piece
 * between two boundary meetings is either inside or outside the other
 * polygon, so its midpoint decides; this catches two equal squares turned
 * 45 degrees and a plus sign of two bars, where no vertex is inside. (3)
 * Equal polygons on top of each other have no point strictly inside the
 * other, hence the coincident-edge test: collinear edges (within tol) with
 * the same outward normal overlapping for more than tol. Depth is the
 * distance from the point to the other polygon's boundary.
 *
 * Cost: every test asks the other polygon's edge index (geometry/
 * edgegrid.c) for the edges near a point or an edge. A point with an edge
 * within tol is not deeper than tol; any other point is decided by a ray
 * through the index. The exact depth (a scan of the whole polygon) is only
 * computed for a point found deep, which ends the check with an error. So
 * a pair costs about its vertices plus the cut points, not their product
 * (a comb of 100,000 vertices under a plate).
 *
 * Side by side: most pairs of a structure are neighbours whose boxes meet
 * only in a thin band at one end on some axis (bricks in a course, a
 * course on the one below). A point deeper than tol inside p has a disc of
 * radius tol inside p, so on each axis it lies more than tol inside p's
 * box; a boundary point of v lies in v's box. When v's box ends at most
 * tol/2 past the start of p's box (or the other way round, on x or y), no
 * point of either boundary can be deeper than tol inside the other, and
 * the vertex and edge samples are skipped; the slack also covers the
 * rounding of distances computed from the coordinates (a few ulps of the
 * largest). Only the coincident-edge test remains. The reference mode
 * samples every pair. */
#include "contact.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#define SMALL_BUF 130

static us_Status report(const us_Structure *s, int i, int j, const char *what, int k, int owner,
                        double depth, us_Error *err) {
  return us_error_set(err, US_ERR_INPUT,
                      "bodies '%s' and '%s' overlap (%s %d of '%s' is %g inside '%s')",
                      us_id_text(s->bodies[i].id).s, us_id_text(s->bodies[j].id).s, what, k,
                      us_id_text(s->bodies[owner].id).s, depth,
                      us_id_text(s->bodies[owner == i ? j : i].id).s);
}

static int in_box(us_Vec2 p, const double bb[4], double tol) {
  return p.x >= bb[0] - tol && p.x <= bb[2] + tol && p.y >= bb[1] - tol && p.y <= bb[3] + tol;
}

/* Is q deeper than tol inside p? Not when an edge of p is within tol
 * (only the edges near q are looked at); else q is strictly inside or
 * outside and the edge index decides which. *depth gets the exact depth. */
static int is_deep(us_EdgeGrid *g, const us_Body *p, us_Vec2 q, double tol, double *depth) {
  double box[4] = {q.x - tol, q.y - tol, q.x + tol, q.y + tol};
  int m = us_edge_grid_query(g, box);
  for (int k = 0; k < m; k++) {
    int e = g->out[k];
    us_Vec2 a = us_poly_vertex(p->verts, p->nvert, e), b = us_poly_vertex(p->verts, p->nvert, e + 1);
    if (us_point_segment_dist(q, a, b, NULL) <= tol) return 0;
  }
  if (!us_edge_grid_inside(g, q)) return 0;
  *depth = us_point_polygon_depth(q, p->verts, p->nvert);
  return *depth > tol;
}

/* First vertex of body v deeper than tol inside body p: index or -1. */
static int deep_vertex(const us_Body *v, const us_Body *p, us_EdgeGrid *gp, double tol,
                       double *depth) {
  double bb[4];
  us_poly_bbox(p->verts, p->nvert, bb);
  for (int k = 0; k < v->nvert; k++) {
    us_Vec2 q = us_poly_vertex(v->verts, v->nvert, k);
    if (in_box(q, bb, 0) && is_deep(gp, p, q, tol, depth)) return k;
  }
  return -1;
}

static int dbl_cmp(const void *pa, const void *pb) {
  double a = *(const double *)pa, b = *(const double *)pb;
  return (a > b) - (a < b);
}

/* Parameters along q0->q1 where it meets p's boundary (only p's edges near
 * the segment can); returns the count. */
static int cut_params(us_Vec2 q0, us_Vec2 q1, const us_Body *p, us_EdgeGrid *gp, double tol,
                      double *ts) {
  int m = 0;
  ts[m++] = 0.0;
  ts[m++] = 1.0;
  double box[4] = {US_MIN(q0.x, q1.x) - tol, US_MIN(q0.y, q1.y) - tol, US_MAX(q0.x, q1.x) + tol,
                   US_MAX(q0.y, q1.y) + tol};
  int ne = us_edge_grid_query(gp, box);
  for (int k = 0; k < ne; k++) {
    int e = gp->out[k];
    us_Vec2 p0 = us_poly_vertex(p->verts, p->nvert, e);
    us_Vec2 p1 = us_poly_vertex(p->verts, p->nvert, e + 1);
    double t;
    if (us_segment_intersect(q0, q1, p0, p1, &t, NULL) == US_SEG_PROPER) ts[m++] = t;
    if (us_point_segment_dist(p0, q0, q1, &t) <= tol) ts[m++] = t;
  }
  if (m > 16) qsort(ts, (size_t)m, sizeof *ts, dbl_cmp);
  else /* a few cuts: insertion (equal values are interchangeable) */
    for (int a = 1; a < m; a++)
      for (int b = a; b > 0 && ts[b - 1] > ts[b]; b--) {
        double t = ts[b];
        ts[b] = ts[b - 1], ts[b - 1] = t;
      }
  return m;
}

/* Edge f of body v cut by p's boundary: depth of the deepest piece
 * midpoint deeper than tol inside p (or -inf when none is). */
static double edge_depth(const us_Body *v, int f, const us_Body *p, us_EdgeGrid *gp, double tol,
                         double *ts) {
  us_Vec2 q0 = us_poly_vertex(v->verts, v->nvert, f);
  us_Vec2 q1 = us_poly_vertex(v->verts, v->nvert, f + 1);
  double len = us_v2_dist(q0, q1), worst = -INFINITY, d;
  int m = cut_params(q0, q1, p, gp, tol, ts);
  for (int k = 0; k + 1 < m; k++) {
    if ((ts[k + 1] - ts[k]) * len <= 2 * tol) continue; /* too short to go deeper than tol */
    double t = 0.5 * (ts[k] + ts[k + 1]);
    us_Vec2 mid = us_v2_add(q0, us_v2_scale(us_v2_sub(q1, q0), t));
    if (is_deep(gp, p, mid, tol, &d)) worst = US_MAX(worst, d);
  }
  return worst;
}

/* First edge of v with a piece deeper than tol inside p: index or -1. */
static int deep_edge(const us_Body *v, const us_Body *p, us_EdgeGrid *gp, double tol, double *ts,
                     double *depth) {
  double bb[4];
  us_poly_bbox(p->verts, p->nvert, bb);
  for (int f = 0; f < v->nvert; f++) {
    us_Vec2 q0 = us_poly_vertex(v->verts, v->nvert, f);
    us_Vec2 q1 = us_poly_vertex(v->verts, v->nvert, f + 1);
    if (US_MAX(q0.x, q1.x) < bb[0] || US_MIN(q0.x, q1.x) > bb[2] || US_MAX(q0.y, q1.y) < bb[1] ||
        US_MIN(q0.y, q1.y) > bb[3])
      continue;
    double d = edge_depth(v, f, p, gp, tol, ts);
    if (d > tol) {
      *depth = d;
      return f;
    }
  }
  return -1;
}

/* Outward unit normal of CCW edge e of body b. */
static us_Vec2 edge_normal(const us_Body *b, int e) {
  us_Vec2 d =
      us_v2_sub(us_poly_vertex(b->verts, b->nvert, e + 1), us_poly_vertex(b->verts, b->nvert, e));
  double l = us_v2_norm(d);
  return l > 0 ? us_v2(d.y / l, -d.x / l) : us_v2(0, 0);
}

/* Edges e of a (outward normal na) and f of b collinear, same outward
 * side, sharing > tol. */
static int same_side_overlap(const us_Body *a, int e, us_Vec2 na, const us_Body *b, int f,
                             double tol) {
  us_Vec2 p0 = us_poly_vertex(a->verts, a->nvert, e);
  us_Vec2 q0 = us_poly_vertex(b->verts, b->nvert, f),
          q1 = us_poly_vertex(b->verts, b->nvert, f + 1);
  /* off e's line first: it needs no square root */
  if (fabs(us_v2_dot(us_v2_sub(q0, p0), na)) > tol || fabs(us_v2_dot(us_v2_sub(q1, p0), na)) > tol)
    return 0;
  if (us_v2_dot(na, edge_normal(b, f)) < US_CONTACT_NORMAL_COS) return 0;
  us_Vec2 dir = us_v2(-na.y, na.x); /* along edge e */
  double la = us_v2_dist(p0, us_poly_vertex(a->verts, a->nvert, e + 1));
  double u0 = us_v2_dot(us_v2_sub(q0, p0), dir), u1 = us_v2_dot(us_v2_sub(q1, p0), dir);
  double lo = US_MAX(0.0, US_MIN(u0, u1)), hi = US_MIN(la, US_MAX(u0, u1));
  return hi - lo > tol;
}

/* Edges e of a and f of b (the first such pair in (e, f) order) that lie
 * on each other with both bodies on the same side; only b's edges near e
 * can. */
static us_Status coincident(const us_Structure *s, int i, int j, us_EdgeGrid *gb, double tol,
                            us_Error *err) {
  const us_Body *a = &s->bodies[i], *b = &s->bodies[j];
  for (int e = 0; e < a->nvert; e++) {
    us_Vec2 na = edge_normal(a, e);
    us_Vec2 p0 = us_poly_vertex(a->verts, a->nvert, e), p1 = us_poly_vertex(a->verts, a->nvert, e + 1);
    double box[4] = {US_MIN(p0.x, p1.x) - tol, US_MIN(p0.y, p1.y) - tol, US_MAX(p0.x, p1.x) + tol,
                     US_MAX(p0.y, p1.y) + tol};
    int m = us_edge_grid_query(gb, box);
    for (int k = 0; k < m; k++) {
      int f = gb->out[k];
      if (same_side_overlap(a, e, na, b, f, tol))
        return us_error_set(err, US_ERR_INPUT,
                            "bodies '%s' and '%s' overlap (edge %d of '%s' lies on edge %d of "
                            "'%s' with both bodies on the same side)",
                            us_id_text(a->id).s, us_id_text(b->id).s, e, us_id_text(a->id).s, f,
                            us_id_text(b->id).s);
    }
  }
  return US_OK;
}

/* Do the boxes of a and b meet only in a band of at most tol/2 (less the
 * rounding slack) at one end, on x or on y? */
static int side_by_side(const us_Body *a, const us_Body *b, double tol) {
  double p[4], q[4], big = 0.0;
  us_poly_bbox(a->verts, a->nvert, p);
  us_poly_bbox(b->verts, b->nvert, q);
  for (int k = 0; k < 4; k++) big = US_MAX(big, US_MAX(fabs(p[k]), fabs(q[k])));
  double m = 0.5 * tol - 64 * DBL_EPSILON * big;
  for (int ax = 0; ax < 2; ax++)
    if (p[ax + 2] - q[ax] <= m || q[ax + 2] - p[ax] <= m) return 1;
  return 0;
}

static us_Status overlap_with(const us_Structure *s, int i, int j, us_EdgeGrid **g, double tol,
                              double *ts, us_Error *err) {
  int pr[2][2] = {{j, i}, {i, j}}; /* (owner of the boundary, the other) */
  double d = 0.0;
  for (int r = 0; r < 2; r++) {
    const us_Body *v = &s->bodies[pr[r][0]], *p = &s->bodies[pr[r][1]];
    int k = deep_vertex(v, p, g[r], tol, &d);
    if (k >= 0) return report(s, i, j, "vertex", k, pr[r][0], d, err);
  }
  for (int r = 0; r < 2; r++) {
    const us_Body *v = &s->bodies[pr[r][0]], *p = &s->bodies[pr[r][1]];
    int k = deep_edge(v, p, g[r], tol, ts, &d);
    if (k >= 0) return report(s, i, j, "a point of edge", k, pr[r][0], d, err);
  }
  return coincident(s, i, j, g[1], tol, err);
}

us_Status us_pair_overlap(us_Detect *dt, int i, int j, double tol, us_Error *err) {
  const us_Structure *s = dt->s;
  us_EdgeGrid *g[2] = {us_detect_grid(dt, i), us_detect_grid(dt, j)};
  int need = 2 + 2 * US_MAX(s->bodies[i].nvert, s->bodies[j].nvert);
  double small[SMALL_BUF];
  double *ts = need <= SMALL_BUF ? small : us_malloc((size_t)need * sizeof *ts);
  if (!ts || !g[0] || !g[1]) {
    if (ts != small) us_free(ts);
    return us_error_set(err, US_ERR_NOMEM, "out of memory in contact detection");
  }
  us_Status st = !dt->reference && side_by_side(&s->bodies[i], &s->bodies[j], tol)
                     ? coincident(s, i, j, g[1], tol, err)
                     : overlap_with(s, i, j, g, tol, ts, err);
  if (ts != small) us_free(ts);
  return st;
}
