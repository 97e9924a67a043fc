/* The LCP operator of a structure, A = J M^-1 J^T and b = J M^-1 F_ext,
 * kept implicit: entries are computed on demand from the per-contact
 * wrenches, products go through the bodies, so memory is O(bodies +
 * contacts) and never O(contacts^2). The dimension is a parameter (nw
 * rows per body, K indices per contact, lcp_sys.h); this file fills the
 * 2D operators, lcp3_sys.c the 3D one, and both share the products.
 *
 * 2D indices: 2c is the normal of structure contact c, 2c + 1 its friction
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
    int ends[2] = {y->cb[2 * c], y->cb[2 * c + 1]};
    y->slots[2 * c] = 0, y->slots[2 * c + 1] = 1, y->nslot[c] = 2;
    for (int side = 0; side < 2; side++) {
        for (int comp = 0; comp < 2; comp++) {
        double *w = us_lcp_sys_w(y, 2 * c + comp, side);
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

double us_lcp_sys_movable_mass(const us_Structure *s) {
  double mt = 0.0;
  for (int i = 0; i < s->nbody; i++)
    if (!s->bodies[i].fixed) mt += s->bodies[i].mass;
  return mt > 0 ? mt : 1.0;
}

static void fill_masses(us_LcpSys *y) {
  const us_Structure *s = y->s;
  double mt = us_lcp_sys_movable_mass(s), L = s->scale > 0 ? s->scale : 1.0;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    double *mi = y->minv + 3 * (size_t)i;
    int ok = !b->fixed && b->mass > 0;
    mi[0] = mi[1] = ok ? mt / b->mass : 0.0;
    mi[2] = ok && b->inertia > 0 ? mt * L * L / b->inertia : 0.0;
  }
}

/* Contacts of every body (CSR). */
int us_lcp_sys_link(us_LcpSys *y) {
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

int us_lcp_sys_alloc(us_LcpSys *y, const us_Structure *s, int nw, int K) {
  memset(y, 0, sizeof *y);
  y->s = s;
  y->nbody = s->nbody;
  y->ncontact = s->ncontact;
  y->nw = nw;
  y->K = K;
  size_t nb = (size_t)(s->nbody > 0 ? s->nbody : 1),
         nc = (size_t)(s->ncontact > 0 ? s->ncontact : 1), w = (size_t)nw, k = (size_t)K;
  y->minv = us_calloc(w * nb, sizeof(double));
  y->rinv = nw == 6 ? us_calloc(9 * nb, sizeof(double)) : NULL;
  y->fext = us_calloc(w * nb, sizeof(double));
  y->present = us_calloc(nb, 1);
  y->cb = us_malloc(2 * nc * sizeof(int));
  y->w = us_calloc(2 * w * k * nc, sizeof(double));
  y->slots = us_calloc(k * nc, 1);
  y->nslot = us_calloc(nc, sizeof(int));
  y->u = us_calloc(w * nb, sizeof(double));
  y->touched = us_malloc(nb * sizeof(int));
  y->bmark = us_calloc(nb, 1);
  y->cmark = us_calloc(nc, 1);
  if (!y->minv || (nw == 6 && !y->rinv) || !y->fext || !y->present || !y->cb || !y->w ||
      !y->slots || !y->nslot || !y->u || !y->touched || !y->bmark || !y->cmark)
    return -1;
  for (int c = 0; c < s->ncontact; c++) {
    const us_Contact *ct = &s->contacts[c];
    y->cb[2 * c] = side_body(s, ct->a);
    y->cb[2 * c + 1] = side_body(s, ct->b);
  }
  return 0;
}

static int sys_init(us_LcpSys *y, const us_Structure *s, int cone) {
  if (us_lcp_sys_alloc(y, s, 3, 2)) return -1;
  fill_contacts(y, cone);
  fill_masses(y);
  return us_lcp_sys_link(y);
}

int us_lcp_sys_init(us_LcpSys *y, const us_Structure *s) { return sys_init(y, s, 0); }

int us_lcp_sys_init_cone(us_LcpSys *y, const us_Structure *s) { return sys_init(y, s, 1); }

void us_lcp_sys_free(us_LcpSys *y) {
  void *arrs[] = {y->minv,      y->rinv, y->fext, y->present, y->cb,    y->w,     y->slots,
                  y->nslot,     y->adj_start, y->adj,  y->u,       y->touched, y->bmark, y->cmark};
  for (size_t i = 0; i < sizeof arrs / sizeof arrs[0]; i++) us_free(arrs[i]);
  memset(y, 0, sizeof *y);
}

/* Body of side `side` of LCP index i if it moves, else -1. */
static int moving(const us_LcpSys *y, int i, int side) {
  int b = y->cb[2 * (i / y->K) + side];
  return b >= 0 && y->present[b] ? b : -1;
}

/* Index m of contact c's slots in use. */
static int slot_index(const us_LcpSys *y, int c, int m) {
  return y->K * c + y->slots[(size_t)y->K * (size_t)c + (size_t)m];
}

/* p^T M^-1 q on body b (3D: the rotation through its 3 x 3 block). */
static double mdot(const us_LcpSys *y, int b, const double *p, const double *q) {
  const double *mi = y->minv + (size_t)y->nw * (size_t)b;
  double sum = 0.0;
  int nd = y->rinv ? 3 : y->nw;
  for (int r = 0; r < nd; r++) sum += p[r] * mi[r] * q[r];
  if (!y->rinv) return sum;
  const double *R = y->rinv + 9 * (size_t)b;
  for (int r = 0; r < 3; r++)
    sum += p[3 + r] * (R[3 * r] * q[3] + R[3 * r + 1] * q[4] + R[3 * r + 2] * q[5]);
  return sum;
}

static double sys_entry(void *ctx, int i, int j) {
  const us_LcpSys *y = ctx;
  double sum = 0.0;
  for (int si = 0; si < 2; si++) {
    int b = moving(y, i, si);
    if (b < 0) continue;
    for (int sj = 0; sj < 2; sj++) {
      if (moving(y, j, sj) != b) continue;
      sum += mdot(y, b, us_lcp_sys_w(y, i, si), us_lcp_sys_w(y, j, sj));
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
    double *u = y->u + (size_t)y->nw * (size_t)b;
    for (int r = 0; r < y->nw; r++) u[r] += x * w[r];
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
    const double *w = us_lcp_sys_w(y, i, side), *v = y->u + (size_t)y->nw * (size_t)b;
    double t = 0.0; /* per side, then summed: the 2D operator's rounding */
    for (int r = 0; r < y->nw; r++) t += w[r] * v[r];
    s += t;
  }
  return s;
}

/* out = M^-1 u of body b (out may be u). */
static void minv_apply(const us_LcpSys *y, int b, const double *u, double *out) {
  const double *mi = y->minv + (size_t)y->nw * (size_t)b;
  double rot[3] = {0.0, 0.0, 0.0};
  if (y->rinv) {
    const double *R = y->rinv + 9 * (size_t)b;
    for (int r = 0; r < 3; r++) rot[r] = R[3 * r] * u[3] + R[3 * r + 1] * u[4] + R[3 * r + 2] * u[5];
  }
  int nd = y->rinv ? 3 : y->nw;
  for (int r = 0; r < nd; r++) out[r] = u[r] * mi[r];
  if (y->rinv) memcpy(out + 3, rot, sizeof rot);
}

static void to_velocity(us_LcpSys *y, int b) {
  double *u = y->u + (size_t)y->nw * (size_t)b;
  minv_apply(y, b, u, u);
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
      for (int m = 0; m < y->nslot[c]; m++) {
        int i = slot_index(y, c, m);
        out_y[i] = gather(y, i);
        out[nout++] = i;
      }
    }
  }
  for (int q = 0; q < nout; q++) y->cmark[out[q] / y->K] = 0;
  for (int t = 0; t < nt; t++) {
    int b = y->touched[t];
    y->bmark[b] = 0;
    memset(y->u + (size_t)y->nw * (size_t)b, 0, (size_t)y->nw * sizeof(double));
  }
  return nout;
}

/* u = E f + F_ext on present bodies (the net normalized wrench); forces
 * sit only at the contacts' slots in use. */
static void net_wrench(us_LcpSys *y, const double *f) {
  size_t nw = (size_t)y->nw;
  for (int b = 0; b < y->nbody; b++)
    if (y->present[b]) memcpy(y->u + nw * (size_t)b, y->fext + nw * (size_t)b, nw * sizeof(double));
  int nt = 0;
  for (int c = 0; c < y->ncontact; c++)
    for (int m = 0; m < y->nslot[c]; m++) {
      int i = slot_index(y, c, m);
      if (f[i] != 0.0) scatter(y, i, f[i], &nt);
    }
  for (int t = 0; t < nt; t++) y->bmark[y->touched[t]] = 0;
}

static void sys_full(void *ctx, const double *f, const unsigned char *live, double *a) {
  us_LcpSys *y = ctx;
  net_wrench(y, f);
  for (int b = 0; b < y->nbody; b++)
    if (y->present[b]) to_velocity(y, b);
  for (int c = 0; c < y->ncontact; c++)
    for (int m = 0; m < y->nslot[c]; m++) {
      int i = slot_index(y, c, m);
      if (live[i]) a[i] = gather(y, i);
    }
  memset(y->u, 0, (size_t)y->nw * (size_t)y->nbody * sizeof(double));
}

double us_lcp_sys_residual(us_LcpSys *y, const double *f, int *worst_body, double *energy) {
  net_wrench(y, f);
  double worst = 0.0, q = 0.0;
  *worst_body = -1;
  for (int b = 0; b < y->nbody; b++) {
    if (!y->present[b]) continue;
    const double *u = y->u + (size_t)y->nw * (size_t)b, *mi = y->minv + (size_t)y->nw * (size_t)b;
    if (y->rinv)
      q += mdot(y, b, u, u);
    else /* component by component: the 2D operator's rounding */
      for (int r = 0; r < y->nw; r++) q += u[r] * mi[r] * u[r];
    for (int r = 0; r < y->nw; r++) {
      if (fabs(u[r]) > worst) {
        worst = fabs(u[r]);
        *worst_body = b;
      }
    }
  }
  memset(y->u, 0, (size_t)y->nw * (size_t)y->nbody * sizeof(double));
  if (energy) *energy = q;
  return worst;
}

void us_lcp_sys_velocity(us_LcpSys *y, const double *f, double *v) {
  net_wrench(y, f);
  size_t nw = (size_t)y->nw;
  for (int b = 0; b < y->nbody; b++)
    if (y->present[b]) minv_apply(y, b, y->u + nw * (size_t)b, v + nw * (size_t)b);
  memset(y->u, 0, nw * (size_t)y->nbody * sizeof(double));
}

us_LcpOps us_lcp_sys_ops(us_LcpSys *y) {
  us_LcpOps o = {y, sys_entry, sys_apply, sys_full};
  return o;
}
