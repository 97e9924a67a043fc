/* Tests of the LCP's clamped-system factorization on its own (lcp_factor.c,
 * with the dense inverse of lcp_dense.c; no solver): long random sequences
 * of members joining (clamped rows and friction bound rows) and leaving,
 * with refactorizations in between, checked after every change against
 * the system matrix built densely from its definition: K x = r must hold
 * for random r. Index 2c is a normal, 2c + 1 its friction. */
#include "stability/lcp_factor.h"
#include "lcp_dense.h"
#include "test.h"

#define N 48 /* 24 contacts: normal 2c, friction 2c + 1 */

static unsigned long long seed = 88172645463325252ULL;
static double rnd(void) { return test_rnd(&seed); }

/* A symmetric positive definite A (B B^T / N + 0.2 I). */
static void random_spd(double *A) {
  double B[N * N];
  for (int i = 0; i < N * N; i++) B[i] = rnd() - 0.5;
  for (int i = 0; i < N; i++)
    for (int j = 0; j < N; j++) {
      double s = i == j ? 0.2 : 0.0;
      for (int t = 0; t < N; t++) s += B[i * N + t] * B[j * N + t] / N;
      A[i * N + j] = s;
    }
}

#define MU 0.5

/* K(row member m, column index j) from the definition of the rows: a
 * clamped row is row m of A, a bound row f_m + coef f_n = 0. */
static double k_entry(const us_LcpFactor *F, const double *A, int m, int j) {
  if (F->row[m] == US_LCP_ROW_CLAMP) return A[m * N + j];
  if (j == m) return 1.0;
  return j == F->bnorm[m] ? F->bcoef[m] : 0.0;
}

/* Largest |K x - r| over the members for a random r, relative. */
static double solve_error(us_LcpFactor *F, const double *A) {
  double r[N], x[N], err = 0.0, scale = 1.0;
  for (int s = 0; s < F->k; s++) r[s] = rnd() - 0.5;
  us_lcp_fac_solve(F, r, x);
  for (int s = 0; s < F->k; s++) scale = US_MAX(scale, fabs(x[s]));
  for (int s = 0; s < F->k; s++) {
    double v = -r[s];
    for (int t = 0; t < F->k; t++) v += k_entry(F, A, F->mem[s], F->mem[t]) * x[t];
    err = US_MAX(err, fabs(v));
  }
  return err / scale;
}

/* Index i joins with a clamped row (bound_normal < 0) or the bound row
 * f_i + coef f_n = 0: u, v, alpha from the definition. */
static int join(us_LcpFactor *F, const double *A, int i, int bound_normal, double coef) {
  double u[N], v[N];
  for (int s = 0; s < F->k; s++) {
    int m = F->mem[s];
    u[s] = k_entry(F, A, m, i);
    v[s] = bound_normal < 0 ? A[i * N + m] : m == i ? 1.0 : m == bound_normal ? coef : 0.0;
  }
  double alpha = bound_normal < 0 ? A[i * N + i] : 1.0;
  return us_lcp_fac_append(F, i, bound_normal, coef, u, v, alpha, 1e-12);
}

/* A random candidate that may join now, or -1 (a friction joins only
 * once its normal is a member, as in the solver). */
static int candidate(const us_LcpFactor *F) {
  int i = (int)(rnd() * N);
  if (F->pos[i] >= 0) return -1;
  if (i % 2 && F->pos[i - 1] < 0) return -1;
  return i;
}

static void add_one(us_LcpFactor *F, const double *A) {
  int i = candidate(F);
  if (i < 0) return;
  int bound = i % 2 && rnd() < 0.5; /* a friction at its bound */
  double coef = bound ? (rnd() < 0.5 ? -MU : MU) : 0.0;
  CHECK_INT(join(F, A, i, bound ? i - 1 : -1, coef), ==, 0); /* A is positive definite */
}

/* A member leaves; a normal takes its friction along (as the solver does). */
static void remove_one(us_LcpFactor *F) {
  if (F->k == 0) return;
  int i = F->mem[(int)(rnd() * F->k)], dep[N], nd;
  if (i % 2 == 0 && F->pos[i + 1] >= 0) {
    CHECK_INT(us_lcp_fac_delete(F, F->pos[i + 1], dep, &nd), ==, 0);
    CHECK_INT(F->pos[i + 1], ==, -1);
  }
  CHECK_INT(us_lcp_fac_delete(F, F->pos[i], dep, &nd), ==, 0);
  CHECK_INT(F->row[i], ==, US_LCP_ROW_NONE);
}

/* One random walk with border limit `limit` (0: refactorize every time). */
static void walk(int limit, int steps) {
  double A[N * N], b[N] = {0};
  random_spd(A);
  Dense d = {N, A, b};
  us_LcpOps ops = dense_ops(&d);
  us_LcpFactorSettings set = us_lcp_factor_default_settings();
  set.border_limit = limit;
  us_LcpFactor F;
  CHECK_INT(us_lcp_fac_init(&F, N, &ops, &set), ==, 0);
  double worst = 0.0;
  int dep[N], deferred = 0;
  for (int step = 0; step < steps; step++) {
    if (rnd() < 0.6 - 0.4 * F.k / N)
      add_one(&F, A);
    else
      remove_one(&F);
    if (us_test_failed) break;
    if (us_lcp_fac_stale(&F)) {
      int nd = us_lcp_fac_rebuild(&F, dep);
      CHECK_INT(nd, >=, 0);
      deferred += nd;
    }
    worst = US_MAX(worst, solve_error(&F, A));
  }
  int refactors = (int)F.refactors;
  us_lcp_fac_free(&F);
  CHECK(!us_test_failed);
  CHECK(worst < 1e-10);
  CHECK_INT(deferred, ==, 0);
  if (limit > 0 && limit < 100) CHECK(refactors > 0);
}

static void dense_only(void) { walk(1 << 20, 1500); }
static void small_border(void) { walk(4, 1500); }
static void every_change(void) { walk(0, 600); }
static void medium_border(void) { walk(16, 1500); }

/* A dependent index is refused on arrival; a member that has become
 * dependent (here: A changed under the factorization) is found by the
 * rebuild and returned as dependent, and the rest is factorized. */
static void dependent_member_deferred(void) {
  double A[N * N], b[N] = {0};
  for (int i = 0; i < N * N; i++) A[i] = 0.0;
  for (int i = 0; i < N; i++) A[i * N + i] = 1.0;
  A[2 * N + 2] = A[0] = A[2] = A[2 * N] = 1.0; /* rows 0 and 2 equal */
  Dense d = {N, A, b};
  us_LcpOps ops = dense_ops(&d);
  us_LcpFactor F;
  CHECK_INT(us_lcp_fac_init(&F, N, &ops, NULL), ==, 0);
  int ok = join(&F, A, 0, -1, 0.0) == 0;
  ok &= join(&F, A, 2, -1, 0.0) == 1; /* refused on arrival */
  ok &= F.pos[2] == -1;
  int more[3] = {4, 6, 8};
  for (int j = 0; j < 3; j++) ok &= join(&F, A, more[j], -1, 0.0) == 0;
  A[4 * N + 4] = A[0 * N + 4] = A[4 * N + 0] = 1.0; /* rows 0 and 4 now equal */
  int dep[N], nd = us_lcp_fac_rebuild(&F, dep);
  int k = F.k, gone = nd == 1 ? dep[0] : -1;
  double err = solve_error(&F, A);
  us_lcp_fac_free(&F);
  CHECK(ok);
  CHECK_INT(nd, ==, 1);
  CHECK_INT(k, ==, 3);
  CHECK(gone == 0 || gone == 4);
  CHECK(err < 1e-12);
}

US_TEST_MAIN(T(dense_only), T(small_border), T(every_change), T(medium_border),
             T(dependent_member_deferred))
