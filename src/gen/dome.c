/* A hemispherical dome of voussoir courses standing on the ground.
 *
 * Geometry: the dome's centre is the origin, z up. Course k (0-based from
 * the ground) lies between latitudes phi_k = k P / n and phi_{k+1}, where
 * P = 90 - oculus degrees; voussoir j of a course lies between longitudes
 * theta_j = 2 pi j / m and theta_{j+1} (m = segments). A voussoir is the
 * convex hull of the 8 corners r (cos phi cos theta, cos phi sin theta,
 * sin phi) for r in {R, R + T} and the course's two latitudes and two
 * longitudes. Its 6 faces are planar: the side joints lie in meridian
 * planes; a bed joint joins two lines through the origin (the generators of
 * the cone of latitude phi at two longitudes), hence is a plane through the
 * origin; the inner and outer faces are isosceles trapezoids, the inner one
 * the outer one scaled by R / (R + T) about the origin. So a voussoir is a
 * frustum of a pyramid with its apex at the origin: convex, and the joints
 * of two neighbours (side by side, or one course above the other: the
 * meridians are aligned, stack bond) are the same 4 corners, computed from
 * the same (r, phi, theta) and so bit-identical: every joint is a face
 * contact. The bottom course's bed has z = R sin 0 = 0 exactly (on the
 * ground).
 *
 * The opening at the top (latitude P) is the oculus; with g->cap it is
 * closed by one keystone, the hull of the top ring's 2 m upper corners and
 * the outer pole (0, 0, R + T): the region above the faceted cone of
 * latitude P is convex, so the keystone's lower faces are exactly the top
 * course's upper beds (plus a horizontal face spanning the inner ring).
 *
 * Statics, in short: a complete course is a horizontal arch of wedges. Its
 * beds push each voussoir up and inward (the bed of latitude phi is tilted
 * by phi), its radial side joints push back outward (hoop compression), so
 * a complete ring stands even without friction. A lone voussoir, or the end
 * of a broken ring, has no hoop force on its open side and slides inward
 * when tan(phi) > mu: a course above latitude atan(mu) cannot be started
 * one block at a time, which is why a dome cannot be unstacked one voussoir
 * at a time (docs/format.md, "Generators").
 *
 * Chamfer (g->chamfer = c > 0): the two lower side edges of every voussoir
 * are bevelled, each lower corner replaced by a point c of the way along
 * the bed and one c of the way up the side joint. The top of a course is a
 * faceted cone with a valley along every meridian, and a sharp voussoir's
 * lower side edges lie in those valleys against its diagonal neighbours
 * below: a real contact for exact blocks, through which the two diagonal
 * neighbours can pinch a lone voussoir and hold it by friction. Bevelled,
 * those edges clear the valleys (960 contacts for the default dome instead
 * of 1,824), and a lone voussoir rests on its bed alone, as the statics
 * above assume.
 *
 * Bodies: course by course from the ground, within a course by longitude
 * from theta = 0 counter-clockwise seen from above; the keystone last. */
#include "gen.h"

#include <math.h>

#define US_PI 3.14159265358979323846

static us_Status check_dome(const us_GenSettings *g, us_Error *err) {
  us_Status st = us_gen_check_common(g, "dome", err);
  if (!st) st = us_gen_check_positive(g->radius, "dome", "radius", err);
  if (!st) st = us_gen_check_positive(g->thickness, "dome", "thickness", err);
  if (!st && g->n < 1) st = us_error_set(err, US_ERR_USAGE, "dome: courses must be >= 1, got %d", g->n);
  if (!st && g->segments < 3)
    st = us_error_set(err, US_ERR_USAGE, "dome: segments must be >= 3, got %d", g->segments);
  if (!st && !(g->oculus > 0 && g->oculus < 90))
    st = us_error_set(err, US_ERR_USAGE,
                      "dome: oculus must be in (0, 90) degrees from the vertical, got %g", g->oculus);
  if (!st && !(g->chamfer >= 0 && g->chamfer < 0.5))
    st = us_error_set(err, US_ERR_USAGE, "dome: chamfer must be in [0, 0.5), got %g", g->chamfer);
  if (!st && (long)g->n * g->segments + 1 > US_GEN_MAX_BODIES)
    st = us_error_set(err, US_ERR_USAGE, "dome: %ld voussoirs is more than the limit of %ld",
                      (long)g->n * g->segments, US_GEN_MAX_BODIES);
  return st;
}

/* Latitude of course boundary k, radians. */
static double latitude(const us_GenSettings *g, int k) {
  return (double)k * ((90.0 - g->oculus) * (US_PI / 180.0)) / (double)g->n;
}

/* The corner at radius r, latitude boundary k, longitude boundary j (taken
 * modulo segments, so the last joint closes on the first bit for bit). */
static void corner(const us_GenSettings *g, double r, int k, int j, double *p) {
  double phi = latitude(g, k), theta = 2.0 * US_PI * (double)(j % g->segments) / (double)g->segments;
  p[0] = r * cos(phi) * cos(theta);
  p[1] = r * cos(phi) * sin(theta);
  p[2] = r * sin(phi);
}

/* p = (1 - t) a + t b. */
static void lerp3(const double *a, const double *b, double t, double *p) {
  for (int d = 0; d < 3; d++) p[d] = (1.0 - t) * a[d] + t * b[d];
}

/* Voussoir j of course k as body number `id`: the hull of its 8 corners,
 * or with g->chamfer = c > 0 its lower side edges bevelled: each lower
 * corner becomes two points, one a fraction c along the bed towards the
 * other side (on the bed's plane: a combination of two points of that
 * plane through the origin) and one a fraction c up the side joint (on the
 * meridian plane and the inner or outer face). */
static us_Status add_voussoir(us_Structure *s, const us_GenSettings *g, int id, int k, int j,
                              us_Error *err) {
  double p[36], c = g->chamfer;
  int np = 0;
  for (int q = 0; q < 8; q++) {
    double r = q & 1 ? g->radius + g->thickness : g->radius, *at = p + 3 * np++;
    int up = (q >> 1) & 1, side = q >> 2;
    corner(g, r, k + up, j + side, at);
    if (up || !(c > 0)) continue;
    double across[3], above[3];
    corner(g, r, k, j + 1 - side, across);
    corner(g, r, k + 1, j + side, above);
    lerp3(at, above, c, p + 3 * np++);
    lerp3(at, across, c, at);
  }
  return us_gen_add_solid(s, g, id, np, p, err);
}

/* The keystone over the top ring as body number `id`. */
static us_Status add_cap(us_Structure *s, const us_GenSettings *g, int id, us_Error *err) {
  int m = g->segments;
  double *p = us_malloc((size_t)(2 * m + 1) * 3 * sizeof *p);
  if (!p) return us_error_set(err, US_ERR_NOMEM, "dome: out of memory");
  for (int j = 0; j < m; j++) {
    corner(g, g->radius, g->n, j, p + 6 * j);
    corner(g, g->radius + g->thickness, g->n, j, p + 6 * j + 3);
  }
  p[6 * m] = 0.0, p[6 * m + 1] = 0.0, p[6 * m + 2] = g->radius + g->thickness;
  us_Status st = us_gen_add_solid(s, g, id, 2 * m + 1, p, err);
  us_free(p);
  return st;
}

us_Structure *us_gen_dome(const us_GenSettings *g, us_Error *err) {
  if (check_dome(g, err)) return NULL;
  us_Structure *s = us_gen_begin_dim(g, 3, err);
  us_Status st = s ? US_OK : US_ERR_NOMEM;
  int id = 0;
  for (int k = 0; !st && k < g->n; k++)
    for (int j = 0; !st && j < g->segments; j++) st = add_voussoir(s, g, id++, k, j, err);
  if (!st && g->cap) st = add_cap(s, g, id, err);
  if (st) {
    us_structure_free(s);
    return NULL;
  }
  return us_gen_finish(s, g, err);
}
