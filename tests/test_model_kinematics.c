/* Tests of removal kinematics (src/contact/kinematics.c): small scenes with
 * known answers for US_REMOVAL_UP and US_REMOVAL_FREE (columns, a bridge,
 * slots, wedges, non-convex bodies, bodies without geometry), invariance
 * under scaling, and differential tests on random piles: the UP lists
 * against a brute-force evaluation of the definition over every pair of
 * bodies (cross-sections at every breakpoint, and the plain interval rule
 * for boxes), the FREE answers against a search over candidate directions.
 * Out-of-memory sweep at the end. */
#include "contact/kinematics.h"
#include "geometry/geometry.h"
#include "scenes.h"
#include "test.h"

#define PI 3.14159265358979323846

static us_Structure *g_s;   /* the scene of the current case */
static us_Kinematics *g_up, *g_free;
static us_Bitset g_all;     /* every movable body */

static int fixed_box(us_Structure *s, const char *id, double x0, double y0, double w, double h) {
  double xy[8] = {x0, y0, x0 + w, y0, x0 + w, y0 + h, x0, y0 + h};
  return scene_polygon(s, id, 4, xy, 1);
}

/* Finalize g_s and build both workspaces and g_all; 0 on failure. */
static int setup(void) {
  us_Error err;
  g_s = scene_seal(g_s);
  if (!g_s) return 0;
  g_up = us_kinematics_new(g_s, US_REMOVAL_UP, &err);
  g_free = us_kinematics_new(g_s, US_REMOVAL_FREE, &err);
  return g_up && g_free && us_structure_movable_set(g_s, &g_all) == 0;
}

static void teardown(void) {
  us_kinematics_free(g_up);
  us_kinematics_free(g_free);
  us_bitset_free(&g_all);
  us_structure_free(g_s);
  g_s = NULL;
  g_up = g_free = NULL;
}

static int up(int b) { return us_kinematics_can_remove(g_up, &g_all, b); }
static int fr(int b) { return us_kinematics_can_remove(g_free, &g_all, b); }

/* FREE direction of b in g_all: 1 when free with d ~ (dx, dy) and the
 * given cone width (each within 1e-9). */
static int free_dir_is(int b, double dx, double dy, double width) {
  double d[2], w;
  int ok = us_kinematics_direction(g_free, &g_all, b, d, &w);
  if (ok && fabs(d[0] - dx) <= 1e-9 && fabs(d[1] - dy) <= 1e-9 && fabs(w - width) <= 1e-9) return 1;
  fprintf(stderr, "  body %d: free %d, d (%g, %g), width %g\n", b, ok, d[0], d[1], w);
  return 0;
}

/* ------------------------------------------------------------ small scenes */

/* Three blocks: UP only the top; FREE every block (the middle one slides
 * out sideways, like a Jenga block: normals up and down lie in a closed
 * half-plane, and the cone is the horizontal line). */
static void column(void) {
  g_s = us_structure_new(2);
  for (int k = 0; k < 3; k++) {
    char id[32];
    snprintf(id, sizeof id, "c%d", k);
    CHECK(scene_box(g_s, id, 0, k, 1, 1, 1) == k);
  }
  CHECK(setup());
  CHECK_INT(up(0), ==, 0);
  CHECK_INT(up(1), ==, 0);
  CHECK_INT(up(2), ==, 1);
  CHECK_INT(us_kinematics_blocker(g_up, &g_all, 0), ==, 1); /* the lowest blocker */
  CHECK_INT(us_kinematics_blocker(g_up, &g_all, 2), ==, US_KIN_NONE);
  us_bitset_clear(&g_all, 1);
  CHECK_INT(up(0), ==, 0);
  CHECK_INT(us_kinematics_blocker(g_up, &g_all, 0), ==, 2); /* hanging above with a gap */
  us_bitset_clear(&g_all, 2);
  CHECK_INT(up(0), ==, 1);
  us_bitset_fill(&g_all);
  CHECK(fr(0) && fr(1) && fr(2));
  CHECK(free_dir_is(2, 0, 1, PI));
  CHECK_INT(us_kinematics_blocker(g_free, &g_all, 1), ==, US_KIN_NONE);
  double d[2], w;
  CHECK(us_kinematics_direction(g_free, &g_all, 1, d, &w));
  CHECK_NEAR(fabs(d[0]), 1.0, 1e-12);
  CHECK_NEAR(w, 0.0, 1e-12);
  teardown();
}

/* A neighbour touching the side: nothing blocks; FREE cone from up to
 * away from the neighbour. */
static void side_neighbour(void) {
  g_s = us_structure_new(2);
  CHECK(scene_box(g_s, "b", 0, 0, 1, 1, 1) == 0);
  CHECK(scene_box(g_s, "n", 1, 0, 1, 2, 1) == 1);
  CHECK(setup());
  CHECK(up(0) && up(1));
  CHECK(fr(0) && fr(1));
  CHECK(free_dir_is(0, -sqrt(0.5), sqrt(0.5), PI / 2));
  int n;
  us_kinematics_up_blockers(g_up, 0, &n);
  CHECK_INT(n, ==, 0);
  CHECK_INT(us_kinematics_up_pairs(g_up), ==, 0);
  teardown();
}

/* Overlaps far below the pair's tolerance (1e-6 of its size) but above
 * rounding: a neighbour reaching 1e-8 into b's side does not block; a
 * block resting on b, sunk 1e-8 into it, blocks b; b sunk 1e-8 into the
 * block under it is not blocked by it. Pairs far above tol do block. */
static void tolerance(void) {
  g_s = us_structure_new(2);
  CHECK(scene_box(g_s, "base", 0, 0, 4, 1, 1) == 0);
  CHECK(scene_box(g_s, "b", 0, 1 - 1e-8, 1, 1, 1) == 1);
  CHECK(scene_box(g_s, "side", 1 - 1e-8, 1, 1, 2, 1) == 2);
  CHECK(scene_box(g_s, "top", 0, 2 - 2e-8, 1, 1, 1) == 3);
  double u[16] = {2, 0, 4, 0, 4, 2, 3.5, 2, 3.5, 1, 2.5, 1, 2.5, 2, 2, 2};
  for (int i = 0; i < 8; i++) u[2 * i + 1] += 1; /* a U on the base, x 2..4 */
  CHECK(scene_polygon(g_s, "u", 8, u, 0) == 4);
  CHECK(scene_box(g_s, "in", 2.75, 2 - 1e-8, 0.5, 0.5, 1) == 5); /* sunk into its floor */
  CHECK(setup());
  CHECK(up(5) && !up(4));
  CHECK(up(3) && up(2) && !up(1) && !up(0));
  CHECK_INT(us_kinematics_blocker(g_up, &g_all, 1), ==, 3);
  us_bitset_clear(&g_all, 3);
  CHECK_INT(up(1), ==, 1);
  teardown();
  g_s = us_structure_new(2); /* 1e-4 of the pair's size sideways: blocks */
  g_s->contact_tol = 1e-3;    /* (finalize accepts it with a loose tolerance) */
  CHECK(scene_box(g_s, "b", 0, 0, 1, 1, 1) == 0);
  CHECK(scene_box(g_s, "side", 1 - 1e-4, 0.5, 1, 2, 1) == 1);
  g_s = scene_seal(g_s);
  CHECK(g_s);
  us_Kinematics *k = us_kinematics_new(g_s, US_REMOVAL_UP, NULL);
  int n;
  CHECK(k && us_kinematics_up_blockers(k, 0, &n) && n == 1);
  us_kinematics_free(k);
  us_structure_free(g_s);
  g_s = NULL;
}

/* The angular tolerance of the half-plane test: normals into b at 0,
 * pi / 2 and pi + e leave a largest gap of pi - e (the normal at pi + e
 * is given twice, once from each side of a contact). */
static void angle_tolerance(void) {
  double es[4] = {1e-9, -1e-3, 1e-3, 1e-5};
  int expect[4] = {1, 1, 0, 0};
  for (int t = 0; t < 4; t++) {
    us_Error err;
    g_s = us_structure_new(2);
    double c[2] = {0, 0}, p[3] = {0, 0, 0};
    for (int i = 0; i < 4; i++) {
      char id[32];
      snprintf(id, sizeof id, "p%d", i);
      CHECK(us_structure_add_point_body(g_s, id, 1, c, 0, &err) == i);
    }
    double n0[3] = {1, 0, 0}, n1[3] = {0, 1, 0}, n2[3] = {cos(es[t]), sin(es[t]), 0};
    CHECK(us_structure_add_contact(g_s, 1, 0, p, n0, -1, &err) >= 0);
    CHECK(us_structure_add_contact(g_s, US_GROUND, 0, p, n1, -1, &err) >= 0);
    CHECK(us_structure_add_contact(g_s, 0, 2, p, n2, -1, &err) >= 0); /* b is a: flipped */
    n2[0] = -n2[0];
    n2[1] = -n2[1];
    CHECK(us_structure_add_contact(g_s, 3, 0, p, n2, -1, &err) >= 0);
    CHECK(setup());
    CHECK_INT(fr(0), ==, expect[t]);
    if (t == 1) CHECK(free_dir_is(0, cos(PI / 2 - 5e-4), sin(PI / 2 - 5e-4), 1e-3));
    teardown();
  }
}

/* A block under a bridge, a gap above it: UP blocked by the lintel, FREE
 * allowed. A fixed lintel blocks the same way and always. */
static void under_bridge(void) {
  for (int fixed = 0; fixed <= 1; fixed++) {
    g_s = us_structure_new(2);
    CHECK(scene_box(g_s, "pl", 0, 0, 1, 2, 1) == 0);
    CHECK(scene_box(g_s, "pr", 3, 0, 1, 2, 1) == 1);
    CHECK(fixed ? fixed_box(g_s, "lintel", 0, 2, 4, 0.5) == 2
                : scene_box(g_s, "lintel", 0, 2, 4, 0.5, 1) == 2);
    CHECK(scene_box(g_s, "b", 1.5, 0, 1, 1, 1) == 3);
    CHECK(setup());
    CHECK_INT(up(3), ==, 0);
    CHECK_INT(us_kinematics_blocker(g_up, &g_all, 3), ==, 2);
    CHECK_INT(fr(3), ==, 1);
    CHECK(free_dir_is(3, 0, 1, PI));
    us_bitset_clear(&g_all, 2);
    CHECK_INT(up(3), ==, !fixed);
    CHECK_INT(up(0), ==, !fixed);
    CHECK_INT(up(2), ==, fixed ? 0 : 1);
    teardown();
  }
}

/* A block between two walls (touching both), then with a lid: FREE
 * straight up only, then blocked; the lid is named as the blocker. */
static void slot(void) {
  for (int lid = 0; lid <= 1; lid++) {
    g_s = us_structure_new(2);
    CHECK(scene_box(g_s, "wl", 0, 0, 1, 1, 1) == 0);
    CHECK(scene_box(g_s, "b", 1, 0, 1, 1, 1) == 1);
    CHECK(scene_box(g_s, "wr", 2, 0, 1, 1, 1) == 2);
    if (lid) CHECK(scene_box(g_s, "lid", 0, 1, 3, 0.5, 1) == 3);
    CHECK(setup());
    CHECK_INT(up(1), ==, !lid);
    CHECK_INT(fr(1), ==, !lid);
    if (!lid) CHECK(free_dir_is(1, 0, 1, 0));
    if (lid) {
      CHECK_INT(us_kinematics_blocker(g_free, &g_all, 1), ==, 3);
      double d[2] = {7, 7}, w = 7;
      CHECK_INT(us_kinematics_direction(g_free, &g_all, 1, d, &w), ==, 0);
      CHECK(d[0] == 0 && d[1] == 0 && w == 0);
      us_bitset_clear(&g_all, 3);
      CHECK_INT(fr(1), ==, 1);
      us_bitset_set(&g_all, 3);
      us_bitset_clear(&g_all, 0); /* a wall gone: slides out to the left */
      CHECK(free_dir_is(1, -1, 0, 0));
    }
    teardown();
  }
}

/* A slot between fixed walls under a fixed lid: no single movable body to
 * blame, the blocker is the body of the first contact in angle order. */
static void fixed_slot(void) {
  g_s = us_structure_new(2);
  CHECK(fixed_box(g_s, "wl", 0, 0, 1, 1) == 0);
  CHECK(scene_box(g_s, "b", 1, 0, 1, 1, 1) == 1);
  CHECK(fixed_box(g_s, "wr", 2, 0, 1, 1) == 2);
  CHECK(fixed_box(g_s, "lid", 0, 1, 3, 0.5) == 3);
  CHECK(setup());
  CHECK_INT(fr(1), ==, 0);
  CHECK_INT(us_kinematics_blocker(g_free, &g_all, 1), ==, 3); /* normal (0, -1) comes first */
  CHECK_INT(up(1), ==, 0);
  CHECK_INT(us_kinematics_blocker(g_up, &g_all, 1), ==, 3);
  /* fixed bodies are never removable; their bits do not matter */
  CHECK_INT(fr(0), ==, 0);
  CHECK_INT(up(3), ==, 0);
  CHECK_INT(us_kinematics_blocker(g_up, &g_all, 3), ==, 3);
  teardown();
  g_s = us_structure_new(2); /* the left wall movable: removing it alone frees b */
  CHECK(scene_box(g_s, "wl", 0, 0, 1, 1, 1) == 0);
  CHECK(scene_box(g_s, "b", 1, 0, 1, 1, 1) == 1);
  CHECK(fixed_box(g_s, "wr", 2, 0, 1, 1) == 2);
  CHECK(fixed_box(g_s, "lid", 0, 1, 3, 0.5) == 3);
  CHECK(setup());
  CHECK_INT(fr(1), ==, 0);
  CHECK_INT(us_kinematics_blocker(g_free, &g_all, 1), ==, 0);
  teardown();
}

/* UP names the lowest present blocker, not the first by index. */
static void blocker_order(void) {
  g_s = us_structure_new(2);
  CHECK(scene_box(g_s, "high", 0, 5, 1, 1, 1) == 0);
  CHECK(scene_box(g_s, "base", 0, 0, 1, 1, 1) == 1);
  CHECK(scene_box(g_s, "mid", 0, 1, 1, 1, 1) == 2);
  CHECK(setup());
  CHECK_INT(us_kinematics_blocker(g_up, &g_all, 1), ==, 2);
  us_bitset_clear(&g_all, 2);
  CHECK_INT(us_kinematics_blocker(g_up, &g_all, 1), ==, 0);
  teardown();
}

/* Two wedges meeting at a sharp apex: c lies on b's slope, thin at the
 * apex, and reaches far above b only at the right end of their common
 * x-range (the far end of the edge pair decides). */
static void thin_wedges(void) {
  double b[6] = {0, 0, 2, 0, 2, 1}, c[6] = {0, 0, 2, 1, 2, 1.5};
  g_s = us_structure_new(2);
  CHECK(scene_polygon(g_s, "b", 3, b, 0) == 0 && scene_polygon(g_s, "c", 3, c, 0) == 1);
  CHECK(setup());
  CHECK(!up(0) && up(1));
  CHECK_INT(us_kinematics_up_pairs(g_up), ==, 1);
  teardown();
}

/* The leaning slabs of tests/data/leaning.json: their x-ranges only touch,
 * so both lift; FREE: each may slide outwards or lift. */
static void leaning(void) {
  double l[8] = {0, 0, 0.3, 0, 1, 1.75, 1, 2.25}, r[8] = {2, 0, 1, 2.25, 1, 1.75, 1.7, 0};
  g_s = us_structure_new(2);
  CHECK(scene_polygon(g_s, "left", 4, l, 0) == 0);
  CHECK(scene_polygon(g_s, "right", 4, r, 0) == 1);
  CHECK(setup());
  CHECK(up(0) && up(1) && fr(0) && fr(1));
  CHECK(free_dir_is(0, -sqrt(0.5), sqrt(0.5), PI / 2));
  CHECK(free_dir_is(1, sqrt(0.5), sqrt(0.5), PI / 2));
  teardown();
}

/* A V notch between two blocks whose faces lean outwards holds a wedge
 * (slanted normals (+-2, 1)/sqrt 5): the wedge lifts out, the blocks are
 * under it. A dovetail (faces leaning inwards) locks its key: both UP and
 * FREE blocked, and removing either block frees it under FREE. */
static void wedge(void) {
  double lb[8] = {0, 0, 2, 0, 1, 2, 0, 2}, rb[8] = {4, 0, 6, 0, 6, 2, 5, 2};
  double w[8] = {1.5, 1, 4.5, 1, 5, 2, 1, 2};
  g_s = us_structure_new(2);
  CHECK(scene_polygon(g_s, "l", 4, lb, 0) == 0 && scene_polygon(g_s, "r", 4, rb, 0) == 1 && scene_polygon(g_s, "w", 4, w, 0) == 2);
  CHECK(setup());
  CHECK(up(2) && !up(0) && !up(1));
  CHECK_INT(us_kinematics_blocker(g_up, &g_all, 0), ==, 2);
  CHECK(fr(2) && fr(0) && fr(1));
  CHECK(free_dir_is(2, 0, 1, 2 * atan(0.5)));
  teardown();

  double dl[8] = {0, 0, 2, 0, 3, 2, 0, 2}, dr[8] = {5, 0, 7, 0, 7, 2, 4, 2};
  double key[8] = {2, 0, 5, 0, 4, 2, 3, 2};
  g_s = us_structure_new(2);
  CHECK(scene_polygon(g_s, "l", 4, dl, 0) == 0 && scene_polygon(g_s, "r", 4, dr, 0) == 1 && scene_polygon(g_s, "k", 4, key, 0) == 2);
  CHECK(setup());
  CHECK(!up(2) && up(0) && up(1));
  CHECK_INT(us_kinematics_blocker(g_up, &g_all, 2), ==, 0); /* equal heights: lower index */
  CHECK_INT(fr(2), ==, 0);
  CHECK_INT(us_kinematics_blocker(g_free, &g_all, 2), ==, 1); /* normal (-2, -1) comes first */
  us_bitset_clear(&g_all, 0);
  CHECK(fr(2) && !up(2));
  teardown();
}

/* A U-shaped body with a block in its notch. Tight fit: the block lifts
 * straight up, the U is blocked both ways. Loose fit: UP still blocks the
 * U, but FREE lets it slide sideways: the local test does not see the
 * block it would hit farther on (documented). */
static void u_notch(void) {
  double u[16] = {0, 0, 3, 0, 3, 2, 2, 2, 2, 1, 1, 1, 1, 2, 0, 2};
  for (int tight = 1; tight >= 0; tight--) {
    g_s = us_structure_new(2);
    CHECK(scene_polygon(g_s, "u", 8, u, 0) == 0);
    CHECK(tight ? scene_box(g_s, "b", 1, 1, 1, 0.5, 1) == 1 : scene_box(g_s, "b", 1.25, 1, 0.5, 0.5, 1) == 1);
    CHECK(setup());
    CHECK(up(1) && !up(0));
    CHECK_INT(us_kinematics_blocker(g_up, &g_all, 0), ==, 1);
    CHECK_INT(fr(1), ==, 1);
    CHECK_INT(fr(0), ==, !tight);
    if (tight) CHECK(free_dir_is(1, 0, 1, 0));
    if (tight) CHECK_INT(us_kinematics_blocker(g_free, &g_all, 0), ==, 1);
    teardown();
  }
}

/* A C shape (opening to the right) round a block resting on its lower
 * arm: each blocks the other under UP (the pair is tested both ways). */
static void c_interlock(void) {
  double c[16] = {0, 0, 3, 0, 3, 0.5, 1, 0.5, 1, 1.5, 3, 1.5, 3, 2, 0, 2};
  g_s = us_structure_new(2);
  CHECK(scene_polygon(g_s, "c", 8, c, 0) == 0);
  CHECK(scene_box(g_s, "b", 1.5, 0.5, 1, 0.5, 1) == 1);
  CHECK(setup());
  CHECK(!up(0) && !up(1));
  CHECK_INT(us_kinematics_up_pairs(g_up), ==, 2);
  CHECK(fr(1) && free_dir_is(1, 0, 1, PI)); /* the upper arm is not touched */
  teardown();
}

/* Bodies far apart never block, and a far body does not change answers. */
static void far_apart(void) {
  g_s = us_structure_new(2);
  CHECK(scene_box(g_s, "a", 0, 0, 1, 1, 1) == 0);
  CHECK(scene_box(g_s, "b", 100, 0, 1, 1, 1) == 1);
  CHECK(scene_box(g_s, "c", 50, 1000, 1, 1, 1) == 2);  /* high up, between */
  CHECK(scene_box(g_s, "d", 1, 500, 49, 1, 1) == 3);   /* x 1..50: touches a and c */
  CHECK(setup());
  CHECK(up(0) && up(1) && up(2) && up(3) && fr(0) && fr(1));
  CHECK_INT(us_kinematics_up_pairs(g_up), ==, 0);
  teardown();
}

/* Bodies without geometry: contacts pressing down block; side contacts do
 * not; a ground contact pressing down (a ceiling) names the ground. */
static void point_bodies(void) {
  us_Error err;
  g_s = us_structure_new(2);
  double c0[2] = {0, 0.5}, c1[2] = {0, 1.5}, c2[2] = {1, 1.5}, c3[2] = {5, 0.5};
  CHECK(us_structure_add_point_body(g_s, "p0", 1, c0, 0, &err) == 0);
  CHECK(us_structure_add_point_body(g_s, "p1", 1, c1, 0, &err) == 1);
  CHECK(us_structure_add_point_body(g_s, "p2", 1, c2, 0, &err) == 2);
  CHECK(us_structure_add_point_body(g_s, "p3", 1, c3, 0, &err) == 3);
  double p[3] = {0, 0, 0}, nup[3] = {0, 1, 0}, nside[3] = {1, -1e-12, 0}, ndown[3] = {0, -1, 0};
  CHECK(us_structure_add_contact(g_s, US_GROUND, 0, p, nup, -1, &err) >= 0);
  CHECK(us_structure_add_contact(g_s, 0, 1, p, nup, -1, &err) >= 0);
  CHECK(us_structure_add_contact(g_s, 0, 1, p, nup, -1, &err) >= 0);
  CHECK(us_structure_add_contact(g_s, 1, 2, p, nside, -1, &err) >= 0);
  CHECK(us_structure_add_contact(g_s, US_GROUND, 3, p, nup, -1, &err) >= 0);
  CHECK(us_structure_add_contact(g_s, US_GROUND, 3, p, ndown, -1, &err) >= 0);
  CHECK(setup());
  CHECK(!up(0) && up(1) && up(2) && !up(3));
  CHECK_INT(us_kinematics_blocker(g_up, &g_all, 0), ==, 1);
  CHECK_INT(us_kinematics_blocker(g_up, &g_all, 3), ==, US_GROUND);
  int n;
  const int *l = us_kinematics_up_blockers(g_up, 3, &n);
  CHECK(n == 1 && l[0] == US_GROUND);
  l = us_kinematics_up_blockers(g_up, 0, &n); /* two contacts, one blocker */
  CHECK(n == 1 && l[0] == 1);
  CHECK(fr(0) && fr(1) && fr(2) && fr(3)); /* 3: up and down, slides sideways */
  CHECK(free_dir_is(2, 1, 0, PI));
  teardown();
}

/* Mode ANY allows everything; bad structures are usage errors; b's own bit
 * never matters (removal and placement are the same question). */
static void modes_and_bits(void) {
  us_Error err;
  g_s = us_structure_new(2);
  CHECK(scene_box(g_s, "a", 0, 0, 1, 1, 1) == 0);
  us_error_clear(&err);
  CHECK(us_kinematics_new(g_s, US_REMOVAL_UP, &err) == NULL);
  CHECK_INT(err.code, ==, US_ERR_USAGE);
  CHECK(us_kinematics_new(g_s, US_REMOVAL_UP, NULL) == NULL);
  CHECK(scene_box(g_s, "b", 0, 1, 1, 1, 1) == 1);
  CHECK(setup());
  us_Kinematics *any = us_kinematics_new(g_s, US_REMOVAL_ANY, &err);
  CHECK(any);
  CHECK_INT(us_kinematics_mode(any), ==, US_REMOVAL_ANY);
  CHECK_INT(us_kinematics_can_remove(any, &g_all, 0), ==, 1);
  CHECK_INT(us_kinematics_blocker(any, &g_all, 0), ==, US_KIN_NONE);
  CHECK(us_kinematics_up_blockers(any, 0, &(int){0}) == NULL && us_kinematics_up_pairs(any) == 0);
  us_kinematics_free(any);
  CHECK(us_kinematics_new(g_s, (us_Removal)7, &err) == NULL);
  for (int bit = 0; bit <= 1; bit++) {
    us_bitset_fill(&g_all);
    if (!bit) us_bitset_clear(&g_all, 0);
    CHECK_INT(up(0), ==, 0);
    us_bitset_fill(&g_all);
    if (!bit) us_bitset_clear(&g_all, 1);
    CHECK_INT(up(1), ==, 1);
  }
  teardown();
}

/* ------------------------------------------------------------- invariance */

/* Column, bridge, wedge, U with its block, dovetail, C round a block, all
 * scaled by `k`. */
static int mixed_scene(us_Structure *s, double k) {
  static const double polys[][17] = {
      {4, 0, 0, 1, 0, 1, 1, 0, 1},           {4, 0, 1, 1, 1, 1, 2, 0, 2},
      {4, 2, 0, 3, 0, 3, 2, 2, 2},           {4, 5, 0, 6, 0, 6, 2, 5, 2},
      {4, 2, 2, 6, 2, 6, 2.5, 2, 2.5},       {4, 3.5, 0, 4.5, 0, 4.5, 1, 3.5, 1},
      {4, 7, 0, 9, 0, 8, 2, 7, 2},           {4, 11, 0, 13, 0, 13, 2, 12, 2},
      {4, 8.5, 1, 11.5, 1, 12, 2, 8, 2},     {8, 14, 0, 17, 0, 17, 2, 16, 2, 16, 1, 15, 1, 15, 2, 14, 2},
      {4, 15, 1, 16, 1, 16, 1.5, 15, 1.5},   {8, 18, 0, 21, 0, 21, 0.5, 19, 0.5, 19, 1.5, 21, 1.5, 21, 2, 18, 2},
      {4, 19.5, 0.5, 20.5, 0.5, 20.5, 1, 19.5, 1}};
  for (int i = 0; i < (int)(sizeof polys / sizeof polys[0]); i++) {
    int n = (int)polys[i][0];
    double xy[16];
    for (int j = 0; j < 2 * n; j++) xy[j] = k * polys[i][1 + j];
    char id[32];
    snprintf(id, sizeof id, "m%d", i);
    if (scene_polygon(s, id, n, xy, 0) != i) return -1;
  }
  return (int)(sizeof polys / sizeof polys[0]);
}

/* Every query on random sub-assemblies answers the same at scale 1, 1e-6
 * and 1e6. */
static void scale_invariance(void) {
  us_Structure *s[3] = {NULL, NULL, NULL};
  us_Kinematics *k[3][2] = {{NULL, NULL}, {NULL, NULL}, {NULL, NULL}};
  double scale[3] = {1.0, 1e-6, 1e6};
  int n = 0;
  for (int i = 0; i < 3; i++) {
    s[i] = us_structure_new(2);
    CHECK(s[i] && (n = mixed_scene(s[i], scale[i])) > 0);
    CHECK((s[i] = scene_seal(s[i])) != NULL);
    k[i][0] = us_kinematics_new(s[i], US_REMOVAL_UP, NULL);
    k[i][1] = us_kinematics_new(s[i], US_REMOVAL_FREE, NULL);
    CHECK(k[i][0] && k[i][1]);
  }
  CHECK_INT(us_kinematics_up_pairs(k[0][0]), >, 5);
  us_Bitset p;
  CHECK(us_bitset_init(&p, n) == 0);
  unsigned long long rng = 12345;
  int diffs = 0;
  for (int trial = 0; trial < 200; trial++) {
    for (int b = 0; b < n; b++)
      if (trial == 0 || test_rnd(&rng) < 0.6) us_bitset_set(&p, b); else us_bitset_clear(&p, b);
    for (int b = 0; b < n; b++)
      for (int m = 0; m < 2; m++)
        for (int i = 1; i < 3; i++) {
          diffs += us_kinematics_can_remove(k[0][m], &p, b) != us_kinematics_can_remove(k[i][m], &p, b);
          diffs += us_kinematics_blocker(k[0][m], &p, b) != us_kinematics_blocker(k[i][m], &p, b);
        }
  }
  us_bitset_free(&p);
  for (int i = 0; i < 3; i++) {
    us_kinematics_free(k[i][0]);
    us_kinematics_free(k[i][1]);
    us_structure_free(s[i]);
  }
  CHECK_INT(diffs, ==, 0);
}

/* ---------------------------------------------------- random piles, brute force */

/* Highest (top) or lowest point of polygon xy on the vertical line at x,
 * over its non-vertical edges whose x-range holds x. */
static double cross_extreme(const double *xy, int n, double x, int top) {
  double best = top ? -INFINITY : INFINITY;
  for (int i = 0; i < n; i++) {
    double x0 = xy[2 * i], y0 = xy[2 * i + 1], x1 = xy[2 * ((i + 1) % n)], y1 = xy[2 * ((i + 1) % n) + 1];
    if (x0 == x1 || x < fmin(x0, x1) || x > fmax(x0, x1)) continue;
    double y = y0 + (x - x0) / (x1 - x0) * (y1 - y0);
    best = top ? fmax(best, y) : fmin(best, y);
  }
  return best;
}

static int dbl_cmp(const void *pa, const void *pb) {
  double a = *(const double *)pa, b = *(const double *)pb;
  return (a > b) - (a < b);
}

/* The definition, evaluated at every breakpoint of the two envelopes in
 * the shrunk common x-range and halfway between them: c reaches more than
 * tol above b on one vertical line. */
static int ref_blocks(const us_Body *c, const us_Body *b) {
  double bc[4], bb[4];
  us_poly_bbox(c->verts, c->nvert, bc);
  us_poly_bbox(b->verts, b->nvert, bb);
  double tol = US_KIN_TOL_REL * fmax(hypot(bc[2] - bc[0], bc[3] - bc[1]), hypot(bb[2] - bb[0], bb[3] - bb[1]));
  double lo = fmax(bc[0], bb[0]) + tol, hi = fmin(bc[2], bb[2]) - tol;
  if (lo > hi) return 0;
  double xs[130];
  int m = 0;
  xs[m++] = lo;
  xs[m++] = hi;
  for (int i = 0; i < c->nvert + b->nvert && m < 64; i++) {
    double x = i < c->nvert ? c->verts[2 * i] : b->verts[2 * (i - c->nvert)];
    if (x > lo && x < hi) xs[m++] = x;
  }
  qsort(xs, (size_t)m, sizeof *xs, dbl_cmp);
  for (int i = 0, m0 = m; i + 1 < m0; i++) xs[m++] = 0.5 * (xs[i] + xs[i + 1]);
  for (int i = 0; i < m; i++)
    if (cross_extreme(c->verts, c->nvert, xs[i], 1) - cross_extreme(b->verts, b->nvert, xs[i], 0) > tol)
      return 1;
  return 0;
}

/* For two axis-aligned boxes: open x-ranges overlapping by more than 2 tol
 * and c's top more than tol above b's bottom. */
static int ref_boxes(const us_Body *c, const us_Body *b) {
  double bc[4], bb[4];
  us_poly_bbox(c->verts, c->nvert, bc);
  us_poly_bbox(b->verts, b->nvert, bb);
  double tol = US_KIN_TOL_REL * fmax(hypot(bc[2] - bc[0], bc[3] - bc[1]), hypot(bb[2] - bb[0], bb[3] - bb[1]));
  return fmin(bc[2], bb[2]) - fmax(bc[0], bb[0]) >= 2 * tol && bc[3] - bb[1] > tol;
}

/* Random shape in the box [x0, x1] x [y0, y1]: a box (most), a triangle, an
 * L, or a U with a block in its notch. Returns bodies added or -1. */
static int add_shape(us_Structure *s, int *nb, double x0, double x1, double y0, double y1, int kind) {
  char id[16];
  snprintf(id, sizeof id, "s%d", *nb);
  double xm = 0.5 * (x0 + x1), ym = 0.5 * (y0 + y1), q = 0.25 * (x1 - x0);
  double tri[6] = {x0, y0, x1, y0, xm, y1}, l[12] = {x0, y0, x1, y0, x1, ym, xm, ym, xm, y1, x0, y1};
  double u[16] = {x0, y0, x1, y0, x1, y1, x1 - q, y1, x1 - q, ym, x0 + q, ym, x0 + q, y1, x0, y1};
  int r;
  if (kind == 1) r = scene_polygon(s, id, 3, tri, 0);
  else if (kind == 2) r = scene_polygon(s, id, 6, l, 0);
  else if (kind == 3) r = scene_polygon(s, id, 8, u, 0);
  else r = scene_box(s, id, x0, y0, x1 - x0, y1 - y0, 1);
  if (r != (*nb)++) return -1;
  if (kind != 3) return 1;
  snprintf(id, sizeof id, "s%d", *nb);
  double w = x1 - x0 - 2 * q, shrink = (*nb % 2) ? 0.0 : 0.25 * w;
  if (scene_box(s, id, x0 + q + shrink, ym, w - 2 * shrink, 0.5 * (y1 - ym), 1) != (*nb)++) return -1;
  return 2;
}

/* A pile of n shapes on a grid of quarter units: each dropped at a random
 * x onto the boxes below it, sometimes with a gap, many touching side by
 * side or corner to corner. boxes_only: only boxes; then every other pile
 * is packed (each box starts where the last one ended, rows of random
 * bond 10 units wide) so that many boxes are locked in by their
 * neighbours. */
static us_Structure *random_pile(unsigned long long *rng, int n, int boxes_only, double k) {
  us_Structure *s = us_structure_new(2);
  double bx[200][4];
  int nb = 0, packed = boxes_only && test_rnd(rng) < 0.5;
  for (int i = 0; i < n && s; i++) {
    double x0 = 0.25 * (int)(40 * test_rnd(rng)), w = 0.25 * (2 + (int)(7 * test_rnd(rng)));
    if (packed) x0 = i > 0 && bx[i - 1][2] < 10 ? bx[i - 1][2] : 0;
    double h = 0.25 * (1 + (int)(4 * test_rnd(rng))), y0 = 0;
    for (int j = 0; j < i; j++)
      if (x0 < bx[j][2] && bx[j][0] < x0 + w) y0 = fmax(y0, bx[j][3]);
    if (!packed && test_rnd(rng) < 0.25) y0 += 0.25 * (1 + (int)(4 * test_rnd(rng)));
    int kind = boxes_only ? 0 : (int)(6 * test_rnd(rng)) % 4;
    double b4[4] = {x0, y0, x0 + w, y0 + h};
    memcpy(bx[i], b4, sizeof b4);
    if (add_shape(s, &nb, k * x0, k * (x0 + w), k * y0, k * (y0 + h), kind) < 0) {
      us_structure_free(s);
      return NULL;
    }
  }
  return s ? scene_seal(s) : NULL;
}

/* The precomputed UP lists equal the brute-force reference over all
 * ordered pairs. */
static int up_lists_match(const us_Structure *s, const us_Kinematics *k, int boxes_only) {
  for (int b = 0; b < s->nbody; b++) {
    int n, pos = 0;
    const int *l = us_kinematics_up_blockers(k, b, &n);
    for (int c = 0; c < s->nbody; c++) {
      if (c == b) continue;
      int ref = boxes_only ? ref_boxes(&s->bodies[c], &s->bodies[b])
                           : ref_blocks(&s->bodies[c], &s->bodies[b]);
      int got = pos < n && l[pos] == c;
      pos += got;
      if (ref != got) {
        fprintf(stderr, "  body %s: blocker %s reference %d, got %d\n", s->bodies[b].id,
                s->bodies[c].id, ref, got);
        return 0;
      }
    }
    if (pos != n) return 0;
  }
  return 1;
}

/* Brute-force FREE: some direction among (0, 1) and each present normal
 * turned by +-90 degrees has d . n >= -1e-9 for every present normal. */
static int ref_free(const us_Structure *s, const us_Bitset *p, int b) {
  double nx[256], ny[256];
  int m = 0;
  for (int i = 0; i < s->ncontact && m < 256; i++) {
    const us_Contact *c = &s->contacts[i];
    int o = c->b == b ? c->a : c->a == b ? c->b : -9;
    if (o == -9 || (o >= 0 && !s->bodies[o].fixed && !us_bitset_get(p, o))) continue;
    double sg = c->b == b ? 1.0 : -1.0;
    nx[m] = sg * c->n[0];
    ny[m++] = sg * c->n[1];
  }
  for (int i = -1; i < 2 * m; i++) {
    double dx = i < 0 ? 0 : (i % 2 ? 1 : -1) * -ny[i / 2], dy = i < 0 ? 1 : (i % 2 ? 1 : -1) * nx[i / 2];
    int ok = 1;
    for (int j = 0; j < m && ok; j++) ok = dx * nx[j] + dy * ny[j] >= -1e-9;
    if (ok) return 1;
  }
  return 0;
}

/* Queries on random sub-assemblies agree with the references. */
static int queries_match(const us_Structure *s, const us_Kinematics *ku, const us_Kinematics *kf,
                         int boxes_only, unsigned long long *rng) {
  us_Bitset p;
  if (us_bitset_init(&p, s->nbody)) return 0;
  int bad = 0;
  for (int trial = 0; trial < 20 && !bad; trial++) {
    for (int b = 0; b < s->nbody; b++)
      if (test_rnd(rng) < 0.5) us_bitset_set(&p, b); else us_bitset_clear(&p, b);
    for (int b = 0; b < s->nbody && !bad; b++) {
      int blocked = 0;
      for (int c = 0; c < s->nbody && !blocked; c++)
        blocked = c != b && us_bitset_get(&p, c) &&
                  (boxes_only ? ref_boxes(&s->bodies[c], &s->bodies[b]) : ref_blocks(&s->bodies[c], &s->bodies[b]));
      int bl = us_kinematics_blocker(ku, &p, b);
      bad = us_kinematics_can_remove(ku, &p, b) == blocked || (bl != US_KIN_NONE) != blocked ||
            (bl >= 0 && !us_bitset_get(&p, bl));
      double d[2], w;
      int f = us_kinematics_direction(kf, &p, b, d, &w);
      bad = bad || f != ref_free(s, &p, b) || us_kinematics_can_remove(kf, &p, b) != f;
      if (bad) fprintf(stderr, "  body %s: UP %d (ref blocked %d), FREE %d (ref %d)\n", s->bodies[b].id,
                       us_kinematics_can_remove(ku, &p, b), blocked, f, ref_free(s, &p, b));
    }
  }
  us_bitset_free(&p);
  return !bad;
}

static int pile_case(unsigned long long *rng, int boxes_only, double k) {
  us_Structure *s = random_pile(rng, 20 + (int)(30 * test_rnd(rng)), boxes_only, k);
  if (!s) return 0;
  us_Kinematics *ku = us_kinematics_new(s, US_REMOVAL_UP, NULL);
  us_Kinematics *kf = us_kinematics_new(s, US_REMOVAL_FREE, NULL);
  int ok = ku && kf && up_lists_match(s, ku, boxes_only) && queries_match(s, ku, kf, boxes_only, rng);
  us_kinematics_free(ku);
  us_kinematics_free(kf);
  us_structure_free(s);
  return ok;
}

static void random_boxes(void) {
  unsigned long long rng = 0x9e3779b97f4a7c15ull;
  for (int t = 0; t < 150; t++) CHECK(pile_case(&rng, 1, t % 3 == 0 ? 1e-3 : 1.0));
}

static void random_shapes(void) {
  unsigned long long rng = 0x2545f4914f6cdd1dull;
  for (int t = 0; t < 150; t++) CHECK(pile_case(&rng, 0, t % 3 == 0 ? 7.3 : 1.0));
}

/* ---------------------------------------------------------- out of memory */

/* Every allocation failure gives NULL with US_ERR_NOMEM and no leak; with
 * enough allocations the same lists as without the hook. */
static void out_of_memory(void) {
  unsigned long long rng = 77;
  us_Structure *s = random_pile(&rng, 30, 0, 1.0);
  CHECK(s);
  for (int mode = US_REMOVAL_ANY; mode <= US_REMOVAL_FREE; mode++) {
    us_Kinematics *ref = us_kinematics_new(s, (us_Removal)mode, NULL);
    CHECK(ref);
    int failures = 0, done = 0;
    for (long n = 0; n < 100 && !done; n++) {
      us_Error err;
      us_error_clear(&err);
      us_alloc_fail_after(n);
      us_Kinematics *k = us_kinematics_new(s, (us_Removal)mode, &err);
      us_alloc_fail_after(-1);
      if (!k) {
        CHECK_INT(err.code, ==, US_ERR_NOMEM);
        failures++;
        continue;
      }
      done = 1;
      CHECK_INT(us_kinematics_up_pairs(k), ==, us_kinematics_up_pairs(ref));
      for (int b = 0; b < s->nbody; b++) {
        int n1, n2;
        const int *l1 = us_kinematics_up_blockers(k, b, &n1), *l2 = us_kinematics_up_blockers(ref, b, &n2);
        CHECK(n1 == n2 && (n1 == 0 || memcmp(l1, l2, (size_t)n1 * sizeof *l1) == 0));
      }
      us_kinematics_free(k);
    }
    us_kinematics_free(ref);
    CHECK(failures > 0 && done);
  }
  us_structure_free(s);
}

US_TEST_MAIN(T(column), T(side_neighbour), T(tolerance), T(angle_tolerance), T(under_bridge), T(slot), T(fixed_slot), T(blocker_order), T(thin_wedges), T(leaning),
             T(wedge), T(u_notch), T(c_interlock), T(far_apart), T(point_bodies),
             T(modes_and_bits), T(scale_invariance), T(random_boxes), T(random_shapes),
             T(out_of_memory))
