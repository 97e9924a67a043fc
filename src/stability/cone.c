/* Friction cones by their generators: the columns of the LP backends'
 * statics LP (lp_gen.h states the form, the 2D and 3D cones and why each
 * verdict is exact).
 *
 * Algorithm: one pass over the active contacts counts the columns (so the
 * arrays grow once), a second writes them. A column of contact ci with
 * frame components (cn, ct1, ct2) is that combination of the contact's
 * component columns in A (equilibrium.c): on each side's row block,
 * v_r = cn w_n,r + ct1 w_t1,r (+ ct2 w_t2,r), exact zeros dropped. Every
 * generator has unit length in the contact frame, so no entry of G grows
 * with mu (mu = 1e300 or INFINITY included). Cost O(columns * nw).
 *
 * The 3D polygons (us_ConeSet): contact c's directions are the uniform
 * 2 pi i / US_CONE_START until its first refinement copies them into its
 * own sorted array (at most US_CONE_MAX_EDGES). Invariants: directions
 * ascend in [0, 2 pi), consecutive ones (cyclically) differ by more than
 * ANGLE_TIE and by less than pi (the start's gaps are pi / 4 and refining
 * only splits gaps), so the outer polygon's sides meet at finite corners.
 */
#include "lp_gen.h"

#include <math.h>
#include <string.h>

#define TWO_PI 6.283185307179586
#define ANGLE_TIE 1e-9 /* directions closer than this (radians) are one */

/* ------------------------------------------------------- the 3D polygons */

int us_cone_set_init(us_ConeSet *c, int ncontact) {
  memset(c, 0, sizeof *c);
  size_t n = (size_t)(ncontact > 0 ? ncontact : 1);
  c->nang = us_calloc(n, sizeof(int));
  c->ang = us_calloc(n, sizeof(double *));
  c->ncontact = ncontact;
  if (c->nang && c->ang) return 0;
  us_cone_set_free(c);
  return -1;
}

void us_cone_set_free(us_ConeSet *c) {
  if (c->ang)
    for (int i = 0; i < c->ncontact; i++) us_free(c->ang[i]);
  us_free(c->ang);
  us_free(c->nang);
  memset(c, 0, sizeof *c);
}

static void uniform(double *a) {
  for (int i = 0; i < US_CONE_START; i++) a[i] = TWO_PI * (double)i / US_CONE_START;
}

/* Contact c's directions (buf: room for the uniform ones). */
static int polygon(const us_ConeSet *cs, int c, const double **ang, double *buf) {
  if (cs && cs->ang[c]) {
    *ang = cs->ang[c];
    return cs->nang[c];
  }
  uniform(buf);
  *ang = buf;
  return US_CONE_START;
}

int us_cone_set_refine(us_ConeSet *cs, int c, double theta) {
  if (!isfinite(theta)) return 0;
  theta = fmod(theta, TWO_PI);
  if (theta < 0) theta += TWO_PI;
  if (!(theta < TWO_PI)) theta = 0.0;
  if (!cs->ang[c]) {
    double *a = us_malloc(US_CONE_MAX_EDGES * sizeof(double));
    if (!a) return -1;
    uniform(a);
    cs->ang[c] = a;
    cs->nang[c] = US_CONE_START;
  }
  double *a = cs->ang[c];
  int n = cs->nang[c], pos = 0;
  if (n >= US_CONE_MAX_EDGES) return 0;
  while (pos < n && a[pos] < theta) pos++;
  double prev = pos > 0 ? a[pos - 1] : a[n - 1] - TWO_PI;
  double next = pos < n ? a[pos] : a[0] + TWO_PI;
  if (theta - prev < ANGLE_TIE || next - theta < ANGLE_TIE) return 0;
  memmove(a + pos + 1, a + pos, (size_t)(n - pos) * sizeof(double));
  a[pos] = theta;
  cs->nang[c] = n + 1;
  return 1;
}

double us_cone_set_gap(const us_ConeSet *cs, int c) {
  double buf[US_CONE_START];
  const double *a;
  int n = polygon(cs, c, &a, buf);
  double gap = a[0] + TWO_PI - a[n - 1];
  for (int i = 1; i < n; i++) gap = US_MAX(gap, a[i] - a[i - 1]);
  return gap;
}

/* ------------------------------------------------------------ generators */

void us_eq_gen_free(us_EqGen *g) {
  us_free(g->start);
  us_free(g->row);
  us_free(g->val);
  us_free(g->col_contact);
  us_free(g->col_slot);
  us_free(g->col_coef);
  us_free(g->col_blk);
  memset(g, 0, sizeof *g);
}

static int gen_reserve(us_EqGen *g, int ncol, int nnz) {
  if (ncol + 1 > g->cap_col) {
    size_t n = (size_t)ncol + 1;
    int *start = us_realloc(g->start, n * sizeof(int));
    if (!start) return -1;
    g->start = start;
    int *cc = us_realloc(g->col_contact, n * sizeof(int));
    if (!cc) return -1;
    g->col_contact = cc;
    unsigned char *cs = us_realloc(g->col_slot, n);
    if (!cs) return -1;
    g->col_slot = cs;
    double *cf = us_realloc(g->col_coef, 3 * n * sizeof(double));
    if (!cf) return -1;
    g->col_coef = cf;
    int *cb = us_realloc(g->col_blk, 2 * n * sizeof(int));
    if (!cb) return -1;
    g->col_blk = cb;
    g->cap_col = ncol + 1;
  }
  if (nnz > g->cap_nnz) {
    int *row = us_realloc(g->row, (size_t)nnz * sizeof(int));
    if (!row) return -1;
    g->row = row;
    double *val = us_realloc(g->val, (size_t)nnz * sizeof(double));
    if (!val) return -1;
    g->val = val;
    g->cap_nnz = nnz;
  }
  return 0;
}

/* (cos a, sin a) of a = atan(mu): the edge directions of the cone. */
static void edge_angle(double mu, double *c, double *s) {
  if (isinf(mu)) {
    *c = 0.0, *s = 1.0;
    return;
  }
  double h = hypot(1.0, mu);
  *c = 1.0 / h, *s = mu / h;
}

/* Append the column of active contact ci with frame components cf. */
static void gen_column(const us_EqSystem *e, us_EqGen *g, int ci, int slot, const double *cf) {
  size_t j0 = (size_t)ci * (size_t)e->dim, nw = (size_t)e->nw;
  int nnz = g->start[g->ncol];
  for (size_t side = 0; side < 2; side++) {
    int blk = e->blk[2 * j0 + side]; /* the same for every component */
    g->col_blk[2 * (size_t)g->ncol + side] = blk;
    if (blk < 0) continue;
    if (e->dim == 2 && nw == 3) { /* 2D: the same sums, unrolled (most region LP set-up) */
      const double *w0 = e->w + (2 * j0 + side) * 3, *w1 = e->w + (2 * (j0 + 1) + side) * 3;
      for (int r = 0; r < 3; r++) {
        double v = (cf[0] != 0.0 ? cf[0] * w0[r] : 0.0) + (cf[1] != 0.0 ? cf[1] * w1[r] : 0.0);
        if (v == 0.0) continue;
        g->row[nnz] = blk * 3 + r;
        g->val[nnz++] = v;
      }
      continue;
    }
    for (size_t r = 0; r < nw; r++) {
      double v = 0.0;
      for (int k = 0; k < e->dim; k++)
        if (cf[k] != 0.0) v += cf[k] * e->w[(2 * (j0 + (size_t)k) + side) * nw + r];
      if (v == 0.0) continue; /* exact zeros only: keeps the matrix honest */
      g->row[nnz] = blk * e->nw + (int)r;
      g->val[nnz++] = v;
    }
  }
  g->col_contact[g->ncol] = ci;
  g->col_slot[g->ncol] = (unsigned char)slot;
  memcpy(g->col_coef + 3 * (size_t)g->ncol, cf, 3 * sizeof(double));
  g->start[++g->ncol] = nnz;
}

/* The column along n, and in 3D those of the half-space (mu = INFINITY). */
static void gen_normal(const us_EqSystem *e, us_EqGen *g, int ci) {
  const double n[3] = {1.0, 0.0, 0.0};
  gen_column(e, g, ci, 0, n);
}

static void gen_half_space(const us_EqSystem *e, us_EqGen *g, int ci) {
  for (int k = 0; k < 4; k++) {
    double cf[3] = {0.0, 0.0, 0.0};
    cf[1 + k / 2] = k % 2 ? -1.0 : 1.0;
    gen_column(e, g, ci, 1 + k, cf);
  }
}

/* The last friction coefficient's edge angle (most contacts share one mu). */
typedef struct EdgeMemo {
  double mu, c, s;
  int set;
} EdgeMemo;

/* 2D edges e+, e- (slots 1, 2). */
static void gen_edges_2d(const us_EqSystem *e, us_EqGen *g, int ci, EdgeMemo *m) {
  if (!m->set || !(m->mu == e->mu[ci])) edge_angle(e->mu[ci], &m->c, &m->s), m->mu = e->mu[ci], m->set = 1;
  double c = m->c, s = m->s;
  const double ep[3] = {c, s, 0.0}, em[3] = {c, -s, 0.0};
  if (e->nw != 3 || !(c != 0.0 && s != 0.0)) {
    gen_column(e, g, ci, 1, ep);
    gen_column(e, g, ci, 2, em);
    return;
  }
  /* both edges in one pass over the two sides' wrenches (gen_column's
     sums, the same values): most of a region LP's set-up */
  size_t j0 = (size_t)ci * 2;
  int jp = g->ncol, np = g->start[jp], nm = 0, rm[6];
  double vm[6];
  for (size_t side = 0; side < 2; side++) {
    int blk = e->blk[2 * j0 + side];
    g->col_blk[2 * (size_t)jp + side] = g->col_blk[2 * (size_t)jp + 2 + side] = blk;
    if (blk < 0) continue;
    const double *w0 = e->w + (2 * j0 + side) * 3, *w1 = e->w + (2 * (j0 + 1) + side) * 3;
    for (int r = 0; r < 3; r++) {
      double a = c * w0[r], b = s * w1[r], v = a + b, u = a + -s * w1[r];
      if (v != 0.0) g->row[np] = blk * 3 + r, g->val[np++] = v;
      if (u != 0.0) rm[nm] = blk * 3 + r, vm[nm++] = u;
    }
  }
  g->start[jp + 1] = np;
  memcpy(g->row + np, rm, (size_t)nm * sizeof(int));
  memcpy(g->val + np, vm, (size_t)nm * sizeof(double));
  g->start[jp + 2] = np + nm;
  g->col_contact[jp] = g->col_contact[jp + 1] = ci;
  g->col_slot[jp] = 1, g->col_slot[jp + 1] = 2;
  memcpy(g->col_coef + 3 * (size_t)jp, ep, sizeof ep);
  memcpy(g->col_coef + 3 * (size_t)jp + 3, em, sizeof em);
  g->ncol = jp + 2;
}

/* 3D edges of the polygon (slots 1..k): at the directions (inner) or at
 * the corners of the tangent polygon (outer). */
static void gen_edges_3d(const us_EqSystem *e, us_EqGen *g, int ci) {
  double buf[US_CONE_START], mu = e->mu[ci];
  const double *a;
  int n = polygon(e->cones, e->contact[ci], &a, buf);
  int outer = e->cones && e->cones->mode == US_CONE_OUTER;
  for (int i = 0; i < n; i++) {
    double phi = a[i], m = mu;
    if (outer) {
      double gap = (i + 1 < n ? a[i + 1] : a[0] + TWO_PI) - a[i];
      phi += 0.5 * gap;
      m = mu / cos(0.5 * gap);
    }
    double c, s;
    edge_angle(m, &c, &s);
    const double cf[3] = {c, s * cos(phi), s * sin(phi)};
    gen_column(e, g, ci, 1 + i, cf);
  }
}

/* Which columns contact ci gets: bit 0 the column n, bit 1 the edges (or
 * in 3D with mu = INFINITY the half-space's +-t1, +-t2). */
static int gen_kinds(double mu, double n_column_mu) {
  if (!(mu > 0)) return 1;
  return 2 | (mu > n_column_mu ? 1 : 0);
}

static int edge_count(const us_EqSystem *e, int ci) {
  if (e->dim == 2) return 2;
  if (isinf(e->mu[ci])) return 4;
  const us_ConeSet *cs = e->cones;
  int c = e->contact[ci];
  return cs && cs->ang[c] ? cs->nang[c] : US_CONE_START;
}

/* Bilateral joints: +-n, +-t1 (+-t2), slots 0 .. 2 dim - 1, so every
 * force component is free in sign whatever mu (classify's "stands only
 * with equality constraints", docs/classify.md). */
static void gen_bilateral(const us_EqSystem *e, us_EqGen *g, int ci) {
  for (int k = 0; k < 2 * e->dim; k++) {
    double cf[3] = {0.0, 0.0, 0.0};
    cf[k / 2] = k % 2 ? -1.0 : 1.0;
    gen_column(e, g, ci, k, cf);
  }
}

int us_eq_generators(const us_EqSystem *e, double n_column_mu, us_EqGen *g) {
  if (e->bilateral) {
    int ncol = 2 * e->dim * e->ncontact;
    if (gen_reserve(g, ncol, ncol * 2 * e->nw)) return -1;
    g->ncol = 0;
    g->nrow = e->nbody * e->nw;
    g->start[0] = 0;
    for (int c = 0; c < e->ncontact; c++) gen_bilateral(e, g, c);
    return 0;
  }
  int ncol = 0;
  for (int c = 0; c < e->ncontact; c++) {
    int k = gen_kinds(e->mu[c], n_column_mu);
    ncol += (k & 1) + (k & 2 ? edge_count(e, c) : 0);
  }
  if (gen_reserve(g, ncol, ncol * 2 * e->nw)) return -1;
  g->ncol = 0;
  g->nrow = e->nbody * e->nw;
  g->start[0] = 0;
  EdgeMemo memo = {0.0, 0.0, 0.0, 0};
  for (int c = 0; c < e->ncontact; c++) {
    int k = gen_kinds(e->mu[c], n_column_mu);
    if (k & 1) gen_normal(e, g, c);
    if (!(k & 2)) continue;
    if (e->dim == 2)
      gen_edges_2d(e, g, c, &memo);
    else if (isinf(e->mu[c]))
      gen_half_space(e, g, c);
    else
      gen_edges_3d(e, g, c);
  }
  return 0;
}

int us_eq_gen_slot(const us_EqGen *g, int j) { return g->col_slot[j]; }

int us_eq_gen_slots(int dim) { return dim == 2 ? 4 : 1 + US_CONE_MAX_EDGES; } /* 4: bilateral */

void us_eq_gen_forces(const us_EqSystem *e, const us_EqGen *g, const double *l, double *f) {
  memset(f, 0, (size_t)e->ncontact * (size_t)e->dim * sizeof(double));
  for (int j = 0; j < g->ncol; j++) {
    double x = l[j] > 0 ? l[j] : 0.0; /* solver round-off below the bound */
    double *fc = f + (size_t)g->col_contact[j] * (size_t)e->dim;
    const double *cf = g->col_coef + 3 * (size_t)j;
    for (int k = 0; k < e->dim; k++) fc[k] += cf[k] * x;
  }
}

us_Verdict us_eq_no_columns_verdict(const us_EqSystem *e) {
  for (int r = 0; r < e->nbody * e->nw; r++)
    if (e->rhs[r] != 0.0) return US_UNSTABLE;
  return US_STABLE;
}

int us_eq_gen_farkas_body(const us_EqSystem *e, const us_EqGen *g, const double *y,
                          double slack) {
  double by = 0.0, ymax = 0.0;
  int nrow = e->nbody * e->nw;
  for (int r = 0; r < nrow; r++) {
    by += e->rhs[r] * y[r];
    ymax = US_MAX(ymax, fabs(y[r]));
  }
  if (!(ymax > 0) || !isfinite(by) || by == 0.0) return -1;
  /* orient y so that b.y < 0; then every column must have g.y >= 0 */
  double sg = by < 0 ? 1.0 : -1.0, tol = slack * fabs(by);
  for (int j = 0; j < g->ncol; j++) {
    double gy = 0.0;
    for (int k = g->start[j]; k < g->start[j + 1]; k++) gy += g->val[k] * y[g->row[k]];
    if (sg * gy < -tol) return -1;
  }
  int best = -1;
  double bn = -1.0;
  for (int i = 0; i < e->nbody; i++) {
    const double *yb = y + (size_t)e->nw * (size_t)i;
    double n = 0.0;
    for (int r = 0; r < e->nw; r++) n += yb[r] * yb[r];
    if (n > bn) {
      bn = n;
      best = e->body[i];
    }
  }
  return best;
}
