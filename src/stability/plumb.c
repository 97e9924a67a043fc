/* The plumb-line load path (plumb.h; argument in docs/local.md).
 *
 * Algorithm, per added body a with weight share w = m_a / M and plumb
 * position c = com_a . h (h the horizontal axis):
 *   u = a; repeat: find a hop below u at c, add w to it, u = the body
 *   below, until the body below is the ground or a fixed body.
 * A hop is a support contact of u (one that pushes u up, with a present
 * body, the ground or a fixed body on the other side) that the line
 * crosses: a contact point at c (within 1e-9 of u's width), or two
 * contact points with the same body and normal on either side of c,
 * sharing the vertical force w up by the lever rule (weights (s2 - c) /
 * (s2 - s1) and (c - s1) / (s2 - s1)), whose resultant then acts on the
 * line. The force w up on u is, as contact components (force on the
 * contact's b side, normal n from a into b): +-(w up . n, w up . t); the
 * hop is admissible only if those lie in each point's cone (normal part
 * positive, |tangential| <= mu normal). The body below receives the
 * opposite force at the same points: the same vertical force on the same
 * line, which it passes on at the next hop.
 *
 * Invariants: every change to f is logged (contact, old components)
 * before it is made, so a failed route, or us_plumb_undo, restores f
 * exactly; p->path lists each body whose contacts changed once (mark[]).
 * A line descends strictly (each hop's contact has an upward normal
 * part), and a route stops after nbody hops per line regardless.
 */
#include "plumb.h"

#include <math.h>
#include <string.h>

#define SUPPORT_COS 1e-3 /* a contact supports if its push has this much "up" */
#define AT_POINT 1e-9    /* a point this close to the line (x u's width) is on it */
#define SAME_NORMAL 1e-9 /* normals closer than this (1 - cos) are one contact face */
#define CONE_SLACK 1e-12 /* relative slack of the hop's own cone test */
#define PLUMB_HOPS 4096  /* hops one added body's lines may take */

typedef struct Hop {
  int k[2];      /* contact indices (k[1] = -1: one point) */
  double w[2];   /* their shares of the load */
  int below[2];  /* the bodies under them (US_GROUND, fixed or present movable) */
  int split;     /* 0: one line goes on in below[0] at pos[0]; 1: two */
  double pos[2]; /* where the lines go on */
} Hop;

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static int held(const us_Plumb *p, int v) { return v < 0 || p->s->bodies[v].fixed; }

static int present(const us_Plumb *p, const us_Bitset *cur, int v) {
  return held(p, v) || us_bitset_get(cur, v);
}

static int other_side(const us_Contact *k, int u) { return k->a == u ? k->b : k->a; }

/* Does contact k push body u up? */
static int supports(const us_Plumb *p, const us_Contact *k, int u) {
  double d = dot3(k->n, p->up);
  return (u == k->b ? d : -d) > SUPPORT_COS;
}

/* The contact components of a vertical force `load` (along up) on body u
 * through contact k: d[0] normal, d[1] tangential (2D). */
static void components(const us_Plumb *p, const us_Contact *k, int u, double load, double d[2]) {
  double sg = u == k->b ? load : -load;
  d[0] = sg * dot3(p->up, k->n);
  d[1] = sg * dot3(p->up, k->t[0]);
}

static int in_cone(const us_Plumb *p, const us_Contact *k, int u) {
  double d[2];
  components(p, k, u, 1.0, d);
  if (!(d[0] > 0.0)) return 0;
  return isinf(k->mu) || fabs(d[1]) <= (k->mu + CONE_SLACK) * d[0];
}

static double width_of(const us_Plumb *p, int u) {
  const us_Body *b = &p->s->bodies[u];
  double lo = INFINITY, hi = -INFINITY;
  for (int k = 0; k < b->nvert; k++) {
    double x = b->verts[2 * k] * p->hz[0] + b->verts[2 * k + 1] * p->hz[1];
    lo = US_MIN(lo, x), hi = US_MAX(hi, x);
  }
  return hi > lo ? hi - lo : 0.0;
}

/* Each body's support points whose cone holds a vertical load, with the
 * body below and the horizontal position (they depend on the geometry
 * only; presence is asked per hop). */
static void list_supports(us_Plumb *p) {
  const us_Structure *s = p->s;
  int n = 0;
  for (int u = 0; u < s->nbody; u++) {
    p->sup_start[u] = n;
    p->width[u] = width_of(p, u);
    for (int m = p->inc_start[u]; m < p->inc_start[u + 1]; m++) {
      const us_Contact *k = &s->contacts[p->inc[m]];
      if (!supports(p, k, u) || !in_cone(p, k, u)) continue;
      p->sup[n++] = (us_PlumbSupport){p->inc[m], other_side(k, u), dot3(k->p, p->hz)};
    }
  }
  p->sup_start[s->nbody] = n;
}

int us_plumb_init(us_Plumb *p, const us_Structure *s, const int *inc_start, const int *inc,
                  const double up[3], double mass_total) {
  memset(p, 0, sizeof *p);
  p->s = s;
  p->inc_start = inc_start;
  p->inc = inc;
  memcpy(p->up, up, sizeof p->up);
  p->hz[0] = up[1], p->hz[1] = -up[0], p->hz[2] = 0.0;
  p->mass_total = mass_total;
  size_t nb = (size_t)(s->nbody > 0 ? s->nbody : 1);
  p->mark = us_calloc(nb, 1);
  p->width = us_malloc(nb * sizeof(double));
  p->sup_start = us_calloc(nb + 1, sizeof(int));
  p->sup = us_malloc((size_t)(2 * s->ncontact + 1) * sizeof(us_PlumbSupport));
  if (!p->mark || !p->width || !p->sup_start || !p->sup) return -1;
  if (s->dim == 2) list_supports(p);
  return 0;
}

void us_plumb_free(us_Plumb *p) {
  us_free(p->log_c);
  us_free(p->log_f);
  us_free(p->path);
  us_free(p->mark);
  us_free(p->stack);
  us_free(p->width);
  us_free(p->sup_start);
  us_free(p->sup);
  memset(p, 0, sizeof *p);
}

/* A hop below u at position c; 1 found, 0 none. A support point on the
 * line takes the whole load; else the nearest support points on either
 * side share it by the lever rule. */
static int find_hop(const us_Plumb *p, const us_Bitset *cur, int u, double c, Hop *h) {
  int best[2] = {-1, -1};
  double tol = AT_POINT * p->width[u];
  for (int m = p->sup_start[u]; m < p->sup_start[u + 1]; m++) {
    const us_PlumbSupport *q = &p->sup[m];
    if (!present(p, cur, q->below)) continue;
    if (fabs(q->pos - c) <= tol) {
      h->k[0] = q->contact, h->k[1] = -1;
      h->w[0] = 1.0, h->w[1] = 0.0;
      h->below[0] = h->below[1] = q->below;
      h->pos[0] = c;
      h->split = 0;
      return 1;
    }
    int side = q->pos > c;
    if (best[side] < 0 || (side ? q->pos < p->sup[best[1]].pos : q->pos > p->sup[best[0]].pos))
      best[side] = m;
  }
  if (best[0] < 0 || best[1] < 0) return 0;
  for (int q = 0; q < 2; q++) {
    h->k[q] = p->sup[best[q]].contact;
    h->below[q] = p->sup[best[q]].below;
    h->pos[q] = p->sup[best[q]].pos;
  }
  h->w[1] = (c - h->pos[0]) / (h->pos[1] - h->pos[0]);
  h->w[0] = 1.0 - h->w[1];
  h->split = h->below[0] != h->below[1];
  if (!h->split) h->pos[0] = c; /* one body takes both: their resultant is on the line */
  return 1;
}

static void mark_body(us_Plumb *p, int v) {
  if (held(p, v) || p->mark[v]) return;
  p->mark[v] = 1;
  p->path[p->npath++] = v;
}

/* Add share w of load on u to contact kc, logging its old value. */
static int add_force(us_Plumb *p, int kc, int u, double load, double *f) {
  const us_Contact *k = &p->s->contacts[kc];
  if (US_GROW(p->log_c, p->cap_c, p->nlog + 1) || US_GROW(p->log_f, p->cap_f, 2 * (p->nlog + 1)))
    return -1;
  double *fk = f + 2 * (size_t)kc, d[2];
  p->log_c[p->nlog] = kc;
  memcpy(p->log_f + 2 * (size_t)p->nlog, fk, 2 * sizeof(double));
  p->nlog++;
  components(p, k, u, load, d);
  fk[0] += d[0];
  fk[1] += d[1];
  return 0;
}

void us_plumb_undo(us_Plumb *p, double *f) {
  for (int q = p->nlog - 1; q >= 0; q--)
    memcpy(f + 2 * (size_t)p->log_c[q], p->log_f + 2 * (size_t)q, 2 * sizeof(double));
  p->nlog = 0;
}

/* Push a line (body, position, load) to route on. */
static int push_line(us_Plumb *p, int u, double c, double load) {
  if (US_GROW(p->stack, p->cap_stack, p->nstack + 1)) return -1;
  p->stack[p->nstack++] = (us_PlumbLine){u, c, load};
  return 0;
}

/* One added body's weight, down its line and the lines it splits into:
 * 1 routed, 0 no route (some line found no hop, or the hop budget ran
 * out), -1 OOM. */
static int route_one(us_Plumb *p, const us_Bitset *cur, int a, double *f) {
  const us_Body *b = &p->s->bodies[a];
  mark_body(p, a);
  p->nstack = 0;
  if (push_line(p, a, dot3(b->com, p->hz), b->mass / p->mass_total)) return -1;
  for (int hops = 0; p->nstack > 0; hops++) {
    if (hops >= PLUMB_HOPS) return 0;
    us_PlumbLine l = p->stack[--p->nstack];
    Hop h;
    if (!find_hop(p, cur, l.body, l.pos, &h)) return 0;
    for (int q = 0; q < 2 && (q == 0 || h.k[1] >= 0); q++)
      if (add_force(p, h.k[q], l.body, h.w[q] * l.load, f)) return -1;
    for (int q = 0; q <= h.split; q++) {
      int v = h.below[q];
      if (held(p, v)) continue;
      mark_body(p, v);
      if (push_line(p, v, h.pos[q], h.split ? h.w[q] * l.load : l.load)) return -1;
    }
  }
  return 1;
}

int us_plumb_route(us_Plumb *p, const us_Bitset *cur, const int *added, int nadd, double *f) {
  for (int q = 0; q < p->npath; q++) p->mark[p->path[q]] = 0;
  p->npath = 0;
  p->nlog = 0;
  if (p->s->dim != 2) return 0;
  if (US_GROW(p->path, p->cap_path, p->s->nbody + 1)) return -1;
  for (int q = 0; q < nadd; q++) {
    int r = route_one(p, cur, added[q], f);
    if (r <= 0) {
      us_plumb_undo(p, f);
      return r;
    }
  }
  return 1;
}
