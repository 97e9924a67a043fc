/* The independent certificate check: do given contact forces really hold
 * every present movable body in equilibrium, inside the friction cones?
 *
 * Algorithm: derived again straight from the structure, sharing no code
 * with the equilibrium system or any solver. One pass over the forces
 * accumulates, per body, each contact force F = f_n n + f_t1 t1 (+ f_t2 t2)
 * at p on body b and -F on body a, with torques (p - com) x F about that
 * body's centre of mass; a second pass over the bodies adds gravity
 * (m g at the centre of mass, so no torque) and takes the worst residuals.
 *
 * Units: everything is normalized before it is added, so that no legal
 * input overflows or underflows: forces are divided by the total weight
 * W = M |g| first, gravity enters as the share m_i / M times the unit
 * direction g / |g|, and lever arms are divided by the structure's scale
 * L.
 *
 * Measures, each relative to what it could be compared with on its own
 * body or contact (not to the whole structure: a residual of 1e-6 W on a
 * body of weight W / 1000 is a tenth of a percent of its weight, and a
 * torque residual of 1e-6 W L on a block of size L / 100 is a tenth of
 * its weight times its size; the first version of this check measured
 * against W and W L, and passed a barrier solution of an unstable
 * 1,256-block stack whose torque residual was 13 % of a block's weight
 * times its size):
 *   force residual of body i:  |sum F + m_i g| / (m_i / M + sum |F|)
 *   torque residual of body i: |sum r x F| / ((m_i / M + sum |F|) r_i)
 * with the sums over the forces on body i and r_i the longest lever arm
 * among them (torques are about the centre of mass, where gravity acts);
 * the cone measure of a contact is the Euclidean distance of its force
 * from the cone over |F| + the smaller weight share of its movable
 * sides, and the sign measure max(-f_n, 0) over the same. Scales are
 * never below CERT_FLOOR (in units of W): the solvers work in units of W
 * to about 1e-13, so a body lighter than 1e-12 of the whole (a pebble on
 * a mountain) is held only to 1e-6 of 1e-12 W, not of its own weight. The distance
 * does not grow with mu (mu |f_n| - |f_t| would, and would reject a
 * correct force of a nearly flat cone on round-off). A contact with
 * mu = INFINITY has the half-space f_n >= 0 as its cone.
 *
 * A force on a contact that is not active in the sub-assembly (a side
 * absent, or both sides fixed), a contact listed twice, a bad index or a
 * non-finite value makes the check fail outright.
 */
#include "certificate.h"

#include "model/massprops.h"

#include <math.h>
#include <string.h>

#define CERT_FLOOR 1e-12 /* least scale of a measure, in units of W */

/* The normalization of one check. */
typedef struct Units {
  double inv_w;   /* 1 / W */
  double inv_l;   /* 1 / L */
  double m;       /* M (divided by, not inverted: 1 / M may overflow) */
  double gdir[3]; /* unit gravity direction */
} Units;

/* mass: the movable mass M when the caller knows it (< 0: summed here,
 * O(bodies)). */
static Units units_of_mass(const us_Structure *s, double mass) {
  Units u;
  double g = us_gravity_norm(s->gravity), m = mass >= 0 ? mass : us_movable_mass(s), w = m * g;
  u.inv_w = w > 0 && isfinite(w) ? 1.0 / w : 1.0;
  u.m = m > 0 && isfinite(m) ? m : 1.0;
  u.inv_l = s->scale > 0 ? 1.0 / s->scale : 1.0;
  for (int j = 0; j < 3; j++) u.gdir[j] = g > 0 && isfinite(g) ? s->gravity[j] / g : 0.0;
  return u;
}

static Units units_of(const us_Structure *s) { return units_of_mass(s, -1.0); }

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

static double norm3(const double *v) { return hypot(hypot(v[0], v[1]), v[2]); }

/* The same without hypot's care, for scales (normalized values are far
 * from overflow; norm3 when they are not). */
static double fast_norm3(const double *v) {
  double q = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return isfinite(q) ? q : norm3(v);
}

double us_cone_distance(double fn, double ft, double mu) {
  ft = fabs(ft);
  if (fn >= 0.0 && (isinf(mu) || ft <= mu * fn)) return 0.0; /* inside (no hypot) */
  double c = 1.0, s = 0.0; /* cone edge direction (cos a, sin a), a = atan(mu) */
  if (isinf(mu)) {
    c = 0.0, s = 1.0;
  } else if (mu > 0) {
    double h = hypot(1.0, mu);
    c = 1.0 / h, s = mu / h;
  }
  if (fn >= 0.0 && ft * c <= fn * s) return 0.0;      /* inside */
  if (fn * c + ft * s <= 0.0) return hypot(fn, ft); /* nearest point: the apex */
  return ft * c - fn * s;                             /* nearest point on the edge */
}

/* Add normalized force F (of norm fn, fast_norm3(F)) at p to body i's
 * accumulator a (US_CERT_ACC values: force, torque about com / L, sum of
 * |F|, longest lever arm). */
static void push_at(const us_Structure *s, const Units *u, double *a, int i, const double *p,
                    const double *F, double fn, double sign) {
  const double *c = s->bodies[i].com;
  double r[3] = {(p[0] - c[0]) * u->inv_l, (p[1] - c[1]) * u->inv_l, (p[2] - c[2]) * u->inv_l};
  if (F[0] == 0.0 && F[1] == 0.0 && F[2] == 0.0) { /* adds nothing but the lever arm */
    a[7] = US_MAX(a[7], fast_norm3(r));
    return;
  }
  for (int j = 0; j < 3; j++) a[j] += sign * F[j];
  a[3] += sign * (r[1] * F[2] - r[2] * F[1]);
  a[4] += sign * (r[2] * F[0] - r[0] * F[2]);
  a[5] += sign * (r[0] * F[1] - r[1] * F[0]);
  a[6] += fn;
  a[7] = US_MAX(a[7], fast_norm3(r));
}

/* The same into the accumulator of body i among all bodies' (acc). */
static void push(const us_Structure *s, const Units *u, double *acc, int i, const double *p,
                 const double *F, double fn, double sign) {
  if (side_moves(s, i)) push_at(s, u, acc + US_CERT_ACC * (size_t)i, i, p, F, fn, sign);
}

/* The smaller weight share of the movable sides of contact k (the floor
 * of its cone and sign measures). */
static double contact_floor(const us_Structure *s, const Units *u, const us_Contact *k) {
  double fl = INFINITY;
  if (side_moves(s, k->a)) fl = s->bodies[k->a].mass / u->m;
  if (side_moves(s, k->b)) fl = US_MIN(fl, s->bodies[k->b].mass / u->m);
  return isfinite(fl) ? US_MAX(fl, CERT_FLOOR) : 1.0;
}

/* Body i's residuals relative to its own scales (file header), from its
 * accumulator a with gravity not yet added. */
static void body_residuals(const us_Structure *s, const Units *u, int i, const double *a,
                           double *fr, double *tr) {
  double share = s->bodies[i].mass / u->m;
  double G[3] = {a[0] + share * u->gdir[0], a[1] + share * u->gdir[1],
                 a[2] + share * u->gdir[2]};
  double fscale = US_MAX(share + a[6], CERT_FLOOR), tscale = fscale * a[7];
  *fr = norm3(G) / fscale;
  double t = norm3(a + 3);
  *tr = t > 0 ? t / tscale : 0.0;
  if (!isfinite(*fr) || !isfinite(*tr)) *fr = *tr = INFINITY;
}

/* Cone and sign measures of one force (normalized); F gets the normalized
 * force vector, *fn its norm. Returns 0, or -1 if a component is not
 * finite. */
static int one_force(const us_Structure *s, const Units *u, const us_Contact *k, const double *f,
                     int bilateral, double *F, double *fn, double *cone, double *sign) {
  int dim = s->dim;
  double fc[3] = {0.0, 0.0, 0.0};
  int zero = 1;
  for (int j = 0; j < dim; j++) {
    if (!isfinite(f[j])) return -1;
    fc[j] = f[j] * u->inv_w;
    zero &= fc[j] == 0.0;
  }
  if (zero) { /* an idle contact (most side joints of a wall): inside, no sign */
    F[0] = F[1] = F[2] = 0.0;
    *fn = *cone = *sign = 0.0;
    return 0;
  }
  for (int j = 0; j < 3; j++) F[j] = fc[0] * k->n[j];
  for (int t = 1; t < dim; t++)
    for (int j = 0; j < 3; j++) F[j] += fc[t] * k->t[t - 1][j];
  *fn = fast_norm3(F);
  double dist = us_cone_distance(fc[0], dim == 2 ? fabs(fc[1]) : hypot(fc[1], fc[2]), k->mu);
  if (bilateral || (dist == 0.0 && fc[0] >= 0.0)) { /* a joint (docs/classify.md), or inside */
    *cone = *sign = 0.0;
    return 0;
  }
  double scale = *fn + contact_floor(s, u, k);
  *cone = dist / scale;
  *sign = US_MAX(-fc[0], 0.0) / scale;
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
static int add_forces(const us_Structure *s, const Units *u, const us_Bitset *present,
                      const us_Forces *f, int bilateral, double *acc, unsigned char *seen,
                      us_CertCheck *r) {
  double worst = 0.0; /* -1 unless something is violated */
  for (int i = 0; i < f->ncontact; i++) {
    int c = f->contact[i];
    if (!usable(s, present, c) || seen[c]) {
      r->worst_contact = c;
      return -1;
    }
    seen[c] = 1;
    const us_Contact *k = &s->contacts[c];
    double F[3], fn, cone, sign;
    if (one_force(s, u, k, f->f + (size_t)i * (size_t)s->dim, bilateral, F, &fn, &cone, &sign)) {
      r->worst_contact = c;
      return -1;
    }
    push(s, u, acc, k->b, k->p, F, fn, 1.0);
    push(s, u, acc, k->a, k->p, F, fn, -1.0);
    r->max_cone_violation = US_MAX(r->max_cone_violation, cone);
    r->max_sign_violation = US_MAX(r->max_sign_violation, sign);
    if (cone + sign > worst) {
      worst = cone + sign;
      r->worst_contact = c;
    }
  }
  return 0;
}

/* Pass 2: gravity and the residual of every present movable body. */
static void residuals(const us_Structure *s, const Units *u, const us_Bitset *present,
                      const double *acc, us_CertCheck *r) {
  double worst = -1.0;
  for (int i = us_bitset_next(present, -1); i >= 0; i = us_bitset_next(present, i)) {
    if (s->bodies[i].fixed) continue;
    double fr, tr;
    body_residuals(s, u, i, acc + US_CERT_ACC * (size_t)i, &fr, &tr);
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
  return us_certificate_check_mode(s, present, f, tol, 0, acc, seen, out);
}

int us_certificate_check_mode(const us_Structure *s, const us_Bitset *present,
                              const us_Forces *f, double tol, int bilateral, double *acc,
                              unsigned char *seen, us_CertCheck *out) {
  us_CertCheck r;
  memset(&r, 0, sizeof r);
  r.worst_body = r.worst_contact = -1;
  if (present->nbits != s->nbody || f->ncontact < 0 || (f->ncontact > 0 && (!f->contact || !f->f))) {
    *out = failed_check();
    return -1;
  }
  /* scratch cleared where this check reads it: O(sub-assembly), not O(structure) */
  for (int i = us_bitset_next(present, -1); i >= 0; i = us_bitset_next(present, i))
    memset(acc + US_CERT_ACC * (size_t)i, 0, US_CERT_ACC * sizeof(double));
  for (int i = 0; i < f->ncontact; i++)
    if (f->contact[i] >= 0 && f->contact[i] < s->ncontact) seen[f->contact[i]] = 0;
  Units u = units_of(s);
  if (add_forces(s, &u, present, f, bilateral, acc, seen, &r)) {
    int c = r.worst_contact;
    *out = failed_check();
    out->worst_contact = c;
    return -1;
  }
  residuals(s, &u, present, acc, &r);
  r.ok = r.max_force_residual <= tol && r.max_torque_residual <= tol &&
         r.max_cone_violation <= tol && r.max_sign_violation <= tol;
  *out = r;
  return 0;
}

/* One listed body of the local check: its residual with every active
 * contact touching it, and the cones of those contacts, into r. */
static void check_one_body(const us_Structure *s, const Units *u, const us_Bitset *present, int i,
                           const int *inc_start, const int *inc, const double *fc,
                           us_CertCheck *r) {
  double acc[US_CERT_ACC] = {0, 0, 0, 0, 0, 0, 0, 0};
  for (int m = inc_start[i]; m < inc_start[i + 1]; m++) {
    int c = inc[m];
    if (!usable(s, present, c)) continue;
    const us_Contact *k = &s->contacts[c];
    double F[3], fn, cone, sign;
    if (one_force(s, u, k, fc + (size_t)c * (size_t)s->dim, 0, F, &fn, &cone, &sign)) {
      cone = sign = INFINITY;
      F[0] = F[1] = F[2] = fn = 0.0;
    }
    push_at(s, u, acc, i, k->p, F, fn, i == k->b ? 1.0 : -1.0);
    if (cone + sign > r->max_cone_violation + r->max_sign_violation) r->worst_contact = c;
    r->max_cone_violation = US_MAX(r->max_cone_violation, cone);
    r->max_sign_violation = US_MAX(r->max_sign_violation, sign);
  }
  double fr, tr;
  body_residuals(s, u, i, acc, &fr, &tr);
  if (fr + tr > r->max_force_residual + r->max_torque_residual) r->worst_body = i;
  r->max_force_residual = US_MAX(r->max_force_residual, fr);
  r->max_torque_residual = US_MAX(r->max_torque_residual, tr);
}

void us_certificate_check_bodies(const us_Structure *s, const us_Bitset *present,
                                 const int *bodies, int nb, const int *inc_start, const int *inc,
                                 const double *fc, double mass, double tol, us_CertCheck *out) {
  us_CertCheck r;
  memset(&r, 0, sizeof r);
  r.worst_body = r.worst_contact = -1;
  Units u = units_of_mass(s, mass);
  u.inv_w = 1.0; /* fc is normalized already */
  for (int q = 0; q < nb; q++)
    if (side_moves(s, bodies[q]) && us_bitset_get(present, bodies[q]))
      check_one_body(s, &u, present, bodies[q], inc_start, inc, fc, &r);
  r.ok = r.max_force_residual <= tol && r.max_torque_residual <= tol &&
         r.max_cone_violation <= tol && r.max_sign_violation <= tol;
  *out = r;
}

void us_certificate_check_list(const us_Structure *s, const us_Bitset *present,
                               const int *bodies, int nb, const int *inc_start, const int *inc,
                               const double *fc, double mass, double tol, int *slot,
                               double *acc, us_CertCheck *out) {
  us_CertCheck r;
  memset(&r, 0, sizeof r);
  r.worst_body = r.worst_contact = -1;
  Units u = units_of_mass(s, mass);
  u.inv_w = 1.0; /* fc is normalized already */
  int n = 0;
  for (int q = 0; q < nb; q++) {
    int b = bodies[q];
    if (!side_moves(s, b) || !us_bitset_get(present, b) || slot[b] >= 0) continue;
    slot[b] = n;
    memset(acc + US_CERT_ACC * (size_t)n++, 0, US_CERT_ACC * sizeof(double));
  }
  /* each active contact once: from the side with the smaller slot when
     both sides are listed, its force pushed on both */
  for (int q = 0; q < nb; q++) {
    int b = bodies[q], sb = slot[b];
    if (sb < 0) continue;
    for (int m = inc_start[b]; m < inc_start[b + 1]; m++) {
      int c = inc[m];
      const us_Contact *k = &s->contacts[c];
      int o = k->a == b ? k->b : k->a, so = o >= 0 ? slot[o] : -1;
      if ((so >= 0 && so < sb) || !usable(s, present, c)) continue;
      double F[3], fn, cone, sign;
      if (one_force(s, &u, k, fc + (size_t)c * (size_t)s->dim, 0, F, &fn, &cone, &sign)) {
        cone = sign = INFINITY;
        F[0] = F[1] = F[2] = fn = 0.0;
      }
      push_at(s, &u, acc + US_CERT_ACC * (size_t)sb, b, k->p, F, fn, b == k->b ? 1.0 : -1.0);
      if (so >= 0) push_at(s, &u, acc + US_CERT_ACC * (size_t)so, o, k->p, F, fn, o == k->b ? 1.0 : -1.0);
      if (cone + sign > r.max_cone_violation + r.max_sign_violation) r.worst_contact = c;
      r.max_cone_violation = US_MAX(r.max_cone_violation, cone);
      r.max_sign_violation = US_MAX(r.max_sign_violation, sign);
    }
  }
  for (int q = 0; q < nb; q++) {
    int b = bodies[q], sb = slot[b];
    if (sb < 0) continue;
    double fr, tr;
    body_residuals(s, &u, b, acc + US_CERT_ACC * (size_t)sb, &fr, &tr);
    if (fr + tr > r.max_force_residual + r.max_torque_residual) r.worst_body = b;
    r.max_force_residual = US_MAX(r.max_force_residual, fr);
    r.max_torque_residual = US_MAX(r.max_torque_residual, tr);
    slot[b] = -1;
  }
  r.ok = r.max_force_residual <= tol && r.max_torque_residual <= tol &&
         r.max_cone_violation <= tol && r.max_sign_violation <= tol;
  *out = r;
}

us_CertCheck us_certificate_check(const us_Structure *s, const us_Bitset *present,
                                  const us_Forces *f, double tol) {
  us_CertCheck r;
  double *acc = us_calloc((size_t)(s->nbody > 0 ? s->nbody : 1) * US_CERT_ACC, sizeof(double));
  unsigned char *seen = us_calloc((size_t)(s->ncontact > 0 ? s->ncontact : 1), 1);
  if (!acc || !seen)
    r = failed_check(); /* no memory: nothing is certified */
  else
    us_certificate_check_buf(s, present, f, tol, acc, seen, &r);
  us_free(acc);
  us_free(seen);
  return r;
}

/* ------------------------------------------------------------ mechanisms */

void us_mechanism_free(us_Mechanism *m) {
  if (!m) return;
  us_free(m->body);
  us_free(m->v);
  memset(m, 0, sizeof *m);
}

/* Velocities per mechanism body: 3 in 2D (vx, vy, omega), 6 in 3D (v, omega). */
static int mech_stride(const us_Structure *s) { return s->dim == 3 ? 6 : 3; }

/* Velocity of body slot q of m at point p: v + omega x r, the lever arm r
 * divided by L (2D: omega about z). */
static void point_velocity(const us_Structure *s, const Units *u, const us_Mechanism *m, int q,
                           const double *p, double *out) {
  int dof = mech_stride(s);
  const double *v = m->v + (size_t)dof * (size_t)q, *c = s->bodies[m->body[q]].com;
  double r[3] = {(p[0] - c[0]) * u->inv_l, (p[1] - c[1]) * u->inv_l, 0.0};
  if (dof == 3) {
    out[0] = v[0] - v[2] * r[1];
    out[1] = v[1] + v[2] * r[0];
    out[2] = 0.0;
    return;
  }
  r[2] = (p[2] - c[2]) * u->inv_l;
  const double *w = v + 3;
  out[0] = v[0] + w[1] * r[2] - w[2] * r[1];
  out[1] = v[1] + w[2] * r[0] - w[0] * r[2];
  out[2] = v[2] + w[0] * r[1] - w[1] * r[0];
}

/* The least power of the unit generators of contact k's cone for relative
 * velocity vr (of b against a): the normal part minus mu times the
 * tangential part's length, over the generator's length (the circular
 * cone in 3D, exactly; mu = INFINITY the half-space). */
static double least_power(const us_Contact *k, const double *vr, int bilateral) {
  if (bilateral) return -norm3(vr); /* a joint: the unit force against vr */
  double pn = k->n[0] * vr[0] + k->n[1] * vr[1] + k->n[2] * vr[2];
  double t[3] = {vr[0] - pn * k->n[0], vr[1] - pn * k->n[1], vr[2] - pn * k->n[2]};
  double pt = norm3(t);
  if (k->mu == 0.0) return pn;
  if (isinf(k->mu)) return US_MIN(pn, -pt);
  double h = hypot(1.0, k->mu);
  return (pn - k->mu * pt) / h;
}

/* slot[i]: body i's index in m, or -1. Returns the worst power over the
 * contacts in list (NULL: all), only those active in present and touching
 * a moving body. */
static double worst_contact_power(const us_Structure *s, const Units *u, const us_Bitset *present,
                                  const us_Mechanism *m, const int *slot, const int *list,
                                  int nlist, int bilateral) {
  double worst = 0.0;
  int n = list ? nlist : s->ncontact;
  for (int j = 0; j < n; j++) {
    int c = list ? list[j] : j;
    const us_Contact *k = &s->contacts[c];
    int qa = k->a >= 0 ? slot[k->a] : -1, qb = k->b >= 0 ? slot[k->b] : -1;
    if ((qa < 0 && qb < 0) || !usable(s, present, c)) continue;
    double va[3] = {0, 0, 0}, vb[3] = {0, 0, 0};
    if (qa >= 0) point_velocity(s, u, m, qa, k->p, va);
    if (qb >= 0) point_velocity(s, u, m, qb, k->p, vb);
    double vr[3] = {vb[0] - va[0], vb[1] - va[1], vb[2] - va[2]};
    double p = least_power(k, vr, bilateral);
    if (!isfinite(p)) return -INFINITY;
    worst = US_MIN(worst, p);
  }
  return worst;
}

/* Normalize m so that gravity's power is 1; 0, or -1 if it is not > 0. */
static int normalize_mechanism(const us_Structure *s, const Units *u, const us_Bitset *present,
                               us_Mechanism *m) {
  int dof = mech_stride(s);
  double pg = 0.0;
  for (int q = 0; q < m->nbody; q++) {
    int i = m->body[q];
    if (i < 0 || i >= s->nbody || s->bodies[i].fixed || !us_bitset_get(present, i)) return -1;
    const double *v = m->v + (size_t)dof * (size_t)q;
    double up = u->gdir[0] * v[0] + u->gdir[1] * v[1] + (dof == 6 ? u->gdir[2] * v[2] : 0.0);
    pg += s->bodies[i].mass / u->m * up;
  }
  if (!(pg > 0) || !isfinite(pg)) return -1;
  for (int q = 0; q < dof * m->nbody; q++) m->v[q] /= pg;
  return 0;
}

static int mechanism_check_slots(const us_Structure *s, const us_Bitset *present, us_Mechanism *m,
                                 double tol, int *slot, const int *list, int nlist,
                                 int bilateral) {
  Units u = units_of(s);
  m->ok = 0;
  m->worst_power = INFINITY;
  if (m->nbody <= 0 || normalize_mechanism(s, &u, present, m)) return 0;
  for (int q = 0; q < m->nbody; q++) slot[m->body[q]] = q;
  m->worst_power = worst_contact_power(s, &u, present, m, slot, list, nlist, bilateral);
  for (int q = 0; q < m->nbody; q++) slot[m->body[q]] = -1;
  m->ok = m->worst_power >= -tol;
  return m->ok;
}

int us_mechanism_check_list(const us_Structure *s, const us_Bitset *present, us_Mechanism *m,
                            double tol, int *slot, const int *list, int nlist) {
  return mechanism_check_slots(s, present, m, tol, slot, list, nlist, 0);
}

int us_mechanism_check(const us_Structure *s, const us_Bitset *present, us_Mechanism *m,
                       double tol) {
  return us_mechanism_check_mode(s, present, m, tol, 0);
}

int us_mechanism_check_mode(const us_Structure *s, const us_Bitset *present, us_Mechanism *m,
                            double tol, int bilateral) {
  if (!s || !present || !m) return 0;
  m->ok = 0;
  m->worst_power = INFINITY;
  if (present->nbits != s->nbody || m->nbody < 0 || (m->nbody > 0 && (!m->body || !m->v)))
    return 0;
  for (int q = 0; q < m->nbody; q++)
    if (m->body[q] < 0 || m->body[q] >= s->nbody) return 0;
  int *slot = us_malloc((size_t)(s->nbody > 0 ? s->nbody : 1) * sizeof(int));
  if (!slot) return 0;
  for (int i = 0; i < s->nbody; i++) slot[i] = -1;
  int ok = mechanism_check_slots(s, present, m, tol, slot, NULL, 0, bilateral);
  us_free(slot);
  return ok;
}

/* The farthest vertex of body i from its centre of mass, over L. */
static double body_reach(const us_Structure *s, const Units *u, int i) {
  const us_Body *b = &s->bodies[i];
  double r = 0.0;
  for (int k = 0; k < b->nvert; k++) {
    double d[3] = {b->verts[2 * k] - b->com[0], b->verts[2 * k + 1] - b->com[1], 0.0};
    r = US_MAX(r, fast_norm3(d));
  }
  for (int p = 0; p < b->npart; p++)
    for (int k = 0; k < b->parts[p].nvert; k++) {
      const double *x = b->parts[p].verts + 3 * (size_t)k;
      double d[3] = {x[0] - b->com[0], x[1] - b->com[1], x[2] - b->com[2]};
      r = US_MAX(r, fast_norm3(d));
    }
  return r * u->inv_l;
}

double us_mechanism_margin(const us_Structure *s, const us_Mechanism *m) {
  Units u = units_of(s);
  int dof = mech_stride(s), nw = dof == 6 ? 3 : 1;
  double scale = 0.0;
  for (int q = 0; q < m->nbody; q++) {
    int i = m->body[q];
    const double *v = m->v + (size_t)dof * (size_t)q;
    double lin[3] = {v[0], v[1], dof == 6 ? v[2] : 0.0};
    double w[3] = {0.0, 0.0, v[dof - 1]};
    if (nw == 3) w[0] = v[3], w[1] = v[4];
    scale += s->bodies[i].mass / u.m * (fast_norm3(lin) + fast_norm3(w) * body_reach(s, &u, i));
  }
  return scale > 0 && isfinite(scale) ? 1.0 / scale : 0.0;
}

int us_forces_reserve(us_Forces *f, int n) {
  if (n <= f->cap) return 0;
  int cap = US_MAX(n, 8);
  int *c = us_realloc(f->contact, (size_t)cap * sizeof(int));
  if (!c) return -1;
  f->contact = c;
  double *v = us_realloc(f->f, (size_t)cap * 3 * sizeof(double));
  if (!v) return -1;
  f->f = v;
  f->cap = cap;
  return 0;
}
