/* Private interface of the structure model: the steps of finalize, each in
 * its own file, so that validation, mass properties and contact detection
 * can be tested separately. */
#ifndef US_MODEL_H
#define US_MODEL_H

#include "core/core.h"

/* validate.c: geometry checks of every body (>= 3 vertices, finite, non-zero
 * area, simple, not below the ground when there is one), orienting each
 * polygon counter-clockwise. Explicit-contact structures: point bodies need
 * a finite centre and positive mass. Messages name the body. */
us_Status us_model_validate(us_Structure *s, double deadline, us_Error *err);

/* massprops.c: mass (from density unless given), centre of mass and polar
 * inertia about it, for every polygon body. */
us_Status us_model_mass_properties(us_Structure *s, us_Error *err);

/* structure.c: bounding box, scale and total weight (contact_tol is left
 * as the caller set it). */
void us_model_measure(us_Structure *s);

/* Does the body have geometry (a polygon, or 3D parts)? Bodies without
 * are point bodies (explicit contacts only). */
static inline int us_body_has_shape(const us_Body *b) { return b->nvert > 0 || b->npart > 0; }

/* The lowest and highest points of body b along "up" (y in 2D, z in 3D:
 * the vertical axis of the generators and of the ground); a point body
 * has its centre for both. */
static inline void us_body_vertical_range(const us_Structure *s, const us_Body *b, double *lo,
                                          double *hi) {
  int up = s->dim == 3 ? 2 : 1;
  *lo = *hi = b->com[up];
  int first = 1;
  for (int k = 0; k < b->nvert && s->dim == 2; k++, first = 0) {
    double y = b->verts[2 * k + 1];
    *lo = first || y < *lo ? y : *lo;
    *hi = first || y > *hi ? y : *hi;
  }
  for (int p = 0; p < b->npart && s->dim == 3; p++)
    for (int k = 0; k < b->parts[p].nvert; k++, first = 0) {
      double z = b->parts[p].verts[3 * k + 2];
      *lo = first || z < *lo ? z : *lo;
      *hi = first || z > *hi ? z : *hi;
    }
}

/* solid.c: 3D bodies. Copy a definition's point sets into parts (the
 * points given; the hulls come in finalize): 0, or -1 with err set (bad
 * arrays, out of memory). */
int us_solid_parts_from_def(const us_BodyDef *def, us_Polyhedron **parts, int *npart,
                            us_Error *err);
void us_body_free_parts(us_Body *b);
/* Values that need no tolerance: >= 4 points per part, all finite. */
us_Status us_solid_check_values(const us_Body *b, us_Error *err);
/* Shape with the body's own tolerance: each part's convex hull (points not
 * all near one plane, volume above tol * size^2), parts of one body not
 * overlapping beyond tol, not below the ground. Builds the hulls in place. */
us_Status us_solid_check_shape(const us_Structure *s, us_Body *b, double deadline, us_Error *err);
/* Mass (from density unless given), centre of mass and inertia tensor of a
 * 3D body from its parts' hulls. */
void us_solid_mass_props(us_Body *b);

/* structure.c: room for n bodies in the body array and the id index, so
 * a reader that knows the count neither copies nor rehashes them; 0 or -1
 * out of memory. */
int us_structure_reserve(us_Structure *s, int n);

/* Fill the tangent basis of a contact from its normal. */
void us_contact_frame(int dim, us_Contact *c);

#endif
