/* Small scenes shared by the test programs: an axis-aligned box and
 * sealing a structure. Header-only (static inline) because each test
 * program links only its own concept library. */
#ifndef US_TEST_SCENES_H
#define US_TEST_SCENES_H

#include <stdio.h>

#include "unstack/unstack.h"

/* Box [x0, x0 + w] x [y0, y0 + h]; returns the body index or -1. */
static inline int scene_box(us_Structure *s, const char *id, double x0, double y0, double w,
                            double h, double density) {
  double xy[8] = {x0, y0, x0 + w, y0, x0 + w, y0 + h, x0, y0 + h};
  us_Error err;
  return us_structure_add_polygon(s, id, 4, xy, density, 0.0, 0, -1.0, &err);
}

/* Finalize; NULL (and the structure freed) on error. */
static inline us_Structure *scene_seal(us_Structure *s) {
  us_Error err;
  if (us_structure_finalize(s, &err) != US_OK) {
    fprintf(stderr, "finalize: %s\n", err.msg);
    us_structure_free(s);
    return NULL;
  }
  return s;
}

#endif
