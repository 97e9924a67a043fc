/* Tests of 3D contact detection (src/contact/detect3.c): patches of face
 * on face (a rectangle of an offset box, the octagon of a box turned 45
 * degrees), edge on face, vertex on face, edge across edge, the ground,
 * separated and overlapping bodies, the tolerance rule, the broad phase
 * against the every-pair reference, and 2D structures extruded into
 * prisms, whose contacts must be the 2D contacts at both ends. Every
 * scene is also checked for generic properties: unit normals, every point
 * on the boundary of both bodies (within tol), no part of b behind the
 * contact plane and no part of a in front of it near the point. */
#include "geometry/geometry3.h"
#include "model/model.h"
#include "test.h"

#include <math.h>

static int add_points(us_Structure *s, const char *id, int n, const double *xyz, us_Error *err) {
  us_BodyDef d = us_default_body_def();
  d.id = id, d.nvert = n, d.xyz = xyz;
  return us_structure_add_body(s, &d, err);
}

static int add_box(us_Structure *s, const char *id, const double c[3], const double sz[3],
                   double turn_z, us_Error *err) {
  double deg[3] = {0, 0, turn_z}, q[4], p[24];
  us_quat_from_euler(deg, q);
  us_box_points(c, sz, q, p);
  return add_points(s, id, 8, p, err);
}

/* Signed distance of x from body i's surface: > 0 outside (the largest
 * plane excess over its parts, minimized over parts). */
static double outside(const us_Structure *s, int i, us_Vec3 x) {
  if (i == US_GROUND) return x.z;
  double best = INFINITY;
  for (int k = 0; k < s->bodies[i].npart; k++) {
    const us_Polyhedron *p = &s->bodies[i].parts[k];
    double e = -INFINITY;
    for (int f = 0; f < p->nface; f++) e = fmax(e, us_v3_dot(us_face_normal(p, f), x) - p->planes[4 * f + 3]);
    best = fmin(best, e);
  }
  return best;
}

static double body_tol(const us_Structure *s, const us_Contact *c) {
  double t = 1e-6 * us_body_diameter(&s->bodies[c->b]);
  return c->a == US_GROUND ? t : fmin(t, 1e-6 * us_body_diameter(&s->bodies[c->a]));
}

/* Generic properties of every contact (file comment). */
static int contacts_sane(const us_Structure *s) {
  for (int k = 0; k < s->ncontact; k++) {
    const us_Contact *c = &s->contacts[k];
    us_Vec3 p = us_v3(c->p[0], c->p[1], c->p[2]), n = us_v3(c->n[0], c->n[1], c->n[2]);
    double tol = body_tol(s, c), step = 1e3 * tol;
    int ok = fabs(us_v3_norm(n) - 1) < 1e-12 && c->mu >= 0 && c->b >= 0 && c->a != c->b;
    ok = ok && fabs(outside(s, c->b, p)) <= tol && (c->a == US_GROUND || fabs(outside(s, c->a, p)) <= tol);
    /* a step along n leaves a, a step against it leaves b */
    ok = ok && outside(s, c->a, us_v3_add(p, us_v3_scale(n, step))) > tol;
    ok = ok && outside(s, c->b, us_v3_sub(p, us_v3_scale(n, step))) > tol;
    if (!ok) {
      fprintf(stderr, "contact %d (%d, %d) at (%g, %g, %g) n (%g, %g, %g) not sane\n", k, c->a, c->b,
              p.x, p.y, p.z, n.x, n.y, n.z);
      return 0;
    }
  }
  return 1;
}

static int count_pair(const us_Structure *s, int i, int j) {
  int n = 0;
  for (int k = 0; k < s->ncontact; k++)
    n += (s->contacts[k].a == i && s->contacts[k].b == j) || (s->contacts[k].a == j && s->contacts[k].b == i);
  return n;
}

/* Contact of the pair (either order) at x, normal from i into j = nn. */
static int has(const us_Structure *s, int i, int j, us_Vec3 x, us_Vec3 nn) {
  for (int k = 0; k < s->ncontact; k++) {
    const us_Contact *c = &s->contacts[k];
    double sg = c->a == i && c->b == j ? 1 : c->a == j && c->b == i ? -1 : 0;
    if (sg != 0 && us_v3_dist(us_v3(c->p[0], c->p[1], c->p[2]), x) < 1e-9 &&
        us_v3_dist(us_v3_scale(us_v3(c->n[0], c->n[1], c->n[2]), sg), nn) < 1e-9)
      return 1;
  }
  return 0;
}

static const double UNIT[3] = {1, 1, 1};

static void box_on_box_offset(void) {
  us_Error err;
  us_Structure *s = us_structure_new(3);
  double c0[3] = {0.5, 0.5, 0.5}, c1[3] = {0.8, 0.1, 1.5};
  add_box(s, "low", c0, UNIT, 0, &err);
  add_box(s, "high", c1, UNIT, 0, &err);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  us_Vec3 up = us_v3(0, 0, 1);
  int n01 = count_pair(s, 0, 1), ng = count_pair(s, US_GROUND, 0) + count_pair(s, US_GROUND, 1);
  int corners = has(s, 0, 1, us_v3(0.3, 0, 1), up) && has(s, 0, 1, us_v3(1, 0, 1), up) &&
                has(s, 0, 1, us_v3(1, 0.6, 1), up) && has(s, 0, 1, us_v3(0.3, 0.6, 1), up);
  int ground = has(s, US_GROUND, 0, us_v3(0, 1, 0), up) && has(s, US_GROUND, 0, us_v3(1, 0, 0), up);
  int sane = contacts_sane(s);
  us_structure_free(s);
  CHECK_INT(n01, ==, 4);
  CHECK_INT(ng, ==, 4);
  CHECK(corners);
  CHECK(ground);
  CHECK(sane);
}

/* A square turned 45 degrees on an equal square: an octagon whose corners
 * are where the two outlines cross. */
static void turned_box_octagon(void) {
  us_Error err;
  us_Structure *s = us_structure_new(3);
  double c0[3] = {0, 0, 0.5}, c1[3] = {0, 0, 1.5};
  add_box(s, "low", c0, UNIT, 0, &err);
  add_box(s, "high", c1, UNIT, 45, &err);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  int n = count_pair(s, 0, 1), on_outlines = 1;
  double e = sqrt(2.0) - 1; /* crossings at (+-0.5, +-(sqrt2 - 1)/2) and swapped */
  for (int k = 0; k < s->ncontact; k++) {
    const us_Contact *c = &s->contacts[k];
    if (c->a != 0) continue;
    double x = fabs(c->p[0]), y = fabs(c->p[1]);
    on_outlines &= fabs(c->p[2] - 1) < 1e-12 && fabs(x + y - sqrt(0.5)) < 1e-9 &&
                   (fabs(x - 0.5) < 1e-9 || fabs(y - 0.5) < 1e-9) && fabs(fmin(x, y) - e / 2) < 1e-9;
  }
  int sane = contacts_sane(s);
  us_structure_free(s);
  CHECK_INT(n, ==, 8);
  CHECK(on_outlines);
  CHECK(sane);
}

/* A triangular prism lying on a box: edge down (2 points at its ends),
 * and a tetrahedron standing on a vertex (1 point). */
static void edge_and_vertex_on_face(void) {
  us_Error err;
  us_Structure *s = us_structure_new(3);
  double c0[3] = {0, 0, 0.5}, big[3] = {4, 4, 1};
  double prism[18] = {-1, -0.2, 1, -1, 0.2, 1.6, -1, -0.3, 1.5, 0.5, -0.2, 1, 0.5, 0.2, 1.6, 0.5, -0.3, 1.5};
  double tet[12] = {1.2, 1, 1, 1.7, 1.1, 1.5, 1.1, 1.6, 1.4, 0.9, 0.8, 1.6};
  add_box(s, "slab", c0, big, 0, &err);
  add_points(s, "prism", 6, prism, &err);
  add_points(s, "tet", 4, tet, &err);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  us_Vec3 up = us_v3(0, 0, 1);
  int np = count_pair(s, 0, 1), nt = count_pair(s, 0, 2);
  int ends = has(s, 0, 1, us_v3(-1, -0.2, 1), up) && has(s, 0, 1, us_v3(0.5, -0.2, 1), up);
  int apex = has(s, 0, 2, us_v3(1.2, 1, 1), up);
  int sane = contacts_sane(s);
  us_structure_free(s);
  CHECK_INT(np, ==, 2);
  CHECK_INT(nt, ==, 1);
  CHECK(ends);
  CHECK(apex);
  CHECK(sane);
}

/* Two ridges crossing: a roof along x, an upside-down roof along y on it. */
static void edge_across_edge(void) {
  us_Error err;
  us_Structure *s = us_structure_new(3);
  double low[18] = {-1, -0.5, 0, -1, 0.5, 0, -1, 0, 1, 1, -0.5, 0, 1, 0.5, 0, 1, 0, 1};
  double high[18] = {-0.5, -1, 2, 0.5, -1, 2, 0, -1, 1, -0.5, 1, 2, 0.5, 1, 2, 0, 1, 1};
  double c2[3] = {0, 0, 2.5}, top[3] = {3, 3, 1};
  add_points(s, "low", 6, low, &err);
  add_points(s, "high", 6, high, &err);
  add_box(s, "lid", c2, top, 0, &err);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  int n = count_pair(s, 0, 1), x = has(s, 0, 1, us_v3(0, 0, 1), us_v3(0, 0, 1));
  int sane = contacts_sane(s);
  us_structure_free(s);
  CHECK_INT(n, ==, 1);
  CHECK(x);
  CHECK(sane);
}

static void separated_and_tolerance(void) {
  us_Error err;
  double gaps[4] = {1e-3, 1e-5, 1e-6, 0}, want[4] = {0, 0, 4, 4}; /* tol = 1e-6 * sqrt(3) */
  for (int k = 0; k < 4; k++) {
    us_Structure *s = us_structure_new(3);
    double c0[3] = {0.5, 0.5, 0.5}, c1[3] = {0.5, 0.5, 1.5 + gaps[k]};
    add_box(s, "a", c0, UNIT, 0, &err);
    add_box(s, "b", c1, UNIT, 0, &err);
    CHECK_OK(us_structure_finalize(s, &err), &err);
    int n = count_pair(s, 0, 1);
    us_structure_free(s);
    CHECK_INT(n, ==, want[k]);
  }
  /* side by side with a gap: nothing between them */
  us_Structure *s = us_structure_new(3);
  double c0[3] = {0.5, 0.5, 0.5}, c1[3] = {1.51, 0.5, 0.5};
  add_box(s, "a", c0, UNIT, 0, &err);
  add_box(s, "b", c1, UNIT, 0, &err);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  int n = count_pair(s, 0, 1);
  us_structure_free(s);
  CHECK_INT(n, ==, 0);
}

static void overlap_names_both(void) {
  us_Error err;
  us_Structure *s = us_structure_new(3);
  double c0[3] = {0.5, 0.5, 0.5}, c1[3] = {0.5, 0.9, 1.2};
  add_box(s, "left", c0, UNIT, 0, &err);
  add_box(s, "right", c1, UNIT, 30, &err);
  us_Status st = us_structure_finalize(s, &err);
  us_structure_free(s);
  CHECK_INT(st, ==, US_ERR_INPUT);
  CHECK(strstr(err.msg, "'left'") && strstr(err.msg, "'right'") && strstr(err.msg, "overlap"));
}

/* Boxes side by side edge to edge (diagonal in the x-z plane): both face
 * directions are admissible normals, as for 2D corner on corner. */
static void diagonal_edge_contact(void) {
  us_Error err;
  us_Structure *s = us_structure_new(3);
  double c0[3] = {0.5, 0.5, 0.5}, c1[3] = {1.5, 0.5, 1.5};
  add_box(s, "a", c0, UNIT, 0, &err);
  add_box(s, "b", c1, UNIT, 0, &err);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  int n = count_pair(s, 0, 1);
  int both = has(s, 0, 1, us_v3(1, 0, 1), us_v3(1, 0, 0)) && has(s, 0, 1, us_v3(1, 1, 1), us_v3(0, 0, 1));
  us_structure_free(s);
  CHECK_INT(n, ==, 4);
  CHECK(both);
}

/* Extrude every (convex) polygon of a 2D structure along y into a prism
 * of the given depth: 2D (x, y) -> 3D (x, y', z = y). */
static us_Structure *extrude(const us_Structure *s2, double depth, us_Error *err) {
  us_Structure *s = us_structure_new(3);
  s->friction = s2->friction;
  for (int i = 0; i < s2->nbody; i++) {
    const us_Body *b = &s2->bodies[i];
    double *p = malloc((size_t)b->nvert * 6 * sizeof(double));
    for (int k = 0; k < b->nvert; k++)
      for (int e = 0; e < 2; e++) {
        p[3 * (2 * k + e)] = b->verts[2 * k];
        p[3 * (2 * k + e) + 1] = e * depth;
        p[3 * (2 * k + e) + 2] = b->verts[2 * k + 1];
      }
    us_BodyDef d = us_default_body_def();
    d.id = b->id, d.nvert = 2 * b->nvert, d.xyz = p, d.fixed = b->fixed;
    int r = us_structure_add_body(s, &d, err);
    free(p);
    if (r < 0) break;
  }
  if (us_structure_finalize(s, err)) {
    us_structure_free(s);
    return NULL;
  }
  return s;
}

/* Every 2D contact appears at y = 0 and y = depth with the same normal
 * (either orientation of the pair), and there are no others. */
static int extrusion_matches(const us_Structure *s2, const us_Structure *s3, double depth) {
  if (s3->ncontact != 2 * s2->ncontact) {
    fprintf(stderr, "3D %d contacts, 2D %d\n", s3->ncontact, s2->ncontact);
    return 0;
  }
  for (int k = 0; k < s2->ncontact; k++) {
    const us_Contact *c = &s2->contacts[k];
    us_Vec3 n = us_v3(c->n[0], 0, c->n[1]);
    for (int e = 0; e < 2; e++)
      if (!has(s3, c->a, c->b, us_v3(c->p[0], e * depth, c->p[1]), n)) {
        fprintf(stderr, "2D contact %d (%d, %d) at (%g, %g) missing at y = %g\n", k, c->a, c->b, c->p[0],
                c->p[1], e * depth);
        return 0;
      }
  }
  return 1;
}

static void extruded_2d_structures(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  for (int kind = 0; kind < 4; kind++) {
    g.n = 7, g.rows = 5, g.cols = 4;
    us_Structure *s2 = kind == 0 ? us_gen_column(&g, &err)
                       : kind == 1 ? us_gen_pyramid(&g, &err)
                       : kind == 2 ? us_gen_wall(&g, &err)
                                   : us_gen_arch(&g, &err);
    CHECK(s2 != NULL);
    us_Structure *s3 = extrude(s2, 0.75, &err);
    int ok = s3 && extrusion_matches(s2, s3, 0.75) && contacts_sane(s3);
    us_structure_free(s2);
    us_structure_free(s3);
    CHECK(ok);
  }
}

/* The broad phase finds the pairs the every-pair reference finds: the
 * same contact lists on towers with turned boxes and random piles. */
static void broadphase_matches_reference(void) {
  unsigned long long rng = 7;
  for (int trial = 0; trial < 6; trial++) {
    us_Error err;
    us_Structure *s = us_structure_new(3);
    for (int i = 0; i < 40; i++) { /* a grid of towers of 2 boxes, some turned */
      char id[16];
      snprintf(id, sizeof id, "b%d", i);
      double c[3] = {1.5 * (i % 5) + 0.5 * (i / 20), 1.5 * ((i / 5) % 4), 0.5 + (i / 20)};
      double sz[3] = {1 + 0.3 * test_rnd(&rng), 1, 1};
      add_box(s, id, c, sz, 40 * test_rnd(&rng) * (trial % 2), &err);
    }
    CHECK_OK(us_structure_finalize(s, &err), &err);
    us_ContactList a = {0}, b = {0};
    us_ContactSettings fast = {0, 0}, ref = {0, 1};
    us_Status s1 = us_detect_contacts(s, &fast, &a, &err), s2 = us_detect_contacts(s, &ref, &b, &err);
    int same = s1 == US_OK && s2 == US_OK && a.n == b.n && a.n == s->ncontact && a.n > 40;
    for (int k = 0; same && k < a.n; k++)
      same = a.c[k].a == b.c[k].a && a.c[k].b == b.c[k].b && !memcmp(a.c[k].p, b.c[k].p, sizeof a.c[k].p);
    int sane = contacts_sane(s);
    us_contact_list_free(&a);
    us_contact_list_free(&b);
    us_structure_free(s);
    CHECK(same);
    CHECK(sane);
  }
}

/* Tolerances follow the pair: a block far away changes nothing, and the
 * structure scaled by 1e-4 or 1e5 has the same contacts scaled. */
static void tolerance_follows_the_pair(void) {
  double scales[3] = {1, 1e-4, 1e5};
  int counts[3];
  for (int k = 0; k < 3; k++) {
    us_Error err;
    us_Structure *s = us_structure_new(3);
    double f = scales[k], c0[3] = {0.5 * f, 0.5 * f, 0.5 * f}, c1[3] = {0.8 * f, 0.1 * f, (1.5 + 1e-7) * f},
           sz[3] = {f, f, f}, far[3] = {1e4, 1e4, 5e3}, fsz[3] = {1e4, 1e4, 1e4};
    add_box(s, "a", c0, sz, 0, &err);
    add_box(s, "b", c1, sz, 0, &err);
    if (k == 0) add_box(s, "far", far, fsz, 0, &err);
    CHECK_OK(us_structure_finalize(s, &err), &err);
    counts[k] = count_pair(s, 0, 1);
    us_structure_free(s);
  }
  CHECK_INT(counts[0], ==, 4);
  CHECK_INT(counts[1], ==, 4);
  CHECK_INT(counts[2], ==, 4);
}

/* Boxes turned about the vertical by arbitrary angles keep exactly level
 * tops and bottoms (their corners share z exactly), so every contact
 * between them and with the ground has a normal with exactly zero
 * horizontal part: with mu = 0, a tilt of 1e-17 was a slope that the LP
 * turned into slides at 1e18 speed (tests/test_stability_local3d.c). */
static void level_faces_exact(void) {
  for (unsigned long seed = 1; seed <= 40; seed++) {
    us_GenSettings g = us_gen_default_settings();
    g.n = 10, g.jitter = 20.0 + (double)seed, g.seed = seed, g.friction = 0.0;
    us_Error err;
    us_Structure *s = us_gen_tower(&g, &err);
    CHECK(s);
    if (!s) continue;
    int level = 0;
    for (int c = 0; c < s->ncontact; c++) {
      const us_Contact *k = &s->contacts[c];
      CHECK(k->n[0] == 0.0 && k->n[1] == 0.0 && fabs(k->n[2]) == 1.0);
      level += k->n[2] == 1.0;
    }
    CHECK_INT(level, ==, s->ncontact);
    us_structure_free(s);
  }
}

US_TEST_MAIN(T(level_faces_exact), T(box_on_box_offset), T(turned_box_octagon), T(edge_and_vertex_on_face), T(edge_across_edge),
             T(separated_and_tolerance), T(overlap_names_both), T(diagonal_edge_contact),
             T(extruded_2d_structures), T(broadphase_matches_reference), T(tolerance_follows_the_pair))
