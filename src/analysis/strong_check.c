/* The independent check of a strong-stability witness: a motion from rest
 * that the contact dynamics with static Coulomb friction allow, re-checked
 * from the structure's bodies and contacts alone (no solver, no model).
 *
 * Units are physical: accelerations in m/s^2 and rad/s^2, forces in
 * newtons. Each measure is relative to its own pair or body: a body's
 * force residual to its weight plus the magnitudes of the forces on it
 * (its torque residual times its own reach: the farthest of its contact
 * points from its centre, at least its radius of gyration), a contact's force measures to the force plus
 * the lighter side's weight, accelerations to |g|. Adding a body far away
 * changes none of them. Sign conventions are the structure's: the normal
 * points from a into b, the force on b is f_n n + f_t t with t = t[0] (3D:
 * f_t1 t[0] + f_t2 t[1], the cone circular), and
 * a = acc_b(p) - acc_a(p) with acc(p) = a + alpha x (p - com) at rest. */
#include "strong.h"

#include "model/massprops.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct Ctx {
  const us_Structure *s;
  const us_StrongResult *w;
  int *slot;        /* [nbody] witness row of a body, -1 at rest */
  double *res;      /* [nbody * 6] Newton-Euler residual (force, torque) */
  double *scale;    /* [nbody] force magnitude scale */
  double *reach;    /* [nbody] */
  double g, tol;
  char *why;
  size_t why_size;
} Ctx;

static int fail(Ctx *x, const char *msg, const char *name) {
  if (x->why) snprintf(x->why, x->why_size, "%s%s%s", msg, name ? " " : "", name ? name : "");
  return 0;
}

/* The witness's linear and angular acceleration of body i (zero at rest);
 * 2D: (ax, ay, 0) and (0, 0, alpha). */
static void body_acc(const Ctx *x, int i, double lin[3], double ang[3]) {
  lin[0] = lin[1] = lin[2] = ang[0] = ang[1] = ang[2] = 0;
  if (i < 0 || x->slot[i] < 0) return;
  int nw = x->s->dim == 3 ? 6 : 3;
  const double *a = x->w->accel + nw * x->slot[i];
  if (nw == 3) {
    lin[0] = a[0], lin[1] = a[1], ang[2] = a[2];
    return;
  }
  for (int k = 0; k < 3; k++) lin[k] = a[k], ang[k] = a[3 + k];
}

static void cross(const double *a, const double *b, double *out) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Acceleration of the material point p of body i at rest, a + alpha x r
 * (0 for the ground, fixed bodies and bodies at rest). */
static void point_acc(const Ctx *x, int i, const double *p, double out[3]) {
  double lin[3], ang[3], r[3] = {0, 0, 0}, t[3];
  body_acc(x, i, lin, ang);
  if (i >= 0)
    for (int k = 0; k < x->s->dim; k++) r[k] = p[k] - x->s->bodies[i].com[k];
  cross(ang, r, t);
  for (int k = 0; k < 3; k++) out[k] = lin[k] + t[k];
}

/* The witness's force at contact c in the contact frame (f_n, f_t...; 0
 * when it lists none). */
static int witness_force(const Ctx *x, int c, double f[3]) {
  int dim = x->s->dim;
  f[0] = f[1] = f[2] = 0;
  for (int k = 0; k < x->w->ncontact; k++)
    if (x->w->contact[k] == c) {
      for (int q = 0; q < dim; q++) f[q] = x->w->force[dim * k + q];
      return 1;
    }
  return 0;
}

/* Add the push F at p on body i (sign +1) to its residual. */
static void push(Ctx *x, int i, const double *p, const double F[3], double sign) {
  if (i < 0 || x->slot[i] < 0) return;
  const double *c = x->s->bodies[i].com;
  double r[3] = {0, 0, 0}, t[3];
  for (int k = 0; k < x->s->dim; k++) r[k] = p[k] - c[k];
  cross(r, F, t);
  double *res = x->res + 6 * i;
  for (int k = 0; k < 3; k++) res[k] += sign * F[k], res[3 + k] += sign * t[k];
  x->scale[i] += sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
  x->reach[i] = fmax(x->reach[i], sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]));
}

static double dot(const double *a, const double *b, int n) {
  double v = 0;
  for (int k = 0; k < n; k++) v += a[k] * b[k];
  return v;
}

/* The conditions at contact c with the circular Coulomb cone (2D: the
 * interval): cone, complementarity, sliding friction mu f_n against the
 * slip. */
static int check_contact(Ctx *x, int c) {
  const us_Contact *k = &x->s->contacts[c];
  int dim = x->s->dim;
  double f[3], pa[3], pb[3], d[3];
  witness_force(x, c, f);
  point_acc(x, k->a, k->p, pa);
  point_acc(x, k->b, k->p, pb);
  for (int q = 0; q < 3; q++) d[q] = pb[q] - pa[q];
  double an = dot(d, k->n, dim), at[2] = {dot(d, k->t[0], dim), dim == 3 ? dot(d, k->t[1], dim) : 0};
  double ft = hypot(f[1], f[2]), slip = hypot(at[0], at[1]);
  double wa = k->a >= 0 && !x->s->bodies[k->a].fixed ? x->s->bodies[k->a].mass : INFINITY;
  double wb = k->b >= 0 && !x->s->bodies[k->b].fixed ? x->s->bodies[k->b].mass : INFINITY;
  double fs = x->tol * (fabs(f[0]) + ft + fmin(wa, wb) * x->g), as = x->tol * x->g;
  const char *name = x->s->bodies[k->b >= 0 ? k->b : k->a].id;
  if (f[0] < -fs) return fail(x, "negative normal force at a contact of", name);
  if (an < -as) return fail(x, "interpenetration at a contact of", name);
  if (ft > k->mu * f[0] + fs) return fail(x, "friction outside the cone at", name);
  if (f[0] > fs && fabs(an) > as) return fail(x, "normal acceleration at a closed contact of", name);
  /* slipping: f_t = -mu f_n (slip direction) */
  double mf = k->mu * fmax(f[0], 0) / (slip > 0 ? slip : 1);
  if (slip > as && hypot(f[1] + mf * at[0], f[2] + mf * at[1]) > fs)
    return fail(x, "friction not against the slip at", name);
  double F[3];
  for (int q = 0; q < 3; q++) {
    double t1 = dim == 3 ? k->t[1][q] : 0;
    F[q] = q < dim ? f[0] * k->n[q] + f[1] * k->t[0][q] + f[2] * t1 : 0;
  }
  push(x, k->b, k->p, F, 1.0);
  push(x, k->a, k->p, F, -1.0);
  return 1;
}

/* I alpha of body b (2D: the polar moment about z; 3D: the tensor). */
static void inertia_times(const us_Body *b, int dim, const double ang[3], double out[3]) {
  for (int r = 0; r < 3; r++)
    out[r] = dim == 2 ? (r == 2 ? b->inertia * ang[2] : 0)
                      : dot(b->inertia3[r], ang, 3);
}

/* Newton-Euler on every moving body; the gravity power into *power. */
static int check_bodies(Ctx *x, double *power) {
  const us_Structure *s = x->s;
  double wsum = 0;
  *power = 0;
  for (int i = 0; i < s->nbody; i++) {
    if (x->slot[i] < 0) continue;
    const us_Body *b = &s->bodies[i];
    double lin[3], ang[3], ia[3];
    body_acc(x, i, lin, ang);
    inertia_times(b, s->dim, ang, ia);
    const double *r = x->res + 6 * i;
    double g3[3] = {s->gravity[0], s->gravity[1], s->dim == 3 ? s->gravity[2] : 0};
    double fs = x->tol * (b->mass * (x->g + sqrt(dot(lin, lin, 3))) + x->scale[i]);
    for (int q = 0; q < 3; q++)
      if (fabs(b->mass * (lin[q] - g3[q]) - r[q]) > fs)
        return fail(x, "forces do not give the acceleration of", b->id);
    /* lever: its farthest contact point, at least its radius of gyration */
    double ts = fs * fmax(x->reach[i], sqrt(b->inertia / b->mass)) + x->tol * sqrt(dot(ia, ia, 3));
    for (int q = 0; q < 3; q++)
      if (fabs(ia[q] - r[3 + q]) > ts)
        return fail(x, "torques do not give the angular acceleration of", b->id);
    *power += b->mass * dot(g3, lin, 3);
    wsum += b->mass;
  }
  *power /= wsum * x->g * x->g;
  return 1;
}

/* Every listed body present and movable, every listed contact active. */
static int check_lists(Ctx *x, const us_Bitset *present) {
  const us_Structure *s = x->s;
  for (int i = 0; i < s->nbody; i++) x->slot[i] = -1;
  for (int k = 0; k < x->w->nbody; k++) {
    int i = x->w->body[k];
    if (i < 0 || i >= s->nbody || s->bodies[i].fixed || !us_bitset_get(present, i))
      return fail(x, "the witness moves a body that is not movable or present", NULL);
    int nw = s->dim == 3 ? 6 : 3;
    for (int q = 0; q < nw; q++)
      if (!isfinite(x->w->accel[nw * k + q]))
        return fail(x, "non-finite acceleration of", s->bodies[i].id);
    x->slot[i] = k;
  }
  for (int k = 0; k < x->w->ncontact; k++) {
    int c = x->w->contact[k];
    if (c < 0 || c >= s->ncontact || !us_contact_active(s, present, c))
      return fail(x, "the witness lists a contact that is not active", NULL);
    for (int q = 0; q < s->dim; q++)
      if (!isfinite(x->w->force[s->dim * k + q]))
        return fail(x, "non-finite force at a contact of the witness", NULL);
  }
  return 1;
}

static int run(Ctx *x, const us_Bitset *present) {
  if (!check_lists(x, present)) return 0;
  for (int c = 0; c < x->s->ncontact; c++)
    if (us_contact_active(x->s, present, c) && !check_contact(x, c)) return 0;
  double power;
  if (!check_bodies(x, &power)) return 0;
  if (!(power > x->tol)) return fail(x, "the witness does not move (gravity power at most tol)", NULL);
  return 1;
}

int us_strong_check(const us_Structure *s, const us_Bitset *present, const us_StrongResult *w,
                    double tol, char *why, size_t why_size) {
  Ctx x = {.s = s, .w = w, .g = us_gravity_norm(s->gravity), .tol = tol > 0 ? tol : 1e-6,
           .why = why, .why_size = why_size};
  if (why && why_size) why[0] = 0;
  if (!w || !w->has_witness || (w->dim && w->dim != s->dim))
    return fail(&x, "no witness of the structure's dimension to check", NULL);
  us_Bitset all = {0};
  size_t nb = (size_t)(s->nbody > 0 ? s->nbody : 1);
  x.slot = us_malloc(nb * sizeof(int));
  x.res = us_calloc(6 * nb, sizeof(double));
  x.scale = us_calloc(nb, sizeof(double));
  x.reach = us_calloc(nb, sizeof(double));
  int ok = x.slot && x.res && x.scale && x.reach;
  if (ok && !present) {
    ok = us_bitset_init(&all, s->nbody) == 0;
    for (int i = 0; ok && i < s->nbody; i++)
      if (!s->bodies[i].fixed) us_bitset_set(&all, i);
  }
  ok = ok ? run(&x, present ? present : &all) : fail(&x, "out of memory checking a witness", NULL);
  us_bitset_free(&all);
  us_free(x.slot);
  us_free(x.res);
  us_free(x.scale);
  us_free(x.reach);
  return ok;
}
