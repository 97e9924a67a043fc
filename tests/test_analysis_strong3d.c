/* Tests of strong stability with friction in 3D (src/analysis/strong*.c,
 * the polygonal inner and outer cones): hand-derived boxes (pinched off the
 * ground, on the ground, on a slope below, at and above the friction
 * angle), the 2D cases extruded into prisms giving the 2D answers, random
 * extruded piles against the 2D decision, and tampered 3D witnesses
 * rejected by the independent check. No timing is asserted. */
#include "analysis/strong.h"
#include "extrude.h"
#include "piles.h"
#include "scenes.h"
#include "test.h"

#include "unstack/analysis.h"

/* ----------------------------------------------------------------- scenes */

/* The 2D unit box between two fixed walls, bottom at y0 (as in
 * test_analysis_strong.c). */
static us_Structure *pinched2(double y0, double mu) {
  us_Structure *s = us_structure_new(2);
  double wl[8] = {0, 0, 1, 0, 1, 3, 0, 3}, wr[8] = {2, 0, 3, 0, 3, 3, 2, 3};
  s->friction = mu;
  scene_polygon(s, "left", 4, wl, 1);
  scene_polygon(s, "right", 4, wr, 1);
  scene_box(s, "box", 1, y0, 1, 1, 1);
  return scene_seal(s);
}

/* s extruded 1 deep, turned by 0.3 rad so that no axis is special; s freed. */
static us_Structure *prism(us_Structure *s) {
  if (!s) return NULL;
  us_Structure *e = test_extrude(s, 1.0, 0.3, 0.5, -0.25);
  us_structure_free(s);
  return e;
}

/* A unit cube on the ground with gravity tilted to slope tan(theta) = t
 * along the horizontal direction (cos 0.7, sin 0.7): the ground plays the
 * inclined plane, the slope direction off every axis of the contact
 * frames. */
static us_Structure *slope3(double t, double mu) {
  us_Structure *s = us_structure_new(2);
  s->friction = mu;
  scene_box(s, "box", 0, 0, 1, 1, 1);
  us_Structure *e = prism(scene_seal(s));
  if (!e) return NULL;
  double n = hypot(t, 1.0);
  e->gravity[0] = 9.81 * t / n * cos(0.7);
  e->gravity[1] = 9.81 * t / n * sin(0.7);
  e->gravity[2] = -9.81 / n;
  return e;
}

/* The cube on a slope tan(theta) = t down along t[0] of its ground
 * contacts' frame (one of the cones' directions): the slide down-slope is
 * then a slide of the inner cones, found with its witness. */
static us_Structure *slope_along_frame(double t, double mu) {
  us_Structure *e = slope3(0.0, mu);
  if (!e || e->ncontact == 0) return e;
  const double *d = e->contacts[0].t[0];
  double n = hypot(t, 1.0), h = hypot(d[0], d[1]);
  e->gravity[0] = -9.81 * t / n * d[0] / h;
  e->gravity[1] = -9.81 * t / n * d[1] / h;
  e->gravity[2] = -9.81 / n;
  return e;
}

/* The verdict (-2 on error); a "no" of a standing structure must carry a
 * witness that passes the check. */
static int strong3_budget(const us_Structure *s, long max_nodes, us_StrongResult *r) {
  us_StrongSettings set = us_strong_default_settings();
  set.time_limit = 0; /* budgets only: LPs, not seconds */
  set.max_nodes = max_nodes;
  us_Error err;
  if (us_strong_stability(s, NULL, &set, r, &err) != US_OK) {
    fprintf(stderr, "strong: %s\n", err.msg);
    return -2;
  }
  char why[128] = "";
  if (r->strong == 0 && r->has_witness && !us_strong_check(s, NULL, r, 1e-5, why, sizeof why)) {
    fprintf(stderr, "witness rejected: %s\n", why);
    return -3;
  }
  return r->strong;
}

static int strong3(const us_Structure *s, us_StrongResult *r) { return strong3_budget(s, 3000, r); }

static int verdict3_budget(const us_Structure *s, long max_nodes) {
  us_StrongResult r;
  int v = strong3_budget(s, max_nodes, &r);
  if (v == -1) fprintf(stderr, "undecided: %s\n", r.note);
  us_strong_result_free(&r);
  return v;
}

static int verdict3(const us_Structure *s) { return verdict3_budget(s, 3000); }

/* ------------------------------------------------------- hand-derived cases */

/* Pinched off the ground between two fixed walls (mu 0.5): it stands (a
 * squeeze), but free fall with no force at either wall is a solution: no,
 * with a checked witness moving the box down. */
static void pinched_off_ground_no(void) {
  us_Structure *s = prism(pinched2(1, 0.5));
  CHECK(s);
  CHECK_INT(scene_verdict(s, US_METHOD_LP, NULL), ==, US_STABLE);
  us_StrongResult r;
  CHECK_INT(strong3(s, &r), ==, 0);
  CHECK(r.has_witness);
  CHECK_INT(r.dim, ==, 3);
  CHECK_INT(r.nbody, ==, 1);
  CHECK(r.accel[2] < 0);
  us_strong_result_free(&r);
  us_structure_free(s);
}

/* A box on the ground: every motion from rest either lifts it (a rotation
 * about an edge raises the centre) or slides it horizontally, where gravity
 * does no work and friction only takes energy: yes at mu 0.5 and 0. Also
 * resting between the walls: yes. */
static void box_on_ground_yes(void) {
  for (int k = 0; k < 2; k++) {
    us_Structure *s = us_structure_new(2);
    s->friction = k ? 0.0 : 0.5;
    scene_box(s, "box", 0, 0, 1, 1, 1);
    s = prism(scene_seal(s));
    CHECK(s);
    CHECK_INT(verdict3(s), ==, 1);
    us_structure_free(s);
  }
  us_Structure *s = prism(pinched2(0, 0.5));
  CHECK(s);
  CHECK_INT(verdict3(s), ==, 1);
  us_structure_free(s);
}

/* The cube on a slope, mu 0.5. Below the friction angle (t = 0.3): the
 * outer cones resist a slip with at least mu cos(2 pi / d) f_n = 0.35 f_n
 * > 0.3 f_n, so the outer model has no motion either: yes, proven for the
 * circular cone. Above (t = 0.7): it slides, weak no, strong no. At the
 * angle (t = 0.5) the circular cone has no motion (the sliding solution
 * has zero acceleration) but the outer cones, weaker against slips
 * between their directions, have one that the circular check rejects:
 * never "no"; the library reports undecided rather than claim more. */
static void slope_below_at_above(void) {
  us_Structure *s = slope3(0.3, 0.5);
  CHECK(s);
  CHECK_INT(scene_verdict(s, US_METHOD_LP, NULL), ==, US_STABLE);
  CHECK_INT(verdict3(s), ==, 1);
  us_structure_free(s);
  s = slope3(0.7, 0.5);
  CHECK(s);
  CHECK_INT(verdict3(s), ==, 0);
  us_structure_free(s);
  s = slope3(0.5, 0.5);
  CHECK(s);
  int v = verdict3(s);
  CHECK(v == 1 || v == -1);
  us_structure_free(s);
}

/* The 2D cases extruded: the box between movable piers off the ground (no:
 * free fall; 16 contacts of 10 modes: the search needs between 12,000 and
 * 20,000 LPs per model, so under AddressSanitizer only "never yes" is
 * asserted within 3000), a frictionless column (yes) and the frictionless
 * pinched box (no: it does not stand). */
static void extruded_2d_cases(void) {
  us_Structure *s = us_structure_new(2);
  s->friction = 0.5;
  scene_box(s, "pierL", 0, 0, 2, 3, 1);
  scene_box(s, "pierR", 3, 0, 2, 3, 1);
  scene_box(s, "box", 2, 1, 1, 1, 1);
  s = prism(scene_seal(s));
  CHECK(s);
  CHECK_INT(scene_verdict(s, US_METHOD_LP, NULL), ==, US_STABLE);
#if defined(__SANITIZE_ADDRESS__)
  int v = verdict3_budget(s, 300); /* memory errors, not the verdict: it needs 30,000 */
  CHECK(v == 0 || v == -1);
#else
  CHECK_INT(verdict3_budget(s, 30000), ==, 0);
#endif
  us_structure_free(s);
  s = prism(scene_column(3));
  CHECK(s);
  for (int c = 0; c < s->ncontact; c++) s->contacts[c].mu = 0;
  CHECK_INT(verdict3(s), ==, 1);
  us_structure_free(s);
  s = prism(pinched2(1, 0.0));
  CHECK(s);
  CHECK_INT(verdict3(s), ==, 0);
  us_structure_free(s);
}

/* ---------------------------------------------------- the witness check */

/* The pinched box's free fall passes the check; wrong accelerations, a
 * pulling contact, friction outside the circular cone or along the slip
 * of the sliding cube do not. */
static void tampered_witness_rejected(void) {
  us_Structure *s = prism(pinched2(1, 0.5));
  CHECK(s);
  us_StrongResult r;
  CHECK_INT(strong3(s, &r), ==, 0);
  char why[128];
  CHECK(us_strong_check(s, NULL, &r, 1e-5, why, sizeof why));
  double az = r.accel[2];
  r.accel[2] = 0.9 * az; /* Newton fails */
  CHECK(!us_strong_check(s, NULL, &r, 1e-5, why, sizeof why));
  r.accel[2] = az;
  r.accel[4] = 0.5; /* a spin the forces do not give */
  CHECK(!us_strong_check(s, NULL, &r, 1e-5, why, sizeof why));
  r.accel[4] = 0;
  double a[6];
  memcpy(a, r.accel, sizeof a);
  memset(r.accel, 0, sizeof a); /* at rest: no motion */
  CHECK(!us_strong_check(s, NULL, &r, 1e-5, why, sizeof why));
  memcpy(r.accel, a, sizeof a);
  CHECK(us_strong_check(s, NULL, &r, 1e-5, why, sizeof why));
  r.force[0] = -1.0; /* a contact pulling */
  CHECK(!us_strong_check(s, NULL, &r, 1e-5, why, sizeof why));
  r.force[0] = 0;
  us_strong_result_free(&r);
  us_structure_free(s);

  s = slope_along_frame(0.7, 0.5);
  CHECK(s);
  CHECK_INT(strong3(s, &r), ==, 0);
  CHECK(r.has_witness);
  CHECK(us_strong_check(s, NULL, &r, 1e-5, why, sizeof why));
  /* friction turned a quarter: as large, inside the cone, not against the
     slip */
  for (int k = 0; k < r.ncontact; k++) {
    double *f = r.force + 3 * k, f1 = f[1];
    f[1] = -f[2], f[2] = f1;
  }
  CHECK(!us_strong_check(s, NULL, &r, 1e-5, why, sizeof why));
  for (int k = 0; k < r.ncontact; k++) {
    double *f = r.force + 3 * k, f1 = f[1];
    f[1] = f[2], f[2] = -f1;
  }
  CHECK(us_strong_check(s, NULL, &r, 1e-5, why, sizeof why));
  for (int k = 0; k < r.ncontact; k++) r.force[3 * k + 1] *= 1.5; /* outside the cone */
  CHECK(!us_strong_check(s, NULL, &r, 1e-5, why, sizeof why));
  us_strong_result_free(&r);
  us_structure_free(s);
}

/* ------------------------------------------------- differential tests */

/* Random 2D piles extruded, mu 0.5, every body present: an extruded motion
 * of the 2D pile is one of the prism, so 2D "no" forbids 3D "yes", and a
 * 3D "yes" (a proof for the circular cone) forces 2D "yes"; every 3D "no"
 * carries a witness that passes the check. The sample is smaller under
 * AddressSanitizer. */
static void extruded_piles_match_2d(void) {
  unsigned long long rng = 20261126;
#if defined(__SANITIZE_ADDRESS__)
  int n = 4, cases = 0, decided = 0, yes = 0;
#else
  int n = 24, cases = 0, decided = 0, yes = 0;
#endif
  for (int it = 0; it < n; it++) {
    us_Structure *s2 = pile_random(&rng, 3 + it % 2);
    if (!s2) continue;
    s2->friction = 0.5;
    for (int c = 0; c < s2->ncontact; c++) s2->contacts[c].mu = 0.5;
    us_StrongResult r2;
    us_StrongSettings set = us_strong_default_settings();
    set.method = US_STRONG_ENUM, set.time_limit = 0;
    us_Error err;
    CHECK_INT(us_strong_stability(s2, NULL, &set, &r2, &err), ==, US_OK);
    us_Structure *s3 = test_extrude(s2, 1.0, 0.3, 0.5, -0.25);
    CHECK(s3);
    for (int c = 0; s3 && c < s3->ncontact; c++) s3->contacts[c].mu = 0.5;
    /* 300 nodes: the 18 of 24 piles that 3,000 decide are decided by 300
       (the 6 others cost 1-15 s each undecided at 3,000, 0.3-2 s at 300) */
    int v3 = s3 ? verdict3_budget(s3, 300) : -2;
    if (r2.strong == 0) CHECK(v3 != 1);
    if (v3 == 1) CHECK_INT(r2.strong, ==, 1);
    CHECK(v3 >= -1);
    decided += v3 >= 0, yes += v3 == 1, cases++;
    us_strong_result_free(&r2);
    us_structure_free(s3);
    us_structure_free(s2);
  }
  fprintf(stderr, "%d extruded piles: %d decided in 3D, %d yes (not asserted)\n", cases, decided, yes);
  CHECK(cases >= n / 2);
  CHECK(decided > 0);
}

/* Every allocation failing in turn on the 3D pinched box: an error or a
 * full answer, never a crash or a leak (the harness checks leaks). */
static void out_of_memory(void) {
  us_Structure *s = prism(pinched2(1, 0.5));
  CHECK(s);
  us_StrongSettings set = us_strong_default_settings();
  set.time_limit = 0;
  int done = 0;
  for (int n = 0; n < 600 && !done; n++) {
    us_StrongResult r;
    us_Error err;
    us_alloc_fail_after(n);
    us_Status st = us_strong_stability(s, NULL, &set, &r, &err);
    us_alloc_fail_after(-1);
    if (st == US_OK) done = r.strong == 0, us_strong_result_free(&r);
    else CHECK(st == US_ERR_NOMEM || st == US_ERR_SOLVER);
  }
  CHECK(done);
  us_structure_free(s);
}

US_TEST_MAIN(T(pinched_off_ground_no), T(box_on_ground_yes), T(slope_below_at_above),
             T(extruded_2d_cases), T(tampered_witness_rejected), T(extruded_piles_match_2d), T(out_of_memory))
