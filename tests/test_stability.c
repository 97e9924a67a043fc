/* Tests of the stability front end with the LP backends: verdicts of small
 * structures whose answer follows from hand statics (stated per case),
 * sub-assemblies, the empty sub-assembly, result reuse, the workspace's
 * added/removed bookkeeping (through a spying backend), order independence
 * and out-of-memory paths. Every STABLE verdict is checked to come with a
 * passing certificate; no test looks at particular force values. */
#include "stability/backend.h"
#include "stability/certificate.h"
#include "stability/lp_gen.h"
#include "stability/lp_small.h"
#include "stability/equilibrium.h"
#include "scenes.h"
#include "test.h"

static const us_Method lp_methods[] = {US_METHOD_LP, US_METHOD_LPSOLVE};

/* ---------------------------------------------------------------- helpers */

/* Both LP methods must give `want`. */
#define CHECK_VERDICT(s, present, want)                               \
  do {                                                                \
    for (int mi_ = 0; mi_ < 2; mi_++)                                 \
      CHECK_INT(scene_verdict((s), lp_methods[mi_], (present)), ==, (want)); \
  } while (0)

/* A point body of mass 1 at (cx, cy) on two ground contacts at x = xl, xr. */
static us_Structure *point_on_ground(double cx, double xl, double xr) {
  us_Structure *s = us_structure_new(2);
  us_Error err;
  double c[2] = {cx, 0.5}, up[2] = {0, 1}, pl[2] = {xl, 0}, pr[2] = {xr, 0};
  int b = us_structure_add_point_body(s, "p", 1.0, c, 0, &err);
  us_structure_add_contact(s, US_GROUND, b, pl, up, -1, &err);
  us_structure_add_contact(s, US_GROUND, b, pr, up, -1, &err);
  s->explicit_contacts = 1;
  return scene_seal(s);
}

/* ------------------------------------------------------------------ cases */

static void names_and_defaults(void) {
  for (int m = 0; m < US_METHOD_COUNT; m++) {
    us_Method out = US_METHOD_COUNT;
    CHECK_INT(us_method_parse(us_method_name((us_Method)m), &out), ==, 0);
    CHECK_INT(out, ==, m);
  }
  us_Method out;
  CHECK_INT(us_method_parse("simplex", &out), ==, -1);
  CHECK_INT(us_method_parse(NULL, &out), ==, -1);
  CHECK(strcmp(us_method_name(US_METHOD_LCP_REUSE), "lcp-reuse") == 0);
  CHECK(strcmp(us_verdict_name(US_UNSTABLE), "unstable") == 0);
  us_StabilitySettings d = us_stability_default_settings();
  CHECK_INT(d.method, ==, US_METHOD_AUTO);
  CHECK(strcmp(us_method_name(US_METHOD_AUTO), "auto") == 0);
  CHECK_NEAR(d.cert_tol, 1e-6, 0);
}

/* Point body between its two supports stands; outside them it tips. */
static void point_body_support(void) {
  us_Structure *s = point_on_ground(0.1, -0.5, 0.5);
  CHECK(s);
  CHECK_VERDICT(s, NULL, US_STABLE);
  us_structure_free(s);
  s = point_on_ground(0.8, -0.5, 0.5);
  CHECK(s);
  CHECK_VERDICT(s, NULL, US_UNSTABLE);
  us_structure_free(s);
}

static void single_block(void) {
  us_Structure *s = us_structure_new(2);
  scene_box(s, "a", 0, 0, 1, 1, 1);
  CHECK(scene_seal(s));
  CHECK(s->ncontact >= 2);
  CHECK_VERDICT(s, NULL, US_STABLE);
  us_structure_free(s);
}

/* An L-shaped body standing on a 0.2-wide foot with its arm reaching to
 * x = 2: its centre of mass is far right of the foot, so it tips. */
static void overhanging_body(void) {
  us_Structure *s = us_structure_new(2);
  double xy[12] = {0, 0, 0.2, 0, 0.2, 0.2, 2, 0.2, 2, 0.4, 0, 0.4};
  CHECK(scene_polygon(s, "L", 6, xy, 0) == 0);
  CHECK(scene_seal(s));
  CHECK(s->bodies[0].com[0] > 0.5);
  CHECK_VERDICT(s, NULL, US_UNSTABLE);
  us_structure_free(s);
}

/* Two unit boxes; the top one shifted by dx: its centre is over the lower
 * box's top face iff dx < 0.5. */
static us_Structure *two_blocks(double dx) {
  us_Structure *s = us_structure_new(2);
  scene_box(s, "low", 0, 0, 1, 1, 1);
  scene_box(s, "top", dx, 1, 1, 1, 1);
  return scene_seal(s);
}

static void two_block_column(void) {
  us_Structure *s = two_blocks(0.0);
  CHECK(s);
  CHECK_VERDICT(s, NULL, US_STABLE);
  us_structure_free(s);
  s = two_blocks(0.35);
  CHECK(s);
  CHECK_VERDICT(s, NULL, US_STABLE);
  us_structure_free(s);
  s = two_blocks(0.65); /* top centre at x = 1.15 > 1 */
  CHECK(s);
  CHECK_VERDICT(s, NULL, US_UNSTABLE);
  us_structure_free(s);
}

/* Plank 3 x 0.2 on a unit base (support x in [0, 1]), plank centre at 1.5:
 * tips alone. A 0.5 x 0.5 block of density 10 on its left end brings the
 * joint centre to x = (0.6 * 1.5 + 2.5 * 0.25) / 3.1 = 0.49: stands. */
static void cantilever(void) {
  for (int cw = 0; cw < 2; cw++) {
    us_Structure *s = us_structure_new(2);
    scene_box(s, "base", 0, 0, 1, 1, 1);
    scene_box(s, "plank", 0, 1, 3, 0.2, 1);
    if (cw) scene_box(s, "weight", 0, 1.2, 0.5, 0.5, 10);
    CHECK(scene_seal(s));
    CHECK_VERDICT(s, NULL, cw ? US_STABLE : US_UNSTABLE);
    us_structure_free(s);
  }
}

/* Two slabs leaning on each other along x = 1, y in [2, 2.4], feet on the
 * ground over [0, 0.3] and [1.7, 2]. Each slab's centre is at x ~ 0.58
 * (resp. 1.42), outside its foot, so it needs a horizontal push at the
 * apex, which a foot can only resist by friction: H = W (xc - 0.3) / y <=
 * about 0.12 W, so mu = 0.5 stands and mu = 0 falls. */
static void inverted_v(void) {
  for (int k = 0; k < 2; k++) {
    us_Structure *s = us_structure_new(2);
    s->friction = k == 0 ? 0.5 : 0.0;
    double l[8] = {0, 0, 0.3, 0, 1, 2, 1, 2.4};
    double r[8] = {1.7, 0, 2, 0, 1, 2.4, 1, 2};
    CHECK(scene_polygon(s, "left", 4, l, 0) == 0);
    CHECK(scene_polygon(s, "right", 4, r, 0) == 1);
    CHECK(scene_seal(s));
    CHECK(s->bodies[0].com[0] > 0.3 && s->bodies[1].com[0] < 1.7);
    CHECK_VERDICT(s, NULL, k == 0 ? US_STABLE : US_UNSTABLE);
    us_structure_free(s);
  }
}

/* Column of three boxes on a fixed pier: sub-assemblies. */
static us_Structure *pier_column(void) {
  us_Structure *s = us_structure_new(2);
  double pier[8] = {0, 0, 1, 0, 1, 1, 0, 1};
  scene_polygon(s, "pier", 4, pier, 1);
  scene_box(s, "b1", 0, 1, 1, 1, 1);
  scene_box(s, "b2", 0, 2, 1, 1, 1);
  scene_box(s, "b3", 0.2, 3, 1, 1, 1);
  return scene_seal(s);
}

static void sub_assemblies(void) {
  us_Structure *s = pier_column();
  CHECK(s);
  us_Bitset p;
  CHECK(us_bitset_init(&p, s->nbody) == 0);
  int want[8];
  /* bit k of the mask = body k+1 present: stands iff no gap below a body */
  for (int mask = 0; mask < 8; mask++) {
    int ok = 1, below = 1;
    for (int k = 0; k < 3; k++) {
      int here = (mask >> k) & 1;
      if (here && !below) ok = 0;
      below = here;
    }
    want[mask] = ok ? US_STABLE : US_UNSTABLE;
  }
  for (int mask = 0; mask < 8; mask++) {
    memset(p.w, 0, (size_t)p.nwords * 8);
    for (int k = 0; k < 3; k++)
      if ((mask >> k) & 1) us_bitset_set(&p, k + 1);
    if (mask & 1) us_bitset_set(&p, 0); /* the pier's bit is ignored either way */
    CHECK_VERDICT(s, &p, want[mask]);
  }
  us_bitset_free(&p);
  us_structure_free(s);
}

/* The empty sub-assembly and active contacts. */
static void empty_and_active(void) {
  us_Structure *s = pier_column();
  CHECK(s);
  us_Bitset p;
  CHECK(us_bitset_init(&p, s->nbody) == 0);
  int idx[64];
  CHECK(s->ncontact <= 64);
  CHECK_INT(us_active_contacts(s, &p, idx), ==, 0); /* pier-ground is fixed-fixed */
  us_Error err;
  us_Stability *w = us_stability_new(s, NULL, &err);
  CHECK(w);
  us_StabilityResult res = {0};
  CHECK_OK(us_stability_test(w, &p, &res, &err), &err);
  CHECK_INT(res.verdict, ==, US_STABLE);
  CHECK_INT(res.forces.ncontact, ==, 0);
  CHECK(res.check.ok);
  CHECK_INT(us_stability_info(w)->tests, ==, 1);
  us_bitset_set(&p, 1);
  int na = us_active_contacts(s, &p, idx);
  CHECK(na >= 2);
  for (int i = 0; i < na; i++) {
    const us_Contact *c = &s->contacts[idx[i]];
    CHECK((c->a == 0 && c->b == 1) || (c->a == 1 && c->b == 0));
  }
  CHECK_OK(us_stability_test(w, &p, &res, &err), &err);
  CHECK_INT(res.verdict, ==, US_STABLE);
  CHECK_INT(res.forces.ncontact, ==, na);
  CHECK_INT(us_stability_info(w)->tests, ==, 2);
  us_stability_result_free(&res);
  us_stability_free(w);
  us_bitset_free(&p);
  us_structure_free(s);
}

/* A body without any contact falls; bad arguments are usage errors. */
static void floating_and_usage(void) {
  us_Structure *s = us_structure_new(2);
  us_Error err;
  double c[2] = {0, 3};
  us_structure_add_point_body(s, "p", 1.0, c, 0, &err);
  s->explicit_contacts = 1;
  CHECK(scene_seal(s));
  CHECK_VERDICT(s, NULL, US_UNSTABLE);
  us_Stability *w = us_stability_new(s, NULL, &err);
  CHECK(w);
  us_Bitset p;
  CHECK(us_bitset_init(&p, s->nbody + 1) == 0);
  us_StabilityResult res = {0};
  CHECK_INT(us_stability_test(w, &p, &res, &err), ==, US_ERR_USAGE);
  us_bitset_free(&p);
  us_stability_free(w);
  us_StabilitySettings set = us_stability_default_settings();
  set.cert_tol = -1;
  CHECK(us_stability_new(s, &set, &err) == NULL);
  CHECK_INT(err.code, ==, US_ERR_USAGE);
  set = us_stability_default_settings();
  set.method = (us_Method)(US_METHOD_AUTO + 1);
  CHECK(us_stability_new(s, &set, &err) == NULL);
  CHECK_INT(err.code, ==, US_ERR_USAGE);
  us_structure_free(s);
}

/* The unstable evidence names a present movable body (or is -1). */
static void unstable_evidence(void) {
  us_Structure *s = two_blocks(0.8);
  CHECK(s);
  for (int mi = 0; mi < 2; mi++) {
    us_StabilitySettings set = us_stability_default_settings();
    set.method = lp_methods[mi];
    us_Error err;
    us_Stability *w = us_stability_new(s, &set, &err);
    CHECK(w);
    us_Bitset p;
    CHECK(us_bitset_init(&p, s->nbody) == 0);
    us_bitset_fill(&p);
    us_StabilityResult res = {0};
    CHECK_OK(us_stability_test(w, &p, &res, &err), &err);
    CHECK_INT(res.verdict, ==, US_UNSTABLE);
    CHECK(res.unstable_body == -1 || res.unstable_body == 0 || res.unstable_body == 1);
    /* CLP's Farkas ray is checked and used (lp_solve gives none) */
    if (lp_methods[mi] == US_METHOD_LP) CHECK(res.unstable_body >= 0);
    CHECK(res.note[0] != '\0');
    us_stability_result_free(&res);
    us_bitset_free(&p);
    us_stability_free(w);
  }
  us_structure_free(s);
}

/* A backend that claims stable with made-up forces: the front end must
 * not pass that on as stable. */
static us_Status liar_solve(void *ws, const us_BackendProblem *pb, us_BackendOut *out,
                            us_Error *err) {
  US_UNUSED(ws), US_UNUSED(err);
  for (int j = 0; j < pb->sys->ncontact * pb->sys->dim; j++) out->f[j] = j % 2 ? 0.0 : 0.01;
  out->verdict = US_STABLE;
  return US_OK;
}

static void *liar_create(const us_Structure *s, const us_StabilitySettings *set,
                         us_Error *err) {
  return us_backend_clp.create(s, set, err);
}

static void liar_destroy(void *ws) { us_backend_clp.destroy(ws); }

static const us_Backend liar_backend = {
    .method = US_METHOD_LP, .create = liar_create, .destroy = liar_destroy, .solve = liar_solve};

static void never_stable_without_certificate(void) {
  us_Structure *s = two_blocks(0.0);
  CHECK(s);
  us_Error err;
  us_Stability *w = us_stability_new_backend(s, NULL, &liar_backend, &err);
  CHECK(w);
  us_Bitset p;
  CHECK(us_bitset_init(&p, s->nbody) == 0);
  us_bitset_fill(&p);
  us_StabilityResult res = {0};
  CHECK_OK(us_stability_test(w, &p, &res, &err), &err);
  CHECK_INT(res.verdict, ==, US_UNDECIDED);
  CHECK(!res.check.ok);
  CHECK(strstr(res.note, "certificate") != NULL);
  us_stability_result_free(&res);
  us_bitset_free(&p);
  us_stability_free(w);
  us_structure_free(s);
}

/* ---- bookkeeping: a backend that checks added/removed against present */

static struct {
  int calls, errors;
  us_Bitset mirror; /* the backend's own idea of the sub-assembly */
} spy;

static void *spy_create(const us_Structure *s, const us_StabilitySettings *set, us_Error *err) {
  if (us_bitset_init(&spy.mirror, s->nbody)) return NULL;
  return us_backend_clp.create(s, set, err);
}

static void spy_destroy(void *ws) {
  us_bitset_free(&spy.mirror);
  us_backend_clp.destroy(ws);
}

static us_Status spy_solve(void *ws, const us_BackendProblem *pb, us_BackendOut *out,
                           us_Error *err) {
  const us_EqSystem *sys = pb->sys;
  const int *added = pb->added, *removed = pb->removed;
  int nadded = pb->nadded, nremoved = pb->nremoved, restart = pb->restart;
  spy.calls++;
  if (restart) memset(spy.mirror.w, 0, (size_t)spy.mirror.nwords * 8);
  for (int i = 0; i < nremoved; i++) {
    if (!us_bitset_get(&spy.mirror, removed[i]) && !restart) spy.errors++;
    us_bitset_clear(&spy.mirror, removed[i]);
  }
  for (int i = 0; i < nadded; i++) {
    if (us_bitset_get(&spy.mirror, added[i])) spy.errors++;
    us_bitset_set(&spy.mirror, added[i]);
  }
  if (restart) /* a restart carries no list: take the system's bodies */
    for (int r = 0; r < sys->nbody; r++) us_bitset_set(&spy.mirror, sys->body[r]);
  /* the mirror must now equal the system's bodies exactly */
  if (us_bitset_count(&spy.mirror) != sys->nbody) spy.errors++;
  for (int r = 0; r < sys->nbody; r++)
    if (!us_bitset_get(&spy.mirror, sys->body[r])) spy.errors++;
  return us_backend_clp.solve(ws, pb, out, err);
}

static const us_Backend spy_backend = {
    .method = US_METHOD_LP, .create = spy_create, .destroy = spy_destroy, .solve = spy_solve};

static unsigned long long rng_state = 12345;
static double rnd(void) { return test_lcg(&rng_state); }

/* A 3 x 3 wall of unit bricks (odd row shifted by 0.3) on a fixed pier. */
static us_Structure *small_wall(void) {
  us_Structure *s = us_structure_new(2);
  double pier[8] = {-1, 0, 4, 0, 4, 0.5, -1, 0.5};
  scene_polygon(s, "pier", 4, pier, 1);
  char id[32];
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) {
      snprintf(id, sizeof id, "b%d%d", r, c);
      scene_box(s, id, c + (r % 2) * 0.3, 0.5 + r * 0.6, 1, 0.6, 1);
    }
  return scene_seal(s);
}

static void random_subset(us_Bitset *p) {
  memset(p->w, 0, (size_t)p->nwords * 8);
  for (int i = 0; i < p->nbits; i++)
    if (rnd() < 0.6) us_bitset_set(p, i);
}

/* Random sequences of sub-assemblies on one workspace give the verdicts of
 * fresh workspaces, and the backend always sees a consistent add/remove
 * list (restart only on the first call). */
static void order_independence(void) {
  us_Structure *s = small_wall();
  CHECK(s);
  us_Error err;
  memset(&spy, 0, sizeof spy);
  us_Stability *w = us_stability_new_backend(s, NULL, &spy_backend, &err);
  CHECK(w);
  us_Bitset p;
  CHECK(us_bitset_init(&p, s->nbody) == 0);
  us_StabilityResult res = {0};
  int nstable = 0, nunstable = 0, nempty = 0, nloose = 0;
  for (int t = 0; t < 150; t++) {
    random_subset(&p);
    if (t % 7 == 3) us_bitset_fill(&p);
    CHECK_OK(us_stability_test(w, &p, &res, &err), &err);
    int fresh = scene_verdict(s, t % 2 ? US_METHOD_LP : US_METHOD_LPSOLVE, &p);
    CHECK_INT(res.verdict, ==, fresh);
    if (res.verdict == US_STABLE) CHECK(res.check.ok);
    nstable += res.verdict == US_STABLE;
    nunstable += res.verdict == US_UNSTABLE;
    nempty += us_bitset_count(&p) - us_bitset_get(&p, 0) == 0;
    /* a body touching nothing is decided by the front end */
    nloose += strcmp(res.note, "a body with weight touches nothing") == 0;
  }
  CHECK_INT(spy.errors, ==, 0);
  CHECK_INT(spy.calls, ==, 150 - nempty - nloose);
  CHECK(nstable > 10 && nunstable > 10); /* the sample exercises both */
  CHECK_INT(us_stability_info(w)->tests, ==, 150);
  us_stability_result_free(&res);
  us_bitset_free(&p);
  us_stability_free(w);
  us_structure_free(s);
}

/* Out of memory at every allocation of new + test (+ a second test that
 * grows the result): US_ERR_NOMEM, never a crash or leak; then success. */
static void out_of_memory(void) {
  us_Structure *s = small_wall();
  CHECK(s);
  us_Bitset p, q;
  CHECK(us_bitset_init(&p, s->nbody) == 0 && us_bitset_init(&q, s->nbody) == 0);
  us_bitset_set(&p, 1);
  us_bitset_fill(&q);
  for (int mi = 0; mi < 2; mi++) {
    us_StabilitySettings set = us_stability_default_settings();
    set.method = lp_methods[mi];
    int succeeded = 0;
    for (long n = 0; n < 200 && !succeeded; n++) {
      long live0 = us_alloc_live();
      us_Error err;
      us_StabilityResult res = {0};
      us_alloc_fail_after(n);
      us_Status st = US_ERR_NOMEM;
      us_Stability *w = us_stability_new(s, &set, &err);
      if (w) st = us_stability_test(w, &p, &res, &err);
      if (w && st == US_OK) st = us_stability_test(w, &q, &res, &err);
      us_alloc_fail_after(-1);
      if (!w) CHECK_INT(err.code, ==, US_ERR_NOMEM);
      CHECK(st == US_OK || st == US_ERR_NOMEM);
      if (st == US_OK) {
        CHECK_INT(res.verdict, ==, US_STABLE);
        succeeded = 1;
      }
      us_stability_result_free(&res);
      us_stability_free(w);
      CHECK_INT(us_alloc_live(), ==, live0);
    }
    CHECK(succeeded);
  }
  us_bitset_free(&p);
  us_bitset_free(&q);
  us_structure_free(s);
}

/* One result reused over many tests of varying size stays consistent. */
static void result_reuse(void) {
  us_Structure *s = small_wall();
  CHECK(s);
  us_Error err;
  us_Stability *w = us_stability_new(s, NULL, &err);
  CHECK(w);
  us_Bitset p;
  CHECK(us_bitset_init(&p, s->nbody) == 0);
  us_StabilityResult res = {0};
  int idx[256];
  CHECK(s->ncontact <= 256);
  for (int t = 0; t < 40; t++) {
    random_subset(&p);
    CHECK_OK(us_stability_test(w, &p, &res, &err), &err);
    if (res.verdict == US_STABLE) {
      CHECK_INT(res.forces.ncontact, ==, us_active_contacts(s, &p, idx));
      us_CertCheck again = us_certificate_check(s, &p, &res.forces, 1e-6);
      CHECK(again.ok);
    } else {
      CHECK_INT(res.forces.ncontact, ==, 0);
    }
  }
  us_stability_result_free(&res);
  us_bitset_free(&p);
  us_stability_free(w);
  us_structure_free(s);
}

/* The dense simplex of lp_small.c settles small systems by itself, both
 * ways: a feasible answer (checked against its residual) or a Farkas ray
 * from the duals of its final basis that passes the ray's own check;
 * wrong duals would be rejected and the verdict would stay undecided. */
static void small_lp_settles(void) {
  const double dx[] = {-0.8, -0.6, -0.3, 0.0, 0.2, 0.45, 0.55, 0.65, 0.9};
  for (int k = 0; k < (int)(sizeof dx / sizeof dx[0]); k++) {
    us_Structure *s = two_blocks(dx[k]);
    CHECK(s);
    us_Error err;
    us_StabilitySettings set = us_stability_default_settings();
    us_EqSystem eq;
    us_Bitset p;
    CHECK(us_eq_init(&eq, s) == 0 && us_bitset_init(&p, s->nbody) == 0);
    us_bitset_fill(&p);
    CHECK(us_eq_build(&eq, &p) == 0);
    void *ws = us_backend_small.create(s, &set, &err);
    CHECK(ws);
    double f[64] = {0};
    char note[128];
    us_StabilityInfo info = {0};
    CHECK(eq.ncontact * eq.dim < 64);
    us_BackendOut out = {US_UNDECIDED, f, &info, note, sizeof note};
    CHECK_OK(us_backend_small.solve(ws, &(us_BackendProblem){.sys = &eq, .restart = 1}, &out, &err),
             &err);
    CHECK_INT(out.verdict, ==, fabs(dx[k]) < 0.5 ? US_STABLE : US_UNSTABLE);
    const double *y = NULL;
    int ny = us_backend_small.farkas_ray(ws, &y);
    if (out.verdict == US_UNSTABLE) CHECK(ny == eq.nbody * eq.nw && y);
    if (out.verdict == US_UNSTABLE) CHECK(us_backend_small.unstable_body(ws) >= 0);
    us_backend_small.destroy(ws);
    us_bitset_free(&p);
    us_eq_free(&eq);
    us_structure_free(s);
  }
}

US_TEST_MAIN(T(names_and_defaults), T(point_body_support), T(single_block), T(overhanging_body),
             T(two_block_column), T(cantilever), T(inverted_v), T(sub_assemblies),
             T(empty_and_active), T(floating_and_usage), T(unstable_evidence), T(never_stable_without_certificate),
             T(order_independence), T(out_of_memory), T(result_reuse), T(small_lp_settles))
