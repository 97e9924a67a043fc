/* Tests of 3D bodies (geometry/hull3.c, polyhedron.c, model/solid.c and the
 * 3D reader and writer): the convex hull of point sets with duplicate,
 * collinear and coplanar points; mass, centre of mass and inertia tensor
 * against closed forms (box, rotated box, tetrahedron from its vertex
 * formula, a compound L by the parallel-axis theorem) and their invariance
 * under rotation and translation; bad input; write/read round trips;
 * out-of-memory sweeps. */
#include "geometry/geometry3.h"
#include "model/model.h"
#include "test.h"

#define PI 3.14159265358979323846

/* Row-major R = Rz(c) Ry(b) Rx(a), built by hand from the three turns
 * (an independent path from the quaternion code). */
static void euler_matrix(double a, double b, double c, double r[9]) {
  double ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b), cc = cos(c), sc = sin(c);
  double rx[9] = {1, 0, 0, 0, ca, -sa, 0, sa, ca}, ry[9] = {cb, 0, sb, 0, 1, 0, -sb, 0, cb},
         rz[9] = {cc, -sc, 0, sc, cc, 0, 0, 0, 1}, t[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      t[3 * i + j] = 0;
      for (int k = 0; k < 3; k++) t[3 * i + j] += ry[3 * i + k] * rx[3 * k + j];
    }
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      r[3 * i + j] = 0;
      for (int k = 0; k < 3; k++) r[3 * i + j] += rz[3 * i + k] * t[3 * k + j];
    }
}

/* out = R m R^T (3x3 row-major). */
static void rotate_tensor(const double r[9], const double m[9], double out[9]) {
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      out[3 * i + j] = 0;
      for (int k = 0; k < 3; k++)
        for (int l = 0; l < 3; l++) out[3 * i + j] += r[3 * i + k] * m[3 * k + l] * r[3 * j + l];
    }
}

/* Every point within tol inside every face plane; faces planar within tol. */
static int hull_contains(const us_Polyhedron *p, const double *xyz, int n, double tol) {
  for (int f = 0; f < p->nface; f++) {
    us_Vec3 nf = us_face_normal(p, f);
    if (fabs(us_v3_norm(nf) - 1) > 1e-12) return 0;
    for (int i = 0; i < n; i++)
      if (us_v3_dot(nf, us_v3_at(xyz, i)) > p->planes[4 * f + 3] + tol) return 0;
    for (int k = 0; k < us_face_size(p, f); k++)
      if (fabs(us_v3_dot(nf, us_face_vertex(p, f, k)) - p->planes[4 * f + 3]) > tol) return 0;
  }
  return 1;
}

static void hull_box_with_redundant_points(void) {
  double c[3] = {1, 2, 3}, sz[3] = {2, 1, 0.5}, q[4] = {1, 0, 0, 0}, pts[3 * 64];
  us_box_points(c, sz, q, pts);
  int n = 8;
  for (int k = 0; k < 8; k++, n++) memcpy(pts + 3 * n, pts + 3 * k, 3 * sizeof(double)); /* duplicates */
  for (int k = 1; k < 8; k *= 2, n++) /* midpoints of edges from corner 0 */
    for (int d = 0; d < 3; d++) pts[3 * n + d] = 0.5 * (pts[d] + pts[3 * k + d]);
  for (int d = 0; d < 3; d++) pts[3 * n + d] = 0.25 * (pts[d] + pts[3 + d] + pts[6 + d] + pts[9 + d]);
  n++; /* a face centre */
  memcpy(pts + 3 * n, c, sizeof c), n++; /* the centre */
  us_Polyhedron p;
  CHECK_INT(us_hull3(pts, n, 1e-9, &p), ==, US_HULL_OK);
  CHECK_INT(p.nvert, ==, 8);
  CHECK_INT(p.nface, ==, 6);
  CHECK_INT(p.nedge, ==, 12);
  for (int f = 0; f < 6; f++) CHECK_INT(us_face_size(&p, f), ==, 4);
  CHECK_NEAR(p.volume, 1.0, 1e-12);
  int ok = hull_contains(&p, pts, n, 1e-9);
  us_polyhedron_free(&p);
  CHECK(ok);
}

static void hull_random_points(void) {
  unsigned long long rng = 12345;
  for (int trial = 0; trial < 20; trial++) {
    int n = 4 + trial * 13;
    double *pts = malloc((size_t)n * 3 * sizeof(double));
    for (int i = 0; i < 3 * n; i++) pts[i] = 10 * test_rnd(&rng) - 5 + (trial % 2 ? 1e6 : 0);
    us_Polyhedron p;
    us_HullStatus st = us_hull3(pts, n, 1e-6, &p);
    int euler = p.nvert - p.nedge + p.nface, ok = hull_contains(&p, pts, n, 1e-6);
    int outward = 1; /* the centroid is inside every face */
    double vol = 0, m1[3], m2[9];
    us_polyhedron_moments(&p, us_v3_at(pts, 0), &vol, m1, m2);
    us_Vec3 cen = us_v3_add(us_v3_at(pts, 0), us_v3(m1[0] / vol, m1[1] / vol, m1[2] / vol));
    for (int f = 0; f < p.nface; f++)
      outward &= us_v3_dot(us_face_normal(&p, f), cen) < p.planes[4 * f + 3];
    us_polyhedron_free(&p);
    free(pts);
    CHECK_INT(st, ==, US_HULL_OK);
    CHECK_INT(euler, ==, 2);
    CHECK(ok);
    CHECK(outward);
    CHECK(vol > 0 && vol <= 1000 * (1 + 1e-9));
  }
}

static void hull_flat_sets(void) {
  double plane[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0.3, 0.2, 1e-9};
  double line[12] = {0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3.0000000001};
  double same[12] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
  us_Polyhedron p;
  CHECK_INT(us_hull3(plane, 5, 1e-6, &p), ==, US_HULL_FLAT);
  CHECK_INT(us_hull3(line, 4, 1e-6, &p), ==, US_HULL_FLAT);
  CHECK_INT(us_hull3(same, 4, 1e-6, &p), ==, US_HULL_FLAT);
  CHECK_INT(us_hull3(plane, 3, 1e-6, &p), ==, US_HULL_FLAT);
  /* the same plane set, lifted by more than tol: a thin solid */
  plane[14] = 1e-3;
  CHECK_INT(us_hull3(plane, 5, 1e-6, &p), ==, US_HULL_OK);
  us_polyhedron_free(&p);
}

/* Brute-force reference for the hull (independent of hull3.c): the
 * supporting planes through every triple of points (all points within eps
 * below), one per distinct plane, and the vertices: points on three
 * supporting planes of independent normals. */
typedef struct Brute {
  double pl[4 * 500];
  int npl, nvert;
} Brute;

static void brute_hull(const double *x, int n, double eps, Brute *b) {
  b->npl = b->nvert = 0;
  for (int i = 0; i < n; i++)
    for (int j = i + 1; j < n; j++)
      for (int k = j + 1; k < n; k++) {
        us_Vec3 a = us_v3_at(x, i), nn = us_v3_cross(us_v3_sub(us_v3_at(x, j), a), us_v3_sub(us_v3_at(x, k), a));
        if (!(us_v3_norm(nn) > 1e-6)) continue; /* collinear */
        nn = us_v3_unit(nn);
        for (int side = 0; side < 2; side++, nn = us_v3_scale(nn, -1)) {
          double d = us_v3_dot(nn, a);
          int ok = 1, dup = 0;
          for (int m = 0; m < n && ok; m++) ok = us_v3_dot(nn, us_v3_at(x, m)) <= d + eps;
          for (int q = 0; q < b->npl && ok && !dup; q++)
            dup = us_v3_dist(nn, us_v3(b->pl[4 * q], b->pl[4 * q + 1], b->pl[4 * q + 2])) < 1e-9;
          if (ok && !dup && b->npl < 500) {
            double *p = b->pl + 4 * b->npl++;
            p[0] = nn.x, p[1] = nn.y, p[2] = nn.z, p[3] = d;
          }
        }
      }
  for (int i = 0; i < n; i++) { /* a vertex: three independent planes through it */
    us_Vec3 v = us_v3_at(x, i), on[500];
    int m = 0, dup = 0;
    for (int q = 0; q < b->npl; q++)
      if (fabs(us_v3_dot(us_v3(b->pl[4 * q], b->pl[4 * q + 1], b->pl[4 * q + 2]), v) - b->pl[4 * q + 3]) <= eps)
        on[m++] = us_v3(b->pl[4 * q], b->pl[4 * q + 1], b->pl[4 * q + 2]);
    for (int j = 0; j < i; j++) dup |= us_v3_dist(v, us_v3_at(x, j)) == 0;
    int rank3 = 0;
    for (int p = 0; p < m && !rank3; p++)
      for (int q = p + 1; q < m && !rank3; q++)
        for (int r = q + 1; r < m && !rank3; r++)
          rank3 = fabs(us_v3_dot(on[p], us_v3_cross(on[q], on[r]))) > 1e-9;
    b->nvert += rank3 && !dup;
  }
}

/* Does the hull have the reference's planes and vertices? */
static int hull_matches(const us_Polyhedron *p, const Brute *b) {
  if (p->nface != b->npl) return 0;
  for (int f = 0; f < p->nface; f++) {
    int found = 0;
    for (int q = 0; q < b->npl && !found; q++)
      found = us_v3_dist(us_face_normal(p, f), us_v3(b->pl[4 * q], b->pl[4 * q + 1], b->pl[4 * q + 2])) < 1e-9 &&
              fabs(p->planes[4 * f + 3] - b->pl[4 * q + 3]) < 1e-9;
    if (!found) return 0;
  }
  return p->nvert == b->nvert;
}

/* Differential test against the brute force on small random sets: points
 * in general position, and points on a 3x3x3 grid (duplicates, collinear
 * and coplanar points, and flat sets, which both must call flat). */
static void hull_against_brute_force(void) {
  unsigned long long rng = 777;
  static Brute b;
  for (int trial = 0; trial < 120; trial++) {
    int n = 4 + (int)(test_rnd(&rng) * 30), grid = trial % 2;
    double x[3 * 40];
    for (int i = 0; i < 3 * n; i++) x[i] = grid ? floor(3 * test_rnd(&rng)) : 2 * test_rnd(&rng) - 1;
    if (grid && trial % 6 == 1)
      for (int i = 0; i < n; i++) x[3 * i + 2] = 1; /* flat */
    brute_hull(x, n, 1e-9, &b);
    us_Polyhedron p;
    us_HullStatus st = us_hull3(x, n, 1e-9, &p);
    if (b.nvert < 4) {
      CHECK_INT(st, ==, US_HULL_FLAT);
      continue;
    }
    int ok = st == US_HULL_OK && hull_matches(&p, &b);
    if (!ok) printf("  trial %d (n %d, grid %d): status %d, %d faces (%d), %d vertices (%d)\n", trial, n, grid, st,
                    p.nface, b.npl, p.nvert, b.nvert);
    us_polyhedron_free(&p);
    CHECK(ok);
  }
}

/* A deadline already past stops a large hull (checked every 1024 points). */
static void hull_deadline(void) {
  int n = 5000;
  double *x = malloc((size_t)n * 3 * sizeof *x);
  unsigned long long rng = 5;
  for (int i = 0; i < n; i++) {
    double z = 2 * test_rnd(&rng) - 1, t = 2 * PI * test_rnd(&rng), r = sqrt(1 - z * z);
    x[3 * i] = r * cos(t), x[3 * i + 1] = r * sin(t), x[3 * i + 2] = z;
  }
  us_Polyhedron p;
  CHECK_INT(us_hull3_until(x, n, 1e-9, 1e-9, &p), ==, US_HULL_TIMEOUT);
  CHECK_INT(p.nface, ==, 0);
  CHECK_INT(us_hull3_until(x, n, 1e-9, us_now() + 1e6, &p), ==, US_HULL_OK);
  CHECK_INT(p.nvert, ==, n);
  us_polyhedron_free(&p);
  free(x);
}

/* us_structure_finalize_until: a past deadline stops the hull with
 * US_ERR_TIME_LIMIT naming the body; finalizing again without one works. */
static void finalize_deadline(void) {
  int n = 3000;
  double *x = malloc((size_t)n * 3 * sizeof *x);
  unsigned long long rng = 9;
  for (int i = 0; i < n; i++) {
    double z = 2 * test_rnd(&rng) - 1, t = 2 * PI * test_rnd(&rng), r = sqrt(1 - z * z);
    x[3 * i] = r * cos(t), x[3 * i + 1] = r * sin(t), x[3 * i + 2] = z + 5;
  }
  us_Structure *s = us_structure_new(3);
  us_BodyDef d = us_default_body_def();
  us_Error err;
  d.id = "ball", d.nvert = n, d.xyz = x;
  s->ground = 0;
  CHECK_INT(us_structure_add_body(s, &d, &err), ==, 0);
  CHECK_INT(us_structure_finalize_until(s, 1e-9, &err), ==, US_ERR_TIME_LIMIT);
  CHECK(strstr(err.msg, "convex hull of body 'ball'") != NULL);
  CHECK_INT(us_structure_finalize_until(s, us_now() + 1e6, &err), ==, US_OK);
  CHECK(us_structure_is_finalized(s) && s->bodies[0].parts[0].nface > 0);
  us_structure_free(s);
  free(x);
}

/* Extreme sizes get their true reason (issue 24, point 5): a cube of side
 * 1e-100 is accepted (as a 2D square is), 1e101 overflows its inertia,
 * 1e-300 underflows its volume; a huge quaternion is normalized without
 * overflow; zero gravity in 3D suggests a 3D vector. */
static void extreme_sizes(void) {
  static const char *const sides[] = {"1e-100", "1e101", "1e-300"};
  static const char *const want[] = {NULL, "the inertia overflows", "the volume underflows"};
  for (int k = 0; k < 3; k++) {
    char text[256];
    snprintf(text, sizeof text, "{\"dimension\": 3, \"ground\": false, \"bodies\": [{\"id\": \"c\", \"box\": "
             "{\"center\": [0, 0, 0], \"size\": [%s, %s, %s]}}]}", sides[k], sides[k], sides[k]);
    us_Error err;
    us_error_clear(&err);
    us_Structure *s = us_structure_parse(text, "cube", 0, &err);
    if (want[k]) CHECK(!s && strstr(err.msg, want[k]) != NULL);
    else CHECK(s != NULL && s->bodies[0].parts[0].nface == 6);
    us_structure_free(s);
  }
  us_Error err;
  us_Structure *s = us_structure_parse("{\"dimension\": 3, \"bodies\": [{\"id\": \"c\", \"box\": {\"center\": "
                                       "[0, 0, 1], \"size\": [1, 2, 1], \"rotation\": [1e308, 1e308, 0, 0]}}]}",
                                       "q", 0, &err);
  CHECK(s != NULL); /* turned 90 degrees about x: 2 high */
  if (s) CHECK_NEAR(s->bbox3[5] - s->bbox3[2], 2.0, 1e-12);
  us_structure_free(s);
  us_error_clear(&err);
  s = us_structure_parse("{\"dimension\": 3, \"gravity\": [0, 0, 0], \"bodies\": [{\"id\": \"c\", \"box\": "
                         "{\"center\": [0, 0, 0.5], \"size\": [1, 1, 1]}}]}", "g", 0, &err);
  CHECK(!s && strstr(err.msg, "[0, 0, -9.81]") != NULL);
}

/* A structure of one 3D body given by its points (hull taken). */
static us_Structure *one_body(int n, const double *xyz, double density, us_Error *err) {
  us_Structure *s = us_structure_new(3);
  us_BodyDef d = us_default_body_def();
  d.id = "b", d.nvert = n, d.xyz = xyz, d.density = density;
  s->ground = 0;
  if (us_structure_add_body(s, &d, err) < 0 || us_structure_finalize(s, err)) {
    us_structure_free(s);
    return NULL;
  }
  return s;
}

/* Inertia of a solid box about its centre in its own axes. */
static void box_inertia(double m, const double sz[3], double out[9]) {
  memset(out, 0, 9 * sizeof *out);
  out[0] = m * (sz[1] * sz[1] + sz[2] * sz[2]) / 12;
  out[4] = m * (sz[0] * sz[0] + sz[2] * sz[2]) / 12;
  out[8] = m * (sz[0] * sz[0] + sz[1] * sz[1]) / 12;
}

static void mass_box(void) {
  us_Error err;
  double c[3] = {3, -2, 7}, sz[3] = {2, 3, 0.5}, q[4] = {1, 0, 0, 0}, pts[24], ref[9];
  us_box_points(c, sz, q, pts);
  us_Structure *s = one_body(8, pts, 2.5, &err);
  CHECK(s != NULL);
  const us_Body *b = &s->bodies[0];
  double m = b->mass, com[3] = {b->com[0], b->com[1], b->com[2]}, I[9];
  memcpy(I, b->inertia3, sizeof I);
  double inertia = b->inertia;
  us_structure_free(s);
  CHECK_NEAR(m, 2.5 * 3, 1e-12);
  for (int k = 0; k < 3; k++) CHECK_NEAR(com[k], c[k], 1e-12);
  box_inertia(7.5, sz, ref);
  for (int k = 0; k < 9; k++) CHECK_NEAR(I[k], ref[k], 1e-12);
  CHECK_NEAR(inertia, (ref[0] + ref[4] + ref[8]) / 3, 1e-12);
}

static void mass_rotated_box(void) {
  us_Error err;
  double c[3] = {0.5, 1.5, 4}, sz[3] = {1, 2, 3}, deg[3] = {20, -35, 70}, q[4], pts[24], R[9],
         body[9], ref[9];
  us_quat_from_euler(deg, q);
  us_box_points(c, sz, q, pts);
  us_Structure *s = one_body(8, pts, 1.0, &err);
  CHECK(s != NULL);
  double m = s->bodies[0].mass, com[3], I[9];
  memcpy(com, s->bodies[0].com, sizeof com);
  memcpy(I, s->bodies[0].inertia3, sizeof I);
  int nface = s->bodies[0].parts[0].nface;
  us_structure_free(s);
  CHECK_INT(nface, ==, 6);
  CHECK_NEAR(m, 6, 1e-12);
  for (int k = 0; k < 3; k++) CHECK_NEAR(com[k], c[k], 1e-12);
  euler_matrix(deg[0] * PI / 180, deg[1] * PI / 180, deg[2] * PI / 180, R);
  box_inertia(6, sz, body);
  rotate_tensor(R, body, ref);
  for (int k = 0; k < 9; k++) CHECK_NEAR(I[k], ref[k], 1e-12);
}

/* Tetrahedron v0..v3: int x x^T dV = V / 20 (sum v v^T + S S^T), S = sum v
 * (the vertex formula, independent of the face fans). */
static void mass_tetrahedron(void) {
  us_Error err;
  double v[12] = {1, 1, 1, 3, 1.5, 1, 1.2, 4, 1.3, 0.7, 1.1, 3.5};
  us_Structure *s = one_body(4, v, 3.0, &err);
  CHECK(s != NULL);
  us_Body b = s->bodies[0];
  double I[9];
  memcpy(I, b.inertia3, sizeof I);
  us_structure_free(s);
  us_Vec3 a = us_v3_sub(us_v3_at(v, 1), us_v3_at(v, 0)), bb = us_v3_sub(us_v3_at(v, 2), us_v3_at(v, 0)),
          cc = us_v3_sub(us_v3_at(v, 3), us_v3_at(v, 0));
  double vol = fabs(us_v3_dot(a, us_v3_cross(bb, cc))) / 6, S[3] = {0, 0, 0}, C[9] = {0}, com[3];
  for (int k = 0; k < 4; k++)
    for (int i = 0; i < 3; i++) S[i] += v[3 * k + i];
  for (int i = 0; i < 3; i++) com[i] = S[i] / 4;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double sum = S[i] * S[j];
      for (int k = 0; k < 4; k++) sum += v[3 * k + i] * v[3 * k + j];
      C[3 * i + j] = vol / 20 * sum - vol * com[i] * com[j];
    }
  CHECK_NEAR(b.mass, 3 * vol, 1e-12);
  for (int i = 0; i < 3; i++) CHECK_NEAR(b.com[i], com[i], 1e-12);
  double tr = C[0] + C[4] + C[8];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) CHECK_NEAR(I[3 * i + j], 3 * ((i == j) * tr - C[3 * i + j]), 1e-12);
}

/* An L of two boxes, combined by hand with the parallel-axis theorem. */
static void mass_compound_l(void) {
  us_Error err;
  double c1[3] = {0.5, 0.5, 1.5}, s1[3] = {1, 1, 3}, c2[3] = {2, 0.5, 0.5}, s2[3] = {2, 1, 1},
         q[4] = {1, 0, 0, 0}, p1[24], p2[24];
  us_box_points(c1, s1, q, p1);
  us_box_points(c2, s2, q, p2);
  us_PartDef parts[2] = {{8, p1}, {8, p2}};
  us_Structure *s = us_structure_new(3);
  us_BodyDef d = us_default_body_def();
  d.id = "L", d.npart = 2, d.parts = parts, d.density = 2;
  CHECK(us_structure_add_body(s, &d, &err) == 0);
  us_Status st = us_structure_finalize(s, &err);
  us_Body b = s->bodies[0];
  double I[9];
  memcpy(I, b.inertia3, sizeof I);
  int nc = s->ncontact;
  us_structure_free(s);
  CHECK_INT(st, ==, US_OK);
  CHECK_INT(nc, ==, 6); /* on the ground: the two bottoms share an edge */
  double m1 = 2 * 3, m2 = 2 * 2, m = m1 + m2, com[3], ref[9] = {0}, a[9], bx[9];
  for (int k = 0; k < 3; k++) com[k] = (m1 * c1[k] + m2 * c2[k]) / m;
  CHECK_NEAR(b.mass, m, 1e-12);
  for (int k = 0; k < 3; k++) CHECK_NEAR(b.com[k], com[k], 1e-12);
  box_inertia(m1, s1, a);
  box_inertia(m2, s2, bx);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double d1[3] = {c1[0] - com[0], c1[1] - com[1], c1[2] - com[2]};
      double d2[3] = {c2[0] - com[0], c2[1] - com[1], c2[2] - com[2]};
      double n1 = d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2], n2 = d2[0] * d2[0] + d2[1] * d2[1] + d2[2] * d2[2];
      ref[3 * i + j] = a[3 * i + j] + bx[3 * i + j] + m1 * ((i == j) * n1 - d1[i] * d1[j]) +
                       m2 * ((i == j) * n2 - d2[i] * d2[j]);
    }
  for (int k = 0; k < 9; k++) CHECK_NEAR(I[k], ref[k], 1e-12);
}

/* The hull of random points, turned and moved: volume kept, centre moved
 * with it, inertia turned as R I R^T. */
static void mass_invariance(void) {
  unsigned long long rng = 99;
  for (int trial = 0; trial < 10; trial++) {
    double pts[3 * 30], moved[3 * 30], R[9], t[3];
    for (int i = 0; i < 90; i++) pts[i] = test_rnd(&rng) * 2;
    euler_matrix(test_rnd(&rng) * 6, test_rnd(&rng) * 6, test_rnd(&rng) * 6, R);
    for (int k = 0; k < 3; k++) t[k] = 100 * test_rnd(&rng);
    for (int i = 0; i < 30; i++)
      for (int r = 0; r < 3; r++)
        moved[3 * i + r] = t[r] + R[3 * r] * pts[3 * i] + R[3 * r + 1] * pts[3 * i + 1] + R[3 * r + 2] * pts[3 * i + 2];
    us_Error err;
    us_Structure *a = one_body(30, pts, 1, &err), *b = one_body(30, moved, 1, &err);
    int ok = a && b;
    double rot[9], ca[3], ia[9], ib[9];
    if (ok) {
      memcpy(ia, a->bodies[0].inertia3, sizeof ia);
      memcpy(ib, b->bodies[0].inertia3, sizeof ib);
      rotate_tensor(R, ia, rot);
      for (int r = 0; r < 3; r++)
        ca[r] = t[r] + R[3 * r] * a->bodies[0].com[0] + R[3 * r + 1] * a->bodies[0].com[1] +
                R[3 * r + 2] * a->bodies[0].com[2];
      ok = fabs(a->bodies[0].mass - b->bodies[0].mass) < 1e-12;
      for (int k = 0; k < 3; k++) ok &= fabs(ca[k] - b->bodies[0].com[k]) < 1e-10;
      for (int k = 0; k < 9; k++) ok &= fabs(rot[k] - ib[k]) < 1e-10;
      ok &= a->bodies[0].parts[0].nvert == b->bodies[0].parts[0].nvert;
    }
    us_structure_free(a);
    us_structure_free(b);
    CHECK(ok);
  }
}

/* Parse text; NULL and the message in err when rejected. */
static us_Structure *parse(const char *text, us_Error *err) {
  return us_structure_parse(text, "t.json", 0, err);
}

static int rejects(const char *text, const char *fragment) {
  us_Error err;
  us_error_clear(&err);
  us_Structure *s = parse(text, &err);
  if (s) {
    us_structure_free(s);
    fprintf(stderr, "accepted: %s\n", text);
    return 0;
  }
  if (err.code != US_ERR_INPUT || !strstr(err.msg, fragment) || !strstr(err.msg, "t.json")) {
    fprintf(stderr, "message '%s' lacks '%s'\n", err.msg, fragment);
    return 0;
  }
  return 1;
}

#define BOX(id, x, y, z) "{\"id\": \"" id "\", \"box\": {\"center\": [" #x ", " #y ", " #z "], \"size\": [1, 1, 1]}}"

static void reader_errors(void) {
  CHECK(rejects("{\"dimension\": 3, \"bodies\": [{\"id\": \"a\", \"vertices\": [[0,0,0],[1,0,0],[0,1,0]]}]}",
                "needs at least 4 points"));
  CHECK(rejects("{\"dimension\": 3, \"bodies\": [{\"id\": \"f\", \"vertices\": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]]}]}",
                "body 'f': its points lie in one plane"));
  CHECK(rejects("{\"dimension\": 3, \"bodies\": [{\"id\": \"a\", \"vertices\": [[0,0,0],[1,0,0],[0,1,0],[0,0,\"x\"]]}]}",
                "vertices[3]: expected [x, y, z]"));
  CHECK(rejects("{\"dimension\": 3, \"bodies\": [" BOX("a", 0.5, 0.5, 0.5) ", " BOX("b", 1.2, 0.5, 0.5) "]}",
                "bodies 'a' and 'b' overlap"));
  CHECK(rejects("{\"dimension\": 3, \"bodies\": [" BOX("low", 0.5, 0.5, 0.3) "]}",
                "body 'low' is below the ground"));
  CHECK(rejects("{\"dimension\": 3, \"bodies\": [{\"id\": \"c\", \"parts\": [{\"box\": {\"center\": [0.5,0.5,0.5], \"size\": [1,1,1]}}, "
                "{\"vertices\": [[0,0,1],[1,0,1],[0,1,1],[1,1,1]]}]}]}",
                "body 'c': part 1: its points lie in one plane"));
  CHECK(rejects("{\"dimension\": 3, \"bodies\": [{\"id\": \"c\", \"parts\": []}]}", "parts: expected a non-empty array"));
  CHECK(rejects("{\"dimension\": 3, \"bodies\": [{\"id\": \"a\", \"box\": {\"center\": [0,0,1], \"size\": [1,-1,1]}}]}",
                "box.size: must be > 0"));
  CHECK(rejects("{\"dimension\": 3, \"bodies\": [{\"id\": \"a\", \"box\": {\"size\": [1,1,1]}}]}",
                "box: missing field 'center'"));
  CHECK(rejects("{\"dimension\": 3, \"gravity\": [0, 0], \"bodies\": []}", "gravity: expected [x, y, z]"));
  CHECK(rejects("{\"dimension\": 2.5, \"bodies\": []}", "dimension: must be 2 or 3"));
  CHECK(rejects("{\"dimension\": 3, \"bodies\": [{\"id\": \"p\", \"mass\": 1, \"center\": [0, 0, 1]}], \"contacts\": "
                "[{\"a\": \"ground\", \"b\": \"p\", \"point\": [0, 0, 0], \"normal\": [0, 0, 2]}]}",
                "normal: must be a unit vector"));
  /* a sliver: 4 points within 1e-9 of a plane but not within tol of a line */
  CHECK(rejects("{\"dimension\": 3, \"bodies\": [{\"id\": \"s\", \"vertices\": [[0,0,0],[1,0,0],[0,1,0],[0.2,0.2,1e-9]]}]}",
                "its points lie in one plane"));
}

static void reader_defaults_and_rotations(void) {
  us_Error err;
  us_Structure *s = parse("{\"dimension\": 3, \"bodies\": [{\"id\": \"q\", \"box\": {\"center\": [0, 0, 1], \"size\": [1, 2, 2], "
                          "\"rotation\": [0.7071067811865476, 0.7071067811865476, 0, 0]}}, "
                          "{\"id\": \"e\", \"box\": {\"center\": [5, 0, 1], \"size\": [1, 2, 2], \"euler\": [90, 0, 0]}}]}",
                          &err);
  CHECK(s != NULL);
  int dim = s->dim, nc = s->ncontact;
  double g2 = s->gravity[2], d = 0;
  for (int k = 0; k < 8; k++)
    for (int i = 0; i < 3; i++)
      d = fmax(d, fabs(s->bodies[0].parts[0].verts[3 * k + i] + (i == 0 ? 5 : 0) -
                       s->bodies[1].parts[0].verts[3 * k + i]));
  us_structure_free(s);
  CHECK_INT(dim, ==, 3);
  CHECK_NEAR(g2, -9.81, 0);
  CHECK(d < 1e-12); /* a quarter turn about x either way */
  CHECK_INT(nc, ==, 8);
}

/* Write a 3D structure and read it back: the same bodies (hull vertices
 * bit for bit, mass properties) and contacts; the second write is the
 * same text. */
static void write_read_round_trip(void) {
  us_Error err;
  us_Structure *s = parse("{\"dimension\": 3, \"friction\": 0.4, \"bodies\": [" BOX("a", 0.5, 0.5, 0.5) ", "
                          "{\"id\": \"t\", \"box\": {\"center\": [0.6, 0.4, 1.5], \"size\": [1, 1, 1], \"euler\": [0, 0, 33]}, \"density\": 3}, "
                          "{\"id\": \"c\", \"parts\": [{\"box\": {\"center\": [3, 0.5, 0.5], \"size\": [1, 1, 1]}}, "
                          "{\"vertices\": [[3.5,0,0],[5,0,0],[3.5,1,0],[5,1,0],[3.5,0,0.5],[3.5,1,0.5]]}], \"friction\": 0.2}]}",
                          &err);
  CHECK(s != NULL);
  const char *p1 = "test_model3d_rt1.json", *p2 = "test_model3d_rt2.json";
  us_Status st = us_structure_write(s, p1, &err);
  us_Structure *b = st ? NULL : us_structure_read(p1, 0, &err);
  int same = b && b->nbody == s->nbody && b->ncontact == s->ncontact && b->dim == 3;
  for (int i = 0; same && i < s->nbody; i++) {
    const us_Body *x = &s->bodies[i], *y = &b->bodies[i];
    same = x->npart == y->npart && x->mass == y->mass && !memcmp(x->com, y->com, sizeof x->com) &&
           !memcmp(x->inertia3, y->inertia3, sizeof x->inertia3) && x->friction == y->friction;
    for (int k = 0; same && k < x->npart; k++)
      same = x->parts[k].nvert == y->parts[k].nvert &&
             !memcmp(x->parts[k].verts, y->parts[k].verts, 3 * sizeof(double) * (size_t)x->parts[k].nvert);
  }
  for (int k = 0; same && k < s->ncontact; k++)
    same = !memcmp(s->contacts[k].p, b->contacts[k].p, sizeof s->contacts[k].p) &&
           !memcmp(s->contacts[k].n, b->contacts[k].n, sizeof s->contacts[k].n) &&
           s->contacts[k].mu == b->contacts[k].mu;
  us_Status st2 = b ? us_structure_write(b, p2, &err) : US_ERR_IO;
  FILE *f1 = fopen(p1, "rb"), *f2 = fopen(p2, "rb");
  char t1[8192] = {0}, t2[8192] = {0};
  size_t n1 = f1 ? fread(t1, 1, sizeof t1 - 1, f1) : 0, n2 = f2 ? fread(t2, 1, sizeof t2 - 1, f2) : 0;
  if (f1) fclose(f1);
  if (f2) fclose(f2);
  remove(p1), remove(p2);
  us_structure_free(s);
  us_structure_free(b);
  CHECK_INT(st, ==, US_OK);
  CHECK_INT(st2, ==, US_OK);
  CHECK(same);
  CHECK(n1 > 0 && n1 == n2 && !memcmp(t1, t2, n1));
  CHECK(strstr(t1, "\"dimension\": 3") && strstr(t1, "\"parts\""));
}

/* Explicit contacts in 3D: point bodies, unit normals, orthonormal
 * tangent frames with t1 x t2 = n. */
static void explicit_contacts(void) {
  us_Error err;
  us_Structure *s = parse("{\"dimension\": 3, \"bodies\": [{\"id\": \"p\", \"mass\": 2, \"center\": [0, 0, 1]}], \"contacts\": ["
                          "{\"a\": \"ground\", \"b\": \"p\", \"point\": [1, 0, 0], \"normal\": [0, 0, 1]},"
                          "{\"a\": \"ground\", \"b\": \"p\", \"point\": [-1, 1, 0], \"normal\": [0.6, 0, 0.8], \"friction\": 0.1}]}",
                          &err);
  CHECK(s != NULL);
  int ok = s->ncontact == 2 && s->explicit_contacts && s->contacts[1].mu == 0.1;
  for (int k = 0; ok && k < 2; k++) {
    const us_Contact *c = &s->contacts[k];
    us_Vec3 n = us_v3(c->n[0], c->n[1], c->n[2]), t1 = us_v3(c->t[0][0], c->t[0][1], c->t[0][2]),
            t2 = us_v3(c->t[1][0], c->t[1][1], c->t[1][2]);
    ok = fabs(us_v3_norm(t1) - 1) < 1e-12 && fabs(us_v3_dot(t1, n)) < 1e-12 &&
         us_v3_dist(us_v3_cross(t1, t2), n) < 1e-12;
  }
  ok = ok && s->bodies[0].inertia3[0][0] > 0 && s->bodies[0].com[2] == 1;
  us_structure_free(s);
  CHECK(ok);
}

/* Every allocation failure while reading and finalizing a 3D structure
 * is US_ERR_NOMEM and leaks nothing. */
static void out_of_memory_sweep(void) {
  const char *text = "{\"dimension\": 3, \"bodies\": [" BOX("a", 0.5, 0.5, 0.5) ", "
                     "{\"id\": \"c\", \"parts\": [{\"box\": {\"center\": [0.5, 0.5, 1.5], \"size\": [1, 1, 1]}}, "
                     "{\"box\": {\"center\": [1.5, 0.5, 1.5], \"size\": [1, 1, 1], \"euler\": [0, 0, 0]}}]}]}";
  int done = 0;
  for (long n = 0; n < 5000 && !done; n++) {
    us_Error err;
    us_error_clear(&err);
    long live = us_alloc_live();
    us_alloc_fail_after(n);
    us_Structure *s = parse(text, &err);
    us_alloc_fail_after(-1);
    if (s) done = 1;
    else CHECK_INT(err.code, ==, US_ERR_NOMEM);
    us_structure_free(s);
    CHECK_INT(us_alloc_live(), ==, live);
  }
  CHECK(done);
}

US_TEST_MAIN(T(hull_box_with_redundant_points), T(hull_random_points), T(hull_flat_sets), T(hull_against_brute_force), T(hull_deadline), T(finalize_deadline), T(extreme_sizes), T(mass_box),
             T(mass_rotated_box), T(mass_tetrahedron), T(mass_compound_l), T(mass_invariance),
             T(reader_errors), T(reader_defaults_and_rotations), T(write_read_round_trip),
             T(explicit_contacts), T(out_of_memory_sweep))
