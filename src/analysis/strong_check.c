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
 * points from a into b, the force on b is f_n n + f_t t with t = t[0], and
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
  double *res;      /* [nbody * 3] Newton-Euler residual */
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

/* Acceleration of the material point p of body i (0 for the ground,
 * fixed bodies and bodies at rest). */
static void point_acc(const Ctx *x, int i, const double *p, double out[2]) {
  out[0] = out[1] = 0;
  if (i < 0 || x->slot[i] < 0) return;
  const double *a = x->w->accel + 3 * x->slot[i], *c = x->s->bodies[i].com;
  out[0] = a[0] - a[2] * (p[1] - c[1]);
  out[1] = a[1] + a[2] * (p[0] - c[0]);
}

/* The witness's force at contact c (0 when it lists none), its mode. */
static int witness_force(const Ctx *x, int c, double f[2]) {
  f[0] = f[1] = 0;
  for (int k = 0; k < x->w->ncontact; k++)
    if (x->w->contact[k] == c) {
      f[0] = x->w->force[2 * k], f[1] = x->w->force[2 * k + 1];
      return 1;
    }
  return 0;
}

/* Add the push F at p on body i (sign +1) to its residual. */
static void push(Ctx *x, int i, const double *p, const double F[2], double sign) {
  if (i < 0 || x->slot[i] < 0) return;
  const double *c = x->s->bodies[i].com;
  double *r = x->res + 3 * i, rx = p[0] - c[0], ry = p[1] - c[1];
  r[0] += sign * F[0], r[1] += sign * F[1];
  r[2] += sign * (rx * F[1] - ry * F[0]);
  x->scale[i] += hypot(F[0], F[1]);
  x->reach[i] = fmax(x->reach[i], hypot(rx, ry));
}

/* The conditions at contact c: cone, complementarity, sliding friction. */
static int check_contact(Ctx *x, int c) {
  const us_Contact *k = &x->s->contacts[c];
  double f[2], pa[2], pb[2];
  witness_force(x, c, f);
  point_acc(x, k->a, k->p, pa);
  point_acc(x, k->b, k->p, pb);
  double d[2] = {pb[0] - pa[0], pb[1] - pa[1]};
  double an = d[0] * k->n[0] + d[1] * k->n[1], at = d[0] * k->t[0][0] + d[1] * k->t[0][1];
  double wa = k->a >= 0 && !x->s->bodies[k->a].fixed ? x->s->bodies[k->a].mass : INFINITY;
  double wb = k->b >= 0 && !x->s->bodies[k->b].fixed ? x->s->bodies[k->b].mass : INFINITY;
  double fs = x->tol * (fabs(f[0]) + fabs(f[1]) + fmin(wa, wb) * x->g), as = x->tol * x->g;
  const char *name = x->s->bodies[k->b >= 0 ? k->b : k->a].id;
  if (f[0] < -fs) return fail(x, "negative normal force at a contact of", name);
  if (an < -as) return fail(x, "interpenetration at a contact of", name);
  if (fabs(f[1]) > k->mu * f[0] + fs) return fail(x, "friction outside the cone at", name);
  if (f[0] > fs && fabs(an) > as) return fail(x, "normal acceleration at a closed contact of", name);
  if (at > as && f[1] > -k->mu * f[0] + fs) return fail(x, "friction not against the slip at", name);
  if (at < -as && f[1] < k->mu * f[0] - fs) return fail(x, "friction not against the slip at", name);
  double F[2] = {f[0] * k->n[0] + f[1] * k->t[0][0], f[0] * k->n[1] + f[1] * k->t[0][1]};
  push(x, k->b, k->p, F, 1.0);
  push(x, k->a, k->p, F, -1.0);
  return 1;
}

/* Newton-Euler on every moving body; the gravity power into *power. */
static int check_bodies(Ctx *x, double *power) {
  const us_Structure *s = x->s;
  double wsum = 0;
  *power = 0;
  for (int i = 0; i < s->nbody; i++) {
    if (x->slot[i] < 0) continue;
    const us_Body *b = &s->bodies[i];
    const double *a = x->w->accel + 3 * x->slot[i], *r = x->res + 3 * i;
    double fs = x->tol * (b->mass * (x->g + hypot(a[0], a[1])) + x->scale[i]);
    if (fabs(b->mass * (a[0] - s->gravity[0]) - r[0]) > fs ||
        fabs(b->mass * (a[1] - s->gravity[1]) - r[1]) > fs)
      return fail(x, "forces do not give the acceleration of", b->id);
    /* lever: its farthest contact point, at least its radius of gyration */
    double ts = fs * fmax(x->reach[i], sqrt(b->inertia / b->mass)) + x->tol * fabs(b->inertia * a[2]);
    if (fabs(b->inertia * a[2] - r[2]) > ts)
      return fail(x, "torques do not give the angular acceleration of", b->id);
    *power += b->mass * (s->gravity[0] * a[0] + s->gravity[1] * a[1]);
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
    if (!isfinite(x->w->accel[3 * k]) || !isfinite(x->w->accel[3 * k + 1]) ||
        !isfinite(x->w->accel[3 * k + 2]))
      return fail(x, "non-finite acceleration of", s->bodies[i].id);
    x->slot[i] = k;
  }
  for (int k = 0; k < x->w->ncontact; k++) {
    int c = x->w->contact[k];
    if (c < 0 || c >= s->ncontact || !us_contact_active(s, present, c) ||
        !isfinite(x->w->force[2 * k]) || !isfinite(x->w->force[2 * k + 1]))
      return fail(x, "the witness lists a contact that is not active", NULL);
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
  if (!w || !w->has_witness || s->dim != 2) return fail(&x, "no 2D witness to check", NULL);
  us_Bitset all = {0};
  size_t nb = (size_t)(s->nbody > 0 ? s->nbody : 1);
  x.slot = us_malloc(nb * sizeof(int));
  x.res = us_calloc(3 * nb, sizeof(double));
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
