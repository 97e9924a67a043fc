/* The LCP operator of a 2D structure, A = J M^-1 J^T and b = J M^-1 F_ext,
 * kept implicit: entries are computed on demand from the per-contact
 * wrenches, products go through the bodies, so memory is O(bodies +
 * contacts) and never O(contacts^2).
 *
 * Indices: 2c is the normal of structure contact c, 2c + 1 its friction
 * (component along t[0]). Units follow us_EqSystem: a unit component
 * pushes body b with +d at p and body a with -d; its wrench on a body is
 * (d, ((p - com) x d)_z / L) with L the structure's scale, and forces are in
 * units of the weight W. The generalized coordinates conjugate to these
 * rows are (x, y, angle * L), so the mass matrix is (m, m, I / L^2),
 * divided by the total movable mass m_t so that gravity gives every free
 * body an acceleration of magnitude 1. A_ij = sum over the bodies shared
 * by contacts i and j of w_i^T M^-1 w_j; a_i = w_i^T v summed over the
 * contact's bodies, v = M^-1 (E f + F_ext) per body.
 *
 * The cone operator (us_lcp_sys_init_cone) gives a contact with a finite
 * mu > 0 the two edges of its friction cone instead: index 2c pushes along
 * n + mu t, 2c + 1 along n - mu t, so a force in the cone is a
 * non-negative combination of the two (f_n = l0 + l1, f_t = mu (l0 - l1))
 * and a_2c, a_2c+1 >= 0 says that the contact's acceleration lies in the
 * dual cone. Contacts with mu = 0 or mu = +inf keep (n, t).
 *
 * Only `present` bodies move; fixed, ground and absent bodies have
 * M^-1 = 0. A body with zero inertia (a point body whose contacts all act
 * at its centre) gets no rotational freedom: its torque rows are zero.
 */
#include "lcp_sys.h"

#include <math.h>
#include <string.h>

/* Wrench of a unit push along d at p on body `body`, sign +-1. */
static void unit_wrench(const us_Structure *s, double L, int body, const double *p, const double *d,
                        double sign, double *out) {
  const double *com = s->bodies[body].com;
  double rx = p[0] - com[0], ry = p[1] - com[1];
  out[0] = sign * d[0];
  out[1] = sign * d[1];
  out[2] = sign * (rx * d[1] - ry * d[0]) / L;
}

static int side_body(const us_Structure *s, int b) {
  return b >= 0 && !s->bodies[b].fixed ? b : -1;
}

/* Direction of LCP index 2c + comp of contact k (cone: the cone's edges). */
static void index_dir(const us_Contact *k, int comp, int cone, double *d) {
  const double *t = k->t[0];
  double mu = k->mu;
  if (!cone || !(mu > 0) || isinf(mu)) {
    memcpy(d, comp == 0 ? k->n : t, 2 * sizeof(double));
    return;
  }
  double s = comp == 0 ? mu : -mu;
  d[0] = k->n[0] + s * t[0];
  d[1] = k->n[1] + s * t[1];
}

static void fill_contacts(us_LcpSys *y, int cone) {
  const us_Structure *s = y->s;
  double L = s->scale > 0 ? s->scale : 1.0;
  for (int c = 0; c < s->ncontact; c++) {
    const us_Contact *k = &s->contacts[c];
    int ends[2] = {side_body(s, k->a), side_body(s, k->b)};
    for (int side = 0; side < 2; side++) {
      y->cb[2 * c + side] = ends[side];
      for (int comp = 0; comp < 2; comp++) {
        double *w = y->w + ((size_t)(2 * c + comp) * 2 + (size_t)side) * 3;
        if (ends[side] < 0)
          memset(w, 0, 3 * sizeof(double));
        else {
          double d[2];
          index_dir(k, comp, cone, d);
          unit_wrench(s, L, ends[side], k->p, d, side == 0 ? -1.0 : 1.0, w);
        }
      }
    }
  }
}

static void fill_masses(us_LcpSys *y) {
  const us_Structure *s = y->s;
  double mt = 0.0, L = s->scale > 0 ? s->scale : 1.0;
  for (int i = 0; i < s->nbody; i++)
    if (!s->bodies[i].fixed) mt += s->bodies[i].mass;
  if (!(mt > 0)) mt = 1.0;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    double *mi = y->minv + 3 * (size_t)i;
    int ok = !b->fixed && b->mass > 0;
    mi[0] = mi[1] = ok ? mt / b->mass : 0.0;
    mi[2] = ok && b->inertia > 0 ? mt * L * L / b->inertia : 0.0;
  }
}

/* Contacts of every body (CSR). */
static int fill_adjacency(us_LcpSys *y) {
  const us_Structure *s = y->s;
  y->adj_start = us_calloc((size_t)s->nbody + 1, sizeof(int));
  y->adj = us_malloc((size_t)(2 * s->ncontact + 1) * sizeof(int));
  if (!y->adj_start || !y->adj) return -1;
  for (int c = 0; c < 2 * s->ncontact; c++)
    if (y->cb[c] >= 0) y->adj_start[y->cb[c] + 1]++;
  for (int i = 0; i < s->nbody; i++) y->adj_start[i + 1] += y->adj_start[i];
  for (int i = 0; i < s->nbody; i++) y->touched[i] = y->adj_start[i]; /* cursors */
  for (int c = 0; c < 2 * s->ncontact; c++)
    if (y->cb[c] >= 0) y->adj[y->touched[y->cb[c]]++] = c / 2;
  return 0;
}

static int sys_init(us_LcpSys *y, const us_Structure *s, int cone) {
  memset(y, 0, sizeof *y);
  y->s = s;
  y->nbody = s->nbody;
  y->ncontact = s->ncontact;
  size_t nb = (size_t)(s->nbody > 0 ? s->nbody : 1),
         nc = (size_t)(s->ncontact > 0 ? s->ncontact : 1);
  y->minv = us_calloc(3 * nb, sizeof(double));
  y->fext = us_calloc(3 * nb, sizeof(double));
  y->present = us_calloc(nb, 1);
  y->cb = us_malloc(2 * nc * sizeof(int));
  y->w = us_calloc(12 * nc, sizeof(double));
  y->u = us_calloc(3 * nb, sizeof(double));
  y->touched = us_malloc(nb * sizeof(int));
  y->bmark = us_calloc(nb, 1);
  y->cmark = us_calloc(nc, 1);
  if (!y->minv || !y->fext || !y->present || !y->cb || !y->w || !y->u || !y->touched || !y->bmark ||
      !y->cmark)
    return -1;
  fill_contacts(y, cone);
  fill_masses(y);
  return fill_adjacency(y);
}

int us_lcp_sys_init(us_LcpSys *y, const us_Structure *s) { return sys_init(y, s, 0); }

int us_lcp_sys_init_cone(us_LcpSys *y, const us_Structure *s) { return sys_init(y, s, 1); }

void us_lcp_sys_free(us_LcpSys *y) {
  void *arrs[] = {y->minv, y->fext, y->present, y->cb,    y->w,    y->adj_start,
                  y->adj,  y->u,    y->touched, y->bmark, y->cmark};
  for (size_t i = 0; i < sizeof arrs / sizeof arrs[0]; i++) us_free(arrs[i]);
  memset(y, 0, sizeof *y);
}

/* Body of side `side` of LCP index i if it moves, else -1. */
static int moving(const us_LcpSys *y, int i, int side) {
  int b = y->cb[2 * (i >> 1) + side];
  return b >= 0 && y->present[b] ? b : -1;
}

static double sys_entry(void *ctx, int i, int j) {
  const us_LcpSys *y = ctx;
  double sum = 0.0;
  for (int si = 0; si < 2; si++) {
    int b = moving(y, i, si);
    if (b < 0) continue;
    for (int sj = 0; sj < 2; sj++) {
      if (moving(y, j, sj) != b) continue;
      const double *wi = us_lcp_sys_w(y, i, si), *wj = us_lcp_sys_w(y, j, sj);
      const double *mi = y->minv + 3 * (size_t)b;
      sum += wi[0] * mi[0] * wj[0] + wi[1] * mi[1] * wj[1] + wi[2] * mi[2] * wj[2];
    }
  }
  return sum;
}

/* u[b] += x * w for both sides of index i; remember touched bodies. */
static void scatter(us_LcpSys *y, int i, double x, int *nt) {
  for (int side = 0; side < 2; side++) {
    int b = moving(y, i, side);
    if (b < 0) continue;
    const double *w = us_lcp_sys_w(y, i, side);
    double *u = y->u + 3 * (size_t)b;
    for (int r = 0; r < 3; r++) u[r] += x * w[r];
    if (!y->bmark[b]) {
      y->bmark[b] = 1;
      y->touched[(*nt)++] = b;
    }
  }
}

/* w_i . v over the moving sides, v held in u. */
static double gather(const us_LcpSys *y, int i) {
  double s = 0.0;
  for (int side = 0; side < 2; side++) {
    int b = moving(y, i, side);
    if (b < 0) continue;
    const double *w = us_lcp_sys_w(y, i, side), *v = y->u + 3 * (size_t)b;
    s += w[0] * v[0] + w[1] * v[1] + w[2] * v[2];
  }
  return s;
}

static void to_velocity(us_LcpSys *y, int b) {
  double *u = y->u + 3 * (size_t)b;
  const double *mi = y->minv + 3 * (size_t)b;
  for (int r = 0; r < 3; r++) u[r] *= mi[r];
}

static int sys_apply(void *ctx, const int *idx, const double *x, int k, double *out_y, int *out) {
  us_LcpSys *y = ctx;
  int nt = 0, nout = 0;
  for (int j = 0; j < k; j++)
    if (x[j] != 0.0) scatter(y, idx[j], x[j], &nt);
  for (int t = 0; t < nt; t++) to_velocity(y, y->touched[t]);
  for (int t = 0; t < nt; t++) {
    int b = y->touched[t];
    for (int q = y->adj_start[b]; q < y->adj_start[b + 1]; q++) {
      int c = y->adj[q];
      if (y->cmark[c]) continue;
      y->cmark[c] = 1;
      for (int comp = 0; comp < 2; comp++) {
        out_y[2 * c + comp] = gather(y, 2 * c + comp);
        out[nout++] = 2 * c + comp;
      }
    }
  }
  for (int q = 0; q < nout; q += 2) y->cmark[out[q] >> 1] = 0;
  for (int t = 0; t < nt; t++) {
    int b = y->touched[t];
    y->bmark[b] = 0;
    memset(y->u + 3 * (size_t)b, 0, 3 * sizeof(double));
  }
  return nout;
}

/* u = E f + F_ext on present bodies (the net normalized wrench). */
static void net_wrench(us_LcpSys *y, const double *f) {
  for (int b = 0; b < y->nbody; b++)
    if (y->present[b]) memcpy(y->u + 3 * (size_t)b, y->fext + 3 * (size_t)b, 3 * sizeof(double));
  int nt = 0;
  for (int i = 0; i < 2 * y->ncontact; i++)
    if (f[i] != 0.0) scatter(y, i, f[i], &nt);
  for (int t = 0; t < nt; t++) y->bmark[y->touched[t]] = 0;
}

static void sys_full(void *ctx, const double *f, const unsigned char *live, double *a) {
  us_LcpSys *y = ctx;
  net_wrench(y, f);
  for (int b = 0; b < y->nbody; b++)
    if (y->present[b]) to_velocity(y, b);
  for (int i = 0; i < 2 * y->ncontact; i++)
    if (live[i]) a[i] = gather(y, i);
  memset(y->u, 0, 3 * (size_t)y->nbody * sizeof(double));
}

double us_lcp_sys_residual(us_LcpSys *y, const double *f, int *worst_body, double *energy) {
  net_wrench(y, f);
  double worst = 0.0, q = 0.0;
  *worst_body = -1;
  for (int b = 0; b < y->nbody; b++) {
    if (!y->present[b]) continue;
    const double *u = y->u + 3 * (size_t)b, *mi = y->minv + 3 * (size_t)b;
    for (int r = 0; r < 3; r++) {
      q += u[r] * mi[r] * u[r];
      if (fabs(u[r]) > worst) {
        worst = fabs(u[r]);
        *worst_body = b;
      }
    }
  }
  memset(y->u, 0, 3 * (size_t)y->nbody * sizeof(double));
  if (energy) *energy = q;
  return worst;
}

us_LcpOps us_lcp_sys_ops(us_LcpSys *y) {
  us_LcpOps o = {y, sys_entry, sys_apply, sys_full};
  return o;
}
