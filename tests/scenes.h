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

/* A column of n boxes 1 x 0.5, ids c0 (bottom) .. c<n-1>. */
static inline us_Structure *scene_column(int n) {
  us_Structure *s = us_structure_new(2);
  char id[16];
  for (int i = 0; i < n; i++) {
    snprintf(id, sizeof id, "c%d", i);
    scene_box(s, id, 0, 0.5 * i, 1, 0.5, 1);
  }
  return scene_seal(s);
}

/* Pier P, spacer S and plank L on it, heavy counterweight C on S and the
 * plank's inner end. C is highest, but removing it first tips the plank:
 * the plank must go first. */
static inline us_Structure *scene_cantilever(void) {
  us_Structure *s = us_structure_new(2);
  scene_box(s, "P", 0, 0, 1, 1, 1);
  scene_box(s, "S", 0, 1, 0.6, 0.2, 1);
  scene_box(s, "L", 0.6, 1, 3, 0.2, 1);
  scene_box(s, "C", 0, 1.2, 1, 0.5, 10);
  return scene_seal(s);
}

/* Two slabs leaning on each other (an inverted V), touching along x = 1,
 * y 1.5..2: each needs the other; they stand only with friction (hand
 * statics, docs/classify.md: mu* = 13/165). */
static inline us_Structure *scene_leaning(double mu) {
  us_Structure *s = us_structure_new(2);
  s->friction = mu;
  double l[8] = {0, 0, 0.4, 0, 1.0, 1.5, 1.0, 2.0};
  double r[8] = {1.6, 0, 2.0, 0, 1.0, 2.0, 1.0, 1.5};
  us_structure_add_polygon(s, "left", 4, l, 1, 0, 0, -1, NULL);
  us_structure_add_polygon(s, "right", 4, r, 1, 0, 0, -1, NULL);
  return scene_seal(s);
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
