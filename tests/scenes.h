/* Small scenes shared by the test programs: an axis-aligned box and
 * sealing a structure. Header-only (static inline) because each test
 * program links only its own concept library. */
#ifndef US_TEST_SCENES_H
#define US_TEST_SCENES_H

#include <stdio.h>
#include <string.h>

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

/* Finalize must fail with US_ERR_INPUT and a message containing both
 * fragments (the second may be NULL). */
static inline int scene_fails_with(us_Structure *s, const char *frag1, const char *frag2) {
  us_Error err;
  us_error_clear(&err);
  us_Status st = us_structure_finalize(s, &err);
  int ok = st == US_ERR_INPUT && strstr(err.msg, frag1) && (!frag2 || strstr(err.msg, frag2));
  if (!ok) fprintf(stderr, "  status %s, message: %s\n", us_status_name(st), err.msg);
  return ok;
}

#endif
