/* Benchmark of the LCP backends against the LP: time per stability test of
 * lp (CLP), lcp (from scratch) and lcp-reuse on the sequence of
 * sub-assemblies of a running-bond wall taken down from the top, one block
 * at a time, with and without friction; plus the size of the dense part
 * (the inverse of the clamped system) on the full wall.
 *
 * Usage: bench_lcp [rows cols [border_limit]] (default 10 10 and 20 20;
 * the border limit of the LCP's factorization, us_LcpSettings, default
 * 64, applies to both LCP methods and the full-wall solve). Each method gets
 * a budget of BUDGET seconds per structure (tests beyond it are skipped
 * and the count is printed). Every verdict of the LCP methods is compared
 * with the LP's; a mismatch is reported and makes the exit status 1. */
#include "core/core.h"
#include "stability/lcp.h"
#include "stability/lcp_backend.h"
#include "stability/lcp_sys.h"
#include "stability/backend.h"
#include "stability/equilibrium.h"
#include "unstack/unstack.h"

#include <stdio.h>
#include <stdlib.h>

#define BUDGET 10.0 /* seconds per method and structure: the rest is skipped */

typedef struct Row {
  double per_test; /* seconds */
  int tests;       /* run within the budget */
  long pivots, fallbacks, reused, stable;
} Row;

static us_LcpSettings lcp_set; /* the LCP methods' settings */

static void *create_lcp(const us_Structure *s, const us_StabilitySettings *set, us_Error *err) {
  return us_lcp_backend_create(s, set, &lcp_set, 0, err);
}

static void *create_lcp_reuse(const us_Structure *s, const us_StabilitySettings *set,
                              us_Error *err) {
  return us_lcp_backend_create(s, set, &lcp_set, 1, err);
}

static const us_Backend *backend(int k) {
  static us_Backend be[2];
  if (k == 0) return &us_backend_clp;
  be[k - 1] = k == 1 ? us_backend_lcp : us_backend_lcp_reuse;
  be[k - 1].create = k == 1 ? create_lcp : create_lcp_reuse;
  return &be[k - 1];
}

/* Bodies by decreasing height of the centre (the top comes off first). */
static const us_Structure *sort_s;
static int by_height(const void *a, const void *b) {
  double ya = sort_s->bodies[*(const int *)a].com[1], yb = sort_s->bodies[*(const int *)b].com[1];
  return ya < yb ? 1 : ya > yb ? -1 : *(const int *)a - *(const int *)b;
}

/* Run the take-down sequence on one backend; verdicts into v. */
static int run(const us_Structure *s, const int *order, int k, unsigned char *v, Row *row) {
  us_StabilitySettings set = us_stability_default_settings();
  us_Error err;
  us_Stability *w = us_stability_new_backend(s, &set, backend(k), &err);
  if (!w) {
    fprintf(stderr, "bench_lcp: %s\n", err.msg);
    return -1;
  }
  us_Bitset sub;
  us_bitset_init(&sub, s->nbody);
  us_bitset_fill(&sub);
  us_StabilityResult res = {0};
  double t0 = us_now();
  row->tests = 0;
  for (int i = 0; i < s->nbody && us_now() - t0 < BUDGET; i++) {
    row->tests++;
    if (us_stability_test(w, &sub, &res, &err)) {
      fprintf(stderr, "bench_lcp: %s\n", err.msg);
      return -1;
    }
    v[i] = (unsigned char)res.verdict;
    row->stable += res.verdict == US_STABLE;
    us_bitset_clear(&sub, order[i]);
  }
  row->per_test = (us_now() - t0) / row->tests;
  const us_StabilityInfo *info = us_stability_info(w);
  row->pivots = info->pivots;
  row->fallbacks = info->lp_fallbacks;
  row->reused = info->reused;
  us_stability_result_free(&res);
  us_bitset_free(&sub);
  us_stability_free(w);
  return 0;
}

/* The full structure's LCP from scratch: clamped-set size and the bytes of
 * its factorization (sparse LU of the base, border), next to the implicit
 * operator's memory and to what a dense k x k inverse would take. */
static void dense_part(const us_Structure *s) {
  us_LcpSys y;
  us_Lcp p;
  if (us_lcp_sys_init(&y, s)) return;
  us_LcpOps ops = us_lcp_sys_ops(&y);
  if (us_lcp_init(&p, 2 * s->ncontact, &ops) == 0) {
    us_lcp_configure(&p, &lcp_set);
    for (int c = 0; c < s->ncontact; c++)
      if (s->contacts[c].mu > 0) us_lcp_set_friction(&p, 2 * c + 1, 2 * c, s->contacts[c].mu);
    double W = s->weight > 0 ? s->weight : 1.0;
    for (int b = 0; b < s->nbody; b++) {
      if (s->bodies[b].fixed) continue;
      y.present[b] = 1;
      for (int r = 0; r < 2; r++) y.fext[3 * b + r] = s->bodies[b].mass * s->gravity[r] / W;
    }
    int *idx = us_malloc(sizeof(int) * (size_t)(2 * s->ncontact + 1)), k = 0;
    for (int c = 0; c < s->ncontact && idx; c++) {
      idx[k++] = 2 * c;
      if (s->contacts[c].mu > 0) idx[k++] = 2 * c + 1;
    }
    us_lcp_add(&p, idx, k);
    double t0 = us_now();
    int r = us_lcp_run(&p);
    long nnz = 0;
    double fb = us_lcp_fac_bytes(&p.fac, &nnz);
    printf("  full wall from scratch: %s, %ld pivots, %.1f ms; clamped system %d of %d indices, "
           "factorization %.2f MB (LU entries %ld, border %d; a dense inverse: %.2f MB); "
           "operator %.2f MB\n",
           r == US_LCP_SOLVED ? "solved" : "not solved", p.pivots, 1e3 * (us_now() - t0), p.fac.k, k,
           fb / 1e6, nnz, p.fac.m, 8.0 * p.fac.k * p.fac.k / 1e6,
           (double)(12 * 8 * s->ncontact + 6 * 8 * s->nbody) / 1e6);
    us_free(idx);
  }
  us_lcp_free(&p);
  us_lcp_sys_free(&y);
}

static int bench(int rows, int cols, double mu) {
  us_GenSettings g = us_gen_default_settings();
  g.rows = rows;
  g.cols = cols;
  g.friction = mu;
  us_Error err;
  us_Structure *s = us_gen_wall(&g, &err);
  if (!s) {
    fprintf(stderr, "bench_lcp: %s\n", err.msg);
    return 1;
  }
  int *order = us_malloc(sizeof(int) * (size_t)s->nbody);
  unsigned char *v[3];
  for (int k = 0; k < 3; k++) v[k] = us_malloc((size_t)s->nbody);
  for (int i = 0; i < s->nbody; i++) order[i] = i;
  sort_s = s;
  qsort(order, (size_t)s->nbody, sizeof(int), by_height);
  printf("wall %d x %d (%d blocks, %d contacts), mu = %.2f, %d tests (top block first)\n", rows,
         cols, s->nbody, s->ncontact, mu, s->nbody);
  static const char *names[3] = {"lp", "lcp", "lcp-reuse"};
  Row row[3] = {{0}};
  int bad = 0;
  for (int k = 0; k < 3; k++) {
    if (run(s, order, k, v[k], &row[k])) return 1;
    int mismatch = 0, common = US_MIN(row[k].tests, row[0].tests);
    for (int i = 0; i < common; i++) mismatch += v[k][i] != v[0][i];
    bad += mismatch;
    printf("  %-10s %9.3f ms/test  %7.2fx lp  tests %d  stable %ld  pivots %ld  "
           "LP fallbacks %ld  reused %ld%s\n",
           names[k], 1e3 * row[k].per_test, row[k].per_test / row[0].per_test, row[k].tests,
           row[k].stable, row[k].pivots, row[k].fallbacks, row[k].reused,
           mismatch ? "  VERDICTS DIFFER" : "");
  }
  dense_part(s);
  for (int k = 0; k < 3; k++) us_free(v[k]);
  us_free(order);
  us_structure_free(s);
  return bad ? 1 : 0;
}

int main(int argc, char **argv) {
  int sizes[2][2] = {{10, 10}, {20, 20}}, nsizes = 2;
  if (argc == 3 || argc == 4) {
    sizes[0][0] = atoi(argv[1]);
    sizes[0][1] = atoi(argv[2]);
    nsizes = 1;
  }
  lcp_set = us_lcp_default_settings();
  if (argc == 4) lcp_set.factor.border_limit = atoi(argv[3]);
  int bad = 0;
  for (int i = 0; i < nsizes; i++) {
    bad |= bench(sizes[i][0], sizes[i][1], 0.0);
    bad |= bench(sizes[i][0], sizes[i][1], 0.6);
  }
  return bad;
}
