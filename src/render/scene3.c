/* The 3D part of the scene: an axonometric (orthographic) view of convex
 * polyhedra, with hidden surfaces by back-face culling and the painter's
 * order, shading by face orientation, and a grid on the ground.
 *
 * Axes. The viewer looks from the unit direction
 *   e = (sin az cos el, -cos az cos el, sin el)
 * (az, el in degrees): az = 0, el = 0 looks along +y with x to the right
 * and z up, the 2D picture of a structure extruded along y; a positive az
 * walks the viewer round towards +x, a positive el lifts it. The picture's
 * right is r = (cos az, sin az, 0) and its up u = e x r (z's projection is
 * up for every el in (-90, 90)). A point p lands at (p . r, p . u), its
 * depth is p . e (larger is nearer the viewer).
 *
 * Hidden surfaces. Each part is a convex polyhedron whose face planes have
 * outward unit normals n: a face is drawn only when n . e > 0 (it faces
 * the viewer; for one convex part this alone is exact). Across parts the
 * faces are painted in the painter's order of src/render/depth3.c: a part
 * after every part it is in front of where their pictures overlap, which
 * is right for convex parts that do not interpenetrate, whatever their
 * sizes (cycles of parts overlapping each other in turn are broken at the
 * farthest). Labels, contact dots, force arrows, hand rings and mechanism
 * arrows are drawn over the faces, each only where no part painted after
 * its bodies covers it (depth3.c: "Covering").
 *
 * Shading is a pure factor on the sRGB bytes of the body's colour,
 *   f = 0.70 + 0.30 n_z - 0.12 (n . r),  clamped to [0.25, 1],
 * so a top face (n = z) has f = 1, exactly the ramp's colour, sides are
 * darker, the one facing the picture's left lighter than the one facing
 * its right (light from the upper left). Hatched paints are not shaded.
 *
 * The ground grid (with a ground): lines on z = 0 at a round spacing (1, 2
 * or 5 times a power of ten, about an eighth of the footprint's larger
 * side) covering the bodies' x-y footprint and a margin of a tenth of it,
 * drawn under every face. */
#include "render/render.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEG (3.14159265358979323846 / 180.0)

static double dot3(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void us_scene3_axes(us_SceneView *v, double az, double el) {
  double ca = cos(az * DEG), sa = sin(az * DEG), ce = cos(el * DEG), se = sin(el * DEG);
  double e[3] = {sa * ce, -ca * ce, se}, r[3] = {ca, sa, 0.0};
  memcpy(v->e, e, sizeof e);
  memcpy(v->r, r, sizeof r);
  v->u[0] = e[1] * r[2] - e[2] * r[1];
  v->u[1] = e[2] * r[0] - e[0] * r[2];
  v->u[2] = e[0] * r[1] - e[1] * r[0];
}

void us_scene_px(const us_SceneView *v, const double p[3], double *X, double *Y) {
  *X = v->ox + (dot3(p, v->r) - v->x0) * v->k;
  *Y = v->oy + (v->y1 - dot3(p, v->u)) * v->k;
}

void us_scene3_count(const us_Structure *s, size_t *nentry, size_t *npt) {
  *nentry = *npt = 0;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    *nentry += b->npart == 0;
    for (int p = 0; p < b->npart; p++) {
      *nentry += (size_t)b->parts[p].nface;
      *npt += b->parts[p].nface ? (size_t)b->parts[p].face_start[b->parts[p].nface] : 0;
    }
  }
}

/* ----------------------------------------------------------------- grid */

/* The bodies' x-y footprint with its margin (0: no geometry). */
static int footprint(const us_Structure *s, double fp[4]) {
  fp[0] = fp[1] = INFINITY, fp[2] = fp[3] = -INFINITY;
  for (int i = 0; i < s->nbody; i++)
    for (int p = 0; p < s->bodies[i].npart; p++) {
      const us_Polyhedron *h = &s->bodies[i].parts[p];
      for (int k = 0; k < h->nvert; k++)
        for (int d = 0; d < 2; d++) {
          fp[d] = US_MIN(fp[d], h->verts[3 * k + d]);
          fp[d + 2] = US_MAX(fp[d + 2], h->verts[3 * k + d]);
        }
    }
  if (!(fp[0] <= fp[2]) || !isfinite(fp[0] + fp[1] + fp[2] + fp[3])) return 0;
  double side = US_MAX(fp[2] - fp[0], fp[3] - fp[1]), pad = 0.1 * (side > 0 ? side : 1.0);
  fp[0] -= pad, fp[1] -= pad, fp[2] += pad, fp[3] += pad;
  return 1;
}

/* 1, 2 or 5 times a power of ten, near x. */
static double round_step(double x) {
  double p = pow(10.0, floor(log10(x))), m = x / p;
  return (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * p;
}

/* Grid lines in world coordinates (x1, y1, x2, y2 on z = 0); their count. */
static int grid_world(const us_Structure *s, double *out) {
  double fp[4];
  if (!s->ground || !footprint(s, fp)) return 0;
  double step = round_step(US_MAX(fp[2] - fp[0], fp[3] - fp[1]) / 8.0);
  double lo[2] = {floor(fp[0] / step) * step, floor(fp[1] / step) * step};
  double hi[2] = {ceil(fp[2] / step) * step, ceil(fp[3] / step) * step};
  int n = 0;
  for (int d = 0; d < 2; d++)
    for (double c = lo[d]; c <= hi[d] + 0.5 * step && n < US_GRID_LINES; c += step, n++) {
      double *l = out + 4 * n;
      l[d] = l[d + 2] = c;
      l[1 - d] = lo[1 - d];
      l[3 - d] = hi[1 - d];
    }
  return n;
}

/* --------------------------------------------------------------- bounds */

static void grow(double bb[4], const us_SceneView *v, const double p[3]) {
  double x = dot3(p, v->r), y = dot3(p, v->u);
  bb[0] = US_MIN(bb[0], x), bb[1] = US_MIN(bb[1], y);
  bb[2] = US_MAX(bb[2], x), bb[3] = US_MAX(bb[3], y);
}

void us_scene3_bounds(const us_Structure *s, const us_SceneView *v, double bb[4]) {
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    if (b->npart == 0) grow(bb, v, b->com);
    for (int p = 0; p < b->npart; p++)
      for (int k = 0; k < b->parts[p].nvert; k++) grow(bb, v, b->parts[p].verts + 3 * k);
  }
  double g[4 * US_GRID_LINES];
  int n = grid_world(s, g);
  for (int k = 0; k < n; k++) {
    double a[3] = {g[4 * k], g[4 * k + 1], 0.0}, c[3] = {g[4 * k + 2], g[4 * k + 3], 0.0};
    grow(bb, v, a);
    grow(bb, v, c);
  }
}

static void put_grid(us_Scene *sc, const us_SceneView *v, const us_Structure *s) {
  double g[4 * US_GRID_LINES];
  sc->nline = grid_world(s, g);
  for (int k = 0; k < sc->nline; k++) {
    double a[3] = {g[4 * k], g[4 * k + 1], 0.0}, c[3] = {g[4 * k + 2], g[4 * k + 3], 0.0};
    double *l = sc->lines + 4 * k;
    us_scene_px(v, a, &l[0], &l[1]);
    us_scene_px(v, c, &l[2], &l[3]);
  }
  sc->line_width = 0.8;
  sc->line_color = (us_Rgb){170, 170, 170};
}

/* ---------------------------------------------------------------- faces */

static us_Paint shade(us_Paint p, const double *n, const us_SceneView *v) {
  if (p.hatch >= 0) return p;
  double f = 0.70 + 0.30 * n[2] - 0.12 * dot3(n, v->r);
  f = f < 0.25 ? 0.25 : (f > 1.0 ? 1.0 : f);
  p.fill = (us_Rgb){(unsigned char)lround(p.fill.r * f), (unsigned char)lround(p.fill.g * f),
                    (unsigned char)lround(p.fill.b * f)};
  return p;
}

/* Face f of part h of body i as entry sb, its points from pts[2 first]. */
static void put_face(us_Scene *sc, us_SceneBody *sb, const us_SceneView *v,
                     const us_Polyhedron *h, int f, int *first) {
  int a = h->face_start[f], n = h->face_start[f + 1] - a;
  double c[3] = {0, 0, 0};
  sb->first = *first;
  sb->npt = n;
  for (int k = 0; k < n; k++, (*first)++) {
    const double *p = h->verts + 3 * h->face_vert[a + k];
    us_scene_px(v, p, &sc->pts[2 * *first], &sc->pts[2 * *first + 1]);
    for (int d = 0; d < 3; d++) c[d] += p[d] / n;
  }
  us_scene_px(v, c, &sb->cx, &sb->cy);
  sb->depth = dot3(c, v->e);
}

/* Where collect puts what depth3.c needs: per entry its face plane (NULL
 * for a point body) and its node (one per convex part or point body). */
typedef struct Collected {
  const double **plane;
  int *node;
  int nnode;
} Collected;

/* Every face turned to the viewer, and every point body, by body and part. */
static void collect(us_Scene *sc, const us_SceneView *v, const us_Structure *s,
                    const us_SceneBody *proto, Collected *out) {
  int first = 0;
  sc->nbody = 0;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    if (proto[i].hidden) continue;
    for (int p = 0; p < b->npart; p++, out->nnode++)
      for (int f = 0; f < b->parts[p].nface; f++) {
        const double *n = b->parts[p].planes + 4 * f;
        if (!(dot3(n, v->e) > 1e-9)) continue;
        out->plane[sc->nbody] = n, out->node[sc->nbody] = out->nnode;
        us_SceneBody *sb = &sc->bodies[sc->nbody++];
        *sb = (us_SceneBody){.body = i, .paint = shade(proto[i].paint, n, v),
                             .mark = proto[i].mark};
        put_face(sc, sb, v, &b->parts[p], f, &first);
      }
    if (b->npart == 0) {
      out->plane[sc->nbody] = NULL, out->node[sc->nbody] = out->nnode++;
      us_SceneBody *sb = &sc->bodies[sc->nbody++];
      *sb = (us_SceneBody){.body = i, .paint = proto[i].paint, .depth = dot3(b->com, v->e),
                           .mark = proto[i].mark};
      us_scene_px(v, b->com, &sb->cx, &sb->cy);
    }
  }
}

/* ---------------------------------------------------------------- labels */

/* Label point (the centre of mass once finalized, else the mean vertex)
 * and the projected extent (w, h) of body b, in pixels. */
static void body_box(const us_SceneView *v, const us_Structure *s, const us_Body *b,
                     double c[3], double *w, double *h) {
  double bb[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
  int n = 0;
  memcpy(c, b->com, 3 * sizeof *c);
  if (!us_structure_is_finalized(s)) c[0] = c[1] = c[2] = 0.0;
  for (int p = 0; p < b->npart; p++)
    for (int k = 0; k < b->parts[p].nvert; k++, n++) {
      grow(bb, v, b->parts[p].verts + 3 * k);
      for (int d = 0; !us_structure_is_finalized(s) && d < 3; d++) c[d] += b->parts[p].verts[3 * k + d];
    }
  for (int d = 0; !us_structure_is_finalized(s) && n && d < 3; d++) c[d] /= n;
  *w = n ? (bb[2] - bb[0]) * v->k : 0.0;
  *h = n ? (bb[3] - bb[1]) * v->k : 0.0;
}

/* The area of face entry f in px^2 (0 for a point body). */
static double face_area(const us_Scene *sc, const us_SceneBody *f) {
  double a = 0.0;
  const double *p = sc->pts + 2 * f->first;
  for (int k = 0; k < f->npt; k++) {
    int j = (k + 1) % f->npt;
    a += p[2 * k] * p[2 * j + 1] - p[2 * j] * p[2 * k + 1];
  }
  return 0.5 * fabs(a);
}

/* Where the label of entry e's body goes (a box of half sides hw, hh): at
 * (x, y), its projected centre, when nearer bodies leave it seen, else at
 * the centroid of the largest face they leave it seen on (of the faces
 * in e's run: its last part's); 0 when there is none. */
static int label_spot(const us_Scene *sc, int e, double hw, double hh, double *x, double *y) {
  int body = sc->bodies[e].body;
  if (!us_depth3_hides_label(sc, body, *x, *y, hw, hh)) return 1;
  double best = 0.0;
  for (int k = e; k >= 0 && sc->bodies[k].body == body; k--) {
    const us_SceneBody *f = &sc->bodies[k];
    double a = face_area(sc, f);
    if (a > best && !us_depth3_hides_label(sc, body, f->cx, f->cy, hw, hh))
      best = a, *x = f->cx, *y = f->cy;
  }
  return best > 0.0;
}

/* proto's label on body i's last entry sb in the painter's order, sized as
 * in 2D (45% of the projected height, at most 16 px, fitted to the width,
 * none under 5 px), at the projected centre of mass, or where that is
 * covered (parts painted later cover a quarter of its box, depth3.c) on
 * the largest face it is not, else left out. */
static void put_label(const us_Scene *sc, us_SceneBody *sb, const us_SceneView *v,
                      const us_Structure *s, const us_SceneBody *proto) {
  const us_Body *b = &s->bodies[sb->body];
  double c[3], w, h, len = (double)strlen(proto->label.text);
  body_box(v, s, b, c, &w, &h);
  double fs = b->npart ? US_MIN(US_MIN(0.45 * h, 16.0), 0.9 * w / (0.6 * US_MAX(len, 1.0)))
                       : 9.0;
  if (fs < 5.0) return;
  sb->label = proto->label;
  memcpy(sb->num, proto->num, sizeof sb->num);
  if (proto->label.text == proto->num) sb->label.text = sb->num;
  sb->label.size = fs;
  us_scene_px(v, c, &sb->label.x, &sb->label.y);
  double hw = 0.3 * fs * US_MAX(len, 1.0), hh = 0.5 * fs; /* the text's box, as sized */
  if (!label_spot(sc, (int)(sb - sc->bodies), hw, hh, &sb->label.x, &sb->label.y))
    sb->label.text = NULL; /* nearer bodies cover much of it wherever it goes */
}

static void put_labels(us_Scene *sc, const us_SceneView *v, const us_Structure *s,
                       us_SceneBody *proto) {
  for (int k = sc->nbody - 1; k >= 0; k--) { /* last entry of each body first */
    us_SceneBody *sb = &sc->bodies[k];
    us_SceneBody *pr = &proto[sb->body];
    if (!pr->label.text || pr->depth < 0) continue;
    pr->depth = -1.0; /* proto's depth marks "labelled" */
    put_label(sc, sb, v, s, pr);
  }
}

int us_scene3_bodies(us_Scene *sc, const us_SceneView *v, const us_Structure *s,
                     us_SceneBody *proto) {
  size_t ne, np;
  us_scene3_count(s, &ne, &np);
  Collected c = {us_malloc((ne + 1) * sizeof *c.plane), us_malloc((ne + 1) * sizeof *c.node), 0};
  int bad = !c.plane || !c.node;
  put_grid(sc, v, s);
  if (!bad) collect(sc, v, s, proto, &c);
  if (!bad) bad = us_depth3_order(sc, v, s->nbody, (const double *const *)c.plane, c.node);
  us_free(c.plane), us_free(c.node);
  if (bad) return 1;
  put_labels(sc, v, s, proto);
  sc->labels_in_order = 1;
  return 0;
}
