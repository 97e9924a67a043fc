/* The cone LCP solved by Lemke's method with a lexicographic ratio test
 * (lemke.c) on a dense tableau: the LCP backends' exact fallback where
 * the cone LCP's Dantzig pivoting (lcp.c) ends degenerate or at its pivot
 * limit, before the LP.
 *
 * The problem: the live indices of a us_Lcp whose operator is symmetric
 * positive semidefinite (the cone operator of lcp_sys.c, A' = G^T M^-1 G),
 * every one a normal (l >= 0, a >= 0, l a = 0) or a friction with
 * mu = +inf (free, a = 0). A free index x is split as x = u - v with
 * u, v >= 0, two columns with signs +1 and -1: the tableau's matrix is
 * M_pq = s_p s_q A'_{i_p i_q} and q_p = s_p b'_{i_p}, and
 * z^T M z = (sum over columns s_p z_p e_{i_p})^T A' (...) >= 0, so M is
 * again symmetric PSD. At a solution both a_u = a_i and a_v = -a_i are
 * >= 0, so a_i = 0: the free index's condition.
 *
 * Why Lemke always ends with a solution here. The LCP is the KKT system
 * of the convex QP min 1/2 l^T A' l + b'^T l over l >= 0 (free parts
 * free), which is |G l + F|^2 / 2 in the M^-1 norm minus a constant, so
 * it is bounded below and attains its minimum (Frank-Wolfe); its KKT
 * point solves the LCP, which is therefore feasible. M is PSD, hence
 * copositive-plus, and Lemke's method with the lexicographic rule then
 * terminates with a solution (lemke.c, Cottle-Pang-Stone 4.4.13, 4.9).
 * A secondary ray can only come from round-off; it is reported, not
 * trusted. Degenerate problems (many edges with l = 0 and a = 0 at once,
 * nearly dependent edge wrenches) are what the lexicographic rule is
 * for: they cost pivots, not termination.
 *
 * Scaling. The tableau holds D M D and D q with D = diag(1 / sqrt(A'_ii))
 * (1 where A'_ii = 0, whose row and column are then 0), a unit diagonal
 * and |entries| <= 1 (M is PSD), and the solution is z = D z'. Lemke's
 * tolerances (lemke.c) are absolute; unscaled, A'_ii ~ 10^3 on the
 * stacker's stacks made the ratio test's ties wrong and 3 of 26 runs end
 * with basic edge forces of -0.01 (a wrong basis, caught by the proof).
 * Scaling keeps PSD, so termination is unchanged.
 *
 * Cost: the tableau is dense, dim x (dim + 1) doubles, a pivot touches
 * every row in the pivot row's non-zero columns, so callers cap dim.
 * The operator's sparse product fills it column by column (contacts
 * couple only through shared bodies, the start is sparse).
 */
#include "lcp_lemke.h"

#include <math.h>
#include <string.h>

void us_lcp_lemke_free(us_LcpLemke *k) {
  us_lemke_free(&k->lk);
  us_free(k->col);
  us_free(k->sgn);
  us_free(k->colof);
  us_free(k->d);
  us_free(k->b);
  us_free(k->zero);
  us_free(k->y);
  us_free(k->out);
  memset(k, 0, sizeof *k);
}

static int reserve_index_scratch(us_LcpLemke *k, int n) {
  return US_GROW(k->colof, k->cap_colof, n) || US_GROW(k->d, k->cap_d, n) ||
                 US_GROW(k->b, k->cap_b, n) ||
                 US_GROW(k->zero, k->cap_zero, n) || US_GROW(k->y, k->cap_y, n) ||
                 US_GROW(k->out, k->cap_out, n)
             ? -1
             : 0;
}

/* Columns of the live indices into colof (first column, -1 if none);
 * returns their count, or -1 if some live friction has a finite mu. */
static int count_columns(us_LcpLemke *k, const us_Lcp *p) {
  int dim = 0;
  for (int i = 0; i < p->n; i++) {
    k->colof[i] = -1;
    if (!p->live[i]) continue;
    if (p->kind[i] == US_LCP_FRICTION && !isinf(p->mu[i])) return -1;
    k->colof[i] = dim;
    dim += p->kind[i] == US_LCP_FRICTION ? 2 : 1;
  }
  return dim;
}

/* The column map (a free index's second column is its negative part)
 * and the scale of each index (file head). */
static void map_columns(us_LcpLemke *k, const us_Lcp *p) {
  for (int i = 0; i < p->n; i++) {
    int c = k->colof[i];
    if (c < 0) continue;
    double aii = p->ops.entry(p->ops.ctx, i, i);
    k->d[i] = aii > 0 ? 1.0 / sqrt(aii) : 1.0;
    k->col[c] = i, k->sgn[c] = 1;
    if (p->kind[i] != US_LCP_FRICTION) continue;
    k->col[c + 1] = i, k->sgn[c + 1] = -1;
  }
}

/* The columns of LCP index j: column j of A' through the sparse product,
 * scattered into every row of the touched indices with the signs. */
static void fill_index_columns(us_LcpLemke *k, us_Lcp *p, int j) {
  double one = 1.0;
  int cnt = p->ops.apply(p->ops.ctx, &j, &one, 1, k->y, k->out);
  int qs = k->colof[j], qe = qs + (p->kind[j] == US_LCP_FRICTION ? 2 : 1);
  for (int m = 0; m < cnt; m++) {
    int i = k->out[m], ps = k->colof[i];
    if (ps < 0) continue;
    int pe = ps + (p->kind[i] == US_LCP_FRICTION ? 2 : 1);
    for (int r = ps; r < pe; r++)
      for (int q = qs; q < qe; q++)
        us_lemke_row(&k->lk, r)[q] = k->sgn[r] * k->sgn[q] * k->d[i] * k->d[j] * k->y[i];
  }
}

/* The starting tableau: M's columns, q = s b' with b' = a at l = 0. */
static void fill_tableau(us_LcpLemke *k, us_Lcp *p) {
  us_lemke_clear(&k->lk);
  for (int i = 0; i < p->n; i++)
    if (k->colof[i] >= 0) fill_index_columns(k, p, i);
  memset(k->zero, 0, (size_t)p->n * sizeof(double));
  p->ops.full(p->ops.ctx, k->zero, p->live, k->b);
  for (int c = 0; c < k->lk.dim; c++) k->lk.qb[c] = k->sgn[c] * k->d[k->col[c]] * k->b[k->col[c]];
}

/* The basic solution into p->f (normals clipped at 0 against round-off). */
static void read_solution(us_LcpLemke *k, us_Lcp *p) {
  for (int i = 0; i < p->n; i++)
    if (p->live[i]) p->f[i] = 0.0;
  for (int c = 0; c < k->lk.dim; c++)
    p->f[k->col[c]] +=
        k->sgn[c] * k->d[k->col[c]] * US_MAX(us_lemke_value(&k->lk, k->lk.dim + c), 0.0);
}

us_LcpLemkeEnd us_lcp_lemke(us_LcpLemke *k, us_Lcp *p, int max_dim, long *pivots) {
  if (reserve_index_scratch(k, p->n + 1)) return US_LCP_LEMKE_NOMEM;
  int dim = count_columns(k, p);
  if (dim < 0) return US_LCP_LEMKE_NOT_PSD;
  if (dim > max_dim) return US_LCP_LEMKE_TOO_BIG;
  if (us_lemke_reserve(&k->lk, dim) || US_GROW(k->col, k->cap_col, dim + 1) ||
      US_GROW(k->sgn, k->cap_sgn, dim + 1))
    return US_LCP_LEMKE_NOMEM;
  map_columns(k, p);
  fill_tableau(k, p);
  long piv0 = k->lk.pivots;
  k->lk.limit = piv0 + us_lemke_default_limit(dim);
  k->lk.deadline = p->set.deadline;
  int ray_col = -1;
  us_LemkeEnd e = us_lemke_run(&k->lk, &ray_col);
  *pivots += k->lk.pivots - piv0;
  if (e == US_LEMKE_RAY) return US_LCP_LEMKE_RAY;
  if (e != US_LEMKE_SOLVED) return US_LCP_LEMKE_LIMIT;
  read_solution(k, p);
  return US_LCP_LEMKE_SOLVED;
}
