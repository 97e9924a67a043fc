/* Tests of the 3D statics with circular Coulomb cones (cone.c and the
 * refinement in stability.c), on point bodies with explicit contacts:
 *   - a block on a tilted plank stands iff tan(angle) <= mu, decided to
 *     1e-6 of the critical friction for random slopes and frames;
 *   - cases where an 8-sided inscribed or circumscribed pyramid gives the
 *     wrong answer (the needed friction direction halfway between the
 *     pyramid's edges) are decided by the circular cone;
 *   - every stable verdict's forces pass the certificate check of the true
 *     cone; lp (CLP) and lpsolve agree on random 3D stacks;
 *   - the planner plans a 3D tower top-down; the LCP methods refuse 3D. */
#include "stability/backend.h"
#include "stability/lp_gen.h"
#include "stability/stability.h"
#include "extrude.h"
#include "test.h"

#include <math.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

/* A point block resting on a plane through the origin with slope `alpha`
 * (radians) descending along azimuth phi: four contacts at the corners of
 * a unit square on the plane, the centre of mass h above its middle. */
static us_Structure *plank(double alpha, double phi, double mu, double h) {
  us_Structure *s = us_structure_new(3);
  us_Error err;
  s->gravity[0] = s->gravity[1] = 0.0, s->gravity[2] = -9.81;
  double n[3] = {sin(alpha) * cos(phi), sin(alpha) * sin(phi), cos(alpha)};
  double u[3] = {cos(alpha) * cos(phi), cos(alpha) * sin(phi), -sin(alpha)}; /* downhill */
  double v[3] = {-sin(phi), cos(phi), 0.0};
  double c[3];
  for (int j = 0; j < 3; j++) c[j] = h * n[j];
  int b = us_structure_add_point_body(s, "block", 2.0, c, 0, &err);
  for (int k = 0; k < 4; k++) {
    double su = k % 2 ? 0.5 : -0.5, sv = k / 2 ? 0.5 : -0.5, p[3];
    for (int j = 0; j < 3; j++) p[j] = su * u[j] + sv * v[j];
    us_structure_add_contact(s, US_GROUND, b, p, n, mu, &err);
  }
  s->explicit_contacts = 1;
  return test_finalized(s, "plank");
}

/* The full structure's verdict with a method and local tests on (1) or
 * off (-1) into *v (UNDECIDED on an error); the certificate of a stable
 * one must pass. info (optional) gets the workspace's statistics. */
static void verdict_local(const us_Structure *s, us_Method m, int local, us_StabilityInfo *info,
                          us_Verdict *v) {
  *v = US_UNDECIDED;
  us_StabilitySettings set = us_stability_default_settings();
  set.method = m;
  set.local = local;
  us_Error err;
  us_Stability *w = us_stability_new(s, &set, &err);
  CHECK(w);
  us_StabilityResult r;
  us_stability_result_init(&r);
  us_Status st = us_stability_test_full(w, &r, &err);
  CHECK_OK(st, &err);
  if (r.verdict == US_STABLE) CHECK(r.check.ok && r.check.max_cone_violation <= 1e-6);
  if (info) *info = *us_stability_info(w);
  *v = r.verdict;
  us_stability_result_free(&r);
  us_stability_free(w);
}

/* The verdict of the full LP with its cone refinement (local tests off:
 * info counts its refinements); the local tests (plumb lines, which test
 * the circular cones directly, and region LPs) must agree. */
static void verdict_into(const us_Structure *s, us_Method m, us_StabilityInfo *info,
                         us_Verdict *v) {
  us_Verdict lv;
  verdict_local(s, m, -1, info, v);
  verdict_local(s, m, 1, NULL, &lv);
  CHECK_INT(lv, ==, *v);
}

static us_Verdict verdict_of(const us_Structure *s, us_Method m, us_StabilityInfo *info) {
  us_Verdict v;
  verdict_into(s, m, info, &v);
  return v;
}

/* tan(alpha) <= mu, to a relative 1e-6 on either side, random slopes and
 * azimuths (so the needed friction direction falls anywhere in the
 * contact frames), both LP backends. */
static void tilted_plank_critical(void) {
  unsigned long long rng = 11 * 0x9E3779B97F4A7C15ull;
  long refined = 0;
  for (int trial = 0; trial < 40; trial++) {
    double alpha = (5.0 + 50.0 * test_rnd(&rng)) * PI / 180.0;
    double phi = 2.0 * PI * test_rnd(&rng), t = tan(alpha);
    for (int side = 0; side < 2; side++) {
      double mu = t * (side ? 1.0 + 1e-6 : 1.0 - 1e-6);
      us_Structure *s = plank(alpha, phi, mu, 0.1);
      CHECK(s);
      if (!s) continue;
      us_StabilityInfo in;
      us_Method m = trial % 4 == 3 ? US_METHOD_LPSOLVE : US_METHOD_LP;
      us_Verdict v = verdict_of(s, m, &in);
      CHECK_INT(v, ==, side ? US_STABLE : US_UNSTABLE);
      refined += in.cone3_refined;
      us_structure_free(s);
    }
  }
  CHECK(refined > 0); /* the uniform polygons alone could not decide these */
}

/* Turn every contact's tangent frame about its normal by beta. */
static void turn_frames(us_Structure *s, double beta) {
  for (int k = 0; k < s->ncontact; k++) {
    us_Contact *c = &s->contacts[k];
    double t1[3], t2[3];
    for (int j = 0; j < 3; j++) {
      t1[j] = cos(beta) * c->t[0][j] + sin(beta) * c->t[1][j];
      t2[j] = -sin(beta) * c->t[0][j] + cos(beta) * c->t[1][j];
    }
    memcpy(c->t[0], t1, sizeof t1);
    memcpy(c->t[1], t2, sizeof t2);
  }
}

/* The plank with its frames turned so that the uphill direction (where
 * friction must act) lies at pi / 8 in every contact's frame: halfway
 * between two edges of the uniform 8-sided polygon. */
static us_Structure *plank_mid(double alpha, double phi, double mu) {
  us_Structure *s = plank(alpha, phi, mu, 0.1);
  if (!s) return NULL;
  const us_Contact *c = &s->contacts[0];
  double up[3] = {-cos(alpha) * cos(phi), -cos(alpha) * sin(phi), sin(alpha)};
  double th = atan2(up[0] * c->t[1][0] + up[1] * c->t[1][1] + up[2] * c->t[1][2],
                    up[0] * c->t[0][0] + up[1] * c->t[0][1] + up[2] * c->t[0][2]);
  turn_frames(s, th - PI / 8); /* the uphill direction at angle pi / 8 */
  return s;
}

/* An 8-sided inscribed pyramid reaches only mu cos(pi / 8) = 0.924 mu
 * halfway between its edges, a circumscribed one mu / cos(pi / 8) =
 * 1.082 mu: with tan(alpha) = 0.95 mu the inscribed pyramid would call a
 * standing block unstable, with tan(alpha) = 1.05 mu the circumscribed one
 * would call a sliding block stable. The circular cone decides both. */
static void pyramid_would_be_wrong(void) {
  for (int trial = 0; trial < 6; trial++) {
    double alpha = (10.0 + 8.0 * trial) * PI / 180.0, phi = 0.7 * trial;
    us_Structure *st = plank_mid(alpha, phi, tan(alpha) / 0.95);
    us_Structure *sl = plank_mid(alpha, phi, tan(alpha) / 1.05);
    CHECK(st && sl);
    if (!st || !sl) continue;
    us_StabilityInfo in;
    CHECK_INT(verdict_of(st, US_METHOD_LP, &in), ==, US_STABLE);
    CHECK(in.cone3_outer == 1 && in.cone3_refined > 0); /* the inner 8-gon failed */
    CHECK_INT(verdict_of(sl, US_METHOD_LP, &in), ==, US_UNSTABLE);
    CHECK(in.cone3_refined > 0); /* the outer 8-gon held */
    CHECK_INT(verdict_of(sl, US_METHOD_LPSOLVE, NULL), ==, US_UNSTABLE);
    us_structure_free(st);
    us_structure_free(sl);
  }
}

/* The full LP's verdict with a budget of cone refinement rounds (-1: the
 * default) into *v; *rounds gets the most rounds the test ran. A stable
 * verdict's certificate must pass whatever the budget. */
static void verdict_budget(const us_Structure *s, int budget, us_Verdict *v, int *rounds) {
  *v = US_UNDECIDED, *rounds = -1;
  us_StabilitySettings set = us_stability_default_settings();
  set.local = -1;
  us_Error err;
  us_Stability *w = us_stability_new(s, &set, &err);
  CHECK(w);
  if (budget >= 0) us_stability_set_cone_rounds(w, budget);
  us_StabilityResult r;
  us_stability_result_init(&r);
  us_Status st = us_stability_test_full(w, &r, &err);
  CHECK_OK(st, &err);
  if (r.verdict == US_STABLE) CHECK(r.check.ok && r.check.max_cone_violation <= 1e-6);
  *v = r.verdict, *rounds = us_stability_cone_rounds_max(w);
  us_stability_result_free(&r);
  us_stability_free(w);
}

/* us_stability_set_cone_rounds caps the refinement (what random3d's drop
 * tests use): planks standing 1e-6 inside their cones need some rounds by
 * default; with one round less the test runs at most that many and never
 * calls them unstable (undecided, or stable with a passed certificate),
 * with exactly as many it decides them stable again. */
static void cone_rounds_budget(void) {
  unsigned long long rng = 23 * 0x9E3779B97F4A7C15ull;
  int capped = 0;
  for (int trial = 0; trial < 12; trial++) {
    double alpha = (5.0 + 50.0 * test_rnd(&rng)) * PI / 180.0;
    double phi = 2.0 * PI * test_rnd(&rng);
    us_Structure *s = plank(alpha, phi, tan(alpha) * (1.0 + 1e-6), 0.1);
    CHECK(s);
    us_Verdict v;
    int r0, r;
    verdict_budget(s, -1, &v, &r0);
    CHECK_INT(v, ==, US_STABLE);
    CHECK_INT(r0, <=, 60);
    if (r0 > 0) {
      verdict_budget(s, r0 - 1, &v, &r);
      CHECK_INT(r, <=, r0 - 1);
      CHECK_INT(v, !=, US_UNSTABLE);
      capped += v == US_UNDECIDED;
      verdict_budget(s, r0, &v, &r);
      CHECK_INT(v, ==, US_STABLE);
      CHECK_INT(r, ==, r0);
    }
    us_structure_free(s);
  }
  CHECK(capped > 0); /* some plank needed its last round */
}

/* Zero and infinite friction are exact cones: a level block stands with
 * mu = 0, a tilted one slides with mu = 0 and stands with mu = INFINITY,
 * with no refinement at all. */
static void exact_cones(void) {
  us_StabilityInfo in;
  us_Structure *s = plank(0.0, 0.0, 0.0, 0.1);
  CHECK_INT(verdict_of(s, US_METHOD_LP, &in), ==, US_STABLE);
  us_structure_free(s);
  s = plank(0.3, 1.0, 0.0, 0.1);
  CHECK_INT(verdict_of(s, US_METHOD_LP, &in), ==, US_UNSTABLE);
  CHECK_INT(in.cone3_refined, ==, 0);
  us_structure_free(s);
  s = plank(1.2, 2.0, INFINITY, 0.1);
  CHECK_INT(verdict_of(s, US_METHOD_LP, &in), ==, US_STABLE);
  CHECK_INT(in.cone3_refined, ==, 0);
  us_structure_free(s);
}

/* A stack of point blocks, each on four contacts to the one below (or the
 * ground) with a random tilt and friction: the bodies' centres drift
 * sideways at random, so some stacks tip and some slide. */
static us_Structure *random_stack(unsigned long long *rng, int nb) {
  us_Structure *s = us_structure_new(3);
  us_Error err;
  s->gravity[0] = s->gravity[1] = 0.0, s->gravity[2] = -9.81;
  double base[3] = {0, 0, 0};
  for (int i = 0; i < nb; i++) {
    double tx = 0.5 * (test_rnd(rng) - 0.5), ty = 0.5 * (test_rnd(rng) - 0.5);
    double n[3] = {tx, ty, 1.0}, l = sqrt(tx * tx + ty * ty + 1.0);
    for (int j = 0; j < 3; j++) n[j] /= l;
    double c[3] = {base[0] + 0.6 * (test_rnd(rng) - 0.5),
                   base[1] + 0.6 * (test_rnd(rng) - 0.5), base[2] + 0.5};
    char id[16];
    snprintf(id, sizeof id, "b%d", i);
    int b = us_structure_add_point_body(s, id, 1.0 + test_rnd(rng), c, 0, &err);
    double mu = 0.2 + 0.6 * test_rnd(rng);
    for (int k = 0; k < 4; k++) {
      double p[3] = {base[0] + (k % 2 ? 0.5 : -0.5), base[1] + (k / 2 ? 0.5 : -0.5), base[2]};
      p[2] -= (n[0] * (p[0] - base[0]) + n[1] * (p[1] - base[1])) / n[2]; /* on the plane */
      us_structure_add_contact(s, i == 0 ? US_GROUND : b - 1, b, p, n, mu, &err);
    }
    base[0] = c[0], base[1] = c[1], base[2] = c[2] + 0.5;
  }
  s->explicit_contacts = 1;
  if (us_structure_finalize(s, &err) != US_OK) {
    us_structure_free(s);
    return NULL;
  }
  return s;
}

/* lp and lpsolve agree on every prefix of random stacks (each prefix a
 * sub-assembly of one workspace, so refinements carry over). */
static void backends_agree(void) {
  unsigned long long rng = 5 * 0x9E3779B97F4A7C15ull;
  int stable = 0, unstable = 0;
  for (int trial = 0; trial < 30; trial++) {
    us_Structure *s = random_stack(&rng, 2 + trial % 5);
    CHECK(s);
    if (!s) continue;
    us_StabilitySettings set = us_stability_default_settings();
    us_Error err;
    set.method = US_METHOD_LP;
    us_Stability *a = us_stability_new(s, &set, &err);
    set.method = US_METHOD_LPSOLVE;
    us_Stability *b = us_stability_new(s, &set, &err);
    CHECK(a && b);
    us_Bitset sub;
    us_bitset_init(&sub, s->nbody);
    us_StabilityResult ra, rb;
    us_stability_result_init(&ra);
    us_stability_result_init(&rb);
    for (int k = 0; a && b && k < s->nbody; k++) {
      us_bitset_set(&sub, k);
      CHECK_OK(us_stability_test(a, &sub, &ra, &err), &err);
      CHECK_OK(us_stability_test(b, &sub, &rb, &err), &err);
      CHECK_INT(ra.verdict, ==, rb.verdict);
      CHECK(ra.verdict != US_UNDECIDED);
      stable += ra.verdict == US_STABLE;
      unstable += ra.verdict == US_UNSTABLE;
    }
    us_stability_result_free(&ra);
    us_stability_result_free(&rb);
    us_bitset_free(&sub);
    us_stability_free(a);
    us_stability_free(b);
    us_structure_free(s);
  }
  CHECK(stable > 10 && unstable > 10); /* both verdicts exercised */
}

/* A straight 3D tower plans top-down, with every method. */
static void tower_plans(void) {
  unsigned long long rng = 2 * 0x9E3779B97F4A7C15ull;
  us_Structure *s = NULL;
  for (int tries = 0; tries < 50 && !s; tries++) { /* a stack that stands */
    s = random_stack(&rng, 6);
    if (s && verdict_of(s, US_METHOD_LP, NULL) != US_STABLE) us_structure_free(s), s = NULL;
  }
  CHECK(s);
  if (!s) return;
  us_PlanSettings set = us_plan_default_settings();
  us_Plan p;
  us_Error err;
  CHECK_OK(us_plan(s, &set, &p, &err), &err);
  CHECK_INT(p.status, ==, US_PLAN_FOUND);
  for (int k = 0; k < p.nsteps; k++) CHECK_INT(p.order[k], ==, s->nbody - 1 - k);
  us_plan_free(&p);
  us_Method lcps[3] = {US_METHOD_LCP, US_METHOD_LCP_REUSE, US_METHOD_LP_LCP};
  for (int m = 0; m < 3; m++) { /* the LCP methods plan it the same way */
    set.stability.method = lcps[m];
    CHECK_OK(us_plan(s, &set, &p, &err), &err);
    CHECK_INT(p.status, ==, US_PLAN_FOUND);
    for (int k = 0; k < p.nsteps; k++) CHECK_INT(p.order[k], ==, s->nbody - 1 - k);
    us_plan_free(&p);
  }
  us_structure_free(s);
}

/* A 2D structure and its extrusion (turned and shifted) give the same
 * verdict on every sub-assembly tried: the full one and random subsets,
 * for mu = 0 and mu = 0.5, on columns, pyramids, walls, arches and the
 * stacker's random stacks. (A 3D solution mirrored through the mid-plane
 * and averaged projects to a 2D one; a 2D one split over the two faces is
 * a 3D one, so the verdicts must agree.) */
static void extrusion_invariance(void) {
  unsigned long long rng = 77;
  int agree = 0, stable = 0, unstable = 0;
  for (int kind = 0; kind < 5; kind++) {
    for (int fr = 0; fr < 2; fr++) {
      us_GenSettings g = us_gen_default_settings();
      us_Error err;
      g.friction = fr ? 0.5 : 0.0;
      us_Structure *s = NULL;
      if (kind == 0) g.n = 5, s = us_gen_column(&g, &err);
      if (kind == 1) g.n = 4, s = us_gen_pyramid(&g, &err);
      if (kind == 2) g.rows = g.cols = 4, s = us_gen_wall(&g, &err);
      if (kind == 3) g.n = 7, g.radius = 2.0, g.thickness = 0.5, s = us_gen_arch(&g, &err);
      if (kind == 4) g.rows = 6, g.width = 5, g.seed = 3, s = us_gen_stacker(&g, &err);
      CHECK(s);
      if (!s) continue;
      us_Structure *e = test_extrude(s, 0.7, 2.0 * PI * test_rnd(&rng), 3.5, -1.25);
      CHECK(e);
      us_StabilitySettings set = us_stability_default_settings();
      set.method = US_METHOD_LP;
      us_Stability *w2 = us_stability_new(s, &set, &err);
      us_Stability *w3 = e ? us_stability_new(e, &set, &err) : NULL;
      CHECK(w2 && w3);
      us_Bitset sub;
      us_bitset_init(&sub, s->nbody);
      us_StabilityResult r2, r3;
      us_stability_result_init(&r2);
      us_stability_result_init(&r3);
      for (int t = 0; w2 && w3 && t < 25; t++) {
        for (int i = 0; i < s->nbody; i++)
          if (t == 0 || test_rnd(&rng) < 0.7) us_bitset_set(&sub, i);
          else us_bitset_clear(&sub, i);
        CHECK_OK(us_stability_test(w2, &sub, &r2, &err), &err);
        CHECK_OK(us_stability_test(w3, &sub, &r3, &err), &err);
        CHECK_INT(r3.verdict, ==, r2.verdict);
        agree += r3.verdict == r2.verdict;
        stable += r2.verdict == US_STABLE;
        unstable += r2.verdict == US_UNSTABLE;
      }
      us_stability_result_free(&r2);
      us_stability_result_free(&r3);
      us_bitset_free(&sub);
      us_stability_free(w2);
      us_stability_free(w3);
      us_structure_free(e);
      us_structure_free(s);
    }
  }
  CHECK(stable > 30 && unstable > 30); /* both verdicts exercised */
  CHECK_INT(agree, ==, 5 * 2 * 25);
}

/* A copy of the 3D structure s (single-part bodies) with every point moved
 * to M p + shift and gravity turned by M (for a rotation) or kept (for a
 * scaling: turn_g = 0); the ground as given, plus, with floor, a fixed
 * slab 40 x 40 x 1 under z = 0 (moved like the rest) standing for it. */
static us_Structure *transformed(const us_Structure *s, const double M[9], const double shift[3],
                                 int turn_g, int ground, int floor) {
  us_Structure *e = us_structure_new(3);
  us_Error err;
  e->friction = s->friction;
  e->ground = ground;
  for (int j = 0; j < 3; j++)
    e->gravity[j] = turn_g ? M[3 * j] * s->gravity[0] + M[3 * j + 1] * s->gravity[1] +
                                 M[3 * j + 2] * s->gravity[2]
                           : s->gravity[j];
  int ok = 1;
  for (int i = 0; ok && i <= s->nbody; i++) {
    double slab[24], *xyz = slab;
    int n = 8;
    if (i == s->nbody) {
      if (!floor) break;
      for (int k = 0; k < 8; k++) {
        slab[3 * k] = k & 1 ? 20.0 : -20.0, slab[3 * k + 1] = k & 2 ? 20.0 : -20.0;
        slab[3 * k + 2] = k & 4 ? 0.0 : -1.0;
      }
    } else {
      const us_Body *b = &s->bodies[i];
      if (b->npart != 1) { /* compounds are not needed here */
        ok = 0;
        break;
      }
      n = b->parts[0].nvert;
      xyz = us_malloc(3 * (size_t)n * sizeof(double));
      memcpy(xyz, b->parts[0].verts, 3 * (size_t)n * sizeof(double));
    }
    double *out = us_malloc(3 * (size_t)n * sizeof(double));
    for (int k = 0; k < n; k++)
      for (int j = 0; j < 3; j++)
        out[3 * k + j] = M[3 * j] * xyz[3 * k] + M[3 * j + 1] * xyz[3 * k + 1] +
                         M[3 * j + 2] * xyz[3 * k + 2] + shift[j];
    us_BodyDef d = us_default_body_def();
    d.id = i == s->nbody ? "floor" : s->bodies[i].id;
    d.nvert = n, d.xyz = out, d.fixed = i == s->nbody;
    if (i < s->nbody) d.friction = s->bodies[i].friction;
    ok = us_structure_add_body(e, &d, &err) >= 0;
    us_free(out);
    if (xyz != slab) us_free(xyz);
  }
  if (!ok) {
    fprintf(stderr, "transformed: %s\n", err.msg);
    us_structure_free(e);
    return NULL;
  }
  return test_finalized(e, "transformed");
}

/* A random rotation (Euler angles) into M. */
static void random_rotation(unsigned long long *rng, double M[9]) {
  double a = 2 * PI * test_rnd(rng), b = PI * test_rnd(rng), c = 2 * PI * test_rnd(rng);
  double ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b), cc = cos(c), sc = sin(c);
  double r[9] = {ca * cc - sa * cb * sc, -ca * sc - sa * cb * cc, sa * sb,
                 sa * cc + ca * cb * sc, -sa * sc + ca * cb * cc, -ca * sb,
                 sb * sc, sb * cc, cb};
  memcpy(M, r, sizeof r);
}

/* Verdicts of sub-assemblies of a (bodies 0..n-1) and b (the same bodies
 * first; fixed extras always present) agree: the full structure, every
 * prefix from the top down and random subsets. Counts into agree and the
 * verdict tallies. */
static void compare_verdicts(const us_Structure *a, const us_Structure *b, int n,
                             unsigned long long *rng, int *agree, int *tally) {
  us_StabilitySettings set = us_stability_default_settings();
  us_Error err;
  us_Stability *wa = us_stability_new(a, &set, &err), *wb = us_stability_new(b, &set, &err);
  CHECK(wa && wb);
  us_Bitset sa, sb;
  us_bitset_init(&sa, a->nbody);
  us_bitset_init(&sb, b->nbody);
  us_StabilityResult ra, rb;
  us_stability_result_init(&ra);
  us_stability_result_init(&rb);
  for (int t = 0; wa && wb && t < n + 20; t++) {
    for (int i = 0; i < b->nbody; i++) {
      int on = i >= n ? 1 : t < n ? i < n - t : test_rnd(rng) < 0.7;
      if (on) us_bitset_set(&sb, i);
      else us_bitset_clear(&sb, i);
      if (i < a->nbody && on) us_bitset_set(&sa, i);
      else if (i < a->nbody) us_bitset_clear(&sa, i);
    }
    for (int i = n; i < a->nbody; i++) us_bitset_set(&sa, i);
    CHECK_OK(us_stability_test(wa, &sa, &ra, &err), &err);
    CHECK_OK(us_stability_test(wb, &sb, &rb, &err), &err);
    CHECK_INT(rb.verdict, ==, ra.verdict);
    *agree += rb.verdict == ra.verdict;
    tally[ra.verdict == US_STABLE]++;
  }
  us_stability_result_free(&ra);
  us_stability_result_free(&rb);
  us_bitset_free(&sa);
  us_bitset_free(&sb);
  us_stability_free(wa);
  us_stability_free(wb);
}

/* Rigid motions and scalings change no verdict: a 3D structure turned
 * about the vertical and shifted; turned by a random rotation with
 * gravity turned with it (the ground replaced by a fixed slab in both);
 * scaled by 3.7 and by 0.02 (masses by the cube). On pyramid3d, jenga
 * with pieces out, a jittered tower and random3d piles, mu 0.5 and 0.2. */
static void transform_invariance(void) {
  unsigned long long rng = 4242;
  int agree = 0, total = 0, tally[2] = {0, 0};
  for (int kind = 0; kind < 4; kind++) {
    for (int fr = 0; fr < 2; fr++) {
      us_GenSettings g = us_gen_default_settings();
      us_Error err;
      g.friction = fr ? 0.2 : 0.5;
      us_Structure *s = NULL;
      if (kind == 0) g.n = 3, s = us_gen_pyramid3d(&g, &err);
      if (kind == 1) {
        static const int rm[4] = {2, 1, 3, 3};
        g.n = 5, g.remove = rm, g.nremove = 2;
        s = us_gen_jenga(&g, &err);
      }
      if (kind == 2) g.n = 8, g.jitter = 40.0, g.seed = 5, s = us_gen_tower(&g, &err);
      if (kind == 3) g.n = 14, g.width = 2.5, g.seed = 9 + (unsigned)fr, s = us_gen_random3d(&g, &err);
      CHECK(s);
      if (!s) continue;
      double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, R[9], zero[3] = {0, 0, 0};
      double th = 2 * PI * test_rnd(&rng), Z[9] = {cos(th), -sin(th), 0, sin(th), cos(th), 0, 0, 0, 1};
      double shift[3] = {4.0 * test_rnd(&rng) - 2.0, 4.0 * test_rnd(&rng) - 2.0, 0.0};
      double big[9] = {3.7, 0, 0, 0, 3.7, 0, 0, 0, 3.7}, tiny[9] = {0.02, 0, 0, 0, 0.02, 0, 0, 0, 0.02};
      double far[3] = {10.0 * test_rnd(&rng), -7.0, 3.0 * test_rnd(&rng)};
      random_rotation(&rng, R);
      us_Structure *t[4] = {transformed(s, Z, shift, 1, 1, 0), transformed(s, big, zero, 0, 1, 0),
                            transformed(s, tiny, zero, 0, 1, 0), transformed(s, R, far, 1, 0, 1)};
      us_Structure *slab = transformed(s, I, zero, 1, 0, 1); /* the original on a slab */
      for (int k = 0; k < 4; k++) {
        CHECK(t[k]);
        if (!t[k] || !slab) continue;
        compare_verdicts(k == 3 ? slab : s, t[k], s->nbody, &rng, &agree, tally);
        total += s->nbody + 20;
      }
      for (int k = 0; k < 4; k++) us_structure_free(t[k]);
      us_structure_free(slab);
      us_structure_free(s);
    }
  }
  CHECK_INT(agree, ==, total);
  CHECK(tally[0] > 40 && tally[1] > 40); /* both verdicts exercised */
}

/* A 3D counterweight: a plank on a pier carries a load on its far end,
 * which tips it unless a tall counterweight stands on its back end. The
 * counterweight is the highest body, but removing it first drops the plank
 * and the load: DFS (highest first) must step back and take the load
 * first; every search finds load, counterweight, plank, pier, and the
 * plank with the load alone is unstable. */
static void counterweight_backtracks(void) {
  us_Structure *s = us_structure_new(3);
  us_Error err;
  s->gravity[2] = -9.81;
  s->friction = 0.6;
  static const double box[4][6] = {{0, 0, 0, 1, 1, 1},          /* pier */
                                   {-0.5, 0, 1, 2, 1, 1.2},      /* plank, COM over the pier */
                                   {-0.5, 0, 1.2, 0, 1, 2.7},    /* counterweight, tall */
                                   {1.5, 0, 1.2, 2, 1, 1.7}};    /* load, 1 m out */
  static const char *ids[4] = {"pier", "plank", "weight", "load"};
  for (int i = 0; i < 4; i++) {
    double xyz[24];
    for (int k = 0; k < 8; k++) {
      xyz[3 * k] = box[i][k & 1 ? 3 : 0], xyz[3 * k + 1] = box[i][k & 2 ? 4 : 1];
      xyz[3 * k + 2] = box[i][k & 4 ? 5 : 2];
    }
    us_BodyDef d = us_default_body_def();
    d.id = ids[i], d.nvert = 8, d.xyz = xyz;
    CHECK(us_structure_add_body(s, &d, &err) >= 0);
  }
  CHECK_OK(us_structure_finalize(s, &err), &err);
  us_Bitset sub;
  us_bitset_init(&sub, 4);
  us_bitset_set(&sub, 0), us_bitset_set(&sub, 1), us_bitset_set(&sub, 3);
  us_StabilitySettings ss = us_stability_default_settings();
  us_Stability *w = us_stability_new(s, &ss, &err);
  us_StabilityResult r;
  us_stability_result_init(&r);
  CHECK_OK(us_stability_test(w, &sub, &r, &err), &err);
  CHECK_INT(r.verdict, ==, US_UNSTABLE); /* plank and load alone tip */
  us_bitset_set(&sub, 2);
  CHECK_OK(us_stability_test(w, &sub, &r, &err), &err);
  CHECK_INT(r.verdict, ==, US_STABLE);
  us_stability_result_free(&r);
  us_stability_free(w);
  us_bitset_free(&sub);
  static const us_Search searches[3] = {US_SEARCH_DFS, US_SEARCH_BFS, US_SEARCH_ASSEMBLE};
  for (int k = 0; k < 3; k++) {
    us_PlanSettings set = us_plan_default_settings();
    set.search = searches[k];
    us_Plan p;
    CHECK_OK(us_plan(s, &set, &p, &err), &err);
    CHECK_INT(p.status, ==, US_PLAN_FOUND);
    CHECK_INT(p.nsteps, ==, 4);
    if (p.nsteps == 4) CHECK(p.order[0] == 3 && p.order[1] == 2 && p.order[3] == 0);
    if (k == 0) CHECK(p.stats.unstable > 0); /* DFS tried the counterweight first */
    us_plan_free(&p);
  }
  us_structure_free(s);
}

US_TEST_MAIN(T(tilted_plank_critical), T(pyramid_would_be_wrong), T(cone_rounds_budget),
             T(exact_cones),
             T(backends_agree), T(tower_plans),
             T(extrusion_invariance), T(transform_invariance), T(counterweight_backtracks))
