/* The independent certificate check: do given contact forces really hold
 * every present movable body in equilibrium, inside the friction cones?
 *
 * Algorithm: derived again straight from the structure, sharing no code
 * with the equilibrium system or any solver. One pass over the forces
 * accumulates, per body, gravity (m g at the centre of mass, so no torque)
 * plus each contact force F = f_n n + f_t1 t1 (+ f_t2 t2) at p on body b and
 * -F on body a, with torques (p - com) x F about that body's centre of
 * mass; a second pass over the bodies takes the worst residuals. All
 * measures are relative: forces to the total weight W, torques to
 * W * scale. A force on a contact that is not active in the sub-assembly
 * (a side absent, or both sides fixed), a contact listed twice, a bad
 * index or a non-finite value makes the check fail outright.
 */
#include "stability.h"

#include <math.h>
#include <string.h>

static int side_in(const us_Structure *s, const us_Bitset *present, int i) {
  return i < 0 || s->bodies[i].fixed || us_bitset_get(present, i);
}

static int side_moves(const us_Structure *s, int i) { return i >= 0 && !s->bodies[i].fixed; }

/* Can contact c carry a force in sub-assembly `present`? */
static int usable(const us_Structure *s, const us_Bitset *present, int c) {
  if (c < 0 || c >= s->ncontact) return 0;
  const us_Contact *k = &s->contacts[c];
  return side_in(s, present, k->a) && side_in(s, present, k->b) &&
         (side_moves(s, k->a) || side_moves(s, k->b));
}

static double norm3(const double *v) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

/* Add force F at p to body i's accumulator (force, torque about com). */
static void push(const us_Structure *s, double *acc, int i, const double *p, const double *F,
                 double sign) {
  if (!side_moves(s, i)) return;
  const double *c = s->bodies[i].com;
  double r[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
  double *a = acc + 6 * (size_t)i;
  for (int j = 0; j < 3; j++) a[j] += sign * F[j];
  a[3] += sign * (r[1] * F[2] - r[2] * F[1]);
  a[4] += sign * (r[2] * F[0] - r[0] * F[2]);
  a[5] += sign * (r[0] * F[1] - r[1] * F[0]);
}

/* Cone and sign measures of one force (absolute, newtons); F gets the
 * force vector. Returns 0, or -1 if a component is not finite. */
static int one_force(const us_Structure *s, const us_Contact *k, const double *f, double *F,
                     double *cone, double *sign) {
  int dim = s->dim;
  double ft2 = 0.0;
  for (int j = 0; j < dim; j++)
    if (!isfinite(f[j])) return -1;
  for (int j = 0; j < 3; j++) F[j] = f[0] * k->n[j];
  for (int t = 1; t < dim; t++) {
    ft2 += f[t] * f[t];
    for (int j = 0; j < 3; j++) F[j] += f[t] * k->t[t - 1][j];
  }
  *cone = US_MAX(sqrt(ft2) - k->mu * f[0], 0.0);
  *sign = US_MAX(-f[0], 0.0);
  return 0;
}

static us_CertCheck failed_check(void) {
  us_CertCheck r;
  memset(&r, 0, sizeof r);
  r.ok = 0;
  r.max_force_residual = r.max_torque_residual = INFINITY;
  r.max_cone_violation = r.max_sign_violation = INFINITY;
  r.worst_body = r.worst_contact = -1;
  return r;
}

/* Pass 1: forces into the accumulators; cone and sign measures. Returns 0,
 * or -1 (r->worst_contact set) for an unusable contact or bad value. */
static int add_forces(const us_Structure *s, const us_Bitset *present, const us_Forces *f,
                      double *acc, unsigned char *seen, us_CertCheck *r) {
  double inv_w = 1.0 / s->weight, worst = 0.0; /* -1 unless something is violated */
  for (int i = 0; i < f->ncontact; i++) {
    int c = f->contact[i];
    if (!usable(s, present, c) || seen[c]) {
      r->worst_contact = c;
      return -1;
    }
    seen[c] = 1;
    const us_Contact *k = &s->contacts[c];
    double F[3], cone, sign;
    if (one_force(s, k, f->f + (size_t)i * (size_t)s->dim, F, &cone, &sign)) {
      r->worst_contact = c;
      return -1;
    }
    push(s, acc, k->b, k->p, F, 1.0);
    push(s, acc, k->a, k->p, F, -1.0);
    r->max_cone_violation = US_MAX(r->max_cone_violation, cone * inv_w);
    r->max_sign_violation = US_MAX(r->max_sign_violation, sign * inv_w);
    if (cone + sign > worst) {
      worst = cone + sign;
      r->worst_contact = c;
    }
  }
  return 0;
}

/* Pass 2: gravity and the residual of every present movable body. */
static void residuals(const us_Structure *s, const us_Bitset *present, const double *acc,
                      us_CertCheck *r) {
  double inv_w = 1.0 / s->weight, inv_wl = 1.0 / (s->weight * s->scale), worst = -1.0;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    if (b->fixed || !us_bitset_get(present, i)) continue;
    const double *a = acc + 6 * (size_t)i;
    double F[3] = {a[0] + b->mass * s->gravity[0], a[1] + b->mass * s->gravity[1],
                   a[2] + b->mass * s->gravity[2]};
    double fr = norm3(F) * inv_w, tr = norm3(a + 3) * inv_wl;
    if (!isfinite(fr) || !isfinite(tr)) fr = tr = INFINITY;
    r->max_force_residual = US_MAX(r->max_force_residual, fr);
    r->max_torque_residual = US_MAX(r->max_torque_residual, tr);
    if (fr + tr > worst) {
      worst = fr + tr;
      r->worst_body = i;
    }
  }
}

int us_certificate_check_buf(const us_Structure *s, const us_Bitset *present,
                             const us_Forces *f, double tol, double *acc, unsigned char *seen,
                             us_CertCheck *out) {
  us_CertCheck r;
  memset(&r, 0, sizeof r);
  r.worst_body = r.worst_contact = -1;
  memset(acc, 0, 6 * (size_t)s->nbody * sizeof(double));
  memset(seen, 0, (size_t)s->ncontact);
  if (present->nbits != s->nbody || f->ncontact < 0 || (f->ncontact > 0 && (!f->contact || !f->f))) {
    *out = failed_check();
    return -1;
  }
  if (add_forces(s, present, f, acc, seen, &r)) {
    int c = r.worst_contact;
    *out = failed_check();
    out->worst_contact = c;
    return -1;
  }
  residuals(s, present, acc, &r);
  r.ok = r.max_force_residual <= tol && r.max_torque_residual <= tol &&
         r.max_cone_violation <= tol && r.max_sign_violation <= tol;
  *out = r;
  return 0;
}

us_CertCheck us_certificate_check(const us_Structure *s, const us_Bitset *present,
                                  const us_Forces *f, double tol) {
  us_CertCheck r;
  double *acc = us_calloc((size_t)(s->nbody > 0 ? s->nbody : 1) * 6, sizeof(double));
  unsigned char *seen = us_calloc((size_t)(s->ncontact > 0 ? s->ncontact : 1), 1);
  if (!acc || !seen)
    r = failed_check(); /* no memory: nothing is certified */
  else
    us_certificate_check_buf(s, present, f, tol, acc, seen, &r);
  us_free(acc);
  us_free(seen);
  return r;
}
