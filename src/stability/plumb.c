/* The plumb-line load path (plumb.h; argument in docs/local.md).
 *
 * Algorithm, per added body a with weight share w = m_a / M and plumb
 * position c = the horizontal coordinates of com_a (one axis h in 2D, two
 * in 3D):
 *   u = a; repeat: find a hop below u at c, add w to it, u = the body
 *   below, until the body below is the ground or a fixed body.
 * A hop is a set of support contact points of u (each pushes u up, with a
 * present body, the ground or a fixed body on the other side) whose
 * shares of the vertical force w have their resultant on the line:
 *   2D: a point at c (within 1e-9 of u's width), or the nearest points on
 *       either side of c, weights (s2 - c) / (s2 - s1) and (c - s1) /
 *       (s2 - s1) (the lever rule);
 *   3D: a point at c, or the corners of a triangle of support points that
 *       holds c, weights its barycentric coordinates (all >= 0, within the
 *       same relative tolerance); triangles whose corners lie on one body
 *       below are tried first, so that the line stays one line.
 * The force w up on u is, as contact components (force on the contact's b
 * side, normal n from a into b): +-(w up . n, w up . t1 [, w up . t2]);
 * the hop is admissible only if those lie in each point's cone (normal
 * part positive, |tangential| <= mu normal). The bodies below receive the
 * opposite forces at the same points; the points on one body give it a
 * vertical force on the line through their weighted mean, on which its
 * own line goes on (at c itself when one body takes the whole hop).
 *
 * Invariants: every change to f is logged (contact, old components)
 * before it is made, so a failed route, or us_plumb_undo, restores f
 * exactly; p->path lists each body whose contacts changed once (mark[]).
 * A line descends strictly (each hop's contact has an upward normal
 * part), and a route stops after PLUMB_HOPS hops per added body
 * regardless.
 */
#include "plumb.h"

#include "certificate.h"
#include "geometry/geometry3.h"

#include <math.h>
#include <string.h>

#define SUPPORT_COS 1e-3 /* a contact supports if its push has this much "up" */
#define AT_POINT 1e-9    /* a point this close to the line (x u's width) is on it */
#define SAME_NORMAL 1e-9 /* normals closer than this (1 - cos) are one contact face */
#define CONE_SLACK 1e-12 /* relative slack of the hop's own cone test */
#define PLUMB_HOPS 4096  /* hops one added body's lines may take */
#define LEVER_HOPS 128   /* bodies a lever's signed route may visit (merged
                            per body: route_signed). Instructions of `unstack
                            plan`, 64 / 128 / 256: 1,076 blocks 852 / 678 /
                            678 M, seed 15 468 / 474 / 474 M, 632 blocks
                            238 / 241 / 241 M. Before the merging (lines split
                            at every hop and never met) 64 hops were best and
                            most routes failed on the budget */
#define PLUMB_RETRIES 2  /* a lazy route starts over at most this often:
                            with levers and their path LPs behind it, a
                            failed route is cheaper to give up (8 -> 2:
                            seed 15 231 -> 192 M instructions, 9,352 blocks
                            2,768 -> 2,406 M; 1: 9,352 blocks 3,173 M) */
#define PLUMB_MAX_TRI 48 /* 3D: support points of a body searched for triangles at most */

typedef struct Hop {
  int n;         /* points carrying the load: 1 to 3 */
  int k[3];      /* their contact indices */
  double w[3];   /* their shares of the load (sum 1) */
  int below[3];  /* the bodies under them (US_GROUND, fixed or present movable) */
  double pos[3][2]; /* their horizontal positions */
} Hop;

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static int held(const us_Plumb *p, int v) { return v < 0 || p->s->bodies[v].fixed; }

/* Is support point m of body u excluded from this route (a line through
 * it failed further down: line_entry)? */
static int excluded(const us_Plumb *p, int u, int m) {
  for (int i = 0; i < p->nexcl; i++)
    if (p->excl[i].body == u && p->excl[i].contact == p->sup[m].contact) return 1;
  return 0;
}

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
 * through contact k: d[0] normal, d[1] (and d[2] in 3D) tangential. */
static void components(const us_Plumb *p, const us_Contact *k, int u, double load, double d[3]) {
  double sg = u == k->b ? load : -load;
  d[0] = sg * dot3(p->up, k->n);
  d[1] = sg * dot3(p->up, k->t[0]);
  d[2] = p->s->dim == 3 ? sg * dot3(p->up, k->t[1]) : 0.0;
}

static int in_cone(const us_Plumb *p, const us_Contact *k, int u) {
  double d[3];
  components(p, k, u, 1.0, d);
  if (!(d[0] > 0.0)) return 0;
  return isinf(k->mu) || hypot(d[1], d[2]) <= (k->mu + CONE_SLACK) * d[0];
}

void us_plumb_horizontal(const us_Plumb *p, const double *x, double out[2]) {
  out[0] = dot3(x, p->hz[0]);
  out[1] = p->nax == 2 ? dot3(x, p->hz[1]) : 0.0;
}

/* The largest horizontal extent of body u (its vertices, all parts). */
static double width_of(const us_Plumb *p, int u) {
  const us_Body *b = &p->s->bodies[u];
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY}, h[2];
  for (int k = 0; k < b->nvert && p->s->dim == 2; k++) {
    double x[3] = {b->verts[2 * k], b->verts[2 * k + 1], 0.0};
    us_plumb_horizontal(p, x, h);
    for (int a = 0; a < p->nax; a++) lo[a] = US_MIN(lo[a], h[a]), hi[a] = US_MAX(hi[a], h[a]);
  }
  for (int q = 0; q < b->npart && p->s->dim == 3; q++)
    for (int k = 0; k < b->parts[q].nvert; k++) {
      us_plumb_horizontal(p, b->parts[q].verts + 3 * k, h);
      for (int a = 0; a < p->nax; a++) lo[a] = US_MIN(lo[a], h[a]), hi[a] = US_MAX(hi[a], h[a]);
    }
  double w = 0.0;
  for (int a = 0; a < p->nax; a++) w = hi[a] > lo[a] ? US_MAX(w, hi[a] - lo[a]) : w;
  return w;
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
      us_PlumbSupport q = {p->inc[m], other_side(k, u), {0.0, 0.0}};
      us_plumb_horizontal(p, k->p, q.pos);
      p->sup[n++] = q;
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
  memset(p->hz, 0, sizeof p->hz);
  if (s->dim == 3) {
    us_Vec3 t1, t2;
    us_v3_frame((us_Vec3){up[0], up[1], up[2]}, &t1, &t2);
    p->nax = 2;
    p->hz[0][0] = t1.x, p->hz[0][1] = t1.y, p->hz[0][2] = t1.z;
    p->hz[1][0] = t2.x, p->hz[1][1] = t2.y, p->hz[1][2] = t2.z;
  } else {
    p->nax = 1;
    p->hz[0][0] = up[1], p->hz[0][1] = -up[0];
  }
  p->mass_total = mass_total;
  size_t nb = (size_t)(s->nbody > 0 ? s->nbody : 1);
  p->mark = us_calloc(nb, 1);
  p->width = us_malloc(nb * sizeof(double));
  p->sup_start = us_calloc(nb + 1, sizeof(int));
  p->sup = us_malloc((size_t)(2 * s->ncontact + 1) * sizeof(us_PlumbSupport));
  if (!p->mark || !p->width || !p->sup_start || !p->sup) return -1;
  list_supports(p);
  return 0;
}

void us_plumb_free(us_Plumb *p) {
  us_free(p->frames);
  us_free(p->ent);
  us_free(p->tab);
  us_bitset_free(&p->dep);
  us_free(p->heap);
  us_free(p->excl);
  us_free(p->added_e);
  us_free(p->added_l);
  us_free(p->log_c);
  us_free(p->log_f);
  us_free(p->path);
  us_free(p->mark);
  us_free(p->stack);
  us_free(p->sgF);
  us_free(p->sgM);
  us_free(p->sg_in);
  us_free(p->sg_heap);
  us_free(p->sg_skip);
  us_free(p->width);
  us_free(p->sup_start);
  us_free(p->sup);
  memset(p, 0, sizeof *p);
}

static void hop_point(const us_Plumb *p, Hop *h, int j, int m, double w) {
  const us_PlumbSupport *q = &p->sup[m];
  h->k[j] = q->contact;
  h->below[j] = q->below;
  h->w[j] = w;
  h->pos[j][0] = q->pos[0], h->pos[j][1] = q->pos[1];
}

/* A support point of u on the line at c (within tol): its index, or -1. */
static int point_on_line(const us_Plumb *p, const us_Bitset *cur, int u, const double c[2],
                         double tol) {
  for (int m = p->sup_start[u]; m < p->sup_start[u + 1]; m++) {
    const us_PlumbSupport *q = &p->sup[m];
    if (present(p, cur, q->below) && !excluded(p, u, m) && fabs(q->pos[0] - c[0]) <= tol &&
        fabs(q->pos[1] - c[1]) <= tol)
      return m;
  }
  return -1;
}

/* 2D: the nearest support points on either side of c share the load by
 * the lever rule. 1 found, 0 none. */
static int hop_lever(const us_Plumb *p, const us_Bitset *cur, int u, const double c[2], Hop *h) {
  int best[2] = {-1, -1};
  for (int m = p->sup_start[u]; m < p->sup_start[u + 1]; m++) {
    const us_PlumbSupport *q = &p->sup[m];
    if (!present(p, cur, q->below) || excluded(p, u, m)) continue;
    int side = q->pos[0] > c[0];
    if (best[side] < 0 ||
        (side ? q->pos[0] < p->sup[best[1]].pos[0] : q->pos[0] > p->sup[best[0]].pos[0]))
      best[side] = m;
  }
  if (best[0] < 0 || best[1] < 0) return 0;
  double s1 = p->sup[best[0]].pos[0], s2 = p->sup[best[1]].pos[0], w1 = (c[0] - s1) / (s2 - s1);
  h->n = 2;
  hop_point(p, h, 0, best[0], 1.0 - w1);
  hop_point(p, h, 1, best[1], w1);
  return 1;
}

/* Barycentric weights of c in triangle (a, b, d) of horizontal points:
 * 1 if all are >= -tol (then clamped to [0, 1], summing to 1), else 0;
 * 0 for a triangle thinner than tol. */
static int barycentric(const double *a, const double *b, const double *d, const double c[2],
                       double tol, double w[3]) {
  double e1x = b[0] - a[0], e1y = b[1] - a[1], e2x = d[0] - a[0], e2y = d[1] - a[1];
  double det = e1x * e2y - e1y * e2x, span = hypot(e1x, e1y) + hypot(e2x, e2y);
  if (!(fabs(det) > tol * span)) return 0;
  double rx = c[0] - a[0], ry = c[1] - a[1];
  w[1] = (rx * e2y - ry * e2x) / det;
  w[2] = (e1x * ry - e1y * rx) / det;
  w[0] = 1.0 - w[1] - w[2];
  double t = tol / span;
  if (w[0] < -t || w[1] < -t || w[2] < -t) return 0;
  double sum = 0.0;
  for (int j = 0; j < 3; j++) sum += (w[j] = US_MAX(w[j], 0.0));
  for (int j = 0; j < 3; j++) w[j] /= sum;
  return 1;
}

/* 3D: a triangle of u's support points that holds c, its corners on one
 * body below when same_body (else anywhere). 1 found, 0 none. */
static int hop_triangle(const us_Plumb *p, const us_Bitset *cur, int u, const double c[2],
                        double tol, int same_body, Hop *h) {
  int m0 = p->sup_start[u], m1 = p->sup_start[u + 1];
  for (int i = m0; i < m1; i++) {
    const us_PlumbSupport *qi = &p->sup[i];
    if (!present(p, cur, qi->below) || excluded(p, u, i)) continue;
    for (int j = i + 1; j < m1; j++) {
      const us_PlumbSupport *qj = &p->sup[j];
      if ((same_body && qj->below != qi->below) || !present(p, cur, qj->below) ||
          excluded(p, u, j))
        continue;
      for (int k = j + 1; k < m1; k++) {
        const us_PlumbSupport *qk = &p->sup[k];
        if ((same_body && qk->below != qi->below) || !present(p, cur, qk->below) ||
            excluded(p, u, k))
          continue;
        double w[3];
        if (!barycentric(qi->pos, qj->pos, qk->pos, c, tol, w)) continue;
        h->n = 3;
        hop_point(p, h, 0, i, w[0]);
        hop_point(p, h, 1, j, w[1]);
        hop_point(p, h, 2, k, w[2]);
        return 1;
      }
    }
  }
  return 0;
}

/* A hop below u at position c; 1 found, 0 none. A support point on the
 * line takes the whole load; else the lever rule (2D) or a triangle (3D,
 * one body below first). */
static int find_hop(const us_Plumb *p, const us_Bitset *cur, int u, const double c[2], Hop *h) {
  double tol = AT_POINT * p->width[u];
  int m = point_on_line(p, cur, u, c, tol);
  if (m >= 0) {
    h->n = 1;
    hop_point(p, h, 0, m, 1.0);
    return 1;
  }
  if (p->nax == 1) return hop_lever(p, cur, u, c, h);
  if (p->sup_start[u + 1] - p->sup_start[u] > PLUMB_MAX_TRI) return 0;
  return hop_triangle(p, cur, u, c, tol, 1, h) || hop_triangle(p, cur, u, c, tol, 0, h);
}

static void mark_body(us_Plumb *p, int v) {
  if (held(p, v) || p->mark[v]) return;
  p->mark[v] = 1;
  p->path[p->npath++] = v;
}

/* Add share w of load on u to contact kc, logging its old value. */
static int add_force(us_Plumb *p, int kc, int u, double load, double *f) {
  const us_Contact *k = &p->s->contacts[kc];
  if (US_GROW(p->log_c, p->cap_c, p->nlog + 1) || US_GROW(p->log_f, p->cap_f, 3 * (p->nlog + 1)))
    return -1;
  size_t dim = (size_t)p->s->dim;
  double *fk = f + dim * (size_t)kc, d[3];
  p->log_c[p->nlog] = kc;
  memcpy(p->log_f + 3 * (size_t)p->nlog, fk, dim * sizeof(double));
  p->nlog++;
  components(p, k, u, load, d);
  for (size_t j = 0; j < dim; j++) fk[j] += d[j];
  return 0;
}

void us_plumb_undo(us_Plumb *p, double *f) {
  size_t dim = (size_t)p->s->dim;
  for (int q = p->nlog - 1; q >= 0; q--)
    memcpy(f + dim * (size_t)p->log_c[q], p->log_f + 3 * (size_t)q, dim * sizeof(double));
  p->nlog = 0;
}

/* Push a line (body, position, load) to route on. */
static int push_line(us_Plumb *p, int u, const double c[2], double load) {
  if (US_GROW(p->stack, p->cap_stack, p->nstack + 1)) return -1;
  p->stack[p->nstack++] = (us_PlumbLine){u, {c[0], c[1]}, load};
  return 0;
}

/* The lines hop h (of a line at c) goes on as: one per movable body
 * below, its share w[j] of the load at the share-weighted mean of its
 * points (c itself when one body takes the whole hop). Signed hops
 * (sgn 1) have shares of any sign, and a body whose shares cancel gets
 * no line. Returns their number (at most 3). */
static int hop_children(const us_Plumb *p, const Hop *h, const double c[2], int sgn,
                        int body[3], double w[3], double at[3][2]) {
  int n = 0;
  for (int q = 0; q < h->n; q++) {
    int v = h->below[q], first = 1;
    for (int r = 0; r < q; r++) first = first && h->below[r] != v;
    if (!first || held(p, v)) continue;
    double s = 0.0, x[2] = {0.0, 0.0};
    for (int r = q; r < h->n; r++) {
      if (h->below[r] != v) continue;
      s += h->w[r];
      x[0] += h->w[r] * h->pos[r][0], x[1] += h->w[r] * h->pos[r][1];
    }
    int whole = sgn ? fabs(s - 1.0) <= 1e-15 : s >= 1.0 - 1e-15;
    if (whole) x[0] = c[0], x[1] = c[1]; /* one body: on the line */
    else if (s != 0.0) x[0] /= s, x[1] /= s;
    else if (sgn) continue;
    body[n] = v, w[n] = s, at[n][0] = x[0], at[n][1] = x[1];
    n++;
  }
  return n;
}

static int take_hop(us_Plumb *p, const Hop *h, int u, const double c[2], double load, double *f) {
  for (int q = 0; q < h->n; q++)
    if (add_force(p, h->k[q], u, h->w[q] * load, f)) return -1;
  int body[3];
  double w[3], at[3][2];
  for (int j = 0, n = hop_children(p, h, c, 0, body, w, at); j < n; j++) {
    mark_body(p, body[j]);
    if (push_line(p, body[j], at[j], w[j] * load)) return -1;
  }
  return 0;
}

/* One added body's weight, down its line and the lines it splits into:
 * 1 routed, 0 no route (some line found no hop, or the hop budget ran
 * out), -1 OOM. */
static int route_one(us_Plumb *p, const us_Bitset *cur, int a, double *f) {
  const us_Body *b = &p->s->bodies[a];
  mark_body(p, a);
  p->nstack = 0;
  double c[2];
  us_plumb_horizontal(p, b->com, c);
  if (push_line(p, a, c, b->mass / p->mass_total)) return -1;
  for (int hops = 0; p->nstack > 0; hops++) {
    if (hops >= PLUMB_HOPS) return 0;
    us_PlumbLine l = p->stack[--p->nstack];
    Hop h;
    if (!find_hop(p, cur, l.body, l.pos, &h)) return 0;
    if (take_hop(p, &h, l.body, l.pos, l.load, f)) return -1;
  }
  return 1;
}

/* An eager route's start: no path, an empty log and stack. 0, -1 OOM. */
static int route_start(us_Plumb *p) {
  for (int q = 0; q < p->npath; q++) p->mark[p->path[q]] = 0;
  p->npath = 0;
  p->nlog = 0;
  p->nstack = 0;
  return US_GROW(p->path, p->cap_path, p->s->nbody + 1) ? -1 : 0;
}

int us_plumb_route(us_Plumb *p, const us_Bitset *cur, const int *added, int nadd, double *f) {
  if (route_start(p)) return -1;
  for (int q = 0; q < nadd; q++) {
    int r = route_one(p, cur, added[q], f);
    if (r <= 0) {
      us_plumb_undo(p, f);
      return r;
    }
  }
  return 1;
}

int us_plumb_route_hint(us_Plumb *p, const us_Bitset *cur, const int *added, int nadd,
                        double *f) {
  if (route_start(p)) return -1;
  for (int q = 0; q < nadd; q++) /* a line that finds no hop stops there */
    if (route_one(p, cur, added[q], f) < 0) return -1;
  return 0;
}

/* ------------------------------------------------------------ levers */

/* Support point m of u usable by a lever's lines: its body below present
 * and not the cantilever itself (skip). */
static int usable(const us_Plumb *p, const us_Bitset *cur, int m, int skip, int skip2) {
  int v = p->sup[m].below;
  return (skip < 0 || v != skip) && (skip2 < 0 || v != skip2) && present(p, cur, v);
}

/* Does support point m of u stay in its cone after a vertical load on u
 * through it (signed)? A release needs force where it takes it off,
 * friction included (us_cone_distance, the check's own measure). */
static int inside_after(const us_Plumb *p, int u, int m, double load, const double *f) {
  const us_Contact *k = &p->s->contacts[p->sup[m].contact];
  double d[3];
  components(p, k, u, load, d);
  const double *fc = f + (size_t)p->s->dim * (size_t)p->sup[m].contact;
  double n = fc[0] + d[0], t = p->s->dim == 2 ? fabs(fc[1] + d[1]) : hypot(fc[1] + d[1], fc[2] + d[2]);
  return us_cone_distance(n, t, k->mu) == 0.0;
}

/* The far point of an extended lever rule for a load on u at c beyond its
 * point `near`: the usable point on the other side of near, at least tol
 * away, whose normal force is largest after its share is taken off (or
 * put on); -1 if none. (Largest slack in the cone instead, friction
 * counted: seed 17 +18 % instructions, seed 11 +10 %.) */
static int release_point(const us_Plumb *p, const us_Bitset *cur, int skip, int skip2, int u,
                         double c, int near, double load, const double *f, double tol) {
  double sn = p->sup[near].pos[0], best_left = -INFINITY;
  int best = -1;
  size_t dim = (size_t)p->s->dim;
  for (int m = p->sup_start[u]; m < p->sup_start[u + 1]; m++) {
    double x = p->sup[m].pos[0];
    if (!usable(p, cur, m, skip, skip2) || !(fabs(x - sn) > tol) || (x - sn) * (c - sn) > 0) continue;
    double share = (c - sn) / (x - sn), d[3]; /* x's share of the load (< 0) */
    components(p, &p->s->contacts[p->sup[m].contact], u, share * load, d);
    double left = f[dim * (size_t)p->sup[m].contact] + d[0];
    if (left > best_left) best_left = left, best = m;
  }
  return best;
}

/* 2D hop of a signed load on u at c, not resting on skip: a point on the
 * line takes it all; else the nearest points on either side (lever rule);
 * else (c beyond u's points) the two outermost points, by the
 * same rule extended (one share negative: part of the load the far point
 * carries already is taken off it; the caller's check decides whether it
 * had that much). 1 found, 0 none. */
static int hop_signed(const us_Plumb *p, const us_Bitset *cur, int skip, int skip2, int u,
                      const double c[2],
                      double load, const double *f, Hop *h) {
  double tol = AT_POINT * p->width[u];
  int best[2] = {-1, -1}, lo = -1, hi = -1;
  for (int m = p->sup_start[u]; m < p->sup_start[u + 1]; m++) {
    if (!usable(p, cur, m, skip, skip2)) continue;
    double x = p->sup[m].pos[0];
    if (fabs(x - c[0]) <= tol) {
      h->n = 1;
      hop_point(p, h, 0, m, 1.0);
      return 1;
    }
    int side = x > c[0];
    if (best[side] < 0 || (side ? x < p->sup[best[1]].pos[0] : x > p->sup[best[0]].pos[0]))
      best[side] = m;
    if (lo < 0 || x < p->sup[lo].pos[0]) lo = m;
    if (hi < 0 || x > p->sup[hi].pos[0]) hi = m;
  }
  if (best[0] < 0 || best[1] < 0) { /* c outside the points: the rule extended */
    if (lo < 0 || !(p->sup[hi].pos[0] - p->sup[lo].pos[0] > tol)) return 0;
    int near = best[0] < 0 ? lo : hi, far = release_point(p, cur, skip, skip2, u, c[0], near, load, f, tol);
    if (far < 0) return 0;
    best[0] = p->sup[far].pos[0] < p->sup[near].pos[0] ? far : near;
    best[1] = best[0] == far ? near : far;
  }
  double s1 = p->sup[best[0]].pos[0], s2 = p->sup[best[1]].pos[0], w1 = (c[0] - s1) / (s2 - s1);
  h->n = 2;
  hop_point(p, h, 0, best[0], 1.0 - w1);
  hop_point(p, h, 1, best[1], w1);
  return 1;
}

/* Signed lines merge per body: the loads on body u sum to a vertical
 * force sgF[u] and a moment sgM[u] (sum of load x position), so a body is
 * routed once however many lines reach it (split lines never merging grew
 * past any budget in a stack's column, and a release and a push meeting
 * in the same column now cancel there). Bodies go in decreasing height
 * (a max-heap on the centre's height), so what rests on a body is routed
 * before it, mostly. */
static double height(const us_Plumb *p, int u) { return dot3(p->s->bodies[u].com, p->up); }

static void sg_sift_up(us_Plumb *p, int i) {
  int *h = p->sg_heap;
  while (i > 0) {
    int up = (i - 1) / 2;
    if (!(height(p, h[up]) < height(p, h[i]))) break;
    int t = h[up];
    h[up] = h[i], h[i] = t, i = up;
  }
}

static int sg_pop(us_Plumb *p) {
  int *h = p->sg_heap, top = h[0], n = --p->nsg, i = 0;
  h[0] = h[n];
  for (;;) {
    int l = 2 * i + 1, r = l + 1, m = i;
    if (l < n && height(p, h[l]) > height(p, h[m])) m = l;
    if (r < n && height(p, h[r]) > height(p, h[m])) m = r;
    if (m == i) break;
    int t = h[m];
    h[m] = h[i], h[i] = t, i = m;
  }
  return top;
}

static void sg_add(us_Plumb *p, int u, double load, double x) {
  if (!p->sg_in[u]) {
    p->sg_in[u] = 1;
    p->sg_skip[u] = -1;
    p->sgF[u] = p->sgM[u] = 0.0;
    p->sg_heap[p->nsg++] = u;
    sg_sift_up(p, p->nsg - 1);
  }
  p->sgF[u] += load;
  p->sgM[u] += load * x;
}

/* A (nearly) pure couple on u, force F and moment M: its outermost
 * usable points take f_hi = (M - F s_lo) / (s_hi - s_lo) and F - f_hi
 * (h->w: the loads themselves). 1 found, 0 none. */
static int hop_couple(const us_Plumb *p, const us_Bitset *cur, int skip, int skip2, int u, double F,
                      double M, Hop *h) {
  int lo = -1, hi = -1;
  for (int m = p->sup_start[u]; m < p->sup_start[u + 1]; m++) {
    if (!usable(p, cur, m, skip, skip2)) continue;
    if (lo < 0 || p->sup[m].pos[0] < p->sup[lo].pos[0]) lo = m;
    if (hi < 0 || p->sup[m].pos[0] > p->sup[hi].pos[0]) hi = m;
  }
  double span = lo < 0 ? 0.0 : p->sup[hi].pos[0] - p->sup[lo].pos[0];
  if (!(span > AT_POINT * p->width[u])) return 0;
  double fhi = (M - F * p->sup[lo].pos[0]) / span;
  h->n = 2;
  hop_point(p, h, 0, lo, F - fhi);
  hop_point(p, h, 1, hi, fhi);
  return 1;
}

static int lever_points(const us_Plumb *p, const us_Bitset *cur, int a, double c, int *ms,
                        int *mp);

/* Does d rest on something besides u (where a presser's release goes)?
 * A presser resting on its cantilever alone cannot press harder (its
 * release finds no hop): the extended rule then, whose check the path's
 * LP may repair (seed 15 299 -> 275 M instructions). */
static int rests_beside(const us_Plumb *p, const us_Bitset *cur, int d, int u) {
  for (int m = p->sup_start[d]; m < p->sup_start[d + 1]; m++)
    if (usable(p, cur, m, u, -1)) return 1;
  return 0;
}

/* Has u's own far support room for the release of the extended lever
 * rule (a load F at c beyond u's tipping point ms), friction included
 * (inside_after)? With the normal force alone: 632 blocks 217 M
 * instructions against 180 M. */
static int release_room(const us_Plumb *p, const us_Bitset *cur, int skip, int u, double c,
                        int ms, double F, const double *f) {
  double tol = AT_POINT * p->width[u];
  int far = release_point(p, cur, skip, -1, u, c, ms, F, f, tol);
  if (far < 0) return 0;
  double sn = p->sup[ms].pos[0];
  return inside_after(p, u, far, (c - sn) / (p->sup[far].pos[0] - sn) * F, f);
}

/* Route the stacked lines (signed loads) down, not resting on skip,
 * merged per body: 1 routed, 0 no hop or out of budget (LEVER_HOPS
 * bodies), -1 OOM. */
static int route_signed(us_Plumb *p, const us_Bitset *cur, int skip, double *f) {
  size_t nb = (size_t)(p->s->nbody > 0 ? p->s->nbody : 1);
  if (!p->sgF) {
    p->sgF = us_malloc(nb * sizeof(double));
    p->sgM = us_malloc(nb * sizeof(double));
    p->sg_in = us_calloc(nb, 1);
    p->sg_heap = us_malloc(nb * sizeof(int));
    p->sg_skip = us_malloc(nb * sizeof(int));
    if (!p->sgF || !p->sgM || !p->sg_in || !p->sg_heap || !p->sg_skip) return -1;
  }
  p->nsg = 0;
  while (p->nstack > 0) {
    us_PlumbLine l = p->stack[--p->nstack];
    sg_add(p, l.body, l.load, l.pos[0]);
  }
  int r = 1;
  for (int hops = 0; p->nsg > 0 && r > 0; hops++) {
    int u = sg_pop(p);
    p->sg_in[u] = 0;
    double F = p->sgF[u], M = p->sgM[u], scale = fabs(F) + fabs(M) / p->width[u];
    if (!(scale > 1e-300)) continue; /* the lines cancelled */
    if (hops >= LEVER_HOPS) {
      r = 0;
      break;
    }
    Hop h;
    double c[2] = {F != 0.0 ? M / F : 0.0, 0.0}, load = F;
    int found, ms, mp, skip2 = p->sg_skip[u];
    if (F > 1e-12 * scale && isfinite(c[0]) && skip2 < 0 &&
        lever_points(p, cur, u, c[0], &ms, &mp) &&
        other_side(&p->s->contacts[p->sup[mp].contact], u) != skip &&
        rests_beside(p, cur, other_side(&p->s->contacts[p->sup[mp].contact], u), u) &&
        !release_room(p, cur, skip, u, c[0], ms, F, f)) {
      /* u a cantilever under a load beyond its support s, a presser d
         across s (us_plumb_lever's rule): d pushes u down at q with
         Fp = F (c - s) / (s - q), s takes F + Fp, and d releases Fp at q
         from its other supports (its lines not resting on u) */
      const us_PlumbSupport *qs = &p->sup[ms], *qp = &p->sup[mp];
      double Fp = F * (c[0] - qs->pos[0]) / (qs->pos[0] - qp->pos[0]);
      int d = other_side(&p->s->contacts[qp->contact], u);
      mark_body(p, d);
      if (add_force(p, qp->contact, d, Fp, f) || add_force(p, qs->contact, u, F + Fp, f))
        return -1;
      if (!held(p, qs->below)) {
        mark_body(p, qs->below);
        sg_add(p, qs->below, F + Fp, qs->pos[0]);
      }
      sg_add(p, d, -Fp, qp->pos[0]);
      p->sg_skip[d] = u;
      continue;
    }
    if (F != 0.0 && isfinite(c[0]) && fabs(F) > 1e-12 * scale) {
      found = hop_signed(p, cur, skip, skip2, u, c, F, f, &h);
    } else { /* (nearly) a couple */
      found = hop_couple(p, cur, skip, skip2, u, F, M, &h);
      load = 1.0;
    }
    if (!found) {
      r = 0;
      break;
    }
    for (int q = 0; q < h.n; q++) {
      if (add_force(p, h.k[q], u, h.w[q] * load, f)) return -1;
      int v = h.below[q];
      if (held(p, v)) continue;
      mark_body(p, v);
      sg_add(p, v, h.w[q] * load, h.pos[q][0]);
    }
  }
  while (p->nsg > 0) p->sg_in[sg_pop(p)] = 0;
  return r;
}

/* Is c within the span of u's present support points? */
static int within(const us_Plumb *p, const us_Bitset *cur, int u, double c) {
  double tol = AT_POINT * p->width[u], lo = INFINITY, hi = -INFINITY;
  for (int m = p->sup_start[u]; m < p->sup_start[u + 1]; m++)
    if (present(p, cur, p->sup[m].below))
      lo = US_MIN(lo, p->sup[m].pos[0]), hi = US_MAX(hi, p->sup[m].pos[0]);
  return c >= lo - tol && c <= hi + tol;
}

/* The cantilever's tipping point s (its outermost present support toward
 * its centre c) and the presser point across it: a point of a present
 * movable body resting on a, on the other side of s, farthest from it.
 * 1 found (*ms, *mp: support entries, of a and of the presser), else 0. */
static int lever_points(const us_Plumb *p, const us_Bitset *cur, int a, double c, int *ms,
                        int *mp) {
  double tol = AT_POINT * p->width[a];
  int lo = -1, hi = -1;
  for (int m = p->sup_start[a]; m < p->sup_start[a + 1]; m++) {
    if (!present(p, cur, p->sup[m].below)) continue;
    if (lo < 0 || p->sup[m].pos[0] < p->sup[lo].pos[0]) lo = m;
    if (hi < 0 || p->sup[m].pos[0] > p->sup[hi].pos[0]) hi = m;
  }
  if (lo < 0) return 0;
  int right = c > p->sup[hi].pos[0] + tol;
  if (!right && !(c < p->sup[lo].pos[0] - tol)) return 0; /* not a cantilever */
  *ms = right ? hi : lo;
  double sx = p->sup[*ms].pos[0];
  *mp = -1;
  for (int j = p->inc_start[a]; j < p->inc_start[a + 1]; j++) {
    int v = other_side(&p->s->contacts[p->inc[j]], a);
    if (held(p, v) || !us_bitset_get(cur, v)) continue;
    for (int m = p->sup_start[v]; m < p->sup_start[v + 1]; m++) {
      const us_PlumbSupport *q = &p->sup[m];
      if (q->contact != p->inc[j] || q->below != a) continue;
      double arm = right ? sx - q->pos[0] : q->pos[0] - sx;
      if (arm > tol && (*mp < 0 || arm > fabs(sx - p->sup[*mp].pos[0]))) *mp = m;
    }
  }
  return *mp >= 0;
}

int us_plumb_lever(us_Plumb *p, const us_Bitset *cur, int a, double *f) {
  if (route_start(p)) return -1;
  if (p->nax != 1) return 0;
  double c[2], w = p->s->bodies[a].mass / p->mass_total;
  us_plumb_horizontal(p, p->s->bodies[a].com, c);
  int ms, mp;
  mark_body(p, a);
  if (!lever_points(p, cur, a, c[0], &ms, &mp)) { /* a's own line, extended levers below */
    if (!within(p, cur, a, c[0])) {
      p->tipped = 1;
      return 0; /* a beyond its supports with nothing on it: it tips */
    }
    int r = push_line(p, a, c, w) ? -1 : route_signed(p, cur, -1, f);
    if (r <= 0) us_plumb_undo(p, f);
    return r;
  }
  const us_PlumbSupport *qs = &p->sup[ms], *qp = &p->sup[mp];
  double load = w * (c[0] - qs->pos[0]) / (qs->pos[0] - qp->pos[0]); /* the presser's push */
  int d = other_side(&p->s->contacts[qp->contact], a);
  mark_body(p, d);
  /* a: up w + load at s, down load at the presser's point (its weight's
     torque about s balanced); the presser: up load there, and as much
     released from its other supports at the same point */
  int r = add_force(p, qp->contact, d, load, f) ? -1 : 1;
  if (r > 0 && (push_line(p, a, qs->pos, w + load) || push_line(p, d, qp->pos, -load))) r = -1;
  if (r > 0) r = route_signed(p, cur, a, f);
  if (r <= 0) us_plumb_undo(p, f);
  return r;
}

/* ------------------------------------------------------ lazy routing */

int us_plumb_lazy_valid(const us_Plumb *p, const us_Bitset *cur) {
  for (int k = 0; k < p->dep.nwords; k++)
    if (p->dep.w[k] & ~cur->w[k]) return 0;
  return 1;
}

static uint64_t line_hash(int u, const double c[2]) {
  uint64_t a, b;
  memcpy(&a, &c[0], sizeof a);
  memcpy(&b, &c[1], sizeof b);
  uint64_t h = (uint64_t)(unsigned)u * 0x9E3779B97F4A7C15ULL;
  h ^= a + 0x7F4A7C159E3779B9ULL + (h << 6) + (h >> 2);
  h ^= b + 0x94D049BB133111EBULL + (h << 6) + (h >> 2);
  return h ^ (h >> 31);
}

static int same_line(const us_PlumbEntry *e, int u, const double c[2]) {
  return e->body == u && memcmp(e->pos, c, 2 * sizeof(double)) == 0;
}

/* The entry of line (u, c), or -1. */
static int line_find(const us_Plumb *p, int u, const double c[2]) {
  if (!p->tab_cap) return -1;
  long i = (long)(line_hash(u, c) & (uint64_t)(p->tab_cap - 1));
  for (; p->tab[i]; i = (i + 1) & (p->tab_cap - 1))
    if (same_line(&p->ent[p->tab[i] - 1], u, c)) return (int)p->tab[i] - 1;
  return -1;
}

static void tab_put(us_Plumb *p, int e) {
  us_PlumbEntry *x = &p->ent[e];
  long i = (long)(line_hash(x->body, x->pos) & (uint64_t)(p->tab_cap - 1));
  while (p->tab[i]) i = (i + 1) & (p->tab_cap - 1);
  p->tab[i] = e + 1;
  x->slot = i;
}

/* Room for one more entry (the table at most half full). 0 or -1 OOM. */
static int line_room(us_Plumb *p) {
  if (US_GROW(p->ent, p->cap_ent, p->nent + 1)) return -1;
  if (2 * (long)(p->nent + 1) <= p->tab_cap) return 0;
  long ncap = p->tab_cap ? 2 * p->tab_cap : 1024;
  long *t = us_calloc((size_t)ncap, sizeof(long));
  if (!t) return -1;
  us_free(p->tab);
  p->tab = t;
  p->tab_cap = ncap;
  for (int e = 0; e < p->nent; e++) tab_put(p, e);
  return 0;
}

/* Re-check a line's hop without the routing's own tests, on the forces
 * the hop will add (as contact components, turned back into vectors):
 * both sides of every point present, each force in its point's cone,
 * weights >= 0, the forces on the body summing to the unit load up with
 * no torque about the line, and each child's share at its own line.
 * Returns the largest relative residual (rounding leaves ~1e-16). */
static double check_line(const us_Plumb *p, const us_Bitset *cur, const us_PlumbEntry *e) {
  double worst = 0.0, wd = p->width[e->body] > 0 ? p->width[e->body] : 1.0;
  double F[3] = {0.0, 0.0, 0.0}, T[3] = {0.0, 0.0, 0.0}, P[3];
  for (int j = 0; j < 3; j++) P[j] = e->pos[0] * p->hz[0][j] + e->pos[1] * p->hz[1][j];
  for (int q = 0; q < e->n; q++) {
    const us_Contact *k = &p->s->contacts[e->k[q]];
    double d[3];
    if (!present(p, cur, k->a) || !present(p, cur, k->b) || other_side(k, e->body) == e->body ||
        (k->a != e->body && k->b != e->body) || !(e->w[q] >= 0.0))
      return INFINITY;
    components(p, k, e->body, e->w[q], d);
    worst = US_MAX(worst, us_cone_distance(d[0], hypot(d[1], d[2]), k->mu));
    double sg = k->b == e->body ? 1.0 : -1.0, f[3], r[3];
    for (int j = 0; j < 3; j++) {
      f[j] = sg * (d[0] * k->n[j] + d[1] * k->t[0][j] + d[2] * k->t[1][j]);
      r[j] = (k->p[j] - P[j]) / wd;
      F[j] += f[j];
    }
    T[0] += r[1] * f[2] - r[2] * f[1];
    T[1] += r[2] * f[0] - r[0] * f[2];
    T[2] += r[0] * f[1] - r[1] * f[0];
  }
  for (int j = 0; j < 3; j++) F[j] -= p->up[j];
  worst = US_MAX(worst, hypot(hypot(F[0], F[1]), F[2]));
  worst = US_MAX(worst, hypot(hypot(T[0], T[1]), T[2]));
  for (int j = 0; j < e->nchild; j++) { /* the child's points, at its line */
    const us_PlumbEntry *c = &p->ent[e->child[j]];
    double cw = 0.0, ca[2] = {0.0, 0.0};
    for (int q = 0; q < e->n; q++) {
      const us_Contact *k = &p->s->contacts[e->k[q]];
      if (other_side(k, e->body) != c->body) continue;
      double x[2];
      us_plumb_horizontal(p, k->p, x);
      cw += e->w[q], ca[0] += e->w[q] * x[0], ca[1] += e->w[q] * x[1];
    }
    worst = US_MAX(worst, fabs(cw - e->cw[j]));
    worst = US_MAX(worst, hypot(ca[0] - cw * c->pos[0], ca[1] - cw * c->pos[1]) / wd);
  }
  return isfinite(worst) ? worst : INFINITY;
}

/* A line being built by line_entry: its entry so far, and its child
 * lines (one per movable body below) still to resolve. */
typedef struct us_PlumbFrame {
  us_PlumbEntry x;
  int below[3];          /* the hop's bodies below (for dep) */
  int nkid, next;        /* child lines, the next one to resolve */
  int kid[3];
  double kid_pos[3][2], kid_w[3];
} us_PlumbFrame;

/* Open a frame for line (u, c): its hop and child lines. 0 no hop. */
static int open_frame(const us_Plumb *p, const us_Bitset *cur, int u, const double c[2],
                      us_PlumbFrame *F) {
  Hop h;
  memset(&h, 0, sizeof h);
  memset(F, 0, sizeof *F);
  if (!find_hop(p, cur, u, c, &h)) return 0;
  F->x.body = u, F->x.pos[0] = c[0], F->x.pos[1] = c[1], F->x.n = h.n;
  for (int q = 0; q < h.n; q++) F->x.k[q] = h.k[q], F->x.w[q] = h.w[q], F->below[q] = h.below[q];
  int body[3];
  double w[3], at[3][2];
  for (int j = 0, n = hop_children(p, &h, c, 0, body, w, at); j < n; j++) {
    if (!(w[j] > 0)) continue; /* no load goes that way */
    F->kid[F->nkid] = body[j], F->kid_w[F->nkid] = w[j];
    F->kid_pos[F->nkid][0] = at[j][0], F->kid_pos[F->nkid][1] = at[j][1];
    F->nkid++;
  }
  return 1;
}

static void attach(const us_Plumb *p, us_PlumbFrame *F, int ce) {
  F->x.child[F->x.nchild] = ce, F->x.cw[F->x.nchild++] = F->kid_w[F->next++];
  F->x.level = US_MAX(F->x.level, p->ent[ce].level + 1);
}

/* Memoise a frame whose children are all resolved, after its check: the
 * entry, -2 the check failed, -1 OOM. */
static int close_frame(us_Plumb *p, const us_Bitset *cur, const us_PlumbFrame *F, double tol) {
  if (line_room(p)) return -1;
  int e = p->nent;
  p->ent[e] = F->x;
  double r = check_line(p, cur, &p->ent[e]);
  if (!(r <= tol)) return -2;
  p->nent++;
  tab_put(p, e);
  p->worst_line = US_MAX(p->worst_line, r);
  p->nnew++;
  us_bitset_set(&p->dep, F->x.body);
  for (int q = 0; q < F->x.n; q++)
    if (!held(p, F->below[q])) us_bitset_set(&p->dep, F->below[q]);
  return e;
}

/* A child line on v of frame F found no hop: F's points on v are
 * excluded from F's body for this route, which starts over (-3; the
 * lines checked so far stay memoised), or -2 when they were already
 * excluded or -1 on OOM. */
static int exclude(us_Plumb *p, const us_PlumbFrame *F, int v) {
  int n = 0;
  for (int q = 0; q < F->x.n; q++) {
    if (F->below[q] != v) continue;
    if (US_GROW(p->excl, p->cap_excl, p->nexcl + 1)) return -1;
    p->excl[p->nexcl++] = (us_PlumbExcl){F->x.body, F->x.k[q]};
    n++;
  }
  return n ? -3 : -2;
}

/* The entry of line (u, c): memoised, or routed now, its child lines
 * first (an explicit stack, at most PLUMB_HOPS deep), each checked.
 * Returns it, -2 no route (or a check failed), -1 OOM. */
static int line_entry(us_Plumb *p, const us_Bitset *cur, int u, const double c[2], double tol) {
  int e = line_find(p, u, c), nf = 0;
  if (e >= 0) return e;
  if (US_GROW(p->frames, p->cap_frames, 1)) return -1;
  if (!open_frame(p, cur, u, c, &p->frames[nf++])) return -2;
  while (nf > 0) {
    us_PlumbFrame *F = &p->frames[nf - 1];
    if (F->next < F->nkid) {
      int v = F->kid[F->next], ce = line_find(p, v, F->kid_pos[F->next]);
      if (ce >= 0) {
        attach(p, F, ce);
        continue;
      }
      if (nf >= PLUMB_HOPS) return -2;
      double at[2] = {F->kid_pos[F->next][0], F->kid_pos[F->next][1]};
      if (US_GROW(p->frames, p->cap_frames, nf + 1)) return -1;
      if (!open_frame(p, cur, v, at, &p->frames[nf++])) return exclude(p, &p->frames[nf - 2], v);
      continue;
    }
    e = close_frame(p, cur, F, tol);
    if (e < 0) return e;
    if (--nf > 0) attach(p, &p->frames[nf - 1], e);
  }
  return e;
}

/* line_entry, started over while a failed child line excludes more
 * support points (at most PLUMB_RETRIES times); the exclusions end with
 * the route. */
static int line_entry_retry(us_Plumb *p, const us_Bitset *cur, int u, const double c[2],
                            double tol) {
  int e = -3;
  for (int t = 0; t <= PLUMB_RETRIES && e == -3; t++) e = line_entry(p, cur, u, c, tol);
  p->nexcl = 0;
  return e == -3 ? -2 : e;
}

static int heap_above(const us_Plumb *p, int i, int j) {
  return p->ent[p->heap[i]].level > p->ent[p->heap[j]].level;
}

static void heap_swap(us_Plumb *p, int i, int j) {
  int t = p->heap[i];
  p->heap[i] = p->heap[j];
  p->heap[j] = t;
}

static int heap_push(us_Plumb *p, int e) {
  if (p->ent[e].in_heap) return 0;
  if (US_GROW(p->heap, p->cap_heap, p->nheap + 1)) return -1;
  p->ent[e].in_heap = 1;
  int i = p->nheap++;
  p->heap[i] = e;
  while (i > 0 && heap_above(p, i, (i - 1) / 2)) heap_swap(p, i, (i - 1) / 2), i = (i - 1) / 2;
  return 0;
}

static int heap_pop(us_Plumb *p) {
  int top = p->heap[0], i = 0;
  p->heap[0] = p->heap[--p->nheap];
  for (;;) {
    int l = 2 * i + 1, r = l + 1, m = i;
    if (l < p->nheap && heap_above(p, l, m)) m = l;
    if (r < p->nheap && heap_above(p, r, m)) m = r;
    if (m == i) break;
    heap_swap(p, i, m);
    i = m;
  }
  p->ent[top].in_heap = 0;
  return top;
}

/* Add load to entry e's pending load, its old value logged for a
 * take-back (restored, not subtracted: bit for bit). */
static int add_pending(us_Plumb *p, int e, double load) {
  if (US_GROW(p->added_e, p->cap_added_e, p->nadded_e + 1) ||
      US_GROW(p->added_l, p->cap_added_l, p->nadded_e + 1) || heap_push(p, e))
    return -1;
  p->added_e[p->nadded_e] = e;
  p->added_l[p->nadded_e++] = p->ent[e].pending;
  p->ent[e].pending += load;
  return 0;
}

int us_plumb_route_lazy(us_Plumb *p, const us_Bitset *cur, const int *added, int nadd,
                        double tol) {
  if (!p->dep.w && us_bitset_init(&p->dep, p->s->nbody)) return -1;
  p->nnew = 0;
  p->worst_line = 0.0;
  p->nadded_e = 0;
  int r = 1;
  for (int q = 0; q < nadd && r == 1; q++) {
    const us_Body *b = &p->s->bodies[added[q]];
    double c[2];
    us_plumb_horizontal(p, b->com, c);
    int e = line_entry_retry(p, cur, added[q], c, tol);
    r = e >= 0 ? (add_pending(p, e, b->mass / p->mass_total) ? -1 : 1) : e == -1 ? -1 : 0;
  }
  if (r != 1) /* take the loads back; the lines checked stay memoised */
    for (int q = p->nadded_e - 1; q >= 0; q--) p->ent[p->added_e[q]].pending = p->added_l[q];
  return r;
}

int us_plumb_materialize(us_Plumb *p, double *f) {
  size_t dim = (size_t)p->s->dim;
  while (p->nheap > 0) {
    int e = heap_pop(p);
    us_PlumbEntry *x = &p->ent[e];
    double load = x->pending;
    x->pending = 0.0;
    if (!(load != 0.0)) continue;
    for (int q = 0; q < x->n; q++) {
      double d[3];
      components(p, &p->s->contacts[x->k[q]], x->body, x->w[q] * load, d);
      for (size_t j = 0; j < dim; j++) f[dim * (size_t)x->k[q] + j] += d[j];
    }
    for (int j = 0; j < x->nchild; j++) {
      if (heap_push(p, x->child[j])) return -1;
      p->ent[x->child[j]].pending += x->cw[j] * load;
    }
  }
  return 0;
}

void us_plumb_drop(us_Plumb *p) {
  for (int i = 0; i < p->nheap; i++) {
    p->ent[p->heap[i]].pending = 0.0;
    p->ent[p->heap[i]].in_heap = 0;
  }
  p->nheap = 0;
}

void us_plumb_flush(us_Plumb *p) {
  us_plumb_drop(p);
  for (int e = 0; e < p->nent; e++) p->tab[p->ent[e].slot] = 0;
  p->nent = 0;
  if (p->dep.w) memset(p->dep.w, 0, (size_t)p->dep.nwords * sizeof(uint64_t));
}
