/* Validation of a structure before its mass properties and contacts are
 * computed: every problem is reported as US_ERR_INPUT with a message that
 * names the body.
 *
 * Two passes. The first checks values that need no tolerance (finite
 * numbers, vertex counts, masses, densities, friction, point bodies only
 * with explicit contacts). The second checks each polygon's shape against
 * the body's own tolerance (contact_tol when the caller set one, else
 * US_GEOM_TOL_REL times the body's bounding-box diagonal: the tolerance
 * contact detection uses for the body against the ground, and at least the
 * one of any pair it belongs to). First the size and area must be finite
 * (huge coordinates overflow: said so, not reported as a zero area); then
 * the polygon must be simple, its area must exceed tol * diameter (the body
 * is on average thicker than the tolerance), and with a ground no vertex
 * may lie below y = -tol. Polygons are made counter-clockwise in place
 * (vertex 0 is kept). Interpenetration of two bodies is checked by contact
 * detection (contact/overlap.c) with the pair's tolerance. 3D bodies get
 * the same two passes from solid.c (points per part and finite values;
 * then hulls, volume, parts not overlapping, ground). */
#include "geometry/geometry.h"
#include "model.h"

#include <math.h>

static us_Status check_globals(const us_Structure *s, us_Error *err) {
  if (s->dim != 2 && s->dim != 3)
    return us_error_set(err, US_ERR_INPUT, "dimension %d is not supported (2 or 3)", s->dim);
  for (int k = 0; k < 3; k++)
    if (!isfinite(s->gravity[k])) return us_error_set(err, US_ERR_INPUT, "gravity is not finite");
  if (s->gravity[0] == 0.0 && s->gravity[1] == 0.0 && s->gravity[2] == 0.0)
    return us_error_set(err, US_ERR_INPUT, "gravity is zero: every part would stand, touching "
                        "anything or not (give its direction and size, e.g. %s)",
                        s->dim == 3 ? "[0, 0, -9.81]" : "[0, -9.81]");
  if (isnan(s->friction) || s->friction < 0) /* INFINITY: no sliding */
    return us_error_set(err, US_ERR_INPUT, "default friction %g must be >= 0 or infinite",
                        s->friction);
  if (isnan(s->contact_tol) || isinf(s->contact_tol))
    return us_error_set(err, US_ERR_INPUT, "contact tolerance is not finite");
  for (int k = 0; k < s->ncontact; k++)
    if (!isfinite(s->contacts[k].p[0]) || !isfinite(s->contacts[k].p[1]) ||
        !isfinite(s->contacts[k].p[2]) || isnan(s->contacts[k].mu) || s->contacts[k].mu < 0)
      return us_error_set(err, US_ERR_INPUT, "contact %d: non-finite point or bad friction", k);
  return US_OK;
}

/* Mass, density and friction of one body (either kind). */
static us_Status check_material(const us_Body *b, us_Error *err) {
  if (b->mass_given && !b->fixed && !(isfinite(b->mass) && b->mass > 0))
    return us_error_set(err, US_ERR_INPUT, "body '%s': mass %g must be finite and > 0",
                        us_id_text(b->id).s, b->mass);
  if (us_body_has_shape(b) && !b->mass_given && !(isfinite(b->density) && b->density > 0))
    return us_error_set(err, US_ERR_INPUT, "body '%s': density %g must be finite and > 0",
                        us_id_text(b->id).s, b->density);
  if (isnan(b->friction))
    return us_error_set(err, US_ERR_INPUT, "body '%s': friction %g must be >= 0 or infinite",
                        us_id_text(b->id).s, b->friction);
  if (!isfinite(b->inertia) || b->inertia < 0)
    return us_error_set(err, US_ERR_INPUT, "body '%s': inertia %g must be finite and >= 0",
                        us_id_text(b->id).s, b->inertia);
  return US_OK;
}

static us_Status check_values(const us_Structure *s, const us_Body *b, us_Error *err) {
  int explicit_ok = s->explicit_contacts || s->ncontact > 0;
  if (!us_body_has_shape(b)) {
    if (!explicit_ok)
      return us_error_set(err, US_ERR_INPUT,
                          "body '%s' has no %s (only allowed with explicit contacts)",
                          us_id_text(b->id).s, s->dim == 3 ? "geometry" : "polygon");
    if (!isfinite(b->com[0]) || !isfinite(b->com[1]) || !isfinite(b->com[2]))
      return us_error_set(err, US_ERR_INPUT, "body '%s': centre is not finite",
                          us_id_text(b->id).s);
    if (!b->fixed && !(isfinite(b->mass) && b->mass > 0))
      return us_error_set(err, US_ERR_INPUT, "body '%s': mass %g must be finite and > 0",
                          us_id_text(b->id).s, b->mass);
    return check_material(b, err);
  }
  if (b->npart > 0) {
    us_Status st = us_solid_check_values(b, err);
    return st ? st : check_material(b, err);
  }
  if (b->nvert < 3 || !b->verts)
    return us_error_set(err, US_ERR_INPUT, "body '%s': polygon has %d vertices (needs >= 3)",
                        us_id_text(b->id).s, b->nvert);
  for (int k = 0; k < 2 * b->nvert; k++)
    if (!isfinite(b->verts[k]))
      return us_error_set(err, US_ERR_INPUT, "body '%s': vertex %d has a non-finite coordinate",
                          us_id_text(b->id).s, k / 2);
  return check_material(b, err);
}

static us_Status defect_error(const us_Body *b, us_PolyDefect d, int i, int j, us_Error *err) {
  switch (d) {
    case US_POLY_NOMEM:
      return us_error_set(err, US_ERR_NOMEM, "out of memory checking body '%s'",
                          us_id_text(b->id).s);
    case US_POLY_REPEATED_VERTEX:
      return us_error_set(err, US_ERR_INPUT,
                          "body '%s': repeated vertex (vertices %d and %d coincide)",
                          us_id_text(b->id).s, i, j);
    case US_POLY_EDGES_FOLD:
      return us_error_set(err, US_ERR_INPUT,
                          "body '%s': polygon folds back on itself (edges %d and %d overlap)",
                          us_id_text(b->id).s, i, j);
    default:
      return us_error_set(err, US_ERR_INPUT,
                          "body '%s': polygon is self-intersecting (edges %d and %d cross)",
                          us_id_text(b->id).s, i, j);
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
static us_Status check_shape(const us_Structure *s, us_Body *b, us_Error *err) {
  double bb[4];
  us_poly_bbox(b->verts, b->nvert, bb);
  double diam = hypot(bb[2] - bb[0], bb[3] - bb[1]);
  if (!isfinite(diam) || !isfinite(us_poly_signed_area(b->verts, b->nvert)))
    return us_error_set(err, US_ERR_INPUT, "body '%s': coordinates too large, the area overflows",
                        us_id_text(b->id).s);
  double tol = s->contact_tol > 0 ? s->contact_tol : us_geom_tol(diam);
  int i = -1, j = -1;
  us_PolyDefect d = us_poly_check_simple(b->verts, b->nvert, tol, &i, &j);
  if (d == US_POLY_NOMEM || (d == US_POLY_EDGES_CROSS && crosses_properly(b, i, j)))
    return defect_error(b, d, i, j, err);
  double area = us_poly_signed_area(b->verts, b->nvert);
  if (area == 0 && diam > 0 && diam * diam < 0x1p-1000) /* not a sliver: too small */
    return us_error_set(err, US_ERR_INPUT, "body '%s': coordinates too small, the area "
                        "underflows (size %g)", us_id_text(b->id).s, diam);
  if (!(fabs(area) > tol * diam))
    return us_error_set(err, US_ERR_INPUT, "body '%s': polygon has (almost) zero area (%g)",
                        us_id_text(b->id).s, area);
  if (d != US_POLY_SIMPLE) return defect_error(b, d, i, j, err);
  us_poly_make_ccw(b->verts, b->nvert);
  if (s->ground && bb[1] < -tol)
    return us_error_set(err, US_ERR_INPUT, "body '%s' is below the ground (y = %g)",
                        us_id_text(b->id).s, bb[1]);
  return US_OK;
}

us_Status us_model_validate(us_Structure *s, double deadline, us_Error *err) {
  us_Status st = check_globals(s, err);
  for (int i = 0; !st && i < s->nbody; i++) st = check_values(s, &s->bodies[i], err);
  for (int i = 0; !st && i < s->nbody; i++)
    if (s->bodies[i].npart > 0) st = us_solid_check_shape(s, &s->bodies[i], deadline, err);
    else if (s->bodies[i].nvert > 0) st = check_shape(s, &s->bodies[i], err);
  return st;
}
