/* Known cases of the 3D generators dome, jenga and random3d (src/gen/
 * dome.c, jenga.c, random3d.c): the layouts' contacts and volumes from
 * independent formulas, and the statics each structure must show, decided
 * by the library's stability test and planner. */
#include "gen/gen.h"
#include "scenes.h"
#include "test.h"

#include <math.h>

#define PI 3.14159265358979323846
#ifndef US_TEST_SANITIZED
#define US_TEST_SANITIZED 0
#endif

static int count_pair(const us_Structure *s, int i, int j) {
  int n = 0;
  for (int k = 0; k < s->ncontact; k++)
    n += (s->contacts[k].a == i && s->contacts[k].b == j) || (s->contacts[k].a == j && s->contacts[k].b == i);
  return n;
}

/* The verdict on the bodies of s whose bit is set in `present` (NULL: all). */
static us_Verdict verdict_of(const us_Structure *s, const us_Bitset *present) {
  int v = scene_verdict(s, US_METHOD_AUTO, present);
  return v < 0 ? US_UNDECIDED : (us_Verdict)v;
}

static us_PlanStatus plan_status(const us_Structure *s) {
  us_PlanSettings set = us_plan_default_settings();
  us_Plan p = {0};
  us_Error err;
  us_PlanStatus st = us_plan(s, &set, &p, &err) ? US_PLAN_UNDECIDED : p.status;
  us_plan_free(&p);
  return st;
}

/* ------------------------------------------------------------------ dome */

/* Triple product a . (b x c). */
static double det3(const double *a, const double *b, const double *c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
}

/* Volume of a voussoir of a course between latitudes p0, p1 and a segment
 * of angle d: the pyramid from the origin over the outer trapezoid minus
 * the one over the inner (its copy scaled by R / (R + T)). */
static double voussoir_volume(double R, double T, double p0, double p1, double d) {
  double c[4][3];
  for (int k = 0; k < 4; k++) {
    double phi = k < 2 ? p0 : p1, th = k == 1 || k == 2 ? d : 0.0;
    c[k][0] = cos(phi) * cos(th), c[k][1] = cos(phi) * sin(th), c[k][2] = sin(phi);
  }
  double unit = (fabs(det3(c[0], c[1], c[2])) + fabs(det3(c[0], c[2], c[3]))) / 6.0;
  return unit * (pow(R + T, 3) - pow(R, 3));
}

/* Every voussoir touches its ring neighbours and the voussoir under it on
 * a face (4 corners), the bottom course touches the ground the same way,
 * and the masses are the frustums' volumes. */
static void dome_layout(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.chamfer = 0.0; /* sharp: every joint a 4-corner face */
  int n = g.n, m = g.segments;
  us_Structure *s = us_gen_dome(&g, &err);
  CHECK(s != NULL);
  int ok = s->dim == 3 && s->nbody == n * m;
  double P = (90.0 - g.oculus) * PI / 180.0, worst = 0;
  for (int k = 0; ok && k < n; k++)
    for (int j = 0; ok && j < m; j++) {
      int i = k * m + j, right = k * m + (j + 1) % m;
      ok = count_pair(s, i, right) == 4 && count_pair(s, i, k ? i - m : US_GROUND) == 4;
      double v = voussoir_volume(g.radius, g.thickness, k * P / n, (k + 1) * P / n, 2 * PI / m);
      worst = fmax(worst, fabs(s->bodies[i].mass - v) / v);
    }
  us_structure_free(s);
  CHECK(ok);
  CHECK(worst < 1e-9);
}

/* With a cap: one more body, on every voussoir of the top course. */
static void dome_cap(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.n = 4, g.segments = 8, g.cap = 1, g.oculus = 30;
  us_Structure *s = us_gen_dome(&g, &err);
  CHECK(s != NULL);
  int ok = s->nbody == 33;
  for (int j = 0; ok && j < 8; j++) ok = count_pair(s, 32, 24 + j) >= 4;
  us_Verdict v = ok ? verdict_of(s, NULL) : US_UNDECIDED;
  us_structure_free(s);
  CHECK(ok);
  CHECK_INT(v, ==, US_STABLE);
}

/* The defaults (friction 0.5) stand, and with no sliding; without friction
 * nothing holds the outward thrust at the ground. */
static void dome_stands(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  double mus[3] = {0.5, INFINITY, 0.0};
  us_Verdict want[3] = {US_STABLE, US_STABLE, US_UNSTABLE};
  for (int k = 0; k < 3; k++) {
    g.friction = mus[k];
    us_Structure *s = us_gen_dome(&g, &err);
    CHECK(s != NULL);
    us_Verdict v = verdict_of(s, NULL);
    us_structure_free(s);
    CHECK_INT(v, ==, want[k]);
  }
}

/* Drop every contact of body b except those with body keep (the test's own
 * surgery on a finalized structure, to see which contacts hold b). */
static void keep_contacts_with(us_Structure *s, int b, int keep) {
  int n = 0;
  for (int k = 0; k < s->ncontact; k++) {
    const us_Contact *c = &s->contacts[k];
    if ((c->a == b || c->b == b) && c->a != keep && c->b != keep) continue;
    s->contacts[n++] = *c;
  }
  s->ncontact = n;
}

/* One voussoir at a time: with this library's contacts the planner finds
 * an order (top course first). The first voussoir of a course, alone on the
 * complete courses below, stands although its centre of mass lies inward
 * of its bed: its lower side edges lie on the valleys between the beds of
 * the three voussoirs under it, and the diagonal neighbours' contacts there
 * (edge on edge, normals of the beds and of the meridian joints) pinch it.
 * With its contacts reduced to the voussoir under it, it falls. */
static void dome_one_at_a_time(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.chamfer = 0.0;
  us_Structure *s = us_gen_dome(&g, &err);
  CHECK(s != NULL);
  int n = g.n, m = g.segments, lone = (n - 1) * m, below = lone - m;
  us_PlanStatus st = plan_status(s);
  us_Bitset present = {0};
  CHECK(us_bitset_init(&present, s->nbody) == 0);
  for (int i = 0; i <= lone; i++) us_bitset_set(&present, i);
  us_Verdict pinched = verdict_of(s, &present);
  double rho = hypot(s->bodies[lone].com[0], s->bodies[lone].com[1]);
  double phi = (n - 1) * (90.0 - g.oculus) * PI / 180.0 / n;
  double inner = g.radius * cos(phi) * cos(PI / m); /* the bed's inner edge */
  keep_contacts_with(s, lone, below);
  us_Verdict alone = verdict_of(s, &present);
  us_bitset_free(&present);
  us_structure_free(s);
  CHECK_INT(st, ==, US_PLAN_FOUND);
  CHECK_INT(pinched, ==, US_STABLE);
  CHECK(rho < inner);
  CHECK_INT(alone, ==, US_UNSTABLE);
}

/* The first `courses` complete courses and voussoir 0 of the next one. */
static us_Verdict course_started(const us_Structure *s, int m, int courses) {
  us_Bitset present = {0};
  if (us_bitset_init(&present, s->nbody)) return US_UNDECIDED;
  for (int i = 0; i <= courses * m; i++) us_bitset_set(&present, i);
  us_Verdict v = verdict_of(s, &present);
  us_bitset_free(&present);
  return v;
}

/* Bevelled lower side edges (--chamfer) clear the valleys: no diagonal
 * contacts, the dome still stands, and a course can be started one
 * voussoir at a time exactly while its bed is flatter than the friction
 * angle: with mu = 0.5 (26.6 degrees) and beds every 7.5 degrees, the
 * voussoir on the bed at 22.5 degrees stands alone, the one at 30 does not
 * (sharp edges: it stands, pinched). */
static void dome_chamfer(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  CHECK(g.chamfer == 0.02); /* the default */
  us_Structure *bev = us_gen_dome(&g, &err);
  g.chamfer = 0.0;
  us_Structure *sharp = us_gen_dome(&g, &err);
  CHECK(sharp && bev);
  if (!sharp || !bev) return;
  int m = g.segments;
  CHECK(bev->ncontact < sharp->ncontact);
  CHECK_INT(verdict_of(bev, NULL), ==, US_STABLE);
  CHECK_INT(course_started(bev, m, 3), ==, US_STABLE);   /* bed at 22.5 degrees */
  CHECK_INT(course_started(bev, m, 4), ==, US_UNSTABLE); /* bed at 30 degrees */
  CHECK_INT(course_started(sharp, m, 4), ==, US_STABLE); /* pinched in the valleys */
  us_structure_free(sharp);
  us_structure_free(bev);
  g.chamfer = 0.5;
  CHECK(us_gen_dome(&g, &err) == NULL && err.code == US_ERR_USAGE && strstr(err.msg, "chamfer"));
}

/* The default dome (10 courses of 12, bevelled): `none` in steps of 1, 2
 * and 3 voussoirs, proven by the cut (exact.c) without an exhaustive
 * search. What can be built are exactly the courses whose beds are
 * flatter than the friction angle (atan 0.5 = 26.6 degrees: the beds at
 * 0, 7.5, 15 and 22.5), and every voussoir above them is blocked. */
static void dome_default_none(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  us_Structure *s = us_gen_dome(&g, &err);
  CHECK(s != NULL);
  if (!s) return;
  int m = g.segments, flat = 0;
  while (flat < g.n && tan(flat * (90.0 - g.oculus) / g.n * PI / 180.0) < g.friction) flat++;
  CHECK_INT(flat, ==, 4);
  for (int K = 1; K <= 3; K++) {
    us_PlanSettings set = us_plan_default_settings();
    set.max_group = K;
    us_Plan p = {0};
    CHECK_OK(us_plan(s, &set, &p, &err), &err);
    CHECK_INT(p.status, ==, US_PLAN_NONE);
    CHECK_INT(p.stats.exhaustive, ==, 0);
    CHECK_INT(p.stats.cuts, ==, 1);
    CHECK_INT(p.nbuildable, ==, flat * m);
    CHECK_INT(p.nblocked, ==, s->nbody - flat * m);
    int low = 1;
    for (int i = 0; i < p.nbuildable; i++) low &= p.buildable[i] < flat * m;
    CHECK(low);
    us_plan_free(&p);
  }
  us_structure_free(s);
}

/* The known case: a dome cannot be unstacked one voussoir at a time. Two
 * courses of 6 with the upper bed at 30 degrees (steeper than atan(0.5)),
 * edges bevelled: it stands, and every search proves `none` (the upper
 * course cannot be started, nor broken, one voussoir at a time). With
 * sharp edges the valley pinch gives an order instead. */
static void dome_none_one_at_a_time(void) {
  us_GenSettings g = us_gen_default_settings();
  g.n = 2, g.segments = 6, g.oculus = 30.0, g.chamfer = 0.02;
  us_Error err;
  us_Structure *s = us_gen_dome(&g, &err);
  CHECK(s != NULL);
  if (!s) return;
  CHECK_INT(verdict_of(s, NULL), ==, US_STABLE);
  static const us_Search searches[3] = {US_SEARCH_ASSEMBLE, US_SEARCH_DFS, US_SEARCH_BFS};
  for (int k = 0; k < 3; k++) {
    us_PlanSettings set = us_plan_default_settings();
    set.search = searches[k];
    us_Plan p = {0};
    CHECK_OK(us_plan(s, &set, &p, &err), &err);
    CHECK_INT(p.status, ==, US_PLAN_NONE);
    CHECK_INT(p.stats.exhaustive, ==, 0); /* the cut proved it */
    us_plan_free(&p);
  }
  us_structure_free(s);
  g.chamfer = 0.0;
  s = us_gen_dome(&g, &err);
  CHECK(s != NULL);
  if (s) CHECK_INT(plan_status(s), ==, US_PLAN_FOUND);
  us_structure_free(s);
}

static void dome_bad_settings(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.oculus = 90;
  CHECK(us_gen_dome(&g, &err) == NULL && err.code == US_ERR_USAGE && strstr(err.msg, "oculus"));
  g = us_gen_default_settings(), g.segments = 2;
  CHECK(us_gen_dome(&g, &err) == NULL && err.code == US_ERR_USAGE && strstr(err.msg, "segments"));
  g = us_gen_default_settings(), g.thickness = -1;
  CHECK(us_gen_dome(&g, &err) == NULL && err.code == US_ERR_USAGE && strstr(err.msg, "thickness"));
}

/* ----------------------------------------------------------------- jenga */

/* The tower of `levels` levels without the pieces in rm (pairs). */
static us_Structure *jenga(int levels, int nrm, const int *rm) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.n = levels, g.height = 0.6, g.nremove = nrm, g.remove = rm;
  return us_gen_jenga(&g, &err);
}

/* Each piece crosses the three under it on unit squares (4 corners each);
 * side by side pieces share a long face. */
static void jenga_layout(void) {
  us_Structure *s = jenga(18, 0, NULL);
  CHECK(s != NULL);
  int ok = s->nbody == 54;
  for (int i = 0; ok && i < 54; i++) {
    int lv = i / 3, p = i % 3;
    for (int q = 0; ok && q < 3; q++) ok = lv == 0 || count_pair(s, i, 3 * (lv - 1) + q) == 4;
    ok = ok && (p == 2 || count_pair(s, i, i + 1) == 4) && (lv || count_pair(s, i, US_GROUND) == 4);
  }
  ok = ok && fabs(s->bodies[53].com[2] - 17.5 * 0.6) < 1e-12 && fabs(s->bodies[0].mass - 1.8) < 1e-12;
  us_structure_free(s);
  CHECK(ok);
}

/* Which removals leave the tower standing (18 levels, level 9 in the
 * middle); the body count is 3 N minus the pieces removed. */
static void jenga_removals(void) {
  static const struct {
    int n, rm[6];
    us_Verdict want;
  } cases[] = {
      {0, {0}, US_STABLE},
      {1, {9, 2}, US_STABLE},             /* the middle: the sides hold the centre line */
      {1, {9, 1}, US_STABLE},             /* one side: the other two hold it */
      {2, {9, 1, 9, 3}, US_STABLE},       /* both sides: it balances on the middle piece */
      {2, {9, 1, 9, 2}, US_UNSTABLE},     /* one side left: the centre is off its strip */
      {2, {1, 3, 1, 2}, US_UNSTABLE},     /* the same on the ground level */
      {3, {9, 1, 9, 2, 9, 3}, US_UNSTABLE}, /* a whole level: the top half floats */
      {2, {18, 1, 18, 2}, US_STABLE},     /* one side left on the top level: nothing above */
      {3, {4, 2, 9, 1, 14, 3}, US_STABLE}, /* one piece from three levels */
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    us_Structure *s = jenga(18, cases[k].n, cases[k].rm);
    CHECK(s != NULL);
    int nb = s->nbody;
    us_Verdict v = verdict_of(s, NULL);
    us_structure_free(s);
    CHECK_INT(nb, ==, 54 - cases[k].n);
    CHECK_INT(v, ==, cases[k].want);
  }
}

/* Knocked-out pieces keep the ids of the rest: b<3 (L - 1) + P>. */
static void jenga_ids(void) {
  int rm[4] = {2, 2, 3, 1};
  us_Structure *s = jenga(3, 2, rm);
  CHECK(s != NULL);
  int ok = s->nbody == 7 && !strcmp(s->bodies[3].id, "b4") && !strcmp(s->bodies[4].id, "b6") &&
           !strcmp(s->bodies[5].id, "b8");
  us_structure_free(s);
  CHECK(ok);
}

static void jenga_bad_settings(void) {
  us_Error err;
  int out[2] = {4, 1}, pos[2] = {2, 4}, twice[4] = {2, 1, 2, 1};
  CHECK(jenga(3, 1, out) == NULL);
  us_GenSettings g = us_gen_default_settings();
  g.n = 3, g.nremove = 1, g.remove = pos;
  CHECK(us_gen_jenga(&g, &err) == NULL && err.code == US_ERR_USAGE && strstr(err.msg, "2:4"));
  g.nremove = 2, g.remove = twice;
  CHECK(us_gen_jenga(&g, &err) == NULL && err.code == US_ERR_USAGE && strstr(err.msg, "twice"));
}

/* -------------------------------------------------------------- random3d */

static us_Structure *random3d(int n, double width, unsigned long seed, int tries) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.n = n, g.width = width, g.seed = seed, g.max_tries = tries;
  return us_gen_random3d(&g, &err);
}

/* Every box rests on something: the ground or a box whose top is its
 * bottom, touching it from below with an upward normal. */
static int all_supported(const us_Structure *s) {
  for (int i = 0; i < s->nbody; i++) {
    int held = 0;
    for (int k = 0; k < s->ncontact && !held; k++) {
      const us_Contact *c = &s->contacts[k];
      double up = c->b == i ? c->n[2] : c->a == i ? -c->n[2] : 0.0; /* normals point a -> b */
      held = up == 1.0 && fabs(c->p[2] - (s->bodies[i].com[2] - 0.25)) < 1e-12;
    }
    if (!held) return 0;
  }
  return 1;
}

/* Seeds 1..6: each structure stands whole, every box rests on the boxes
 * under it, and the count is the one asked for (a generous try limit). */
static void random3d_stands(void) {
  int seeds = US_TEST_SANITIZED ? 2 : 6;
  for (int seed = 1; seed <= seeds; seed++) {
    us_Structure *s = random3d(30, 3, (unsigned long)seed, 1000);
    CHECK(s != NULL);
    int nb = s->nbody, held = all_supported(s);
    us_Verdict v = verdict_of(s, NULL);
    double top = s->bbox3[5];
    us_structure_free(s);
    CHECK_INT(nb, ==, 30);
    CHECK(held);
    CHECK_INT(v, ==, US_STABLE);
    CHECK(top > 0.5); /* something stands on something */
  }
}

/* With one try per box the run stops early on some seed: fewer boxes,
 * still standing. */
static void random3d_fewer(void) {
  int fewer = 0;
  for (unsigned long seed = 1; seed <= 20 && !fewer; seed++) {
    us_Structure *s = random3d(40, 2, seed, 1);
    CHECK(s != NULL);
    if (s->nbody < 40) {
      fewer = 1;
      CHECK(s->nbody >= 1);
      CHECK_INT(verdict_of(s, NULL), ==, US_STABLE);
    }
    us_structure_free(s);
  }
  CHECK(fewer);
}

/* The same seed gives the same boxes; another seed others. A width of 1
 * is a column of n boxes. */
static void random3d_seeded(void) {
  us_Structure *a = random3d(15, 3, 7, 200), *b = random3d(15, 3, 7, 200), *c = random3d(15, 3, 8, 200);
  us_Structure *col = random3d(6, 1, 3, 10);
  CHECK(a && b && c && col);
  int same = a->nbody == b->nbody, differs = 0;
  for (int i = 0; same && i < a->nbody; i++)
    same = !memcmp(a->bodies[i].com, b->bodies[i].com, sizeof a->bodies[i].com);
  for (int i = 0; i < a->nbody && i < c->nbody; i++)
    differs |= memcmp(a->bodies[i].com, c->bodies[i].com, sizeof a->bodies[i].com) != 0;
  int column = col->nbody == 6 && fabs(col->bbox3[5] - 3.0) < 1e-12 && col->bbox3[3] == 1.0;
  us_structure_free(a), us_structure_free(b), us_structure_free(c), us_structure_free(col);
  CHECK(same);
  CHECK(differs);
  CHECK(column);
}

/* Whole tests that start from the last standing whole's forces (the local
 * tests' base, carried over) keep the boxes the slow path keeps (every
 * whole tested from scratch on the full system), with the same number of
 * whole tests, and send at most half of them to the full system; both
 * keep to the cone refinement budget of the drop tests. */
static void random3d_carried_forces(void) {
  int seeds = US_TEST_SANITIZED ? 1 : 3;
  long whole = 0, seeded = 0, full = 0;
  for (int seed = 1; seed <= seeds; seed++) {
    us_GenSettings g = us_gen_default_settings();
    us_Error err;
    g.n = 90, g.width = 8, g.seed = (unsigned long)seed, g.max_tries = 1000;
    us_Random3dStats fast, slow;
    us_Structure *a = us_gen_random3d_stats(&g, 0, &fast, &err);
    us_Structure *b = us_gen_random3d_stats(&g, 1, &slow, &err);
    CHECK(a && b);
    int same = a && b && a->nbody == b->nbody && a->ncontact == b->ncontact;
    for (int i = 0; same && i < a->nbody; i++)
      same = !memcmp(a->bodies[i].com, b->bodies[i].com, sizeof a->bodies[i].com);
    us_structure_free(a), us_structure_free(b);
    CHECK(same);
    CHECK_INT(fast.whole_tests, ==, slow.whole_tests);
    CHECK_INT(slow.full_lps, ==, slow.whole_tests);
    CHECK_INT(slow.seeded, ==, 0);
    CHECK_INT(fast.cone_rounds_max, <=, US_RANDOM3D_CONE_ROUNDS); /* the drop tests' budget */
    CHECK_INT(slow.cone_rounds_max, <=, US_RANDOM3D_CONE_ROUNDS);
    whole += fast.whole_tests, seeded += fast.seeded, full += fast.full_lps;
  }
  CHECK(whole > 10);      /* the cheap tests leave some drops to the whole test */
  CHECK(seeded >= whole - seeds); /* every whole test after a seed's first starts from forces */
  CHECK(2 * full <= whole);
}

static void random3d_bad_settings(void) {
  us_Error err;
  us_GenSettings g = us_gen_default_settings();
  g.width = 0.5;
  CHECK(us_gen_random3d(&g, &err) == NULL && err.code == US_ERR_USAGE && strstr(err.msg, "width"));
  g = us_gen_default_settings(), g.n = 0;
  CHECK(us_gen_random3d(&g, &err) == NULL && err.code == US_ERR_USAGE && strstr(err.msg, "blocks"));
}

/* --------------------------------------------------- wall3d with returns */

/* A walled corner (4 courses of 6 columns, returns of 3 bricks at both
 * ends; src/gen/corner.c): 4 (6 + 2 x 3) - 2 bricks (the odd courses'
 * main walls lose a brick to the returns' through bricks); it stands, the
 * planner takes it apart one brick at a time, and the order re-checks
 * step by step (us_verify_order: fresh tests, certificates re-checked). */
static void wall3d_corner_plans(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.rows = 4, g.cols = 6, g.returns = 3;
  us_Structure *s = us_gen_wall3d(&g, &err);
  CHECK(s != NULL);
  int nb = s->nbody;
  us_Verdict v = verdict_of(s, NULL);
  us_PlanSettings set = us_plan_default_settings();
  us_StabilitySettings sset = us_stability_default_settings();
  us_Plan p = {0};
  us_VerifyReport rep = {0};
  us_Status st = us_plan(s, &set, &p, &err);
  int found = !st && p.status == US_PLAN_FOUND, steps = found ? p.nsteps : -1;
  us_Status vst = found ? us_verify_order(s, &sset, p.order, p.nsteps, &rep, &err) : US_ERR_USAGE;
  us_plan_free(&p);
  us_structure_free(s);
  CHECK_INT(nb, ==, 4 * (6 + 2 * 3) - 2);
  CHECK_INT(v, ==, US_STABLE);
  CHECK(found);
  CHECK_INT(steps, ==, nb);
  CHECK_INT(vst, ==, US_OK);
  CHECK(rep.ok);
}

US_TEST_MAIN(T(dome_layout), T(dome_cap), T(dome_stands), T(dome_one_at_a_time), T(dome_chamfer), T(dome_default_none), T(dome_none_one_at_a_time), T(dome_bad_settings),
             T(jenga_layout), T(jenga_removals), T(jenga_ids), T(jenga_bad_settings),
             T(random3d_stands), T(random3d_fewer), T(random3d_seeded), T(random3d_carried_forces),
             T(random3d_bad_settings),
             T(wall3d_corner_plans))
