/* Vertex-on-edge contacts between two bodies, and the candidate list.
 *
 * A vertex v of body B touches edge e of body A when its distance to the
 * edge is <= tol and B does not locally enter A's side of that edge:
 *  - v inside the edge's span: each polygon edge of B adjacent to v,
 *    followed only while it stays over edge e (its projection on e's line
 *    within the edge, or within v's own projection if that lies beyond),
 *    must end no deeper than tol behind e's line. Following only over the
 *    edge keeps slightly tilted blocks (deeper than tol only far away,
 *    where A has ended) in contact.
 *  - v within tol of an end of the edge (corner on corner): both edges of
 *    B at v must point into the closed outer half-plane of e, up to an
 *    angle of US_CONTACT_DIR_SIN. Here there is no span to follow, and a
 *    direction test is what tells a block stacked on an aligned block
 *    (its bottom edge runs into the lower block: no sideways contact) or a
 *    triangle standing on its apex on a block's corner (its sides slope
 *    into the side edge's half-plane) from diagonal boxes.
 *  - a reflex vertex of B (interior angle > 180 degrees) touches only when
 *    both neighbours lie on e's line, since its interior would otherwise
 *    cover A's side.
 * The contact is (a = A, b = B, p = v, n = outward normal of e), so the
 * normal points from a into b.
 *
 * Candidates of a pair are collected as: vertices of j on edges of i, then
 * vertices of i on edges of j, each in vertex then edge order; a candidate
 * within tol of an earlier kept one with the same normal (same a) or the
 * opposite normal (swapped a and b) is a duplicate and dropped. Only the
 * edges near a vertex are tested (the polygon's edge index, geometry/
 * edgegrid.c) and duplicates are searched among candidates within tol along
 * the axis of larger spread, so a pair costs about its vertices plus its
 * contacts, not their product. Corner on
 * corner (diagonal boxes, an apex on a block's corner) keeps every edge
 * normal at that point that separates the two corners (for diagonal boxes
 * both the vertical and the horizontal one): the contact normal of two
 * corners is not defined, and each kept normal is an admissible one. */
#include "contact.h"

#include <math.h>
#include <stdlib.h>

int us_cand_push(us_CandList *l, int a, int b, us_Vec2 p, us_Vec2 n) {
  if (US_GROW(l->c, l->cap, l->n + 1)) return -1;
  us_Cand *c = &l->c[l->n++];
  c->a = a;
  c->b = b;
  c->p = p;
  c->n = n;
  return 0;
}

/* Signed distance (outward +) of the end of B's edge v->w, followed while
 * it stays over edge [p0, p0 + len * dir] of A. */
static double follow_depth(us_Vec2 v, us_Vec2 w, us_Vec2 p0, us_Vec2 dir, us_Vec2 n, double len) {
  double uv = us_v2_dot(us_v2_sub(v, p0), dir), uw = us_v2_dot(us_v2_sub(w, p0), dir);
  double lo = US_MIN(0.0, uv), hi = US_MAX(len, uv), s = 1.0;
  if (uw > hi) s = (hi - uv) / (uw - uv);
  if (uw < lo) s = (lo - uv) / (uw - uv);
  us_Vec2 end = us_v2_add(v, us_v2_scale(us_v2_sub(w, v), s));
  return us_v2_dot(us_v2_sub(end, p0), n);
}

/* Cosine-like slope of B's edge v->w against the outward normal n. */
static double slope(us_Vec2 v, us_Vec2 w, us_Vec2 n) {
  us_Vec2 d = us_v2_sub(w, v);
  double l = us_v2_norm(d);
  return l > 0 ? us_v2_dot(d, n) / l : 0.0;
}

/* Vertex on an end of the edge (corner on corner): both of B's edges at v
 * must point into the closed outer half-plane, up to a small angle; a
 * reflex v only if both run along the edge's line. */
static int corner_ok(us_Vec2 v, us_Vec2 prev, us_Vec2 next, us_Vec2 n) {
  double sp = slope(v, prev, n), sn = slope(v, next, n);
  if (sp < -US_CONTACT_DIR_SIN || sn < -US_CONTACT_DIR_SIN) return 0;
  return us_orient(prev, v, next) >= 0 || (sp <= US_CONTACT_DIR_SIN && sn <= US_CONTACT_DIR_SIN);
}

/* Vertex inside the edge's span: B's edges, followed while over the edge,
 * end no deeper than tol; a reflex v only if both stay on the line. */
static int face_ok(us_Vec2 v, us_Vec2 prev, us_Vec2 next, us_Vec2 p0, us_Vec2 dir, us_Vec2 n,
                   double len, double tol) {
  double dp = follow_depth(v, prev, p0, dir, n, len), dn = follow_depth(v, next, p0, dir, n, len);
  if (dp < -tol || dn < -tol) return 0;
  return us_orient(prev, v, next) >= 0 || (dp <= tol && dn <= tol);
}

/* Does vertex k of B touch edge e of A? Fills the outward normal. */
static int vertex_on_edge(const us_Body *A, int e, const us_Body *B, int k, double tol,
                          us_Vec2 *n) {
  us_Vec2 p0 = us_poly_vertex(A->verts, A->nvert, e);
  us_Vec2 p1 = us_poly_vertex(A->verts, A->nvert, e + 1);
  us_Vec2 v = us_poly_vertex(B->verts, B->nvert, k);
  if (us_point_segment_dist(v, p0, p1, NULL) > tol) return 0;
  double len = us_v2_dist(p0, p1);
  if (!(len > 0)) return 0;
  us_Vec2 dir = us_v2_scale(us_v2_sub(p1, p0), 1.0 / len);
  *n = us_v2(dir.y, -dir.x);
  us_Vec2 prev = us_poly_vertex(B->verts, B->nvert, k - 1);
  us_Vec2 next = us_poly_vertex(B->verts, B->nvert, k + 1);
  if (us_v2_dist(v, p0) <= tol || us_v2_dist(v, p1) <= tol) return corner_ok(v, prev, next, *n);
  return face_ok(v, prev, next, p0, dir, *n, len, tol);
}

/* Is c (later) a duplicate of d (earlier)? Within tol, same normal from
 * the same owner or the opposite normal from the other body. */
static int duplicates(const us_Cand *d, const us_Cand *c, double tol) {
  if (us_v2_dist(d->p, c->p) > tol) return 0;
  double dot = us_v2_dot(d->n, c->n);
  return d->a == c->a ? dot >= US_CONTACT_NORMAL_COS : dot <= -US_CONTACT_NORMAL_COS;
}

typedef struct Key {
  double x;
  int idx;
} Key;

static int key_cmp(const void *pa, const void *pb) {
  const Key *a = pa, *b = pb;
  if (a->x != b->x) return a->x < b->x ? -1 : 1;
  return (a->idx > b->idx) - (a->idx < b->idx);
}

/* The axis (0 x, 1 y) along which the points spread most. */
static int spread_axis(const us_Cand *c, int m) {
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (int k = 0; k < m; k++) {
    lo[0] = US_MIN(lo[0], c[k].p.x), hi[0] = US_MAX(hi[0], c[k].p.x);
    lo[1] = US_MIN(lo[1], c[k].p.y), hi[1] = US_MAX(hi[1], c[k].p.y);
  }
  return hi[1] - lo[1] > hi[0] - lo[0];
}

/* Is candidate c a duplicate of a kept earlier one? Scan the neighbours
 * of its place r in the sorted keys while they are within tol. */
static int dup_of_kept(const us_Cand *cd, const Key *key, int m, int r, const unsigned char *keep,
                       double tol) {
  int c = key[r].idx;
  for (int dir = -1; dir <= 1; dir += 2)
    for (int q = r + dir; q >= 0 && q < m && fabs(key[q].x - key[r].x) <= tol; q += dir)
      if (key[q].idx < c && keep[key[q].idx] && duplicates(&cd[key[q].idx], &cd[c], tol)) return 1;
  return 0;
}

/* Drop, in generation order, every candidate from `from` on that
 * duplicates an earlier kept one. Candidates are sorted along the axis of
 * larger spread so that only those within tol along it are compared. */
/* The reference: every earlier kept candidate is compared. */
static void drop_duplicates_slow(us_CandList *l, int from, double tol) {
  int n = from;
  for (int c = from; c < l->n; c++) {
    int dup = 0;
    for (int k = from; k < n && !dup; k++) dup = duplicates(&l->c[k], &l->c[c], tol);
    if (!dup) l->c[n++] = l->c[c];
  }
  l->n = n;
}

#define DUP_SMALL 32

static int drop_duplicates(us_CandList *l, int from, double tol) {
  int m = l->n - from;
  if (m < 2) return 0;
  us_Cand *cd = l->c + from;
  Key key_s[DUP_SMALL]; /* a pair's few candidates need no allocation */
  int pos_s[DUP_SMALL];
  unsigned char keep_s[DUP_SMALL];
  int small = m <= DUP_SMALL;
  Key *key = small ? key_s : us_malloc((size_t)m * sizeof *key);
  int *pos = small ? pos_s : us_malloc((size_t)m * sizeof *pos);
  unsigned char *keep = small ? keep_s : us_malloc((size_t)m);
  if (!key || !pos || !keep) {
    if (!small) us_free(key), us_free(pos), us_free(keep);
    return -1;
  }
  int ax = spread_axis(cd, m), n = 0;
  for (int k = 0; k < m; k++) key[k] = (Key){ax ? cd[k].p.y : cd[k].p.x, k};
  if (m > 16) qsort(key, (size_t)m, sizeof *key, key_cmp);
  else /* a pair's few candidates: insertion, the same total order */
    for (int a = 1; a < m; a++)
      for (int b = a; b > 0 && key_cmp(&key[b - 1], &key[b]) > 0; b--) {
        Key t = key[b];
        key[b] = key[b - 1], key[b - 1] = t;
      }
  for (int r = 0; r < m; r++) pos[key[r].idx] = r;
  for (int c = 0; c < m; c++) keep[c] = !dup_of_kept(cd, key, m, pos[c], keep, tol);
  for (int c = 0; c < m; c++)
    if (keep[c]) cd[n++] = cd[c];
  l->n = from + n;
  if (!small) us_free(key), us_free(pos), us_free(keep);
  return 0;
}

/* Vertices of body ib on edges of body ia: for each vertex of ib (in
 * order), the edges of ia near it (from ia's edge index, in order). */
static int vertices_on_edges(us_Detect *d, int ia, int ib, double tol, us_CandList *out) {
  const us_Body *A = &d->s->bodies[ia], *B = &d->s->bodies[ib];
  us_EdgeGrid *g = us_detect_grid(d, ia);
  if (!g) return -1;
  double bb[4];
  us_poly_bbox(A->verts, A->nvert, bb);
  for (int k = 0; k < B->nvert; k++) {
    us_Vec2 v = us_poly_vertex(B->verts, B->nvert, k), n;
    if (v.x < bb[0] - tol || v.x > bb[2] + tol || v.y < bb[1] - tol || v.y > bb[3] + tol) continue;
    double box[4] = {v.x - tol, v.y - tol, v.x + tol, v.y + tol};
    int m = us_edge_grid_query(g, box);
    for (int q = 0; q < m; q++)
      if (vertex_on_edge(A, g->out[q], B, k, tol, &n) && us_cand_push(out, ia, ib, v, n)) return -1;
  }
  return 0;
}

us_Status us_pair_contacts(us_Detect *d, int i, int j, double tol, us_CandList *out,
                           us_Error *err) {
  int from = out->n;
  if (vertices_on_edges(d, i, j, tol, out) || vertices_on_edges(d, j, i, tol, out))
    return us_error_set(err, US_ERR_NOMEM, "out of memory in contact detection");
  if (d->reference)
    drop_duplicates_slow(out, from, tol);
  else if (drop_duplicates(out, from, tol))
    return us_error_set(err, US_ERR_NOMEM, "out of memory in contact detection");
  return US_OK;
}
