/* The 3D verdicts (lp, lcp, lcp-reuse) against an independent reference,
 * siconos-numerics' 3D friction-contact solver (fc3d_driver, NSGS:
 * Gauss-Seidel over contacts with a local Newton on each; the global
 * Alart-Curnier Newton failed to converge on most of these problems,
 * whose W is singular: four coplanar contacts per face), on sub-assemblies of small
 * towers, pyramid3d and wall3d, at mu 0.2 and 0.5, under vertical and
 * tilted gravity.
 *
 * What is compared. Siconos solves a dynamics problem in the local
 * (contact) frame: u = W r + q, with r = (r_n, r_t1, r_t2) per contact in
 * the circular Coulomb cone |r_t| <= mu r_n and u the relative velocity,
 * related to r by the De Saxce complementarity (sticking: u = 0; sliding:
 * r on the cone's edge opposing u_t; separating: r = 0). We pose it at
 * the acceleration level over one unit time step from rest: W = J M^-1
 * J^T (J the contact Jacobian over 6 dof per body, M masses and inertia
 * tensors), q = J M^-1 F (F gravity), so u is the contact points'
 * relative acceleration. Its answer r gives every body's acceleration
 * a = M^-1 (J^T r + F), which we compute ourselves:
 *   - a = 0 on every body and r in the circular cones (both checked
 *     here, whatever the solver reports): the forces balance gravity, a
 *     weak-stability certificate found without our code. Our LP is exact for circular cones (docs/cones3d.md), so every
 *     method must then say stable (hard check);
 *   - a clearly non-zero: the reference found the structure moving. With
 *     friction the problem may have several solutions (a structure that can
 *     stand may also have a consistent sliding solution), so this does not
 *     prove that no static forces exist; it is counted, and our unstable
 *     verdicts must be met by moving solutions (a static one would be the
 *     hard check above failing); where we say stable instead, our
 *     certificate must pass (static forces exist beside the sliding ones);
 *   - the solver not converging or a in between: no reference, counted.
 * Forces are never compared (they are not unique). */
#include "test.h"

#include <FrictionContactProblem.h>
#include <Friction_cst.h>
#include <NonSmoothDrivers.h>
#include <NumericsMatrix.h>
#include <SolverOptions.h>

static const double PI = 3.14159265358979323846;

#ifdef US_TEST_SANITIZED
enum { SCALE = 4 }; /* fewer random subsets under the sanitizers */
#else
enum { SCALE = 1 };
#endif

static double rnd(unsigned long long *s) { return test_lcg(s); }

/* Kind 0 tower of 5, 1 turned tower of 5, 2 pyramid3d of 3 levels, 3
 * wall3d 2 x 3; friction mu, gravity tilted by `tilt` towards `az`. */
static us_Structure *scene(int kind, double mu, double tilt, double az, unsigned seed) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.friction = mu;
  g.seed = seed;
  us_Structure *s = NULL;
  switch (kind) {
  case 0: g.n = 5, s = us_gen_tower(&g, &err); break;
  case 1: g.n = 5, g.jitter = 35.0, s = us_gen_tower(&g, &err); break;
  case 2: g.n = 3, s = us_gen_pyramid3d(&g, &err); break;
  default: g.rows = 2, g.cols = 3, s = us_gen_wall3d(&g, &err); break;
  }
  if (!s) {
    fprintf(stderr, "scene %d: %s\n", kind, err.msg);
    return NULL;
  }
  s->gravity[0] = 9.81 * sin(tilt) * cos(az);
  s->gravity[1] = 9.81 * sin(tilt) * sin(az);
  s->gravity[2] = -9.81 * cos(tilt);
  return s;
}

/* Inverse of a symmetric positive definite 3x3 matrix (cofactors). */
static void inv3(const double m[3][3], double r[3][3]) {
  double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1], c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2],
         c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
  double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
  r[0][0] = c00 / det, r[1][0] = c01 / det, r[2][0] = c02 / det;
  r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
  r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
  r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
  r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
  r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
  r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
}

/* The local problem of the present bodies: contact rows J (3 per contact:
 * n, t0, t1; 6 columns per body), M^-1 per body, F gravity. */
typedef struct Sys {
  int nb, nc, *slot; /* slot[body]: its dof block, -1 absent or fixed */
  double *J, *minv, *F; /* J: 3 nc x 6 nb row-major; minv: nb 6x6 blocks */
} Sys;

/* Body k's Jacobian row for direction d at point p, sign sg. */
static void jrow(const us_Structure *s, double *row, int k, int slot, const double *p,
                 const double *d, double sg) {
  const double *c = s->bodies[k].com;
  double r[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
  double *x = row + 6 * slot;
  for (int i = 0; i < 3; i++) x[i] += sg * d[i];
  x[3] += sg * (r[1] * d[2] - r[2] * d[1]);
  x[4] += sg * (r[2] * d[0] - r[0] * d[2]);
  x[5] += sg * (r[0] * d[1] - r[1] * d[0]);
}

static void sys_build(Sys *y, const us_Structure *s, const us_Bitset *b) {
  y->slot = calloc((size_t)s->nbody, sizeof(int));
  y->nb = y->nc = 0;
  for (int k = 0; k < s->nbody; k++)
    y->slot[k] = !s->bodies[k].fixed && us_bitset_get(b, k) ? y->nb++ : -1;
  for (int c = 0; c < s->ncontact; c++) { /* contacts between present or fixed bodies */
    const us_Contact *ct = &s->contacts[c];
    int pa = ct->a == US_GROUND || s->bodies[ct->a].fixed || y->slot[ct->a] >= 0;
    int pb = s->bodies[ct->b].fixed || y->slot[ct->b] >= 0;
    y->nc += pa && pb && (ct->a == US_GROUND ? y->slot[ct->b] >= 0 : y->slot[ct->a] >= 0 || y->slot[ct->b] >= 0);
  }
  y->J = calloc((size_t)(3 * y->nc * 6 * y->nb) + 1, sizeof(double));
  y->minv = calloc((size_t)(36 * y->nb) + 1, sizeof(double));
  y->F = calloc((size_t)(6 * y->nb) + 1, sizeof(double));
  int row = 0;
  for (int c = 0; c < s->ncontact; c++) {
    const us_Contact *ct = &s->contacts[c];
    int sa = ct->a == US_GROUND ? -1 : y->slot[ct->a], sb = y->slot[ct->b];
    int pa = ct->a == US_GROUND || s->bodies[ct->a].fixed || sa >= 0;
    int pb = s->bodies[ct->b].fixed || sb >= 0;
    if (!pa || !pb || (sa < 0 && sb < 0)) continue;
    const double *dir[3] = {ct->n, ct->t[0], ct->t[1]};
    for (int d = 0; d < 3; d++, row++) { /* u = velocity of b relative to a */
      double *r = y->J + (size_t)row * (size_t)(6 * y->nb);
      if (sb >= 0) jrow(s, r, ct->b, sb, ct->p, dir[d], 1.0);
      if (sa >= 0) jrow(s, r, ct->a, sa, ct->p, dir[d], -1.0);
    }
  }
  for (int k = 0; k < s->nbody; k++) {
    int sl = y->slot[k];
    if (sl < 0) continue;
    const us_Body *bd = &s->bodies[k];
    double *mi = y->minv + 36 * sl, ii[3][3];
    inv3(bd->inertia3, ii);
    for (int i = 0; i < 3; i++) {
      mi[i * 6 + i] = 1.0 / bd->mass;
      for (int j = 0; j < 3; j++) mi[(3 + i) * 6 + 3 + j] = ii[i][j];
      y->F[6 * sl + i] = bd->mass * s->gravity[i];
    }
  }
}

static void sys_free(Sys *y) {
  free(y->slot), free(y->J), free(y->minv), free(y->F);
}

/* Body accelerations a = M^-1 (J^T r + F) (6 per body). */
static void accel(const Sys *y, const double *r, double *a) {
  int n = 6 * y->nb;
  for (int k = 0; k < y->nb; k++) {
    double g[6];
    for (int i = 0; i < 6; i++) {
      g[i] = y->F[6 * k + i];
      for (int c = 0; c < 3 * y->nc; c++) g[i] += y->J[(size_t)c * (size_t)n + 6 * (size_t)k + (size_t)i] * r[c];
    }
    for (int i = 0; i < 6; i++) {
      a[6 * k + i] = 0.0;
      for (int j = 0; j < 6; j++) a[6 * k + i] += y->minv[36 * k + 6 * i + j] * g[j];
    }
  }
}

enum { REF_NONE, REF_STATIC, REF_MOVING };

/* Siconos' answer for the sub-assembly: static, moving, or none. The
 * angular part is scaled by the structure's size so both compare with g. */
static int reference(const us_Structure *s, const us_Bitset *b, double *residual, double *amax_out) {
  Sys y;
  sys_build(&y, s, b);
  int n = 6 * y.nb, m = 3 * y.nc, out = REF_NONE;
  double *r = calloc((size_t)m + 1, sizeof(double)), *u = calloc((size_t)m + 1, sizeof(double));
  double *a = calloc((size_t)n + 1, sizeof(double)), *mu = calloc((size_t)y.nc + 1, sizeof(double));
  int info = 0;
  *residual = 0.0;
  if (y.nc > 0) {
    NumericsMatrix *W = NM_create(NM_DENSE, m, m);
    double *q = calloc((size_t)m, sizeof(double)), *mj = calloc((size_t)n, sizeof(double));
    for (int i = 0; i < m; i++) { /* W column i = J M^-1 J_i^T; q = J M^-1 F */
      const double *ji = y.J + (size_t)i * (size_t)n;
      for (int k = 0; k < y.nb; k++)
        for (int p = 0; p < 6; p++) {
          mj[6 * k + p] = 0.0;
          for (int t = 0; t < 6; t++) mj[6 * k + p] += y.minv[36 * k + 6 * p + t] * ji[6 * k + t];
        }
      for (int j = 0; j < m; j++) {
        double w = 0.0;
        for (int p = 0; p < n; p++) w += y.J[(size_t)j * (size_t)n + (size_t)p] * mj[p];
        W->matrix0[j + i * m] = w;
      }
      double qi = 0.0;
      for (int k = 0; k < y.nb; k++)
        for (int p = 0; p < 6; p++)
          for (int t = 0; t < 6; t++) qi += ji[6 * k + p] * y.minv[36 * k + 6 * p + t] * y.F[6 * k + t];
      q[i] = qi;
    }
    int c = 0;
    for (int k = 0; k < s->ncontact; k++) { /* mu of the contacts kept, in order */
      const us_Contact *ct = &s->contacts[k];
      int sa = ct->a == US_GROUND ? -1 : y.slot[ct->a], sb = y.slot[ct->b];
      int pa = ct->a == US_GROUND || s->bodies[ct->a].fixed || sa >= 0;
      int pb = s->bodies[ct->b].fixed || sb >= 0;
      if (pa && pb && (sa >= 0 || sb >= 0)) mu[c++] = ct->mu;
    }
    FrictionContactProblem fc = {3, y.nc, W, q, mu};
    SolverOptions *o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
    o->iparam[SICONOS_IPARAM_MAX_ITER] = 2000;
    o->dparam[SICONOS_DPARAM_TOL] = 1e-9;
    info = fc3d_driver(&fc, r, u, o);
    *residual = o->dparam[SICONOS_DPARAM_RESIDU];
    solver_options_delete(o);
    free(o);
    free(NM_free(W)); /* NULL once it freed the struct itself */
    free(q), free(mj);
  }
  accel(&y, r, a);
  double amax = 0.0, L = s->scale;
  for (int k = 0; k < y.nb; k++)
    for (int i = 0; i < 6; i++) amax = fmax(amax, fabs(a[6 * k + i]) * (i < 3 ? 1.0 : L));
  int incone = 1; /* checked here, whatever the solver reports */
  double rmax = 0.0;
  for (int c = 0; c < m; c++) rmax = fmax(rmax, fabs(r[c]));
  for (int c = 0; c < y.nc; c++)
    incone &= r[3 * c] >= -1e-9 * rmax &&
              hypot(r[3 * c + 1], r[3 * c + 2]) <= mu[c] * r[3 * c] + 1e-9 * rmax;
  *amax_out = amax / 9.81;
  if (incone && amax <= 1e-5 * 9.81) out = REF_STATIC; /* a certificate, converged or not */
  if (info == 0 && amax >= 1e-3 * 9.81) out = REF_MOVING;
  free(r), free(u), free(a), free(mu);
  sys_free(&y);
  return out;
}

typedef struct Tally {
  long tests, stat_stable, mov_unstable, mov_stable, none;
} Tally;

static const us_Method METHODS[3] = {US_METHOD_LP, US_METHOD_LCP, US_METHOD_LCP_REUSE};

/* Walk structure s: prefixes, shrinking suffixes, random subsets. */
static void walk(const us_Structure *s, int extra, unsigned long long *rng, Tally *t) {
  us_Stability *w[3] = {0};
  us_StabilityResult res[3];
  us_Error err;
  for (int m = 0; m < 3; m++) {
    us_StabilitySettings set = us_stability_default_settings();
    set.method = METHODS[m];
    set.local = -1;
    w[m] = us_stability_new(s, &set, &err);
    CHECK(w[m]);
    us_stability_result_init(&res[m]);
  }
  us_Bitset b;
  us_bitset_init(&b, s->nbody);
  int n = s->nbody;
  for (int k = 0; w[0] && w[1] && w[2] && k < 2 * n + extra && !us_test_failed; k++) {
    for (int i = 0; i < n; i++) {
      int on = k < n ? i <= k : k < 2 * n ? i < 2 * n - k : rnd(rng) < 0.7;
      if (on)
        us_bitset_set(&b, i);
      else
        us_bitset_clear(&b, i);
    }
    for (int m = 0; m < 3; m++) CHECK_OK(us_stability_test(w[m], &b, &res[m], &err), &err);
    for (int m = 1; m < 3; m++) CHECK_INT(res[m].verdict, ==, res[0].verdict);
    double resid, am;
    int ref = reference(s, &b, &resid, &am);
    t->tests++;
    if (ref == REF_STATIC) { /* a certificate from siconos: we must find one */
      CHECK_INT(res[0].verdict, ==, US_STABLE);
      t->stat_stable++;
    } else if (ref == REF_MOVING && res[0].verdict == US_STABLE) {
      /* a sliding solution beside our checked static one (non-uniqueness) */
      CHECK(res[0].check.ok);
      t->mov_stable++;
    } else if (ref == REF_MOVING) {
      t->mov_unstable += res[0].verdict == US_UNSTABLE;
    } else {
      t->none++;
    }
    if (getenv("SICONOS3_VERBOSE") && (ref == REF_NONE || (ref == REF_MOVING) != (res[0].verdict == US_UNSTABLE)))
      fprintf(stderr, "test %ld: verdict %d ref %d residual %.1e |a|/g %.1e\n", t->tests, (int)res[0].verdict, ref,
              resid, am);
  }
  us_bitset_free(&b);
  for (int m = 0; m < 3; m++) {
    us_stability_result_free(&res[m]);
    us_stability_free(w[m]);
  }
}

/* Every kind at mu 0.2 and 0.5, vertical and tilted gravity. */
static void fc3d_reference(void) {
  Tally t = {0};
  unsigned long long rng = 99991ull;
  static const double MU[2] = {0.2, 0.5};
  for (int kind = 0; kind < 4 && !us_test_failed; kind++)
    for (int mi = 0; mi < 2; mi++)
      for (int sd = 0; sd < 2; sd++) {
        double tilt = sd ? 0.05 + 0.15 * rnd(&rng) : 0.0, az = 2 * PI * rnd(&rng);
        us_Structure *s = scene(kind, MU[mi], tilt, az, 5u + (unsigned)sd);
        CHECK(s);
        if (s) walk(s, 30 / SCALE, &rng, &t);
        us_structure_free(s);
      }
  fprintf(stderr,
          "%ld sub-assemblies: siconos static %ld (all stable here), moving %ld where we say "
          "unstable, moving %ld where we say stable (a sliding solution beside a static one), "
          "no reference %ld\n",
          t.tests, t.stat_stable, t.mov_unstable, t.mov_stable, t.none);
  CHECK(t.stat_stable > 100 / SCALE && t.mov_unstable > 50 / SCALE); /* both sides exercised */
  CHECK(t.mov_stable * 50 <= t.tests); /* sliding beside static stays rare */
  CHECK(t.none * 10 <= t.tests);      /* the reference answers almost everywhere */
}

US_TEST_MAIN(T(fc3d_reference))
