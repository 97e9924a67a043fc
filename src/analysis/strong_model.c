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
#define STRONG_PI 3.14159265358979323846

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
  us_free(m->mrot);
  us_free(m->mrinv);
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

/* The force and acceleration variables of component k (0 the normal, then
 * the tangents) of contact c. */
static int fvar(const us_StrongModel *m, int c, int k) {
  if (m->dim == 2) return us_sv(m, c, k == 0 ? SV_FN : SV_FT);
  return us_sv(m, c, k == 0 ? SV3_FN : k == 1 ? SV3_FT1 : SV3_FT2);
}
static int avar(const us_StrongModel *m, int c, int k) {
  if (m->dim == 2) return us_sv(m, c, k == 0 ? SV_AN : SV_AT);
  return us_sv(m, c, k == 0 ? SV3_AN : k == 1 ? SV3_AT1 : SV3_AT2);
}

/* Entry (r, q) of the normalized mass matrix (r, q in one body's block). */
static double mass_entry(const us_StrongModel *m, int r, int q) {
  int i = r / m->e.nw, a = r % m->e.nw, b = q % m->e.nw;
  if (m->dim == 3 && a >= 3 && b >= 3) return m->mrot[9 * i + 3 * (a - 3) + (b - 3)];
  return r == q ? m->mdiag[r] : 0.0;
}

/* Newton-Euler rows: M u - A f + s rhs = 0. */
static int newton_rows(us_StrongModel *m) {
  const us_EqSystem *e = &m->e;
  int s_var = m->nv - 1;
  for (int r = 0; r < m->nu; r++) {
    int r0 = r - r % e->nw;
    for (int q = r0; q < r0 + e->nw; q++)
      if (put(m, q, mass_entry(m, r, q))) return -1;
    for (int c = 0; c < m->nc; c++)
      for (int k = 0; k < m->dim; k++)
        if (put(m, fvar(m, c, k), -a_entry(e, c, k, r))) return -1;
    if (put(m, s_var, e->rhs[r])) return -1;
    end_row(m, 0, 0);
  }
  return 0;
}

/* 3D: direction j of the polygonal cones in the tangent frame, on the unit
 * circle (mid 0) or halfway to the next one (mid 1). */
static void cone_dir(int j, int mid, double out[2]) {
  double t = 2 * STRONG_PI * (j + 0.5 * mid) / US_STRONG_EDGES;
  out[0] = cos(t), out[1] = sin(t);
}

/* 3D: the cone rows of contact c (strong.h): f_n, f_t and a_t from the
 * generators. */
static int cone_rows3(us_StrongModel *m, int c) {
  double mu = m->e.mu[c], muo = mu / cos(STRONG_PI / US_STRONG_EDGES), w[2];
  if (put(m, us_sv(m, c, SV3_FN), 1.0) || put(m, us_sv(m, c, SV3_G), -1.0)) return -1;
  for (int j = 0; j < US_STRONG_EDGES; j++)
    if (put(m, us_sv(m, c, SV3_LIN + j), -1.0) || put(m, us_sv(m, c, SV3_LOUT + j), -1.0))
      return -1;
  end_row(m, 0, 0);
  for (int i = 0; i < 2; i++) {
    if (put(m, us_sv(m, c, SV3_FT1 + i), 1.0)) return -1;
    for (int j = 0; j < US_STRONG_EDGES; j++) {
      cone_dir(j, 0, w);
      if (put(m, us_sv(m, c, SV3_LIN + j), -mu * w[i])) return -1;
      cone_dir(j, 1, w);
      if (put(m, us_sv(m, c, SV3_LOUT + j), -muo * w[i])) return -1;
    }
    end_row(m, 0, 0);
    if (put(m, us_sv(m, c, SV3_AT1 + i), 1.0)) return -1;
    for (int j = 0; j < US_STRONG_EDGES; j++) {
      cone_dir(j, 0, w);
      if (put(m, us_sv(m, c, SV3_BETA + j), -w[i])) return -1;
    }
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
    for (int k = 0; k < m->dim; k++) {
      if (put(m, avar(m, c, k), 1.0)) return -1;
      for (int r = 0; r < m->nu; r++)
        if (put(m, r, -a_entry(e, c, k, r))) return -1;
      end_row(m, 0, 0);
    }
    if (m->dim == 3) {
      if (cone_rows3(m, c)) return -1;
      continue;
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

/* The inverse of the 3x3 matrix a (row-major) into inv; 0 when singular. */
static int invert3(const double *a, double *inv) {
  double c[9] = {a[4] * a[8] - a[5] * a[7], a[2] * a[7] - a[1] * a[8], a[1] * a[5] - a[2] * a[4],
                 a[5] * a[6] - a[3] * a[8], a[0] * a[8] - a[2] * a[6], a[2] * a[3] - a[0] * a[5],
                 a[3] * a[7] - a[4] * a[6], a[1] * a[6] - a[0] * a[7], a[0] * a[4] - a[1] * a[3]};
  double det = a[0] * c[0] + a[1] * c[3] + a[2] * c[6];
  if (!(fabs(det) > 0) || !isfinite(det)) return 0;
  for (int k = 0; k < 9; k++) inv[k] = c[k] / det;
  return 1;
}

/* The mass matrix and the gravity power; 1 when a body has no inertia. */
static int masses(us_StrongModel *m, char *why, size_t why_size) {
  const us_EqSystem *e = &m->e;
  double l = e->length_scale, ml2 = e->mass_total * l * l;
  for (int i = 0; i < e->nbody; i++) {
    const us_Body *b = &e->s->bodies[e->body[i]];
    double share = b->mass / e->mass_total, rot = b->inertia / ml2;
    int ok = rot > 0 && isfinite(rot) && share > 0;
    double *mr = m->dim == 3 ? m->mrot + 9 * i : NULL;
    for (int k = 0; mr && k < 9; k++) mr[k] = b->inertia3[k / 3][k % 3] / ml2;
    if (ok && mr) ok = invert3(mr, m->mrinv + 9 * i) && mr[0] > 0 && mr[4] > 0 && mr[8] > 0;
    if (!ok) {
      snprintf(why, why_size, "body \"%s\" has no rotational inertia", b->id);
      return 1;
    }
    for (int k = 0; k < e->nw; k++) m->mdiag[e->nw * i + k] = k < m->dim ? share : rot;
  }
  for (int r = 0; r < m->nu; r++) m->obj[r] = -e->rhs[r];
  return 0;
}

/* The bound of the body accelerations u: row r of Newton-Euler is a
 * combination of the f_n and s with weights summing to 1 (file head), so
 * its right side is within w[r], and u = M^-1 (that side) per block. */
static void accel_bounds(us_StrongModel *m) {
  const us_EqSystem *e = &m->e;
  double rad = m->dim == 3 ? 1 / cos(STRONG_PI / US_STRONG_EDGES) : 1;
  for (int r = 0; r < m->nu; r++) {
    double w = fabs(e->rhs[r]);
    for (int c = 0; c < m->nc; c++) {
      double t = 0;
      for (int k = 1; k < m->dim; k++) t += fabs(a_entry(e, c, k, r));
      w = fmax(w, fabs(a_entry(e, c, 0, r)) + rad * e->mu[c] * t);
    }
    m->lo[r] = -INFINITY, m->hi[r] = INFINITY;
    m->bound[r] = w; /* the side's bound, turned into u's below */
  }
  for (int r = 0; r < m->nu; r++) {
    int i = r / e->nw, a = r % e->nw;
    if (m->dim == 2 || a < 3) continue;
    double u = 0; /* 3D rotation: |I^-1 tau| row by row */
    for (int q = 0; q < 3; q++) u += fabs(m->mrinv[9 * i + 3 * (a - 3) + q]) * m->bound[r - a + 3 + q];
    m->mdiag[r] = u; /* scratch: mdiag's rotational entries are unused in 3D */
  }
  for (int r = 0; r < m->nu; r++) {
    int a = r % e->nw;
    m->bound[r] = m->dim == 3 && a >= 3 ? m->mdiag[r] : m->bound[r] / m->mdiag[r];
  }
}

/* Relaxation bounds and the certified magnitudes (file head; 3D: f_t
 * within the outer radius mu', the generators within f_n <= 1, and beta_j
 * within |a_t| / sin(2 pi / d): the slides use one direction or two
 * adjacent ones, and a free a_t has a representation on two adjacent
 * ones, so the bound cuts no motion). */
static void bounds(us_StrongModel *m) {
  const us_EqSystem *e = &m->e;
  accel_bounds(m);
  double rad = 1 / cos(STRONG_PI / US_STRONG_EDGES), sn = sin(2 * STRONG_PI / US_STRONG_EDGES);
  for (int c = 0; c < m->nc; c++) {
    double mu = e->mu[c];
    us_strong_mode_bounds(m, c, -1, m->lo, m->hi);
    for (int k = 0; k < m->vpc; k++) {
      int j = us_sv(m, c, k);
      if (m->dim == 2) m->bound[j] = k == SV_FN ? 1.0 : k == SV_FT ? mu : 2 * mu;
      else m->bound[j] = k == SV3_FT1 || k == SV3_FT2 ? rad * mu : 1.0;
    }
    for (int k = 0; k < m->dim; k++) {
      double a = 0;
      for (int r = 0; r < m->nu; r++) a += fabs(a_entry(e, c, k, r)) * m->bound[r];
      m->bound[avar(m, c, k)] = a;
    }
    if (m->dim == 3) {
      double at = m->bound[avar(m, c, 1)] + m->bound[avar(m, c, 2)];
      for (int j = 0; j < US_STRONG_EDGES; j++) m->bound[us_sv(m, c, SV3_BETA + j)] = at / sn;
    }
  }
  m->lo[m->nv - 1] = 0, m->hi[m->nv - 1] = 1, m->bound[m->nv - 1] = 1;
}

static int alloc_arrays(us_StrongModel *m) {
  size_t nv = (size_t)m->nv, nr = (size_t)(m->nu + 1 + 8 * m->nc);
  m->row_start = us_calloc(nr + 1, sizeof(int));
  m->rlo = us_calloc(nr, sizeof(double));
  m->rhi = us_calloc(nr, sizeof(double));
  m->lo = us_calloc(nv, sizeof(double));
  m->hi = us_calloc(nv, sizeof(double));
  m->obj = us_calloc(nv, sizeof(double));
  m->bound = us_calloc(nv, sizeof(double));
  m->mdiag = us_calloc((size_t)(m->nu > 0 ? m->nu : 1), sizeof(double));
  size_t nr9 = 9 * (size_t)(m->e.nbody > 0 ? m->e.nbody : 1);
  m->mrot = m->dim == 3 ? us_calloc(nr9, sizeof(double)) : NULL;
  m->mrinv = m->dim == 3 ? us_calloc(nr9, sizeof(double)) : NULL;
  return m->row_start && m->rlo && m->rhi && m->lo && m->hi && m->obj && m->bound && m->mdiag &&
                 (m->dim == 2 || (m->mrot && m->mrinv))
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
  return us_strong_model_build3(m, s, present, 0, why, why_size);
}

int us_strong_model_build3(us_StrongModel *m, const us_Structure *s, const us_Bitset *present,
                           int outer, char *why, size_t why_size) {
  memset(m, 0, sizeof *m);
  if (build_system(m, s, present)) return -1;
  m->dim = s->dim, m->outer = outer;
  m->vpc = m->dim == 3 ? SV3_COUNT : US_STRONG_VARS_PER_CONTACT;
  m->nu = m->e.nw * m->e.nbody;
  m->nc = m->e.ncontact;
  m->nv = m->nu + m->vpc * m->nc + 1;
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
  if (m->dim == 3) return 0; /* 3D: the certified bounds as they are */
  return us_strong_tighten(m, tighten_deadline(deadline)) || hull_rows(m) ? -1 : 0;
}

/* 3D: the generators a mode leaves free (strong.h): slide k of the inner
 * model uses direction k and the opposite edge; of the outer model the
 * sector (k, k + 1) and the triangle of its opposite arc. */
static int slide_allows(const us_StrongModel *m, int k, int block, int j) {
  int d = US_STRONG_EDGES, opp = (k + d / 2) % d;
  if (block == SV3_BETA) return j == k || (m->outer && j == (k + 1) % d);
  if (block == SV3_LIN) return j == opp || (m->outer && j == (opp + 1) % d);
  return m->outer && j == opp; /* SV3_LOUT */
}

static void mode_bounds3(const us_StrongModel *m, int c, int k, double *lo, double *hi) {
  double *l = lo + us_sv(m, c, 0), *h = hi + us_sv(m, c, 0);
  static const int blocks[3] = {SV3_LIN, SV3_LOUT, SV3_BETA};
  for (int v = 0; v < SV3_COUNT; v++) l[v] = 0, h[v] = INFINITY;
  l[SV3_FT1] = l[SV3_FT2] = l[SV3_AT1] = l[SV3_AT2] = -INFINITY;
  for (int j = 0; j < US_STRONG_EDGES && !m->outer; j++) h[SV3_LOUT + j] = 0;
  if (k == US_MODE_SEPARATES) h[SV3_FN] = 0;
  if (k >= US_MODE_STICKS) h[SV3_AN] = 0;
  for (int j = 0; j < US_STRONG_EDGES && k == US_MODE_STICKS && m->e.mu[c] > 0; j++)
    h[SV3_BETA + j] = 0;
  if (k < US_MODE_SLIDES_POS) return;
  h[SV3_G] = 0;
  for (int b = 0; b < 3; b++)
    for (int j = 0; j < US_STRONG_EDGES; j++)
      if (!slide_allows(m, k - US_MODE_SLIDES_POS, blocks[b], j)) h[blocks[b] + j] = 0;
}

/* 3D: the mode of x at contact c (within tol), or -1. */
static int mode_of3(const us_StrongModel *m, const double *x, int c, double tol) {
  const double *v = x + us_sv(m, c, 0);
  static const int blocks[3] = {SV3_LIN, SV3_LOUT, SV3_BETA};
  if (v[SV3_FN] <= tol) return US_MODE_SEPARATES;
  if (fabs(v[SV3_AN]) > tol) return -1;
  int slip = 0;
  for (int j = 0; j < US_STRONG_EDGES; j++) slip |= v[SV3_BETA + j] > tol;
  int inner_force = 1;
  for (int j = 0; j < US_STRONG_EDGES; j++) inner_force &= m->outer || v[SV3_LOUT + j] <= tol;
  if (!slip || m->e.mu[c] == 0) return inner_force ? US_MODE_STICKS : -1;
  if (v[SV3_G] > tol) return -1;
  for (int k = 0; k < US_STRONG_EDGES; k++) {
    int ok = 1;
    for (int b = 0; b < 3; b++)
      for (int j = 0; j < US_STRONG_EDGES; j++)
        if (v[blocks[b] + j] > tol && !slide_allows(m, k, blocks[b], j)) ok = 0;
    if (ok) return US_MODE_SLIDES_POS + k;
  }
  return -1;
}

/* 3D: the mode closest to x at contact c: separates when it lifts off or
 * carries nothing, sticks without slip, else the slide of the slip's
 * direction (inner: the nearest w_k; outer: the sector holding it). */
static int mode_guess3(const us_StrongModel *m, const double *x, int c) {
  const double *v = x + us_sv(m, c, 0);
  double at1 = v[SV3_AT1], at2 = v[SV3_AT2], slip = hypot(at1, at2);
  if (v[SV3_AN] > 1e-9 || v[SV3_FN] <= 1e-9) return US_MODE_SEPARATES;
  if (slip <= 1e-9 || m->e.mu[c] == 0) return US_MODE_STICKS;
  double a = atan2(at2, at1) / (2 * STRONG_PI) * US_STRONG_EDGES;
  a = m->outer ? floor(a) : floor(a + 0.5);
  int k = ((int)a % US_STRONG_EDGES + US_STRONG_EDGES) % US_STRONG_EDGES;
  return US_MODE_SLIDES_POS + k;
}

int us_strong_modes(const us_StrongModel *m, int c, const double *x, int *modes) {
  int n = 0;
  modes[n++] = US_MODE_SEPARATES;
  /* 2D mu = 0: sticking is inside the two slides (f_t = 0 in all three);
     3D mu = 0: "sticks" leaves the slip free (f_t = 0 anyway) */
  if (m->dim == 3 || m->e.mu[c] > 0) modes[n++] = US_MODE_STICKS;
  int nslide = m->dim == 2 ? 2 : m->e.mu[c] > 0 ? US_STRONG_EDGES : 0;
  for (int k = 0; k < nslide; k++) modes[n++] = US_MODE_SLIDES_POS + k;
  if (m->dim == 3 && x) { /* 3D: the guess first, the order of the rest kept */
    int g = mode_guess3(m, x, c), i = 0;
    while (i < n && modes[i] != g) i++;
    for (; i > 0 && i < n; i--) modes[i] = modes[i - 1];
    if (i == 0) modes[0] = g;
  }
  return n;
}

void us_strong_mode_bounds(const us_StrongModel *m, int c, int k, double *lo, double *hi) {
  if (m->dim == 3) {
    mode_bounds3(m, c, k, lo, hi);
    return;
  }
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
  if (m->dim == 3) return mode_of3(m, x, c, tol);
  const double *v = x + us_sv(m, c, 0);
  if (v[SV_FN] <= tol && fabs(v[SV_FT]) <= tol) return US_MODE_SEPARATES;
  if (fabs(v[SV_AN]) > tol) return -1;
  if (fabs(v[SV_AT]) <= tol) return US_MODE_STICKS;
  if (v[SV_AT] > 0 && v[SV_GM] <= tol) return US_MODE_SLIDES_POS;
  if (v[SV_AT] < 0 && v[SV_GP] <= tol) return US_MODE_SLIDES_NEG;
  return -1;
}
