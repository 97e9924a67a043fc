/* Contact detection in 3D: the contacts of a structure's convex parts with
 * each other and with the ground (the plane z = 0), returned as a list.
 *
 * Tolerances follow the bodies involved exactly as in 2D (detect.c): a
 * body's own is US_GEOM_TOL_REL times its bounding-box diagonal (over all
 * its parts), a pair's the smaller of the two, a body against the ground
 * its own; a tolerance in the settings replaces them all.
 *
 * A pair of parts (P of body i, Q of body j, i < j) whose boxes meet
 * (padded by tol) gets the separating-axis test (geometry/sat3.c): its
 * largest axis gap S. S > tol: apart. S < -tol: they interpenetrate by
 * -S, US_ERR_INPUT naming both bodies. Otherwise they touch, and each
 * *touching direction* gives a patch:
 *  - every face normal of P or Q along which the gap is >= -tol (the
 *    parts touch across that plane within tol), taken once per direction
 *    (normals within US_CONTACT_NORMAL_COS of an earlier one are the same);
 *  - when no face normal touches (edge on edge, corner on corner), the
 *    test's best axis.
 * Two touching directions arise only where the contact normal is not
 * defined (boxes meeting edge to edge, diagonally); each is an admissible
 * normal, as 2D keeps both normals of corner-on-corner contacts.
 *
 * The patch of direction u (unit, oriented from P into Q): P's support
 * set SA (vertices with u . v >= max - tol) and Q's SB (u . v <= min +
 * tol) are projected on the plane normal to u (frame us_v3_frame(u)); each
 * projection's planar hull (us_hull2, tol) is a point, a segment or a
 * convex polygon, so one rule covers face on face (coplanar and opposed
 * faces: the intersection of the two polygons), edge on face, vertex on
 * face and edge across edge. The intersection of the two hulls is the
 * hull of: the vertices of each inside the other (within tol) and the
 * proper crossings of their edges. Its vertices, lifted to the mid-plane
 * u . x = (max_P + min_Q) / 2, are the contact points, with normal u, a = i,
 * b = j. The ground is the half-space z <= 0 with an infinite face, so a
 * body's ground patch is the hull of its support set at the bottom when
 * that lies within tol of z = 0 (movable bodies only).
 *
 * A point within tol of an earlier point of the same pair (or the same
 * body on the ground) with a normal within US_CONTACT_NORMAL_COS is a
 * duplicate (parts of a compound sharing a corner). Order: ground contacts
 * in body order, then pairs in (i, j) order, parts in order, directions in
 * order, patch points counter-clockwise about u from the least (t1, t2)
 * corner: it depends only on the input. Cost: the broad phase (shared with
 * 2D) and, per touching pair of parts, the axis test, which grows with
 * the product of their edge directions (microseconds for blocks). */
#include "contact.h"

#include "geometry/geometry3.h"

#include <math.h>
#include <string.h>

typedef struct Det3 {
  const us_Structure *s;
  const double *tol;
  us_ContactList *out;
  /* scratch of one patch, grown as needed */
  us_Vec2 *uv, *pts;
  int *ia, *ib, *idx, *work;
  int cap_uv, cap_pts, cap_ia, cap_ib, cap_idx, cap_work;
} Det3;

static us_Status nomem(us_Error *err) {
  return us_error_set(err, US_ERR_NOMEM, "out of memory in contact detection");
}

/* Room for n support points and the intersection's candidates (at most
 * the vertices of both hulls and two crossings per edge of either). */
static int reserve(Det3 *d, int n) {
  int m = 4 * n + 8;
  return US_GROW(d->uv, d->cap_uv, n) || US_GROW(d->ia, d->cap_ia, n + 2) ||
                 US_GROW(d->ib, d->cap_ib, n + 2) || US_GROW(d->pts, d->cap_pts, (int)m) ||
                 US_GROW(d->idx, d->cap_idx, (int)m + 2) || US_GROW(d->work, d->cap_work, (int)m + 2)
             ? -1
             : 0;
}

/* Is contact (p, n) a duplicate of one of out's entries from `from` on? */
static int duplicate(const us_ContactList *l, int from, us_Vec3 p, us_Vec3 n, double tol) {
  for (int k = from; k < l->n; k++) {
    const us_Contact *c = &l->c[k];
    if (us_v3_dist(p, us_v3(c->p[0], c->p[1], c->p[2])) <= tol &&
        us_v3_dot(n, us_v3(c->n[0], c->n[1], c->n[2])) >= US_CONTACT_NORMAL_COS)
      return 1;
  }
  return 0;
}

static int push(us_ContactList *l, int from, int a, int b, us_Vec3 p, us_Vec3 n, double tol) {
  if (duplicate(l, from, p, n, tol)) return 0;
  if (US_GROW(l->c, l->cap, l->n + 1)) return -1;
  us_Contact *c = &l->c[l->n++];
  memset(c, 0, sizeof *c);
  c->a = a, c->b = b;
  c->p[0] = p.x, c->p[1] = p.y, c->p[2] = p.z;
  c->n[0] = n.x + 0.0, c->n[1] = n.y + 0.0, c->n[2] = n.z + 0.0; /* no -0 */
  c->mu = -1.0;
  return 0;
}

/* Projection frame of one patch: origin r, tangents t1, t2, normal u. */
typedef struct Frame {
  us_Vec3 r, t1, t2, u;
} Frame;

static us_Vec2 to_plane(const Frame *f, us_Vec3 v) {
  us_Vec3 w = us_v3_sub(v, f->r);
  return us_v2(us_v3_dot(w, f->t1), us_v3_dot(w, f->t2));
}

static us_Vec3 to_space(const Frame *f, us_Vec2 q, double h) {
  us_Vec3 p = us_v3_add(f->r, us_v3_add(us_v3_scale(f->t1, q.x), us_v3_scale(f->t2, q.y)));
  return us_v3_add(p, us_v3_scale(f->u, h - us_v3_dot(f->u, f->r)));
}

/* The planar hull of p's vertices with side * u . v >= ext - tol (the
 * support set on that side), as points uv[hull[k]]; returns its size. The
 * hull's indices go to hull (room n + 2). */
static int support_hull(Det3 *d, const Frame *f, const us_Polyhedron *p, double side, double ext,
                        double tol, us_Vec2 *uv, int *hull) {
  int m = 0;
  for (int k = 0; k < p->nvert; k++) {
    us_Vec3 v = us_v3_at(p->verts, k);
    if (side * us_v3_dot(f->u, v) >= ext - tol) uv[m++] = to_plane(f, v);
  }
  return us_hull2(uv, m, tol, hull, d->work);
}

/* Is q inside (within tol) the planar hull h[0..m) of points uv? */
static int in_hull(const us_Vec2 *uv, const int *h, int m, us_Vec2 q, double tol) {
  if (m == 1) return us_v2_dist(uv[h[0]], q) <= tol;
  if (m == 2) return us_point_segment_dist(q, uv[h[0]], uv[h[1]], NULL) <= tol;
  for (int k = 0; k < m; k++) {
    us_Vec2 a = uv[h[k]], b = uv[h[(k + 1) % m]];
    if (us_orient(a, b, q) < -tol * us_v2_dist(a, b)) return 0;
  }
  return 1;
}

/* Edges of a hull of m points: m for a polygon, 1 for a segment, 0. */
static int hull_edges(int m) { return m >= 3 ? m : m - 1; }

/* Candidates of the intersection of hulls A (ua, ha, ma) and B: vertices of
 * each inside the other and proper edge crossings, into d->pts. */
static int intersect(Det3 *d, const us_Vec2 *ua, const int *ha, int ma, const us_Vec2 *ub,
                     const int *hb, int mb, double tol) {
  int n = 0, cap = d->cap_pts;
  for (int k = 0; k < ma; k++)
    if (in_hull(ub, hb, mb, ua[ha[k]], tol)) d->pts[n++] = ua[ha[k]];
  for (int k = 0; k < mb; k++)
    if (in_hull(ua, ha, ma, ub[hb[k]], tol)) d->pts[n++] = ub[hb[k]];
  for (int e = 0; e < hull_edges(ma); e++)
    for (int g = 0; g < hull_edges(mb) && n < cap; g++) {
      us_Vec2 a0 = ua[ha[e]], a1 = ua[ha[(e + 1) % ma]], b0 = ub[hb[g]], b1 = ub[hb[(g + 1) % mb]];
      double t;
      if (us_segment_intersect(a0, a1, b0, b1, &t, NULL) == US_SEG_PROPER)
        d->pts[n++] = us_v2_add(a0, us_v2_scale(us_v2_sub(a1, a0), t));
    }
  return n;
}

/* Emit the hull of the n candidate points at height h. */
static int emit(Det3 *d, const Frame *f, int n, double h, int a, int b, int from, double tol) {
  int m = us_hull2(d->pts, n, tol, d->idx, d->work);
  for (int k = 0; k < m; k++)
    if (push(d->out, from, a, b, to_space(f, d->pts[d->idx[k]], h), f->u, tol)) return -1;
  return 0;
}

/* The patch of direction u between parts P (body a) and Q (body b). */
static int patch(Det3 *d, const us_Polyhedron *P, const us_Polyhedron *Q, us_Vec3 u, int a, int b,
                 int from, double tol) {
  if (reserve(d, P->nvert + Q->nvert)) return -1;
  Frame f = {us_v3_at(P->verts, 0), us_v3(0, 0, 0), us_v3(0, 0, 0), u};
  us_v3_frame(u, &f.t1, &f.t2);
  double alo, ahi, blo, bhi;
  us_polyhedron_project(P, u, &alo, &ahi);
  us_polyhedron_project(Q, u, &blo, &bhi);
  us_Vec2 *ua = d->uv, *ub = d->uv + P->nvert;
  int ma = support_hull(d, &f, P, 1.0, ahi, tol, ua, d->ia);
  int mb = support_hull(d, &f, Q, -1.0, -blo, tol, ub, d->ib);
  int n = intersect(d, ua, d->ia, ma, ub, d->ib, mb, tol);
  return emit(d, &f, n, 0.5 * (ahi + blo), a, b, from, tol);
}

/* Is u within the normal tolerance of one of the used directions? */
static int used_dir(const us_Vec3 *used, int nu, us_Vec3 u) {
  for (int k = 0; k < nu; k++)
    if (us_v3_dot(used[k], u) >= US_CONTACT_NORMAL_COS) return 1;
  return 0;
}

/* The face axes of P and Q whose gap is >= -tol (touching directions,
 * oriented from P to Q, parallel ones once) into dir[] (at most MAX_DIRS;
 * *nd their count); returns the largest face-axis gap and its axis. */
#define MAX_DIRS 32
static double face_gaps(const us_Polyhedron *P, const us_Polyhedron *Q, double tol, us_Vec3 *dir,
                        int *nd, us_Vec3 *best_axis) {
  double best = -INFINITY;
  *nd = 0;
  for (int side = 0; side < 2; side++) {
    const us_Polyhedron *F = side ? Q : P;
    for (int k = 0; k < F->nface; k++) {
      us_Vec3 u;
      double g = us_axis_gap(P, Q, us_face_normal(F, k), &u);
      if (g > best) best = g, *best_axis = u;
      if (g > tol) return g; /* apart */
      if (g >= -tol && *nd < MAX_DIRS && !used_dir(dir, *nd, u)) dir[(*nd)++] = u;
    }
  }
  return best;
}

static us_Status overlap_error(const us_Structure *s, int i, int j, int pi, int pj, double depth,
                               us_Error *err) {
  const us_Body *a = &s->bodies[i], *b = &s->bodies[j];
  char pa[32] = "", pb[32] = "";
  if (a->npart > 1) snprintf(pa, sizeof pa, " (part %d)", pi);
  if (b->npart > 1) snprintf(pb, sizeof pb, " (part %d)", pj);
  return us_error_set(err, US_ERR_INPUT, "bodies '%s'%s and '%s'%s overlap (penetration depth %g)",
                      us_id_text(a->id).s, pa, us_id_text(b->id).s, pb, depth);
}

static int boxes_meet(const us_Polyhedron *P, const us_Polyhedron *Q, double tol) {
  double a[6], b[6];
  us_points3_bbox(P->verts, P->nvert, a);
  us_points3_bbox(Q->verts, Q->nvert, b);
  for (int k = 0; k < 3; k++)
    if (a[k] > b[k + 3] + tol || b[k] > a[k + 3] + tol) return 0;
  return 1;
}

/* Contacts (or the overlap error) of bodies i < j, tolerance tol. */
static us_Status pair3(Det3 *d, int i, int j, double tol, us_Error *err) {
  const us_Body *A = &d->s->bodies[i], *B = &d->s->bodies[j];
  int from = d->out->n;
  for (int pi = 0; pi < A->npart; pi++)
    for (int pj = 0; pj < B->npart; pj++) {
      const us_Polyhedron *P = &A->parts[pi], *Q = &B->parts[pj];
      if (!boxes_meet(P, Q, tol)) continue;
      us_Vec3 axis = us_v3(0, 0, 1), dir[MAX_DIRS];
      int nd = 0;
      double sep = face_gaps(P, Q, tol, dir, &nd, &axis);
      if (sep <= tol) sep = us_edge_separation(P, Q, tol, sep, &axis);
      if (sep > tol) continue;
      if (sep < -tol) return overlap_error(d->s, i, j, pi, pj, -sep, err);
      if (nd == 0) dir[nd++] = axis; /* no face touches: edge on edge, corners */
      for (int k = 0; k < nd; k++)
        if (patch(d, P, Q, dir[k], i, j, from, tol)) return nomem(err);
    }
  return US_OK;
}

/* Body i on the ground: each part's support set at the bottom, when it
 * lies within tol of z = 0. */
static int ground3(Det3 *d, int i) {
  const us_Body *b = &d->s->bodies[i];
  double tol = d->tol[i];
  int from = d->out->n;
  for (int k = 0; k < b->npart; k++) {
    const us_Polyhedron *Q = &b->parts[k];
    double lo, hi;
    us_polyhedron_project(Q, us_v3(0, 0, 1), &lo, &hi);
    if (fabs(lo) > tol) continue;
    if (reserve(d, Q->nvert)) return -1;
    Frame f = {us_v3(0, 0, 0), us_v3(0, 0, 0), us_v3(0, 0, 0), us_v3(0, 0, 1)};
    us_v3_frame(f.u, &f.t1, &f.t2);
    int m = support_hull(d, &f, Q, -1.0, -lo, tol, d->uv, d->ib);
    for (int q = 0; q < m; q++) d->pts[q] = d->uv[d->ib[q]];
    if (emit(d, &f, m, 0.5 * lo, US_GROUND, i, from, tol)) return -1;
  }
  return 0;
}

static void det_free(Det3 *d) {
  us_free(d->uv), us_free(d->pts), us_free(d->ia), us_free(d->ib), us_free(d->idx), us_free(d->work);
}

us_Status us_detect_contacts3(const us_Structure *s, const double *tol, int reference,
                              double deadline, us_ContactList *out, us_Error *err) {
  Det3 d = {s, tol, out, NULL, NULL, NULL, NULL, NULL, NULL, 0, 0, 0, 0, 0, 0};
  us_Status st = US_OK;
  for (int i = 0; !st && s->ground && i < s->nbody; i++)
    if (!s->bodies[i].fixed && s->bodies[i].npart > 0 && ground3(&d, i)) st = nomem(err);
  us_BodyPair *pairs = NULL;
  int np = 0;
  if (!st) st = reference ? us_broadphase_all(s, &pairs, &np, err) : us_broadphase(s, tol, &pairs, &np, err);
  for (int k = 0; !st && k < np; k++)
    st = (k & 1023) == 1023 && us_past(deadline)
             ? us_detect_timeout(k, np, err)
             : pair3(&d, pairs[k].i, pairs[k].j, US_MIN(tol[pairs[k].i], tol[pairs[k].j]), err);
  us_free(pairs);
  det_free(&d);
  if (st) out->n = 0;
  return st;
}
