/* The equilibrium system of one sub-assembly: the linear map from contact
 * force components to the net wrench on every present movable body.
 *
 * Algorithm: one pass over the bodies numbers the row blocks (present
 * movable bodies, in body-index order), one pass over the contacts keeps
 * the active ones and writes, for each force component, the wrench it
 * exerts on each of the contact's two bodies. Each build is
 * O(#bodies + #contacts); arrays grow once and are reused between builds.
 *
 * Sign conventions (see equilibrium.h): the unit component k of contact c
 * (direction d = n for k = 0, d = t[k-1] otherwise) pushes body b with +d
 * at p and body a with -d at p. A body's wrench rows are (force, torque
 * about its centre of mass / length_scale), forces in units of the total
 * weight W. rhs = minus the normalized gravity wrench, so A f = rhs is
 * equilibrium. Gravity acts at the centre of mass: no torque about it.
 *
 * Normalization without overflow: body i's gravity row is -(m_i / M) g^,
 * the mass share times the unit direction g^ = g / |g| (|g| by hypot), so
 * masses up to DBL_MAX and gravity components up to DBL_MAX give rows of
 * magnitude at most 1; W = M |g| itself is only used to report newtons
 * (finalize guarantees it is finite and normal).
 */
#include "equilibrium.h"

#include "model/massprops.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int us_eq_init(us_EqSystem *e, const us_Structure *s) {
  memset(e, 0, sizeof *e);
  e->s = s;
  e->dim = s->dim;
  e->nw = s->dim == 3 ? 6 : 3;
  double g = us_gravity_norm(s->gravity), m = us_movable_mass(s), w = m * g;
  e->force_scale = w > 0 && isfinite(w) ? w : 1.0;
  e->mass_total = m > 0 && isfinite(m) ? m : 1.0;
  for (int j = 0; j < 3; j++) e->gdir[j] = g > 0 && isfinite(g) ? s->gravity[j] / g : 0.0;
  e->length_scale = s->scale > 0 ? s->scale : 1.0;
  /* row_of_body has a fixed size: allocate it now */
  size_t nb = (size_t)(s->nbody > 0 ? s->nbody : 1);
  e->row_of_body = us_malloc(nb * sizeof(int));
  if (!e->row_of_body) return -1;
  for (size_t i = 0; i < nb; i++) e->row_of_body[i] = -1;
  return 0;
}

void us_eq_free(us_EqSystem *e) {
  us_free(e->body);
  us_free(e->row_of_body);
  us_free(e->contact);
  us_free(e->blk);
  us_free(e->w);
  us_free(e->rhs);
  us_free(e->mu);
  us_free(e->inc_start);
  us_free(e->inc);
  memset(e, 0, sizeof *e);
}

/* Grow the body-indexed and contact-indexed arrays to hold nb bodies and nc
 * contacts. Capacities only move once every array reached its size, so a
 * failure leaves the system valid (with old capacities). */
static int reserve(us_EqSystem *e, int nb, int nc) {
  if (nb > e->cap_body) {
    size_t n = (size_t)nb;
    int *body = us_realloc(e->body, n * sizeof(int));
    if (!body) return -1;
    e->body = body;
    double *rhs = us_realloc(e->rhs, n * (size_t)e->nw * sizeof(double));
    if (!rhs) return -1;
    e->rhs = rhs;
    e->cap_body = nb;
  }
  if (nc > e->cap_contact) {
    size_t n = (size_t)nc, cols = n * (size_t)e->dim;
    int *contact = us_realloc(e->contact, n * sizeof(int));
    if (!contact) return -1;
    e->contact = contact;
    double *mu = us_realloc(e->mu, n * sizeof(double));
    if (!mu) return -1;
    e->mu = mu;
    int *blk = us_realloc(e->blk, 2 * cols * sizeof(int));
    if (!blk) return -1;
    e->blk = blk;
    double *w = us_realloc(e->w, 2 * cols * (size_t)e->nw * sizeof(double));
    if (!w) return -1;
    e->w = w;
    e->cap_contact = nc;
  }
  return 0;
}

/* Is body i (>= 0) present in the sub-assembly? Fixed bodies always are. */
static int body_present(const us_Structure *s, const us_Bitset *present, int i) {
  return s->bodies[i].fixed || us_bitset_get(present, i);
}

static int side_present(const us_Structure *s, const us_Bitset *present, int i) {
  return i < 0 || body_present(s, present, i);
}

static int side_movable(const us_Structure *s, int i) { return i >= 0 && !s->bodies[i].fixed; }

int us_contact_active(const us_Structure *s, const us_Bitset *present, int c) {
  const us_Contact *k = &s->contacts[c];
  if (!side_present(s, present, k->a) || !side_present(s, present, k->b)) return 0;
  return side_movable(s, k->a) || side_movable(s, k->b);
}

/* Wrench (force d, torque (p - com) x d / L) of a unit push d at p on body
 * `body`, times sign; written as nw values. 2D keeps (fx, fy, tz). */
static void unit_wrench(const us_EqSystem *e, int body, const double *p, const double *d,
                        double sign, double *out) {
  const double *com = e->s->bodies[body].com;
  double r[3] = {p[0] - com[0], p[1] - com[1], p[2] - com[2]};
  double t[3] = {r[1] * d[2] - r[2] * d[1], r[2] * d[0] - r[0] * d[2],
                 r[0] * d[1] - r[1] * d[0]};
  double inv_l = 1.0 / e->length_scale;
  if (e->nw == 3) {
    out[0] = sign * d[0];
    out[1] = sign * d[1];
    out[2] = sign * t[2] * inv_l;
    return;
  }
  for (int j = 0; j < 3; j++) {
    out[j] = sign * d[j];
    out[3 + j] = sign * t[j] * inv_l;
  }
}

/* Columns of active contact number `ci` (structure contact c). */
static void write_contact(us_EqSystem *e, int ci, int c) {
  const us_Contact *k = &e->s->contacts[c];
  int ends[2] = {k->a, k->b};
  if (e->dim == 2 && e->nw == 3) { /* unit_wrench's values, unrolled (region set-up) */
    double inv_l = 1.0 / e->length_scale;
    for (int side = 0; side < 2; side++) {
      int body = ends[side];
      int blk = body >= 0 ? e->row_of_body[body] : -1;
      for (int comp = 0; comp < 2; comp++) {
        size_t j = (size_t)ci * 2 + (size_t)comp;
        double *w = e->w + (2 * j + (size_t)side) * 3;
        e->blk[2 * j + (size_t)side] = blk;
        if (blk < 0) {
          w[0] = w[1] = w[2] = 0.0;
          continue;
        }
        const double *d = comp == 0 ? k->n : k->t[0], *com = e->s->bodies[body].com;
        double sign = side == 0 ? -1.0 : 1.0, r0 = k->p[0] - com[0], r1 = k->p[1] - com[1];
        w[0] = sign * d[0];
        w[1] = sign * d[1];
        w[2] = sign * (r0 * d[1] - r1 * d[0]) * inv_l;
      }
    }
    return;
  }
  for (int comp = 0; comp < e->dim; comp++) {
    const double *d = comp == 0 ? k->n : k->t[comp - 1];
    size_t j = (size_t)ci * (size_t)e->dim + (size_t)comp;
    for (int side = 0; side < 2; side++) {
      int body = ends[side];
      int blk = body >= 0 ? e->row_of_body[body] : -1;
      double *w = e->w + (2 * j + (size_t)side) * (size_t)e->nw;
      e->blk[2 * j + (size_t)side] = blk;
      if (blk < 0)
        memset(w, 0, (size_t)e->nw * sizeof(double));
      else
        unit_wrench(e, body, k->p, d, side == 0 ? -1.0 : 1.0, w);
    }
  }
}

static void clear_rows(us_EqSystem *e);

/* The structure's contacts by body (CSR), built at the first whole-system
 * build: a build then walks only the present bodies' contacts. */
static int build_incidence(us_EqSystem *e) {
  const us_Structure *s = e->s;
  int n = s->nbody;
  e->inc_start = us_calloc((size_t)n + 1, sizeof(int));
  e->inc = us_malloc((size_t)(2 * s->ncontact + 1) * sizeof(int));
  if (!e->inc_start || !e->inc) {
    us_free(e->inc_start), us_free(e->inc);
    e->inc_start = e->inc = NULL;
    return -1;
  }
  for (int c = 0; c < s->ncontact; c++) {
    const us_Contact *k = &s->contacts[c];
    if (k->a >= 0) e->inc_start[k->a + 1]++;
    if (k->b >= 0) e->inc_start[k->b + 1]++;
  }
  for (int i = 0; i < n; i++) e->inc_start[i + 1] += e->inc_start[i];
  for (int c = 0; c < s->ncontact; c++) { /* fill, then shift the starts back */
    const us_Contact *k = &s->contacts[c];
    if (k->a >= 0) e->inc[e->inc_start[k->a]++] = c;
    if (k->b >= 0) e->inc[e->inc_start[k->b]++] = c;
  }
  for (int i = n; i > 0; i--) e->inc_start[i] = e->inc_start[i - 1];
  e->inc_start[0] = 0;
  return 0;
}

/* Row r for body i, with its gravity row. */
static void number_body(us_EqSystem *e, int i, int r) {
  e->row_of_body[i] = r;
  e->body[r] = i;
  double *rhs = e->rhs + (size_t)r * (size_t)e->nw;
  memset(rhs, 0, (size_t)e->nw * sizeof(double));
  double share = e->s->bodies[i].mass / e->mass_total;
  for (int j = 0; j < e->dim; j++) rhs[j] = -share * e->gdir[j];
}

static int int_cmp(const void *a, const void *b) {
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

/* The next present movable body after body i (-1: from the start), or -1. */
static int next_present(const us_Structure *s, const us_Bitset *present, int i) {
  do
    i = us_bitset_next(present, i);
  while (i >= 0 && s->bodies[i].fixed);
  return i;
}

/* O(present bodies + their contacts), not O(structure): the planner
 * builds whole systems of one component of a large structure. The
 * contacts keep ascending order (the backends' column order). */
int us_eq_build(us_EqSystem *e, const us_Bitset *present) {
  const us_Structure *s = e->s;
  if (!e->inc_start && build_incidence(e)) return -1;
  /* sizes first (counting is cheap) so that an OOM leaves nothing half-built */
  int nb = 0, nc = 0;
  for (int i = next_present(s, present, -1); i >= 0; i = next_present(s, present, i)) {
    nb++;
    nc += e->inc_start[i + 1] - e->inc_start[i];
  }
  if (reserve(e, nb, nc)) return -1;
  clear_rows(e);
  for (int i = next_present(s, present, -1); i >= 0; i = next_present(s, present, i))
    number_body(e, i, e->nbody++);
  e->ncontact = 0;
  for (int r = 0; r < e->nbody; r++) { /* each active contact once, from its first movable side */
    int u = e->body[r];
    for (int m = e->inc_start[u]; m < e->inc_start[u + 1]; m++) {
      int c = e->inc[m];
      const us_Contact *k = &s->contacts[c];
      int v = k->a == u ? k->b : k->a;
      if (v >= 0 && e->row_of_body[v] >= 0 && v < u) continue;
      if (us_contact_active(s, present, c)) e->contact[e->ncontact++] = c;
    }
  }
  if (e->ncontact > 1) qsort(e->contact, (size_t)e->ncontact, sizeof(int), int_cmp);
  for (int ci = 0; ci < e->ncontact; ci++) {
    e->mu[ci] = s->contacts[e->contact[ci]].mu;
    write_contact(e, ci, e->contact[ci]);
  }
  return 0;
}

void us_eq_mult(const us_EqSystem *e, const double *x, double *y) {
  size_t rows = (size_t)e->nbody * (size_t)e->nw;
  memset(y, 0, rows * sizeof(double));
  size_t cols = (size_t)e->ncontact * (size_t)e->dim;
  for (size_t j = 0; j < cols; j++) {
    if (x[j] == 0.0) continue;
    for (size_t side = 0; side < 2; side++) {
      int blk = e->blk[2 * j + side];
      if (blk < 0) continue;
      const double *w = e->w + (2 * j + side) * (size_t)e->nw;
      double *yb = y + (size_t)blk * (size_t)e->nw;
      for (int r = 0; r < e->nw; r++) yb[r] += w[r] * x[j];
    }
  }
}

/* ------------------------------------------------------ region systems */

/* Forget the rows of the previous build (row_of_body back to all -1). */
static void clear_rows(us_EqSystem *e) {
  for (int r = 0; r < e->nbody; r++) e->row_of_body[e->body[r]] = -1;
  e->nbody = 0;
}

/* Rows of the region's bodies, in the order given, with their gravity. */
static void number_region(us_EqSystem *e, const int *reg, int nreg) {
  for (int q = 0; q < nreg; q++) number_body(e, reg[q], e->nbody++);
}

/* Move the known force fb (dim components) of contact c on row body u to
 * the right-hand side: rhs_u -= wrench of fb on u. */
static void fold_fixed(us_EqSystem *e, int u, int c, const double *fb) {
  const us_Contact *k = &e->s->contacts[c];
  double sign = u == k->a ? -1.0 : 1.0, w[6];
  double *rhs = e->rhs + (size_t)e->row_of_body[u] * (size_t)e->nw;
  for (int comp = 0; comp < e->dim; comp++) {
    if (fb[comp] == 0.0) continue;
    unit_wrench(e, u, k->p, comp == 0 ? k->n : k->t[comp - 1], sign, w);
    for (int r = 0; r < e->nw; r++) rhs[r] -= w[r] * fb[comp];
  }
}

int us_eq_build_region(us_EqSystem *e, const us_Bitset *present, const us_EqRegion *g,
                       const double *fbase) {
  const us_Structure *s = e->s;
  int nc = 0;
  for (int q = 0; q < g->nreg; q++) nc += g->inc_start[g->reg[q] + 1] - g->inc_start[g->reg[q]];
  if (reserve(e, g->nreg, nc)) return -1;
  clear_rows(e);
  number_region(e, g->reg, g->nreg);
  e->ncontact = 0;
  for (int q = 0; q < g->nreg; q++) {
    int u = g->reg[q];
    for (int m = g->inc_start[u]; m < g->inc_start[u + 1]; m++) {
      int c = g->inc[m];
      const us_Contact *k = &s->contacts[c];
      int v = k->a == u ? k->b : k->a;
      int v_in = v >= 0 && g->in_r[v];
      if (v_in && u != k->a) continue; /* both sides in R: listed once, from a */
      if (!us_contact_active(s, present, c)) continue;
      int outside = v >= 0 && !v_in && !s->bodies[v].fixed;
      if (outside && g->fixed_boundary) {
        fold_fixed(e, u, c, fbase + (size_t)c * (size_t)e->dim);
        continue;
      }
      int ci = e->ncontact++;
      e->contact[ci] = c;
      e->mu[ci] = k->mu;
      write_contact(e, ci, c);
    }
  }
  return 0;
}
