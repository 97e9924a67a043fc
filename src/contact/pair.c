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
 * within tol of an earlier one with the same normal (same a) or the
 * opposite normal (swapped a and b) is a duplicate and dropped. Corner on
 * corner (diagonal boxes, an apex on a block's corner) keeps every edge
 * normal at that point that separates the two corners (for diagonal boxes
 * both the vertical and the horizontal one): the contact normal of two
 * corners is not defined, and each kept normal is an admissible one. */
#include "contact.h"

#include <math.h>

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

static int is_duplicate(const us_CandList *l, int from, int a, us_Vec2 p, us_Vec2 n, double tol) {
  for (int k = from; k < l->n; k++) {
    const us_Cand *c = &l->c[k];
    if (us_v2_dist(c->p, p) > tol) continue;
    double dot = us_v2_dot(c->n, n);
    if (c->a == a ? dot >= US_CONTACT_NORMAL_COS : dot <= -US_CONTACT_NORMAL_COS) return 1;
  }
  return 0;
}

/* Vertices of body ib on edges of body ia. */
static int vertices_on_edges(const us_Structure *s, int ia, int ib, double tol, int from,
                             us_CandList *out) {
  const us_Body *A = &s->bodies[ia], *B = &s->bodies[ib];
  double bb[4];
  us_poly_bbox(A->verts, A->nvert, bb);
  for (int k = 0; k < B->nvert; k++) {
    us_Vec2 v = us_poly_vertex(B->verts, B->nvert, k), n;
    if (v.x < bb[0] - tol || v.x > bb[2] + tol || v.y < bb[1] - tol || v.y > bb[3] + tol) continue;
    for (int e = 0; e < A->nvert; e++) {
      if (!vertex_on_edge(A, e, B, k, tol, &n) || is_duplicate(out, from, ia, v, n, tol)) continue;
      if (us_cand_push(out, ia, ib, v, n)) return -1;
    }
  }
  return 0;
}

us_Status us_pair_contacts(const us_Structure *s, int i, int j, double tol, us_CandList *out,
                           us_Error *err) {
  int from = out->n;
  if (vertices_on_edges(s, i, j, tol, from, out) || vertices_on_edges(s, j, i, tol, from, out))
    return us_error_set(err, US_ERR_NOMEM, "out of memory in contact detection");
  return US_OK;
}
