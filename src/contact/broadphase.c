/* Broad phase of contact detection: sort and sweep over axis-aligned boxes.
 *
 * Every polygon body gets its box inflated by its own tolerance (at least
 * the tolerance of any pair it belongs to, which is the smaller of the two
 * bodies' own). The boxes are sorted by
 * their low end along the axis on which the box centres spread most (x for
 * a wide wall, y for a tall column), ties broken by body index so the order
 * is deterministic; a sweep then compares each box only with the following
 * boxes that start before it ends, and keeps the pairs that also overlap on
 * the other axis. Pairs of two fixed bodies are dropped (no contact between
 * them matters). The pair list is finally sorted by (i, j). */
#include "contact.h"

#include <math.h>
#include <stdlib.h>

typedef struct Box {
  double lo[2], hi[2];
  int body;
} Box;

/* Order by the low end on one axis, then by body index (a total order, so
 * qsort gives the same result on every run). One comparator per axis keeps
 * qsort free of shared state. */
static int box_cmp_on(const Box *a, const Box *b, int ax) {
  if (a->lo[ax] != b->lo[ax]) return a->lo[ax] < b->lo[ax] ? -1 : 1;
  return (a->body > b->body) - (a->body < b->body);
}
static int box_cmp_x(const void *pa, const void *pb) { return box_cmp_on(pa, pb, 0); }
static int box_cmp_y(const void *pa, const void *pb) { return box_cmp_on(pa, pb, 1); }

static int pair_cmp(const void *pa, const void *pb) {
  const us_BodyPair *a = pa, *b = pb;
  if (a->i != b->i) return a->i < b->i ? -1 : 1;
  return (a->j > b->j) - (a->j < b->j);
}

/* Fill boxes of polygon bodies; returns their count. */
static int make_boxes(const us_Structure *s, const double *tol, Box *bx) {
  int n = 0;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    if (b->nvert < 3) continue;
    double bb[4];
    us_poly_bbox(b->verts, b->nvert, bb);
    double t = tol[i];
    bx[n] = (Box){{bb[0] - t, bb[1] - t}, {bb[2] + t, bb[3] + t}, i};
    n++;
  }
  return n;
}

/* The axis (0 = x, 1 = y) along which the box centres spread most. */
static int choose_axis(const Box *bx, int n) {
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (int k = 0; k < n; k++)
    for (int d = 0; d < 2; d++) {
      double c = 0.5 * (bx[k].lo[d] + bx[k].hi[d]);
      lo[d] = US_MIN(lo[d], c);
      hi[d] = US_MAX(hi[d], c);
    }
  return n > 0 && hi[1] - lo[1] > hi[0] - lo[0] ? 1 : 0;
}

static int push_pair(us_BodyPair **pairs, int *np, int *cap, int a, int b) {
  if (US_GROW(*pairs, *cap, *np + 1)) return -1;
  (*pairs)[*np].i = US_MIN(a, b);
  (*pairs)[*np].j = US_MAX(a, b);
  (*np)++;
  return 0;
}

static int sweep(const us_Structure *s, const Box *bx, int n, int ax, us_BodyPair **pairs, int *np,
                 int *cap) {
  int other = 1 - ax;
  for (int k = 0; k < n; k++)
    for (int m = k + 1; m < n && bx[m].lo[ax] <= bx[k].hi[ax]; m++) {
      if (bx[m].lo[other] > bx[k].hi[other] || bx[k].lo[other] > bx[m].hi[other]) continue;
      if (s->bodies[bx[k].body].fixed && s->bodies[bx[m].body].fixed) continue;
      if (push_pair(pairs, np, cap, bx[k].body, bx[m].body)) return -1;
    }
  return 0;
}

us_Status us_broadphase(const us_Structure *s, const double *tol, us_BodyPair **pairs,
                        int *npairs, us_Error *err) {
  *pairs = NULL;
  *npairs = 0;
  int cap = 0;
  Box *bx = us_malloc((size_t)(s->nbody > 0 ? s->nbody : 1) * sizeof *bx);
  if (!bx || US_GROW(*pairs, cap, 16)) {
    us_free(bx);
    return us_error_set(err, US_ERR_NOMEM, "out of memory in contact detection");
  }
  int n = make_boxes(s, tol, bx);
  int ax = choose_axis(bx, n);
  qsort(bx, (size_t)n, sizeof *bx, ax ? box_cmp_y : box_cmp_x);
  int rc = sweep(s, bx, n, ax, pairs, npairs, &cap);
  us_free(bx);
  if (rc) {
    us_free(*pairs);
    *pairs = NULL;
    *npairs = 0;
    return us_error_set(err, US_ERR_NOMEM, "out of memory in contact detection");
  }
  qsort(*pairs, (size_t)*npairs, sizeof **pairs, pair_cmp);
  return US_OK;
}
