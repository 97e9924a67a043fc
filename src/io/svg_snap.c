/* Snapping a drawing's shapes into contact (docs/svg.md, "Snapping").
 *
 * In a drawing, blocks that should rest on each other often miss by a
 * little (rounded coordinates, a hand that was not quite steady), and
 * contact detection only accepts 1e-6 of a body's size. So before the
 * structure is finalized, bodies are settled one by one from the lowest
 * (smallest lowest y; ties by input order), and each vertex v of the body
 * being settled, i, is moved by at most the pair's tolerance tol_ij onto
 * the nearest of:
 *   1. the ground line y = 0, when |v.y| <= tol_i (first, for all bodies);
 *   2. a vertex of a body j settled before i, within tol_ij (a corner on
 *      a corner);
 *   3. else the nearest point inside an edge (not at its ends) of any
 *      other body j, within tol_ij.
 * tol_ij is one given tolerance, or rel times the smaller of the two
 * bodies' bounding-box diagonals (tol_i: rel times i's own), so that
 * adding a body far away changes nothing. Either way tol_i is at most
 * SNAP_THICK times body i's thickness 2 area / perimeter (a rectangle
 * w x h: wh / (w + h), about h when it is thin), so that snapping never
 * flattens a body: a plank 2000 x 1 keeps its height (its diagonal alone
 * would allow 2). Its vertices on opposite sides move towards each other
 * by at most 2 SNAP_THICK of its thickness a pass, 2 SNAP_PASSES
 * SNAP_THICK = 0.4 of it in all.
 *
 * Why this order: a block drawn a little above its support moves down
 * onto it, the support does not move up, and two corners that nearly meet
 * end on the earlier one's position (the later finds it at distance 0), so
 * corners never swap. Rule 3 lets a vertex of a lower body reach the edge
 * of a higher one beside it (side by side blocks), but not its corners:
 * those come to it by rule 2 when the higher body is settled. A later move
 * can take a point an earlier vertex was snapped onto away from it (by at
 * most that move's tolerance), so passes repeat until one moves nothing
 * (at most SNAP_PASSES); moves below 1e-9 of the tolerance are not made.
 * Invariant: no vertex moves farther than its tolerance in one pass.
 *
 * Candidates come from the contact broad phase (boxes inflated by twice
 * each body's tolerance, computed once: moves never exceed that margin
 * within the passes that matter); a vertex is compared with a partner's
 * vertices and edges only when it lies in the partner's inflated box.
 * Cost: the broad phase's, plus sum over candidate pairs of the vertices
 * of one body that lie in the other's box times the other's vertices. */
#include "svg.h"

#include "contact/contact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SNAP_PASSES 4
#define SNAP_MIN_REL 1e-9
#define SNAP_THICK 0.05

typedef struct Snap {
  us_Structure *s;
  const double *tol;
  int *adj, *adj_start;   /* partners of body i: adj[adj_start[i] .. adj_start[i+1]) */
  double *box;            /* 4 per body, inflated by 2 tol */
  unsigned char *moved;   /* per vertex, in body order */
  int *vbase;             /* index of body i's first vertex in moved */
  int *order, *rank;      /* bodies from the lowest; rank[order[r]] = r */
} Snap;

/* 2 area / perimeter: the inradius of a regular polygon, the smaller
 * side of a thin rectangle. */
static double thickness(const us_Body *b) {
  double per = 0;
  for (int k = 0; k < b->nvert; k++)
    per += us_v2_dist(us_poly_vertex(b->verts, b->nvert, k), us_poly_vertex(b->verts, b->nvert, k + 1));
  return per > 0 ? 2 * fabs(us_poly_signed_area(b->verts, b->nvert)) / per : 0;
}

static void body_box(const us_Body *b, double t, double *box) {
  us_poly_bbox(b->verts, b->nvert, box);
  box[0] -= t, box[1] -= t, box[2] += t, box[3] += t;
}

static int in_box(const double *box, us_Vec2 p) {
  return p.x >= box[0] && p.x <= box[2] && p.y >= box[1] && p.y <= box[3];
}

/* The nearest target for p on body b within t: a vertex (edges == 0) or
 * a point strictly inside an edge (edges == 1); 1 found, *best (in: the
 * distance to beat) and *to updated. */
static int nearest_on(const us_Body *b, us_Vec2 p, double t, double *best, us_Vec2 *to,
                      int edges) {
  int found = 0;
  for (int k = 0; k < b->nvert; k++) {
    us_Vec2 a = us_poly_vertex(b->verts, b->nvert, k), q = a;
    if (edges) {
      us_Vec2 e = us_v2_sub(us_poly_vertex(b->verts, b->nvert, k + 1), a);
      double ee = us_v2_dot(e, e), u = ee > 0 ? us_v2_dot(us_v2_sub(p, a), e) / ee : 0;
      if (!(u > 0 && u < 1)) continue;
      q = us_v2_add(a, us_v2_scale(e, u));
    }
    double d = us_v2_dist(p, q);
    if (d <= t && d < *best) *best = d, *to = q, found = 1;
  }
  return found;
}

/* Snap vertex k of body i; 1 moved. */
static int snap_vertex(Snap *sn, int i, int k) {
  us_Body *b = &sn->s->bodies[i];
  us_Vec2 p = us_v2(b->verts[2 * k], b->verts[2 * k + 1]), to = p;
  double best = INFINITY, tmin = INFINITY;
  for (int edges = 0; edges < 2 && isinf(best); edges++) /* vertices first, then edges */
    for (int a = sn->adj_start[i]; a < sn->adj_start[i + 1]; a++) {
      int j = sn->adj[a];
      if (!in_box(sn->box + 4 * j, p) || (!edges && sn->rank[j] > sn->rank[i])) continue;
      double t = US_MIN(sn->tol[i], sn->tol[j]);
      if (nearest_on(&sn->s->bodies[j], p, t, &best, &to, edges)) tmin = t;
    }
  if (isinf(best) || best <= SNAP_MIN_REL * tmin) return 0;
  b->verts[2 * k] = to.x;
  b->verts[2 * k + 1] = to.y;
  sn->moved[sn->vbase[i] + k] = 1;
  return 1;
}

static int snap_ground(Snap *sn) {
  int m = 0;
  for (int i = 0; i < sn->s->nbody; i++) {
    us_Body *b = &sn->s->bodies[i];
    for (int k = 0; k < b->nvert; k++) {
      double y = fabs(b->verts[2 * k + 1]);
      if (y <= sn->tol[i] && y > SNAP_MIN_REL * sn->tol[i]) {
        b->verts[2 * k + 1] = 0;
        sn->moved[sn->vbase[i] + k] = 1;
        m++;
      }
    }
  }
  return m;
}

/* Partner lists (both directions) from the broad phase's pairs. */
static int adjacency(Snap *sn, const us_BodyPair *pr, int np) {
  int n = sn->s->nbody;
  sn->adj_start = us_calloc((size_t)n + 1, sizeof *sn->adj_start);
  sn->adj = us_malloc((size_t)(2 * np + 1) * sizeof *sn->adj);
  if (!sn->adj_start || !sn->adj) return -1;
  for (int k = 0; k < np; k++) sn->adj_start[pr[k].i + 1]++, sn->adj_start[pr[k].j + 1]++;
  for (int i = 0; i < n; i++) sn->adj_start[i + 1] += sn->adj_start[i];
  int *fill = us_malloc((size_t)(n + 1) * sizeof *fill);
  if (!fill) return -1;
  memcpy(fill, sn->adj_start, (size_t)n * sizeof *fill);
  for (int k = 0; k < np; k++) sn->adj[fill[pr[k].i]++] = pr[k].j, sn->adj[fill[pr[k].j]++] = pr[k].i;
  us_free(fill);
  return 0;
}

/* Bodies by their lowest point, then by index: a total order, so qsort
 * gives the same order on every run. */
typedef struct Key {
  double y;
  int i;
} Key;

static int lower_first(const void *pa, const void *pb) {
  const Key *a = pa, *b = pb;
  if (a->y != b->y) return a->y < b->y ? -1 : 1;
  return (a->i > b->i) - (a->i < b->i);
}

static int settle_order(Snap *sn, const double *tol) {
  int n = sn->s->nbody;
  Key *key = us_malloc((size_t)(n + 1) * sizeof *key);
  sn->order = us_malloc((size_t)(n + 1) * sizeof *sn->order);
  sn->rank = us_malloc((size_t)(n + 1) * sizeof *sn->rank);
  if (!key || !sn->order || !sn->rank) return us_free(key), -1;
  for (int i = 0; i < n; i++) key[i] = (Key){sn->box[4 * i + 1] + 2 * tol[i], i};
  qsort(key, (size_t)n, sizeof *key, lower_first);
  for (int r = 0; r < n; r++) sn->order[r] = key[r].i, sn->rank[key[r].i] = r;
  us_free(key);
  return 0;
}

/* Tolerances, boxes, vertex numbering and partners. */
static us_Status prepare(Snap *sn, double *tol, double tol_abs, double rel, us_Error *err) {
  us_Structure *s = sn->s;
  int nv = 0;
  for (int i = 0; i < s->nbody; i++) {
    sn->vbase[i] = nv;
    nv += s->bodies[i].nvert;
    const us_Body *b = &s->bodies[i];
    tol[i] = tol_abs > 0 ? tol_abs : rel * us_poly_diameter(b->verts, b->nvert);
    tol[i] = US_MIN(tol[i], SNAP_THICK * thickness(b));
  }
  for (int i = 0; i < s->nbody; i++) body_box(&s->bodies[i], 2 * tol[i], sn->box + 4 * i);
  sn->moved = us_calloc((size_t)nv + 1, 1);
  for (int i = 0; i < s->nbody; i++) tol[i] *= 2; /* the broad phase's margin */
  us_BodyPair *pr = NULL;
  int np = 0;
  us_Status st = sn->moved ? us_broadphase(s, tol, &pr, &np, err) : US_ERR_NOMEM;
  for (int i = 0; i < s->nbody; i++) tol[i] /= 2;
  if (!st && (adjacency(sn, pr, np) || settle_order(sn, tol))) st = US_ERR_NOMEM;
  us_free(pr);
  return st == US_ERR_NOMEM ? us_error_set(err, st, "out of memory snapping the drawing") : st;
}

static int count_moved(const Snap *sn) {
  int m = 0, nv = sn->s->nbody ? sn->vbase[sn->s->nbody - 1] + sn->s->bodies[sn->s->nbody - 1].nvert : 0;
  for (int k = 0; k < nv; k++) m += sn->moved[k];
  return m;
}

int us_svg_snap(us_Structure *s, double tol_abs, double rel, us_Error *err) {
  size_t n = (size_t)s->nbody + 1;
  double *tol = us_malloc(n * sizeof *tol);
  Snap sn = {s, tol, NULL, NULL, us_malloc(4 * n * sizeof(double)), NULL, us_malloc(n * sizeof(int)),
             NULL, NULL};
  int moved = -1;
  if (!tol || !sn.box || !sn.vbase) us_error_set(err, US_ERR_NOMEM, "out of memory snapping the drawing");
  else if (!prepare(&sn, tol, tol_abs, rel, err)) {
    for (int pass = 0; pass < SNAP_PASSES; pass++) {
      int m = s->ground ? snap_ground(&sn) : 0;
      for (int r = 0; r < s->nbody; r++)
        for (int k = 0; k < s->bodies[sn.order[r]].nvert; k++) m += snap_vertex(&sn, sn.order[r], k);
      if (!m) break;
    }
    moved = count_moved(&sn);
  }
  us_free(tol), us_free(sn.box), us_free(sn.vbase), us_free(sn.moved);
  us_free(sn.adj), us_free(sn.adj_start), us_free(sn.order), us_free(sn.rank);
  return moved;
}
