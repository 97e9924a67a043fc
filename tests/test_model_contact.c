/* Tests of contact detection (src/contact) through us_structure_finalize
 * and us_detect_contacts: counts, points and normal directions of the
 * contacts in small scenes, overlap and tolerance rules. Every scene is
 * also checked for generic properties: unit normals, each point on the
 * boundary of both bodies (within tol), the normal pointing from a into b
 * (a step along it leaves a, a step against it leaves b). */
#include "geometry/geometry.h"
#include "model/model.h"
#include "scenes.h"
#include "test.h"

static int add_poly(us_Structure *s, const char *id, int n, const double *xy, us_Error *err) {
  return us_structure_add_body(
      s,
      &(us_BodyDef){
          .id = id, .nvert = n, .xy = xy, .density = 1.0, .friction = -1.0},
      err);
}

/* Contacts between bodies i and j (either order; j may be US_GROUND). */
static int count_pair(const us_Structure *s, int i, int j) {
  int n = 0;
  for (int k = 0; k < s->ncontact; k++) {
    const us_Contact *c = &s->contacts[k];
    n += (c->a == i && c->b == j) || (c->a == j && c->b == i);
  }
  return n;
}

/* Contact between i and j at (x, y), or -1. */
static int find_at(const us_Structure *s, int i, int j, double x, double y) {
  for (int k = 0; k < s->ncontact; k++) {
    const us_Contact *c = &s->contacts[k];
    if (((c->a == i && c->b == j) || (c->a == j && c->b == i)) &&
        hypot(c->p[0] - x, c->p[1] - y) <= 1e-9)
      return k;
  }
  return -1;
}

/* Normal of contact k expressed from i into j. */
static us_Vec2 normal_from(const us_Structure *s, int k, int i) {
  const us_Contact *c = &s->contacts[k];
  double sg = c->a == i ? 1.0 : -1.0;
  return us_v2(sg * c->n[0], sg * c->n[1]);
}

static int inside(const us_Structure *s, int i, us_Vec2 p) {
  if (i == US_GROUND) return p.y < 0;
  const us_Body *b = &s->bodies[i];
  return us_point_polygon_depth(p, b->verts, b->nvert) > 0;
}

/* A body's own size (bounding-box diagonal). */
static double body_size(const us_Structure *s, int i) {
  return us_poly_diameter(s->bodies[i].verts, s->bodies[i].nvert);
}

/* The documented tolerance of contact k: the smaller body's size * 1e-6
 * (the body's own against the ground) unless contact_tol is set. */
static double pair_tol(const us_Structure *s, const us_Contact *c) {
  if (s->contact_tol > 0) return s->contact_tol;
  double sz = body_size(s, c->b);
  if (c->a != US_GROUND) sz = US_MIN(sz, body_size(s, c->a));
  return 1e-6 * sz;
}

/* Generic properties of every contact (see the file comment). */
static int contacts_sane(const us_Structure *s) {
  for (int k = 0; k < s->ncontact; k++) {
    const us_Contact *c = &s->contacts[k];
    double tol = pair_tol(s, c), step = 1e3 * tol;
    us_Vec2 p = us_v2(c->p[0], c->p[1]), n = us_v2(c->n[0], c->n[1]);
    int ok = fabs(us_v2_norm(n) - 1.0) < 1e-12 && c->mu >= 0 && c->b >= 0 && c->a != c->b;
    for (int side = 0; side < 2; side++) {
      int i = side ? c->b : c->a;
      if (i == US_GROUND)
        ok = ok && fabs(p.y) <= tol;
      else
        ok = ok && us_point_boundary_dist(p, s->bodies[i].verts, s->bodies[i].nvert, NULL) <= tol;
    }
    ok = ok && !inside(s, c->a, us_v2_add(p, us_v2_scale(n, step)));
    ok = ok && !inside(s, c->b, us_v2_sub(p, us_v2_scale(n, step)));
    if (!ok) {
      fprintf(stderr, "  contact %d (%d, %d) at (%g, %g) n (%g, %g) fails\n", k, c->a, c->b, p.x,
              p.y, n.x, n.y);
      return 0;
    }
  }
  return 1;
}


static void block_on_ground(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  CHECK(scene_box_corners(s, "b0", 0, 0, 2, 1, &err) == 0);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(s->ncontact, ==, 2);
  CHECK(find_at(s, US_GROUND, 0, 0, 0) >= 0 && find_at(s, US_GROUND, 0, 2, 0) >= 0);
  for (int k = 0; k < s->ncontact; k++) {
    CHECK_INT(s->contacts[k].a, ==, US_GROUND);
    CHECK_NEAR(s->contacts[k].n[1], 1.0, 1e-12);
    CHECK_NEAR(s->contacts[k].mu, 0.5, 0);
  }
  CHECK(contacts_sane(s));
  us_structure_free(s);
}

/* Aligned corners: exactly two contacts between the blocks, vertical. */
static void stacked_aligned(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  CHECK(scene_box_corners(s, "lo", 0, 0, 1, 1, &err) == 0);
  CHECK(scene_box_corners(s, "hi", 0, 1, 1, 2, &err) == 1);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(s->ncontact, ==, 4);
  CHECK_INT(count_pair(s, US_GROUND, 0), ==, 2);
  CHECK_INT(count_pair(s, 0, 1), ==, 2);
  for (int x = 0; x <= 1; x++) {
    int k = find_at(s, 0, 1, x, 1);
    CHECK(k >= 0);
    us_Vec2 n = normal_from(s, k, 0);
    CHECK_NEAR(n.x, 0.0, 1e-12);
    CHECK_NEAR(n.y, 1.0, 1e-12);
  }
  CHECK(contacts_sane(s));
  us_structure_free(s);
}

/* Running bond: a brick over the joint of two bricks. */
static void running_bond(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  CHECK(scene_box_corners(s, "l", 0, 0, 2, 1, &err) == 0);
  CHECK(scene_box_corners(s, "r", 2, 0, 4, 1, &err) == 1);
  CHECK(scene_box_corners(s, "top", 1, 1, 3, 2, &err) == 2);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(count_pair(s, US_GROUND, 0), ==, 2);
  CHECK_INT(count_pair(s, US_GROUND, 1), ==, 2);
  CHECK_INT(count_pair(s, 0, 1), ==, 2);
  CHECK_INT(count_pair(s, 0, 2), ==, 2);
  CHECK_INT(count_pair(s, 1, 2), ==, 2);
  CHECK_INT(s->ncontact, ==, 10);
  CHECK(find_at(s, 0, 2, 1, 1) >= 0 && find_at(s, 0, 2, 2, 1) >= 0);
  CHECK(find_at(s, 1, 2, 2, 1) >= 0 && find_at(s, 1, 2, 3, 1) >= 0);
  for (int k = 0; k < s->ncontact; k++) {
    const us_Contact *c = &s->contacts[k];
    int side = (c->a == 0 && c->b == 1) || (c->a == 1 && c->b == 0);
    CHECK_NEAR(fabs(c->n[side ? 0 : 1]), 1.0, 1e-12);
  }
  CHECK(contacts_sane(s));
  us_structure_free(s);
}

/* Side by side, different heights: horizontal normals from left to right. */
static void side_by_side(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  CHECK(scene_box_corners(s, "a", 0, 0, 1, 1, &err) == 0);
  CHECK(scene_box_corners(s, "b", 1, 0, 2, 2, &err) == 1);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(count_pair(s, 0, 1), ==, 2);
  for (int y = 0; y <= 1; y++) {
    int k = find_at(s, 0, 1, 1, y);
    CHECK(k >= 0);
    us_Vec2 n = normal_from(s, k, 0);
    CHECK_NEAR(n.x, 1.0, 1e-12);
    CHECK_NEAR(n.y, 0.0, 1e-12);
  }
  CHECK(contacts_sane(s));
  us_structure_free(s);
}

/* A slab leaning at 30 degrees, its lower corner on the ground and its
 * underside on the top corner of a block: one point, the slab's normal. */
static void leaning_slab(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double c = sqrt(3.0) / 2, sn = 0.5, len = 4.0, t = 0.2;
  /* underside from (0,0) along (c, sn); the block corner is at distance 2 */
  double bx = 2 * c, by = 2 * sn;
  double slab[8] = {0, 0, len * c, len * sn, len * c - t * sn, len * sn + t * c, -t * sn, t * c};
  CHECK(scene_box_corners(s, "block", bx, 0, bx + 1, by, &err) == 0);
  CHECK(add_poly(s, "slab", 4, slab, &err) == 1);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(count_pair(s, 0, 1), ==, 1);
  int k = find_at(s, 0, 1, bx, by);
  CHECK(k >= 0);
  us_Vec2 n = normal_from(s, k, 1); /* from the slab into the block */
  CHECK_NEAR(n.x, sn, 1e-9);
  CHECK_NEAR(n.y, -c, 1e-9);
  CHECK_INT(count_pair(s, US_GROUND, 1), ==, 1);
  CHECK(contacts_sane(s));
  us_structure_free(s);
}

/* A triangle standing on its apex on a block: one vertical contact. */
static void triangle_apex(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double tri[6] = {1.5, 1, 2.5, 2, 0.5, 2};
  CHECK(scene_box_corners(s, "block", 0, 0, 3, 1, &err) == 0);
  CHECK(add_poly(s, "tri", 3, tri, &err) == 1);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(count_pair(s, 0, 1), ==, 1);
  int k = find_at(s, 0, 1, 1.5, 1);
  CHECK(k >= 0);
  CHECK_INT(s->contacts[k].a, ==, 0);
  CHECK_NEAR(s->contacts[k].n[1], 1.0, 1e-12);
  CHECK(contacts_sane(s));
  us_structure_free(s);
}

/* Does direction n (from body i into body j, at vertex vi of i and vj of
 * j) separate the two corners: i's edges there point against n, j's along? */
static int separates(const us_Structure *s, int i, int vi, int j, int vj, us_Vec2 n) {
  const us_Body *bi = &s->bodies[i], *bj = &s->bodies[j];
  for (int d = -1; d <= 1; d += 2) {
    us_Vec2 ei = us_v2_sub(us_poly_vertex(bi->verts, bi->nvert, vi + d),
                           us_poly_vertex(bi->verts, bi->nvert, vi));
    us_Vec2 ej = us_v2_sub(us_poly_vertex(bj->verts, bj->nvert, vj + d),
                           us_poly_vertex(bj->verts, bj->nvert, vj));
    if (us_v2_dot(ei, n) > 1e-12 || us_v2_dot(ej, n) < -1e-12) return 0;
  }
  return 1;
}

/* A triangle standing on its apex exactly on a block's corner: the
 * documented corner-on-corner rule keeps the edge normals that separate
 * the two corners (the block's top face and the triangle's left face),
 * but not the block's side normal (the triangle's left side slopes into
 * the half-plane beyond that side). */
static void apex_on_corner(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double tri[6] = {3, 1, 3.5, 2, 2.5, 2};
  CHECK(scene_box_corners(s, "block", 0, 0, 3, 1, &err) == 0);
  CHECK(add_poly(s, "tri", 3, tri, &err) == 1);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(count_pair(s, 0, 1), ==, 2);
  int up = 0;
  for (int k = 0; k < s->ncontact; k++) {
    if (s->contacts[k].a == US_GROUND) continue;
    us_Vec2 n = normal_from(s, k, 0);
    CHECK_NEAR(s->contacts[k].p[0], 3.0, 1e-12);
    CHECK_NEAR(s->contacts[k].p[1], 1.0, 1e-12);
    CHECK(separates(s, 0, 2, 1, 0, n)); /* block vertex 2 = (3,1), tri vertex 0 */
    CHECK(fabs(n.x - 1.0) > 1e-9);      /* never the side normal (1, 0) */
    up += fabs(n.y - 1.0) < 1e-12;
  }
  CHECK_INT(up, ==, 1);
  us_structure_free(s);
}

/* A block tilted by a tiny slope on another: its low corner is 0.5 tol
 * deep and its bottom edge is 0.75 tol deep where the lower block ends,
 * but 2.5 tol deep at its far end (beyond the lower block). Still two
 * contacts (its corner on the top face, the lower block's corner on its
 * bottom face), no overlap: the edge is judged only where it lies over
 * the other body's face. */
static void tiny_tilt(void) {
  us_Error err;
  double tol = 1e-4, a = 5e-5; /* slope */
  us_Structure *s = us_structure_new(2);
  s->contact_tol = tol;
  CHECK(scene_box_corners(s, "lo", 0, 0, 1, 1, &err) == 0);
  double y0 = 1 - 0.5 * tol, L = 4.0;
  double hi[8] = {0.5, y0, 0.5 + L, y0 - a * L, 0.5 + L + a, y0 - a * L + 1, 0.5 + a, y0 + 1};
  CHECK(add_poly(s, "hi", 4, hi, &err) == 1);
  s->bodies[1].fixed = 1; /* it overhangs; only the contacts matter */
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(count_pair(s, 0, 1), ==, 2);
  CHECK(find_at(s, 0, 1, 0.5, y0) >= 0);
  CHECK(find_at(s, 0, 1, 1, 1) >= 0);
  us_structure_free(s);
}

/* Corner to corner (diagonal boxes): documented to keep both edge
 * normals at the shared point, each pointing away from the lower box. */
static void corner_to_corner(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  CHECK(scene_box_corners(s, "lo", 0, 0, 1, 1, &err) == 0);
  CHECK(scene_box_corners(s, "hi", 1, 1, 2, 2, &err) == 1);
  s->bodies[1].fixed = 1; /* keep it from needing support */
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(count_pair(s, 0, 1), ==, 2);
  double sum[2] = {0, 0};
  for (int k = 0; k < s->ncontact; k++)
    if (s->contacts[k].a >= 0) {
      us_Vec2 n = normal_from(s, k, 0);
      CHECK_NEAR(s->contacts[k].p[0], 1.0, 1e-12);
      CHECK_NEAR(s->contacts[k].p[1], 1.0, 1e-12);
      sum[0] += n.x;
      sum[1] += n.y;
    }
  CHECK_NEAR(sum[0], 1.0, 1e-12); /* (1,0) and (0,1) */
  CHECK_NEAR(sum[1], 1.0, 1e-12);
  us_structure_free(s);
}

/* A box sitting in the notch of an L (non-convex): two contacts on each
 * face of the notch, none sideways at the reflex corner. */
static void box_in_l_notch(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double L[12] = {0, 0, 2, 0, 2, 2, 1, 2, 1, 1, 0, 1}; /* notch at the top left */
  CHECK(add_poly(s, "L", 6, L, &err) == 0);
  CHECK(scene_box_corners(s, "box", 0, 1, 1, 2, &err) == 1);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(count_pair(s, 0, 1), ==, 4);
  int kf0 = find_at(s, 0, 1, 0, 1), kf1 = find_at(s, 0, 1, 1, 1), kw = find_at(s, 0, 1, 1, 2);
  CHECK(kf0 >= 0 && kf1 >= 0 && kw >= 0);
  CHECK_NEAR(normal_from(s, kf0, 0).y, 1.0, 1e-12);
  CHECK_NEAR(normal_from(s, kw, 0).x, -1.0, 1e-12);
  CHECK(contacts_sane(s));
  us_structure_free(s);
}

/* A block resting inside a U (non-convex): floor contacts only. */
static void block_in_u(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double U[16] = {0, 0, 5, 0, 5, 3, 4, 3, 4, 1, 1, 1, 1, 3, 0, 3};
  CHECK(add_poly(s, "U", 8, U, &err) == 0);
  CHECK(scene_box_corners(s, "in", 2, 1, 3, 2, &err) == 1);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(count_pair(s, 0, 1), ==, 2);
  CHECK(find_at(s, 0, 1, 2, 1) >= 0 && find_at(s, 0, 1, 3, 1) >= 0);
  CHECK_INT(count_pair(s, US_GROUND, 0), ==, 2);
  CHECK(contacts_sane(s));
  us_structure_free(s);
}

/* Friction: the smaller of the two sides, each defaulting to the structure. */
static void friction_rule(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  s->friction = 0.6;
  double a[8] = {0, 0, 1, 0, 1, 1, 0, 1}, b[8] = {0, 1, 1, 1, 1, 2, 0, 2};
  CHECK(us_structure_add_body(
            s,
            &(us_BodyDef){
                .id = "a", .nvert = 4, .xy = a, .density = 1, .friction = 0.3},
            &err) == 0);
  CHECK(us_structure_add_body(
            s,
            &(us_BodyDef){
                .id = "b", .nvert = 4, .xy = b, .density = 1, .friction = 0.9},
            &err) == 1);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  for (int k = 0; k < s->ncontact; k++) CHECK_NEAR(s->contacts[k].mu, 0.3, 0);
  us_structure_free(s);
}

static void fixed_bodies(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double p1[8] = {0, 0, 1, 0, 1, 1, 0, 1}, p2[8] = {1, 0, 2, 0, 2, 1, 1, 1};
  CHECK(scene_polygon(s, "pier1", 4, p1, 1) == 0);
  CHECK(scene_polygon(s, "pier2", 4, p2, 1) == 1);
  CHECK(scene_box_corners(s, "deck", 0.5, 1, 1.5, 1.2, &err) == 2);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(count_pair(s, US_GROUND, 0), ==, 0);
  CHECK_INT(count_pair(s, US_GROUND, 1), ==, 0);
  CHECK_INT(count_pair(s, 0, 1), ==, 0);
  CHECK_INT(count_pair(s, 0, 2), ==, 2);
  CHECK_INT(count_pair(s, 1, 2), ==, 2);
  CHECK_INT(s->ncontact, ==, 4);
  CHECK(contacts_sane(s));
  us_structure_free(s);
}

/* A gap of 0.5 tol is a contact, a gap of 2 tol is not. */
static void tolerance(void) {
  us_Error err;
  double tol = 1e-3;
  for (int far = 0; far <= 1; far++) {
    double gap = far ? 2 * tol : 0.5 * tol;
    us_Structure *s = us_structure_new(2);
    s->contact_tol = tol;
    CHECK(scene_box_corners(s, "lo", 0, gap, 1, 1, &err) == 0);
    CHECK(scene_box_corners(s, "hi", 0.25, 1 + gap, 1.25, 2, &err) == 1);
    CHECK_OK(us_structure_finalize(s, &err), &err);
    CHECK_NEAR(s->contact_tol, tol, 0);
    CHECK_INT(count_pair(s, US_GROUND, 0), ==, far ? 0 : 2);
    CHECK_INT(count_pair(s, 0, 1), ==, far ? 0 : 2);
    if (!far) CHECK(contacts_sane(s));
    us_structure_free(s);
  }
  /* a penetration of 0.5 tol is also a contact, not an overlap */
  us_Structure *s = us_structure_new(2);
  s->contact_tol = tol;
  CHECK(scene_box_corners(s, "lo", 0, 0, 1, 1, &err) == 0);
  CHECK(scene_box_corners(s, "hi", 0.25, 1 - 0.5 * tol, 1.25, 2, &err) == 1);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(count_pair(s, 0, 1), ==, 2);
  us_structure_free(s);
  /* ... and 2 tol is an overlap */
  s = us_structure_new(2);
  s->contact_tol = tol;
  CHECK(scene_box_corners(s, "lo", 0, 0, 1, 1, &err) == 0);
  CHECK(scene_box_corners(s, "hi", 0.25, 1 - 2 * tol, 1.25, 2, &err) == 1);
  CHECK(scene_fails_with(s, "'lo' and 'hi' overlap", NULL));
  us_structure_free(s);
}

/* Overlaps are errors naming both bodies, also when no vertex is inside. */
static void overlaps(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  CHECK(scene_box_corners(s, "a", 0, 0, 2, 1, &err) >= 0);
  CHECK(scene_box_corners(s, "b", 1.5, 0.5, 3, 1.5, &err) >= 0);
  CHECK(scene_fails_with(s, "bodies 'a' and 'b' overlap (vertex 0 of 'b' is 0.5 inside 'a')", NULL));
  us_structure_free(s);

  /* two equal squares, one turned 45 degrees about the same centre */
  s = us_structure_new(2);
  double h = 0.5, r = 0.5 * sqrt(2.0), cx = 2, cy = 2;
  double dia[8] = {cx, cy - r, cx + r, cy, cx, cy + r, cx - r, cy};
  CHECK(scene_box_corners(s, "sq", cx - h, cy - h, cx + h, cy + h, &err) >= 0);
  CHECK(add_poly(s, "diamond", 4, dia, &err) >= 0);
  CHECK(scene_fails_with(s, "bodies 'sq' and 'diamond' overlap", NULL));
  us_structure_free(s);

  /* a plus sign of two bars */
  s = us_structure_new(2);
  CHECK(scene_box_corners(s, "h", 0, 1.9, 4, 2.1, &err) >= 0);
  CHECK(scene_box_corners(s, "v", 1.9, 0, 2.1, 4, &err) >= 0);
  CHECK(scene_fails_with(s, "bodies 'h' and 'v' overlap", NULL));
  us_structure_free(s);

  /* the same square twice */
  s = us_structure_new(2);
  CHECK(scene_box_corners(s, "one", 0, 0, 1, 1, &err) >= 0);
  CHECK(scene_box_corners(s, "two", 0, 0, 1, 1, &err) >= 0);
  CHECK(scene_fails_with(s, "bodies 'one' and 'two' overlap", NULL));
  us_structure_free(s);

  /* a triangle inscribed in a square: its vertices on the square's edges */
  s = us_structure_new(2);
  double tri[6] = {1, 0, 2, 1, 0, 2};
  CHECK(scene_box_corners(s, "sq", 0, 0, 2, 2, &err) >= 0);
  CHECK(add_poly(s, "tri", 3, tri, &err) >= 0);
  CHECK(scene_fails_with(s, "bodies 'sq' and 'tri' overlap", NULL));
  us_structure_free(s);

  /* a block pushed into the arm of a U (non-convex), no vertex of the U
   * inside the block */
  s = us_structure_new(2);
  double U[16] = {0, 0, 5, 0, 5, 3, 4, 3, 4, 1, 1, 1, 1, 3, 0, 3};
  CHECK(add_poly(s, "U", 8, U, &err) >= 0);
  CHECK(scene_box_corners(s, "in", 3.5, 1, 4.5, 2, &err) >= 0);
  CHECK(scene_fails_with(s, "bodies 'U' and 'in' overlap", NULL));
  us_structure_free(s);

  /* a small box entirely inside a big one */
  s = us_structure_new(2);
  CHECK(scene_box_corners(s, "big", 0, 0, 4, 4, &err) >= 0);
  CHECK(scene_box_corners(s, "small", 1, 1, 2, 2, &err) >= 0);
  CHECK(scene_fails_with(s, "bodies 'big' and 'small' overlap", NULL));
  us_structure_free(s);
}

/* Detection is deterministic and idempotent; running it again on a
 * finalized structure gives the same contacts. */
static void deterministic(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  CHECK(scene_box_corners(s, "l", 0, 0, 2, 1, &err) == 0);
  CHECK(scene_box_corners(s, "r", 2, 0, 4, 1, &err) == 1);
  CHECK(scene_box_corners(s, "top", 1, 1, 3, 2, &err) == 2);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  int n = s->ncontact;
  us_Contact *copy = us_malloc((size_t)n * sizeof *copy);
  CHECK(copy);
  memcpy(copy, s->contacts, (size_t)n * sizeof *copy);
  us_ContactSettings cs = {0};
  us_Status st = us_structure_detect_contacts(s, &cs, &err);
  int same =
      st == US_OK && s->ncontact == n && !memcmp(copy, s->contacts, (size_t)n * sizeof *copy);
  us_free(copy);
  us_structure_free(s);
  CHECK(same);
}

/* A semicircular arch of n voussoirs on the ground: two contacts per
 * joint with normals along the arch (tangential), two under each foot. */
static void arch(void) {
  us_Error err;
  int n = 9;
  double r = 3.0, R = 4.0, pi = 3.14159265358979323846;
  us_Structure *s = us_structure_new(2);
  for (int k = 0; k < n; k++) {
    double t0 = pi * k / n, t1 = pi * (k + 1) / n;
    double xy[8] = {R * cos(t0), R * sin(t0), R * cos(t1), R * sin(t1),
                    r * cos(t1), r * sin(t1), r * cos(t0), r * sin(t0)};
    if (k == 0) xy[1] = xy[7] = 0.0; /* flat feet */
    if (k == n - 1) xy[3] = xy[5] = 0.0;
    char id[16];
    snprintf(id, sizeof id, "v%d", k);
    CHECK(add_poly(s, id, 4, xy, &err) == k);
  }
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(s->ncontact, ==, 4 + 2 * (n - 1));
  for (int k = 0; k + 1 < n; k++) {
    CHECK_INT(count_pair(s, k, k + 1), ==, 2);
    double t = pi * (k + 1) / n; /* joint angle: normal from k into k+1 is the tangent */
    for (int c = 0; c < s->ncontact; c++) {
      const us_Contact *ct = &s->contacts[c];
      if (!((ct->a == k && ct->b == k + 1) || (ct->a == k + 1 && ct->b == k))) continue;
      us_Vec2 nn = normal_from(s, c, k);
      CHECK_NEAR(nn.x, -sin(t), 1e-9);
      CHECK_NEAR(nn.y, cos(t), 1e-9);
    }
  }
  CHECK(contacts_sane(s));
  us_structure_free(s);
}

/* Clockwise input: the structure-level call orients it (outward normals
 * are right); detection alone, which only reads, refuses it. */
static void direct_call_clockwise(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double cw[8] = {0, 0, 0, 1, 1, 1, 1, 0};
  CHECK(add_poly(s, "cw", 4, cw, &err) == 0);
  CHECK(scene_box_corners(s, "top", 0, 1, 1, 2, &err) == 1);
  us_ContactSettings cs = {1e-6, 0};
  us_ContactList l = {0};
  CHECK(us_detect_contacts(s, &cs, &l, &err) == US_ERR_INPUT);
  CHECK(strstr(err.msg, "body 'cw'") != NULL);
  CHECK_INT(l.n, ==, 0);
  us_contact_list_free(&l);
  CHECK_OK(us_structure_detect_contacts(s, &cs, &err), &err);
  CHECK_INT(count_pair(s, 0, 1), ==, 2);
  CHECK_NEAR(normal_from(s, find_at(s, 0, 1, 0, 1), 0).y, 1.0, 1e-12);
  us_structure_free(s);
}

/* Random rows of boxes of integer widths 1..3 packed side by side (so
 * joints line up across rows, giving aligned and diagonal corners). The
 * expected count comes from the layout: 2 per bottom box on the ground, 2
 * per neighbours in a row, 2 per pair of boxes in consecutive rows whose
 * x-ranges overlap or touch at a corner (the documented diagonal rule).
 * The count must not change when the scene is mirrored, moved far from
 * the origin, or its bodies are added in reverse order. */
enum { SCENE_ROWS = 6, SCENE_MAX = 12 };
typedef struct Scene {
  int n[SCENE_ROWS];
  double x[SCENE_ROWS][SCENE_MAX + 1]; /* joints of each row */
} Scene;

static void scene_make(Scene *sc, unsigned seed) {
  for (int r = 0; r < SCENE_ROWS; r++) {
    sc->n[r] = 0;
    sc->x[r][0] = (double)(seed % 2);
    while (sc->n[r] < SCENE_MAX && sc->x[r][sc->n[r]] < 10) {
      seed = seed * 1103515245u + 12345u;
      sc->x[r][sc->n[r] + 1] = sc->x[r][sc->n[r]] + 1 + (double)((seed >> 16) % 3);
      sc->n[r]++;
    }
  }
}

static int scene_expect(const Scene *sc) {
  int e = 2 * sc->n[0];
  for (int r = 0; r < SCENE_ROWS; r++) e += 2 * (sc->n[r] - 1);
  for (int r = 0; r + 1 < SCENE_ROWS; r++)
    for (int a = 0; a < sc->n[r]; a++)
      for (int b = 0; b < sc->n[r + 1]; b++) {
        double lo = fmax(sc->x[r][a], sc->x[r + 1][b]);
        double hi = fmin(sc->x[r][a + 1], sc->x[r + 1][b + 1]);
        e += hi >= lo ? 2 : 0;
      }
  return e;
}

/* Build the scene mirrored (sx = -1 or 1), shifted by dx, in forward or
 * reverse order; returns the contact count or -1. */
static int scene_count(const Scene *sc, double sx, double dx, int reverse) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  int total = 0, ok = 1;
  for (int r = 0; r < SCENE_ROWS; r++) total += sc->n[r];
  for (int q = 0; q < total && ok; q++) {
    int k = reverse ? total - 1 - q : q, r = 0;
    while (k >= sc->n[r]) k -= sc->n[r++];
    double x0 = sx * sc->x[r][k] + dx, x1 = sx * sc->x[r][k + 1] + dx;
    char id[32];
    snprintf(id, sizeof id, "r%dk%d", r, k);
    ok = scene_box_corners(s, id, fmin(x0, x1), r, fmax(x0, x1), r + 1, &err) >= 0;
  }
  int n = ok && us_structure_finalize(s, &err) == US_OK && contacts_sane(s) ? s->ncontact : -1;
  if (n < 0) fprintf(stderr, "  scene failed: %s\n", err.msg);
  us_structure_free(s);
  return n;
}

static void random_rows(void) {
  for (unsigned seed = 1; seed <= 12; seed++) {
    Scene sc;
    scene_make(&sc, seed);
    int e = scene_expect(&sc);
    CHECK_INT(scene_count(&sc, 1, 0, 0), ==, e);
    CHECK_INT(scene_count(&sc, -1, 0, 0), ==, e);
    CHECK_INT(scene_count(&sc, 1, 1000, 1), ==, e);
  }
}

/* A running-bond wall of rows x cols bricks (odd rows shifted by half a
 * brick): the expected count from the layout is 2 per bottom brick, 2 per
 * pair of neighbours in a row and 2 per overlapping pair of bricks in
 * consecutive rows. */
static void small_wall(void) {
  us_Error err;
  int rows = 8, cols = 7;
  double w = 2.0, h = 1.0;
  us_Structure *s = us_structure_new(2);
  for (int r = 0; r < rows; r++)
    for (int c = 0; c < cols; c++) {
      char id[32];
      snprintf(id, sizeof id, "b%d_%d", r, c);
      double x0 = c * w + (r % 2) * 0.5 * w;
      CHECK(scene_box_corners(s, id, x0, r * h, x0 + w, (r + 1) * h, &err) >= 0);
    }
  CHECK_OK(us_structure_finalize(s, &err), &err);
  int overl = 0; /* pairs with overlapping x-ranges between rows 0 and 1 */
  for (int a = 0; a < cols; a++)
    for (int b = 0; b < cols; b++) {
      double lo = US_MAX(a * w, b * w + 0.5 * w), hi = US_MIN((a + 1) * w, (b + 1) * w + 0.5 * w);
      overl += hi - lo > 0;
    }
  int expect = 2 * cols + rows * 2 * (cols - 1) + (rows - 1) * 2 * overl;
  CHECK_INT(s->ncontact, ==, expect);
  CHECK(contacts_sane(s));
  us_structure_free(s);
}

/* Fast detection (grid broad phase, side-by-side pairs, sweep fallback)
 * and the every-pair reference agree contact for contact, or give the same
 * error: square walls, a tall column, tilted and mixed sizes, long fixed
 * slabs under them (boxes over many cells), and a pair that overlaps. */
static void fast_detection_matches_reference(void) {
  unsigned long long rng = 11;
  for (int trial = 0; trial < 8; trial++) {
    us_Error err;
    us_Structure *s = us_structure_new(2);
    int n = 0;
    char id[24];
    for (int k = 0; trial == 3 && k < 8; k++) { /* long fixed slabs */
      double slab[8] = {-50, k, 60, k, 60, k + 1, -50, k + 1};
      snprintf(id, sizeof id, "slab%d", k);
      CHECK(us_structure_add_polygon(s, id, 4, slab, 1, 0, 1, -1, &err) >= 0);
    }
    if (trial == 3) {
      for (int k = 0; k < 60; k++) {
        double x = -50 + 1.5 * k, xy[8] = {x, 8, x + 1, 8, x + 1, 9, x, 9};
        snprintf(id, sizeof id, "s%d", n++);
        CHECK(add_poly(s, id, 4, xy, &err) >= 0);
      }
    }
    int cols = trial % 2 ? 3 : 12, rows = trial % 2 ? 30 : 12;
    for (int r = 0; r < rows; r++)
      for (int c = 0; c < cols; c++) {
        double w = trial >= 4 && trial < 7 ? 0.5 + test_rnd(&rng) : 1.0, x = c * 1.0 + (r % 2) * 0.5;
        double y = r * 0.5 + (trial == 3 ? 9 : 0), tilt = trial >= 6 ? 0.05 * test_rnd(&rng) : 0;
        double xy[8] = {x, y, x + US_MIN(w, 1.0), y + tilt, x + US_MIN(w, 1.0), y + 0.5, x, y + 0.5};
        if (trial == 7 && r == 5 && c == 1) xy[0] -= 0.3, xy[6] -= 0.3; /* into its neighbour */
        snprintf(id, sizeof id, "b%d", n++);
        CHECK(add_poly(s, id, 4, xy, &err) >= 0);
      }
    us_Error e1, e2;
    us_Status st = us_model_validate(s, 0, &err);
    if (!st) us_model_measure(s), st = us_model_mass_properties(s, &err);
    CHECK_OK(st, &err);
    us_ContactList a = {0}, b = {0};
    us_ContactSettings fast = {0, 0}, ref = {0, 1};
    us_Status s1 = us_detect_contacts(s, &fast, &a, &e1), s2 = us_detect_contacts(s, &ref, &b, &e2);
    int same = s1 == s2 && a.n == b.n && (s1 != US_OK ? !strcmp(e1.msg, e2.msg) : a.n > rows);
    for (int k = 0; same && k < a.n; k++)
      same = a.c[k].a == b.c[k].a && a.c[k].b == b.c[k].b &&
             !memcmp(a.c[k].p, b.c[k].p, sizeof a.c[k].p) && !memcmp(a.c[k].n, b.c[k].n, sizeof a.c[k].n);
    if (!same) fprintf(stderr, "trial %d: %d/%d contacts, %s / %s\n", trial, a.n, b.n,
                       s1 ? e1.msg : "ok", s2 ? e2.msg : "ok");
    if (trial == 7) CHECK_INT(s1, ==, US_ERR_INPUT);
    us_contact_list_free(&a);
    us_contact_list_free(&b);
    us_structure_free(s);
    CHECK(same);
  }
}

US_TEST_MAIN(T(block_on_ground), T(stacked_aligned), T(running_bond), T(side_by_side),
             T(leaning_slab), T(triangle_apex), T(apex_on_corner), T(tiny_tilt),
             T(corner_to_corner), T(box_in_l_notch), T(block_in_u), T(friction_rule),
             T(fixed_bodies), T(tolerance), T(overlaps), T(deterministic), T(arch),
             T(direct_call_clockwise), T(small_wall), T(random_rows),
             T(fast_detection_matches_reference))
