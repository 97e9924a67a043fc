/* Tests of the 3D generators (src/gen/solid.c, regular.c): body counts,
 * the contacts each layout must have (counted from the layout, not from a
 * previous run), round trips through a file, and bad settings. */
#include "geometry/geometry3.h"
#include "test.h"

static int count_pair(const us_Structure *s, int i, int j) {
  int n = 0;
  for (int k = 0; k < s->ncontact; k++)
    n += (s->contacts[k].a == i && s->contacts[k].b == j) || (s->contacts[k].a == j && s->contacts[k].b == i);
  return n;
}

/* Body i's z range. */
static void z_range(const us_Structure *s, int i, double *lo, double *hi) {
  double bb[6];
  us_body_bbox3(&s->bodies[i], bb);
  *lo = bb[2], *hi = bb[5];
}

static void tower_straight(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.n = 6, g.width = 2, g.depth = 1, g.height = 0.5;
  us_Structure *s = us_gen_tower(&g, &err);
  CHECK(s != NULL);
  int ok = s->dim == 3 && s->nbody == 6 && s->ncontact == 4 * 6 && count_pair(s, US_GROUND, 0) == 4;
  for (int k = 0; ok && k + 1 < 6; k++) ok = count_pair(s, k, k + 1) == 4;
  ok = ok && fabs(s->bodies[5].com[2] - 2.75) < 1e-12 && fabs(s->bodies[0].mass - 1.0) < 1e-12;
  us_structure_free(s);
  CHECK(ok);
}

/* Turned boxes touch face to face on a convex polygon of 4 to 8 corners,
 * all at the level height; the turns follow the seed. */
static void tower_jitter(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.n = 12, g.jitter = 40, g.seed = 5;
  us_Structure *s = us_gen_tower(&g, &err), *t = us_gen_tower(&g, &err);
  g.seed = 6;
  us_Structure *u = us_gen_tower(&g, &err);
  CHECK(s && t && u);
  int ok = s->nbody == 12, turned = 0, same = 1, differs = 0;
  for (int k = 0; ok && k + 1 < 12; k++) {
    int n = count_pair(s, k, k + 1);
    ok = n >= 4 && n <= 8;
    turned += n > 4;
  }
  for (int c = 0; ok && c < s->ncontact; c++)
    if (s->contacts[c].a >= 0) {
      double lo, hi;
      z_range(s, s->contacts[c].b, &lo, &hi);
      ok = fabs(s->contacts[c].p[2] - lo) < 1e-12 && s->contacts[c].n[2] == 1.0;
    }
  for (int k = 0; k < 24; k++) same &= s->bodies[3].parts[0].verts[k] == t->bodies[3].parts[0].verts[k];
  for (int k = 0; k < 24; k++) differs |= s->bodies[3].parts[0].verts[k] != u->bodies[3].parts[0].verts[k];
  us_structure_free(s), us_structure_free(t), us_structure_free(u);
  CHECK(ok);
  CHECK(turned > 0);
  CHECK(same);
  CHECK(differs);
}

/* Each box above the ground rests on four, each touching on a quarter of
 * its bottom (4 points); boxes of one course touch their side neighbours
 * on a face (4 points) and their diagonal neighbours along an edge. */
static void pyramid3d_courses(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  int n = 5;
  g.n = n;
  us_Structure *s = us_gen_pyramid3d(&g, &err);
  CHECK(s != NULL);
  int total = n * (n + 1) * (2 * n + 1) / 6, nb = s->nbody, ok = 1, first = 0;
  for (int r = 0; ok && r < n; r++) {
    int m = n - r;
    for (int k = first; ok && k < first + m * m; k++) {
      double lo, hi;
      z_range(s, k, &lo, &hi);
      ok = fabs(lo - r * g.height) < 1e-12 && fabs(hi - (r + 1) * g.height) < 1e-12;
      int below = 0;
      for (int j = 0; j < first; j++)
        if (count_pair(s, j, k) > 0) {
          below++;
          ok &= count_pair(s, j, k) == 4;
        }
      ok &= r == 0 ? count_pair(s, US_GROUND, k) == 4 : below == 4;
    }
    /* neighbours along x in this course: a shared face */
    if (m > 1) ok &= count_pair(s, first, first + 1) == 4 && count_pair(s, first, first + m) == 4;
    first += m * m;
  }
  us_structure_free(s);
  CHECK_INT(nb, ==, total);
  CHECK(ok);
}

/* The 3D wall is the 2D wall extruded: twice its contacts, the same pairs. */
static void wall3d_is_extruded_wall(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.rows = 6, g.cols = 5, g.thickness = 0.3;
  us_Structure *w2 = us_gen_wall(&g, &err), *w3 = us_gen_wall3d(&g, &err);
  CHECK(w2 && w3);
  int ok = w2->nbody == w3->nbody && w3->ncontact == 2 * w2->ncontact;
  for (int i = -1; ok && i < w2->nbody; i++)
    for (int j = i + 1; ok && j < w2->nbody && j < i + 12; j++) ok = count_pair(w3, i, j) == 2 * count_pair(w2, i, j);
  double lo, hi;
  z_range(w3, w3->nbody - 1, &lo, &hi);
  ok = ok && fabs(hi - 6 * g.height) < 1e-12 && fabs(w3->bodies[0].mass - 0.15) < 1e-12;
  us_structure_free(w2), us_structure_free(w3);
  CHECK(ok);
}

/* generate -> file -> read: the same bodies and contacts. */
static void round_trip(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.n = 3, g.rows = 3, g.cols = 3, g.jitter = 25;
  us_Structure *(*fn[3])(const us_GenSettings *, us_Error *) = {us_gen_tower, us_gen_pyramid3d, us_gen_wall3d};
  for (int k = 0; k < 3; k++) {
    us_Structure *s = fn[k](&g, &err);
    CHECK(s != NULL);
    const char *path = "test_gen3d_rt.json";
    us_Status st = us_structure_write(s, path, &err);
    us_Structure *b = st ? NULL : us_structure_read(path, 0, &err);
    remove(path);
    int same = b && b->nbody == s->nbody && b->ncontact == s->ncontact;
    for (int c = 0; same && c < s->ncontact; c++)
      same = !memcmp(s->contacts[c].p, b->contacts[c].p, sizeof s->contacts[c].p) &&
             s->contacts[c].a == b->contacts[c].a && s->contacts[c].b == b->contacts[c].b;
    for (int i = 0; same && i < s->nbody; i++) same = s->bodies[i].mass == b->bodies[i].mass;
    us_structure_free(s);
    us_structure_free(b);
    CHECK_INT(st, ==, US_OK);
    CHECK(same);
  }
}

static void bad_settings(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.jitter = -1;
  CHECK(us_gen_tower(&g, &err) == NULL && err.code == US_ERR_USAGE && strstr(err.msg, "jitter"));
  g = us_gen_default_settings(), g.depth = 0;
  CHECK(us_gen_pyramid3d(&g, &err) == NULL && err.code == US_ERR_USAGE && strstr(err.msg, "depth"));
  g = us_gen_default_settings(), g.thickness = NAN;
  CHECK(us_gen_wall3d(&g, &err) == NULL && err.code == US_ERR_USAGE && strstr(err.msg, "thickness"));
  g = us_gen_default_settings(), g.n = 0;
  CHECK(us_gen_tower(&g, &err) == NULL && err.code == US_ERR_USAGE);
}

US_TEST_MAIN(T(tower_straight), T(tower_jitter), T(pyramid3d_courses), T(wall3d_is_extruded_wall),
             T(round_trip), T(bad_settings))
