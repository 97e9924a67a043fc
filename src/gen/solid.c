/* 3D generators: a tower of boxes and a pyramid of square courses (the 3D
 * wall shares the 2D wall's code in regular.c).
 *
 * Layout: z is up from the ground (z = 0); course or level k spans
 * [k h, (k + 1) h]. Coordinates come from integer half-block indices
 * (x = q * w / 2, y = q * d / 2, z = k * h), so faces shared by two boxes
 * are bit-identical and contacts are exact. Bodies are numbered from the
 * bottom, and within a course along x, then y.
 *
 * tower: g->n boxes of g->width x g->depth x g->height on one vertical
 * axis; with g->jitter > 0 each box is turned about that axis by an angle
 * drawn uniformly from [-jitter, jitter] degrees (splitmix64 stream seeded
 * with g->seed). Only the footprint turns, the level heights stay exact,
 * so successive boxes touch face to face on a polygon (an octagon for two
 * squares 45 degrees apart).
 *
 * pyramid3d: g->n courses in stack bond; course r holds (n - r)^2 boxes
 * and starts half a block further along x and y than course r - 1, so
 * every box above the ground rests on four (n courses: n (n + 1) (2n + 1)
 * / 6 boxes; 30 courses: 9,455). */
#include "gen.h"

#include "geometry/geometry3.h"

#include <math.h>

/* Checks of the box generators: common settings, box size, count. */
static us_Status check_boxes(const us_GenSettings *g, const char *what, long total, us_Error *err) {
  us_Status st = us_gen_check_common(g, what, err);
  if (!st) st = us_gen_check_positive(g->width, what, "block width", err);
  if (!st) st = us_gen_check_positive(g->depth, what, "block depth", err);
  if (!st) st = us_gen_check_positive(g->height, what, "block height", err);
  if (!st && g->n < 1) st = us_error_set(err, US_ERR_USAGE, "%s: n must be >= 1, got %d", what, g->n);
  if (!st && total > US_GEN_MAX_BODIES)
    st = us_error_set(err, US_ERR_USAGE, "%s: %ld blocks is more than the limit of %ld", what, total,
                      US_GEN_MAX_BODIES);
  return st;
}

/* The footprint of a w x d rectangle centred at (cx, cy), turned by deg. */
static void turned_rect(double cx, double cy, double w, double d, double deg, double xy[8]) {
  double a = deg * (3.14159265358979323846 / 180.0), c = cos(a), s = sin(a);
  static const double sx[4] = {-0.5, 0.5, 0.5, -0.5}, sy[4] = {-0.5, -0.5, 0.5, 0.5};
  for (int k = 0; k < 4; k++) {
    double x = sx[k] * w, y = sy[k] * d;
    xy[2 * k] = deg == 0 ? cx + x : cx + c * x - s * y;
    xy[2 * k + 1] = deg == 0 ? cy + y : cy + s * x + c * y;
  }
}

/* A uniform angle in [-j, j] degrees. */
static double draw_angle(uint64_t *rng, double j) {
  double u = (double)(us_rng_next(rng) >> 11) * (1.0 / 9007199254740992.0);
  return j * (2.0 * u - 1.0);
}

us_Structure *us_gen_tower(const us_GenSettings *g, us_Error *err) {
  if (check_boxes(g, "tower", g ? (long)g->n : 0, err)) return NULL;
  if (!(g->jitter >= 0 && g->jitter <= 180)) {
    us_error_set(err, US_ERR_USAGE, "tower: jitter must be in [0, 180] degrees, got %g", g->jitter);
    return NULL;
  }
  us_Structure *s = us_gen_begin_dim(g, 3, err);
  us_Status st = s ? US_OK : US_ERR_NOMEM;
  uint64_t rng = g->seed;
  for (int k = 0; !st && k < g->n; k++) {
    double xy[8], deg = g->jitter > 0 ? draw_angle(&rng, g->jitter) : 0.0;
    turned_rect(0.5 * g->width, 0.5 * g->depth, g->width, g->depth, deg, xy);
    st = us_gen_add_prism(s, g, k, xy, (double)k * g->height, (double)(k + 1) * g->height, err);
  }
  if (st) {
    us_structure_free(s);
    return NULL;
  }
  return us_gen_finish(s, g, err);
}

us_Structure *us_gen_pyramid3d(const us_GenSettings *g, us_Error *err) {
  long n = g ? (long)g->n : 0;
  if (check_boxes(g, "pyramid3d", n * (n + 1) * (2 * n + 1) / 6, err)) return NULL;
  us_Structure *s = us_gen_begin_dim(g, 3, err);
  us_Status st = s ? US_OK : US_ERR_NOMEM;
  int k = 0;
  double hw = 0.5 * g->width, hd = 0.5 * g->depth;
  for (long r = 0; !st && r < n; r++)
    for (long j = 0; !st && j < n - r; j++)
      for (long i = 0; !st && i < n - r; i++, k++)
        st = us_gen_add_box3(s, g, k, (double)(r + 2 * i) * hw, (double)(r + 2 * j) * hd,
                             (double)r * g->height, (double)(r + 2 * i + 2) * hw,
                             (double)(r + 2 * j + 2) * hd, (double)(r + 1) * g->height, err);
  if (st) {
    us_structure_free(s);
    return NULL;
  }
  return us_gen_finish(s, g, err);
}
