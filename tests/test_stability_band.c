/* Differential tests of the boundary band (docs/planning.md, "The boundary
 * band"): a top box whose centre of mass lies d past its base's corner
 * (d relative to the boxes' size 1) tips for d > 0 and stands for d <= 0.
 * Swept across the boundary from both sides, in 2D and 3D, with and
 * without friction, at sizes 1, 1e6 and 1e-3, every method must give the
 * same verdict at every offset (lp_solve used to certify d = 1e-8 and
 * 1e-7 as stable within its tolerance while every other method said
 * unstable; lp-lcp said unstable at 1e-10 where the rest said stable), and
 * the verdict is exact where the offset is clear of the band. */
#include "stability/certificate.h"
#include "scenes.h"
#include "test.h"

/* Box [x0, x1] x [y0, y1] x [z0, z1] of density 1. */
static int box3(us_Structure *s, const char *id, double x0, double x1, double y0, double y1,
                double z0, double z1) {
  double v[24];
  for (int k = 0; k < 8; k++) {
    v[3 * k] = k & 1 ? x1 : x0;
    v[3 * k + 1] = k & 2 ? y1 : y0;
    v[3 * k + 2] = k & 4 ? z1 : z0;
  }
  us_BodyDef d = us_default_body_def();
  d.id = id, d.nvert = 8, d.xyz = v, d.density = 1.0;
  return us_structure_add_body(s, &d, NULL);
}

/* A unit base box on the ground and a 1 x 0.5 (x 1) top box whose centre
 * is d past the base's right edge x = 1, all lengths times sc. */
static us_Structure *corner(int dim, double d, double sc, double mu) {
  us_Structure *s = us_structure_new(dim);
  s->friction = mu;
  if (dim == 2) {
    scene_box(s, "base", 0, 0, sc, sc, 1.0);
    scene_box(s, "top", (0.5 + d) * sc, sc, sc, 0.5 * sc, 1.0);
  } else {
    box3(s, "base", 0, sc, 0, sc, 0, sc);
    box3(s, "top", (0.5 + d) * sc, (1.5 + d) * sc, 0, sc, sc, 1.5 * sc);
  }
  return scene_seal(s);
}

/* The verdict of method m on the whole of s; *band: tests that were in the
 * band (decided by the referee). */
static us_Verdict verdict_of(const us_Structure *s, us_Method m, long *band) {
  us_StabilitySettings set = us_stability_default_settings();
  set.method = m;
  us_Error err;
  us_Stability *w = us_stability_new(s, &set, &err);
  if (!w) return US_UNDECIDED; /* the caller's comparison fails */
  us_StabilityResult r;
  us_stability_result_init(&r);
  us_Verdict v = us_stability_test_full(w, &r, &err) == US_OK ? r.verdict : US_UNDECIDED;
  *band += us_stability_info(w)->band_referee;
  us_stability_result_free(&r);
  us_stability_free(w);
  return v;
}

static const double offsets[] = {-1e-5, -1e-6, -1e-7, -1e-8, -1e-9, -1e-10, -1e-12, 0.0, 1e-12,
                                 1e-10, 3e-10, 1e-9,  3e-9,  1e-8,  3e-8,  1e-7,   3e-7,  1e-6, 1e-5};

/* Every method of the dimension agrees at every offset, at every size and
 * friction; *band counts the tests that went to the referee. */
static void sweep(int dim, long *band) {
  static const us_Method m2[] = {US_METHOD_LP, US_METHOD_LPSOLVE, US_METHOD_LCP,
                                 US_METHOD_LCP_REUSE, US_METHOD_LP_LCP};
  static const us_Method m3[] = {US_METHOD_LP, US_METHOD_LPSOLVE};
  const us_Method *ms = dim == 2 ? m2 : m3;
  int nm = dim == 2 ? 5 : 2;
  for (int si = 0; si < 3; si++)
    for (int mi = 0; mi < 2; mi++)
      for (size_t k = 0; k < sizeof offsets / sizeof offsets[0]; k++) {
        double sc = si == 0 ? 1.0 : si == 1 ? 1e6 : 1e-3, mu = mi ? 0.5 : 0.0, d = offsets[k];
        us_Structure *s = corner(dim, d, sc, mu);
        CHECK(s);
        us_Verdict v0 = verdict_of(s, ms[0], band);
        for (int j = 1; j < nm; j++) {
          us_Verdict v = verdict_of(s, ms[j], band);
          if (v != v0)
            fprintf(stderr, "dim %d size %g mu %g offset %g: %s %s, %s %s\n", dim, sc, mu, d,
                    us_method_name(ms[0]), us_verdict_name(v0), us_method_name(ms[j]),
                    us_verdict_name(v));
          CHECK_INT(v, ==, v0);
        }
        /* clear of the band: the exact answer */
        if (d <= 0.0) CHECK_INT(v0, ==, US_STABLE);
        if (d >= 1e-6) CHECK_INT(v0, ==, US_UNSTABLE);
        us_structure_free(s);
      }
}

static void methods_agree_2d(void) {
  long band = 0;
  sweep(2, &band);
  CHECK(band > 0); /* the sweep reached the band */
}

static void methods_agree_3d(void) {
  long band = 0;
  sweep(3, &band);
  CHECK(band > 0);
}

/* A mechanism's margin follows the moving body: the top box rolling over
 * the corner it is d past has a margin of about d / its reach. */
static void mechanism_margin_is_relative(void) {
  us_Structure *s = corner(2, 1e-3, 1.0, 0.5);
  CHECK(s);
  if (!s) return;
  us_StabilitySettings set = us_stability_default_settings();
  set.method = US_METHOD_LP;
  set.local = -1; /* the full system's ray */
  us_Error err;
  us_Stability *w = us_stability_new(s, &set, &err);
  us_StabilityResult r;
  us_stability_result_init(&r);
  CHECK(us_stability_test_full(w, &r, &err) == US_OK);
  CHECK_INT(r.verdict, ==, US_UNSTABLE);
  CHECK(r.mechanism.nbody >= 1);
  CHECK(r.mechanism.ok);
  double m = us_mechanism_margin(s, &r.mechanism), reach = hypot(0.5, 0.25);
  CHECK(m > 0.3e-3 / reach && m < 3e-3 / reach);
  us_stability_result_free(&r);
  us_stability_free(w);
  us_structure_free(s);
}

US_TEST_MAIN(T(methods_agree_2d), T(methods_agree_3d), T(mechanism_margin_is_relative))
