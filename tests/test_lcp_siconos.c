/* Our LCP solver (src/stability/lcp.c) against an independent reference,
 * siconos-numerics' lexicographic Lemke solver, on small random
 * frictionless LCPs with A = J M^-1 J^T (PSD, often singular: repeated
 * and dependent contact rows):
 *   - b = J M^-1 F (a physical problem, always solvable): both solve it,
 *     both solutions are complementary (w = A f + b >= 0, f >= 0,
 *     f.w = 0) and give the same body accelerations v = M^-1 (J^T f + F)
 *     (unique for a PSD LCP although f need not be);
 *   - b arbitrary: PSD LCPs are solvable iff feasible; when the reference
 *     finds an accurate solution we must solve too and agree on w (unique
 *     as well); when we find none, neither may the reference (on
 *     infeasible problems Lemke here ends with info 0 and a large error,
 *     which lcp_compute_error exposes; that counts as no solution).
 * Forces f are never compared. */
#include "stability/lcp.h"
#include "lcp_dense.h"
#include "test.h"

#include <LCP_Solvers.h>
#include <LinearComplementarityProblem.h>
#include <NumericsMatrix.h>
#include <SolverOptions.h>
#include <lcp_cst.h>

#define MAXC 10
#define MAXB 4


static unsigned long long rng = 88172645463325252ULL;
static double rnd(void) { return test_rnd(&rng); }
static double uniform(double a, double b) { return a + (b - a) * rnd(); }

/* A random problem: nb bodies (masses, inertias), nc contact rows of one
 * or two bodies (unit normal, lever arm), some rows repeated or negated
 * combinations of others; F gravity plus a random push. */
typedef struct Prob {
  int nb, nc;
  double J[MAXC][3 * MAXB], minv[3 * MAXB], F[3 * MAXB];
  double A[MAXC * MAXC], b[MAXC];
} Prob;

static void random_row(Prob *p, int c) {
  int b0 = (int)(rnd() * p->nb), b1 = rnd() < 0.5 ? -1 : (int)(rnd() * p->nb);
  if (b1 == b0) b1 = -1;
  double ang = uniform(0, 6.283185307179586), nx = cos(ang), ny = sin(ang);
  double rx = uniform(-1, 1), ry = uniform(-1, 1);
  p->J[c][3 * b0] = nx;
  p->J[c][3 * b0 + 1] = ny;
  p->J[c][3 * b0 + 2] = rx * ny - ry * nx;
  if (b1 >= 0) {
    double sx = uniform(-1, 1), sy = uniform(-1, 1);
    p->J[c][3 * b1] = -nx;
    p->J[c][3 * b1 + 1] = -ny;
    p->J[c][3 * b1 + 2] = -(sx * ny - sy * nx);
  }
}

static void random_problem(Prob *p, int physical) {
  memset(p, 0, sizeof *p);
  p->nb = 1 + (int)(rnd() * MAXB);
  p->nc = 1 + (int)(rnd() * MAXC);
  for (int k = 0; k < p->nb; k++) {
    double m = uniform(0.2, 5.0);
    p->minv[3 * k] = p->minv[3 * k + 1] = 1.0 / m;
    p->minv[3 * k + 2] = 1.0 / (m * uniform(0.05, 1.0));
    p->F[3 * k] = uniform(-0.5, 0.5) * m;
    p->F[3 * k + 1] = -9.8 * m;
    p->F[3 * k + 2] = uniform(-0.5, 0.5);
  }
  for (int c = 0; c < p->nc; c++) {
    if (c > 0 && rnd() < 0.2)
      memcpy(p->J[c], p->J[(int)(rnd() * c)], sizeof p->J[c]); /* coincident contact */
    else
      random_row(p, c);
  }
  for (int i = 0; i < p->nc; i++) {
    double bi = 0.0;
    for (int r = 0; r < 3 * p->nb; r++) bi += p->J[i][r] * p->minv[r] * p->F[r];
    p->b[i] = physical ? bi : uniform(-5, 5);
    for (int j = 0; j < p->nc; j++) {
      double s = 0.0;
      for (int r = 0; r < 3 * p->nb; r++) s += p->J[i][r] * p->minv[r] * p->J[j][r];
      p->A[i * p->nc + j] = s;
    }
  }
}

/* Our solver; 1 solved (f, w filled), 0 not. */
static int ours(const Prob *p, double *f, double *w) {
  Dense d = {p->nc, p->A, p->b};
  us_LcpOps ops = dense_ops(&d);
  us_Lcp l;
  if (us_lcp_init(&l, p->nc, &ops)) {
    us_lcp_free(&l);
    return -1;
  }
  int idx[MAXC];
  for (int i = 0; i < p->nc; i++) idx[i] = i;
  us_lcp_add(&l, idx, p->nc);
  int ok = us_lcp_run(&l) == US_LCP_SOLVED;
  us_lcp_refresh(&l);
  for (int i = 0; i < p->nc; i++) {
    f[i] = l.f[i];
    w[i] = l.a[i];
  }
  us_lcp_free(&l);
  return ok;
}

/* Siconos' lexicographic Lemke: 1 solved (and its own error measure
 * lcp_compute_error <= 1e-8), 0 reported unsolvable (ray termination),
 * -1 reported solved with a larger error or an answer that fails our own
 * check: on singular, degenerate
 * problems the reference itself is not reliable, those are skipped. */
/* Complementarity of (f, w) against the problem, scaled tolerance. */
static int complementary(const Prob *p, const double *f, const double *w, double tol) {
  for (int i = 0; i < p->nc; i++) {
    double wi = p->b[i];
    for (int j = 0; j < p->nc; j++) wi += p->A[i * p->nc + j] * f[j];
    if (fabs(wi - w[i]) > tol || f[i] < -tol || wi < -tol ||
        fabs(f[i] * wi) > tol * (1 + fabs(f[i])))
      return 0;
  }
  return 1;
}

static int lemke(const Prob *p, double *z, double *w) {
  NumericsMatrix *M = NM_create(NM_DENSE, p->nc, p->nc);
  for (int i = 0; i < p->nc; i++)
    for (int j = 0; j < p->nc; j++) M->matrix0[i + j * p->nc] = p->A[i * p->nc + j];
  double q[MAXC];
  memcpy(q, p->b, sizeof(double) * (size_t)p->nc);
  LinearComplementarityProblem lcp = {p->nc, M, q};
  SolverOptions *o = solver_options_create(SICONOS_LCP_LEMKE);
  memset(z, 0, sizeof(double) * (size_t)p->nc);
  int info = -1;
  double error = INFINITY;
  lcp_lexicolemke(&lcp, z, w, &info, o);
  if (info == 0) lcp_compute_error(&lcp, z, w, 1e-8, &error);
  solver_options_delete(o);
  free(o); /* the options struct itself stays with the caller */
  NM_free(M);
  if (info != 0) return 0;
  /* siconos' error is relative: on a nearly unbounded problem it has been
   * seen to accept z ~ 1e17 with w < 0. A reference answer counts only if
   * it passes our own absolute check. */
  return error <= 1e-8 && complementary(p, z, w, 1e-6) ? 1 : -1;
}

/* Body accelerations v = M^-1 (J^T f + F). */
static void accelerations(const Prob *p, const double *f, double *v) {
  for (int r = 0; r < 3 * p->nb; r++) {
    double s = p->F[r];
    for (int c = 0; c < p->nc; c++) s += p->J[c][r] * f[c];
    v[r] = p->minv[r] * s;
  }
}

static void physical_problems(void) {
  int solved = 0, unreliable = 0;
  for (int t = 0; t < 2000; t++) {
    Prob p;
    random_problem(&p, 1);
    double f1[MAXC], w1[MAXC], f2[MAXC], w2[MAXC], v1[3 * MAXB], v2[3 * MAXB];
    int a = ours(&p, f1, w1), b = lemke(&p, f2, w2);
    CHECK(a >= 0);
    CHECK_INT(a, ==, 1); /* physical problems are always solvable */
    CHECK(complementary(&p, f1, w1, 1e-7));
    if (b != 1) {
      unreliable++;
      continue;
    }
    CHECK(complementary(&p, f1, w1, 1e-7));
    CHECK(complementary(&p, f2, w2, 1e-6));
    accelerations(&p, f1, v1);
    accelerations(&p, f2, v2);
    for (int r = 0; r < 3 * p.nb; r++) CHECK_NEAR(v1[r], v2[r], 1e-6 * (1 + fabs(v2[r])));
    solved++;
  }
  printf("physical: %d of 2000 problems solved by both, %d with an unreliable reference\n", solved,
         unreliable);
  CHECK(solved > 1500);
}

static void arbitrary_b(void) {
  int both = 0, neither = 0, unreliable = 0;
  for (int t = 0; t < 2000; t++) {
    Prob p;
    random_problem(&p, 0);
    double f1[MAXC], w1[MAXC], f2[MAXC], w2[MAXC];
    int a = ours(&p, f1, w1), b = lemke(&p, f2, w2);
    CHECK(a >= 0);
    if (a != (b == 1) && !(a == 1 && b == -1))
      fprintf(stderr, "problem %d: ours %d, Lemke %d\n", t, a, b);
    if (!a) { /* no solution from us: none from the reference either */
      CHECK(b != 1);
      neither++;
      continue;
    }
    CHECK(complementary(&p, f1, w1, 1e-7));
    if (b != 1) { /* the reference failed on a problem we solved */
      CHECK(b == -1);
      unreliable++;
      continue;
    }
    CHECK(complementary(&p, f2, w2, 1e-6));
    for (int i = 0; i < p.nc; i++) CHECK_NEAR(w1[i], w2[i], 1e-6 * (1 + fabs(w2[i])));
    both++;
  }
  printf("arbitrary b: %d solved by both, %d by neither, %d only by us (reference error > "
         "1e-8)\n",
         both, neither, unreliable);
  CHECK(both > 200 && neither > 50);
  CHECK(unreliable < both / 10);
}

US_TEST_MAIN(T(physical_problems), T(arbitrary_b))
