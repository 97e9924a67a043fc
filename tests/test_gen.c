/* Tests of the structure generators (src/gen): body counts and ids, all
 * bodies movable, contact counts, geometry (shared edges, row lengths,
 * springings on the ground), that every generated structure stands under
 * the LP, that the arch needs every voussoir, reproducibility of the random
 * stacker, errors (bad settings, out of memory) without leaks, and that
 * the LCP backends give the LP's verdicts on generated structures. */
#include "scenes.h"
#include "test.h"

/* Verdict of the whole structure with the default (LP) settings, or -1 on
 * error. `skip` (>= 0) is a body left out. */
static int verdict_without(const us_Structure *s, int skip) {
  us_Error err;
  us_StabilitySettings set = us_stability_default_settings();
  us_Stability *w = us_stability_new(s, &set, &err);
  if (!w) return -1;
  us_Bitset b = {0};
  us_StabilityResult res;
  memset(&res, 0, sizeof res);
  int v = -1;
  if (!us_bitset_init(&b, s->nbody)) {
    us_bitset_fill(&b);
    if (skip >= 0) us_bitset_clear(&b, skip);
    if (us_stability_test(w, &b, &res, &err) == US_OK) v = (int)res.verdict;
    else fprintf(stderr, "stability test: %s\n", err.msg);
  }
  us_stability_result_free(&res);
  us_bitset_free(&b);
  us_stability_free(w);
  return v;
}

static int stands(const us_Structure *s) { return verdict_without(s, -1) == US_STABLE; }

/* Ids are b1..bn in order, every body is a movable polygon. */
static int ids_and_movable(const us_Structure *s) {
  char id[24];
  for (int i = 0; i < s->nbody; i++) {
    snprintf(id, sizeof id, "b%d", i + 1);
    if (strcmp(s->bodies[i].id, id) || s->bodies[i].fixed || s->bodies[i].nvert < 3 ||
        !(s->bodies[i].mass > 0))
      return 0;
  }
  return us_structure_movable_count(s) == s->nbody;
}

/* Contacts touching body i (as a or b). */
static int contacts_of(const us_Structure *s, int i) {
  int n = 0;
  for (int k = 0; k < s->ncontact; k++) n += s->contacts[k].a == i || s->contacts[k].b == i;
  return n;
}

/* Every body touches something at >= 2 points (nothing floats). */
static int all_supported(const us_Structure *s) {
  for (int i = 0; i < s->nbody; i++)
    if (contacts_of(s, i) < 2) return 0;
  return 1;
}

static void column(void) {
  us_Error err;
  us_GenSettings g = us_gen_default_settings();
  g.n = 7;
  us_Structure *s = us_gen_column(&g, &err);
  CHECK(s != NULL);
  CHECK_INT(s->nbody, ==, 7);
  CHECK(ids_and_movable(s));
  CHECK_INT(s->ncontact, ==, 2 * 7);
  CHECK_NEAR(s->friction, 0.5, 0);
  double bb[4];
  scene_body_box(s, 6, bb); /* b7 is the top block */
  CHECK_NEAR(bb[1], 6 * 0.5, 1e-12);
  CHECK_NEAR(bb[3], 7 * 0.5, 1e-12);
  CHECK_NEAR(bb[2] - bb[0], 1.0, 1e-12);
  /* mass from density: block area 0.5, density 2 */
  us_structure_free(s);
  g.density = 2.0;
  g.friction = 0.8;
  s = us_gen_column(&g, &err);
  CHECK(s != NULL);
  CHECK_NEAR(s->bodies[0].mass, 1.0, 1e-12);
  CHECK_NEAR(s->friction, 0.8, 0);
  CHECK(stands(s));
  us_structure_free(s);
}

static void pyramid(void) {
  us_Error err;
  us_GenSettings g = us_gen_default_settings();
  g.n = 13;
  us_Structure *s = us_gen_pyramid(&g, &err);
  CHECK(s != NULL);
  CHECK_INT(s->nbody, ==, 91);
  CHECK(ids_and_movable(s));
  CHECK(all_supported(s));
  /* the apex is centred over the base */
  double base[4], apex[4];
  scene_body_box(s, 0, base);
  scene_body_box(s, 90, apex);
  CHECK_NEAR(apex[0], 12 * 0.5, 1e-12);
  CHECK_NEAR(apex[1], 12 * 0.5, 1e-12);
  CHECK_NEAR(0.5 * (apex[0] + apex[2]), 0.5 * (s->bbox[0] + s->bbox[2]), 1e-12);
  /* 13 ground blocks: 2 ground contacts each */
  int ground = 0;
  for (int k = 0; k < s->ncontact; k++) ground += s->contacts[k].a == US_GROUND;
  CHECK_INT(ground, ==, 2 * 13);
  CHECK(stands(s));
  us_structure_free(s);
}

static void wall_small(void) {
  us_Error err;
  us_GenSettings g = us_gen_default_settings();
  g.rows = 4;
  g.cols = 3;
  us_Structure *s = us_gen_wall(&g, &err);
  CHECK(s != NULL);
  CHECK_INT(s->nbody, ==, 3 + 4 + 3 + 4);
  CHECK(ids_and_movable(s));
  CHECK(all_supported(s));
  /* every row spans [0, 3]; the odd rows start and end with half bricks */
  double bb[4];
  scene_body_box(s, 3, bb); /* b4: first of row 1 */
  CHECK_NEAR(bb[0], 0.0, 0);
  CHECK_NEAR(bb[2], 0.5, 1e-15);
  CHECK_NEAR(bb[1], 0.5, 1e-15);
  scene_body_box(s, 6, bb); /* b7: last of row 1 */
  CHECK_NEAR(bb[0], 2.5, 1e-15);
  CHECK_NEAR(bb[2], 3.0, 1e-15);
  CHECK_NEAR(s->bbox[2], 3.0, 1e-15);
  CHECK(stands(s));
  us_structure_free(s);
}

static void wall_large(void) {
  us_Error err;
  us_GenSettings g = us_gen_default_settings();
  g.rows = 25;
  g.cols = 40;
  us_Structure *s = us_gen_wall(&g, &err);
  CHECK(s != NULL);
  CHECK_INT(s->nbody, ==, 13 * 40 + 12 * 41);
  CHECK(ids_and_movable(s));
  CHECK(all_supported(s));
  CHECK_NEAR(s->bbox[2], 40.0, 1e-12);
  CHECK_NEAR(s->bbox[3], 12.5, 1e-12);
  CHECK(stands(s));
  us_structure_free(s);
}

static void arch(void) {
  us_Error err;
  us_GenSettings g = us_gen_default_settings();
  us_Structure *s = us_gen_arch(&g, &err);
  CHECK(s != NULL);
  CHECK_INT(s->nbody, ==, 10);
  CHECK(ids_and_movable(s));
  CHECK(all_supported(s));
  /* both springings stand on the ground: 2 ground contacts each, b1 at
   * the left and b10 at the right */
  int ground_l = 0, ground_r = 0;
  for (int k = 0; k < s->ncontact; k++)
    if (s->contacts[k].a == US_GROUND) {
      ground_l += s->contacts[k].b == 0;
      ground_r += s->contacts[k].b == 9;
    }
  CHECK_INT(ground_l, ==, 2);
  CHECK_INT(ground_r, ==, 2);
  CHECK_NEAR(s->bbox[0], 0.0, 1e-12);
  CHECK_NEAR(s->bbox[2], 2 * 3.25, 1e-12);
  CHECK_NEAR(s->bbox[3], 3.25, 1e-12);
  /* 9 joints, two contacts each, plus the ground */
  CHECK_INT(s->ncontact, ==, 9 * 2 + 4);
  CHECK(stands(s));
  /* every voussoir is needed: no first removal exists */
  for (int i = 0; i < s->nbody; i++) CHECK_INT(verdict_without(s, i), ==, US_UNSTABLE);
  us_structure_free(s);
}

/* The thrust line must fit in the ring: a thin semicircular ring falls, a
 * thicker one with fewer voussoirs stands. */
static void arch_thickness(void) {
  us_Error err;
  us_GenSettings g = us_gen_default_settings();
  g.thickness = 0.15; /* t / R = 0.05, well under the ~0.11 minimum */
  us_Structure *s = us_gen_arch(&g, &err);
  CHECK(s != NULL);
  CHECK_INT(verdict_without(s, -1), ==, US_UNSTABLE);
  us_structure_free(s);
  g.thickness = 0.6;
  g.n = 7;
  s = us_gen_arch(&g, &err);
  CHECK(s != NULL);
  CHECK(stands(s));
  us_structure_free(s);
}

/* Vertices of a and b identical (same bodies, same order). */
static int same_geometry(const us_Structure *a, const us_Structure *b) {
  if (a->nbody != b->nbody) return 0;
  for (int i = 0; i < a->nbody; i++) {
    if (a->bodies[i].nvert != b->bodies[i].nvert) return 0;
    if (memcmp(a->bodies[i].verts, b->bodies[i].verts,
               (size_t)a->bodies[i].nvert * 2 * sizeof(double)))
      return 0;
  }
  return 1;
}

static void random_stacker(void) {
  us_Error err;
  us_GenSettings g = us_gen_default_settings();
  g.width = 4;
  g.rows = 5;
  g.seed = 7;
  us_Structure *a = us_gen_random(&g, &err);
  CHECK(a != NULL);
  us_Structure *b = us_gen_random(&g, &err);
  CHECK(b != NULL);
  CHECK(same_geometry(a, b));
  g.seed = 8;
  us_Structure *c = us_gen_random(&g, &err);
  CHECK(c != NULL);
  int differ = !same_geometry(a, c);
  CHECK(ids_and_movable(a));
  CHECK(stands(a));
  CHECK(stands(c));
  /* the top row is reached, nothing is above it, blocks stay in [0, W] */
  CHECK_NEAR(a->bbox[3], 5 * 0.5, 1e-12);
  CHECK_NEAR(c->bbox[3], 5 * 0.5, 1e-12);
  CHECK(a->bbox[0] >= 0 && a->bbox[2] <= 4.0);
  us_structure_free(a);
  us_structure_free(b);
  us_structure_free(c);
  CHECK(differ);
}

/* Width 1: every block lands on the one below: a column of `rows`. */
static void random_narrow(void) {
  us_Error err;
  us_GenSettings g = us_gen_default_settings();
  g.rows = 6;
  us_Structure *s = us_gen_random(&g, &err);
  CHECK(s != NULL);
  CHECK_INT(s->nbody, ==, 6);
  CHECK_INT(s->ncontact, ==, 12);
  us_structure_free(s);
}

/* max_tries = 1 allows one attempt per rise of the highest row: on a wide
 * base (201 offsets) the second block almost surely lands beside the first
 * or fails, so the run gives up with US_ERR_INPUT (and nothing leaks). */
static void random_gives_up(void) {
  us_Error err;
  us_GenSettings g = us_gen_default_settings();
  g.width = 50;
  g.rows = 30;
  g.max_tries = 1;
  us_Structure *s = us_gen_random(&g, &err);
  if (s) { /* astronomically unlikely; still a valid outcome */
    us_structure_free(s);
    return;
  }
  CHECK_INT(err.code, ==, US_ERR_INPUT);
  CHECK(strstr(err.msg, "gave up") != NULL);
}

typedef us_Structure *(*GenFn)(const us_GenSettings *, us_Error *);

static int rejects(GenFn fn, const us_GenSettings *g) {
  us_Error err;
  us_error_clear(&err);
  us_Structure *s = fn(g, &err);
  if (s) {
    us_structure_free(s);
    return 0;
  }
  return err.code == US_ERR_USAGE && err.msg[0] != 0;
}

static void bad_settings(void) {
  GenFn all[] = {us_gen_column, us_gen_pyramid, us_gen_wall, us_gen_arch, us_gen_random};
  us_GenSettings d = us_gen_default_settings(), g;
  for (int k = 0; k < 5; k++) {
    CHECK(rejects(all[k], NULL));
    g = d, g.friction = -0.1;
    CHECK(rejects(all[k], &g));
    g = d, g.friction = NAN;
    CHECK(rejects(all[k], &g));
    g = d, g.density = 0;
    CHECK(rejects(all[k], &g));
  }
  g = d, g.n = 0;
  CHECK(rejects(us_gen_column, &g));
  CHECK(rejects(us_gen_pyramid, &g));
  CHECK(rejects(us_gen_arch, &g));
  g = d, g.n = 1;
  CHECK(rejects(us_gen_arch, &g));
  g = d, g.width = -1;
  CHECK(rejects(us_gen_column, &g));
  CHECK(rejects(us_gen_wall, &g));
  CHECK(rejects(us_gen_random, &g));
  g = d, g.width = 0.5; /* random: less than one block wide */
  CHECK(rejects(us_gen_random, &g));
  g = d, g.height = INFINITY;
  CHECK(rejects(us_gen_pyramid, &g));
  g = d, g.rows = 0;
  CHECK(rejects(us_gen_wall, &g));
  CHECK(rejects(us_gen_random, &g));
  g = d, g.cols = -3;
  CHECK(rejects(us_gen_wall, &g));
  g = d, g.radius = 0;
  CHECK(rejects(us_gen_arch, &g));
  g = d, g.thickness = 6.0; /* intrados radius 0 */
  CHECK(rejects(us_gen_arch, &g));
  g = d, g.max_tries = 0;
  CHECK(rejects(us_gen_random, &g));
  g = d, g.rows = 100000, g.cols = 100000; /* 10^10 bricks */
  CHECK(rejects(us_gen_wall, &g));
}

/* Fail the k-th allocation for every k until a generator succeeds: each
 * failure is US_ERR_NOMEM (leaks are checked by the harness). The random
 * stacker also goes through the stability workspace and its tests. */
static void out_of_memory(void) {
  GenFn all[] = {us_gen_column, us_gen_pyramid, us_gen_wall, us_gen_arch, us_gen_random};
  us_GenSettings g = us_gen_default_settings();
  g.n = 4, g.rows = 3, g.cols = 3, g.width = 2.5;
  for (int f = 0; f < 5; f++) {
    int done = 0;
    for (long k = 0; k < 10000 && !done; k++) {
      us_Error err;
      us_error_clear(&err);
      us_alloc_fail_after(k);
      us_Structure *s = all[f](&g, &err);
      us_alloc_fail_after(-1);
      if (s) done = 1, us_structure_free(s);
      else CHECK_INT(err.code, ==, US_ERR_NOMEM);
    }
    CHECK(done);
  }
}

/* Verdicts of the three backends (lp, lcp, lcp-reuse) along a walk over
 * sub-assemblies of s: random bodies removed one at a time, then added
 * back, each sub-assembly tested by all three (persistent workspaces, so
 * lcp-reuse reuses both ways). Returns the number of disagreements, or
 * -1 on error; counts verdicts. */
static int backends_walk(const us_Structure *s, unsigned long long *rng, long *counts) {
  const us_Method m[3] = {US_METHOD_LP, US_METHOD_LCP, US_METHOD_LCP_REUSE};
  us_Stability *w[3] = {NULL, NULL, NULL};
  us_Error err;
  us_Bitset sub = {0};
  int bad = -1;
  for (int k = 0; k < 3; k++) {
    us_StabilitySettings set = us_stability_default_settings();
    set.method = m[k];
    if (!(w[k] = us_stability_new(s, &set, &err))) goto done;
  }
  if (us_bitset_init(&sub, s->nbody)) goto done;
  us_bitset_fill(&sub);
  bad = 0;
  for (int step = 0, steps = 2 * s->nbody; step < steps; step++) {
    int v[3];
    for (int k = 0; k < 3; k++) {
      us_StabilityResult res;
      memset(&res, 0, sizeof res);
      v[k] = us_stability_test(w[k], &sub, &res, &err) == US_OK ? (int)res.verdict : -1;
      if (v[k] == US_STABLE && !res.check.ok) v[k] = -2;
      us_stability_result_free(&res);
    }
    if (v[0] < 0 || v[0] != v[1] || v[0] != v[2]) {
      fprintf(stderr, "disagreement: lp %d lcp %d lcp-reuse %d (%d of %d bodies, mu %.2f)\n", v[0],
              v[1], v[2], us_bitset_count(&sub), s->nbody, s->friction);
      bad++;
    } else {
      counts[v[0]]++;
    }
    int left = us_bitset_count(&sub), removing = step < steps / 2 ? left > 1 : 0;
    int i = (int)(test_rnd(rng) * s->nbody);
    while (us_bitset_get(&sub, i) != removing && left < s->nbody) i = (i + 1) % s->nbody;
    if (removing) us_bitset_clear(&sub, i);
    else if (left < s->nbody) us_bitset_set(&sub, i);
  }
done:
  us_bitset_free(&sub);
  for (int k = 0; k < 3; k++) us_stability_free(w[k]);
  return bad;
}

/* The LCP backends against the LP on the project's own generators
 * (columns, pyramids, walls, arches, the random stacker), frictionless
 * and with friction: the same verdict on every sub-assembly of a walk. */
#ifdef US_TEST_SANITIZED
#define GEN_AGREE_STRUCTURES 60 /* memory errors, not statistics (CMakeLists.txt) */
#else
#define GEN_AGREE_STRUCTURES 300
#endif

static void backends_agree_on_generated(void) {
  unsigned long long rng = 0x9e3779b97f4a7c15ULL;
  long counts[2] = {0, 0};
  int structures = 0, bad = 0;
  for (int t = 0; t < GEN_AGREE_STRUCTURES; t++) {
    us_GenSettings g = us_gen_default_settings();
    g.friction = t % 2 ? 0.2 + 0.6 * test_rnd(&rng) : 0.0;
    us_Error err;
    us_Structure *s = NULL;
    switch ((t / 2) % 5) {
    case 0: g.n = 2 + (int)(6 * test_rnd(&rng)); s = us_gen_column(&g, &err); break;
    case 1: g.n = 2 + (int)(4 * test_rnd(&rng)); s = us_gen_pyramid(&g, &err); break;
    case 2:
      g.rows = 2 + (int)(4 * test_rnd(&rng));
      g.cols = 2 + (int)(4 * test_rnd(&rng));
      s = us_gen_wall(&g, &err);
      break;
    case 3:
      g.n = 5 + (int)(8 * test_rnd(&rng));
      g.thickness = 0.3 + 0.6 * test_rnd(&rng);
      s = us_gen_arch(&g, &err);
      break;
    default:
      g.width = 3 + (int)(3 * test_rnd(&rng));
      g.rows = 3 + (int)(4 * test_rnd(&rng));
      g.seed = (unsigned long)t;
      s = us_gen_random(&g, &err);
      break;
    }
    CHECK(s != NULL);
    if (!s) continue;
    structures++;
    int r = backends_walk(s, &rng, counts);
    CHECK(r >= 0);
    bad += r > 0 ? r : 0;
    us_structure_free(s);
  }
  printf("generated: %d structures, %ld stable and %ld unstable sub-assemblies, lp = lcp = "
         "lcp-reuse on all but %d\n",
         structures, counts[US_STABLE], counts[US_UNSTABLE], bad);
  CHECK_INT(bad, ==, 0);
  /* both verdicts well represented (over 2/3 of a sub-assembly per structure each) */
  CHECK(counts[US_STABLE] > 2 * GEN_AGREE_STRUCTURES / 3 &&
        counts[US_UNSTABLE] > 2 * GEN_AGREE_STRUCTURES / 3);
}

US_TEST_MAIN(T(column), T(pyramid), T(wall_small), T(wall_large), T(arch), T(arch_thickness),
             T(random_stacker), T(random_narrow), T(random_gives_up), T(bad_settings),
             T(out_of_memory), T(backends_agree_on_generated))
