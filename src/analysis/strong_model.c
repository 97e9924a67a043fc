/* The model of strong stability (strong.h): the equilibrium system of the
 * sub-assembly read as the contact dynamics at rest, homogenized, written
 * once as sparse rows that both solvers load, with bounds that hold for
 * every normalized solution (the MIP's big-M values, docs/classify.md).
 *
 * At rest (zero velocities) the acceleration of contact point p of body b
 * is a_b + alpha_b x (p - com_b): no centripetal term, so the contact
 * accelerations are linear in u, and with the equilibrium system's column
 * of a unit push d at p (force d, torque (p - com) x d / L) the relative
 * acceleration of b against a along d is exactly that column dotted with
 * u in the normalized coordinates of strong.h: a = A^T u.
 *
 * Bounds. Normalized, s + sum f_n = 1 with everything non-negative, so
 * f_n, s <= 1, |f_t| <= mu f_n <= mu and g+- <= 2 mu. Row i of Newton-Euler
 * gives M_ii u_i = sum_c (A_i,cn f_n + A_i,ct f_t) - s rhs_i, a combination
 * of the f_n and s with weights summing to 1, so |u_i| <= max(|rhs_i|,
 * max_c (|A_i,cn| + mu_c |A_i,ct|)) / M_ii; and |a| <= sum_i |A_i,col| |u_i|. */
#include "strong.h"

#include "model/massprops.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define STRONG_MU_MAX 1e6

void us_strong_model_free(us_StrongModel *m) {
  us_eq_free(&m->e);
  us_free(m->row_start);
  us_free(m->col);
  us_free(m->val);
  us_free(m->rlo);
  us_free(m->rhi);
  us_free(m->lo);
  us_free(m->hi);
  us_free(m->obj);
  us_free(m->mdiag);
  us_free(m->bound);
  memset(m, 0, sizeof *m);
}

/* Append entry (j, v) to the current row; 0 or -1 on OOM. */
static int put(us_StrongModel *m, int j, double v) {
  if (v == 0) return 0;
  if (m->nnz == m->cap) {
    int cap = m->cap ? 2 * m->cap : 256;
    int *col = us_realloc(m->col, (size_t)cap * sizeof(int));
    if (!col) return -1;
    m->col = col;
    double *val = us_realloc(m->val, (size_t)cap * sizeof(double));
    if (!val) return -1;
    m->val = val;
    m->cap = cap;
  }
  m->col[m->nnz] = j;
  m->val[m->nnz++] = v;
  return 0;
}

/* Close the current row with bounds [lo, hi]. */
static void end_row(us_StrongModel *m, double lo, double hi) {
  m->rlo[m->nrow] = lo;
  m->rhi[m->nrow] = hi;
  m->row_start[++m->nrow] = m->nnz;
}

/* Entry of column (c, k) of A in row r (0 when the column misses r). */
static double a_entry(const us_EqSystem *e, int c, int k, int r) {
  int j = c * e->dim + k, blk = r / e->nw;
  double v = 0;
  for (int side = 0; side < 2; side++)
    if (e->blk[2 * j + side] == blk) v += e->w[(size_t)(2 * j + side) * (size_t)e->nw + (size_t)(r % e->nw)];
  return v;
}

/* Newton-Euler rows: M u - A f + s rhs = 0. */
static int newton_rows(us_StrongModel *m) {
  const us_EqSystem *e = &m->e;
  int s_var = m->nv - 1;
  for (int r = 0; r < m->nu; r++) {
    if (put(m, r, m->mdiag[r])) return -1;
    for (int c = 0; c < m->nc; c++)
      for (int k = 0; k < 2; k++)
        if (put(m, us_sv(m, c, k == 0 ? SV_FN : SV_FT), -a_entry(e, c, k, r))) return -1;
    if (put(m, s_var, e->rhs[r])) return -1;
    end_row(m, 0, 0);
  }
  return 0;
}

/* The normalization, the contact accelerations and the cone rows. */
static int contact_rows(us_StrongModel *m) {
  const us_EqSystem *e = &m->e;
  for (int c = 0; c < m->nc; c++)
    if (put(m, us_sv(m, c, SV_FN), 1.0)) return -1;
  if (put(m, m->nv - 1, 1.0)) return -1;
  end_row(m, 1, 1);
  for (int c = 0; c < m->nc; c++) {
    for (int k = 0; k < 2; k++) {
      if (put(m, us_sv(m, c, k == 0 ? SV_AN : SV_AT), 1.0)) return -1;
      for (int r = 0; r < m->nu; r++)
        if (put(m, r, -a_entry(e, c, k, r))) return -1;
      end_row(m, 0, 0);
    }
    double mu = e->mu[c];
    for (int sg = -1; sg <= 1; sg += 2) { /* g+ = mu fn - ft, g- = mu fn + ft */
      if (put(m, us_sv(m, c, sg < 0 ? SV_GP : SV_GM), 1.0) || put(m, us_sv(m, c, SV_FN), -mu) ||
          put(m, us_sv(m, c, SV_FT), sg < 0 ? 1.0 : -1.0))
        return -1;
      end_row(m, 0, 0);
    }
  }
  return 0;
}

/* The mass diagonal and the gravity power; 1 when a body has no inertia. */
static int masses(us_StrongModel *m, char *why, size_t why_size) {
  const us_EqSystem *e = &m->e;
  double l = e->length_scale;
  for (int i = 0; i < e->nbody; i++) {
    const us_Body *b = &e->s->bodies[e->body[i]];
    double share = b->mass / e->mass_total, rot = b->inertia / (e->mass_total * l * l);
    if (!(rot > 0) || !isfinite(rot) || !(share > 0)) {
      snprintf(why, why_size, "body \"%s\" has no rotational inertia", b->id);
      return 1;
    }
    m->mdiag[3 * i] = m->mdiag[3 * i + 1] = share;
    m->mdiag[3 * i + 2] = rot;
  }
  for (int r = 0; r < m->nu; r++) m->obj[r] = -e->rhs[r];
  return 0;
}

/* Relaxation bounds and the certified magnitudes (file head). */
static void bounds(us_StrongModel *m) {
  const us_EqSystem *e = &m->e;
  for (int r = 0; r < m->nu; r++) {
    double w = fabs(e->rhs[r]);
    for (int c = 0; c < m->nc; c++)
      w = fmax(w, fabs(a_entry(e, c, 0, r)) + e->mu[c] * fabs(a_entry(e, c, 1, r)));
    m->lo[r] = -INFINITY, m->hi[r] = INFINITY;
    m->bound[r] = w / m->mdiag[r];
  }
  for (int c = 0; c < m->nc; c++) {
    double mu = e->mu[c];
    us_strong_mode_bounds(m, c, -1, m->lo, m->hi);
    for (int k = 0; k < US_STRONG_VARS_PER_CONTACT; k++) {
      int j = us_sv(m, c, k);
      m->bound[j] = k == SV_FN ? 1.0 : k == SV_FT ? mu : 2 * mu;
    }
    for (int k = 0; k < 2; k++) {
      double a = 0;
      for (int r = 0; r < m->nu; r++) a += fabs(a_entry(e, c, k, r)) * m->bound[r];
      m->bound[us_sv(m, c, k == 0 ? SV_AN : SV_AT)] = a;
    }
  }
  m->lo[m->nv - 1] = 0, m->hi[m->nv - 1] = 1, m->bound[m->nv - 1] = 1;
}

static int alloc_arrays(us_StrongModel *m) {
  size_t nv = (size_t)m->nv, nr = (size_t)(m->nu + 1 + 7 * m->nc);
  m->row_start = us_calloc(nr + 1, sizeof(int));
  m->rlo = us_calloc(nr, sizeof(double));
  m->rhi = us_calloc(nr, sizeof(double));
  m->lo = us_calloc(nv, sizeof(double));
  m->hi = us_calloc(nv, sizeof(double));
  m->obj = us_calloc(nv, sizeof(double));
  m->bound = us_calloc(nv, sizeof(double));
  m->mdiag = us_calloc((size_t)(m->nu > 0 ? m->nu : 1), sizeof(double));
  return m->row_start && m->rlo && m->rhi && m->lo && m->hi && m->obj && m->bound && m->mdiag
             ? 0 : -1;
}

/* The system of `present` (NULL: every movable body). */
static int build_system(us_StrongModel *m, const us_Structure *s, const us_Bitset *present) {
  if (us_eq_init(&m->e, s)) return -1;
  us_Bitset all = {0};
  if (!present) {
    if (us_bitset_init(&all, s->nbody)) return -1;
    for (int i = 0; i < s->nbody; i++)
      if (!s->bodies[i].fixed) us_bitset_set(&all, i);
  }
  int rc = us_eq_build(&m->e, present ? present : &all);
  us_bitset_free(&all);
  return rc;
}

/* Cuts valid for every normalized solution (the hull of each
 * complementarity pair within its bounds): f_n + a_n / B_an <= 1 (one of
 * them is zero, each is within its bound), and a_t / B_at + g- / 2 mu <= 1
 * (slipping along +t makes g- zero; otherwise a_t <= 0), and its mirror.
 * They tighten the relaxation of the mode search and the MIP's. */
static int hull_rows(us_StrongModel *m) {
  for (int c = 0; c < m->nc; c++) {
    int an = us_sv(m, c, SV_AN), at = us_sv(m, c, SV_AT);
    double ban = m->bound[an] * 1.01 + 1e-9, bat = m->bound[at] * 1.01 + 1e-9;
    if (put(m, us_sv(m, c, SV_FN), 1.0) || put(m, an, 1.0 / ban)) return -1;
    end_row(m, -INFINITY, 1.0);
    double bg = 2 * m->e.mu[c] * 1.01 + 1e-9;
    for (int sg = 1; sg >= -1 && m->e.mu[c] > 0; sg -= 2) {
      if (put(m, at, sg / bat) || put(m, us_sv(m, c, sg > 0 ? SV_GM : SV_GP), 1.0 / bg)) return -1;
      end_row(m, -INFINITY, 1.0);
    }
  }
  return 0;
}

/* The tightening gets a quarter of the time left: the bounds it leaves are
 * valid anyway, and the search needs the rest. */
static double tighten_deadline(double deadline) {
  double now = us_now();
  return deadline > 0 ? now + 0.25 * fmax(deadline - now, 0) : 0;
}

int us_strong_model_build(us_StrongModel *m, const us_Structure *s, const us_Bitset *present,
                          char *why, size_t why_size) {
  memset(m, 0, sizeof *m);
  if (build_system(m, s, present)) return -1;
  m->nu = 3 * m->e.nbody;
  m->nc = m->e.ncontact;
  m->nv = m->nu + US_STRONG_VARS_PER_CONTACT * m->nc + 1;
  for (int c = 0; c < m->nc; c++)
    if (!(m->e.mu[c] <= STRONG_MU_MAX)) {
      snprintf(why, why_size, "a contact has friction coefficient above %g", STRONG_MU_MAX);
      return 1;
    }
  if (alloc_arrays(m)) return -1;
  int rc = masses(m, why, why_size);
  if (rc) return rc;
  bounds(m);
  if (newton_rows(m) || contact_rows(m)) return -1;
  return 0;
}

int us_strong_model_tighten(us_StrongModel *m, double deadline) {
  return us_strong_tighten(m, tighten_deadline(deadline)) || hull_rows(m) ? -1 : 0;
}

void us_strong_mode_bounds(const us_StrongModel *m, int c, int k, double *lo, double *hi) {
  int j0 = us_sv(m, c, 0);
  static const double inf = INFINITY;
  /* the relaxation: every mode's conditions but complementarity */
  lo[j0 + SV_FN] = 0, hi[j0 + SV_FN] = inf;
  lo[j0 + SV_FT] = -inf, hi[j0 + SV_FT] = inf;
  lo[j0 + SV_GP] = 0, hi[j0 + SV_GP] = inf;
  lo[j0 + SV_GM] = 0, hi[j0 + SV_GM] = inf;
  lo[j0 + SV_AN] = 0, hi[j0 + SV_AN] = inf;
  lo[j0 + SV_AT] = -inf, hi[j0 + SV_AT] = inf;
  if (k == US_MODE_SEPARATES) hi[j0 + SV_FN] = 0;
  if (k == US_MODE_STICKS || k == US_MODE_SLIDES_POS || k == US_MODE_SLIDES_NEG)
    hi[j0 + SV_AN] = 0;
  if (k == US_MODE_STICKS) hi[j0 + SV_AT] = lo[j0 + SV_AT] = 0;
  if (k == US_MODE_SLIDES_POS) lo[j0 + SV_AT] = 0, hi[j0 + SV_GM] = 0;
  if (k == US_MODE_SLIDES_NEG) hi[j0 + SV_AT] = 0, hi[j0 + SV_GP] = 0;
}

int us_strong_mode_of(const us_StrongModel *m, const double *x, int c, double tol) {
  const double *v = x + us_sv(m, c, 0);
  if (v[SV_FN] <= tol && fabs(v[SV_FT]) <= tol) return US_MODE_SEPARATES;
  if (fabs(v[SV_AN]) > tol) return -1;
  if (fabs(v[SV_AT]) <= tol) return US_MODE_STICKS;
  if (v[SV_AT] > 0 && v[SV_GM] <= tol) return US_MODE_SLIDES_POS;
  if (v[SV_AT] < 0 && v[SV_GP] <= tol) return US_MODE_SLIDES_NEG;
  return -1;
}
