/* Semicircular arch of uniform voussoirs with radial joints, standing on
 * the ground.
 *
 * Geometry: g->radius is the radius of the arch's centre line (the circle
 * halfway through the ring) and g->thickness the ring's radial thickness,
 * so the intrados has radius ri = R - t/2 and the extrados ro = R + t/2.
 * The centre of the circles is (ro, 0), so the arch spans x in [0, 2 ro]
 * and stands on y = 0. With theta_i = pi (1 - i / n), i = 0..n, voussoir
 * "b<i+1>" is the quadrilateral of the intrados and extrados points at
 * theta_i and theta_{i+1} (straight chords, not arcs): b1 stands on the
 * ground at the left, b<n> at the right. Both neighbours of a joint compute
 * its points by the same expression (bit-identical coordinates), and the
 * springing points are put exactly on y = 0.
 *
 * With g->loose = k, unit blocks b<n+1> .. b<n+k> stand on the ground to
 * the right of the arch, 0.5 apart: a structure whose parts touch only
 * through the ground (the planner's test of `none` next to easy parts).
 *
 * Stability (checked by tests/test_gen.c with the LP): the thrust line
 * must fit inside the ring. Measured with the LP (bisection on t / R,
 * friction 0.5): the thinnest ring that stands has t / R = 0.107 for 10
 * voussoirs and 0.1074 for 30 or 50 (the classical minimum for a continuous
 * ring is about 0.107), between 0.095 and 0.107 for 4 to 12 voussoirs; 2 or 3
 * voussoirs stand at any thickness tried (down to 0.01). Friction matters at
 * the joints near the springings: with mu = 0.3 arches of 8 or more
 * voussoirs slide at any thickness; mu = 0.4 already gives the minima above.
 * The defaults (R = 3, t = 0.5, t / R = 0.17, friction 0.5, 10 voussoirs)
 * stand. Every voussoir is needed: removing any
 * single one brings the arch down, so no one-at-a-time order exists. */
#include "gen.h"

#include <math.h>

static const double kPi = 3.14159265358979323846;

/* Point at angle index i of the circle of radius rad centred at (cx, 0). */
static void arch_point(int i, int n, double cx, double rad, double *x, double *y) {
  if (i == 0 || i == n) { /* the springings: exactly on the ground */
    *x = cx + (i == 0 ? -rad : rad);
    *y = 0.0;
    return;
  }
  double th = kPi * (1.0 - (double)i / (double)n);
  *x = cx + rad * cos(th);
  *y = rad * sin(th);
}

static us_Status check_arch(const us_GenSettings *g, us_Error *err) {
  us_Status st = us_gen_check_common(g, "arch", err);
  if (!st) st = us_gen_check_positive(g->radius, "arch", "radius", err);
  if (!st) st = us_gen_check_positive(g->thickness, "arch", "thickness", err);
  if (!st && !(g->thickness < 2.0 * g->radius))
    st = us_error_set(err, US_ERR_USAGE,
                      "arch: thickness (%g) must be less than twice the centre-line radius (%g)",
                      g->thickness, g->radius);
  if (!st && (g->loose < 0 || g->loose > US_GEN_MAX_BODIES))
    st = us_error_set(err, US_ERR_USAGE, "arch: loose blocks must be in 0..%ld, got %d",
                      US_GEN_MAX_BODIES, g->loose);
  if (!st && (g->n < 2 || g->n > US_GEN_MAX_BODIES))
    st = us_error_set(err, US_ERR_USAGE, "arch: n (voussoirs) must be in 2..%ld, got %d",
                      US_GEN_MAX_BODIES, g->n);
  return st;
}

us_Structure *us_gen_arch(const us_GenSettings *g, us_Error *err) {
  if (check_arch(g, err)) return NULL;
  double ri = g->radius - 0.5 * g->thickness, ro = g->radius + 0.5 * g->thickness;
  us_Structure *s = us_gen_begin(g, err);
  us_Status st = s ? US_OK : US_ERR_NOMEM;
  for (int i = 0; !st && i < g->n; i++) {
    double q[8]; /* intrados i, intrados i+1, extrados i+1, extrados i */
    arch_point(i, g->n, ro, ri, &q[0], &q[1]);
    arch_point(i + 1, g->n, ro, ri, &q[2], &q[3]);
    arch_point(i + 1, g->n, ro, ro, &q[4], &q[5]);
    arch_point(i, g->n, ro, ro, &q[6], &q[7]);
    st = us_gen_add(s, g, i, 4, q, err);
  }
  for (int i = 0; !st && i < g->loose; i++) { /* a unit block every 1.5 */
    double x = 2.0 * ro + 1.0 + 1.5 * i;
    st = us_gen_add_box(s, g, g->n + i, x, 0.0, x + 1.0, 1.0, err);
  }
  if (st) {
    us_structure_free(s);
    return NULL;
  }
  return us_gen_finish(s, g, err);
}
