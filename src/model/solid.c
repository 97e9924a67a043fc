/* 3D bodies: building them from point sets, checking their shape, and
 * their mass properties.
 *
 * A 3D body is the union of one or more convex parts (a polyhedron or a
 * box is one part; an L-shaped or interlocking piece several). Until
 * finalize a part holds the points the user gave; the shape check replaces
 * them by their convex hull (geometry/hull3.c) built with the body's own
 * tolerance, tol = contact_tol when the caller set one, else
 * US_GEOM_TOL_REL times the diagonal of the body's bounding box (the
 * tolerance of the body against the ground, and at least that of any pair
 * it belongs to, as in 2D). A hull already built is kept, so finalizing
 * again is idempotent. Checks, in order: the size is finite; each part has
 * 4 points off one plane (else it is flat) and a volume above
 * tol * size^2 (on average thicker than tol); two parts of one body do not
 * overlap by more than tol (the separating-axis depth), since the volume
 * of a compound is the sum of its parts'; with a ground, no vertex below
 * z = -tol.
 *
 * Mass properties: the parts' volume integrals (us_polyhedron_moments,
 * exact by the divergence theorem) about one reference point near the body
 * are summed; com = ref + m1 / V; the second moment about the com is
 * C = m2 - V d d^T with d = com - ref (parallel axes); for a uniform body
 * of mass m = density V (or the mass given) the inertia tensor about the
 * com is (m / V) (trace(C) I - C). The scalar `inertia` of a 3D body is
 * the mean principal moment, trace / 3. */
#include "model.h"

#include "geometry/geometry3.h"

#include <math.h>
#include <string.h>

#define MAX_POINTS 10000000 /* per part: keeps int sizes safe */

static int copy_part(us_Polyhedron *p, int n, const double *xyz) {
  memset(p, 0, sizeof *p);
  p->verts = us_malloc((size_t)(n > 0 ? n : 1) * 3 * sizeof(double));
  if (!p->verts) return -1;
  if (n > 0) memcpy(p->verts, xyz, (size_t)n * 3 * sizeof(double));
  p->nvert = n;
  return 0;
}

int us_solid_parts_from_def(const us_BodyDef *def, us_Polyhedron **parts, int *npart,
                            us_Error *err) {
  us_IdText idt = us_id_text(def->id ? def->id : "?");
  const char *id = idt.s;
  int single = def->npart == 0;
  int np = single ? 1 : def->npart;
  if (def->npart < 0 || (!single && (!def->parts || def->nvert != 0 || def->xyz)) ||
      (single && (def->nvert < 0 || (def->nvert > 0 && !def->xyz)))) {
    us_error_set(err, US_ERR_INPUT, "body '%s': bad point arrays (give xyz or parts, not both)", id);
    return -1;
  }
  for (int k = 0; k < np; k++) {
    int n = single ? def->nvert : def->parts[k].nvert;
    if (n < 0 || n > MAX_POINTS || (n > 0 && !(single ? def->xyz : def->parts[k].xyz))) {
      us_error_set(err, US_ERR_INPUT, "body '%s': part %d: bad point array", id, k);
      return -1;
    }
  }
  *parts = us_calloc((size_t)np, sizeof **parts);
  int k = 0;
  for (; *parts && k < np; k++)
    if (copy_part(&(*parts)[k], single ? def->nvert : def->parts[k].nvert,
                  single ? def->xyz : def->parts[k].xyz))
      break;
  if (!*parts || k < np) {
    for (int j = 0; *parts && j < k; j++) us_polyhedron_free(&(*parts)[j]);
    us_free(*parts);
    *parts = NULL;
    us_error_set(err, US_ERR_NOMEM, "out of memory adding body '%s'", id);
    return -1;
  }
  *npart = np;
  return 0;
}

void us_body_free_parts(us_Body *b) {
  for (int k = 0; k < b->npart; k++) us_polyhedron_free(&b->parts[k]);
  us_free(b->parts);
  b->parts = NULL;
  b->npart = 0;
}

/* "part K: " for compounds, "" for a single part. */
static const char *part_label(const us_Body *b, int k, char *buf, size_t n) {
  if (b->npart > 1) snprintf(buf, n, "part %d: ", k);
  else buf[0] = 0;
  return buf;
}

us_Status us_solid_check_values(const us_Body *b, us_Error *err) {
  char lab[32];
  for (int k = 0; k < b->npart; k++) {
    const us_Polyhedron *p = &b->parts[k];
    if (p->nface > 0) continue; /* hull already built */
    if (p->nvert < 4)
      return us_error_set(err, US_ERR_INPUT, "body '%s': %shas %d points (a polyhedron needs >= 4)",
                          us_id_text(b->id).s, part_label(b, k, lab, sizeof lab), p->nvert);
    for (int j = 0; j < 3 * p->nvert; j++)
      if (!isfinite(p->verts[j]))
        return us_error_set(err, US_ERR_INPUT, "body '%s': %spoint %d has a non-finite coordinate",
                            us_id_text(b->id).s, part_label(b, k, lab, sizeof lab), j / 3);
  }
  return US_OK;
}

/* Replace part k's points by their hull. */
static us_Status build_hull(us_Body *b, int k, double tol, double size, double deadline,
                            us_Error *err) {
  us_Polyhedron *p = &b->parts[k], h;
  char lab[32];
  us_IdText idt = us_id_text(b->id);
  const char *id = idt.s, *pl = part_label(b, k, lab, sizeof lab);
  switch (p->nface > 0 ? US_HULL_OK : us_hull3_until(p->verts, p->nvert, tol, deadline, &h)) {
    case US_HULL_OK: break;
    case US_HULL_TIMEOUT:
      return us_error_set(err, US_ERR_TIME_LIMIT,
                          "time limit reached building the convex hull of body '%s' (%s%d points)",
                          id, pl, p->nvert);
    case US_HULL_NOMEM: return us_error_set(err, US_ERR_NOMEM, "out of memory checking body '%s'", id);
    case US_HULL_FLAT:
      return us_error_set(err, US_ERR_INPUT,
                          "body '%s': %sits points lie in one plane (a polyhedron needs 4 points "
                          "off one plane)", id, pl);
    default:
      return us_error_set(err, US_ERR_INPUT, "body '%s': %scould not build its convex hull", id, pl);
  }
  if (p->nface == 0) us_polyhedron_free(p), *p = h;
  if (p->volume == 0 && size * size * size < 0x1p-1000) /* built, so not flat: too small */
    return us_error_set(err, US_ERR_INPUT, "body '%s': %scoordinates too small, the volume "
                        "underflows (size %g)", id, pl, size);
  if (!(p->volume > tol * size * size)) /* h is kept: freed with the body */
    return us_error_set(err, US_ERR_INPUT, "body '%s': %spolyhedron has (almost) zero volume (%g)",
                        id, pl, p->volume);
  return US_OK;
}

static us_Status parts_overlap(const us_Body *b, double tol, us_Error *err) {
  for (int i = 0; i < b->npart; i++)
    for (int j = i + 1; j < b->npart; j++) {
      double sep = us_convex_separation(&b->parts[i], &b->parts[j], tol, NULL);
      if (sep < -tol)
        return us_error_set(err, US_ERR_INPUT, "body '%s': parts %d and %d overlap (depth %g)",
                            us_id_text(b->id).s, i, j, -sep);
    }
  return US_OK;
}

us_Status us_solid_check_shape(const us_Structure *s, us_Body *b, double deadline, us_Error *err) {
  double size = us_body_diameter(b);
  if (!isfinite(size))
    return us_error_set(err, US_ERR_INPUT, "body '%s': coordinates too large, the size overflows",
                        us_id_text(b->id).s);
  double tol = s->contact_tol > 0 ? s->contact_tol : us_geom_tol(size);
  us_Status st = US_OK;
  for (int k = 0; !st && k < b->npart; k++) st = build_hull(b, k, tol, size, deadline, err);
  if (!st) st = parts_overlap(b, tol, err);
  double bb[6];
  us_body_bbox3(b, bb);
  if (!st && s->ground && bb[2] < -tol)
    st = us_error_set(err, US_ERR_INPUT, "body '%s' is below the ground (z = %g)",
                      us_id_text(b->id).s, bb[2]);
  return st;
}

void us_solid_mass_props(us_Body *b) {
  us_Vec3 ref = us_v3_at(b->parts[0].verts, 0);
  double vol = 0.0, m1[3] = {0, 0, 0}, m2[9] = {0};
  for (int k = 0; k < b->npart; k++) {
    double v, a[3], c[9];
    us_polyhedron_moments(&b->parts[k], ref, &v, a, c);
    vol += v;
    for (int i = 0; i < 3; i++) m1[i] += a[i];
    for (int i = 0; i < 9; i++) m2[i] += c[i];
  }
  if (!b->mass_given) b->mass = b->density * vol;
  double d[3] = {m1[0] / vol, m1[1] / vol, m1[2] / vol}, k = b->mass / vol;
  double cov[9], tr = 0.0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) cov[3 * i + j] = m2[3 * i + j] - vol * d[i] * d[j];
  for (int i = 0; i < 3; i++) tr += cov[4 * i];
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) b->inertia3[i][j] = k * ((i == j ? tr : 0.0) - cov[3 * i + j]);
    b->com[i] = (i == 0 ? ref.x : i == 1 ? ref.y : ref.z) + d[i];
  }
  b->inertia = (b->inertia3[0][0] + b->inertia3[1][1] + b->inertia3[2][2]) / 3.0;
}
