/* Tests of the source-style stacker (src/gen/stacker.c): the same seed
 * gives the same structure; the finished structure stands (default LP, its
 * own friction, also frictionless); block counts; geometry (quarter-block
 * coordinates inside [0, W], rows, every block on the row below or the
 * ground); cantilevers that do not stand alone on their supports exist,
 * and intermediate build stages (rows 0..r) do not all stand; bad settings
 * are rejected with a message; out of memory is clean. stacker_sizes
 * prints the generation times quoted in the file head. */
#include "scenes.h"
#include "test.h"
#include "gen/gen.h"

static us_Structure *stacker(int rows, double width, unsigned long seed, double mu) {
  us_Error err;
  us_GenSettings g = us_gen_default_settings();
  g.rows = rows, g.width = width, g.seed = seed, g.friction = mu;
  us_Structure *s = us_gen_stacker(&g, &err);
  if (!s) fprintf(stderr, "stacker %d x %g seed %lu: %s\n", rows, width, seed, err.msg);
  return s;
}

/* Verdict of the bodies in `present` (NULL: all) with the default settings
 * and friction mu at every contact (< 0: the structure's own); -1 on
 * error. */
static int verdict(us_Structure *s, const us_Bitset *present, double mu) {
  us_Error err;
  us_StabilitySettings set = us_stability_default_settings();
  double *keep = us_malloc((size_t)s->ncontact * sizeof *keep + 1);
  if (!keep) return -1;
  for (int k = 0; k < s->ncontact; k++) {
    keep[k] = s->contacts[k].mu;
    if (mu >= 0) s->contacts[k].mu = mu;
  }
  us_Stability *w = us_stability_new(s, &set, &err);
  us_StabilityResult res;
  memset(&res, 0, sizeof res);
  int v = -1;
  if (w && (present ? us_stability_test(w, present, &res, &err)
                    : us_stability_test_full(w, &res, &err)) == US_OK)
    v = (int)res.verdict;
  us_stability_result_free(&res);
  us_stability_free(w);
  for (int k = 0; k < s->ncontact; k++) s->contacts[k].mu = keep[k];
  us_free(keep);
  return v;
}

/* Contact k supports body i from below (normal pointing up into i). */
static int supports_from_below(const us_Contact *c, int i) {
  return (c->b == i && c->n[1] > 0.5) || (c->a == i && c->n[1] < -0.5);
}

/* A cantilever: i's centre of mass lies outside the x-extent of its
 * supporting contacts below. */
static int is_cantilever(const us_Structure *s, int i) {
  double lo = INFINITY, hi = -INFINITY;
  for (int k = 0; k < s->ncontact; k++)
    if (supports_from_below(&s->contacts[k], i))
      lo = fmin(lo, s->contacts[k].p[0]), hi = fmax(hi, s->contacts[k].p[0]);
  double x = s->bodies[i].com[0];
  return !(x >= lo && x <= hi);
}

static int count_cantilevers(const us_Structure *s) {
  int n = 0;
  for (int i = 0; i < s->nbody; i++) n += is_cantilever(s, i);
  return n;
}

/* Vertices of a and b identical (same bodies, same order). */
static int same_geometry(const us_Structure *a, const us_Structure *b) {
  if (a->nbody != b->nbody) return 0;
  for (int i = 0; i < a->nbody; i++)
    if (a->bodies[i].nvert != b->bodies[i].nvert ||
        memcmp(a->bodies[i].verts, b->bodies[i].verts,
               (size_t)a->bodies[i].nvert * 2 * sizeof(double)))
      return 0;
  return 1;
}

static void deterministic_per_seed(void) {
  us_Structure *a = stacker(14, 12, 5, 0.5), *b = stacker(14, 12, 5, 0.5);
  us_Structure *c = stacker(14, 12, 6, 0.5);
  int same = a && b && same_geometry(a, b), differ = a && c && !same_geometry(a, c);
  us_structure_free(a);
  us_structure_free(b);
  us_structure_free(c);
  CHECK(same);
  CHECK(differ);
}

/* Blocks lie on the quarter grid inside [0, W], in whole rows, 1 to 2
 * blocks wide (counterweights up to 3); ids b1..bn
 * row by row; every block rests on a block of the row below or the ground. */
static int geometry_ok(const us_Structure *s, double width, double h) {
  char id[24];
  double prev_y = 0, bb[4];
  for (int i = 0; i < s->nbody; i++) {
    snprintf(id, sizeof id, "b%d", i + 1);
    scene_body_box(s, i, bb);
    double r = bb[1] / h;
    if (strcmp(s->bodies[i].id, id) || s->bodies[i].nvert != 4 || bb[0] < 0 || bb[2] > width ||
        bb[0] * 4 != floor(bb[0] * 4) || bb[2] * 4 != floor(bb[2] * 4) || r != floor(r) ||
        bb[3] - bb[1] != h || bb[2] - bb[0] < 1 || bb[2] - bb[0] > 3 || bb[1] < prev_y)
      return fprintf(stderr, "body %s: [%g %g] x [%g %g]\n", s->bodies[i].id, bb[0], bb[2],
                     bb[1], bb[3]),
             0;
    prev_y = bb[1];
    int below = 0;
    for (int k = 0; k < s->ncontact; k++) below += supports_from_below(&s->contacts[k], i);
    if (below < 1) return fprintf(stderr, "body %s rests on nothing\n", s->bodies[i].id), 0;
  }
  return 1;
}

static void finished_structure_stands(void) {
  const double mus[3] = {0.5, 0.0, 0.8};
  for (int t = 0; t < 6; t++) {
    double mu = mus[t % 3];
    us_Structure *s = stacker(10 + 3 * t, 8 + 2 * t, (unsigned long)(100 + t), mu);
    CHECK(s != NULL);
    int stands = verdict(s, NULL, -1) == US_STABLE, flat = verdict(s, NULL, 0.0) == US_STABLE;
    int geo = geometry_ok(s, 8 + 2 * t, 0.5);
    CHECK_NEAR(s->friction, mu, 0);
    us_structure_free(s);
    CHECK(stands);
    CHECK(flat); /* it even stands without friction */
    CHECK(geo);
  }
}

/* About 80 blocks for 14 rows of width 12, never outside a wide band. */
static void block_counts(void) {
  int lo = 1 << 30, hi = 0, total = 0;
  for (unsigned long seed = 1; seed <= 10; seed++) {
    us_Structure *s = stacker(14, 12, seed, 0.5);
    CHECK(s != NULL);
    lo = s->nbody < lo ? s->nbody : lo, hi = s->nbody > hi ? s->nbody : hi, total += s->nbody;
    us_structure_free(s);
  }
  printf("14 x 12, seeds 1-10: %d to %d blocks, mean %.1f\n", lo, hi, total / 10.0);
  CHECK_INT(lo, >=, 50);
  CHECK_INT(hi, <=, 110);
  /* width 1: one block per row, a column */
  us_Structure *s = stacker(6, 1, 3, 0.5);
  CHECK(s != NULL);
  int n = s->nbody, nc = s->ncontact;
  us_structure_free(s);
  CHECK_INT(n, ==, 6);
  CHECK_INT(nc, ==, 12);
}

/* Cantilevers that would tip alone exist (5-30 %), and some intermediate
 * build stages (rows 0..r) do not stand while the whole does. */
static void cantilevers_need_the_rows_above(void) {
  int blocks = 0, cants = 0, fallen = 0, stages = 0;
  for (unsigned long seed = 1; seed <= 6; seed++) {
    us_Structure *s = stacker(14, 12, seed, 0.5);
    CHECK(s != NULL);
    blocks += s->nbody, cants += count_cantilevers(s);
    us_Bitset b;
    CHECK(us_bitset_init(&b, s->nbody) == 0);
    double bb[4];
    for (int r = 0; r < 13; r++, stages++) {
      for (int i = 0; i < s->nbody; i++) {
        scene_body_box(s, i, bb);
        if (bb[1] <= r * 0.5) us_bitset_set(&b, i);
      }
      fallen += verdict(s, &b, -1) == US_UNSTABLE;
    }
    us_bitset_free(&b);
    us_structure_free(s);
  }
  printf("cantilevers: %d of %d blocks (%.1f %%); %d of %d build stages do not stand\n", cants,
         blocks, 100.0 * cants / blocks, fallen, stages);
  CHECK(cants > 0);
  /* 5-30 %: a cantilever needs room for its counterweight's tail over B */
  CHECK(cants * 100 >= 5 * blocks && cants * 10 <= 3 * blocks);
  CHECK(fallen > 0);
}

typedef struct {
  us_GenSettings g;
  const char *frag;
} Bad;

static void bad_settings(void) {
  us_GenSettings d = us_gen_default_settings();
  Bad bad[] = {{d, "rows"}, {d, "rows"}, {d, "width"}, {d, "width"}, {d, "width"},
               {d, "limit"}, {d, "max_tries"}, {d, "friction"}, {d, "height"}};
  bad[0].g.rows = 0;
  bad[1].g.rows = -3;
  bad[2].g.width = 0.5;
  bad[3].g.width = NAN;
  bad[4].g.width = 1e9;
  bad[5].g.rows = 100000, bad[5].g.width = 1000; /* absurd: 10^8 block areas */
  bad[6].g.max_tries = 0;
  bad[7].g.friction = -1;
  bad[8].g.height = 0;
  for (size_t t = 0; t < sizeof bad / sizeof bad[0]; t++) {
    us_Error err;
    us_error_clear(&err);
    us_Structure *s = us_gen_stacker(&bad[t].g, &err);
    us_structure_free(s);
    if (s || err.code != US_ERR_USAGE || !strstr(err.msg, "stacker") ||
        !strstr(err.msg, bad[t].frag))
      fprintf(stderr, "case %zu: %s\n", t, err.msg);
    CHECK(s == NULL);
    CHECK_INT(err.code, ==, US_ERR_USAGE);
    CHECK(strstr(err.msg, "stacker") && strstr(err.msg, bad[t].frag));
  }
  us_Error err;
  CHECK(us_gen_stacker(NULL, &err) == NULL);
  CHECK_INT(err.code, ==, US_ERR_USAGE);
}

/* max_tries below the number of rows: the run gives up, naming why. */
static void gives_up(void) {
  us_Error err;
  us_GenSettings g = us_gen_default_settings();
  g.rows = 8, g.width = 6, g.max_tries = 5;
  us_Structure *s = us_gen_stacker(&g, &err);
  us_structure_free(s);
  CHECK(s == NULL);
  CHECK_INT(err.code, ==, US_ERR_INPUT);
  CHECK(strstr(err.msg, "gave up") != NULL);
}

/* Fail the k-th allocation for every k until the generator succeeds. */
static void out_of_memory(void) {
  us_GenSettings g = us_gen_default_settings();
  g.rows = 5, g.width = 6, g.seed = 2;
  int done = 0;
  for (long k = 0; k < 100000 && !done; k++) {
    us_Error err;
    us_error_clear(&err);
    us_alloc_fail_after(k);
    us_Structure *s = us_gen_stacker(&g, &err);
    us_alloc_fail_after(-1);
    if (s) done = 1, us_structure_free(s);
    else CHECK_INT(err.code, ==, US_ERR_NOMEM);
  }
  CHECK(done);
}

/* Generation times for about 80, 300 and 1,000 blocks (the figures in
 * src/gen/stacker.c); each structure stands. Smaller under sanitizers. */
static void stacker_sizes(void) {
#if defined(__SANITIZE_ADDRESS__)
  const int size[3][2] = {{14, 12}, {20, 20}, {24, 24}};
#else
  const int size[3][2] = {{14, 12}, {30, 30}, {60, 60}};
#endif
  for (int t = 0; t < 3; t++) {
    double t0 = us_now();
    us_Structure *s = stacker(size[t][0], size[t][1], 1, 0.5);
    double dt = us_now() - t0;
    CHECK(s != NULL);
    printf("stacker %d rows x width %d: %d blocks, %d cantilevers, %.2f s\n", size[t][0],
           size[t][1], s->nbody, count_cantilevers(s), dt);
    int stands = verdict(s, NULL, -1) == US_STABLE;
    us_structure_free(s);
    CHECK(stands);
  }
}

/* Carried forces and tests by change (stacker.c, test_T) decide every row
 * test as one LP of the whole structure does: the same structures, seed
 * by seed, with and without friction, low and tall. */
static void same_as_whole_lps(void) {
  static const int size[][2] = {{30, 30}, {14, 12}, {8, 30}, {24, 10}};
#ifdef US_TEST_SANITIZED
  const int nsize = 2; /* 30 x 30 seed 1 is the stack a wrong shortcut changes */
#else
  const int nsize = 4;
#endif
  int n = 0, cants = 0;
  for (int z = 0; z < nsize; z++)
    for (unsigned long seed = 1; seed <= (z == 0 ? 2u : 4u); seed++) {
      us_GenSettings g = us_gen_default_settings();
      g.rows = size[z][0], g.width = size[z][1], g.seed = seed;
      g.friction = seed % 2 ? 0.5 : 0.0;
      us_Error err;
      us_Structure *a = us_gen_stacker_ref(&g, 0, &err), *b = us_gen_stacker_ref(&g, 1, &err);
      CHECK(a != NULL && b != NULL);
      if (!same_geometry(a, b))
        fprintf(stderr, "%d x %d seed %lu: %d and %d bodies\n", size[z][0], size[z][1], seed,
                a->nbody, b->nbody);
      CHECK(same_geometry(a, b));
      n += a->nbody, cants += count_cantilevers(a);
      us_structure_free(a);
      us_structure_free(b);
    }
  CHECK_INT(cants, >, n / 20); /* the rows that need the counterweights' tests */
}

/* A deadline that has passed stops the generator with US_ERR_TIME_LIMIT
 * and no structure (it is read before every row attempt); a far one
 * changes nothing. */
static void deadline(void) {
  us_GenSettings g = us_gen_default_settings();
  g.rows = 14, g.width = 12, g.seed = 5;
  g.deadline = 1e-9; /* long past */
  us_Error err;
  us_Structure *s = us_gen_stacker(&g, &err);
  CHECK(s == NULL);
  CHECK_INT(err.code, ==, US_ERR_TIME_LIMIT);
  CHECK(strstr(err.msg, "stacker") && strstr(err.msg, "time limit"));
  g.deadline = us_now() + 3600;
  s = us_gen_stacker(&g, &err);
  us_Structure *ref = stacker(14, 12, 5, 0.5);
  CHECK(s && ref && same_geometry(s, ref));
  us_structure_free(s);
  us_structure_free(ref);
}

US_TEST_MAIN(T(deterministic_per_seed), T(same_as_whole_lps), T(deadline), T(finished_structure_stands), T(block_counts),
             T(cantilevers_need_the_rows_above), T(bad_settings), T(gives_up),
             T(out_of_memory), T(stacker_sizes))
