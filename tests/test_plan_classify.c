/* Tests of src/plan/classify.c: the classes of structures whose classes are
 * known by hand (a column, the cantilever with its counterweight, two slabs
 * leaning on each other, an arch, a block on a ramp, structures that do not
 * stand), the top-down probe's limit, a differential test of every class
 * against brute force over all sub-assemblies of random piles (the greedy
 * "remove the highest body" simulated directly, the smallest K by a
 * dynamic programme over subsets, the count by ground connectivity),
 * the claim of docs/classify.md that frictionless strong and weak
 * stability coincide (LP and LCP verdicts on every sub-assembly, and the
 * LCP's accelerations from different starting points), the class "stands
 * only with equality constraints" on known answers and against lp_solve on
 * every sub-assembly of random piles (tests/piles.h), argument errors and
 * out-of-memory paths. */
#include "extrude.h"
#include "piles.h"
#include "plan/hook.h"
#include "scenes.h"
#include "test.h"

#include "stability/certificate.h" /* the bilateral re-check, run again here */
#include "stability/stability.h"   /* us_stability_set_bilateral */

#include "stability/lcp.h" /* the LCP solver, driven directly by the Gauss tests */
#include "stability/lcp_sys.h"

#define PI 3.14159265358979323846

/* Sanitizer builds look for memory errors, not statistics (CMakeLists.txt):
 * the random differential tests run a quarter or a third of their cases
 * there; the checks that every kind of case occurred stay. */
#ifdef US_TEST_SANITIZED
#define BRUTE_TRIALS 150
#define GAUSS_TRIALS 20
#else
#define BRUTE_TRIALS 600
#define GAUSS_TRIALS 60
#endif

/* ----------------------------------------------------------------- scenes */

/* tests/test_plan.c's cantilever: pier P, spacer S and plank L on it, the
 * heavy counterweight C (highest) on S and the plank's inner end. Removing
 * C first tips the plank: the plank must go first. */
/* tests/test_plan.c's inverted V: two mirrored slabs touching along x = 1,
 * y 1.5..2. Hand statics (docs/classify.md): mu* = 13/165. */
/* The arch of us_gen_arch (src/gen/arch.c), built here because this test
 * links the planner only: n voussoirs b1..bn between the semicircles of
 * radii R -+ t/2 centred at (R + t/2, 0), radial joints, springings on
 * y = 0. */
static void arch_point(int i, int n, double cx, double rad, double *x, double *y) {
  if (i == 0 || i == n) {
    *x = cx + (i == 0 ? -rad : rad);
    *y = 0.0;
    return;
  }
  double th = PI * (1.0 - (double)i / (double)n);
  *x = cx + rad * cos(th);
  *y = rad * sin(th);
}

static us_Structure *arch(int n, double R, double t, double mu) {
  double ri = R - 0.5 * t, ro = R + 0.5 * t;
  us_Structure *s = us_structure_new(2);
  s->friction = mu;
  char id[16];
  for (int i = 0; i < n; i++) {
    double q[8];
    arch_point(i, n, ro, ri, &q[0], &q[1]);
    arch_point(i + 1, n, ro, ri, &q[2], &q[3]);
    arch_point(i + 1, n, ro, ro, &q[4], &q[5]);
    arch_point(i, n, ro, ro, &q[6], &q[7]);
    snprintf(id, sizeof id, "b%d", i + 1);
    scene_polygon(s, id, 4, q, 0);
  }
  return scene_seal(s);
}

/* A square block (side 0.5) on the slope of a fixed wedge of angle alpha:
 * mu* = tan alpha (its centre stays over its base below 45 degrees). */
static us_Structure *ramp(double alpha, double mu) {
  double c = cos(alpha), s = sin(alpha), d = 1.5, b = 0.5, run = 4.0;
  double wedge[6] = {0, 0, run, 0, run, run * s / c};
  double blk[8] = {d * c,         d * s,         (d + b) * c,     (d + b) * s,
                   (d + b) * c - b * s, (d + b) * s + b * c, d * c - b * s, d * s + b * c};
  us_Structure *st = us_structure_new(2);
  st->friction = mu;
  scene_polygon(st, "wedge", 3, wedge, 1);
  scene_polygon(st, "block", 4, blk, 0);
  return scene_seal(st);
}

/* A plank on a short pier, its centre beyond the pier's edge: falls at any
 * mu (it tips). */
static us_Structure *overhang(void) {
  us_Structure *s = us_structure_new(2);
  scene_box(s, "pier", 0, 0, 1, 1, 1);
  scene_box(s, "plank", 0.2, 1, 2.5, 0.2, 1);
  return scene_seal(s);
}

static int classify(const us_Structure *s, const us_ClassifySettings *set, us_Classification *c) {
  us_Error err;
  us_Status st = us_classify(s, set, c, &err);
  if (st != US_OK) fprintf(stderr, "classify: %s: %s\n", us_status_name(st), err.msg);
  return st == US_OK;
}

static int has_id(const us_Structure *s, const us_Classification *c, const char *id) {
  for (int k = 0; k < c->nblocked; k++)
    if (!strcmp(s->bodies[c->blocked[k]].id, id)) return 1;
  return 0;
}

/* ----------------------------------------------------- known classes */

static void column_is_topdown(void) {
  us_Structure *s = scene_column(5);
  CHECK(s);
  us_Classification c;
  CHECK(classify(s, NULL, &c));
  CHECK(c.stands && c.stands_frictionless && c.stands_some_mu && c.strong_equals_weak);
  CHECK_NEAR(c.mu_critical, 0.0, 0.0);
  CHECK_INT(c.friction_probes, ==, 1);
  CHECK_INT(c.topdown, ==, 1);
  CHECK_INT(c.dfs_status, ==, US_PLAN_FOUND);
  CHECK_INT(c.rejected, ==, 0);
  CHECK_INT(c.backtracks, ==, 0);
  CHECK_INT(c.dfs_tests, ==, 5); /* the full column, then every top removed (the empty goal untested) */
  CHECK(c.sequence);
  CHECK_INT(c.nblocked, ==, 0);
  CHECK_INT(c.min_group, ==, 1);
  CHECK_INT(c.count_status, ==, US_COUNT_EXACT);
  CHECK(c.count && !strcmp(c.count, "6")); /* a path: the n + 1 prefixes */
  CHECK(c.seconds >= 0 && c.t_count >= 0);
  us_classification_free(&c);
  us_structure_free(s);
}

static void cantilever_needs_backtracking(void) {
  us_Structure *s = scene_cantilever();
  CHECK(s);
  us_Classification c;
  CHECK(classify(s, NULL, &c));
  CHECK(c.stands && c.stands_frictionless);
  CHECK_INT(c.topdown, ==, 0);
  CHECK_INT(c.dfs_status, ==, US_PLAN_FOUND);
  CHECK_INT(c.rejected, ==, 1); /* removing C, the highest, tips the plank */
  CHECK_INT(c.backtracks, ==, 0);
  CHECK(c.sequence);
  CHECK_INT(c.min_group, ==, 1);
  us_classification_free(&c);
  us_structure_free(s);
}

static void leaning_slabs_need_friction_and_pairs(void) {
  us_Structure *s = scene_leaning(0.5);
  CHECK(s);
  us_Classification c;
  CHECK(classify(s, NULL, &c));
  CHECK(c.stands && !c.stands_frictionless && c.stands_some_mu && !c.strong_equals_weak);
  CHECK_NEAR(c.mu_critical, 13.0 / 165.0, 1e-6);
  CHECK_INT(c.topdown, ==, 0);
  CHECK_INT(c.dfs_status, ==, US_PLAN_NONE);
  CHECK(!c.sequence);
  CHECK_INT(c.nbuildable, ==, 0);
  CHECK_INT(c.nblocked, ==, 2);
  CHECK(has_id(s, &c, "left") && has_id(s, &c, "right"));
  CHECK_INT(c.min_group, ==, 2);
  CHECK(c.count && !strcmp(c.count, "4"));
  us_classification_free(&c);
  us_structure_free(s);
  /* below mu* the pair falls: no K at all; mu* ignores the own coefficient */
  s = scene_leaning(0.07);
  CHECK(s);
  CHECK(classify(s, NULL, &c));
  CHECK(!c.stands && c.stands_some_mu);
  CHECK_NEAR(c.mu_critical, 13.0 / 165.0, 1e-6);
  CHECK_INT(c.dfs_status, ==, US_PLAN_UNSTABLE);
  CHECK_INT(c.topdown, ==, 0);
  CHECK(!c.sequence);
  CHECK_INT(c.sequence_status, ==, US_PLAN_UNSTABLE);
  CHECK_INT(c.group_status, ==, US_PLAN_UNSTABLE);
  CHECK_INT(c.min_group, ==, 0);
  CHECK_INT(c.nblocked, ==, 0);
  us_classification_free(&c);
  us_structure_free(s);
}

static void arch_needs_a_group(void) {
  us_Structure *s = arch(10, 3.0, 0.5, 0.5);
  CHECK(s);
  us_Classification c;
  CHECK(classify(s, NULL, &c));
  CHECK(c.stands && !c.stands_frictionless && c.stands_some_mu);
  CHECK(c.mu_critical > 0.1 && c.mu_critical < 0.5);
  CHECK_INT(c.topdown, ==, 0);
  CHECK(!c.sequence);
  /* R* is the two springers on each side; the crown b3..b8 must go at once */
  CHECK_INT(c.nbuildable, ==, 4);
  CHECK_INT(c.nblocked, ==, 6);
  char id[32];
  for (int i = 3; i <= 8; i++) {
    snprintf(id, sizeof id, "b%d", i);
    CHECK(has_id(s, &c, id));
  }
  CHECK_INT(c.sequence_status, ==, US_PLAN_NONE);
  CHECK_INT(c.group_status, ==, US_PLAN_FOUND);
  CHECK_INT(c.min_group, ==, 6);
  CHECK_INT(c.group_bound, ==, 6);
  us_classification_free(&c);
  us_structure_free(s);
}

static void ramp_needs_tan_alpha(void) {
  const double deg[] = {10, 25, 40};
  for (int k = 0; k < 3; k++) {
    double al = deg[k] * PI / 180, t = tan(al);
    us_Structure *s = ramp(al, t + 0.05);
    CHECK(s);
    us_Classification c;
    CHECK(classify(s, NULL, &c));
    CHECK(c.stands && !c.stands_frictionless);
    CHECK_NEAR(c.mu_critical, t, 1e-6);
    CHECK(c.sequence && c.topdown == 1 && c.min_group == 1);
    us_classification_free(&c);
    us_structure_free(s);
    s = ramp(al, t - 0.05); /* slides: stands only above tan alpha */
    CHECK(s);
    CHECK(classify(s, NULL, &c));
    CHECK(!c.stands && c.stands_some_mu);
    CHECK_NEAR(c.mu_critical, t, 1e-6);
    CHECK_INT(c.min_group, ==, 0);
    us_classification_free(&c);
    us_structure_free(s);
  }
}

static void overhang_stands_for_no_mu(void) {
  us_Structure *s = overhang();
  CHECK(s);
  us_Classification c;
  CHECK(classify(s, NULL, &c));
  CHECK(!c.stands && !c.stands_frictionless && !c.stands_some_mu && !c.strong_equals_weak);
  CHECK(isinf(c.mu_critical));
  CHECK_INT(c.unstable_body, ==, us_structure_find_body(s, "plank"));
  CHECK_INT(c.dfs_status, ==, US_PLAN_UNSTABLE);
  CHECK_INT(c.topdown, ==, 0);
  CHECK_INT(c.rejected, ==, 0);
  CHECK(!c.sequence);
  CHECK_INT(c.group_status, ==, US_PLAN_UNSTABLE);
  CHECK_INT(c.min_group, ==, 0);
  CHECK_INT(c.group_tests, ==, 0); /* decided without the group search */
  CHECK(c.count && !strcmp(c.count, "3"));
  us_classification_free(&c);
  us_structure_free(s);
}

/* ------------------------------------ stands only with equality constraints */

/* Class 8 of one structure: equality, stands_bilateral (0 when it stands:
 * the bilateral test is not run, -1 then). */
static void check_equality(us_Structure *s, int stands, int equality, int bilateral) {
  CHECK(s);
  us_Classification c;
  CHECK(classify(s, NULL, &c));
  CHECK_INT(c.stands, ==, stands);
  CHECK_INT(c.equality, ==, equality);
  CHECK_INT(c.stands_bilateral, ==, bilateral);
  CHECK(!c.undecided);
  if (bilateral == 0) /* not even bilateral: the evidence was checked */
    CHECK(c.bilateral_loose || c.bilateral_mechanism);
  us_classification_free(&c);
  us_structure_free(s);
}

/* Hand-derived answers. Bilateral joints: every contact point carries a
 * free force (normal and tangential, either sign); a face contact is two
 * such points (its ends), so it transmits any force and moment: two bodies
 * on a face act as one rigid body; a single point transmits no moment. */
static void equality_known_answers(void) {
  /* the overhang: plank [0.2, 2.7] x [1, 1.2] on the pier [0, 1]^2; the
     plank's centre x = 1.45 is past the pier's corner x = 1, so it tips
     (no push at x in [0.2, 1] has a moment about its centre of the right
     sign). Bilateral: moments about x = 1: the joint at x = 0.2 pulls down
     with 0.45 / 0.8 of the plank's weight; the pier and plank (centre
     (0.5 * 1 + 1.45 * 0.5) / 1.5 = 0.82 in [0, 1]) stand on the ground
     -> yes */
  check_equality(overhang(), 0, 1, 1);
  /* a column stands already -> no */
  check_equality(scene_column(5), 1, 0, -1);
  /* the arch of arch_needs_a_group stands -> no */
  check_equality(arch(10, 3.0, 0.5, 0.5), 1, 0, -1);
  /* an overhang stack (no counterweight): 1 x 0.25 blocks at x0 = 0, 0.6,
     1.2: the top's centre 1.7 is past the middle's edge 1.6, so it tips;
     bilateral: every joint is a face (overlaps of 0.4), so the stack is
     one rigid body held by the ground face [0, 1] -> yes */
  us_Structure *s = us_structure_new(2);
  for (int i = 0; i < 3; i++) {
    char id[32];
    snprintf(id, sizeof id, "s%d", i);
    scene_box(s, id, 0.6 * i, 0.25 * i, 1.0, 0.25, 1.0);
  }
  check_equality(scene_seal(s), 0, 1, 1);
  /* a block touching nothing (the pier stands, the cloud 2 away from
     everything falls whatever joints are) -> no, a loose body */
  s = us_structure_new(2);
  scene_box(s, "pier", 0, 0, 1, 1, 1.0);
  scene_box(s, "cloud", 3, 3, 1, 1, 1.0);
  s = scene_seal(s);
  CHECK(s);
  us_Classification c;
  CHECK(classify(s, NULL, &c));
  CHECK(!c.stands && c.equality == 0 && c.stands_bilateral == 0 && c.bilateral_loose);
  CHECK_INT(c.bilateral_body, ==, us_structure_find_body(s, "cloud"));
  us_classification_free(&c);
  us_structure_free(s);
  /* a quadrilateral on its vertex (0, 0): the one point joint gives a
     force through (0, 0) and no moment; the centre of mass is off the
     vertical through it (x = -0.03 from the area-weighted triangles), so
     gravity turns it about (0, 0): a mechanism even bilateral -> no */
  s = us_structure_new(2);
  const double quad[8] = {0, 0, 1, 1, 0.2, 2, -1.3, 1};
  scene_polygon(s, "d", 4, quad, 0);
  s = scene_seal(s);
  CHECK(s && s->ncontact == 1);
  CHECK(fabs(s->bodies[0].com[0]) > 0.01);
  CHECK(classify(s, NULL, &c));
  CHECK(!c.stands && c.equality == 0 && c.stands_bilateral == 0 && !c.bilateral_loose);
  CHECK(c.bilateral_mechanism);
  us_classification_free(&c);
  /* 3D, the same extruded 1 deep and turned: the overhang's joint is a
     face (four corners) -> yes; the quadrilateral rests on an edge (two
     points on one line, no moment about it) -> no, a mechanism */
  us_Structure *o = overhang();
  CHECK(o);
  check_equality(test_extrude(o, 1.0, 0.3, 0.0, 0.0), 0, 1, 1);
  us_structure_free(o);
  us_Structure *e = test_extrude(s, 1.0, 0.3, 0.0, 0.0);
  CHECK(e);
  CHECK(classify(e, NULL, &c));
  CHECK(!c.stands && c.equality == 0 && c.stands_bilateral == 0 && c.bilateral_mechanism);
  us_classification_free(&c);
  us_structure_free(e);
  us_structure_free(s);
}

/* The overhang's bilateral certificate pulls (a negative normal): it
 * passes the bilateral re-check and fails the unilateral one; the LCP
 * methods refuse bilateral joints. */
static void bilateral_certificate_modes(void) {
  us_Structure *s = overhang();
  CHECK(s);
  us_StabilitySettings set = us_stability_default_settings();
  us_Stability *w = us_stability_new(s, &set, NULL);
  CHECK(w && us_stability_set_bilateral(w, 1) == 0);
  us_StabilityResult res;
  us_stability_result_init(&res);
  CHECK(us_stability_test_full(w, &res, NULL) == US_OK);
  CHECK_INT(res.verdict, ==, US_STABLE);
  CHECK(res.check.ok && res.forces.ncontact > 0);
  us_Bitset all = {0};
  CHECK(us_structure_movable_set(s, &all) == 0);
  double acc[US_CERT_ACC * 2];
  unsigned char seen[16];
  CHECK(s->ncontact <= 16);
  us_CertCheck bi, uni = us_certificate_check(s, &all, &res.forces, set.cert_tol);
  us_certificate_check_mode(s, &all, &res.forces, set.cert_tol, 1, acc, seen, &bi);
  CHECK(bi.ok && !uni.ok);
  CHECK(uni.max_sign_violation > set.cert_tol); /* the pull, refused */
  us_bitset_free(&all);
  us_stability_result_free(&res);
  us_stability_free(w);
  set.method = US_METHOD_LCP;
  w = us_stability_new(s, &set, NULL);
  CHECK(w && us_stability_set_bilateral(w, 1) == -1);
  us_stability_free(w);
  us_structure_free(s);
}

/* The verdicts of every subset (n <= 10) with joints (bilateral 1) or
 * contacts; with joints, every stable claim's forces re-checked here in
 * that mode and (CLP) every unstable one carrying a checked mechanism. */
static signed char *joint_verdicts(const us_Structure *s, us_Method method, int bilateral,
                                   int *bad) {
  unsigned N = 1u << s->nbody;
  signed char *v = us_malloc(N);
  us_StabilitySettings set = us_stability_default_settings();
  set.method = method;
  us_Stability *w = us_stability_new(s, &set, NULL);
  if (!v || !w || us_stability_set_bilateral(w, bilateral)) {
    us_free(v);
    us_stability_free(w);
    return NULL;
  }
  us_StabilityResult res;
  us_stability_result_init(&res);
  us_Bitset b;
  us_bitset_init(&b, s->nbody);
  double *acc = us_malloc(US_CERT_ACC * (size_t)s->nbody * sizeof(double));
  unsigned char *seen = us_malloc((size_t)s->ncontact + 1);
  for (unsigned m = 0; m < N; m++) {
    b.w[0] = m;
    v[m] = us_stability_test(w, &b, &res, NULL) == US_OK ? res.verdict == US_STABLE : -1;
    if (res.verdict == US_UNDECIDED) v[m] = -1;
    if (!bilateral) continue;
    if (res.verdict == US_STABLE) {
      us_CertCheck ck;
      us_certificate_check_mode(s, &b, &res.forces, set.cert_tol, 1, acc, seen, &ck);
      *bad += !ck.ok;
    }
    if (res.verdict == US_UNSTABLE && method == US_METHOD_LP) /* lp_solve gives no ray */
      *bad += !(res.mechanism.nbody > 0 && res.mechanism.ok);
  }
  us_free(acc);
  us_free(seen);
  us_bitset_free(&b);
  us_stability_result_free(&res);
  us_stability_free(w);
  return v;
}

/* On every sub-assembly of random piles: joints stand whenever contacts
 * do (a superset: a unilateral solution is a bilateral one), CLP and
 * lp_solve (the independent reference) agree on the bilateral verdict,
 * every bilateral certificate and mechanism passes the re-check; and the
 * case "joints only" occurs. */
static void bilateral_superset_on_piles(void) {
  unsigned long long rng = 0x5eedb11a7e1aULL;
  long subsets = 0, only_joints = 0, neither = 0;
  int bad = 0, disagree = 0, lost = 0, undecided = 0;
  for (int t = 0; t < BRUTE_TRIALS / 10; t++) {
    us_Structure *s = pile_random(&rng, 4 + t % 5);
    if (!s) continue;
    signed char *uni = joint_verdicts(s, US_METHOD_LP, 0, &bad);
    signed char *clp = joint_verdicts(s, US_METHOD_LP, 1, &bad);
    signed char *lps = joint_verdicts(s, US_METHOD_LPSOLVE, 1, &bad);
    CHECK(uni && clp && lps);
    for (unsigned m = 0; uni && clp && lps && m < (1u << s->nbody); m++) {
      subsets++;
      if (uni[m] < 0 || clp[m] < 0 || lps[m] < 0) {
        undecided++;
        continue;
      }
      lost += uni[m] && !clp[m];
      disagree += clp[m] != lps[m];
      only_joints += !uni[m] && clp[m];
      neither += !clp[m];
    }
    us_free(uni);
    us_free(clp);
    us_free(lps);
    us_structure_free(s);
  }
  printf("  %ld subsets: %ld stand only with joints, %ld not even so\n", subsets, only_joints,
         neither);
  CHECK_INT(lost, ==, 0);
  CHECK_INT(disagree, ==, 0);
  CHECK_INT(bad, ==, 0);
  CHECK_INT(undecided, ==, 0);
  CHECK(only_joints > 0 && neither > 0);
}

/* The probe's limit: unknown only when no move failed before it. */
static void topdown_probe_limit(void) {
  us_Structure *s = scene_column(30);
  CHECK(s);
  us_ClassifySettings set = us_classify_default_settings();
  set.max_tests = 10;
  us_Classification c;
  CHECK(classify(s, &set, &c));
  CHECK_INT(c.dfs_status, ==, US_PLAN_LIMIT);
  CHECK_INT(c.topdown, ==, -1);
  CHECK(c.dfs_tests <= 10);
  CHECK(c.sequence && c.min_group == 1); /* the other classes have no limit */
  us_classification_free(&c);
  set.max_tests = 0; /* none */
  CHECK(classify(s, &set, &c));
  CHECK_INT(c.topdown, ==, 1);
  CHECK_INT(c.dfs_tests, ==, 30);
  us_classification_free(&c);
  us_structure_free(s);
  s = scene_cantilever();
  CHECK(s);
  set.max_tests = 3; /* the full structure, C (rejected), L: then the limit */
  CHECK(classify(s, &set, &c));
  CHECK_INT(c.dfs_status, ==, US_PLAN_LIMIT);
  CHECK_INT(c.rejected, ==, 1);
  CHECK_INT(c.topdown, ==, 0); /* a rejection before the limit proves it */
  us_classification_free(&c);
  us_structure_free(s);
}

/* Running bond, rows of `cols` unit bricks, odd rows shifted by half a
 * brick and one brick shorter. */
static us_Structure *wall(int rows, int cols) {
  us_Structure *s = us_structure_new(2);
  char id[32];
  for (int r = 0; r < rows; r++)
    for (int c = 0; c < cols - (r & 1); c++) {
      snprintf(id, sizeof id, "w%d_%d", r, c);
      scene_box(s, id, c + 0.5 * (r & 1), 0.5 * r, 1, 0.5, 1);
    }
  return scene_seal(s);
}

/* The searches' time limit: a class cut there is unknown, with what was
 * proven before the cut. A bevelled dome of 5 courses of 8 is `none` one
 * voussoir at a time at once (the cut, exact.c), but its smallest K is
 * beyond the exact decision in half a second (K = 7 and up: the cut no
 * longer proves it, the exhaustive search runs for minutes), and its
 * friction bisection is usually cut by the same limit. Only what holds
 * whatever the machine's speed is asserted: the group search is cut
 * (minutes against half a second), the sequence search and the bisection
 * are cut or end, never undecided. (The 30-voussoir arch, this test's
 * structure before the cut, now gets K = 20 in 0.04 s; its 30 s limit is
 * a ceiling.) */
static void time_limit_leaves_classes_unknown(void) {
  us_GenSettings g = us_gen_default_settings();
  g.n = 5, g.segments = 8;
  us_Error err;
  us_Structure *s = us_gen_dome(&g, &err);
  CHECK(s);
  us_ClassifySettings set = us_classify_default_settings();
  set.time_limit = 0.5;
  set.count_time_limit = 0.1;
  us_Classification c;
  CHECK(classify(s, &set, &c));
  CHECK(c.stands);
  /* the bisection is usually cut (a fast machine may end it): never undecided */
  CHECK(c.friction_undecided == 0);
  CHECK(c.friction_timed_out || (c.stands_some_mu && !c.stands_frictionless && c.mu_critical > 0));
  CHECK(!c.undecided); /* unknown classes, no undecided test */
  /* the sequence search usually finishes in time (none, a proof); on a
     loaded machine it may be cut too: then nothing past it is known */
  CHECK(c.sequence_status == US_PLAN_NONE || c.sequence_status == US_PLAN_LIMIT);
  CHECK(c.sequence_status == US_PLAN_LIMIT || c.nblocked > 0);
  CHECK_INT(c.group_status, ==, US_PLAN_LIMIT);
  CHECK_INT(c.min_group, ==, 0);
  if (c.sequence_status == US_PLAN_NONE) CHECK(c.group_bound >= 1 && c.group_bound < 40);
  else CHECK_INT(c.group_bound, ==, 0);
  us_classification_free(&c);
  us_structure_free(s);
  s = arch(30, 3.0, 0.5, 0.5); /* the cut proves K = 1 .. 19 impossible */
  CHECK(s);
  set.time_limit = 30;
  CHECK(classify(s, &set, &c));
  CHECK_INT(c.sequence_status, ==, US_PLAN_NONE);
  CHECK_INT(c.group_status, ==, US_PLAN_FOUND);
  CHECK_INT(c.min_group, ==, 20);
  us_classification_free(&c);
  us_structure_free(s);
  s = scene_column(4);
  CHECK(s);
  set.time_limit = 1e-9; /* every search is cut at its first test */
  CHECK(classify(s, &set, &c));
  CHECK(c.stands && !c.stands_frictionless && c.friction_timed_out); /* unknown, not "no" */
  CHECK(!c.stands_some_mu && c.friction_undecided == 0 && !c.undecided);
  CHECK_INT(c.dfs_status, ==, US_PLAN_LIMIT);
  CHECK_INT(c.topdown, ==, -1);
  CHECK_INT(c.sequence_status, ==, US_PLAN_LIMIT);
  CHECK(!c.sequence);
  CHECK_INT(c.group_status, ==, US_PLAN_LIMIT);
  CHECK_INT(c.min_group, ==, 0);
  CHECK(c.count && !strcmp(c.count, "5"));
  us_classification_free(&c);
  us_structure_free(s);
}

/* A count past its time limit is a refusal with its reason, not an error;
 * the other classes are unaffected. */
static void count_refusal_is_reported(void) {
  us_Structure *s = wall(10, 10);
  CHECK(s);
  us_ClassifySettings set = us_classify_default_settings();
  set.count_time_limit = 1e-9;
  us_Classification c;
  CHECK(classify(s, &set, &c));
  CHECK_INT(c.count_status, ==, US_COUNT_REFUSED_TIME);
  CHECK(c.count == NULL);
  CHECK(strstr(c.count_note, "time"));
  CHECK(c.stands && c.stands_frictionless && c.topdown == 1 && c.min_group == 1);
  CHECK_INT(c.nbody, ==, 95);
  us_classification_free(&c);
  us_structure_free(s);
}

/* --------------------------------------- brute force over sub-assemblies */

/* Boxes dropped onto the skyline of the boxes below, each near the centre
 * of an earlier box (or anywhere on the ground), some of them heavy, with
 * widths, heights and offsets on a grid so that tops and sides meet:
 * towers, bridges (redundant contacts), overhangs and counterweights;
 * friction mu.
 * NULL when a draw overlaps. */
static us_Structure *random_pile(int n, double mu, unsigned long long *rng) {
  us_Structure *s = us_structure_new(2);
  s->friction = mu;
  SceneSkyline sky = {0};
  char id[16];
  for (int i = 0; i < n; i++) {
    double w = 0.5 * (1 + (int)(3 * test_rnd(rng))), x0 = 2.0 * test_rnd(rng);
    int on = (int)(test_rnd(rng) * (i + 1)) - 1; /* -1: the ground */
    if (on >= 0) x0 = 0.5 * (sky.x0[on] + sky.x1[on]) - w * test_rnd(rng);
    x0 = 0.25 * floor(4 * x0); /* on a grid: edges and tops meet */
    double y = scene_landing(&sky, x0, w);
    double h = test_rnd(rng) < 0.5 ? 0.25 : 0.5; /* equal tops: bridges */
    scene_skyline_add(&sky, x0, w, y + h);
    snprintf(id, sizeof id, "r%d", i);
    scene_box(s, id, x0, y, w, h, test_rnd(rng) < 0.25 ? 5.0 : 1.0);
  }
  us_Error err;
  if (us_structure_finalize(s, &err) != US_OK) {
    us_structure_free(s);
    return NULL;
  }
  return s;
}

/* A backend's verdict on every subset (all bodies movable, n <= 12); adds
 * its LP fallbacks to *fallbacks (may be NULL). */
static signed char *all_verdicts(const us_Structure *s, us_Method method, long *fallbacks) {
  unsigned N = 1u << s->nbody;
  signed char *v = us_malloc(N);
  us_StabilitySettings set = us_stability_default_settings();
  set.method = method;
  us_Stability *w = us_stability_new(s, &set, NULL);
  us_StabilityResult res;
  memset(&res, 0, sizeof res);
  us_Bitset b;
  us_bitset_init(&b, s->nbody);
  for (unsigned m = 0; m < N; m++) {
    b.w[0] = m;
    v[m] = us_stability_test(w, &b, &res, NULL) == US_OK ? res.verdict == US_STABLE : -1;
  }
  if (fallbacks) *fallbacks += us_stability_info(w)->lp_fallbacks;
  us_bitset_free(&b);
  us_stability_result_free(&res);
  us_stability_free(w);
  return v;
}

/* One LP test of the full structure. */
static int full_stands(const us_Structure *s) {
  us_StabilitySettings set = us_stability_default_settings();
  us_Stability *w = us_stability_new(s, &set, NULL);
  us_StabilityResult res;
  memset(&res, 0, sizeof res);
  int v = w && us_stability_test_full(w, &res, NULL) == US_OK && res.verdict == US_STABLE;
  us_stability_result_free(&res);
  us_stability_free(w);
  return v;
}

/* The greedy of the source's DFS run directly: remove the highest body
 * (top of the polygon, then centre height, then index) while the rest
 * stands. */
static int highest(const us_Structure *s, unsigned m) {
  int best = -1;
  double bt = 0, bc = 0;
  for (int i = 0; i < s->nbody; i++) {
    if (!(m >> i & 1)) continue;
    const us_Body *b = &s->bodies[i];
    double top = b->verts[1];
    for (int k = 1; k < b->nvert; k++) top = fmax(top, b->verts[2 * k + 1]);
    if (best < 0 || top > bt || (top == bt && b->com[1] > bc)) best = i, bt = top, bc = b->com[1];
  }
  return best;
}

static int ref_topdown(const us_Structure *s, const signed char *stable) {
  unsigned m = (1u << s->nbody) - 1;
  if (!stable[m]) return 0;
  while (m) {
    m &= ~(1u << highest(s, m));
    if (m && !stable[m]) return 0; /* the empty goal is not tested */
  }
  return 1;
}

/* Can m be emptied in steps of at most k bodies through standing sets? */
static int ref_reach(unsigned m, int k, const signed char *stable, signed char *memo) {
  if (m == 0) return 1;
  if (!stable[m]) return 0;
  if (memo[m] >= 0) return memo[m];
  int ok = 0;
  for (unsigned r = m; r && !ok; r = (r - 1) & m) /* non-empty subsets r of m */
    if (__builtin_popcount(r) <= k) ok = ref_reach(m & ~r, k, stable, memo);
  memo[m] = (signed char)ok;
  return ok;
}

/* The smallest K, 0 when the full structure does not stand. */
static int ref_min_group(int n, const signed char *stable) {
  unsigned N = 1u << n;
  if (!stable[N - 1]) return 0;
  signed char *memo = us_malloc(N);
  int k = 1;
  for (; k <= n; k++) {
    memset(memo, -1, N);
    if (ref_reach(N - 1, k, stable, memo)) break;
  }
  us_free(memo);
  return k;
}

/* Subsets S with S + ground connected in the contact graph. */
static long ref_count(const us_Structure *s) {
  long count = 0;
  for (unsigned m = 0; m < 1u << s->nbody; m++) {
    unsigned reached = 0, grew = 1;
    while (grew) {
      grew = 0;
      for (int c = 0; c < s->ncontact; c++) {
        int a = s->contacts[c].a, b = s->contacts[c].b;
        int ina = a < 0 || (reached >> a & 1), inb = reached >> b & 1;
        if (!(m >> b & 1) || (a >= 0 && !(m >> a & 1)) || ina == inb) continue;
        reached |= ina ? 1u << b : 1u << a;
        grew = 1;
      }
    }
    count += reached == m;
  }
  return count;
}

/* Every class against brute force on random piles (at most a fifteenth of them
 * unstable: they are most draws and all alike). */
static void classes_match_brute_force(void) {
  int seen[4] = {0, 0, 0, 0}, tried = 0; /* topdown, backtracking, groups, unstable */
  unsigned long long rng = 2026;
  for (int trial = 0; trial < BRUTE_TRIALS; trial++) {
    us_Structure *s = random_pile(4 + trial % 6, trial % 3 ? 0.6 : 0.0, &rng);
    if (!s) continue;
    if (seen[3] >= BRUTE_TRIALS / 15 && !full_stands(s)) { /* quota of unstable piles reached */
      us_structure_free(s);
      continue;
    }
    signed char *stable = all_verdicts(s, US_METHOD_LP, NULL);
    int td = ref_topdown(s, stable), k = ref_min_group(s->nbody, stable);
    us_Classification c;
    memset(&c, 0, sizeof c);
    int ok = classify(s, NULL, &c);
    if (ok && (c.topdown != td || c.min_group != k))
      fprintf(stderr, "trial %d: topdown %d vs %d, K %d vs %d\n", trial, c.topdown, td,
              c.min_group, k);
    int agree = ok && (c.stands == stable[(1u << s->nbody) - 1] && c.topdown == td &&
                         c.min_group == k && c.sequence == (k == 1) &&
                         (c.nblocked > 0) == (k > 1) && c.count && atol(c.count) == ref_count(s));
    tried++, seen[td ? 0 : k == 1 ? 1 : k > 1 ? 2 : 3]++;
    us_classification_free(&c);
    us_free(stable);
    us_structure_free(s);
    CHECK(agree);
  }
  printf("brute force: %d piles: %d top-down, %d backtracking, %d groups, %d unstable\n", tried,
         seen[0], seen[1], seen[2], seen[3]);
  CHECK(tried >= BRUTE_TRIALS / 3);
  CHECK(seen[0] > 0 && seen[1] > 0 && seen[2] > 0 && seen[3] > 0);
}

/* ------------------------------------- frictionless: strong = weak (Gauss) */

/* Every subset of frictionless piles: the LP, the LCP from scratch and the
 * LCP with reuse along a random walk (a different start per visit) give
 * the same verdict; the LCP decided nearly all of them itself (a
 * degenerate run goes to the LP, counted as a fallback). */
static void frictionless_verdicts_agree(void) {
  long subsets = 0, stable = 0, tests = 0, fallbacks = 0;
  unsigned long long rng = 1994;
  for (int trial = 0; trial < GAUSS_TRIALS; trial++) {
    us_Structure *s = random_pile(3 + trial % 6, 0.0, &rng);
    if (!s) continue;
    signed char *lp = all_verdicts(s, US_METHOD_LP, NULL);
    signed char *lcp = all_verdicts(s, US_METHOD_LCP, &fallbacks);
    us_StabilitySettings set = us_stability_default_settings();
    set.method = US_METHOD_LCP_REUSE;
    us_Stability *w = us_stability_new(s, &set, NULL);
    us_StabilityResult res;
    memset(&res, 0, sizeof res);
    us_Bitset b;
    us_bitset_init(&b, s->nbody);
    unsigned N = 1u << s->nbody, m = N - 1;
    int agree = 1;
    for (unsigned step = 0; step < 4 * N && agree; step++) {
      m ^= 1u << (int)(test_rnd(&rng) * s->nbody); /* one body in or out */
      b.w[0] = m;
      agree = us_stability_test(w, &b, &res, NULL) == US_OK && (res.verdict == US_STABLE) == lp[m];
    }
    for (unsigned q = 0; q < N && agree; q++) agree = lcp[q] == lp[q];
    for (unsigned q = 0; q < N; q++) stable += lp[q];
    subsets += N;
    tests += 5 * (long)N; /* lcp on every subset, lcp-reuse on the walk */
    fallbacks += us_stability_info(w)->lp_fallbacks;
    us_bitset_free(&b);
    us_stability_result_free(&res);
    us_stability_free(w);
    us_free(lp);
    us_free(lcp);
    us_structure_free(s);
    CHECK(agree);
  }
  printf("gauss: %ld sub-assemblies, %ld stable, same verdict from lp, lcp, lcp-reuse (%ld of %ld "
         "LCP tests settled by the LP)\n", subsets, stable, fallbacks, tests);
  CHECK(subsets > 1000 && stable > 100 && stable < subsets);
  CHECK(fallbacks * 100 < tests);
}

/* The solver of src/stability/lcp.h on one frictionless structure. */
typedef struct Gauss {
  const us_Structure *s;
  unsigned long long *rng; /* the order of a scratch run's drives */
  us_LcpSys sys;
  us_Lcp lcp;
  int *idx, *act;
  double *v; /* [3 nbody] accelerations of the last run */
} Gauss;

static int gauss_init(Gauss *g, const us_Structure *s, unsigned long long *rng) {
  memset(g, 0, sizeof *g);
  g->s = s;
  g->rng = rng;
  if (us_lcp_sys_init(&g->sys, s)) return -1;
  us_LcpOps ops = us_lcp_sys_ops(&g->sys);
  if (us_lcp_init(&g->lcp, 2 * s->ncontact, &ops)) return -1;
  g->idx = us_malloc((size_t)(2 * s->ncontact + 1) * sizeof(int));
  g->act = us_malloc((size_t)(s->ncontact + 1) * sizeof(int));
  g->v = us_calloc(3 * (size_t)s->nbody, sizeof(double));
  return g->idx && g->act && g->v ? 0 : -1;
}

static void gauss_free(Gauss *g) {
  us_lcp_free(&g->lcp);
  us_lcp_sys_free(&g->sys);
  us_free(g->idx);
  us_free(g->act);
  us_free(g->v);
}

/* Present flags and normalized gravity (m g / W) of subset m. */
static void gauss_bodies(Gauss *g, unsigned m) {
  const us_Structure *s = g->s;
  for (int b = 0; b < s->nbody; b++) {
    g->sys.present[b] = (unsigned char)(m >> b & 1);
    for (int k = 0; k < 3; k++)
      g->sys.fext[3 * b + k] = k < 2 ? s->bodies[b].mass * s->gravity[k] / s->weight : 0.0;
  }
}

/* The normal indices of the contacts active in m, into g->idx. */
static int gauss_active(Gauss *g, unsigned m) {
  us_Bitset b;
  us_bitset_init(&b, g->s->nbody);
  b.w[0] = m;
  int k = us_active_contacts(g->s, &b, g->act);
  us_bitset_free(&b);
  for (int j = 0; j < k; j++) g->idx[j] = 2 * g->act[j];
  return k;
}

/* From scratch, the contacts driven in a random order. */
static us_LcpResult gauss_scratch(Gauss *g, unsigned m) {
  us_lcp_reset(&g->lcp);
  gauss_bodies(g, m);
  int k = gauss_active(g, m);
  for (int j = k - 1; j > 0; j--) {
    int r = (int)(test_rnd(g->rng) * (j + 1)), t = g->idx[j];
    g->idx[j] = g->idx[r];
    g->idx[r] = t;
  }
  us_lcp_add(&g->lcp, g->idx, k);
  return us_lcp_run(&g->lcp);
}

/* From the solution of `from` (one body more or less), as lcp-reuse: the
 * leaving body's contacts faded out, the new ones added with zero force. */
static us_LcpResult gauss_reuse(Gauss *g, unsigned from, unsigned to) {
  int k = 0;
  for (int c = 0; c < g->s->ncontact; c++) {
    int a = g->s->contacts[c].a, b = g->s->contacts[c].b;
    int gone = (b >= 0 && (from & ~to) >> b & 1) || (a >= 0 && (from & ~to) >> a & 1);
    if (gone && g->lcp.live[2 * c]) g->idx[k++] = 2 * c;
  }
  gauss_bodies(g, to);
  us_LcpResult r = k ? us_lcp_fade(&g->lcp, g->idx, k) : US_LCP_SOLVED;
  if (r != US_LCP_SOLVED) return r;
  int na = gauss_active(g, to), nn = 0;
  for (int j = 0; j < na; j++)
    if (!g->lcp.live[g->idx[j]]) g->idx[nn++] = g->idx[j];
  us_lcp_add(&g->lcp, g->idx, nn);
  return us_lcp_run(&g->lcp);
}

/* Body accelerations v = M^-1 (F + E f) of the last run into g->v; the
 * largest net wrench component. */
static double gauss_accel(Gauss *g) {
  const us_LcpSys *y = &g->sys;
  double *u = g->v, worst = 0;
  memcpy(u, y->fext, 3 * (size_t)y->nbody * sizeof(double));
  for (int c = 0; c < y->ncontact; c++)
    for (int side = 0; side < 2; side++) {
      int b = y->cb[2 * c + side];
      if (b < 0 || !y->present[b] || !g->lcp.live[2 * c]) continue;
      const double *w = us_lcp_sys_w(y, 2 * c, side);
      for (int k = 0; k < 3; k++) u[3 * b + k] += g->lcp.f[2 * c] * w[k];
    }
  for (int b = 0; b < y->nbody; b++)
    for (int k = 0; k < 3; k++) {
      if (!y->present[b]) u[3 * b + k] = 0;
      worst = fmax(worst, fabs(u[3 * b + k]));
      u[3 * b + k] *= y->minv[3 * b + k];
    }
  return worst;
}

static double max_diff(const double *a, const double *b, int n) {
  double d = 0;
  for (int i = 0; i < n; i++) d = fmax(d, fabs(a[i] - b[i]));
  return d;
}

/* Per structure: the first solved run's accelerations of every subset. */
typedef struct Runs {
  int nv, nf;
  double *ref, *f0;
  unsigned char *have;
  long solved, failed, forces_differ;
} Runs;

/* Compare the run just made on subset m with the LP's verdict and with
 * the first run on m: 0 agrees, -1 not (message printed). */
static int compare_run(Gauss *g, Runs *r, unsigned m, us_LcpResult res, int lp_stable) {
  if (res != US_LCP_SOLVED) return r->failed++, 0; /* no solution to compare */
  r->solved++;
  double w = gauss_accel(g), *ref = r->ref + m * (size_t)r->nv;
  int clear = w <= 1e-9 || w >= 1e-6, zero = w <= 1e-9;
  if (!r->have[m]) {
    r->have[m] = 1;
    memcpy(ref, g->v, (size_t)r->nv * sizeof(double));
    memcpy(r->f0 + m * (size_t)r->nf, g->lcp.f, (size_t)r->nf * sizeof(double));
  }
  double dv = max_diff(g->v, ref, r->nv), df = max_diff(g->lcp.f, r->f0 + m * (size_t)r->nf, r->nf);
  r->forces_differ += df > 1e-6;
  if (clear && zero == lp_stable && dv <= 1e-8) return 0;
  fprintf(stderr, "subset %#x: net wrench %.3g, LP %s, accelerations differ by %.3g\n", m, w,
          lp_stable ? "stable" : "unstable", dv);
  return -1;
}

/* Uniqueness itself: on every subset of frictionless piles the LCP, solved
 * from scratch with the contacts driven in three random orders and
 * repaired from the previous subset of a random walk (as lcp-reuse does),
 * reaches the same body accelerations, zero exactly where the LP says the
 * subset stands, also where the contact forces it reaches differ. */
static void frictionless_accelerations_unique(void) {
  long subsets = 0;
  Runs tot;
  memset(&tot, 0, sizeof tot);
  unsigned long long rng = 1829;
  for (int trial = 0; trial < GAUSS_TRIALS; trial++) {
    us_Structure *s = random_pile(3 + trial % 6, 0.0, &rng);
    if (!s) continue;
    Gauss g;
    CHECK(gauss_init(&g, s, &rng) == 0);
    signed char *lp = all_verdicts(s, US_METHOD_LP, NULL);
    unsigned N = 1u << s->nbody, m = N - 1;
    Runs r = tot;
    r.nv = 3 * s->nbody;
    r.nf = 2 * s->ncontact;
    r.ref = us_malloc(N * (size_t)r.nv * sizeof(double));
    r.f0 = us_malloc(N * (size_t)r.nf * sizeof(double) + 1);
    r.have = us_calloc(N, 1);
    int bad = 0;
    for (unsigned q = 0; q < N && !bad; q++)
      for (int rep = 0; rep < 3 && !bad; rep++) bad = compare_run(&g, &r, q, gauss_scratch(&g, q), lp[q]);
    gauss_scratch(&g, m);
    for (unsigned step = 0; step < 4 * N && !bad; step++) {
      unsigned to = m ^ 1u << (int)(test_rnd(&rng) * s->nbody);
      us_LcpResult res = gauss_reuse(&g, m, to);
      if (res != US_LCP_SOLVED) res = gauss_scratch(&g, to); /* as the backend restarts */
      bad = compare_run(&g, &r, to, res, lp[to]);
      m = to;
    }
    tot.solved = r.solved, tot.failed = r.failed, tot.forces_differ = r.forces_differ;
    subsets += N;
    us_free(r.ref);
    us_free(r.f0);
    us_free(r.have);
    us_free(lp);
    gauss_free(&g);
    us_structure_free(s);
    CHECK(!bad);
  }
  printf("gauss: %ld sub-assemblies, %ld LCP solutions (%ld runs failed), %ld with other forces, "
         "same accelerations\n", subsets, tot.solved, tot.failed, tot.forces_differ);
  CHECK(subsets > 1000);
  CHECK(tot.failed * 50 < tot.solved); /* nearly every run gives a solution */
  CHECK(tot.forces_differ > 0);        /* and different solutions were reached */
}

/* ---------------------------------------------------- errors and memory */

static void argument_errors(void) {
  us_Classification c;
  us_Error err;
  CHECK_INT(us_classify(NULL, NULL, &c, &err), ==, US_ERR_USAGE);
  CHECK(c.count == NULL && c.blocked == NULL);
  us_Structure *s = scene_column(2);
  CHECK(s);
  CHECK_INT(us_classify(s, NULL, NULL, &err), ==, US_ERR_USAGE);
  CHECK_INT(us_classify(s, NULL, NULL, NULL), ==, US_ERR_USAGE); /* err may be NULL */
  CHECK_OK(us_classify(s, NULL, &c, NULL), &err);
  us_classification_free(&c);
  us_classification_free(&c); /* twice is harmless */
  us_classification_free(NULL);
  us_ClassifySettings set = us_classify_default_settings();
  set.stability.method = (us_Method)99;
  CHECK_INT(us_classify(s, &set, &c, &err), ==, US_ERR_USAGE);
  us_structure_free(s);
  s = us_structure_new(2);
  scene_box(s, "raw", 0, 0, 1, 1, 1);
  CHECK_INT(us_classify(s, NULL, &c, &err), ==, US_ERR_USAGE); /* not finalized */
  CHECK(strstr(err.msg, "finalized"));
  us_structure_free(s);
}

/* --------------------------------------------------------- undecided */

static void all_undecided(void *user, const us_Bitset *node, us_StabilityResult *res) {
  (void)node;
  if (user) ++*(long *)user;
  res->verdict = US_UNDECIDED;
  snprintf(res->note, sizeof res->note, "test hook");
}

/* Tests that cannot be decided never decide a class: with every test of
 * the planner undecided (the test-only hook, src/plan/hook.h) the column
 * neither stands nor falls, top-down is unknown, and the sequence and
 * group classes are undecided, not none; with a certificate tolerance no
 * rounding meets (1e-300) the friction probes of the ramp are undecided
 * too. */
static void undecided_tests_decide_no_class(void) {
  us_Structure *s = scene_column(3);
  CHECK(s);
  us_Classification c;
  long calls = 0;
  us_plan_set_test_hook(all_undecided, &calls);
  int ok = classify(s, NULL, &c);
  us_plan_set_test_hook(NULL, NULL);
  CHECK(ok);
  CHECK(calls >= 3);
  CHECK(!c.stands && c.stands_undecided);
  CHECK_INT(c.unstable_body, ==, -1);
  CHECK(c.stands_frictionless); /* the friction probes are not hooked */
  CHECK_INT(c.topdown, ==, -1);
  CHECK_INT(c.dfs_status, ==, US_PLAN_UNDECIDED);
  CHECK(c.dfs_undecided >= 1);
  CHECK_INT(c.sequence_status, ==, US_PLAN_UNDECIDED);
  CHECK(!c.sequence);
  CHECK_INT(c.group_status, ==, US_PLAN_UNDECIDED);
  CHECK_INT(c.min_group, ==, 0);
  CHECK(c.undecided);
  us_classification_free(&c);
  /* decided: the same column, no hook */
  CHECK(classify(s, NULL, &c));
  CHECK(c.stands && !c.stands_undecided && !c.undecided && c.topdown == 1);
  us_classification_free(&c);
  us_structure_free(s);
  s = ramp(30 * PI / 180, 0.8);
  CHECK(s);
  us_ClassifySettings set = us_classify_default_settings();
  set.stability.cert_tol = 1e-300;
  CHECK(classify(s, &set, &c));
  CHECK(!c.stands && c.stands_undecided);
  CHECK(c.friction_undecided >= 1);
  CHECK(c.undecided);
  CHECK(c.sequence_status == US_PLAN_UNDECIDED);
  us_classification_free(&c);
  us_structure_free(s);
}

/* Fail the n-th allocation for every n until classify succeeds: every
 * failure is out of memory (or a backend's report of it), with nothing
 * leaked and an empty result; odd n with a NULL error pointer. */
static void out_of_memory_is_clean(void) {
  us_Structure *scenes[2] = {scene_leaning(0.5), arch(6, 3.0, 0.6, 0.5)};
  CHECK(scenes[0] && scenes[1]);
  for (int k = 0; k < 2; k++) {
    long live0 = us_alloc_live(), n = 0, runs = 0;
    for (;; n += 1 + n / 64, runs++) { /* every point up to 64, then a stride */
      us_Classification c;
      us_Error err;
      us_alloc_fail_after(n);
      us_Status st = us_classify(scenes[k], NULL, &c, n & 1 ? NULL : &err); /* NULL err too */
      us_alloc_fail_after(-1);
      if (st == US_OK) {
        CHECK(c.count != NULL && c.min_group > 1);
        us_classification_free(&c);
        break;
      }
      CHECK(st == US_ERR_NOMEM || st == US_ERR_SOLVER);
      CHECK(c.count == NULL && c.blocked == NULL);
      CHECK_INT(us_alloc_live(), ==, live0);
    }
    printf("oom: scene %d classified after %ld failing runs (%ld allocations)\n", k, runs, n);
    CHECK(runs > 50);
  }
  us_structure_free(scenes[0]);
  us_structure_free(scenes[1]);
}

/* Class 6 with friction (docs/classify.md): asked for, a box pinched
 * between fixed walls off the ground stands but is not strongly stable
 * (free fall with no wall force is a solution of the dynamics), and the
 * witness passes the independent check; the same box seated on the
 * ground is strongly stable; a frictionless column is, by the theorem,
 * without a search; not asked, the class is -2. */
static void strong_with_friction(void) {
  us_ClassifySettings set = us_classify_default_settings();
  us_Classification c;
  us_Error err;
  for (int seated = 0; seated < 2; seated++) {
    us_Structure *s = us_structure_new(2);
    double wl[8] = {0, 0, 1, 0, 1, 3, 0, 3}, wr[8] = {2, 0, 3, 0, 3, 3, 2, 3};
    scene_polygon(s, "left", 4, wl, 1);
    scene_polygon(s, "right", 4, wr, 1);
    scene_box(s, "box", 1, seated ? 0 : 1, 1, 1, 1);
    s = scene_seal(s);
    CHECK(s);
    set.strong = 0;
    CHECK_OK(us_classify(s, &set, &c, &err), &err);
    CHECK_INT(c.strong, ==, -2);
    us_classification_free(&c);
    set.strong = 1;
    CHECK_OK(us_classify(s, &set, &c, &err), &err);
    CHECK(c.stands);
    CHECK_INT(c.strong, ==, seated ? 1 : 0);
    CHECK_INT(c.strong_result.has_witness, ==, !seated);
    if (!seated) CHECK(us_strong_check(s, NULL, &c.strong_result, 1e-6, NULL, 0));
    us_classification_free(&c);
    us_structure_free(s);
  }
  us_Structure *col = scene_column(3);
  CHECK(col);
  CHECK_OK(us_classify(col, &set, &c, &err), &err);
  CHECK_INT(c.strong, ==, 1);
  CHECK_INT(c.strong_result.nodes, ==, 0);
  us_classification_free(&c);
  us_structure_free(col);
}

US_TEST_MAIN(T(column_is_topdown), T(cantilever_needs_backtracking),
             T(leaning_slabs_need_friction_and_pairs), T(arch_needs_a_group),
             T(ramp_needs_tan_alpha), T(overhang_stands_for_no_mu), T(equality_known_answers),
             T(bilateral_certificate_modes), T(bilateral_superset_on_piles), T(topdown_probe_limit), T(time_limit_leaves_classes_unknown), T(count_refusal_is_reported),
             T(classes_match_brute_force), T(frictionless_verdicts_agree),
             T(frictionless_accelerations_unique), T(argument_errors), T(undecided_tests_decide_no_class),
             T(out_of_memory_is_clean), T(strong_with_friction))
