/* Mass properties of every body: mass, centre of mass and polar moment of
 * inertia about it.
 *
 * 3D bodies: src/model/solid.c (exact volume integrals over the parts'
 * hulls; the inertia tensor, and its mean principal moment as `inertia`).
 * Polygons (counter-clockwise after validation; either orientation works):
 * mass = density * area unless a mass was given, com = area centroid,
 * inertia = (polar moment about the centroid for density 1) * mass / area,
 * i.e. a uniform body of the final mass. Bodies without geometry (point
 * bodies, explicit contacts only) keep their centre and mass; when their
 * inertia is not given (0) it is derived as mass * r^2 / 3, with r the
 * largest distance from the centre to the body's contact points (a uniform
 * disc of radius r would have mass * r^2 / 2; the exact value is arbitrary,
 * it only has to be positive and of the right size for the torque
 * residuals), or r = the structure's scale (1 if unmeasured) when the body
 * has no contacts. Fixed bodies are computed alike but their mass and
 * inertia are never used (they are infinite).
 *
 * Representable weights: the stability layer works with the shares
 * m_i / M and the unit gravity direction, so body masses and gravity may
 * span the whole double range; what must exist in floating point is each
 * body's mass (density * area must not overflow) and the total weight
 * W = M |g| in newtons, which the reported forces are multiples of: it
 * must be a finite, positive, normal number (a subnormal W would leave
 * the reported forces with too few digits to re-check). Anything else is
 * rejected here with the values that broke it. */
#include "massprops.h"

#include "geometry/geometry.h"
#include "model.h"

#include <float.h>
#include <math.h>

static void polygon_props(us_Body *b) {
  double area = fabs(us_poly_signed_area(b->verts, b->nvert));
  us_Vec2 c = us_poly_centroid(b->verts, b->nvert);
  double j1 = us_poly_polar_moment(b->verts, b->nvert);
  if (!b->mass_given) b->mass = b->density * area;
  b->com[0] = c.x;
  b->com[1] = c.y;
  b->com[2] = 0.0;
  b->inertia = area > 0 ? j1 * b->mass / area : 0.0;
}

/* Largest distance from body i's centre to its contact points (0: none). */
static double contact_radius(const us_Structure *s, int i) {
  const us_Body *b = &s->bodies[i];
  double r = 0.0;
  for (int k = 0; k < s->ncontact; k++) {
    const us_Contact *c = &s->contacts[k];
    if (c->a != i && c->b != i) continue;
    double d = hypot(c->p[0] - b->com[0], c->p[1] - b->com[1]);
    if (s->dim == 3) d = hypot(d, c->p[2] - b->com[2]);
    r = US_MAX(r, d);
  }
  return r;
}

static void point_props(const us_Structure *s, int i) {
  us_Body *b = &s->bodies[i];
  if (!(b->inertia > 0)) {
    double r = contact_radius(s, i);
    if (!(r > 0)) r = s->scale > 0 ? s->scale : 1.0;
    double m = b->mass > 0 && isfinite(b->mass) ? b->mass : 1.0;
    b->inertia = m * r * r / 3.0;
  }
  if (s->dim == 3) /* isotropic: statics does not depend on it */
    for (int k = 0; k < 3; k++)
      for (int j = 0; j < 3; j++) b->inertia3[k][j] = k == j ? b->inertia : 0.0;
}

double us_gravity_norm(const double *g) { return hypot(hypot(g[0], g[1]), g[2]); }

double us_movable_mass(const us_Structure *s) {
  double m = 0.0;
  for (int i = 0; i < s->nbody; i++)
    if (!s->bodies[i].fixed) m += s->bodies[i].mass;
  return m;
}

double us_total_weight(const us_Structure *s) {
  return us_movable_mass(s) * us_gravity_norm(s->gravity);
}

/* A movable body's mass and inertia must be finite and positive. */
static us_Status check_body(const us_Body *b, us_Error *err) {
  if (b->fixed) return US_OK;
  if (isinf(b->mass) && !b->mass_given && b->npart > 0)
    return us_error_set(err, US_ERR_INPUT, "body '%s': density %g * volume overflows",
                        us_id_text(b->id).s, b->density);
  if (isinf(b->mass) && !b->mass_given && b->nvert >= 3)
    return us_error_set(err, US_ERR_INPUT, "body '%s': density %g * area %g overflows",
                        us_id_text(b->id).s,
                        b->density, fabs(us_poly_signed_area(b->verts, b->nvert)));
  if (!(b->mass > 0 && isfinite(b->mass) && isfinite(b->inertia)))
    return us_error_set(err, US_ERR_INPUT, "body '%s': mass %g / inertia %g not usable",
                        us_id_text(b->id).s,
                        b->mass, b->inertia);
  return US_OK;
}

/* The movable bodies (public, unstack.h); here, below its callers in
 * structure.c and the weight check. */
int us_structure_movable_count(const us_Structure *s) {
  int n = 0;
  for (int i = 0; i < s->nbody; i++) n += !s->bodies[i].fixed;
  return n;
}

/* The total weight must be a finite, positive, normal number. */
static us_Status check_weight(const us_Structure *s, us_Error *err) {
  double m = us_movable_mass(s), g = us_gravity_norm(s->gravity), w = m * g;
  if (us_structure_movable_count(s) == 0 || g == 0.0) return US_OK; /* nothing has weight */
  if (isinf(m))
    return us_error_set(err, US_ERR_INPUT, "the total mass of the movable bodies overflows "
                        "(more than %g)", DBL_MAX);
  if (!isfinite(w) || !(w >= DBL_MIN))
    return us_error_set(err, US_ERR_INPUT, "total weight: mass %g * gravity %g %s", m, g,
                        isfinite(w) ? "is below the smallest normal number (2.2e-308)"
                                    : "overflows");
  return US_OK;
}

us_Status us_model_mass_properties(us_Structure *s, us_Error *err) {
  for (int i = 0; i < s->nbody; i++) {
    us_Body *b = &s->bodies[i];
    if (b->npart > 0)
      us_solid_mass_props(b);
    else if (b->nvert >= 3)
      polygon_props(b);
    else
      point_props(s, i);
    us_Status st = check_body(b, err);
    if (st) return st;
  }
  return check_weight(s, err);
}
