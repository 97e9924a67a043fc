/* Validation of a structure before its mass properties and contacts are
 * computed: every problem is reported as US_ERR_INPUT with a message that
 * names the body.
 *
 * Two passes. The first checks values that need no tolerance (finite
 * numbers, vertex counts, masses, densities, friction, point bodies only
 * with explicit contacts). Then the structure is measured (bounding box ->
 * scale -> contact_tol), and the second pass checks shapes against that
 * tolerance: the polygon must be simple, its area must exceed
 * tol * diameter (the body is on average thicker than the tolerance), and
 * with a ground no vertex may lie below y = -tol. Polygons are made
 * counter-clockwise in place (vertex 0 is kept). On error contact_tol is
 * restored, so a failed call leaves the structure as it was apart from
 * orientation. */
#include "geometry/geometry.h"
#include "model.h"

#include <math.h>

static us_Status check_globals(const us_Structure *s, us_Error *err) {
  if (s->dim != 2)
    return us_error_set(err, US_ERR_INPUT, "dimension %d is not supported (only 2)", s->dim);
  for (int k = 0; k < 3; k++)
    if (!isfinite(s->gravity[k])) return us_error_set(err, US_ERR_INPUT, "gravity is not finite");
  if (isnan(s->friction) || s->friction < 0) /* INFINITY: no sliding */
    return us_error_set(err, US_ERR_INPUT, "default friction %g must be >= 0 or infinite",
                        s->friction);
  if (isnan(s->contact_tol) || isinf(s->contact_tol))
    return us_error_set(err, US_ERR_INPUT, "contact tolerance is not finite");
  for (int k = 0; k < s->ncontact; k++)
    if (!isfinite(s->contacts[k].p[0]) || !isfinite(s->contacts[k].p[1]) ||
        isnan(s->contacts[k].mu) || s->contacts[k].mu < 0)
      return us_error_set(err, US_ERR_INPUT, "contact %d: non-finite point or bad friction", k);
  return US_OK;
}

/* Mass, density and friction of one body (either kind). */
static us_Status check_material(const us_Body *b, us_Error *err) {
  if (b->mass_given && !b->fixed && !(isfinite(b->mass) && b->mass > 0))
    return us_error_set(err, US_ERR_INPUT, "body '%s': mass %g must be finite and > 0", b->id,
                        b->mass);
  if (b->nvert > 0 && !b->mass_given && !(isfinite(b->density) && b->density > 0))
    return us_error_set(err, US_ERR_INPUT, "body '%s': density %g must be finite and > 0", b->id,
                        b->density);
  if (isnan(b->friction))
    return us_error_set(err, US_ERR_INPUT, "body '%s': friction %g must be >= 0 or infinite", b->id,
                        b->friction);
  if (!isfinite(b->inertia) || b->inertia < 0)
    return us_error_set(err, US_ERR_INPUT, "body '%s': inertia %g must be finite and >= 0", b->id,
                        b->inertia);
  return US_OK;
}

static us_Status check_values(const us_Structure *s, const us_Body *b, us_Error *err) {
  int explicit_ok = s->explicit_contacts || s->ncontact > 0;
  if (b->nvert == 0) {
    if (!explicit_ok)
      return us_error_set(err, US_ERR_INPUT,
                          "body '%s' has no polygon (only allowed with explicit contacts)", b->id);
    if (!isfinite(b->com[0]) || !isfinite(b->com[1]))
      return us_error_set(err, US_ERR_INPUT, "body '%s': centre is not finite", b->id);
    if (!b->fixed && !(isfinite(b->mass) && b->mass > 0))
      return us_error_set(err, US_ERR_INPUT, "body '%s': mass %g must be finite and > 0", b->id,
                          b->mass);
    return check_material(b, err);
  }
  if (b->nvert < 3 || !b->verts)
    return us_error_set(err, US_ERR_INPUT, "body '%s': polygon has %d vertices (needs >= 3)", b->id,
                        b->nvert);
  for (int k = 0; k < 2 * b->nvert; k++)
    if (!isfinite(b->verts[k]))
      return us_error_set(err, US_ERR_INPUT, "body '%s': vertex %d has a non-finite coordinate",
                          b->id, k / 2);
  return check_material(b, err);
}

static us_Status defect_error(const us_Body *b, us_PolyDefect d, int i, int j, us_Error *err) {
  switch (d) {
    case US_POLY_NOMEM:
      return us_error_set(err, US_ERR_NOMEM, "out of memory checking body '%s'", b->id);
    case US_POLY_REPEATED_VERTEX:
      return us_error_set(err, US_ERR_INPUT,
                          "body '%s': repeated vertex (vertices %d and %d coincide)", b->id, i, j);
    case US_POLY_EDGES_FOLD:
      return us_error_set(err, US_ERR_INPUT,
                          "body '%s': polygon folds back on itself (edges %d and %d overlap)",
                          b->id, i, j);
    default:
      return us_error_set(err, US_ERR_INPUT,
                          "body '%s': polygon is self-intersecting (edges %d and %d cross)", b->id,
                          i, j);
  }
}

/* Do edges i and j of b cross at one point interior to both? */
static int crosses_properly(const us_Body *b, int i, int j) {
  const double *v = b->verts;
  int n = b->nvert;
  return us_segment_intersect(us_poly_vertex(v, n, i), us_poly_vertex(v, n, i + 1),
                              us_poly_vertex(v, n, j), us_poly_vertex(v, n, j + 1), NULL,
                              NULL) == US_SEG_PROPER;
}

/* Simplicity, area, orientation and ground of one polygon body. A sliver
 * thinner than tol always has vertices or edges within tol of each other,
 * so the area is judged before those defects are reported (the clearer
 * message), but after a proper crossing (a bow-tie may have zero area). */
static us_Status check_shape(const us_Structure *s, us_Body *b, double tol, us_Error *err) {
  double bb[4];
  us_poly_bbox(b->verts, b->nvert, bb);
  int i = -1, j = -1;
  us_PolyDefect d = us_poly_check_simple(b->verts, b->nvert, tol, &i, &j);
  if (d == US_POLY_NOMEM || (d == US_POLY_EDGES_CROSS && crosses_properly(b, i, j)))
    return defect_error(b, d, i, j, err);
  double area = us_poly_signed_area(b->verts, b->nvert);
  if (!(fabs(area) > tol * hypot(bb[2] - bb[0], bb[3] - bb[1])))
    return us_error_set(err, US_ERR_INPUT, "body '%s': polygon has (almost) zero area (%g)", b->id,
                        area);
  if (d != US_POLY_SIMPLE) return defect_error(b, d, i, j, err);
  us_poly_make_ccw(b->verts, b->nvert);
  if (s->ground && bb[1] < -tol)
    return us_error_set(err, US_ERR_INPUT, "body '%s' is below the ground (y = %g)", b->id, bb[1]);
  return US_OK;
}

us_Status us_model_validate(us_Structure *s, us_Error *err) {
  us_Status st = check_globals(s, err);
  for (int i = 0; !st && i < s->nbody; i++) st = check_values(s, &s->bodies[i], err);
  if (st) return st;
  double tol0 = s->contact_tol;
  us_model_measure(s); /* the tolerance scales with the structure */
  double tol = s->contact_tol;
  for (int i = 0; !st && i < s->nbody; i++)
    if (s->bodies[i].nvert > 0) st = check_shape(s, &s->bodies[i], tol, err);
  if (st) s->contact_tol = tol0;
  return st;
}
