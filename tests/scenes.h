/* Small scenes and helpers shared by the test programs, written once:
 * axis-aligned boxes (by size, by corners, auto-named), random rows of
 * boxes, sealing a structure, a verdict with its certificate checked, and
 * a few named structures. Header-only (static inline) because each test
 * program links only its own concept library. */
#ifndef US_TEST_SCENES_H
#define US_TEST_SCENES_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "unstack/unstack.h"

/* Box [x0, x0 + w] x [y0, y0 + h]; returns the body index or -1. */
static inline int scene_box(us_Structure *s, const char *id, double x0, double y0, double w,
                            double h, double density) {
  double xy[8] = {x0, y0, x0 + w, y0, x0 + w, y0 + h, x0, y0 + h};
  us_Error err;
  return us_structure_add_body(
      s,
      &(us_BodyDef){
          .id = id, .nvert = 4, .xy = xy, .density = density, .friction = -1.0},
      &err);
}

/* Polygon of density 1 with the structure's friction; returns the body
 * index or -1. */
static inline int scene_polygon(us_Structure *s, const char *id, int nvert, const double *xy,
                                int fixed) {
  us_BodyDef d = us_default_body_def();
  d.id = id;
  d.nvert = nvert;
  d.xy = xy;
  d.fixed = fixed;
  return us_structure_add_body(s, &d, NULL);
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

/* Box [x0, x1] x [y0, y1] by its corners, density 1; the body index, or
 * -1 with err set. */
static inline int scene_box_corners(us_Structure *s, const char *id, double x0, double y0,
                                    double x1, double y1, us_Error *err) {
  double xy[8] = {x0, y0, x1, y0, x1, y1, x0, y1};
  us_BodyDef d = us_default_body_def();
  d.id = id;
  d.nvert = 4;
  d.xy = xy;
  return us_structure_add_body(s, &d, err);
}

/* Box w x h at (x0, y0), density 1, named b<its index>; the body index or -1. */
static inline int scene_box_auto(us_Structure *s, double x0, double y0, double w, double h) {
  char id[24];
  snprintf(id, sizeof id, "b%d", s->nbody);
  return scene_box(s, id, x0, y0, w, h, 1.0);
}

/* 1-4 rows of 1-3 boxes (scene_box_auto), each row on the previous one's
 * height, with random widths, heights, gaps (some zero: touching
 * neighbours) and a row start in [-spread, spread]: stacks, overhangs,
 * floating pieces. rnd: the caller's uniform numbers in [0, 1). */
static inline double scene_uniform(double (*rnd)(void), double a, double b) {
  return a + (b - a) * rnd();
}

static inline void scene_random_rows(us_Structure *s, double (*rnd)(void), double spread) {
  int rows = 1 + (int)(rnd() * 4);
  double y = 0;
  for (int r = 0; r < rows; r++) {
    int nb = 1 + (int)(rnd() * 3);
    double h = scene_uniform(rnd, 0.3, 1.0), x = scene_uniform(rnd, -spread, spread);
    for (int k = 0; k < nb; k++) {
      double w = scene_uniform(rnd, 0.4, 1.5);
      scene_box_auto(s, x, y, w, h);
      x += w + (rnd() < 0.4 ? 0.0 : scene_uniform(rnd, 0.05, 0.6));
    }
    y += h;
  }
}

/* Verdict of `present` (NULL: the full structure) with method m; -1 on
 * error, -2 for a STABLE verdict without a passing certificate. */
static inline int scene_verdict(const us_Structure *s, us_Method m, const us_Bitset *present) {
  us_StabilitySettings set = us_stability_default_settings();
  set.method = m;
  us_Error err;
  us_Stability *w = us_stability_new(s, &set, &err);
  if (!w) {
    fprintf(stderr, "new: %s\n", err.msg);
    return -1;
  }
  us_StabilityResult res;
  us_stability_result_init(&res);
  us_Status st = present ? us_stability_test(w, present, &res, &err)
                         : us_stability_test_full(w, &res, &err);
  int v = st == US_OK ? (int)res.verdict : -1;
  if (st) fprintf(stderr, "test: %s\n", err.msg);
  if (v == US_STABLE && !res.check.ok) v = -2;
  if (v == US_UNDECIDED) fprintf(stderr, "  %s: undecided: %s\n", us_method_name(m), res.note);
  us_stability_result_free(&res);
  us_stability_free(w);
  return v;
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
  us_structure_add_body(
      s,
      &(us_BodyDef){
          .id = "left", .nvert = 4, .xy = l, .density = 1, .friction = -1},
      NULL);
  us_structure_add_body(
      s,
      &(us_BodyDef){
          .id = "right", .nvert = 4, .xy = r, .density = 1, .friction = -1},
      NULL);
  return scene_seal(s);
}

/* Random piles drop boxes onto the exact skyline of the boxes below: a box
 * [x0, x0 + w] lands on the highest top it overlaps, or on the ground. */
typedef struct SceneSkyline {
  int n;
  double x0[64], x1[64], top[64];
} SceneSkyline;

static inline double scene_landing(const SceneSkyline *k, double x0, double w) {
  double y = 0;
  for (int j = 0; j < k->n; j++)
    if (k->x0[j] < x0 + w && k->x1[j] > x0 && k->top[j] > y) y = k->top[j];
  return y;
}

/* Record a dropped box [x0, x0 + w] whose top is `top` (at most 64). */
static inline void scene_skyline_add(SceneSkyline *k, double x0, double w, double top) {
  k->x0[k->n] = x0;
  k->x1[k->n] = x0 + w;
  k->top[k->n++] = top;
}

/* Bounding box of body i: xmin, ymin, xmax, ymax. */
static inline void scene_body_box(const us_Structure *s, int i, double bb[4]) {
  const us_Body *b = &s->bodies[i];
  bb[0] = bb[1] = INFINITY;
  bb[2] = bb[3] = -INFINITY;
  for (int k = 0; k < b->nvert; k++) {
    bb[0] = fmin(bb[0], b->verts[2 * k]);
    bb[1] = fmin(bb[1], b->verts[2 * k + 1]);
    bb[2] = fmax(bb[2], b->verts[2 * k]);
    bb[3] = fmax(bb[3], b->verts[2 * k + 1]);
  }
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
