/* Tests of the random pile generator for differential tests (tests/piles.h):
 * over 2,000 piles of 4 to 12 bodies, each of the three planner outcomes
 * (an order exists, the pile stands but no one-at-a-time order exists, the
 * pile does not stand) occurs at least 200 times, by an exhaustive
 * reference; draws that overlap (finalize fails) stay under 20 %; piles
 * have the requested number of bodies and are reproducible per seed.
 *
 * The reference decides by a memoized search over sub-assemblies (bit
 * masks): reach(m) = m is empty, or m stands and reach(m - b) for some b.
 * Every sub-assembly is tested at most once, with the default stability
 * settings (the LP); unlike the full 2^n table only the stable ones
 * reachable from the whole pile are visited. */
#include "piles.h"
#include "test.h"

typedef struct Ref {
  const us_Structure *s;
  us_Stability *w;
  us_Bitset b;
  us_StabilityResult res;
  signed char *stable, *reach; /* per mask: -1 unknown */
  long tests;
} Ref;

/* Does sub-assembly m stand? (cached) */
static int ref_stable(Ref *r, unsigned m) {
  if (r->stable[m] < 0) {
    us_Error err;
    r->b.w[0] = m;
    r->stable[m] = (signed char)(us_stability_test(r->w, &r->b, &r->res, &err) == US_OK &&
                                 r->res.verdict == US_STABLE);
    r->tests++;
  }
  return r->stable[m];
}

/* Can m be taken apart one body at a time through standing sub-assemblies? */
static int ref_reach(Ref *r, unsigned m) {
  if (m == 0) return 1;
  if (r->reach[m] >= 0) return r->reach[m];
  int ok = 0;
  if (ref_stable(r, m))
    for (int i = 0; i < r->s->nbody && !ok; i++)
      if (m & (1u << i)) ok = ref_reach(r, m & ~(1u << i));
  r->reach[m] = (signed char)ok;
  return ok;
}

/* Outcome of pile s: 0 found, 1 none, 2 unstable, -1 on error. */
static int reference_outcome(const us_Structure *s, long *tests) {
  Ref r;
  memset(&r, 0, sizeof r);
  unsigned full = (1u << s->nbody) - 1;
  us_StabilitySettings set = us_stability_default_settings();
  int out = -1;
  r.s = s;
  r.stable = us_malloc((size_t)full + 1);
  r.reach = us_malloc((size_t)full + 1);
  r.w = us_stability_new(s, &set, NULL);
  if (r.stable && r.reach && r.w && !us_bitset_init(&r.b, s->nbody)) {
    memset(r.stable, -1, (size_t)full + 1);
    memset(r.reach, -1, (size_t)full + 1);
    out = !ref_stable(&r, full) ? 2 : ref_reach(&r, full) ? 0 : 1;
  }
  *tests += r.tests;
  us_bitset_free(&r.b);
  us_stability_result_free(&r.res);
  us_stability_free(r.w);
  us_free(r.stable);
  us_free(r.reach);
  return out;
}

#ifdef US_TEST_SANITIZED
#define GEN_PILES 100 /* memory errors, not statistics (CMakeLists.txt) */
#else
#define GEN_PILES 2000
#endif

static void outcomes_are_mixed(void) {
  unsigned long long rng = 20261123;
  int counts[3] = {0, 0, 0}, skipped = 0, by_n[13][3];
  long tests = 0;
  double t0 = us_now();
  memset(by_n, 0, sizeof by_n);
  for (int t = 0; t < GEN_PILES; t++) {
    int n = 4 + t % 9;
    us_Structure *s = pile_random(&rng, n);
    if (!s) {
      skipped++;
      continue;
    }
    CHECK_INT(s->nbody, ==, n);
    int o = reference_outcome(s, &tests);
    us_structure_free(s);
    CHECK(o >= 0);
    counts[o]++, by_n[n][o]++;
  }
  printf("%d piles in %.1f s (%ld stability tests): %d found, %d none, %d unstable, %d "
         "skipped (overlap)\n",
         GEN_PILES, us_now() - t0, tests, counts[0], counts[1], counts[2], skipped);
  for (int n = 4; n <= 12; n++)
    printf("  n = %2d: %3d found, %3d none, %3d unstable\n", n, by_n[n][0], by_n[n][1],
           by_n[n][2]);
  /* every outcome in at least a tenth of the piles, few skipped */
  CHECK_INT(counts[0], >=, GEN_PILES / 10);
  CHECK_INT(counts[1], >=, GEN_PILES / 10);
  CHECK_INT(counts[2], >=, GEN_PILES / 10);
  CHECK_INT(skipped, <, GEN_PILES / 5);
}

/* The same seed gives the same pile. */
static void reproducible(void) {
  unsigned long long a = 77, b = 77;
  for (int t = 0; t < 50; t++) {
    us_Structure *p = pile_random(&a, 4 + t % 9), *q = pile_random(&b, 4 + t % 9);
    int same = (!p && !q) || (p && q && p->nbody == q->nbody && p->ncontact == q->ncontact);
    for (int i = 0; same && p && i < p->nbody; i++)
      same = p->bodies[i].nvert == q->bodies[i].nvert &&
             !memcmp(p->bodies[i].verts, q->bodies[i].verts,
                     (size_t)p->bodies[i].nvert * 2 * sizeof(double));
    us_structure_free(p);
    us_structure_free(q);
    CHECK(same);
  }
}

US_TEST_MAIN(T(outcomes_are_mixed), T(reproducible))
