/* Tests of structure validation and mass properties (src/model/validate.c,
 * src/model/massprops.c) through us_structure_finalize: every bad input is
 * rejected with US_ERR_INPUT and a message naming the body. */
#include "model/model.h"
#include "scenes.h"
#include "test.h"

static void self_intersecting(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double bow[8] = {0, 0, 1, 1, 1, 0, 0, 1};
  CHECK(scene_box_corners(s, "ok", 2, 0, 3, 1, &err) >= 0);
  CHECK(
      us_structure_add_body(
          s,
          &(us_BodyDef){
              .id = "b3", .nvert = 4, .xy = bow, .density = 1, .friction = -1},
          &err) >= 0);
  CHECK(scene_fails_with(s, "'b3'", "self-intersecting (edges 0 and 2 cross)"));
  us_structure_free(s);
}

static void zero_area(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double flat[8] = {0, 0, 1, 0, 2, 0, 3, 1e-12};
  CHECK(scene_box_corners(s, "ok", 4, 0, 5, 1, &err) >= 0);
  CHECK(us_structure_add_body(s,
                              &(us_BodyDef){.id = "flat",
                                            .nvert = 4,
                                            .xy = flat,
                                            .density = 1,
                                            .friction = -1},
                              &err) >= 0);
  CHECK(scene_fails_with(s, "'flat'", "zero area"));
  us_structure_free(s);
}

static void too_few_vertices(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double seg[4] = {0, 0, 1, 0};
  CHECK(
      us_structure_add_body(
          s,
          &(us_BodyDef){
              .id = "seg", .nvert = 2, .xy = seg, .density = 1, .friction = -1},
          &err) >= 0);
  CHECK(scene_fails_with(s, "'seg'", "2 vertices"));
  us_structure_free(s);
}

static void non_finite(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double xy[8] = {0, 0, 1, 0, 1, NAN, 0, 1};
  CHECK(
      us_structure_add_body(
          s,
          &(us_BodyDef){
              .id = "nan", .nvert = 4, .xy = xy, .density = 1, .friction = -1},
          &err) >= 0);
  CHECK(scene_fails_with(s, "'nan'", "vertex 2 has a non-finite"));
  us_structure_free(s);
  s = us_structure_new(2);
  xy[5] = INFINITY;
  CHECK(
      us_structure_add_body(
          s,
          &(us_BodyDef){
              .id = "inf", .nvert = 4, .xy = xy, .density = 1, .friction = -1},
          &err) >= 0);
  CHECK(scene_fails_with(s, "'inf'", "non-finite"));
  us_structure_free(s);
}

/* Coordinates whose area overflows: said so, naming the body (was
 * "polygon has (almost) zero area (inf)"). */
static void huge_coordinates(void) {
  const double big[2][8] = {{0, 0, 1e308, 0, 1e308, 1e308, 0, 1e308},
                            {-1e308, 0, 1e308, 0, 1e308, 1, -1e308, 1}};
  for (int k = 0; k < 2; k++) {
    us_Error err;
    us_Structure *s = us_structure_new(2);
    us_BodyDef d = us_default_body_def();
    d.id = "x";
    d.nvert = 4;
    d.xy = big[k];
    CHECK(us_structure_add_body(s, &d, &err) == 0);
    CHECK(scene_fails_with(s, "body 'x': coordinates too large", "overflows"));
    us_structure_free(s);
  }
}

static void below_ground(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  CHECK(scene_box_corners(s, "b0", 0, 0, 1, 1, &err) >= 0);
  CHECK(scene_box_corners(s, "b3", 2, -0.2, 3, 1, &err) >= 0);
  CHECK(scene_fails_with(s, "body 'b3' is below the ground", "y = -0.2"));
  us_structure_free(s);
  /* without a ground the same structure is fine */
  s = us_structure_new(2);
  s->ground = 0;
  CHECK(scene_box_corners(s, "b3", 2, -0.2, 3, 1, &err) >= 0);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(s->ncontact, ==, 0);
  us_structure_free(s);
}

static void duplicate_id(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  CHECK(scene_box_corners(s, "b", 0, 0, 1, 1, &err) == 0);
  CHECK(scene_box_corners(s, "b", 1, 0, 2, 1, &err) == -1);
  CHECK(strstr(err.msg, "'b'") != NULL);
  us_structure_free(s);
}

/* Values set directly (as a file reader may do) are checked too. */
static void bad_materials(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  CHECK(scene_box_corners(s, "d", 0, 0, 1, 1, &err) >= 0);
  s->bodies[0].density = -2.0;
  CHECK(scene_fails_with(s, "'d'", "density"));
  s->bodies[0].density = 1.0;
  s->bodies[0].friction = NAN;
  CHECK(scene_fails_with(s, "'d'", "friction"));
  /* INFINITY is allowed: no sliding (docs/format.md) */
  s->bodies[0].friction = 0.0; /* zero friction is allowed */
  s->bodies[0].mass_given = 1;
  s->bodies[0].mass = NAN;
  CHECK(scene_fails_with(s, "'d'", "mass"));
  s->bodies[0].mass = 2.0;
  s->friction = -1.0;
  CHECK(scene_fails_with(s, "default friction", NULL));
  s->friction = 0.5;
  s->gravity[1] = NAN;
  CHECK(scene_fails_with(s, "gravity", NULL));
  s->gravity[1] = 0.0; /* zero: the planner's "a part touching nothing falls" would not hold */
  CHECK(scene_fails_with(s, "gravity is zero", NULL));
  s->gravity[1] = -9.81;
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_NEAR(s->bodies[0].mass, 2.0, 0);
  us_structure_free(s);
}

static void repeated_vertex(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double xy[10] = {0, 0, 2, 0, 2, 2, 2, 2, 0, 2};
  CHECK(
      us_structure_add_body(
          s,
          &(us_BodyDef){
              .id = "rep", .nvert = 5, .xy = xy, .density = 1, .friction = -1},
          &err) >= 0);
  CHECK(scene_fails_with(s, "'rep'", "vertices 2 and 3 coincide"));
  us_structure_free(s);
}

/* A non-convex (L-shaped) body: centre of mass from the two rectangles. */
static void l_shape_body(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double L[12] = {0, 0, 3, 0, 3, 1, 1, 1, 1, 3, 0, 3};
  CHECK(us_structure_add_body(
            s,
            &(us_BodyDef){
                .id = "L", .nvert = 6, .xy = L, .density = 2.0, .friction = -1},
            &err) == 0);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  const us_Body *b = &s->bodies[0];
  CHECK_NEAR(b->mass, 2.0 * (3.0 + 2.0), 1e-12);
  CHECK_NEAR(b->com[0], (3.0 * 1.5 + 2.0 * 0.5) / 5.0, 1e-12);
  CHECK_NEAR(b->com[1], (3.0 * 0.5 + 2.0 * 2.0) / 5.0, 1e-12);
  CHECK(b->inertia > 0);
  CHECK_INT(s->ncontact, ==, 2); /* (0,0) and (3,0) on the ground */
  us_structure_free(s);
}

static void made_ccw(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double cw[8] = {0, 0, 0, 1, 2, 1, 2, 0};
  CHECK(us_structure_add_body(
            s,
            &(us_BodyDef){
                .id = "cw", .nvert = 4, .xy = cw, .density = 1, .friction = -1},
            &err) >= 0);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  const us_Body *b = &s->bodies[0];
  double a2 = 0;
  for (int k = 0; k < 4; k++) {
    int l = (k + 1) % 4;
    a2 += b->verts[2 * k] * b->verts[2 * l + 1] - b->verts[2 * l] * b->verts[2 * k + 1];
  }
  CHECK_NEAR(a2, 4.0, 1e-12); /* twice the area, positive */
  us_structure_free(s);
}

static void mass_properties(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double w = 2.0, h = 0.5;
  double xy[8] = {1, 0, 1 + w, 0, 1 + w, h, 1, h};
  CHECK(us_structure_add_body(s,
                              &(us_BodyDef){.id = "dens",
                                            .nvert = 4,
                                            .xy = xy,
                                            .density = 3.0,
                                            .friction = -1},
                              &err) == 0);
  double xy2[8] = {1, h, 1 + w, h, 1 + w, 2 * h, 1, 2 * h};
  CHECK(us_structure_add_body(s,
                              &(us_BodyDef){.id = "given",
                                            .nvert = 4,
                                            .xy = xy2,
                                            .density = 3.0,
                                            .mass = 7.0,
                                            .friction = -1},
                              &err) == 1);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  const us_Body *a = &s->bodies[0], *b = &s->bodies[1];
  CHECK_NEAR(a->mass, 3.0 * w * h, 1e-12);
  CHECK_NEAR(a->com[0], 1 + w / 2, 1e-12);
  CHECK_NEAR(a->com[1], h / 2, 1e-12);
  CHECK_NEAR(a->inertia, a->mass * (w * w + h * h) / 12.0, 1e-12);
  CHECK_NEAR(b->mass, 7.0, 0);
  CHECK_NEAR(b->com[1], 1.5 * h, 1e-12);
  CHECK_NEAR(b->inertia, 7.0 * (w * w + h * h) / 12.0, 1e-12);
  CHECK_NEAR(s->weight, 9.81 * (3.0 * w * h + 7.0), 1e-9);
  us_structure_free(s);
}

/* Point bodies need explicit contacts; their inertia is derived from the
 * distance to their contacts when not given. */
static void point_bodies(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double c[2] = {0, 1};
  CHECK(us_structure_add_point_body(s, "p", 2.0, c, 0, &err) == 0);
  CHECK(scene_fails_with(s, "'p'", "explicit contacts"));
  double p[3] = {0.5, 0, 0}, n[3] = {0, 1, 0};
  CHECK(us_structure_add_contact(s, US_GROUND, 0, p, n, -1, &err) == 0);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  double r2 = 0.5 * 0.5 + 1.0;
  CHECK_NEAR(s->bodies[0].inertia, 2.0 * r2 / 3.0, 1e-12);
  CHECK_INT(s->ncontact, ==, 1);
  CHECK(s->explicit_contacts);
  us_structure_free(s);

  /* no contacts at all: the inertia comes from the structure's scale */
  s = us_structure_new(2);
  s->explicit_contacts = 1;
  double c2[2] = {3, 5};
  CHECK(us_structure_add_point_body(s, "lone", 2.0, c, 0, &err) == 0);
  CHECK(us_structure_add_point_body(s, "far", 1.0, c2, 0, &err) == 1);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  double d = hypot(3.0, 4.0); /* bbox diagonal of the two centres */
  CHECK_NEAR(s->scale, d, 1e-12);
  CHECK_NEAR(s->bodies[0].inertia, 2.0 * d * d / 3.0, 1e-12);
  CHECK_INT(s->ncontact, ==, 0);
  us_structure_free(s);

  s = us_structure_new(2);
  CHECK(us_structure_add_point_body(s, "q", 0.0, c, 0, &err) == 0);
  CHECK(us_structure_add_contact(s, US_GROUND, 0, p, n, -1, &err) == 0);
  CHECK(scene_fails_with(s, "'q'", "mass"));
  s->bodies[0].mass = 1.0;
  s->bodies[0].com[0] = NAN;
  CHECK(scene_fails_with(s, "'q'", "centre"));
  us_structure_free(s);
}

static void empty_and_all_fixed(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(s->ncontact, ==, 0);
  CHECK(s->contact_tol == 0 && s->scale > 0); /* tolerances stay per pair */
  us_structure_free(s);
  s = us_structure_new(2);
  double xy[8] = {0, 0, 1, 0, 1, 1, 0, 1};
  CHECK(us_structure_add_body(s,
                              &(us_BodyDef){.id = "pier",
                                            .nvert = 4,
                                            .xy = xy,
                                            .density = 1,
                                            .fixed = 1,
                                            .friction = -1},
                              &err) == 0);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(s->ncontact, ==, 0); /* fixed bodies take no ground contacts */
  us_structure_free(s);
}

/* Every allocation failure is reported as US_ERR_NOMEM, never a crash or
 * a leak (the harness checks leaks after the case). */
static int three_boxes(us_Structure *s, us_Error *err) {
  return scene_box_corners(s, "a", 0, 0, 2, 1, err) >= 0 && scene_box_corners(s, "b", 0, 1, 2, 2, err) >= 0 &&
         scene_box_corners(s, "c", 2, 0, 3, 1, err) >= 0;
}

static void out_of_memory(void) {
  us_Error err;
  us_Structure *ref = us_structure_new(2);
  CHECK(ref && three_boxes(ref, &err));
  CHECK_OK(us_structure_finalize(ref, &err), &err);
  int nref = ref->ncontact;
  us_structure_free(ref);
  int failures = 0;
  for (long n = 0; n < 200; n++) {
    us_Structure *s = us_structure_new(2);
    if (!s) continue;
    if (three_boxes(s, &err)) {
      us_alloc_fail_after(n);
      us_Status st = us_structure_finalize(s, &err);
      us_alloc_fail_after(-1);
      if (st != US_OK) {
        CHECK_INT(st, ==, US_ERR_NOMEM);
        failures++;
      } else {
        CHECK_INT(s->ncontact, ==, nref);
      }
    }
    us_structure_free(s);
  }
  CHECK(failures > 0);
}

/* Finalizing again after adding a body re-detects the contacts (they were
 * detection's own, not the caller's), and ids stay unique. */
static void finalize_again(void) {
  us_Structure *s = us_structure_new(2);
  scene_box(s, "a", 0, 0, 1, 1, 1);
  scene_box(s, "b", 0, 1, 1, 1, 1);
  us_Error err;
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(s->ncontact, ==, 4);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(s->ncontact, ==, 4);
  scene_box(s, "c", 0, 2, 1, 1, 1);
  CHECK_INT(scene_box(s, "c", 5, 0, 1, 1, 1), ==, -1);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(s->ncontact, ==, 6);
  CHECK(!s->explicit_contacts);
  CHECK_INT(us_structure_find_body(s, "c"), ==, 2);
  CHECK_INT(us_structure_find_body(s, "zz"), ==, -1);
  us_structure_free(s);
}

US_TEST_MAIN(T(finalize_again), T(self_intersecting), T(zero_area), T(too_few_vertices), T(non_finite),
             T(huge_coordinates), T(below_ground), T(duplicate_id), T(bad_materials), T(repeated_vertex),
             T(l_shape_body), T(made_ccw), T(mass_properties), T(point_bodies),
             T(empty_and_all_fixed), T(out_of_memory))
