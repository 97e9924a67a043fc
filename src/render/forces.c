/* Which force a picture draws at a contact, and the per-interface
 * resultants: the one convention of every picture (SVG, PNG, the HTML
 * viewer; docs/render.md "Forces").
 *
 * Convention: at every contact the arrow is the force that the lower body
 * (or the ground) exerts on the upper body, drawn from the contact point.
 * The stability code's contact normal n points from body a into body b
 * (a is the ground for ground contacts), and its force components give
 * the force on b, F = f_n n + f_t1 t1 (+ f_t2 t2), a receiving -F
 * (src/stability/equilibrium.h). "Upper" is the side n enters when n
 * points upwards, up = -gravity: b when n . up > 0, a when n . up < 0; on
 * a joint parallel to gravity (|n . up| <= 1e-9) it is the side n enters
 * when n points along the first horizontal axis (x; in 3D then y) of the
 * structure. So the normal part always points into the upper body (it
 * pushes it up, or sideways on a vertical joint), and the friction part
 * lies in the joint.
 *
 * Resultants: the contacts between one pair of bodies (ground included)
 * summed into one arrow, normal and friction parts apart, at the centre of
 * pressure sum |f_n| p / sum |f_n| (the contact points' mean when every
 * f_n is 0). In 2D the contacts of a pair lie on one joint line with one
 * normal, so the resultant acts exactly there (friction along the line
 * has no moment about it); in 3D a twist about the normal may be left
 * over, which one arrow cannot show. */
#include "render/render.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define VERTICAL_TOL 1e-9

/* up = -gravity, unit (no gravity: +y in 2D, +z in 3D). */
static void up_of(const us_Structure *s, double up[3]) {
  double g = sqrt(s->gravity[0] * s->gravity[0] + s->gravity[1] * s->gravity[1] +
                  s->gravity[2] * s->gravity[2]);
  for (int d = 0; d < 3; d++) up[d] = g > 0 ? -s->gravity[d] / g : 0.0;
  if (!(g > 0)) up[s->dim == 3 ? 2 : 1] = 1.0;
}

/* 1 when the upper body of a contact with normal n is its b side. */
static int b_is_upper(const double n[3], const double up[3]) {
  double d = n[0] * up[0] + n[1] * up[1] + n[2] * up[2];
  if (fabs(d) > VERTICAL_TOL) return d > 0;
  if (fabs(n[0]) > VERTICAL_TOL) return n[0] > 0;
  return n[1] > 0;
}

void us_drawn_force(const us_Structure *s, const us_Forces *f, int k, us_DrawnForce *out) {
  const us_Contact *c = &s->contacts[f->contact[k]];
  const double *fk = f->f + (size_t)s->dim * (size_t)k;
  double up[3];
  up_of(s, up);
  int on_b = b_is_upper(c->n, up);
  double sign = on_b ? 1.0 : -1.0;
  out->upper = on_b ? c->b : c->a;
  out->lower = on_b ? c->a : c->b;
  out->fn = fk[0];
  for (int d = 0; d < 3; d++) {
    out->p[d] = c->p[d];
    out->normal[d] = sign * fk[0] * c->n[d];
    out->friction[d] = sign * (fk[1] * c->t[0][d] + (s->dim == 3 ? fk[2] * c->t[1][d] : 0.0));
  }
}

/* Contacts sorted by their pair (lower, upper), then by index. */
typedef struct PairKey {
  int lower, upper, k;
} PairKey;

static int pair_cmp_bodies(const PairKey *a, const PairKey *b) {
  if (a->lower != b->lower) return a->lower < b->lower ? -1 : 1;
  return (a->upper > b->upper) - (a->upper < b->upper);
}
static int pair_cmp(const void *x, const void *y) {
  const PairKey *a = x, *b = y;
  int c = pair_cmp_bodies(a, b);
  return c ? c : (a->k > b->k) - (a->k < b->k);
}

/* The resultant of the contacts key[from .. to) of one pair. */
static void pair_resultant(const us_Structure *s, const us_Forces *f, const PairKey *key,
                           int from, int to, us_DrawnForce *out) {
  double wsum = 0.0, mean[3] = {0, 0, 0}, cp[3] = {0, 0, 0};
  memset(out, 0, sizeof *out);
  for (int q = from; q < to; q++) {
    us_DrawnForce d;
    us_drawn_force(s, f, key[q].k, &d);
    double w = fabs(d.fn);
    wsum += w;
    out->fn += d.fn;
    for (int i = 0; i < 3; i++) {
      out->normal[i] += d.normal[i], out->friction[i] += d.friction[i];
      mean[i] += d.p[i] / (to - from), cp[i] += w * d.p[i];
    }
    out->upper = d.upper, out->lower = d.lower;
  }
  for (int i = 0; i < 3; i++) out->p[i] = wsum > 0 && isfinite(wsum) ? cp[i] / wsum : mean[i];
}

int us_drawn_resultants(const us_Structure *s, const us_Forces *f, us_DrawnForce *out) {
  if (!f || f->ncontact <= 0) return 0;
  PairKey *key = us_malloc((size_t)f->ncontact * sizeof *key);
  if (!key) return -1;
  for (int k = 0; k < f->ncontact; k++) {
    us_DrawnForce d;
    us_drawn_force(s, f, k, &d);
    key[k] = (PairKey){d.lower, d.upper, k};
  }
  qsort(key, (size_t)f->ncontact, sizeof *key, pair_cmp);
  int n = 0;
  for (int a = 0, b; a < f->ncontact; a = b) {
    for (b = a + 1; b < f->ncontact && !pair_cmp_bodies(&key[a], &key[b]);) b++;
    pair_resultant(s, f, key, a, b, &out[n++]);
  }
  us_free(key);
  return n;
}
