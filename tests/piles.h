/* Random small piles for differential tests: pile_random(rng, n) builds a
 * finalized 2D structure of exactly n bodies (4 to 12) that mixes the
 * situations the planner must tell apart, so that over many piles the
 * three outcomes (an order exists, the pile stands but no one-at-a-time
 * order exists, the pile does not stand) are all common. Header-only
 * (static inline): a test links only its concept library; this needs only
 * the structure builder (us_model) and libm.
 *
 * A pile is a row of features side by side on the ground (left to right,
 * gaps of 1/4 to 1), then boxes dropped on the skyline:
 *   - counterweight (3 bodies): a pier, a plank on it overhanging by 1/2 to
 *     2 on one side (its centre beyond the pier, so it tips alone), a dense
 *     block (density 2 to 9) on its inner end: the plank must go before the
 *     block, or the pile falls where the block is too light;
 *   - leaning pair (2): two slabs meeting on a vertical face above the
 *     middle, parallelograms or wedges on one ground vertex (an inverted V):
 *     each needs the other, and without friction they slide apart;
 *   - slab on a block (2): a box and a slab leaning on its side (the slab
 *     must go first);
 *   - arch (3 to 5 voussoirs): semicircular with radial joints on the
 *     ground, thick enough to stand with friction; every voussoir is needed;
 *   - boxes (1 each): dropped at a random place on the exact skyline of the
 *     boxes and planks below (like tests/test_plan.c's old random pile),
 *     never over a leaning pair or an arch; 1 in 5 is dense (density 5).
 * Friction: 0 on 30 % of the piles, else uniform in [0.3, 0.8].
 *
 * Coordinates other than the arches' are multiples of 1/16 (exact), so
 * faces touch exactly; an arch's joints are computed once for both
 * neighbours. A draw whose finalize fails (an overlap) is freed and NULL
 * is returned; tests skip it (measured by tests/test_gen_piles.c: rare). */
#ifndef US_TEST_PILES_H
#define US_TEST_PILES_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "test.h"
#include "unstack/unstack.h"

#define PILE_MAX_RECTS 16

/* xorshift64 in [0, 1); a zero state is moved off the fixed point. */
static inline double pile_rnd(unsigned long long *s) {
  if (!*s) *s = 0x9e3779b97f4a7c15ULL;
  return test_rnd(s);
}

/* Uniform multiple of 1/16 in [lo, hi]. */
static inline double pile_grid(unsigned long long *s, double lo, double hi) {
  int steps = (int)floor((hi - lo) * 16.0 + 0.5);
  return lo + floor(pile_rnd(s) * (steps + 1)) / 16.0;
}

typedef struct PileRect {
  double x0, x1, top;
  int closed; /* nothing may be dropped over it (slabs, arches) */
} PileRect;

typedef struct Pile {
  us_Structure *s;
  unsigned long long *rng;
  int nbody;
  double xnext; /* left end of the next feature */
  PileRect r[PILE_MAX_RECTS];
  int nr;
} Pile;

static inline void pile_rect(Pile *p, double x0, double x1, double top, int closed) {
  if (p->nr < PILE_MAX_RECTS) p->r[p->nr++] = (PileRect){x0, x1, top, closed};
}

/* Add polygon body (2*nv coordinates) with the next id "p<k>". */
static inline void pile_poly(Pile *p, int nv, const double *xy, double density) {
  char id[16];
  snprintf(id, sizeof id, "p%d", p->nbody++);
  us_structure_add_body(p->s,
                        &(us_BodyDef){.id = id,
                                      .nvert = nv,
                                      .xy = xy,
                                      .density = density,
                                      .friction = -1.0},
                        NULL);
}

static inline void pile_box(Pile *p, double x0, double y0, double w, double h, double density) {
  double xy[8] = {x0, y0, x0 + w, y0, x0 + w, y0 + h, x0, y0 + h};
  pile_poly(p, 4, xy, density);
}

/* The next feature's left end, after a gap of 1/4 to 1. */
static inline double pile_slot(Pile *p) { return p->xnext + pile_grid(p->rng, 0.25, 1.0); }

/* Counterweight: pier, overhanging plank, dense block on its inner end. */
static inline void pile_counterweight(Pile *p) {
  double x = pile_slot(p), pw = pile_grid(p->rng, 0.5, 1.0), ph = pile_grid(p->rng, 0.25, 1.0);
  double over = pile_grid(p->rng, 0.5, 2.0), back = pile_grid(p->rng, 0.0, 0.25);
  double t = pile_grid(p->rng, 0.125, 0.25), cw = pile_grid(p->rng, 0.25, 0.5);
  double ch = pile_grid(p->rng, 0.25, 0.5);
  int right = pile_rnd(p->rng) < 0.5;
  double p0 = right ? x + back : x + over + back, p1 = p0 + pw; /* pier */
  double l0 = right ? p0 - back : p0 - over, l1 = right ? p1 + over : p1 + back;
  double c0 = right ? l0 : l1 - cw;
  /* the density that balances the plank about the pier's edge, times 0.5
     to 3 (at least 1, at most 10) */
  double edge = right ? p1 : p0, arm_l = fabs(0.5 * (l0 + l1) - edge);
  double arm_c = fabs(c0 + 0.5 * cw - edge), wl = (l1 - l0) * t;
  double dens = fmin(10.0, fmax(1.0, wl * arm_l / (cw * ch * fmax(arm_c, 0.0625)) *
                                          (0.5 + 2.5 * pile_rnd(p->rng))));
  pile_box(p, p0, 0, pw, ph, 1.0);
  pile_box(p, l0, ph, l1 - l0, t, 1.0);
  pile_box(p, c0, ph + t, cw, ch, dens);
  pile_rect(p, p0, p1, ph, 0);
  pile_rect(p, l0, l1, ph + t, 0);
  pile_rect(p, c0, c0 + cw, ph + t + ch, 0);
  p->xnext = l1;
}

/* Leaning pair: two slabs (parallelograms, or wedges on one ground
 * vertex) meeting on the vertical face x = mid, an inverted V. */
static inline void pile_leaning(Pile *p) {
  double x = pile_slot(p), span = pile_grid(p->rng, 0.5, 1.0), top = pile_grid(p->rng, 1.0, 2.0);
  double face = pile_grid(p->rng, 0.25, 0.5), foot = pile_grid(p->rng, 0.25, 0.5);
  double mid = x + span + foot, y0 = top - face;
  if (pile_rnd(p->rng) < 0.5) { /* parallelograms with a foot on the ground */
    double l[8] = {x, 0, x + foot, 0, mid, y0, mid, top};
    double r[8] = {mid + span, 0, mid + span + foot, 0, mid, top, mid, y0};
    pile_poly(p, 4, l, 1.0), pile_poly(p, 4, r, 1.0);
  } else { /* wedges: one vertex on the ground */
    double l[6] = {x + foot, 0, mid, y0, mid, top};
    double r[6] = {mid + span, 0, mid, top, mid, y0};
    pile_poly(p, 3, l, 1.0), pile_poly(p, 3, r, 1.0);
  }
  pile_rect(p, x, mid + span + foot, top, 1);
  p->xnext = mid + span + foot;
}

/* A box and a slab leaning on its side (left or right). */
static inline void pile_slab_on_block(Pile *p) {
  double x = pile_slot(p), bw = pile_grid(p->rng, 0.5, 1.0), bh = pile_grid(p->rng, 0.75, 1.5);
  double span = pile_grid(p->rng, 0.5, 1.0), foot = pile_grid(p->rng, 0.25, 0.5);
  double top = pile_grid(p->rng, 0.5, bh), face = pile_grid(p->rng, 0.25, 0.375);
  if (pile_rnd(p->rng) < 0.5) { /* slab on the left, leaning right */
    double b0 = x + span + foot, xy[8] = {x, 0, x + foot, 0, b0, top - face, b0, top};
    pile_box(p, b0, 0, bw, bh, 1.0);
    pile_poly(p, 4, xy, 1.0);
    pile_rect(p, x, b0 + bw, bh, 1);
    p->xnext = b0 + bw;
  } else {
    double b1 = x + bw, xy[8] = {b1 + span, 0, b1 + span + foot, 0, b1, top, b1, top - face};
    pile_box(p, x, 0, bw, bh, 1.0);
    pile_poly(p, 4, xy, 1.0);
    pile_rect(p, x, b1 + span + foot, bh, 1);
    p->xnext = b1 + span + foot;
  }
}

/* Semicircular arch of k voussoirs (radial joints) on the ground. */
static inline void pile_arch(Pile *p, int k) {
  double x = pile_slot(p), rad = pile_grid(p->rng, 0.75, 1.5);
  double t = rad * (0.2 + 0.2 * pile_rnd(p->rng)), ri = rad - 0.5 * t, ro = rad + 0.5 * t;
  double cx = x + ro, px[2][6], py[2][6];
  for (int i = 0; i <= k; i++) /* joint i: intrados and extrados points */
    for (int e = 0; e < 2; e++) {
      double th = 3.14159265358979323846 * (1.0 - (double)i / k), r = e ? ro : ri;
      px[e][i] = i == 0 ? cx - r : i == k ? cx + r : cx + r * cos(th);
      py[e][i] = i == 0 || i == k ? 0.0 : r * sin(th);
    }
  for (int i = 0; i < k; i++) {
    double xy[8] = {px[0][i], py[0][i], px[0][i + 1], py[0][i + 1],
                    px[1][i + 1], py[1][i + 1], px[1][i], py[1][i]};
    pile_poly(p, 4, xy, 1.0);
  }
  pile_rect(p, x, x + 2 * ro, ro, 1);
  p->xnext = x + 2 * ro;
}

/* Where a box [x0, x0 + w] dropped lands: *y on the skyline; 0 when it
 * would come down on a closed feature; 2 when its centre lies over the
 * x-extent of what it lands on (it rests), else 1. */
static inline int pile_land(const Pile *p, double x0, double w, double *y) {
  double lo = x0 + w, hi = x0;
  *y = 0;
  for (int i = 0; i < p->nr; i++) {
    if (!(p->r[i].x0 < x0 + w && p->r[i].x1 > x0)) continue;
    if (p->r[i].closed) return 0;
    if (p->r[i].top > *y) *y = p->r[i].top;
  }
  for (int i = 0; i < p->nr && *y > 0; i++)
    if (p->r[i].x0 < x0 + w && p->r[i].x1 > x0 && p->r[i].top == *y)
      lo = fmin(lo, fmax(p->r[i].x0, x0)), hi = fmax(hi, fmin(p->r[i].x1, x0 + w));
  return *y == 0 || (lo < x0 + 0.5 * w && x0 + 0.5 * w < hi) ? 2 : 1;
}

/* Drop a box at a random place on the skyline, clear of closed features:
 * a place where it rests is sought first (up to 20 draws), but 1 drop in
 * 16 takes the first clear place whatever it lands on. */
static inline void pile_drop(Pile *p) {
  double w = pile_grid(p->rng, 0.5, 1.5), h = pile_grid(p->rng, 0.25, 0.5), x0 = 0, y = 0;
  double dens = pile_rnd(p->rng) < 0.2 ? 5.0 : 1.0;
  int need = pile_rnd(p->rng) < 1.0 / 16 ? 1 : 2, how = 0;
  for (int tries = 0; tries < 20 && how < need; tries++) {
    x0 = pile_grid(p->rng, 0.0, p->xnext + 0.5);
    how = pile_land(p, x0, w, &y);
  }
  if (!how) x0 = pile_slot(p), y = 0; /* a fresh place on the ground */
  pile_box(p, x0, y, w, h, dens);
  pile_rect(p, x0, x0 + w, y + h, 0);
  if (x0 + w > p->xnext) p->xnext = x0 + w;
}

/* Features first (each while bodies remain), then boxes. */
static inline void pile_features(Pile *p, int n) {
  int want = (int)floor(pile_rnd(p->rng) * 3.0); /* 0, 1 or 2 features */
  for (int f = 0; f < want; f++) {
    int left = n - p->nbody;
    double u = pile_rnd(p->rng);
    if (u < 0.30 && left >= 3) pile_counterweight(p);
    else if (u < 0.55 && left >= 2) pile_leaning(p);
    else if (u < 0.75 && left >= 2) pile_slab_on_block(p);
    else if (left >= 3) pile_arch(p, 3 + (int)floor(pile_rnd(p->rng) * (left >= 5 ? 3 : left - 2)));
  }
}

/* A pile of exactly n bodies (see the file head), finalized; NULL when the
 * draw overlaps (finalize fails). */
static inline us_Structure *pile_random(unsigned long long *rng, int n) {
  Pile p;
  memset(&p, 0, sizeof p);
  p.rng = rng;
  p.s = us_structure_new(2);
  if (!p.s) return NULL;
  p.s->friction = pile_rnd(rng) < 0.3 ? 0.0 : 0.3 + 0.5 * pile_rnd(rng);
  pile_features(&p, n);
  while (p.nbody < n) pile_drop(&p);
  us_Error err;
  if (us_structure_finalize(p.s, &err) != US_OK) {
    us_structure_free(p.s);
    return NULL;
  }
  return p.s;
}

#endif
