/* Plumb-line load paths (src/stability/plumb.c, docs/local.md).
 *
 * A route is a stable proof without an LP, so what matters is that it is
 * claimed only when the forces it leaves hold every body (the independent
 * certificate check over the changed bodies, and the full check), that it
 * leaves the forces exactly as they were when it refuses, and that it
 * refuses where no vertical load path exists (a cantilever, a contact
 * too steep for its friction), agreeing with the full LP there. Forces
 * are never compared with particular values: they are not unique. */
#include "model/massprops.h"
#include "scenes.h"
#include "stability/certificate.h"
#include "stability/equilibrium.h" /* us_contact_active */
#include "stability/plumb.h"
#include "test.h"

/* The incidence (body -> contacts) that local.c builds, for the tests. */
typedef struct Inc {
  int *start, *list;
} Inc;

static int inc_build(const us_Structure *s, Inc *in) {
  in->start = calloc((size_t)s->nbody + 1, sizeof(int));
  in->list = malloc((size_t)(2 * s->ncontact + 1) * sizeof(int));
  int *fill = malloc(((size_t)s->nbody + 1) * sizeof(int));
  if (!in->start || !in->list || !fill) return free(fill), -1;
  for (int c = 0; c < s->ncontact; c++) {
    if (s->contacts[c].a >= 0) in->start[s->contacts[c].a + 1]++;
    if (s->contacts[c].b >= 0) in->start[s->contacts[c].b + 1]++;
  }
  for (int i = 0; i < s->nbody; i++) in->start[i + 1] += in->start[i];
  memcpy(fill, in->start, (size_t)s->nbody * sizeof(int));
  for (int c = 0; c < s->ncontact; c++) {
    if (s->contacts[c].a >= 0) in->list[fill[s->contacts[c].a]++] = c;
    if (s->contacts[c].b >= 0) in->list[fill[s->contacts[c].b]++] = c;
  }
  free(fill);
  return 0;
}

static void inc_free(Inc *in) {
  free(in->start);
  free(in->list);
}

/* The full certificate check of normalized forces f (every contact) on
 * the sub-assembly cur. */
static int full_check(const us_Structure *s, const us_Bitset *cur, const double *f, double mass) {
  size_t dim = (size_t)s->dim, nf = (size_t)s->ncontact * dim;
  us_Forces fo = {.ncontact = 0};
  fo.contact = malloc((size_t)s->ncontact * sizeof(int) + 1);
  fo.f = malloc(nf * sizeof(double) + 1);
  double w = mass * us_gravity_norm(s->gravity);
  int idle = 1; /* no force on a contact with an absent side */
  for (int k = 0; k < s->ncontact; k++) {
    if (!us_contact_active(s, cur, k)) {
      for (size_t j = 0; j < dim; j++) idle &= f[(size_t)k * dim + j] == 0.0;
      continue;
    }
    fo.contact[fo.ncontact] = k;
    for (size_t j = 0; j < dim; j++) fo.f[(size_t)fo.ncontact * dim + j] = f[(size_t)k * dim + j] * w;
    fo.ncontact++;
  }
  us_CertCheck full = us_certificate_check(s, cur, &fo, 1e-9);
  if (!idle) fprintf(stderr, "a force on a contact with an absent side\n"), full.ok = 0;
  if (!full.ok)
    fprintf(stderr, "forces fail the full check (force %g torque %g cone %g sign %g)\n",
            full.max_force_residual, full.max_torque_residual, full.max_cone_violation,
            full.max_sign_violation);
  free(fo.contact);
  free(fo.f);
  return full.ok;
}

/* A router on s from zero forces: the incidence, an empty sub-assembly,
 * the forces and the movable bodies (all = 1: all present). */
typedef struct Rig {
  Inc in;
  us_Bitset cur;
  us_Plumb p;
  double *f, mass;
  size_t nf;
  int *added, nadd;
} Rig;

static int rig_open(Rig *r, const us_Structure *s, int all) {
  double up[3] = {0, 1, 0};
  memset(r, 0, sizeof *r);
  r->nf = (size_t)s->ncontact * 2;
  r->f = calloc(r->nf + 1, sizeof(double));
  r->added = malloc(((size_t)s->nbody + 1) * sizeof(int));
  if (!r->f || !r->added || inc_build(s, &r->in) || us_bitset_init(&r->cur, s->nbody)) return -1;
  r->mass = us_movable_mass(s);
  if (us_plumb_init(&r->p, s, r->in.start, r->in.list, up, r->mass)) return -1;
  for (int i = 0; all && i < s->nbody; i++)
    if (!s->bodies[i].fixed) us_bitset_set(&r->cur, i), r->added[r->nadd++] = i;
  return 0;
}

static void rig_close(Rig *r) {
  us_plumb_free(&r->p);
  us_bitset_free(&r->cur);
  inc_free(&r->in);
  free(r->f);
  free(r->added);
}

/* 0 when every force is still zero (a refused route left nothing). */
static int all_zero(const Rig *r, const char *what) {
  for (size_t k = 0; k < r->nf; k++)
    if (r->f[k] != 0.0) return fprintf(stderr, "refused %s route left a force\n", what), -1;
  return 0;
}

/* Lazy routing (memoised lines): route every movable body at once, then
 * materialize; same contract as route_all below. */
static int route_all_lazy(const us_Structure *s) {
  Rig g;
  int out = -1;
  if (rig_open(&g, s, 1)) return rig_close(&g), -1;
  int r = us_plumb_route_lazy(&g.p, &g.cur, g.added, g.nadd, 1e-9);
  if (r >= 0 && us_plumb_materialize(&g.p, g.f) == 0) /* refused: the loads were taken back */
    out = r == 1 ? (full_check(s, &g.cur, g.f, g.mass) ? 1 : -1) : all_zero(&g, "lazy");
  rig_close(&g);
  return out;
}

/* The local tests' re-check (us_certificate_check_list: each contact
 * measured once) against the per-body one on g's path, as routed and with
 * one routed force turned to pull (a sign violation both must see). */
static int checks_agree(const us_Structure *s, Rig *g, int *slot, double *acc) {
  us_CertCheck a, b;
  us_certificate_check_bodies(s, &g->cur, g->p.path, g->p.npath, g->in.start, g->in.list, g->f,
                              g->mass, 1e-9, &a);
  us_certificate_check_list(s, &g->cur, g->p.path, g->p.npath, g->in.start, g->in.list, g->f,
                            g->mass, 1e-9, slot, acc, &b);
  for (int i = 0; i < s->nbody; i++)
    if (slot[i] != -1) return fprintf(stderr, "check_list left slot %d set\n", i), 0;
  double tol = 1e-12;
  int same = a.ok == b.ok && fabs(a.max_force_residual - b.max_force_residual) <= tol &&
             fabs(a.max_torque_residual - b.max_torque_residual) <= tol &&
             a.max_cone_violation == b.max_cone_violation &&
             a.max_sign_violation == b.max_sign_violation;
  if (!same)
    fprintf(stderr, "check_list %d (%g %g %g %g) against check_bodies %d (%g %g %g %g)\n", b.ok,
            b.max_force_residual, b.max_torque_residual, b.max_cone_violation,
            b.max_sign_violation, a.ok, a.max_force_residual, a.max_torque_residual,
            a.max_cone_violation, a.max_sign_violation);
  return same;
}

static int list_check_agrees(const us_Structure *s, Rig *g) {
  int *slot = malloc(((size_t)s->nbody + 1) * sizeof(int));
  double *acc = malloc(((size_t)g->p.npath + 1) * US_CERT_ACC * sizeof(double));
  int ok = slot && acc;
  for (int i = 0; ok && i < s->nbody; i++) slot[i] = -1;
  ok = ok && checks_agree(s, g, slot, acc);
  int c = -1; /* the largest routed normal force, turned to a pull */
  for (int q = 0; q < s->ncontact; q++)
    if (g->f[2 * (size_t)q] > 0 && (c < 0 || g->f[2 * (size_t)q] > g->f[2 * (size_t)c])) c = q;
  if (ok && c >= 0) {
    g->f[2 * (size_t)c] = -g->f[2 * (size_t)c];
    ok = checks_agree(s, g, slot, acc);
    us_CertCheck b;
    us_certificate_check_list(s, &g->cur, g->p.path, g->p.npath, g->in.start, g->in.list, g->f,
                              g->mass, 1e-9, slot, acc, &b);
    if (b.ok) ok = 0, fprintf(stderr, "check_list passed a pulling contact\n");
    g->f[2 * (size_t)c] = -g->f[2 * (size_t)c];
  }
  free(slot);
  free(acc);
  return ok;
}

/* Route every movable body of s at once from zero forces: 1 routed (and
 * the forces pass the check on the path and the full check), 0 refused
 * (forces still all zero), -1 a failure (reported). npath: path size.
 * The lazy routing must give the same answer. */
static int route_all(const us_Structure *s, int *npath) {
  Rig g;
  int out = -1;
  if (rig_open(&g, s, 1)) return rig_close(&g), -1;
  int r = us_plumb_route(&g.p, &g.cur, g.added, g.nadd, g.f);
  *npath = g.p.npath;
  if (r == 0) {
    out = all_zero(&g, "eager");
  } else if (r == 1) {
    us_CertCheck c;
    us_certificate_check_bodies(s, &g.cur, g.p.path, g.p.npath, g.in.start, g.in.list, g.f,
                                g.mass, 1e-9, &c);
    out = c.ok && full_check(s, &g.cur, g.f, g.mass) ? 1 : -1;
    if (!c.ok) fprintf(stderr, "routed forces fail the path check (force %g torque %g cone %g)\n",
                       c.max_force_residual, c.max_torque_residual, c.max_cone_violation);
    if (out == 1 && !list_check_agrees(s, &g)) out = -1;
  }
  rig_close(&g);
  int lazy = route_all_lazy(s);
  if (lazy != out) fprintf(stderr, "lazy routing %d, eager %d\n", lazy, out);
  return lazy == out ? out : -1;
}

/* The full LP's verdict on all of s. */
static us_Verdict lp_verdict(const us_Structure *s) {
  us_StabilitySettings set = us_stability_default_settings();
  set.method = US_METHOD_LP;
  set.local = -1;
  us_StabilityResult res;
  us_stability_result_init(&res);
  us_Stability *w = us_stability_new(s, &set, NULL);
  us_Verdict v = US_UNDECIDED;
  if (w && us_stability_test_full(w, &res, NULL) == US_OK) v = res.verdict;
  us_stability_free(w);
  us_stability_result_free(&res);
  return v;
}

/* ------------------------------------------------------------------ cases */

static void column_routes(void) {
  us_Structure *s = scene_column(6);
  CHECK(s);
  int n;
  CHECK_INT(route_all(s, &n), ==, 1);
  CHECK_INT(n, ==, 6);
  us_structure_free(s);
}

/* A plank across two piers, its centre over the gap: the line splits
 * between the piers. */
static void bridge_splits(void) {
  us_Structure *s = us_structure_new(2);
  scene_box(s, "P1", 0, 0, 1, 1, 1);
  scene_box(s, "P2", 2, 0, 1, 1, 1);
  scene_box(s, "plank", 0.5, 1, 2.5, 0.2, 1);
  CHECK(scene_seal(s));
  int n;
  CHECK_INT(route_all(s, &n), ==, 1);
  CHECK_INT(n, ==, 3);
  us_structure_free(s);
}

/* A plank on one pier, its centre beyond it: no vertical path (the plank
 * falls; a route would be a false proof). */
static void cantilever_refused(void) {
  us_Structure *s = us_structure_new(2);
  scene_box(s, "P", 0, 0, 1, 1, 1);
  scene_box(s, "plank", 0.5, 1, 2.5, 0.2, 1);
  CHECK(scene_seal(s));
  int n;
  CHECK_INT(route_all(s, &n), ==, 0);
  CHECK_INT(lp_verdict(s), ==, US_UNSTABLE);
  us_structure_free(s);
}

/* A square on a fixed 30 degree ramp: a vertical load through the slope
 * needs mu >= tan 30 = 0.577. Below, the route refuses (and the block
 * slides); above, it routes. */
static us_Structure *ramp(double mu) {
  us_Structure *s = us_structure_new(2);
  double a = atan(1.0) * 4 / 6, t = tan(a), c = cos(a), sn = sin(a);
  double tri[6] = {0, 0, 4, 0, 4, 4 * t};
  double x0 = 1.5, y0 = 1.5 * t, e = 0.5;
  double sq[8] = {x0, y0, x0 + e * c, y0 + e * sn, x0 + e * c - e * sn, y0 + e * sn + e * c,
                  x0 - e * sn, y0 + e * c};
  us_BodyDef d = us_default_body_def();
  d.id = "ramp", d.nvert = 3, d.xy = tri, d.fixed = 1, d.friction = mu;
  us_structure_add_body(s, &d, NULL);
  d = us_default_body_def();
  d.id = "block", d.nvert = 4, d.xy = sq, d.friction = mu;
  us_structure_add_body(s, &d, NULL);
  return scene_seal(s);
}

static void steep_contact(void) {
  static const double mus[] = {0.0, 0.3, 0.55, 0.6, 1.0, INFINITY};
  for (int k = 0; k < 6; k++) {
    us_Structure *s = ramp(mus[k]);
    CHECK(s);
    CHECK(s->ncontact >= 2);
    int n, stands = mus[k] > 0.5774;
    CHECK_INT(route_all(s, &n), ==, stands);
    CHECK_INT(lp_verdict(s), ==, stands ? US_STABLE : US_UNSTABLE);
    us_structure_free(s);
  }
}

/* A plank X from a block V to a pier W, its centre over the gap. V rests
 * on a pier U under its left part only, so V's right corner overhangs
 * U: the support point of X nearest X's centre on V's side is that
 * corner, and a line there finds no support on its right in V. The
 * other end of X's joint with V is over U: the lazy route, refused at the
 * corner, starts over without that point and routes (the eager routing,
 * with no second try, refuses); the forces pass the full check, and the
 * LP agrees that all stands. */
static void retry_other_point(void) {
  us_Structure *s = us_structure_new(2);
  scene_box(s, "U", 0, 0, 1.6, 1, 1);
  scene_box(s, "V", 0, 1, 2, 1, 1);
  scene_box(s, "W", 3, 0, 1, 2, 1);
  scene_box(s, "X", 1.5, 2, 2.5, 0.2, 1);
  CHECK(scene_seal(s));
  CHECK_INT(route_all_lazy(s), ==, 1);
  Rig g;
  CHECK(rig_open(&g, s, 1) == 0);
  CHECK_INT(us_plumb_route(&g.p, &g.cur, g.added, g.nadd, g.f), ==, 0);
  rig_close(&g);
  CHECK_INT(lp_verdict(s), ==, US_STABLE);
  us_structure_free(s);
}

/* Whole plans of a wall and a pyramid: the assembly's tests are proven by
 * plumb lines (not by LPs), and the plans verify. */
static void plans_use_plumb_lines(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  for (int kind = 0; kind < 2; kind++) {
    g.rows = 12, g.cols = 12, g.n = 12;
    us_Structure *s = kind ? us_gen_pyramid(&g, &err) : us_gen_wall(&g, &err);
    CHECK(s);
    us_PlanSettings ps = us_plan_default_settings();
    us_Plan plan;
    CHECK_INT(us_plan(s, &ps, &plan, &err), ==, US_OK);
    CHECK_INT(plan.status, ==, US_PLAN_FOUND);
    CHECK_INT(plan.nsteps, ==, s->nbody);
    const us_StabilityInfo *in = &plan.stats.stability;
    CHECK(in->local_plumb > 0);
    CHECK(in->local_plumb <= in->local_stable);
    CHECK_INT(in->local_plumb, >=, plan.stats.tests * 9 / 10);
    us_VerifyReport rep;
    CHECK_INT(us_verify_order(s, &ps.stability, plan.order, plan.nsteps, &rep, &err), ==, US_OK);
    CHECK(rep.ok);
    us_plan_free(&plan);
    us_structure_free(s);
  }
}

/* Lazy routing, one body at a time from the bottom (a plan's assembly):
 * after every step the pending loads pushed down the memoised lines give
 * forces that pass the full check (materialized on a copy), a refused
 * body (a cantilever tip added on the way) changes nothing, and the lines
 * routed over the whole walk stay within a few per body (each line is
 * routed once: O(1) per body, not the path's height). */
static void lazy_walk(us_Structure *s, int expect_lines_per_body) {
  Rig g;
  CHECK(rig_open(&g, s, 0) == 0);
  int n = s->nbody, *order = malloc((size_t)n * sizeof(int)), lines = 0, ok = 1, steps = 0;
  for (int i = 0; i < n; i++) order[i] = i;
  for (int i = 1; i < n; i++) /* by centre height, insertion sort */
    for (int j = i; j > 0 && s->bodies[order[j]].com[1] < s->bodies[order[j - 1]].com[1]; j--) {
      int t = order[j];
      order[j] = order[j - 1];
      order[j - 1] = t;
    }
  for (int q = 0; q < n && ok; q++) {
    int b = order[q];
    if (s->bodies[b].fixed) continue;
    us_bitset_set(&g.cur, b);
    int r = us_plumb_route_lazy(&g.p, &g.cur, &b, 1, 1e-9);
    lines += g.p.nnew;
    if (r != 1) { /* a body with no path down: it leaves, nothing pending changed */
      us_bitset_clear(&g.cur, b);
      continue;
    }
    if (++steps % 7 == 0 || q == n - 1) /* the certificate so far: pending pushed into f */
      ok = us_plumb_materialize(&g.p, g.f) == 0 && full_check(s, &g.cur, g.f, g.mass);
  }
  CHECK(ok);
  CHECK(steps > 0);
  printf("lazy walk: %d bodies placed, %d lines routed (%d memoised)\n", steps, lines, g.p.nent);
  CHECK_INT(lines, <=, expect_lines_per_body * steps);
  rig_close(&g);
  free(order);
}

static void lazy_walks(void) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.rows = 30, g.cols = 30, g.n = 30;
  us_Structure *s = us_gen_wall(&g, &err);
  CHECK(s);
  if (s) lazy_walk(s, 4);
  us_structure_free(s);
  s = us_gen_pyramid(&g, &err);
  CHECK(s);
  if (s) lazy_walk(s, 4);
  us_structure_free(s);
  /* two columns with a plank overhanging the right one on top: the plank
     is refused, the rest routes */
  s = us_structure_new(2);
  char id[32];
  for (int c = 0; c < 2; c++)
    for (int r = 0; r < 5; r++) {
      snprintf(id, sizeof id, "c%d_%d", c, r);
      scene_box(s, id, 2.0 * c, 0.5 * r, 1, 0.5, 1);
    }
  scene_box(s, "tip", 2.5, 2.5, 3.0, 0.2, 1);
  CHECK(scene_seal(s));
  if (s) lazy_walk(s, 4);
  us_structure_free(s);
}

US_TEST_MAIN(T(column_routes), T(bridge_splits), T(cantilever_refused), T(steep_contact),
             T(retry_other_point), T(plans_use_plumb_lines), T(lazy_walks))
