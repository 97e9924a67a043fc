/* Removal kinematics: which bodies keep a body from being taken out of a
 * sub-assembly by a translation, precomputed once per structure so that
 * each of the planner's queries costs only the size of its answer.
 *
 * UP: lifted straight up (+y) to infinity. Body c blocks b when some
 * interior point of c lies above some interior point of b on the same
 * vertical line. With top_c(x) the highest point of c and bot_b(x) the
 * lowest point of b on the line at x (over the whole cross-section: the
 * polygons may be non-convex and cut by the line several times), c blocks
 * b iff top_c(x) > bot_b(x) for some x inside both x-ranges. Both are
 * envelopes of edges (top_c = max over c's edges spanning x, bot_b = min
 * over b's), so
 *   max_x (top_c - bot_b) = max over edge pairs (e of c, f of b) of
 *                           max over their common x-range of y_e - y_f,
 * and y_e - y_f is linear there: the two ends of the range decide.
 * Vertical edges are skipped; their end points belong to the neighbouring
 * edges, which reach the same values. A body resting on b, hanging above
 * it with a gap, or reaching over it (a C shape) blocks b; a body beside
 * b, or under it, does not.
 * Tolerance, per pair, never the structure's size: tol = US_KIN_TOL_REL
 * times the larger of the two bodies' box diagonals. x is restricted to the
 * common x-range shrunk by tol at both ends (bodies touching side by side,
 * or overlapping sideways by less than tol, do not block each other) and c
 * blocks b only where top_c - bot_b > tol (b resting on c, sunk into it by
 * less than tol, is not blocked by c). Scaling the structure scales every
 * tol with it: the answers do not depend on the units.
 * Broad phase: the bodies with geometry sorted by the left end of their
 * x-range (ties by index); a sweep pairs each body with the following
 * ones that start strictly before it ends (ranges that only touch are side
 * by side). Each pair is tested both ways (interlocking non-convex bodies
 * may block each other); a pair of two fixed bodies is skipped, and a
 * fixed body is only ever a blocker.
 * Bodies without geometry (nvert == 0): a pair in which either side lacks
 * geometry is decided by its contacts. A contact between b and c whose
 * unit normal into b has n_y < -US_KIN_ANGLE_TOL presses b down: c (or the
 * ground) blocks b. A side contact (n_y about 0) does not. Nothing beyond
 * the contacts is known about such a body, so a body hanging above it
 * with a gap is not seen. The ground blocks no polygon (it lies below).
 * Storage: for each movable body the ascending list of its blockers
 * (US_GROUND first when listed, fixed bodies included), no duplicates. A
 * query walks the list to the first present entry.
 *
 * FREE: some translation d != 0 moves b away from every present body it
 * touches, to first order. Sign convention: n is the unit contact normal
 * pointing INTO b (the stored normal points from the contact's a into its
 * b, so it is flipped when b is the contact's a); the contact allows the
 * motion d iff d . n >= 0 (b slides along or leaves the other body). Such
 * a d exists iff all the normals lie in a closed half-plane, i.e. iff the
 * largest circular gap between consecutive normal angles is >= pi; the
 * free directions then form the cone [beta - pi/2, alpha + pi/2], where
 * the normals span the arc [alpha, beta] (counter-clockwise, the
 * complement of the gap), of width gap - pi. The test accepts a gap
 * of pi - US_KIN_ANGLE_TOL (rounding of normals that are exactly
 * opposite). Contacts count when the other side is present (the ground
 * and fixed bodies always are). It is a local test: bodies that b would
 * meet farther along d are not considered (a body in a U-shaped notch
 * lets the U slide out sideways). Storage: each movable body's contact
 * normals sorted by angle; a query walks them once, skipping absent
 * bodies.
 *
 * Cost: UP precompute O(n log n + P V^2 + B) for n bodies, P pairs whose
 * x-ranges overlap, V vertices per body and B blocking pairs (the lists
 * come out sorted from two counting sorts); a running-bond wall of R rows
 * has about 1.5 R blockers per brick, a column of n blocks n(n-1)/2 pairs
 * in all: that is the size of the answer. Memory: 4 bytes per blocking
 * pair kept, about 16 (plus growth slack) while building. FREE precompute
 * O(C log C) for C contacts. */
#include "kinematics.h"

#include "geometry/geometry.h"

#include <math.h>
#include <stdlib.h>

#define KIN_PI 3.14159265358979323846
#define KIN_NO_SKIP (-3) /* no body has this index (US_GROUND is -1) */

typedef struct KinNormal {
  double angle; /* of the normal into the body, in [-pi, pi] */
  int other;    /* the body on the other side, or US_GROUND */
} KinNormal;

struct us_Kinematics {
  us_Removal mode;
  int nbody;
  unsigned char *fixed; /* [nbody] */
  double *low;          /* [nbody] lowest y (without geometry: the centre) */
  int *up_start;        /* UP: [nbody + 1] offsets into up */
  int *up;              /* UP: blockers of each body, ascending */
  int *fr_start;        /* FREE: [nbody + 1] offsets into fr */
  KinNormal *fr;        /* FREE: normals into each body, by angle */
};

/* A body's box with the size that sets its pairs' tolerance. */
typedef struct KinBox {
  double x0, x1, y0, y1, diag;
  int body;
} KinBox;

/* (blocked, blocker) pairs, flattened. */
typedef struct PairList {
  int *v;
  int n, cap;
} PairList;

static int is_present(const us_Kinematics *k, const us_Bitset *present, int c) {
  return c < 0 || k->fixed[c] || us_bitset_get(present, c);
}

static int has_geometry(const us_Structure *s, int i) {
  return i == US_GROUND || s->bodies[i].nvert >= 3;
}

static int pairs_push(PairList *l, int blocked, int blocker) {
  if (US_GROW(l->v, l->cap, l->n + 2)) return -1;
  l->v[l->n++] = blocked;
  l->v[l->n++] = blocker;
  return 0;
}

/* ------------------------------------------------------- UP: narrow phase */

/* Vertex i (0 <= i < nvert) without us_poly_vertex's modulo: this is the
 * inner loop of the precomputation. */
static us_Vec2 vertex(const us_Body *b, int i) { return us_v2(b->verts[2 * i], b->verts[2 * i + 1]); }

/* y of the non-vertical edge p-q at x. */
static double edge_y(us_Vec2 p, us_Vec2 q, double x) {
  return p.y + (x - p.x) / (q.x - p.x) * (q.y - p.y);
}

/* Edge p-q of c, over [e0, e1], rises more than tol above some edge of b
 * somewhere in their common x-range. */
static int edge_above(us_Vec2 p, us_Vec2 q, const us_Body *b, double e0, double e1, double tol) {
  for (int j = 0; j < b->nvert; j++) {
    us_Vec2 r = vertex(b, j), t = vertex(b, j + 1 < b->nvert ? j + 1 : 0);
    if (r.x == t.x) continue;
    double x0 = US_MAX(e0, US_MIN(r.x, t.x)), x1 = US_MIN(e1, US_MAX(r.x, t.x));
    if (x0 > x1) continue;
    if (edge_y(p, q, x0) - edge_y(r, t, x0) > tol || edge_y(p, q, x1) - edge_y(r, t, x1) > tol)
      return 1;
  }
  return 0;
}

/* Some point of c lies more than tol above some point of b at one x in
 * [lo, hi] (the edge-pair form of top_c(x) - bot_b(x) > tol). */
static int body_above(const us_Body *c, const us_Body *b, double lo, double hi, double tol) {
  for (int i = 0; i < c->nvert; i++) {
    us_Vec2 p = vertex(c, i), q = vertex(c, i + 1 < c->nvert ? i + 1 : 0);
    if (p.x == q.x) continue;
    double e0 = US_MAX(lo, US_MIN(p.x, q.x)), e1 = US_MIN(hi, US_MAX(p.x, q.x));
    if (e0 <= e1 && edge_above(p, q, b, e0, e1, tol)) return 1;
  }
  return 0;
}

/* Test a candidate pair both ways; -1 on OOM. */
static int test_pair(const us_Structure *s, const KinBox *bi, const KinBox *bj, PairList *out) {
  int i = bi->body, j = bj->body;
  const us_Body *a = &s->bodies[i], *c = &s->bodies[j];
  if (a->fixed && c->fixed) return 0;
  double tol = US_KIN_TOL_REL * US_MAX(bi->diag, bj->diag);
  double lo = US_MAX(bi->x0, bj->x0) + tol, hi = US_MIN(bi->x1, bj->x1) - tol;
  if (lo > hi) return 0;
  if (!a->fixed && bj->y1 > bi->y0 + tol && body_above(c, a, lo, hi, tol) && pairs_push(out, i, j))
    return -1;
  if (!c->fixed && bi->y1 > bj->y0 + tol && body_above(a, c, lo, hi, tol) && pairs_push(out, j, i))
    return -1;
  return 0;
}

/* -------------------------------------------------------- UP: broad phase */

static int box_cmp(const void *pa, const void *pb) {
  const KinBox *a = pa, *b = pb;
  if (a->x0 != b->x0) return a->x0 < b->x0 ? -1 : 1;
  return (a->body > b->body) - (a->body < b->body);
}

/* Boxes of the bodies with geometry; returns their count. */
static int make_boxes(const us_Structure *s, KinBox *bx) {
  int n = 0;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    if (b->nvert < 3) continue;
    double bb[4];
    us_poly_bbox(b->verts, b->nvert, bb);
    bx[n++] = (KinBox){bb[0], bb[2], bb[1], bb[3], hypot(bb[2] - bb[0], bb[3] - bb[1]), i};
  }
  return n;
}

static int sweep(const us_Structure *s, const KinBox *bx, int n, PairList *out) {
  for (int k = 0; k < n; k++)
    for (int m = k + 1; m < n && bx[m].x0 < bx[k].x1; m++)
      if (test_pair(s, &bx[k], &bx[m], out)) return -1;
  return 0;
}

static int geometric_blockers(const us_Structure *s, PairList *out) {
  KinBox *bx = us_malloc((size_t)(s->nbody > 0 ? s->nbody : 1) * sizeof *bx);
  if (!bx) return -1;
  int n = make_boxes(s, bx);
  qsort(bx, (size_t)n, sizeof *bx, box_cmp);
  int rc = sweep(s, bx, n, out);
  us_free(bx);
  return rc;
}

/* Pairs with a side without geometry: a contact pressing a body down. */
static int contact_blockers(const us_Structure *s, PairList *out) {
  for (int k = 0; k < s->ncontact; k++) {
    const us_Contact *c = &s->contacts[k];
    if (has_geometry(s, c->a) && has_geometry(s, c->b)) continue;
    double ny = c->n[1]; /* into c->b */
    if (ny < -US_KIN_ANGLE_TOL && !s->bodies[c->b].fixed && pairs_push(out, c->b, c->a)) return -1;
    if (ny > US_KIN_ANGLE_TOL && c->a >= 0 && !s->bodies[c->a].fixed && pairs_push(out, c->a, c->b))
      return -1;
  }
  return 0;
}

/* ------------------------------------------------------------ UP: lists */

static void offsets(int *start, int nkeys) {
  for (int i = 0; i < nkeys; i++) start[i + 1] += start[i];
}

/* After filling with start[key]++: back to the starts. */
static void unshift(int *start, int nkeys) {
  for (int i = nkeys; i > 0; i--) start[i] = start[i - 1];
  start[0] = 0;
}

/* Duplicates (two contacts of one pair) are adjacent: drop them. */
static void dedup(us_Kinematics *k) {
  int w = 0, from = 0;
  for (int b = 0; b < k->nbody; b++) {
    int to = k->up_start[b + 1];
    k->up_start[b] = w;
    for (int i = from; i < to; i++)
      if (i == from || k->up[i] != k->up[i - 1]) k->up[w++] = k->up[i];
    from = to;
  }
  k->up_start[k->nbody] = w;
}

/* Two counting sorts: the pairs bucketed by blocker (+1, so the ground
 * comes first), then read back in blocker order into each blocked body's
 * list, which therefore comes out ascending. O(pairs + bodies). */
static void fill_lists(us_Kinematics *k, const PairList *l, int *bstart, int *bval) {
  int np = l->n / 2, nb = k->nbody;
  for (int p = 0; p < np; p++) bstart[l->v[2 * p + 1] + 2]++;
  offsets(bstart, nb + 1);
  for (int p = 0; p < np; p++) bval[bstart[l->v[2 * p + 1] + 1]++] = l->v[2 * p];
  unshift(bstart, nb + 1);
  for (int p = 0; p < np; p++) k->up_start[l->v[2 * p] + 1]++;
  offsets(k->up_start, nb);
  for (int c = 0; c <= nb; c++)
    for (int i = bstart[c]; i < bstart[c + 1]; i++) k->up[k->up_start[bval[i]]++] = c - 1;
  unshift(k->up_start, nb);
  dedup(k);
}

static int build_lists(us_Kinematics *k, const PairList *l) {
  size_t m = (size_t)(l->n > 0 ? l->n / 2 : 1);
  int *bstart = us_calloc((size_t)k->nbody + 2, sizeof(int)), *bval = us_malloc(m * sizeof(int));
  k->up_start = us_calloc((size_t)k->nbody + 1, sizeof(int));
  k->up = us_malloc(m * sizeof(int));
  int rc = bstart && bval && k->up_start && k->up ? 0 : -1;
  if (!rc) fill_lists(k, l, bstart, bval);
  us_free(bstart);
  us_free(bval);
  return rc;
}

static int build_up(us_Kinematics *k, const us_Structure *s) {
  PairList l = {NULL, 0, 0};
  int rc = geometric_blockers(s, &l);
  if (!rc) rc = contact_blockers(s, &l);
  if (!rc) rc = build_lists(k, &l);
  us_free(l.v);
  return rc;
}

/* ----------------------------------------------------------- FREE: build */

static int normal_cmp(const void *pa, const void *pb) {
  const KinNormal *a = pa, *b = pb;
  if (a->angle != b->angle) return a->angle < b->angle ? -1 : 1;
  return (a->other > b->other) - (a->other < b->other);
}

/* Put the normal into `into` (from `other`) at its slot; counting pass
 * when k->fr is NULL. */
static void place_normal(us_Kinematics *k, int into, int other, double nx, double ny) {
  if (into < 0 || k->fixed[into]) return;
  if (!k->fr) {
    k->fr_start[into + 1]++;
    return;
  }
  k->fr[k->fr_start[into]++] = (KinNormal){atan2(ny, nx), other};
}

static void place_all(us_Kinematics *k, const us_Structure *s) {
  for (int i = 0; i < s->ncontact; i++) {
    const us_Contact *c = &s->contacts[i];
    place_normal(k, c->b, c->a, c->n[0], c->n[1]);
    place_normal(k, c->a, c->b, -c->n[0], -c->n[1]);
  }
}

static int build_free(us_Kinematics *k, const us_Structure *s) {
  k->fr_start = us_calloc((size_t)k->nbody + 1, sizeof(int));
  if (!k->fr_start) return -1;
  place_all(k, s);
  for (int b = 0; b < k->nbody; b++) k->fr_start[b + 1] += k->fr_start[b];
  int total = k->fr_start[k->nbody];
  k->fr = us_malloc((size_t)(total > 0 ? total : 1) * sizeof *k->fr);
  if (!k->fr) return -1;
  place_all(k, s);
  for (int b = k->nbody; b > 0; b--) k->fr_start[b] = k->fr_start[b - 1];
  k->fr_start[0] = 0;
  for (int b = 0; b < k->nbody; b++)
    qsort(k->fr + k->fr_start[b], (size_t)(k->fr_start[b + 1] - k->fr_start[b]), sizeof *k->fr,
          normal_cmp);
  return 0;
}

/* ------------------------------------------------------------- life cycle */

static int build_common(us_Kinematics *k, const us_Structure *s) {
  k->fixed = us_calloc((size_t)(k->nbody > 0 ? k->nbody : 1), 1);
  k->low = us_malloc((size_t)(k->nbody > 0 ? k->nbody : 1) * sizeof(double));
  if (!k->fixed || !k->low) return -1;
  for (int i = 0; i < k->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    double bb[4] = {0, b->com[1], 0, 0};
    if (b->nvert >= 3) us_poly_bbox(b->verts, b->nvert, bb);
    k->fixed[i] = (unsigned char)(b->fixed != 0);
    k->low[i] = bb[1];
  }
  return 0;
}

us_Kinematics *us_kinematics_new(const us_Structure *s, us_Removal mode, us_Error *err) {
  if (!s || !us_structure_is_finalized(s) || s->dim != 2) {
    us_error_set(err, US_ERR_USAGE, "removal kinematics needs a finalized 2D structure");
    return NULL;
  }
  if (mode != US_REMOVAL_ANY && mode != US_REMOVAL_UP && mode != US_REMOVAL_FREE) {
    us_error_set(err, US_ERR_USAGE, "unknown removal mode %d", (int)mode);
    return NULL;
  }
  us_Kinematics *k = us_calloc(1, sizeof *k);
  int rc = k ? 0 : -1;
  if (k) {
    k->mode = mode;
    k->nbody = s->nbody;
    rc = build_common(k, s);
  }
  if (!rc && mode == US_REMOVAL_UP) rc = build_up(k, s);
  if (!rc && mode == US_REMOVAL_FREE) rc = build_free(k, s);
  if (rc) {
    us_kinematics_free(k);
    us_error_set(err, US_ERR_NOMEM, "out of memory in removal kinematics");
    return NULL;
  }
  return k;
}

void us_kinematics_free(us_Kinematics *k) {
  if (!k) return;
  us_free(k->fixed);
  us_free(k->low);
  us_free(k->up_start);
  us_free(k->up);
  us_free(k->fr_start);
  us_free(k->fr);
  us_free(k);
}

us_Removal us_kinematics_mode(const us_Kinematics *k) { return k->mode; }

/* ---------------------------------------------------------------- queries */

/* The largest circular gap between the angles of b's present normals
 * (leaving out body `skip`), where it starts, and how many there were. */
typedef struct KinGap {
  double size, start;
  int count;
} KinGap;

static KinGap max_gap(const us_Kinematics *k, const us_Bitset *present, int b, int skip) {
  KinGap g = {-1.0, 0.0, 0};
  double first = 0.0, prev = 0.0;
  for (int i = k->fr_start[b]; i < k->fr_start[b + 1]; i++) {
    int o = k->fr[i].other;
    if (o == skip || !is_present(k, present, o)) continue;
    double a = k->fr[i].angle;
    if (g.count++ == 0)
      first = a;
    else if (a - prev > g.size)
      g = (KinGap){a - prev, prev, g.count};
    prev = a;
  }
  if (g.count == 0) return (KinGap){2.0 * KIN_PI, 0.5 * KIN_PI, 0};
  if (first + 2.0 * KIN_PI - prev > g.size) g = (KinGap){first + 2.0 * KIN_PI - prev, prev, g.count};
  return g;
}

static int gap_frees(KinGap g) { return g.size >= KIN_PI - US_KIN_ANGLE_TOL; }

static int up_free(const us_Kinematics *k, const us_Bitset *present, int b) {
  for (int i = k->up_start[b]; i < k->up_start[b + 1]; i++)
    if (is_present(k, present, k->up[i])) return 0;
  return 1;
}

int us_kinematics_can_remove(const us_Kinematics *k, const us_Bitset *present, int b) {
  if (k->mode == US_REMOVAL_ANY) return 1;
  if (k->fixed[b]) return 0;
  if (k->mode == US_REMOVAL_UP) return up_free(k, present, b);
  return gap_frees(max_gap(k, present, b, KIN_NO_SKIP));
}

/* c lies lower than d (the ground lowest of all), ties by index. */
static int lower(const us_Kinematics *k, int c, int d) {
  double yc = c < 0 ? -INFINITY : k->low[c], yd = d < 0 ? -INFINITY : k->low[d];
  return yc < yd || (yc == yd && c < d);
}

static int up_blocker(const us_Kinematics *k, const us_Bitset *present, int b) {
  int best = US_KIN_NONE;
  for (int i = k->up_start[b]; i < k->up_start[b + 1]; i++) {
    int c = k->up[i];
    if (is_present(k, present, c) && (best == US_KIN_NONE || lower(k, c, best))) best = c;
  }
  return best;
}

static int free_blocker(const us_Kinematics *k, const us_Bitset *present, int b) {
  if (gap_frees(max_gap(k, present, b, KIN_NO_SKIP))) return US_KIN_NONE;
  int first = US_KIN_NONE;
  for (int i = k->fr_start[b]; i < k->fr_start[b + 1]; i++) {
    int o = k->fr[i].other;
    if (!is_present(k, present, o)) continue;
    if (first == US_KIN_NONE) first = o;
    if (o >= 0 && !k->fixed[o] && gap_frees(max_gap(k, present, b, o))) return o;
  }
  return first;
}

int us_kinematics_blocker(const us_Kinematics *k, const us_Bitset *present, int b) {
  if (k->mode == US_REMOVAL_ANY) return US_KIN_NONE;
  if (k->fixed[b]) return b;
  if (k->mode == US_REMOVAL_UP) return up_blocker(k, present, b);
  return free_blocker(k, present, b);
}

int us_kinematics_direction(const us_Kinematics *k, const us_Bitset *present, int b, double d[2],
                            double *width) {
  d[0] = d[1] = 0.0;
  *width = 0.0;
  if (k->mode != US_REMOVAL_FREE) {
    if (!us_kinematics_can_remove(k, present, b)) return 0;
    d[1] = 1.0;
    *width = k->mode == US_REMOVAL_ANY ? 2.0 * KIN_PI : 0.0;
    return 1;
  }
  KinGap g = k->fixed[b] ? (KinGap){0.0, 0.0, 1} : max_gap(k, present, b, KIN_NO_SKIP);
  if (!gap_frees(g)) return 0;
  /* the normals span the arc opposite the gap; the cone is centred on it */
  double mid = g.start + 0.5 * g.size + KIN_PI;
  d[0] = cos(mid);
  d[1] = sin(mid);
  *width = g.count == 0 ? 2.0 * KIN_PI : US_MAX(0.0, g.size - KIN_PI);
  return 1;
}

const int *us_kinematics_up_blockers(const us_Kinematics *k, int b, int *n) {
  *n = 0;
  if (k->mode != US_REMOVAL_UP) return NULL;
  *n = k->up_start[b + 1] - k->up_start[b];
  return k->up + k->up_start[b];
}

long us_kinematics_up_pairs(const us_Kinematics *k) {
  return k->mode == US_REMOVAL_UP ? (long)k->up_start[k->nbody] : 0;
}
