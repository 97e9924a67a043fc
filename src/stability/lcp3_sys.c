/* The LCP operator of a 3D structure (lcp_sys.h with nw = 6): every index
 * is a generator of a contact's polyhedral friction cone, so the LCP is
 * frictionless and positive semidefinite (docs/lcp.md, "3D").
 *
 * Index K c + s is the cone generator column of slot s of structure
 * contact c in us_eq_generators (lp_gen.h: slot 0 the normal, 1.. the
 * polygon's edges, inner or outer as the front end's cone set says, or
 * the half-space's +-t1, +-t2). The wrenches come from the equilibrium
 * system's columns, already in its units (forces / W, torques / (W L)),
 * and are loaded per test: a refinement or a switch between inner and
 * outer polygons changes them, and us_lcp3_sys_load says which contacts
 * changed so that the caller drops a state built on the old ones.
 * Masses: translational m_total / m, rotational m_total L^2 I^-1 with I
 * the body's inertia tensor about its centre of mass (world axes); a
 * singular tensor (a point body) gets no rotational freedom.
 */
#include "lcp_sys.h"

#include "lp_gen.h"

#include <math.h>
#include <string.h>

/* Inverse of the symmetric 3 x 3 matrix I times k into R; a singular or
 * non-finite one gives R = 0. */
static void inverse3(const double I[3][3], double k, double *R) {
  double c[9] = {
      I[1][1] * I[2][2] - I[1][2] * I[2][1], I[0][2] * I[2][1] - I[0][1] * I[2][2],
      I[0][1] * I[1][2] - I[0][2] * I[1][1], I[1][2] * I[2][0] - I[1][0] * I[2][2],
      I[0][0] * I[2][2] - I[0][2] * I[2][0], I[0][2] * I[1][0] - I[0][0] * I[1][2],
      I[1][0] * I[2][1] - I[1][1] * I[2][0], I[0][1] * I[2][0] - I[0][0] * I[2][1],
      I[0][0] * I[1][1] - I[0][1] * I[1][0]};
  double det = I[0][0] * c[0] + I[0][1] * c[3] + I[0][2] * c[6];
  double tr = I[0][0] + I[1][1] + I[2][2];
  int ok = isfinite(det) && tr > 0 && det > 1e-12 * tr * tr * tr;
  for (int i = 0; i < 9; i++) R[i] = ok ? k * c[i] / det : 0.0;
}

static void fill_masses3(us_LcpSys *y) {
  const us_Structure *s = y->s;
  double mt = us_lcp_sys_movable_mass(s), L = s->scale > 0 ? s->scale : 1.0;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    double *mi = y->minv + 6 * (size_t)i, *R = y->rinv + 9 * (size_t)i;
    int ok = !b->fixed && b->mass > 0;
    for (int r = 0; r < 6; r++) mi[r] = ok && r < 3 ? mt / b->mass : 0.0;
    if (ok)
      inverse3(b->inertia3, mt * L * L, R);
    else
      memset(R, 0, 9 * sizeof(double));
  }
}

int us_lcp3_sys_init(us_LcpSys *y, const us_Structure *s) {
  if (us_lcp_sys_alloc(y, s, 6, us_eq_gen_slots(3))) return -1;
  fill_masses3(y);
  return us_lcp_sys_link(y);
}

/* The wrench of generator column j of g on both sides of its contact c
 * into out[12] (side 0: body a, 1: body b; rows of fixed sides stay 0). */
static void column_wrench(const us_LcpSys *y, const us_EqSystem *e, const us_EqGen *g, int j,
                          int c, double *out) {
  memset(out, 0, 12 * sizeof(double));
  for (int k = g->start[j]; k < g->start[j + 1]; k++) {
    int blk = g->row[k] / 6, r = g->row[k] % 6, body = e->body[blk];
    int side = y->cb[2 * c] == body ? 0 : 1;
    out[6 * side + r] = g->val[k];
  }
}

/* Contact c's slots and wrenches from columns [j0, j1) of g; 1 if they
 * differ from the stored ones. */
static int load_contact(us_LcpSys *y, const us_EqSystem *e, const us_EqGen *g, int j0, int j1,
                        int c) {
  size_t K = (size_t)y->K;
  unsigned char *sl = y->slots + K * (size_t)c;
  int changed = y->nslot[c] != j1 - j0;
  y->nslot[c] = j1 - j0;
  for (int j = j0; j < j1; j++) {
    int slot = us_eq_gen_slot(g, j);
    double wr[12];
    column_wrench(y, e, g, j, c, wr);
    double *w0 = us_lcp_sys_w(y, y->K * c + slot, 0); /* sides 0 and 1 are adjacent */
    changed |= sl[j - j0] != slot || memcmp(w0, wr, sizeof wr) != 0;
    sl[j - j0] = (unsigned char)slot;
    memcpy(w0, wr, sizeof wr);
  }
  return changed;
}

void us_lcp3_sys_load(us_LcpSys *y, const us_EqSystem *e, const us_EqGen *g,
                      unsigned char *changed) {
  for (int j0 = 0, j1; j0 < g->ncol; j0 = j1) {
    int ci = g->col_contact[j0];
    for (j1 = j0 + 1; j1 < g->ncol && g->col_contact[j1] == ci; j1++) {}
    int c = e->contact[ci];
    if (load_contact(y, e, g, j0, j1, c)) changed[c] = 1;
  }
}
