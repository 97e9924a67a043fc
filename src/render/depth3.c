/* The painter's order of a 3D scene's faces, and which of the marks drawn
 * over the faces (labels, contact dots, force arrows, hand rings, mechanism
 * arrows) a nearer body covers.
 *
 * Order. The faces come grouped by convex part (a node; a body without
 * geometry is a node too). Within one convex part back-face culling alone
 * is exact: its front faces never overlap. Between two parts P and Q whose
 * pictures overlap, the one in front is found where they overlap: of the
 * pairs of front faces (f of P, g of Q) the one whose projected polygons
 * share the largest area (at least AREA_EPS px^2), and at the centroid of
 * that common area the depths of the two face planes (larger is nearer;
 * a difference within DEPTH_RTOL of the pair's own projected size is a
 * tie: no relation). For convex parts with disjoint interiors the answer
 * is the same at every pixel of the overlap (a plane separates them and
 * every view ray crosses it the same way), so the edge "Q before P" holds
 * whatever the faces' sizes, unlike the order by face centroids, which
 * paints a long beam's top face over a box resting on its far end. The
 * nodes are drawn in a topological order of these edges (Kahn), taking of
 * the nodes free to go the farthest by mean face depth (then the first
 * collected), so that unrelated nodes keep the depth order. Overlapping
 * cycles (three sticks each lying over the next; interpenetrating parts)
 * have no painter's order: a cycle is broken at its farthest node, drawn
 * as if free, and is then wrong where the cycle's parts overlap (a depth
 * buffer or split faces would be needed there).
 *
 * Covering. A mark belongs to one or two bodies (a label, a hand ring, a
 * mechanism arrow to its body; a contact's dot and force arrows to the two
 * touching bodies, seen through each other). What nearer bodies cover of
 * it is what the nodes painted after its bodies' last node overlap: were
 * the mark painted in the order right after its bodies, they would paint
 * over it. A label is painted there (the writers draw it right after its
 * body's last face), so nearer faces cut it where they overlap it; it is
 * left out when they cover more than LABEL_SHARE of its box (a word
 * mostly hidden reads wrong). The other marks are drawn over all faces, in
 * groups of their own, and are left out whole when covered at all: a box
 * around a ring or dot by more than COVER_AREA, a segment (an arrow's
 * shaft, head included) by more than COVER_LEN. In 2D there is no order
 * (sc->depth is NULL) and nothing is covered. */
#include "render/render.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define AREA_EPS 1e-3   /* px^2: a smaller common area relates no parts */
#define DEPTH_RTOL 1e-9 /* depth ties, relative to the pair's projected size */
#define COVER_AREA 1.0  /* px^2 of a mark's box covered that hides the mark */
#define LABEL_SHARE 0.25 /* share of a label's box covered that hides it */
#define COVER_LEN 0.5   /* px of an arrow covered that hides it */

typedef struct Node {
  int body, first, count; /* entries first .. first + count - 1 of sc->bodies */
  double bb[4];           /* projected bounding box, px: xmin, ymin, xmax, ymax */
  double key;             /* mean depth of its faces' centroids */
} Node;

struct us_Depth {
  int nnode, nbody;
  Node *node;   /* in the painter's order once ordered */
  int *last;    /* per body: position of its last node, -1 for none */
  double *buf;  /* clipping scratch: two polygons of cap points */
  int cap;
};

/* ------------------------------------------------------------ polygons */

static double cross(const double *o, const double *a, const double *b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/* Twice the signed area of p (n points), and its centroid into c when
 * c is given and the area is not zero. */
static double area2(const double *p, int n, double *c) {
  double a = 0.0, cx = 0.0, cy = 0.0;
  for (int i = 0; i < n; i++) {
    const double *s = p + 2 * i, *t = p + 2 * ((i + 1) % n);
    double w = s[0] * t[1] - t[0] * s[1];
    a += w, cx += (s[0] + t[0]) * w, cy += (s[1] + t[1]) * w;
  }
  if (c && a != 0.0) c[0] = cx / (3.0 * a), c[1] = cy / (3.0 * a);
  return a;
}

/* p (n points) cut to the side of the line a->b where sign * cross >= 0,
 * into out; its count (at most n + 1). */
static int cut(const double *p, int n, const double *a, const double *b, double sign,
               double *out) {
  int m = 0;
  for (int i = 0; i < n; i++) {
    const double *c = p + 2 * i, *d = p + 2 * ((i + 1) % n);
    double sc = sign * cross(a, b, c), sd = sign * cross(a, b, d);
    if (sc >= 0) out[2 * m] = c[0], out[2 * m + 1] = c[1], m++;
    if ((sc >= 0) != (sd >= 0)) {
      double t = sc / (sc - sd);
      out[2 * m] = c[0] + t * (d[0] - c[0]), out[2 * m + 1] = c[1] + t * (d[1] - c[1]), m++;
    }
  }
  return m;
}

/* The area common to p (np points) and the convex polygon q (nq), its
 * centroid into c; buf holds two polygons of np + nq points. */
static double common_area(const double *p, int np, const double *q, int nq, double *buf,
                          int cap, double c[2]) {
  double sign = area2(q, nq, NULL) > 0 ? 1.0 : -1.0;
  const double *src = p;
  int n = np;
  for (int i = 0; i < nq && n > 2; i++) {
    double *dst = buf + (size_t)(i % 2) * 2 * (size_t)cap;
    n = cut(src, n, q + 2 * i, q + 2 * ((i + 1) % nq), sign, dst);
    src = dst;
  }
  return n > 2 ? fabs(0.5 * area2(src, n, c)) : 0.0;
}

/* Length of the segment s (x1, y1, x2, y2) inside the convex polygon q. */
static double inside_length(const double *s, const double *q, int nq) {
  double a = area2(q, nq, NULL), sign = a > 0 ? 1.0 : -1.0, t0 = 0.0, t1 = 1.0;
  double dx = s[2] - s[0], dy = s[3] - s[1];
  if (a == 0.0) return 0.0;
  for (int i = 0; i < nq; i++) { /* inside: sign * cross(q_i, q_i+1, s(t)) >= 0 */
    const double *u = q + 2 * i, *w = q + 2 * ((i + 1) % nq);
    double num = sign * cross(u, w, s), den = sign * ((w[0] - u[0]) * dy - (w[1] - u[1]) * dx);
    if (den == 0.0 && num < 0) return 0.0;
    if (den > 0.0) t0 = US_MAX(t0, -num / den);
    if (den < 0.0) t1 = US_MIN(t1, -num / den);
    if (t0 >= t1) return 0.0;
  }
  return (t1 - t0) * hypot(dx, dy);
}

static void box_points(double x, double y, double hw, double hh, double out[8]) {
  const double p[8] = {x - hw, y - hh, x + hw, y - hh, x + hw, y + hh, x - hw, y + hh};
  memcpy(out, p, sizeof p);
}

/* Entry b's outline in px and its count (a body without geometry: the
 * box around its dot, in sq). */
static const double *outline(const us_Scene *sc, const us_SceneBody *b, double sq[8], int *n) {
  if (b->npt > 0) return *n = b->npt, sc->pts + 2 * b->first;
  box_points(b->cx, b->cy, US_POINT_BODY_PX, US_POINT_BODY_PX, sq);
  *n = 4;
  return sq;
}

static int boxes_meet(const double *a, const double *b) {
  return a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
}

/* ---------------------------------------------------------------- nodes */

/* One node per run of entries with the same node id, with its box and key. */
static void make_nodes(us_Depth *d, const us_Scene *sc, const int *node_of) {
  d->nnode = 0;
  for (int e = 0; e < sc->nbody; e++) {
    if (e == 0 || node_of[e] != node_of[e - 1])
      d->node[d->nnode++] = (Node){sc->bodies[e].body, e, 0, {INFINITY, INFINITY, -INFINITY,
                                                              -INFINITY}, 0.0};
    Node *nd = &d->node[d->nnode - 1];
    double sq[8];
    int n;
    const double *p = outline(sc, &sc->bodies[e], sq, &n);
    for (int k = 0; k < n; k++) {
      nd->bb[0] = US_MIN(nd->bb[0], p[2 * k]), nd->bb[1] = US_MIN(nd->bb[1], p[2 * k + 1]);
      nd->bb[2] = US_MAX(nd->bb[2], p[2 * k]), nd->bb[3] = US_MAX(nd->bb[3], p[2 * k + 1]);
    }
    nd->key += (sc->bodies[e].depth - nd->key) / ++nd->count; /* running mean */
    d->cap = US_MAX(d->cap, n);
  }
}

/* Depth (along v->e) at pixel (X, Y) of the plane of entry b (plane: its
 * face's n, d; NULL for a point body: its own depth). */
static double depth_at(const us_SceneView *v, const double *plane, const us_SceneBody *b,
                       const double c[2]) {
  if (!plane) return b->depth;
  const double *n = plane;
  double x = v->x0 + (c[0] - v->ox) / v->k, y = v->y1 - (c[1] - v->oy) / v->k;
  double nr = n[0] * v->r[0] + n[1] * v->r[1] + n[2] * v->r[2];
  double nu = n[0] * v->u[0] + n[1] * v->u[1] + n[2] * v->u[2];
  double ne = n[0] * v->e[0] + n[1] * v->e[1] + n[2] * v->e[2];
  return (plane[3] - x * nr - y * nu) / ne;
}

/* What the order needs while it is built. */
typedef struct Ctx {
  const us_Scene *sc;
  const us_SceneView *v;
  const double *const *plane; /* per entry as collected */
  us_Depth *d;
} Ctx;

/* +1 when node p is in front of node q where their pictures overlap, -1
 * when behind, 0 when they do not overlap or tie (see the file head). */
static int in_front(const Ctx *c, const Node *p, const Node *q) {
  double best = AREA_EPS, at[2] = {0, 0}, sp[8], sq[8], cen[2];
  int bi = -1, bj = -1;
  for (int i = p->first; i < p->first + p->count; i++)
    for (int j = q->first; j < q->first + q->count; j++) {
      int np, nq;
      const double *pp = outline(c->sc, &c->sc->bodies[i], sp, &np);
      const double *pq = outline(c->sc, &c->sc->bodies[j], sq, &nq);
      double a = common_area(pp, np, pq, nq, c->d->buf, c->d->cap, cen);
      if (a > best) best = a, bi = i, bj = j, at[0] = cen[0], at[1] = cen[1];
    }
  if (bi < 0) return 0;
  double dp = depth_at(c->v, c->plane[bi], &c->sc->bodies[bi], at);
  double dq = depth_at(c->v, c->plane[bj], &c->sc->bodies[bj], at);
  double size = (p->bb[2] - p->bb[0] + p->bb[3] - p->bb[1] + q->bb[2] - q->bb[0] + q->bb[3] -
                 q->bb[1]) / c->v->k;
  double tol = DEPTH_RTOL * size;
  return dp > dq + tol ? 1 : dq > dp + tol ? -1 : 0;
}

/* ---------------------------------------------------------------- edges */

typedef struct Edges {
  int n, cap;
  int *from, *to; /* from is drawn before to */
} Edges;

static int add_edge(Edges *g, int from, int to) {
  if (g->n == g->cap) {
    int cap = g->cap ? 2 * g->cap : 64;
    int *f = us_realloc(g->from, (size_t)cap * sizeof *f);
    if (f) g->from = f;
    int *t = f ? us_realloc(g->to, (size_t)cap * sizeof *t) : NULL;
    if (t) g->to = t;
    if (!f || !t) return 1;
    g->cap = cap;
  }
  g->from[g->n] = from, g->to[g->n] = to, g->n++;
  return 0;
}

/* A node's left edge and index, sorted for the sweep. */
typedef struct Left {
  double x;
  int node;
} Left;

static int by_left(const void *pa, const void *pb) {
  const Left *a = pa, *b = pb;
  return a->x < b->x ? -1 : a->x > b->x ? 1 : (a->node > b->node) - (a->node < b->node);
}

/* Every pair of nodes whose boxes meet, related by in_front: a sweep
 * along x over the nodes sorted by their boxes' left edges. */
static int relate_all(const Ctx *c, Left *lf, Edges *g) {
  const Node *nd = c->d->node;
  int n = c->d->nnode;
  for (int i = 0; i < n; i++) lf[i] = (Left){nd[i].bb[0], i};
  qsort(lf, (size_t)n, sizeof *lf, by_left);
  for (int a = 0; a < n; a++)
    for (int b = a + 1; b < n && lf[b].x < nd[lf[a].node].bb[2]; b++) {
      int i = lf[a].node, j = lf[b].node;
      if (!boxes_meet(nd[i].bb, nd[j].bb)) continue;
      int f = in_front(c, &nd[i], &nd[j]);
      if (f && add_edge(g, f > 0 ? j : i, f > 0 ? i : j)) return 1;
    }
  return 0;
}

/* ---------------------------------------------------------------- order */

static void heap_push(int *h, int *n, int x) {
  int i = (*n)++;
  for (; i > 0 && h[(i - 1) / 2] > x; i = (i - 1) / 2) h[i] = h[(i - 1) / 2];
  h[i] = x;
}

static int heap_pop(int *h, int *n) {
  int top = h[0], x = h[--*n], i = 0;
  for (int c = 1; c < *n; i = c, c = 2 * c + 1) {
    if (c + 1 < *n && h[c + 1] < h[c]) c++;
    if (h[c] >= x) break;
    h[i] = h[c];
  }
  h[i] = x;
  return top;
}

/* The edges as lists of successors: start[n + 1] into adj (cur: n ints
 * of scratch). */
static void successors(const Edges *g, int n, int *start, int *adj, int *cur) {
  memset(start, 0, ((size_t)n + 1) * sizeof *start);
  for (int e = 0; e < g->n; e++) start[g->from[e] + 1]++;
  for (int i = 0; i < n; i++) start[i + 1] += start[i], cur[i] = start[i];
  for (int e = 0; e < g->n; e++) adj[cur[g->from[e]]++] = g->to[e];
}

/* Kahn's topological order of the nodes into seq: of the free nodes the
 * least rank (farthest key) first; with none free (a cycle) the
 * farthest node left. lf: n entries of scratch; w: 6 n + 1 + edges ints. */
static void topo_order(const us_Depth *d, const Edges *g, Left *lf, int *w, int *seq) {
  int n = d->nnode, nh = 0, scan = 0;
  int *rank = w, *indeg = w + n, *heap = w + 2 * n, *placed = w + 3 * n, *start = w + 4 * n;
  int *adj = w + 5 * n + 1;
  for (int i = 0; i < n; i++) lf[i] = (Left){d->node[i].key, i};
  qsort(lf, (size_t)n, sizeof *lf, by_left); /* lf[r].node: the node of rank r */
  successors(g, n, start, adj, placed);
  memset(indeg, 0, (size_t)n * sizeof *indeg);
  memset(placed, 0, (size_t)n * sizeof *placed);
  for (int e = 0; e < g->n; e++) indeg[g->to[e]]++;
  for (int r = 0; r < n; r++) rank[lf[r].node] = r;
  for (int i = 0; i < n; i++)
    if (!indeg[i]) heap_push(heap, &nh, rank[i]);
  for (int k = 0; k < n;) {
    while (!nh && placed[lf[scan].node]) scan++;
    int x = nh ? lf[heap_pop(heap, &nh)].node : lf[scan].node; /* no free node: a cycle */
    if (placed[x]) continue;
    placed[x] = 1, seq[k++] = x;
    for (int e = start[x]; e < start[x + 1]; e++)
      if (--indeg[adj[e]] == 0 && !placed[adj[e]]) heap_push(heap, &nh, rank[adj[e]]);
  }
}

/* sc->bodies and the nodes in the order seq; each body's last node. */
static void apply_order(us_Depth *d, us_Scene *sc, const int *seq, us_SceneBody *tmp,
                        Node *ntmp) {
  int e = 0;
  for (int k = 0; k < d->nnode; k++) {
    Node nd = d->node[seq[k]];
    memcpy(tmp + e, sc->bodies + nd.first, (size_t)nd.count * sizeof *tmp);
    nd.first = e;
    e += nd.count;
    ntmp[k] = nd;
  }
  memcpy(sc->bodies, tmp, (size_t)e * sizeof *tmp);
  memcpy(d->node, ntmp, (size_t)d->nnode * sizeof *ntmp);
  for (int i = 0; i < d->nbody; i++) d->last[i] = -1;
  for (int k = 0; k < d->nnode; k++) d->last[d->node[k].body] = k;
}

/* Relate, order and apply (see the file head); 1 on out of memory. */
static int order_nodes(us_Depth *d, us_Scene *sc, const us_SceneView *v,
                       const double *const *plane) {
  size_t n = (size_t)d->nnode + 1;
  Edges g = {0, 0, NULL, NULL};
  Left *lf = us_malloc(n * sizeof *lf);
  Ctx c = {sc, v, plane, d};
  int bad = !lf || relate_all(&c, lf, &g);
  int *w = bad ? NULL : us_malloc((7 * n + (size_t)g.n) * sizeof *w);
  us_SceneBody *tmp = w ? us_malloc(((size_t)sc->nbody + 1) * sizeof *tmp) : NULL;
  Node *ntmp = tmp ? us_malloc(n * sizeof *ntmp) : NULL;
  bad = !ntmp;
  if (!bad) topo_order(d, &g, lf, w, w + 6 * n + (size_t)g.n);
  if (!bad) apply_order(d, sc, w + 6 * n + (size_t)g.n, tmp, ntmp);
  us_free(g.from), us_free(g.to), us_free(lf), us_free(w), us_free(tmp), us_free(ntmp);
  return bad;
}

int us_depth3_order(us_Scene *sc, const us_SceneView *v, int nbody, const double *const *plane,
                    const int *node_of) {
  us_Depth *d = us_calloc(1, sizeof *d);
  sc->depth = d;
  if (!d) return 1;
  d->nbody = nbody;
  d->node = us_malloc(((size_t)sc->nbody + 1) * sizeof *d->node);
  d->last = us_malloc(((size_t)nbody + 1) * sizeof *d->last);
  if (!d->node || !d->last) return 1;
  make_nodes(d, sc, node_of);
  d->cap = 2 * d->cap + 8; /* a clipped polygon has at most np + nq points */
  d->buf = us_malloc(4 * (size_t)d->cap * sizeof *d->buf);
  return !d->buf || order_nodes(d, sc, v, plane);
}

void us_depth3_free(us_Scene *sc) {
  us_Depth *d = sc->depth;
  if (!d) return;
  us_free(d->node), us_free(d->last), us_free(d->buf), us_free(d);
  sc->depth = NULL;
}

/* ------------------------------------------------------------- covering */

/* The first position after every node of bodies a and b (US_GROUND: none). */
static int after(const us_Depth *d, int a, int b) {
  int la = a >= 0 && a < d->nbody ? d->last[a] : -1, lb = b >= 0 && b < d->nbody ? d->last[b] : -1;
  return US_MAX(la, lb) + 1;
}

/* The area of the box (half sides hw, hh at x, y) that faces painted after
 * bodies a and b cover, summed over the faces (overlaps of faces counted
 * twice: a bound), counted until it passes `enough`. */
static double box_cover(const us_Scene *sc, int a, int b, double x, double y, double hw,
                        double hh, double enough) {
  const us_Depth *d = sc->depth;
  double box[8], bb[4] = {x - hw, y - hh, x + hw, y + hh}, c[2], sq[8], sum = 0.0;
  box_points(x, y, hw, hh, box);
  for (int k = after(d, a, b); k < d->nnode && sum <= enough; k++) {
    const Node *nd = &d->node[k];
    for (int e = nd->first; boxes_meet(nd->bb, bb) && e < nd->first + nd->count; e++) {
      int n;
      const double *p = outline(sc, &sc->bodies[e], sq, &n);
      sum += common_area(box, 4, p, n, d->buf, d->cap, c);
    }
  }
  return sum;
}

int us_depth3_covers_box(const us_Scene *sc, int a, int b, double x, double y, double hw,
                         double hh) {
  return sc->depth && box_cover(sc, a, b, x, y, hw, hh, COVER_AREA) > COVER_AREA;
}

int us_depth3_hides_label(const us_Scene *sc, int body, double x, double y, double hw,
                          double hh) {
  double share = LABEL_SHARE * 4.0 * hw * hh;
  return sc->depth && box_cover(sc, body, US_GROUND, x, y, hw, hh, share) > share;
}

int us_depth3_covers_segment(const us_Scene *sc, int a, int b, const double seg[4]) {
  const us_Depth *d = sc->depth;
  if (!d) return 0;
  double bb[4] = {US_MIN(seg[0], seg[2]), US_MIN(seg[1], seg[3]), US_MAX(seg[0], seg[2]),
                  US_MAX(seg[1], seg[3])}, sq[8];
  bb[0] -= 0.5, bb[1] -= 0.5, bb[2] += 0.5, bb[3] += 0.5; /* a vertical arrow's box has width */
  for (int k = after(d, a, b); k < d->nnode; k++) {
    const Node *nd = &d->node[k];
    for (int e = nd->first; boxes_meet(nd->bb, bb) && e < nd->first + nd->count; e++) {
      int n;
      const double *p = outline(sc, &sc->bodies[e], sq, &n);
      if (inside_length(seg, p, n) > COVER_LEN) return 1;
    }
  }
  return 0;
}
