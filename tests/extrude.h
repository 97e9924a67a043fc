/* Shared by the 3D differential tests (stability_cone3, stability_local3d):
 * a 2D structure extruded into prisms, and finalizing a built structure.
 * Header-only (static inline) like walks.h. */
#ifndef US_TEST_EXTRUDE_H
#define US_TEST_EXTRUDE_H

#include "test.h"

/* Finalize s; on failure say why (naming `what`), free it and return NULL. */
static inline us_Structure *test_finalized(us_Structure *s, const char *what) {
  us_Error err;
  if (us_structure_finalize(s, &err) == US_OK) return s;
  fprintf(stderr, "%s: %s\n", what, err.msg);
  us_structure_free(s);
  return NULL;
}

/* The 2D structure s extruded along y into prisms `depth` deep (2D y is 3D
 * z), turned by `turn` about the vertical and shifted by (sx, sy): the
 * same bodies in the same order (friction, density, mass, fixed kept),
 * contacts found by the 3D detector. NULL if a body is refused. */
static inline us_Structure *test_extrude(const us_Structure *s, double depth, double turn,
                                         double sx, double sy) {
  us_Structure *e = us_structure_new(3);
  us_Error err;
  e->friction = s->friction;
  double c = cos(turn), sn = sin(turn);
  int ok = e != NULL;
  for (int i = 0; i < s->nbody && ok; i++) {
    const us_Body *b = &s->bodies[i];
    double *xyz = malloc(6 * (size_t)b->nvert * sizeof(double));
    if (!xyz) {
      ok = 0;
      break;
    }
    for (int k = 0; k < 2 * b->nvert; k++) {
      double x = b->verts[2 * (k % b->nvert)], y = k < b->nvert ? 0.0 : depth;
      xyz[3 * k] = c * x - sn * y + sx;
      xyz[3 * k + 1] = sn * x + c * y + sy;
      xyz[3 * k + 2] = b->verts[2 * (k % b->nvert) + 1];
    }
    us_BodyDef d = us_default_body_def();
    d.id = b->id, d.nvert = 2 * b->nvert, d.xyz = xyz, d.fixed = b->fixed;
    d.friction = b->friction, d.density = b->density;
    if (b->mass_given) d.mass = b->mass;
    ok = us_structure_add_body(e, &d, &err) >= 0;
    free(xyz);
  }
  if (!ok) {
    fprintf(stderr, "extrude: a body was refused\n");
    us_structure_free(e);
    return NULL;
  }
  return test_finalized(e, "extrude");
}

#endif
