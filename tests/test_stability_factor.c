/* Tests of the LCP's clamped-system factorization (lcp_factor.c, with the
 * dense inverse of lcp_dense.c): long random sequences of members joining
 * (clamped rows and friction bound rows) and leaving, with refactorizations
 * in between, checked after every change against the system matrix built
 * densely from its definition: K x = r must hold for random r. */
#include "stability/lcp.h"
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

/* K(row member m, column index j) from the definition of the rows. */
static double k_entry(const us_Lcp *p, const double *A, int m, int j) {
  if (p->state[m] == US_LCP_C) return A[m * N + j];
  if (j == m) return 1.0;
  return j == p->partner[m] ? -p->bsign[m] * p->mu[m] : 0.0;
}

/* Largest |K x - r| over the members for a random r, relative. */
static double solve_error(us_Lcp *p, const double *A) {
  double r[N], x[N], err = 0.0, scale = 1.0;
  for (int s = 0; s < p->k; s++) r[s] = rnd() - 0.5;
  us_lcp_fac_solve(p, r, x);
  for (int s = 0; s < p->k; s++) scale = US_MAX(scale, fabs(x[s]));
  for (int s = 0; s < p->k; s++) {
    double v = -r[s];
    for (int t = 0; t < p->k; t++) v += k_entry(p, A, p->mem[s], p->mem[t]) * x[t];
    err = US_MAX(err, fabs(v));
  }
  return err / scale;
}

/* Index i joins (state already set): u, v, alpha from the definition. */
static int join(us_Lcp *p, const double *A, int i) {
  double u[N], v[N];
  for (int s = 0; s < p->k; s++) {
    u[s] = k_entry(p, A, p->mem[s], i);
    v[s] = k_entry(p, A, i, p->mem[s]);
  }
  return us_lcp_fac_append(p, i, u, v, k_entry(p, A, i, i), 1e-12);
}

/* A random candidate that may join now, or -1. */
static int candidate(const us_Lcp *p) {
  int i = (int)(rnd() * N);
  if (p->pos[i] >= 0) return -1;
  if (p->kind[i] == US_LCP_FRICTION && p->state[p->partner[i]] != US_LCP_C) return -1;
  return i;
}

static void add_one(us_Lcp *p, const double *A) {
  int i = candidate(p);
  if (i < 0) return;
  p->state[i] = US_LCP_C;
  if (p->kind[i] == US_LCP_FRICTION && rnd() < 0.5) {
    p->state[i] = US_LCP_BND;
    p->bsign[i] = rnd() < 0.5 ? -1 : 1;
  }
  int r = join(p, A, i);
  CHECK(r == 0); /* A is positive definite: no pivot is tiny */
  if (r) p->state[i] = US_LCP_OFF;
}

/* A member leaves; a normal takes its friction along (as the solver does). */
static void remove_one(us_Lcp *p) {
  if (p->k == 0) return;
  int i = p->mem[(int)(rnd() * p->k)];
  int t = p->partner[i];
  if (p->kind[i] == US_LCP_NORMAL && t >= 0 && p->pos[t] >= 0) {
    CHECK_INT(us_lcp_fac_delete(p, p->pos[t]), ==, 0);
    p->state[t] = US_LCP_OFF;
  }
  CHECK_INT(us_lcp_fac_delete(p, p->pos[i]), ==, 0);
  p->state[i] = US_LCP_OFF;
}

/* One random walk with border limit `limit` (0: refactorize every time). */
static void walk(int limit, int steps) {
  double A[N * N], b[N] = {0};
  random_spd(A);
  Dense d = {N, A, b};
  us_LcpOps ops = dense_ops(&d);
  us_Lcp p;
  CHECK_INT(us_lcp_init(&p, N, &ops), ==, 0);
  for (int c = 0; c < N / 2; c++) us_lcp_set_friction(&p, 2 * c + 1, 2 * c, 0.5);
  for (int i = 0; i < N; i++) p.live[i] = 1;
  p.fac.limit = limit;
  double worst = 0.0;
  for (int step = 0; step < steps; step++) {
    if (rnd() < 0.6 - 0.4 * p.k / N)
      add_one(&p, A);
    else
      remove_one(&p);
    if (us_lcp_fac_stale(&p)) CHECK_INT(us_lcp_fac_rebuild(&p), ==, 0);
    worst = US_MAX(worst, solve_error(&p, A));
  }
  CHECK(worst < 1e-10);
  CHECK_INT(p.deferred, ==, 0);
  if (limit > 0 && limit < 100) CHECK(p.fac.refactors > 0);
  us_lcp_free(&p);
}

static void dense_only(void) { walk(1 << 20, 1500); }
static void small_border(void) { walk(4, 1500); }
static void every_change(void) { walk(0, 600); }
static void medium_border(void) { walk(16, 1500); }

/* A dependent index is refused on arrival; a member that has become
 * dependent (here: A changed under the factorization) is found by the
 * rebuild and deferred (state FREE), and the rest is factorized. */
static void dependent_member_deferred(void) {
  double A[N * N], b[N] = {0};
  for (int i = 0; i < N * N; i++) A[i] = 0.0;
  for (int i = 0; i < N; i++) A[i * N + i] = 1.0;
  A[2 * N + 2] = A[0] = A[2] = A[2 * N] = 1.0; /* rows 0 and 2 equal */
  Dense d = {N, A, b};
  us_LcpOps ops = dense_ops(&d);
  us_Lcp p;
  CHECK_INT(us_lcp_init(&p, N, &ops), ==, 0);
  for (int i = 0; i < N; i++) p.live[i] = 1;
  p.state[0] = US_LCP_C;
  CHECK_INT(join(&p, A, 0), ==, 0);
  p.state[2] = US_LCP_C;
  CHECK_INT(join(&p, A, 2), ==, 1); /* refused on arrival */
  p.state[2] = US_LCP_OFF;
  int more[3] = {4, 6, 8};
  for (int j = 0; j < 3; j++) {
    p.state[more[j]] = US_LCP_C;
    CHECK_INT(join(&p, A, more[j]), ==, 0);
  }
  A[4 * N + 4] = A[0 * N + 4] = A[4 * N + 0] = 1.0; /* rows 0 and 4 now equal */
  CHECK_INT(us_lcp_fac_rebuild(&p), ==, 0);
  CHECK_INT(p.k, ==, 3);
  CHECK_INT(p.deferred, ==, 1);
  CHECK(p.state[0] == US_LCP_FREE || p.state[4] == US_LCP_FREE);
  CHECK(solve_error(&p, A) < 1e-12);
  us_lcp_free(&p);
}

US_TEST_MAIN(T(dense_only), T(small_border), T(every_change), T(medium_border),
             T(dependent_member_deferred))
