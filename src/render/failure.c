/* Why a structure does not stand, in a picture: the body that cannot be
 * held and the bodies of a plan's failing step are marked (scene bodies'
 * `mark`; the writers outline them in the mark colour), and the unstable
 * verdict's mechanism (us_Mechanism: per moving body its velocity v at the
 * centre of mass and its rotation omega, in radians per unit of the
 * structure's scale) is drawn as arrows of v from each moving body's
 * centre, the longest 12% of the view's larger side, and in 2D as ghosts:
 * each moving polygon displaced rigidly by t v and turned by t omega /
 * scale about its centre, t chosen so the farthest-moving vertex moves 8%
 * of the view's larger side (the turn at most 0.5 rad). The motion is the
 * Farkas ray of the equilibrium system read as velocities: gravity does
 * positive work along it and no contact force can resist it, so it shows
 * how the structure starts to fall, not where it ends. */
#include "render/render.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define ARROW_SHARE 0.12
#define GHOST_SHARE 0.08
#define MAX_TURN 0.5

static int mech_stride(const us_Structure *s) { return s->dim == 3 ? 6 : 3; }

static const us_Mechanism *mechanism_of(const us_RenderFailure *f) {
  return f && f->mechanism && f->mechanism->nbody > 0 ? f->mechanism : NULL;
}

us_Status us_scene_check_failure(const us_Structure *s, const us_RenderSettings *r,
                                 us_Error *err) {
  const us_RenderFailure *f = r->failure;
  if (!f) return US_OK;
  int nsteps = r->group_start ? r->ngroups : r->norder;
  if (f->step < 0 || f->step > nsteps || f->body < -1 || f->body >= s->nbody)
    return us_error_set(err, US_ERR_USAGE, "render: the failure (step %d, body %d) does not "
                        "match the structure and order", f->step, f->body);
  const us_Mechanism *m = mechanism_of(f);
  if (m && (!m->body || !m->v))
    return us_error_set(err, US_ERR_USAGE, "render: bad mechanism (%d bodies)", m->nbody);
  for (int q = 0; m && q < m->nbody; q++)
    if (m->body[q] < 0 || m->body[q] >= s->nbody)
      return us_error_set(err, US_ERR_USAGE, "render: mechanism body %d is not in 0..%d",
                          m->body[q], s->nbody - 1);
  return US_OK;
}

/* The body to mark as falling: the one named, else the mechanism's
 * fastest (|v| + |omega|, omega per unit of scale), else none. */
int us_scene_falling(const us_Structure *s, const us_RenderFailure *f) {
  const us_Mechanism *m = mechanism_of(f);
  if (!f || f->body >= 0 || !m) return f ? f->body : -1;
  int k = mech_stride(s), best = -1;
  double top = 0.0;
  for (int q = 0; q < m->nbody; q++) {
    double sum = 0.0;
    for (int d = 0; d < k; d++) sum += fabs(m->v[(size_t)k * (size_t)q + (size_t)d]);
    if (sum > top) top = sum, best = m->body[q];
  }
  return best;
}

int us_scene_mark(const us_RenderSettings *r, const int *step, int i, int falls) {
  const us_RenderFailure *f = r->failure;
  if (!f) return US_MARK_NONE;
  if (i == falls) return US_MARK_FALLS;
  return f->step > 0 && step[i] == f->step && !r->order_builds ? US_MARK_STEP : US_MARK_NONE;
}

/* Removed at or before the failing step: drawn white, as gone. */
int us_scene_removed(const us_RenderSettings *r, const int *step, int i) {
  const us_RenderFailure *f = r->failure;
  return f && f->step > 0 && !r->order_builds && step[i] > 0 && step[i] <= f->step;
}

void us_scene_failure_line(char *buf, size_t n, const us_Structure *s,
                           const us_RenderSettings *r) {
  const us_RenderFailure *f = r->failure;
  char who[120] = "";
  int falls = us_scene_falling(s, f);
  if (falls >= 0)
    snprintf(who, sizeof who, "; red outline: '%s' cannot be held",
             us_id_text(s->bodies[falls].id).s);
  const char *mech = mechanism_of(f) ? "; red arrows: how it starts to fall" : "";
  if (f->step > 0)
    snprintf(buf, n, "fails at step %d (dashed; white: removed)%s%s", f->step, who, mech);
  else
    snprintf(buf, n, "does not stand%s%s", who, mech);
}

int us_scene_alloc_failure(us_Scene *sc, const us_Structure *s, const us_RenderSettings *r) {
  const us_Mechanism *m = mechanism_of(r->failure);
  size_t nb = m ? (size_t)m->nbody : 0, nv = 0;
  for (size_t q = 0; q < nb; q++)
    if (m->body[q] >= 0 && m->body[q] < s->nbody) nv += (size_t)s->bodies[m->body[q]].nvert;
  sc->mech = us_malloc((4 * nb + 1) * sizeof *sc->mech);
  sc->ghost_start = us_malloc((nb + 2) * sizeof *sc->ghost_start);
  sc->ghost_pts = us_malloc((2 * nv + 1) * sizeof *sc->ghost_pts);
  return !sc->mech || !sc->ghost_start || !sc->ghost_pts;
}

/* Velocity of a point p of moving body q (2D): v + omega / L x (p - c). */
static void point_velocity2(const us_Structure *s, const double *v, const double *c,
                            const double *p, double out[2]) {
  double inv_l = s->scale > 0 ? 1.0 / s->scale : 1.0;
  out[0] = v[0] - v[2] * (p[1] - c[1]) * inv_l;
  out[1] = v[1] + v[2] * (p[0] - c[0]) * inv_l;
}

/* Arrows of the centres' velocities (3D: those no nearer body covers). */
static void put_mech_arrows(us_Scene *sc, const us_SceneView *v, const us_Structure *s,
                            const us_Mechanism *m) {
  int k = mech_stride(s);
  double vmax = 0.0;
  for (int q = 0; q < m->nbody; q++) {
    const double *u = m->v + (size_t)k * (size_t)q;
    double len = sqrt(u[0] * u[0] + u[1] * u[1] + (k == 6 ? u[2] * u[2] : 0.0));
    if (isfinite(len)) vmax = US_MAX(vmax, len);
  }
  if (!(vmax > 0)) return;
  double scale = ARROW_SHARE * v->span / vmax;
  for (int q = 0; q < m->nbody; q++) {
    const double *u = m->v + (size_t)k * (size_t)q, *c = s->bodies[m->body[q]].com;
    double e[3] = {c[0] + u[0] * scale, c[1] + u[1] * scale, c[2] + (k == 6 ? u[2] : 0.0) * scale};
    double *a = &sc->mech[4 * sc->nmech];
    us_scene_px(v, c, &a[0], &a[1]);
    us_scene_px(v, e, &a[2], &a[3]);
    if (isfinite(a[2] + a[3]) && hypot(a[2] - a[0], a[3] - a[1]) >= 0.5 &&
        !us_depth3_covers_segment(sc, m->body[q], US_GROUND, a)) /* 3D: not under a nearer body */
      sc->nmech++;
  }
}

/* The largest vertex speed of 2D moving polygon q. */
static double body_speed(const us_Structure *s, const us_Mechanism *m, int q) {
  const us_Body *b = &s->bodies[m->body[q]];
  double vmax = 0.0, u[2];
  for (int j = 0; j < b->nvert; j++) {
    point_velocity2(s, m->v + 3 * (size_t)q, b->com, b->verts + 2 * j, u);
    if (isfinite(hypot(u[0], u[1]))) vmax = US_MAX(vmax, hypot(u[0], u[1]));
  }
  return vmax;
}

/* The largest vertex speed of the 2D moving polygons. */
static double ghost_speed(const us_Structure *s, const us_Mechanism *m) {
  double vmax = 0.0;
  for (int q = 0; q < m->nbody; q++) vmax = US_MAX(vmax, body_speed(s, m, q));
  return vmax;
}

/* 2D: each moving polygon moved rigidly by time t along the mechanism. */
static void put_ghosts(us_Scene *sc, const us_SceneView *v, const us_Structure *s,
                       const us_Mechanism *m) {
  double vmax = ghost_speed(s, m);
  if (!(vmax > 0)) return;
  double t = GHOST_SHARE * v->span / vmax, inv_l = s->scale > 0 ? 1.0 / s->scale : 1.0;
  int n = 0;
  sc->ghost_start[0] = 0;
  for (int q = 0; q < m->nbody; q++) {
    const us_Body *b = &s->bodies[m->body[q]];
    const double *u = m->v + 3 * (size_t)q, *c = b->com;
    double th = US_MAX(-MAX_TURN, US_MIN(MAX_TURN, t * u[2] * inv_l)), cs = cos(th), sn = sin(th);
    if (b->nvert == 0 || body_speed(s, m, q) < 1e-3 * vmax) continue; /* still */
    for (int j = 0; j < b->nvert; j++, n++) {
      double dx = b->verts[2 * j] - c[0], dy = b->verts[2 * j + 1] - c[1];
      double p[3] = {c[0] + t * u[0] + cs * dx - sn * dy, c[1] + t * u[1] + sn * dx + cs * dy, 0};
      us_scene_px(v, p, &sc->ghost_pts[2 * n], &sc->ghost_pts[2 * n + 1]);
    }
    sc->ghost_start[++sc->nghost] = n;
  }
}

void us_scene_mechanism(us_Scene *sc, const us_SceneView *v, const us_Structure *s,
                        const us_RenderFailure *f) {
  const us_Mechanism *m = mechanism_of(f);
  sc->mark_color = (us_Rgb){200, 0, 30};
  if (!m) return;
  put_mech_arrows(sc, v, s, m);
  if (s->dim == 2) put_ghosts(sc, v, s, m);
}
