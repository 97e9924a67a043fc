/* The 3D LCP methods (lcp, lcp-reuse, lp-lcp) against the LP: the same
 * verdict on every sub-assembly of towers (straight and turned), pyramids,
 * walls, jenga, random piles and domes at mu 0, 0.2 and 0.5, under
 * vertical and tilted gravity, walked in the assembly and the removal
 * direction and at random (so lcp-reuse repairs its parent's solution both
 * ways); every stable verdict's certificate passes and every unstable one
 * carries a checked mechanism. Also extruded 2D structures (the planar
 * verdict), and rotations about the vertical and rigid rotations with
 * gravity turned along. */
#include "test.h"

#include "extrude.h"

#include "stability/lcp3_piv.h"

static const double PI = 3.14159265358979323846;

#ifdef US_TEST_SANITIZED
enum { SCALE = 16 }; /* a sixteenth of the sample under the sanitizers */
#else
enum { SCALE = 1 };
#endif

static double rnd(unsigned long long *s) { return test_lcg(s); }

/* Structure `kind` (0 tower, 1 turned tower, 2 pyramid3d, 3 wall3d, 4
 * jenga, 5 random3d, 6 dome) with friction mu, gravity tilted by `tilt`
 * radians towards azimuth `az`. */
static us_Structure *scene(int kind, double mu, double tilt, double az, unsigned seed) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.friction = mu;
  g.seed = seed;
  us_Structure *s = NULL;
  static const int rm[4] = {2, 1, 3, 3};
  switch (kind) {
  case 0: g.n = 6, s = us_gen_tower(&g, &err); break;
  case 1: g.n = 7, g.jitter = 35.0, s = us_gen_tower(&g, &err); break;
  case 2: g.n = 3, s = us_gen_pyramid3d(&g, &err); break;
  case 3: g.rows = 3, g.cols = 3, s = us_gen_wall3d(&g, &err); break;
  case 4: g.n = 4, g.remove = rm, g.nremove = 2, s = us_gen_jenga(&g, &err); break;
  case 5: g.n = 10, g.width = 2.5, s = us_gen_random3d(&g, &err); break;
  default: g.n = 4, g.segments = 8, s = us_gen_dome(&g, &err); break;
  }
  if (!s) {
    fprintf(stderr, "scene %d: %s\n", kind, err.msg);
    return NULL;
  }
  double gz = 9.81;
  s->gravity[0] = gz * sin(tilt) * cos(az);
  s->gravity[1] = gz * sin(tilt) * sin(az);
  s->gravity[2] = -gz * cos(tilt);
  return s;
}

typedef struct Tally {
  int every; /* lp-lcp joins every this many tests (its Lemke is dense); 0: 8 */
  long tests, stable, unstable, undecided_both, mech, nomech;
  long pivots, reused, fallbacks;
} Tally;

/* One workspace per method over the same walk of sub-assemblies. */
enum { NM = 4 };
static const us_Method METHODS[NM] = {US_METHOD_LP, US_METHOD_LCP, US_METHOD_LCP_REUSE,
                                      US_METHOD_LP_LCP};

/* The next sub-assembly of the walk, step t of n + n + extra: assembly
 * (prefixes), removal (shrinking suffix ends), then random subsets. */
static void walk_step(us_Bitset *b, int n, int t, unsigned long long *rng) {
  for (int i = 0; i < n; i++) {
    int on = t < n ? i <= t : t < 2 * n ? i < 2 * n - t : rnd(rng) < 0.75;
    if (on)
      us_bitset_set(b, i);
    else
      us_bitset_clear(b, i);
  }
}

/* Test one sub-assembly with every method; the verdicts must agree. */
static void compare_one(us_Stability **w, const us_Bitset *b, us_StabilityResult *r, Tally *t) {
  us_Error err;
  int nm = t->tests % (t->every > 0 ? t->every : 8) == 0 ? NM : NM - 1; /* lp-lcp sampled */
  for (int m = 0; m < nm; m++) {
    CHECK_OK(us_stability_test(w[m], b, &r[m], &err), &err);
    if (r[m].verdict == US_STABLE) CHECK(r[m].check.ok);
  }
  for (int m = 1; m < nm; m++) CHECK_INT(r[m].verdict, ==, r[0].verdict);
  t->tests++;
  t->stable += r[0].verdict == US_STABLE;
  t->unstable += r[0].verdict == US_UNSTABLE;
  t->undecided_both += r[0].verdict == US_UNDECIDED;
  for (int m = 1; m < 3 && r[0].verdict == US_UNSTABLE; m++) { /* a checked mechanism */
    if (r[m].mechanism.nbody == 0) { /* counted where the LP has one: a known gap */
      t->nomech += r[0].mechanism.nbody > 0;
      if (getenv("LCP3_VERBOSE") && r[0].mechanism.nbody > 0) { /* name the gap */
        fprintf(stderr, "no mechanism from %s where the LP has one, bodies:",
                us_method_name(METHODS[m]));
        for (int i = 0; i < b->nbits; i++)
          if (us_bitset_get(b, i)) fprintf(stderr, " %d", i);
        fprintf(stderr, " (test %ld of the walk; %s)\n", t->tests, r[m].note);
      }
      continue;
    }
    CHECK(r[m].mechanism.ok);
    t->mech++;
  }
}

/* Walk structure s with every method; tally. */
static void walk(const us_Structure *s, int extra, unsigned long long *rng, Tally *t) {
  us_Stability *w[NM] = {0};
  us_StabilityResult r[NM];
  us_Error err;
  for (int m = 0; m < NM; m++) {
    us_StabilitySettings set = us_stability_default_settings();
    set.method = METHODS[m];
    set.local = -1; /* the full system: the LP decides what the LCP does */
    w[m] = us_stability_new(s, &set, &err);
    CHECK(w[m]);
    us_stability_result_init(&r[m]);
  }
  us_Bitset b;
  us_bitset_init(&b, s->nbody);
  int n = s->nbody;
  for (int k = 0; w[0] && w[1] && w[2] && w[3] && k < 2 * n + extra && !us_test_failed; k++) {
    walk_step(&b, n, k, rng);
    compare_one(w, &b, r, t);
  }
  for (int m = 1; m < 3; m++) {
    if (!w[m]) continue;
    const us_StabilityInfo *in = us_stability_info(w[m]);
    t->pivots += in->pivots;
    t->fallbacks += in->lp_fallbacks;
    if (m == 2) t->reused += in->reused;
  }
  us_bitset_free(&b);
  for (int m = 0; m < NM; m++) {
    us_stability_result_free(&r[m]);
    us_stability_free(w[m]);
  }
}

static void report(const char *what, const Tally *t) {
  fprintf(stderr,
          "%s: %ld sub-assemblies (%ld stable, %ld unstable, %ld undecided by all), %ld "
          "LCP mechanisms checked, %ld missing; LCP pivots %ld, lcp-reuse reused %ld, LP "
          "fallbacks %ld\n",
          what, t->tests, t->stable, t->unstable, t->undecided_both, t->mech, t->nomech, t->pivots,
          t->reused, t->fallbacks);
  CHECK(t->nomech * 100 <= t->unstable); /* under 1 % of the unstable verdicts (x 2 methods) */
}

/* The differential over kinds [k0, k1), mu from MU[m0..2], vertical and
 * tilted gravity, `seeds` variants each. */
static void differential(int k0, int k1, int m0, int seeds, int extra, Tally *t) {
  static const double MU[3] = {0.0, 0.2, 0.5};
  unsigned long long rng = 1234567ull + (unsigned long long)k0;
  for (int kind = k0; kind < k1 && !us_test_failed; kind++)
    for (int mi = m0; mi < 3; mi++)
      for (int sd = 0; sd < seeds && !us_test_failed; sd++) {
        double tilt = sd % 2 ? 0.05 + 0.1 * rnd(&rng) : 0.0, az = 2 * PI * rnd(&rng);
        us_Structure *s = scene(kind, MU[mi], tilt, az, 3u + (unsigned)sd);
        CHECK(s);
        long t0 = t->tests;
        double c0 = us_now();
        walk(s, extra / SCALE, &rng, t);
        if (getenv("LCP3_VERBOSE") && s)
          fprintf(stderr, "kind %d mu %.1f seed %d: %d bodies, %d contacts, %ld tests, %.2f s\n", kind,
                  MU[mi], sd, s->nbody, s->ncontact, t->tests - t0, us_now() - c0);
        us_structure_free(s);
      }
}

/* Towers, straight and turned: the LCP methods give the LP's verdict,
 * and where they decide themselves the LP is not asked (fallbacks, which
 * are counted, stay under 1 % of the LCP methods' tests). */
static void differential_towers(void) {
  Tally t = {0};
  differential(0, 2, 0, SCALE > 1 ? 1 : 4, 220, &t);
  report("towers", &t);
  CHECK(t.tests >= (SCALE > 1 ? 100 : 5000));
  CHECK(t.stable > 100 / SCALE && t.unstable > 100 / SCALE); /* both verdicts exercised */
  CHECK_INT(t.undecided_both, ==, 0);
  CHECK(t.reused > t.tests / 2); /* lcp-reuse repaired its parent's solution */
  CHECK(t.fallbacks * 100 <= t.tests * 2); /* 1 % of lcp's and lcp-reuse's tests */
}

/* pyramid3d and wall3d. */
static void differential_pyramids_walls(void) {
  Tally t = {0};
  differential(2, 4, 0, 1, 220, &t);
  report("pyramid3d, wall3d", &t);
  CHECK(t.tests >= 1400 / SCALE);
  CHECK(t.stable > 100 / SCALE && t.unstable > 100 / SCALE);
  CHECK(t.reused > t.tests / 2);
  CHECK(t.fallbacks * 100 <= t.tests * 2);
}

/* Jenga with pieces out and random piles; domes (4 courses of 8) at mu 0.5. */
static void differential_piles(void) {
  Tally t = {.every = 32};
  differential(4, 6, 0, SCALE > 1 ? 1 : 2, 200, &t);
  if (SCALE == 1) differential(6, 7, 2, 1, 120, &t); /* domes: not under the sanitizers */
  report("jenga, random3d, domes", &t);
  CHECK(t.tests >= 2000 / SCALE);
  CHECK(t.stable > 100 / SCALE && t.unstable > 100 / SCALE);
  /* fallbacks over both LCP methods' 2 x tests: measured 85 of 5,648 (1.5 %,
   * Release; near-dependent edges whose a stays below the proof's slack):
   * bounded at 1.7 % there, at 4 % under the sanitizers' smaller sample */
  if (SCALE == 1) CHECK(t.fallbacks * 1000 <= t.tests * 2 * 17);
  CHECK(t.fallbacks * 100 <= t.tests * 2 * 2);
}

/* A 2D structure extruded into prisms: the LCP methods give the planar
 * verdict on every sub-assembly of the walk. */
static void extruded_planar(void) {
  unsigned long long rng = 99;
  Tally t = {0};
  long agree = 0, total = 0;
  for (int kind = 0; kind < (SCALE > 1 ? 2 : 4); kind++)
    for (int fr = 0; fr < 2; fr++) {
      us_GenSettings g = us_gen_default_settings();
      us_Error err;
      g.friction = fr ? 0.5 : 0.0;
      us_Structure *p = NULL;
      if (kind == 0) g.n = 5, p = us_gen_column(&g, &err);
      if (kind == 1) g.n = 4, p = us_gen_pyramid(&g, &err);
      if (kind == 2) g.rows = 3, g.cols = 3, p = us_gen_wall(&g, &err);
      if (kind == 3) g.rows = 5, g.width = 4, g.seed = 7, p = us_gen_random(&g, &err);
      CHECK(p);
      us_Structure *e = p ? test_extrude(p, 0.8, 2 * PI * rnd(&rng), 1.0, -2.0) : NULL;
      CHECK(e);
      us_StabilitySettings set = us_stability_default_settings();
      set.method = US_METHOD_LP;
      us_Stability *wp = us_stability_new(p, &set, &err);
      CHECK(wp);
      us_Stability *w[NM];
      us_StabilityResult r[NM], rp;
      us_stability_result_init(&rp);
      for (int m = 0; m < NM; m++) {
        set.method = METHODS[m];
        w[m] = us_stability_new(e, &set, &err);
        CHECK(w[m]);
        us_stability_result_init(&r[m]);
      }
      us_Bitset b;
      us_bitset_init(&b, p->nbody);
      for (int k = 0; k < 2 * p->nbody + 20 / SCALE && !us_test_failed; k++) {
        walk_step(&b, p->nbody, k, &rng);
        CHECK_OK(us_stability_test(wp, &b, &rp, &err), &err);
        compare_one(w, &b, r, &t);
        CHECK_INT(r[0].verdict, ==, rp.verdict);
        agree += r[2].verdict == rp.verdict;
        total++;
      }
      us_bitset_free(&b);
      for (int m = 0; m < NM; m++) {
        us_stability_result_free(&r[m]);
        us_stability_free(w[m]);
      }
      us_stability_result_free(&rp);
      us_stability_free(wp);
      us_structure_free(e);
      us_structure_free(p);
    }
  report("extruded 2D", &t);
  CHECK_INT(agree, ==, total);
  CHECK(t.stable > 20 / SCALE && t.unstable > 20 / SCALE);
}

/* Rotations: about the vertical (gravity kept), and a rigid rotation of
 * everything with gravity turned along (the ground kept horizontal cannot
 * turn: a fixed slab stands for it in both). lcp-reuse's verdicts equal
 * the LP's on the original. */
static us_Structure *rotated(const us_Structure *s, const double R[9], int turn_gravity) {
  us_Structure *t = us_structure_new(3);
  us_Error err;
  t->friction = s->friction;
  t->ground = !turn_gravity;
  for (int k = 0; k < 3; k++)
    t->gravity[k] = turn_gravity ? R[3 * k] * s->gravity[0] + R[3 * k + 1] * s->gravity[1] +
                                       R[3 * k + 2] * s->gravity[2]
                                 : s->gravity[k];
  int ok = 1;
  for (int i = 0; ok && i <= s->nbody; i++) { /* the slab last: the ground's stand-in */
    double slab[24];
    const double *src = slab;
    int n = 8;
    if (i == s->nbody) {
      if (!turn_gravity) break;
      for (int c = 0; c < 8; c++) {
        slab[3 * c] = c & 1 ? 20.0 : -20.0, slab[3 * c + 1] = c & 2 ? 20.0 : -20.0;
        slab[3 * c + 2] = c & 4 ? 0.0 : -1.0;
      }
    } else {
      if (s->bodies[i].npart != 1) {
        ok = 0;
        break;
      }
      n = s->bodies[i].parts[0].nvert;
      src = s->bodies[i].parts[0].verts;
    }
    double *xyz = malloc(3 * (size_t)n * sizeof(double));
    if (!xyz) {
      ok = 0;
      break;
    }
    for (int c = 0; c < n; c++)
      for (int k = 0; k < 3; k++)
        xyz[3 * c + k] = R[3 * k] * src[3 * c] + R[3 * k + 1] * src[3 * c + 1] + R[3 * k + 2] * src[3 * c + 2];
    us_BodyDef d = us_default_body_def();
    d.id = i == s->nbody ? "slab" : s->bodies[i].id;
    d.nvert = n, d.xyz = xyz, d.fixed = i == s->nbody;
    if (i < s->nbody) d.friction = s->bodies[i].friction, d.density = s->bodies[i].density;
    ok = us_structure_add_body(t, &d, &err) >= 0;
    free(xyz);
  }
  if (!ok) {
    us_structure_free(t);
    return NULL;
  }
  return test_finalized(t, "rotated");
}

static void rotation_invariance(void) {
  unsigned long long rng = 31337;
  long agree = 0, total = 0, tally[2] = {0, 0};
  for (int kind = 1; kind < 6; kind++) {
    if (kind == 3) continue; /* walls: the slab's long contacts only slow it down */
    us_Structure *s = scene(kind, kind % 2 ? 0.5 : 0.2, 0.0, 0.0, 5);
    CHECK(s);
    if (!s) continue;
    double th = 2 * PI * rnd(&rng), Z[9] = {cos(th), -sin(th), 0, sin(th), cos(th), 0, 0, 0, 1};
    double a = 0.3 + rnd(&rng), X[9] = {1, 0, 0, 0, cos(a), -sin(a), 0, sin(a), cos(a)};
    us_Structure *t[2] = {rotated(s, Z, 0), rotated(s, X, 1)};
    us_Structure *slab = rotated(s, (const double[9]){1, 0, 0, 0, 1, 0, 0, 0, 1}, 1);
    for (int k = 0; k < 2; k++) {
      CHECK(t[k] && slab);
      if (!t[k] || !slab) continue;
      const us_Structure *ref = k ? slab : s;
      int off = 0; /* the slab is the last body */
      us_StabilitySettings set = us_stability_default_settings();
      us_Error err;
      set.method = US_METHOD_LP;
      us_Stability *wa = us_stability_new(ref, &set, &err);
      set.method = US_METHOD_LCP_REUSE;
      us_Stability *wb = us_stability_new(t[k], &set, &err);
      CHECK(wa && wb);
      us_Bitset ba, bb;
      us_bitset_init(&ba, ref->nbody);
      us_bitset_init(&bb, t[k]->nbody);
      us_StabilityResult ra, rb;
      us_stability_result_init(&ra);
      us_stability_result_init(&rb);
      for (int step = 0; wa && wb && step < 2 * s->nbody + 20 / SCALE && !us_test_failed; step++) {
        us_Bitset cur;
        us_bitset_init(&cur, s->nbody);
        walk_step(&cur, s->nbody, step, &rng);
        for (int i = 0; i < s->nbody; i++) {
          if (us_bitset_get(&cur, i)) {
            us_bitset_set(&ba, i + off);
            us_bitset_set(&bb, i + off);
          } else {
            us_bitset_clear(&ba, i + off);
            us_bitset_clear(&bb, i + off);
          }
        }
        us_bitset_free(&cur);
        CHECK_OK(us_stability_test(wa, &ba, &ra, &err), &err);
        CHECK_OK(us_stability_test(wb, &bb, &rb, &err), &err);
        CHECK_INT(rb.verdict, ==, ra.verdict);
        agree += rb.verdict == ra.verdict;
        tally[ra.verdict == US_STABLE]++;
        total++;
      }
      us_stability_result_free(&ra);
      us_stability_result_free(&rb);
      us_bitset_free(&ba);
      us_bitset_free(&bb);
      us_stability_free(wa);
      us_stability_free(wb);
    }
    us_structure_free(t[0]);
    us_structure_free(t[1]);
    us_structure_free(slab);
    us_structure_free(s);
  }
  fprintf(stderr, "rotations: %ld sub-assemblies agree of %ld (%ld stable)\n", agree, total,
          tally[1]);
  CHECK_INT(agree, ==, total);
  CHECK(tally[0] > 20 / SCALE && tally[1] > 20 / SCALE);
}

/* The pivoting on a raw PSD LCP with dependent columns: G has 3 rows and
 * 7 columns (so A = G^T G is singular), l >= 0 solves G l = b where b is
 * in the cone, and else the residual's direction is a Farkas ray. */
typedef struct Dense {
  int n;
  const double *A, *b;
} Dense;
static double dense_entry(void *ctx, int i, int j) {
  const Dense *d = ctx;
  return d->A[i * d->n + j];
}
static void dense_full(void *ctx, const double *f, const unsigned char *live, double *a) {
  const Dense *d = ctx;
  for (int i = 0; i < d->n; i++) {
    if (!live[i]) continue;
    double s = d->b[i];
    for (int j = 0; j < d->n; j++) s += d->A[i * d->n + j] * f[j];
    a[i] = s;
  }
}
static int dense_apply(void *ctx, const int *idx, const double *x, int k, double *y, int *out) {
  const Dense *d = ctx;
  for (int i = 0; i < d->n; i++) {
    y[i] = 0.0;
    for (int m = 0; m < k; m++) y[i] += d->A[i * d->n + idx[m]] * x[m];
    out[i] = i;
  }
  return d->n;
}

static void pivoting_dependent_columns(void) {
  unsigned long long rng = 8;
  int solved = 0, rays = 0;
  for (int trial = 0; trial < 200; trial++) {
    enum { R = 3, N = 7 };
    double G[R * N], A[N * N], q[N], target[R];
    for (int k = 0; k < R * N; k++) G[k] = rnd(&rng) - 0.5;
    for (int r = 0; r < R; r++) target[r] = 0.0;
    for (int j = 0; j < N; j++) { /* inside the cone, or pushed outside */
      double l = trial % 2 ? rnd(&rng) : rnd(&rng) - 0.7;
      for (int r = 0; r < R; r++) target[r] += G[r * N + j] * l;
    }
    for (int i = 0; i < N; i++) { /* a = G^T (G l - target) */
      q[i] = 0.0;
      for (int r = 0; r < R; r++) q[i] -= G[r * N + i] * target[r];
      for (int j = 0; j < N; j++) {
        A[i * N + j] = 0.0;
        for (int r = 0; r < R; r++) A[i * N + j] += G[r * N + i] * G[r * N + j];
      }
    }
    Dense d = {N, A, q};
    us_LcpOps ops = {&d, dense_entry, dense_apply, dense_full};
    us_Lcp p;
    us_Lcp3Piv v;
    CHECK_INT(us_lcp_init(&p, N, &ops), ==, 0);
    CHECK_INT(us_lcp3_piv_init(&v, N), ==, 0);
    for (int i = 0; i < N; i++) p.live[i] = 1, p.state[i] = US_LCP_NC;
    CHECK_INT(us_lcp3_piv_run(&v, &p, 1000), ==, US_LCP_SOLVED);
    double res[R] = {0}, rn = 0.0;
    for (int r = 0; r < R; r++) {
      res[r] = -target[r];
      for (int j = 0; j < N; j++) res[r] += G[r * N + j] * p.f[j];
      rn += res[r] * res[r];
    }
    for (int j = 0; j < N; j++) { /* an LCP solution */
      CHECK(p.f[j] >= 0.0);
      CHECK(p.a[j] >= -1e-9);
      CHECK(fabs(p.f[j] * p.a[j]) <= 1e-9);
    }
    if (sqrt(rn) <= 1e-9) {
      solved++;
    } else { /* y = -res: G^T y <= 0 is -a <= 0, and target . y > 0 */
      double ty = 0.0;
      for (int r = 0; r < R; r++) ty -= target[r] * res[r];
      CHECK(ty > 0.0);
      rays++;
    }
    us_lcp3_piv_free(&v);
    us_lcp_free(&p);
  }
  CHECK(solved > 50 && rays > 20);
}

US_TEST_MAIN(T(differential_towers), T(differential_pyramids_walls), T(differential_piles), T(extruded_planar),
             T(rotation_invariance), T(pivoting_dependent_columns))
