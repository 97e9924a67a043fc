/* Convex hull of a point set in space, as a polyhedron with planar convex
 * faces.
 *
 * Incremental construction on a triangulated hull with conflict lists
 * (Clarkson and Shor; the "outside sets" of Quickhull). Coordinates are
 * shifted by the centre of the points' box (results are translation
 * invariant; the output keeps the input coordinates bit for bit)
 * and scaled by a power of two to a box of side about 1 (exact, so results
 * are scale invariant too, and sides from 1e-300 to 1e300 square without
 * overflow or underflow). Steps:
 *  1. A starting tetrahedron from extreme points: p0 of least x, p1
 *     farthest from p0, p2 farthest from the line p0 p1, p3 farthest from
 *     the plane p0 p1 p2. When one of those distances is <= tol every
 *     point lies within about tol of a line or plane: US_HULL_FLAT.
 *  2. Every other point is put in the conflict list of the triangle it is
 *     farthest above, if more than tol; the others are dropped. While a
 *     triangle has a list, the point of it farthest above it is added
 *     (Quickhull's choice: that point is a vertex of the hull, so points
 *     on edges and faces never come before the corners that make them
 *     redundant): the triangles it sees (more than tol above their plane,
 *     so exactly coplanar triangles of grid-like inputs, whose heights are
 *     rounding noise, stay and cannot pinch the horizon; found by a walk
 *     over neighbours from its own triangle, so the set is connected) are
 *     removed and their boundary (the horizon, which must be one simple
 *     cycle, else US_HULL_FAIL) is joined to the point. The
 *     points of the removed triangles' lists go to the new triangle they
 *     are farthest above (more than tol), else to an old triangle across
 *     the horizon they are more than tol above, else they are dropped.
 *     Why the new triangles suffice: a point p above a removed triangle F
 *     and outside the new hull H' sees the segment from p to F's interior
 *     leave H' through a face lying strictly above F's plane; the old
 *     triangles all lie below that plane, so the face is a new one.
 *  3. Triangles become faces: in order of decreasing area, an unassigned
 *     triangle seeds a face and takes every neighbouring triangle (through
 *     shared edges, transitively) whose three vertices lie within tol of
 *     the seed's plane and which faces the same way; the face's polygon is
 *     the planar hull (geometry3.h, us_hull2, same tol) of its vertices in
 *     the seed plane, so vertices within tol of a face's edge or interior
 *     disappear. Each face's normal is its Newell normal (area-weighted,
 *     robust for nearly collinear corners) and d the largest n . v over
 *     its vertices.
 * Invariants of the output: faces counter-clockwise seen from outside;
 * every input point within about tol inside every face plane; only
 * vertices some face uses are kept; edges listed once, (i, j) with i < j.
 * Cost: each point is tested against the triangles created near it, so
 * about O(n log n) for points in general position (a 1,000,000-point
 * sphere in 4.8 s of CPU here, docs/format.md); the worst case (every point a
 * hull vertex seeing a horizon as long as the hull) stays quadratic.
 * Removed triangles' slots are reused, so memory follows the live hull.
 * A deadline (a us_now() time) is read every 1024 points: US_HULL_TIMEOUT.
 * Why our own and not libqhull_r: measured on this machine, see
 * docs/format.md ("Hull cost"); the output contract (tol semantics, faces
 * merged within tol, vertices bit for bit) is this file's, and step 3 is
 * needed either way. */
#include "geometry3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct Tri {
  int v[3];  /* counter-clockwise seen from outside */
  int nb[3]; /* triangle across edge k = (v[k], v[k+1]) */
  us_Vec3 n; /* outward unit normal */
  double d;  /* n . q for q on the plane */
  int alive;
} Tri;

typedef struct Hull {
  const double *xyz;
  us_Vec3 *q;     /* shifted points */
  int n;
  double tol, deadline;
  Tri *t;
  int nt, cap;    /* triangle slots used (live or free) */
  int *stamp;     /* per triangle: visit mark */
  int *head;      /* per triangle: first point of its conflict list, or -1 */
  int *far;       /* per triangle: the point of its list farthest above it */
  double *fard;   /* per triangle: that point's height */
  int mark;
  int *stack, *vis, *newt, *freet, *work, cap_stamp, cap_head, cap_far, cap_fard, cap_stack,
      cap_vis, cap_newt, cap_free, cap_work;
  int nnew, nfree, nwork; /* triangles made by the last point; free slots;
                             triangles that took points (to visit) */
  int *hstart, *hend; /* per point: horizon edge starting / ending there */
  int *owner, *next;  /* per point: its triangle (-1: none) and list link */
} Hull;

/* A slot for a new triangle: a freed one, else appended (-1: no memory). */
static int new_slot(Hull *h) {
  if (h->nfree > 0) return h->freet[--h->nfree];
  if (US_GROW(h->t, h->cap, h->nt + 1) || US_GROW(h->stamp, h->cap_stamp, h->nt + 1) ||
      US_GROW(h->head, h->cap_head, h->nt + 1) || US_GROW(h->far, h->cap_far, h->nt + 1) ||
      US_GROW(h->fard, h->cap_fard, h->nt + 1))
    return -1;
  return h->nt++;
}

/* Add triangle (a, b, c); its index or -1 (out of memory or degenerate). */
static int add_tri(Hull *h, int a, int b, int c, int *nomem) {
  us_Vec3 n = us_v3_cross(us_v3_sub(h->q[b], h->q[a]), us_v3_sub(h->q[c], h->q[a]));
  if (!(us_v3_norm(n) > 0)) return -1;
  int k = new_slot(h);
  if (k < 0) {
    *nomem = 1;
    return -1;
  }
  Tri *t = &h->t[k];
  t->v[0] = a, t->v[1] = b, t->v[2] = c;
  t->nb[0] = t->nb[1] = t->nb[2] = -1;
  t->n = us_v3_unit(n);
  t->d = us_v3_dot(t->n, h->q[a]);
  t->alive = 1;
  h->stamp[k] = 0;
  h->head[k] = -1;
  return k;
}

static double height(const Hull *h, int t, int i) { return us_v3_dot(h->t[t].n, h->q[i]) - h->t[t].d; }

/* Index of the point farthest from point a (largest key). */
static int farthest(const Hull *h, double (*key)(const Hull *, int, const int *), const int *s) {
  int best = 0;
  double bd = -1.0;
  for (int i = 0; i < h->n; i++) {
    double k = key(h, i, s);
    if (k > bd) bd = k, best = i;
  }
  return best;
}
static double key_point(const Hull *h, int i, const int *s) { return us_v3_dist(h->q[i], h->q[s[0]]); }
static double key_line(const Hull *h, int i, const int *s) {
  us_Vec3 u = us_v3_unit(us_v3_sub(h->q[s[1]], h->q[s[0]]));
  return us_v3_norm(us_v3_cross(us_v3_sub(h->q[i], h->q[s[0]]), u));
}
static double key_plane(const Hull *h, int i, const int *s) {
  us_Vec3 n = us_v3_unit(us_v3_cross(us_v3_sub(h->q[s[1]], h->q[s[0]]), us_v3_sub(h->q[s[2]], h->q[s[0]])));
  return fabs(us_v3_dot(n, us_v3_sub(h->q[i], h->q[s[0]])));
}

/* Step 1: the starting tetrahedron's points, or US_HULL_FLAT. */
static us_HullStatus start_points(const Hull *h, int s[4]) {
  s[0] = 0;
  for (int i = 1; i < h->n; i++)
    if (h->q[i].x < h->q[s[0]].x) s[0] = i;
  s[1] = farthest(h, key_point, s);
  if (!(key_point(h, s[1], s) > h->tol)) return US_HULL_FLAT;
  s[2] = farthest(h, key_line, s);
  if (!(key_line(h, s[2], s) > h->tol)) return US_HULL_FLAT;
  s[3] = farthest(h, key_plane, s);
  if (!(key_plane(h, s[3], s) > h->tol)) return US_HULL_FLAT;
  return US_HULL_OK;
}

/* Link every edge of the first nt triangles to its twin (brute force: the
 * tetrahedron only). */
static void link_brute(Hull *h) {
  for (int a = 0; a < h->nt; a++)
    for (int k = 0; k < 3; k++)
      for (int b = 0; b < h->nt; b++)
        for (int m = 0; m < 3; m++)
          if (h->t[b].v[m] == h->t[a].v[(k + 1) % 3] && h->t[b].v[(m + 1) % 3] == h->t[a].v[k])
            h->t[a].nb[k] = b;
}

static us_HullStatus tetrahedron(Hull *h, const int s[4]) {
  static const int faces[4][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}};
  us_Vec3 centre = us_v3(0, 0, 0);
  for (int k = 0; k < 4; k++) centre = us_v3_add(centre, us_v3_scale(h->q[s[k]], 0.25));
  for (int f = 0; f < 4; f++) {
    int a = s[faces[f][0]], b = s[faces[f][1]], c = s[faces[f][2]], nomem = 0;
    us_Vec3 n = us_v3_cross(us_v3_sub(h->q[b], h->q[a]), us_v3_sub(h->q[c], h->q[a]));
    if (us_v3_dot(n, us_v3_sub(centre, h->q[a])) > 0) b = s[faces[f][2]], c = s[faces[f][1]];
    if (add_tri(h, a, b, c, &nomem) < 0) return nomem ? US_HULL_NOMEM : US_HULL_FAIL;
  }
  link_brute(h);
  return US_HULL_OK;
}

typedef struct Key {
  double k;
  int i;
} Key;

static int key_desc(const void *pa, const void *pb) {
  const Key *a = pa, *b = pb;
  if (a->k != b->k) return a->k > b->k ? -1 : 1;
  return (a->i > b->i) - (a->i < b->i);
}

/* Of the m triangles in ts (live), the one point i is farthest above, if
 * more than tol (its height in *d); with `across`, the triangle across
 * each one's edge 0. */
static int best_of(const Hull *h, int i, const int *ts, int m, int across, double *d) {
  int best = -1;
  *d = h->tol;
  for (int k = 0; k < m; k++) {
    int t = across ? h->t[ts[k]].nb[0] : ts[k];
    double e = height(h, t, i);
    if (e > *d) *d = e, best = t;
  }
  return best;
}

/* Put point i, d above triangle t, in t's conflict list (t < 0: drop it);
 * a triangle's first point puts it on the work list. */
static int assign(Hull *h, int i, int t, double d) {
  h->owner[i] = t;
  if (t < 0) return 0;
  if (h->head[t] < 0) {
    if (US_GROW(h->work, h->cap_work, h->nwork + 1)) return -1;
    h->work[h->nwork++] = t, h->fard[t] = -1.0;
  }
  if (d > h->fard[t]) h->far[t] = i, h->fard[t] = d;
  h->next[i] = h->head[t];
  h->head[t] = i;
  return 0;
}

/* The connected set of triangles point i is above, from t0, in h->vis;
 * their stamp is h->mark. Returns the count (-1: out of memory). */
static int visible_set(Hull *h, int i, int t0) {
  if (US_GROW(h->stack, h->cap_stack, h->nt + 1) || US_GROW(h->vis, h->cap_vis, h->nt + 1)) return -1;
  int ns = 0, nv = 0;
  h->stack[ns++] = t0;
  h->stamp[t0] = ++h->mark;
  while (ns > 0) {
    int t = h->stack[--ns];
    h->vis[nv++] = t;
    for (int k = 0; k < 3; k++) {
      int u = h->t[t].nb[k];
      if (u >= 0 && h->stamp[u] != h->mark && height(h, u, i) > h->tol) {
        h->stamp[u] = h->mark;
        h->stack[ns++] = u;
      }
    }
  }
  return nv;
}

/* Set u's link that pointed to old (across edge a-b) to now. */
static void relink(Hull *h, int u, int old, int now) {
  for (int k = 0; k < 3; k++)
    if (h->t[u].nb[k] == old) h->t[u].nb[k] = now;
}

/* Step 2 for one point: join the horizon of the visible set to i; the
 * new triangles are listed in h->newt. */
static us_HullStatus add_point(Hull *h, int i, int nv) {
  int nh = 0, nomem = 0;
  us_HullStatus st = US_HULL_OK;
  h->nnew = 0;
  for (int q = 0; q < nv && !st; q++) {
    int t = h->vis[q];
    for (int k = 0; k < 3 && !st; k++) {
      int u = h->t[t].nb[k], a = h->t[t].v[k], b = h->t[t].v[(k + 1) % 3];
      if (h->stamp[u] == h->mark) continue;
      if (h->hstart[a] >= 0 || h->hend[b] >= 0) st = US_HULL_FAIL; /* not a simple cycle */
      int nt = st ? -1 : add_tri(h, a, b, i, &nomem);
      if (nt < 0) st = nomem ? US_HULL_NOMEM : US_HULL_FAIL;
      if (!st && US_GROW(h->newt, h->cap_newt, h->nnew + 1)) st = US_HULL_NOMEM;
      if (st) break;
      h->newt[h->nnew++] = nt;
      h->t[nt].nb[0] = u;
      relink(h, u, t, nt);
      h->hstart[a] = nt, h->hend[b] = nt, nh++;
    }
  }
  for (int k = 0; k < h->nnew && !st; k++) {
    int t = h->newt[k], a = h->t[t].v[0], b = h->t[t].v[1];
    if (h->hstart[b] < 0 || h->hend[a] < 0) st = US_HULL_FAIL;
    else h->t[t].nb[1] = h->hstart[b], h->t[t].nb[2] = h->hend[a];
  }
  for (int k = 0; k < h->nnew; k++) {
    int t = h->newt[k];
    h->hstart[h->t[t].v[0]] = h->hend[h->t[t].v[1]] = -1;
  }
  return nh >= 3 || st ? st : US_HULL_FAIL;
}

/* After add_point: the removed triangles' points go to the new triangles
 * (or across the horizon, or are dropped) and their slots are freed. */
static us_HullStatus redistribute(Hull *h, int nv) {
  if (US_GROW(h->freet, h->cap_free, h->nfree + nv)) return US_HULL_NOMEM;
  for (int q = 0; q < nv; q++) {
    int t = h->vis[q];
    for (int p = h->head[t], nx; p >= 0; p = nx) {
      nx = h->next[p];
      if (h->owner[p] != t) continue; /* the point added */
      double d;
      int to = best_of(h, p, h->newt, h->nnew, 0, &d);
      if (to < 0) to = best_of(h, p, h->newt, h->nnew, 1, &d);
      if (assign(h, p, to, d)) return US_HULL_NOMEM;
    }
    h->t[t].alive = 0;
    h->freet[h->nfree++] = t;
  }
  return US_HULL_OK;
}

/* The tetrahedron's four triangles take the points that see them. */
static us_HullStatus assign_start(Hull *h, const int s[4]) {
  int tet[4] = {0, 1, 2, 3};
  for (int i = 0; i < h->n; i++) {
    double d = 0.0;
    int t = i == s[0] || i == s[1] || i == s[2] || i == s[3] ? -1 : best_of(h, i, tet, 4, 0, &d);
    if (assign(h, i, t, d)) return US_HULL_NOMEM;
  }
  return US_HULL_OK;
}

/* Step 2: while a triangle has points above it, add the farthest. */
static us_HullStatus insert_all(Hull *h, const int s[4]) {
  us_HullStatus st = assign_start(h, s);
  for (long it = 1; h->nwork > 0 && !st; it++) {
    int t = h->work[--h->nwork];
    if (!h->t[t].alive || h->head[t] < 0) continue; /* removed since */
    if ((it & 1023) == 0 && us_past(h->deadline)) return US_HULL_TIMEOUT;
    int i = h->far[t];
    h->owner[i] = -1;
    int nv = visible_set(h, i, t);
    st = nv < 0 ? US_HULL_NOMEM : add_point(h, i, nv);
    if (!st) st = redistribute(h, nv);
  }
  return st;
}

/* ---------------------------------------------------- step 3: the faces */

typedef struct Faces {
  int *face_of;    /* per triangle: face index or -1 */
  int *tris;       /* triangles of the face being built */
  int *vseen;      /* per point: stamp */
  int *pts, npts;  /* the face's vertices */
  us_Vec2 *uv;
  int *idx, *work;
} Faces;

static double tri_area(const Hull *h, int t) {
  const Tri *x = &h->t[t];
  return us_v3_norm(us_v3_cross(us_v3_sub(h->q[x->v[1]], h->q[x->v[0]]), us_v3_sub(h->q[x->v[2]], h->q[x->v[0]])));
}

static int fits(const Hull *h, int seed, int u) {
  if (us_v3_dot(h->t[seed].n, h->t[u].n) <= 0) return 0;
  for (int k = 0; k < 3; k++)
    if (fabs(height(h, seed, h->t[u].v[k])) > h->tol) return 0;
  return 1;
}

/* The triangles of the face seeded by `seed` (marked with face id f); their
 * distinct vertices go to F->pts. */
static void grow_face(const Hull *h, Faces *F, int seed, int f, int stamp) {
  int nt = 0, head = 0;
  F->tris[nt++] = seed;
  F->face_of[seed] = f;
  F->npts = 0;
  while (head < nt) {
    int t = F->tris[head++];
    for (int k = 0; k < 3; k++) {
      int v = h->t[t].v[k], u = h->t[t].nb[k];
      if (F->vseen[v] != stamp) F->vseen[v] = stamp, F->pts[F->npts++] = v;
      if (u >= 0 && F->face_of[u] < 0 && fits(h, seed, u)) F->face_of[u] = f, F->tris[nt++] = u;
    }
  }
}

/* Output under construction. */
typedef struct Out {
  int *fstart, *fvert, nf, nfv;
  double *nd; /* 4 per face in shifted coordinates: n, then unused */
} Out;

/* Order the face's points by the planar hull in the seed's plane and
 * append it; faces thinner than tol are dropped. */
static void emit_face(const Hull *h, Faces *F, int seed, Out *o) {
  us_Vec3 t1, t2, n = h->t[seed].n;
  us_v3_frame(n, &t1, &t2);
  for (int k = 0; k < F->npts; k++) F->uv[k] = us_v2(us_v3_dot(h->q[F->pts[k]], t1), us_v3_dot(h->q[F->pts[k]], t2));
  int m = us_hull2(F->uv, F->npts, h->tol, F->idx, F->work);
  if (m < 3) return;
  /* Newell's sum with edge vectors from the face's first point: a face whose
   * points share a coordinate exactly (a level face) gets exactly zero
   * there, where absolute points left ~1e-17 of tilt, which mu = 0 turned
   * into spurious slides (tests/test_stability_local3d.c) */
  us_Vec3 nw = us_v3(0, 0, 0), q0 = h->q[F->pts[F->idx[0]]];
  for (int k = 1; k + 1 < m; k++)
    nw = us_v3_add(nw, us_v3_cross(us_v3_sub(h->q[F->pts[F->idx[k]]], q0),
                                   us_v3_sub(h->q[F->pts[F->idx[k + 1]]], q0)));
  nw = us_v3_unit(nw);
  if (!(us_v3_dot(nw, n) > 0)) nw = n;
  o->fstart[o->nf] = o->nfv;
  for (int k = 0; k < m; k++) o->fvert[o->nfv++] = F->pts[F->idx[k]];
  o->nd[4 * o->nf] = nw.x, o->nd[4 * o->nf + 1] = nw.y, o->nd[4 * o->nf + 2] = nw.z;
  o->nf++;
  o->fstart[o->nf] = o->nfv;
}

static int faces_alloc(Faces *F, Out *o, int nt, int n) {
  memset(F, 0, sizeof *F);
  memset(o, 0, sizeof *o);
  F->face_of = us_malloc((size_t)nt * sizeof(int));
  F->tris = us_malloc((size_t)nt * sizeof(int));
  F->vseen = us_calloc((size_t)n, sizeof(int));
  F->pts = us_malloc((size_t)n * sizeof(int));
  F->uv = us_malloc((size_t)n * sizeof(us_Vec2));
  F->idx = us_malloc((size_t)(n + 2) * sizeof(int));
  F->work = us_malloc((size_t)(n + 2) * sizeof(int));
  o->fstart = us_malloc((size_t)(nt + 1) * sizeof(int));
  o->fvert = us_malloc((size_t)3 * (size_t)nt * sizeof(int));
  o->nd = us_malloc((size_t)4 * (size_t)nt * sizeof(double));
  if (o->fstart) o->fstart[0] = 0;
  return F->face_of && F->tris && F->vseen && F->pts && F->uv && F->idx && F->work && o->fstart &&
                 o->fvert && o->nd ? 0 : -1;
}

static void faces_free(Faces *F) {
  us_free(F->face_of), us_free(F->tris), us_free(F->vseen), us_free(F->pts), us_free(F->uv);
  us_free(F->idx), us_free(F->work);
}

static int build_faces(const Hull *h, Out *o) {
  Faces F;
  int rc = faces_alloc(&F, o, h->nt, h->n);
  Key *order = rc ? NULL : us_malloc((size_t)h->nt * sizeof *order);
  int live = 0;
  for (int t = 0; order && t < h->nt; t++) {
    F.face_of[t] = -1;
    if (h->t[t].alive) order[live++] = (Key){tri_area(h, t), t};
  }
  if (order) qsort(order, (size_t)live, sizeof *order, key_desc);
  for (int r = 0; order && r < live; r++) {
    int seed = order[r].i;
    if (F.face_of[seed] >= 0) continue;
    grow_face(h, &F, seed, o->nf, r + 1);
    emit_face(h, &F, seed, o);
  }
  if (!order) rc = -1;
  us_free(order);
  faces_free(&F);
  return rc;
}

/* ------------------------------------------------------ the polyhedron */

static int edge_cmp(const void *pa, const void *pb) {
  const int *a = pa, *b = pb;
  if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
  return (a[1] > b[1]) - (a[1] < b[1]);
}

/* Edges of the faces, each once. */
static int make_edges(us_Polyhedron *p) {
  int m = p->face_start[p->nface], ne = 0;
  p->edges = us_malloc((size_t)(m > 0 ? m : 1) * 2 * sizeof(int));
  if (!p->edges) return -1;
  for (int f = 0; f < p->nface; f++)
    for (int k = 0, s = us_face_size(p, f); k < s; k++) {
      int a = p->face_vert[p->face_start[f] + k], b = p->face_vert[p->face_start[f] + (k + 1) % s];
      p->edges[2 * ne] = US_MIN(a, b), p->edges[2 * ne + 1] = US_MAX(a, b), ne++;
    }
  qsort(p->edges, (size_t)ne, 2 * sizeof(int), edge_cmp);
  int u = 0;
  for (int e = 0; e < ne; e++)
    if (u == 0 || edge_cmp(&p->edges[2 * e], &p->edges[2 * (u - 1)]) != 0)
      p->edges[2 * u] = p->edges[2 * e], p->edges[2 * u + 1] = p->edges[2 * e + 1], u++;
  p->nedge = u;
  return 0;
}

/* Keep the vertices faces use (renumbered in input order), planes in input
 * coordinates, edges and volume. */
static int assemble(const Hull *h, const Out *o, us_Polyhedron *p) {
  int *map = us_malloc((size_t)h->n * sizeof(int));
  if (!map) return -1;
  for (int i = 0; i < h->n; i++) map[i] = -1;
  for (int k = 0; k < o->nfv; k++) map[o->fvert[k]] = 0;
  int nv = 0;
  for (int i = 0; i < h->n; i++)
    if (map[i] >= 0) map[i] = nv++;
  p->nvert = nv, p->nface = o->nf;
  p->verts = us_malloc((size_t)(nv > 0 ? nv : 1) * 3 * sizeof(double));
  p->face_start = us_malloc((size_t)(o->nf + 1) * sizeof(int));
  p->face_vert = us_malloc((size_t)(o->nfv > 0 ? o->nfv : 1) * sizeof(int));
  p->planes = us_malloc((size_t)(o->nf > 0 ? o->nf : 1) * 4 * sizeof(double));
  int rc = p->verts && p->face_start && p->face_vert && p->planes ? 0 : -1;
  for (int i = 0; !rc && i < h->n; i++)
    if (map[i] >= 0) memcpy(p->verts + 3 * map[i], h->xyz + 3 * i, 3 * sizeof(double));
  for (int f = 0; !rc && f <= o->nf; f++) p->face_start[f] = o->fstart[f];
  for (int k = 0; !rc && k < o->nfv; k++) p->face_vert[k] = map[o->fvert[k]];
  for (int f = 0; !rc && f < o->nf; f++) {
    us_Vec3 n = us_v3(o->nd[4 * f], o->nd[4 * f + 1], o->nd[4 * f + 2]);
    double d = -INFINITY;
    for (int k = 0; k < us_face_size(p, f); k++) d = US_MAX(d, us_v3_dot(n, us_face_vertex(p, f, k)));
    p->planes[4 * f] = n.x, p->planes[4 * f + 1] = n.y, p->planes[4 * f + 2] = n.z, p->planes[4 * f + 3] = d;
  }
  us_free(map);
  if (!rc) rc = make_edges(p);
  if (!rc) {
    double m1[3], m2[9];
    us_polyhedron_moments(p, us_v3_at(p->verts, 0), &p->volume, m1, m2);
  }
  return rc;
}

static void hull_free(Hull *h) {
  us_free(h->q), us_free(h->t), us_free(h->stamp), us_free(h->stack), us_free(h->vis);
  us_free(h->hstart), us_free(h->hend), us_free(h->head), us_free(h->newt), us_free(h->freet);
  us_free(h->far), us_free(h->fard), us_free(h->work);
  us_free(h->owner), us_free(h->next);
}

static us_HullStatus hull_init(Hull *h, const double *xyz, int n, double tol, double deadline) {
  memset(h, 0, sizeof *h);
  h->xyz = xyz, h->n = n, h->tol = tol, h->deadline = deadline;
  h->q = us_malloc((size_t)n * sizeof *h->q);
  h->hstart = us_malloc((size_t)n * sizeof(int));
  h->hend = us_malloc((size_t)n * sizeof(int));
  h->owner = us_malloc((size_t)n * sizeof(int));
  h->next = us_malloc((size_t)n * sizeof(int));
  if (!h->q || !h->hstart || !h->hend || !h->owner || !h->next) return US_HULL_NOMEM;
  double bb[6];
  us_points3_bbox(xyz, n, bb);
  us_Vec3 c = us_v3(0.5 * (bb[0] + bb[3]), 0.5 * (bb[1] + bb[4]), 0.5 * (bb[2] + bb[5]));
  /* scaled by a power of two (exact) to a box of side about 1, so that
   * squares of lengths (norms, cross products) neither overflow (sides
   * near 1e101) nor underflow (sides near 1e-300); tol with them */
  int e = 0;
  frexp(US_MAX(US_MAX(bb[3] - bb[0], bb[4] - bb[1]), bb[5] - bb[2]), &e);
  h->tol = ldexp(tol, -e);
  for (int i = 0; i < n; i++) {
    us_Vec3 d = us_v3_sub(us_v3_at(xyz, i), c);
    h->q[i] = us_v3(ldexp(d.x, -e), ldexp(d.y, -e), ldexp(d.z, -e));
    h->hstart[i] = h->hend[i] = -1;
  }
  return US_HULL_OK;
}

us_HullStatus us_hull3(const double *xyz, int n, double tol, us_Polyhedron *out) {
  return us_hull3_until(xyz, n, tol, 0.0, out);
}

us_HullStatus us_hull3_until(const double *xyz, int n, double tol, double deadline,
                             us_Polyhedron *out) {
  memset(out, 0, sizeof *out);
  if (n < 4) return US_HULL_FLAT;
  Hull h;
  int s[4];
  Out o = {0};
  us_HullStatus st = hull_init(&h, xyz, n, tol, deadline);
  if (!st) st = start_points(&h, s);
  if (!st) st = tetrahedron(&h, s);
  if (!st) st = insert_all(&h, s);
  if (!st && build_faces(&h, &o)) st = US_HULL_NOMEM;
  if (!st && o.nf < 4) st = US_HULL_FLAT;
  if (!st && assemble(&h, &o, out)) st = US_HULL_NOMEM;
  us_free(o.fstart), us_free(o.fvert), us_free(o.nd);
  hull_free(&h);
  if (st) us_polyhedron_free(out);
  return st;
}
