/* Tests of the 3D generators (src/gen/solid.c, regular.c, corner.c): body counts,
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

/* ------------------------------------------------- wall3d with returns */

/* The wall with corner returns: R courses of C columns, returns of L
 * bricks, thickness t, bricks w long and h high. */
static us_Structure *corner_wall(int R, int C, int L, double t, double w, double h) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.rows = R, g.cols = C, g.returns = L, g.thickness = t, g.width = w, g.height = h;
  us_Structure *s = us_gen_wall3d(&g, &err);
  if (!s) fprintf(stderr, "wall3d %d x %d, returns %d, t %g: %s\n", R, C, L, t, err.msg);
  return s;
}

/* The expected count, from the layout: per course the main wall, two
 * returns and, when the thickness is below half a brick, two closers;
 * odd courses have one brick fewer in the main wall (its corners are the
 * returns' through bricks). */
static int corner_count(int R, int C, int L, double t, double w) {
  return R * (C + 2 * L + (t < 0.5 * w ? 2 : 0)) - R / 2;
}

/* Body i's box (all bricks are axis-aligned boxes) and its course. */
static void box_of(const us_Structure *s, int i, double bb[6]) { us_body_bbox3(&s->bodies[i], bb); }
static int course_of(const us_Structure *s, int i, double h) {
  double bb[6];
  box_of(s, i, bb);
  return (int)lround(bb[2] / h);
}

/* A brick belongs to a return when it reaches past the main wall's back
 * face y = t (the returns' through bricks included). */
static int in_return(const double bb[6], double t) { return bb[4] > t + 1e-9; }

static void wall3d_returns_count(void) {
  int rows[4] = {1, 2, 3, 6}, cols[3] = {2, 3, 7}, lens[3] = {1, 2, 5};
  double ts[3] = {0.5, 0.3, 0.7};
  for (int a = 0; a < 4; a++)
    for (int b = 0; b < 3; b++)
      for (int c = 0; c < 3; c++)
        for (int d = 0; d < 3; d++) {
          us_Structure *s = corner_wall(rows[a], cols[b], lens[c], ts[d], 1.0, 0.5);
          CHECK(s != NULL);
          int nb = s->nbody;
          us_structure_free(s);
          CHECK_INT(nb, ==, corner_count(rows[a], cols[b], lens[c], ts[d], 1.0));
        }
  us_Structure *one = corner_wall(4, 1, 2, 0.3, 1.0, 0.5); /* one column: thin enough */
  CHECK(one != NULL);
  int nb = one->nbody;
  us_structure_free(one);
  CHECK_INT(nb, ==, corner_count(4, 1, 2, 0.3, 1.0));
}

/* The bricks tile the U exactly: the structure finalizes (detection
 * rejects interpenetration), no two boxes share interior volume, each
 * lies inside the U, is at most a brick long, fills its box (its mass is
 * its box's volume) and the volumes add up to the U's. */
static int tiles_u(const us_Structure *s, int R, int C, int L, double t, double w, double h) {
  double cw = C * w, lw = L * w, sum = 0, e = 1e-12 * w;
  int ok = 1;
  for (int i = 0; ok && i < s->nbody; i++) {
    double a[6];
    box_of(s, i, a);
    double v = (a[3] - a[0]) * (a[4] - a[1]) * (a[5] - a[2]);
    int in_main = a[4] <= t + e, in_left = a[3] <= t + e, in_right = a[0] >= cw - t - e;
    ok = a[0] >= -e && a[3] <= cw + e && a[1] >= -e && a[4] <= lw + e && (in_main || in_left || in_right);
    ok = ok && fmax(a[3] - a[0], a[4] - a[1]) <= w + e && fabs(s->bodies[i].mass - v) <= 1e-12 * v;
    sum += v;
    for (int j = i + 1; ok && j < s->nbody; j++) {
      double b[6], inter = 1;
      box_of(s, j, b);
      for (int k = 0; k < 3; k++) inter *= fmax(0.0, fmin(a[k + 3], b[k + 3]) - fmax(a[k], b[k]));
      ok = inter <= 1e-15;
    }
  }
  double area = cw * t + 2 * (lw - t) * t;
  return ok && fabs(sum - R * h * area) <= 1e-12 * sum;
}

static void wall3d_returns_tile(void) {
  static const struct {
    int R, C, L;
    double t, w, h;
  } cases[] = {{4, 6, 3, 0.5, 1, 0.5}, {5, 3, 2, 0.3, 1, 0.5}, {5, 4, 1, 0.7, 1, 0.5},
               {3, 3, 2, 0.23, 0.7, 0.3}, {4, 5, 3, 0.35, 0.7, 0.3}, {3, 1, 2, 0.2, 0.7, 0.3}};
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    us_Structure *s = corner_wall(cases[k].R, cases[k].C, cases[k].L, cases[k].t, cases[k].w, cases[k].h);
    CHECK(s != NULL);
    int ok = tiles_u(s, cases[k].R, cases[k].C, cases[k].L, cases[k].t, cases[k].w, cases[k].h);
    us_structure_free(s);
    CHECK(ok);
  }
}

/* Every brick above the bottom course rests on a brick of the course
 * below: their footprints overlap and detection found a face contact
 * between them; the bottom course stands on the ground. */
static void wall3d_returns_supported(void) {
  double ts[3] = {0.5, 0.3, 0.7};
  for (int d = 0; d < 3; d++) {
    us_Structure *s = corner_wall(6, 4, 3, ts[d], 1.0, 0.5);
    CHECK(s != NULL);
    int ok = 1;
    for (int i = 0; ok && i < s->nbody; i++) {
      int r = course_of(s, i, 0.5), held = 0;
      double a[6], b[6];
      box_of(s, i, a);
      for (int j = 0; r > 0 && !held && j < s->nbody; j++) {
        if (course_of(s, j, 0.5) != r - 1) continue;
        box_of(s, j, b);
        double over = fmax(0.0, fmin(a[3], b[3]) - fmax(a[0], b[0])) *
                      fmax(0.0, fmin(a[4], b[4]) - fmax(a[1], b[1]));
        held = over > 1e-12 && b[5] == a[2] && count_pair(s, i, j) >= 4;
      }
      ok = r == 0 ? count_pair(s, US_GROUND, i) == 4 : held;
    }
    us_structure_free(s);
    CHECK(ok);
  }
}

/* The body of course r whose box holds the point (x, y) in plan, or -1. */
static int body_at(const us_Structure *s, int r, double h, double x, double y) {
  for (int i = 0; i < s->nbody; i++) {
    double a[6];
    box_of(s, i, a);
    if (course_of(s, i, h) == r && a[0] < x && x < a[3] && a[1] < y && y < a[4]) return i;
  }
  return -1;
}

/* The bond at both corners in every course: the brick over the corner
 * square belongs to the main wall in courses 1, 3, ... (0-based even) and
 * to the return in the others, is a full brick running through to the
 * other wall's outer face, touches the other wall's first brick of its
 * course on a face, and the corner bricks of consecutive courses rest on
 * one another. */
static int corner_bonded(const us_Structure *s, int R, int C, double t, double w, double h) {
  int ok = 1;
  for (int side = 0; side < 2; side++) {
    double cx = side ? C * w - 0.5 * t : 0.5 * t;
    int prev = -1;
    for (int r = 0; ok && r < R; r++) {
      int i = body_at(s, r, h, cx, 0.5 * t), other = 0;
      double a[6];
      ok = i >= 0;
      if (!ok) break;
      box_of(s, i, a);
      int ret = in_return(a, t);
      ok = ret == (r % 2 == 1) && fabs(fmax(a[3] - a[0], a[4] - a[1]) - w) < 1e-12 &&
           (side ? a[3] == C * w : a[0] == 0.0) && a[1] == 0.0;
      for (int j = 0; ok && j < s->nbody; j++) {
        double b[6];
        box_of(s, j, b);
        int near = side ? b[3] > C * w - w : b[0] < w;
        if (j != i && course_of(s, j, h) == r && near && in_return(b, t) != ret)
          other += count_pair(s, i, j) == 4;
      }
      ok = ok && other == 1 && (prev < 0 || count_pair(s, prev, i) >= 4);
      prev = i;
    }
  }
  return ok;
}

static void wall3d_returns_bond(void) {
  double ts[3] = {0.5, 0.3, 0.7};
  for (int d = 0; d < 3; d++) {
    us_Structure *s = corner_wall(6, 5, 3, ts[d], 1.0, 0.5);
    CHECK(s != NULL);
    int ok = corner_bonded(s, 6, 5, ts[d], 1.0, 0.5);
    us_structure_free(s);
    CHECK(ok);
  }
}

/* The smallest distance between vertical joints of consecutive courses on
 * the outer faces y = 0, x = 0 and x = C w (the faces' own ends are not
 * joints). */
static double min_lap(const us_Structure *s, int C, int L, double w, double h) {
  double lap = INFINITY, cw = C * w, lw = L * w;
  for (int f = 0; f < 3; f++) {
    int ax = f == 0 ? 0 : 1; /* the axis along the face */
    double end = f == 0 ? cw : lw;
    for (int i = 0; i < s->nbody; i++)
      for (int j = 0; j < s->nbody; j++) {
        double a[6], b[6];
        box_of(s, i, a), box_of(s, j, b);
        int on_a = f == 0 ? a[1] == 0.0 : f == 1 ? a[0] == 0.0 : a[3] == cw;
        int on_b = f == 0 ? b[1] == 0.0 : f == 1 ? b[0] == 0.0 : b[3] == cw;
        if (!on_a || !on_b || course_of(s, j, h) != course_of(s, i, h) + 1) continue;
        for (int p = 0; p < 2; p++)
          for (int q = 0; q < 2; q++) {
            double u = a[ax + 3 * p], v = b[ax + 3 * q];
            int joint = u > 1e-9 && u < end - 1e-9 && v > 1e-9 && v < end - 1e-9;
            if (joint) lap = fmin(lap, fabs(u - v));
          }
      }
  }
  return lap;
}

/* Joints are staggered: half a brick when the thickness is half a brick,
 * and never aligned for other thicknesses. */
static void wall3d_returns_staggered(void) {
  double ts[3] = {0.5, 0.3, 0.7}, want[3] = {0.5, 0.5, 0.3};
  for (int d = 0; d < 3; d++) {
    us_Structure *s = corner_wall(5, 5, 3, ts[d], 1.0, 0.5);
    CHECK(s != NULL);
    double lap = min_lap(s, 5, 3, 1.0, 0.5);
    us_structure_free(s);
    CHECK_NEAR(lap, want[d], 1e-12);
  }
}

/* returns = 0 is the straight wall, byte for byte the file the generator
 * wrote before returns existed (tests/data/wall3d_straight.json: 3 x 3,
 * block 0.7 x 0.3, thickness 0.23). */
static void wall3d_returns_zero(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.rows = 3, g.cols = 3, g.width = 0.7, g.height = 0.3, g.thickness = 0.23, g.returns = 0;
  us_Structure *s = us_gen_wall3d(&g, &err);
  CHECK(s != NULL);
  const char *path = "test_gen3d_zero.json";
  us_Status st = us_structure_write(s, path, &err);
  us_structure_free(s);
  CHECK_INT(st, ==, US_OK);
  FILE *a = fopen(path, "rb"), *b = fopen(US_TEST_DATA "/wall3d_straight.json", "rb");
  int same = a && b, ca, cb;
  do {
    ca = a ? fgetc(a) : EOF, cb = b ? fgetc(b) : EOF;
    same &= ca == cb;
  } while (same && ca != EOF);
  if (a) fclose(a);
  if (b) fclose(b);
  remove(path);
  CHECK(same);
}

static void wall3d_returns_bad(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.returns = -1;
  CHECK(us_gen_wall3d(&g, &err) == NULL && err.code == US_ERR_USAGE && strstr(err.msg, "returns"));
  g.returns = 2, g.thickness = 1.0; /* as deep as long */
  CHECK(us_gen_wall3d(&g, &err) == NULL && err.code == US_ERR_USAGE && strstr(err.msg, "thickness"));
  g.thickness = 0.5, g.cols = 1; /* the returns would meet */
  CHECK(us_gen_wall3d(&g, &err) == NULL && err.code == US_ERR_USAGE && strstr(err.msg, "meet"));
  g.cols = 4, g.rows = 0;
  CHECK(us_gen_wall3d(&g, &err) == NULL && err.code == US_ERR_USAGE && strstr(err.msg, "rows"));
  g.rows = 10000, g.returns = 1000; /* 2e7 bricks */
  CHECK(us_gen_wall3d(&g, &err) == NULL && err.code == US_ERR_USAGE && strstr(err.msg, "limit"));
}

/* Fail the k-th allocation for every k until the corner wall is built:
 * each failure is US_ERR_NOMEM (leaks are checked by the harness). */
static void wall3d_returns_oom(void) {
  us_GenSettings g = us_gen_default_settings();
  g.rows = 3, g.cols = 3, g.returns = 2, g.thickness = 0.3;
  int done = 0;
  for (long k = 0; k < 10000 && !done; k++) {
    us_Error err;
    us_error_clear(&err);
    us_alloc_fail_after(k);
    us_Structure *s = us_gen_wall3d(&g, &err);
    us_alloc_fail_after(-1);
    if (s) done = 1, us_structure_free(s);
    else CHECK_INT(err.code, ==, US_ERR_NOMEM);
  }
  CHECK(done);
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
             T(wall3d_returns_count), T(wall3d_returns_tile), T(wall3d_returns_supported),
             T(wall3d_returns_bond), T(wall3d_returns_staggered), T(wall3d_returns_zero),
             T(wall3d_returns_bad), T(wall3d_returns_oom), T(round_trip), T(bad_settings))
