/* The scene: what a picture of a structure shows, computed once from the
 * structure and the render settings, drawn by the SVG and PNG writers.
 *
 * Layout, top to bottom: a title band (26 px, when r->title), the drawing,
 * a legend (legend_layout: the ramp, lines of text beside or under it,
 * a row of swatches; its height is known before the drawing is placed).
 * World coordinates (y up) map to pixels by X = ox + (x - x0) k, Y = oy + (y1 - y) k (y flipped);
 * the view [x0, x0 + ww] x [y1 - wh, y1] is the bounding box of all
 * geometry, centres, contacts (and y = 0 with a ground) plus a margin of
 * 6% of its larger side. k makes the view as wide as the picture; when the
 * picture would then be taller than allowed (r->height_px, or the format's
 * limits max_side and max_pixels), k shrinks so the view fits and the
 * drawing is centred. The picture's sides are whole pixels.
 *
 * Content, back to front: the ground, hatched, under y = 0; bodies as
 * polygons (point bodies, without geometry, as dots of US_POINT_BODY_PX),
 * fixed bodies grey and hatched; with an order, each body in it coloured by
 * its removal step on the ramp (us_ramp: t = 0 for the first step, 1 for
 * the last) and numbered (1 = removed first; the bodies of one step share
 * its number), bodies not in it light grey; bodies named as blocked (a plan
 * with status none) light red crossed by dark red lines, named "cannot be
 * removed" in the legend; without an order, ids as labels (show_labels);
 * contact points as dots (show_contacts); r->forces as arrows from each
 * contact point (or, r->force_resultants, one per touching pair), the
 * force of the lower body on the upper one (src/render/forces.c), its
 * normal part blue and its friction part orange, the longest 12% of the
 * view's larger side. Labels are sized to fit their
 * body and left out when under 5 px; dots and outlines thin out with the
 * typical body size, so a wall of a thousand bricks stays legible.
 * r->hand_state (a plan with hands at one action): bodies not placed yet
 * faint and unlabelled (3D: left out), their contact dots left out; held
 * bodies outlined in magenta with a ring (the hand mark) at their centre.
 *
 * 3D structures (src/render/scene3.c): world points are projected onto the
 * view's right and up axes (us_SceneView; 2D: x and y as they are) before
 * the same fit; the bodies become their visible faces, painted in the
 * painter's order (src/render/depth3.c) and shaded, with labels at the
 * projected centres of mass, and the ground band becomes a grid on z = 0.
 * Contacts and arrows are projected the same way in both dimensions; in 3D
 * those a nearer body covers are left out (depth3.c).
 *
 * Errors: bad settings (order or force indices out of range, repeated
 * bodies in the order, sizes out of range) are US_ERR_USAGE; nothing is
 * allocated by a failed build. */
#include "render/render.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define TITLE_PX 26.0
#define LINE_PX 15.0        /* legend line spacing */
#define MIN_DRAWING_PX 16.0 /* the least room a drawing gets */

const us_Hatch us_hatches[US_NHATCH] = {
    {"hatch", {255, 255, 255}, {85, 85, 85}, 45.0, 8.0, 1.5},     /* ground */
    {"fixed", {160, 160, 160}, {68, 68, 68}, 45.0, 8.0, 1.5},     /* fixed bodies */
    {"blocked", {243, 201, 196}, {178, 24, 43}, -45.0, 6.0, 1.5}, /* cannot be removed */
};

static const us_Rgb kSandstone = {217, 199, 163}, kLeftOut = {228, 228, 228};
static const us_Rgb kBlack = {0, 0, 0}, kWhite = {255, 255, 255};
static const us_Rgb kUnplaced = {246, 246, 246}, kHand = {196, 0, 150};

typedef us_SceneView View; /* render.h */

/* The legend's text and layout (legend_layout). */
typedef struct Legend {
  char line[7][160];
  int nline, ramp, swatches;
  double text_x, text_y, swatch_y, height;
} Legend;

/* What the settings say about each body and the legend. */
typedef struct Info {
  int *step;       /* 1-based removal step, 0 not in the order, -1 blocked */
  int nsteps;      /* steps of the order */
  int nfixed, nleft; /* fixed bodies; movable ones neither ordered nor blocked */
  double fmax;       /* largest force part drawn (0: none) */
  us_DrawnForce *drawn; /* the arrows' forces (ndrawn) */
  int ndrawn;
  us_SceneBody *proto; /* 3D: each body's paint and label text */
  us_Labels labels;    /* resolved: IDS, STEPS or NONE */
  int falls;           /* the body marked as falling, or -1 */
  int nstate[3];       /* bodies per US_HAND_* (r->hand_state) */
  double title_h;
  Legend legend;
} Info;

static double px_x(const View *v, double x) { return v->ox + (x - v->x0) * v->k; }
static double px_y(const View *v, double y) { return v->oy + (v->y1 - y) * v->k; }

static us_Paint solid(us_Rgb c) { return (us_Paint){c, -1}; }
static us_Paint hatched(int h) { return (us_Paint){us_hatches[h].base, h}; }

/* --------------------------------------------------------------- checks */

/* The order (and its steps) into step[]; US_ERR_USAGE on a bad one. */
static us_Status check_order(const us_Structure *s, const us_RenderSettings *r, int *step,
                             us_Error *err) {
  if (r->norder < 0 || (r->norder > 0 && !r->order))
    return us_error_set(err, US_ERR_USAGE, "render: bad order (%d entries)", r->norder);
  for (int k = 0; k < r->norder; k++) {
    int i = r->order[k];
    if (i < 0 || i >= s->nbody)
      return us_error_set(err, US_ERR_USAGE, "render: order entry %d is body %d, not in 0..%d",
                          k, i, s->nbody - 1);
    if (step[i])
      return us_error_set(err, US_ERR_USAGE, "render: body '%s' appears twice in the order",
                          us_id_text(s->bodies[i].id).s);
    step[i] = k + 1;
  }
  if (!r->group_start) return US_OK;
  if (r->ngroups < 0 || r->group_start[0] != 0 || r->group_start[r->ngroups] != r->norder)
    return us_error_set(err, US_ERR_USAGE, "render: steps do not cover the order");
  for (int g = 0; g < r->ngroups; g++) {
    if (r->group_start[g + 1] < r->group_start[g])
      return us_error_set(err, US_ERR_USAGE, "render: steps do not cover the order");
    for (int k = r->group_start[g]; k < r->group_start[g + 1]; k++) step[r->order[k]] = g + 1;
  }
  return US_OK;
}

/* Blocked bodies and forces. */
static us_Status check_rest(const us_Structure *s, const us_RenderSettings *r, int *step,
                            us_Error *err) {
  for (int k = 0; k < r->nblocked; k++) {
    int i = r->blocked ? r->blocked[k] : -1;
    if (i < 0 || i >= s->nbody || step[i])
      return us_error_set(err, US_ERR_USAGE, "render: blocked entry %d is not a body outside "
                          "the order", k);
    step[i] = -1;
  }
  us_Status st = us_scene_check_failure(s, r, err);
  if (st) return st;
  const us_Forces *f = r->forces;
  if (f && (f->ncontact < 0 || (f->ncontact > 0 && (!f->contact || !f->f))))
    return us_error_set(err, US_ERR_USAGE, "render: bad forces (%d contacts)", f->ncontact);
  for (int k = 0; f && k < f->ncontact; k++)
    if (f->contact[k] < 0 || f->contact[k] >= s->ncontact)
      return us_error_set(err, US_ERR_USAGE, "render: force %d names contact %d, not in 0..%d",
                          k, f->contact[k], s->ncontact - 1);
  return US_OK;
}

static us_Status check_settings(const us_Structure *s, const us_RenderSettings *r, Info *in,
                                us_Error *err) {
  if (s->dim != 2 && s->dim != 3)
    return us_error_set(err, US_ERR_USAGE, "render: cannot draw a structure of dimension %d",
                        s->dim);
  if (s->dim == 3 && !(isfinite(r->view_az) && r->view_el >= -90.0 && r->view_el <= 90.0))
    return us_error_set(err, US_ERR_USAGE, "render: bad view (azimuth %g, elevation %g): the "
                        "elevation is in [-90, 90] degrees", r->view_az, r->view_el);
  us_Status st = check_order(s, r, in->step, err);
  if (!st) st = check_rest(s, r, in->step, err);
  if (st) return st;
  in->nsteps = r->group_start ? r->ngroups : r->norder;
  if ((unsigned)r->labels > US_LABELS_NONE)
    return us_error_set(err, US_ERR_USAGE, "render: bad labels setting %d", (int)r->labels);
  in->falls = us_scene_falling(s, r->failure);
  in->labels = !r->show_labels ? US_LABELS_NONE
               : r->labels == US_LABELS_AUTO ? (r->norder > 0 ? US_LABELS_STEPS : US_LABELS_IDS)
                                             : r->labels;
  for (int i = 0; r->hand_state && i < s->nbody; i++) {
    if (r->hand_state[i] > US_HAND_HELD)
      return us_error_set(err, US_ERR_USAGE, "render: bad hand state %d of body '%s'",
                          r->hand_state[i], us_id_text(s->bodies[i].id).s);
    in->nstate[r->hand_state[i]] += !s->bodies[i].fixed;
  }
  for (int i = 0; i < s->nbody; i++) {
    in->nfixed += s->bodies[i].fixed != 0;
    in->nleft += !s->bodies[i].fixed && in->step[i] == 0;
  }
  return US_OK;
}

/* ----------------------------------------------------------------- view */

static void grow_box(double *bb, double x, double y) {
  bb[0] = US_MIN(bb[0], x);
  bb[1] = US_MIN(bb[1], y);
  bb[2] = US_MAX(bb[2], x);
  bb[3] = US_MAX(bb[3], y);
}

/* World bounding box of everything drawn, with the margin. */
static us_Status world_view(const us_Structure *s, const us_RenderSettings *r, View *v,
                            us_Error *err) {
  double bb[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
  if (s->dim == 3) us_scene3_axes(v, r->view_az, r->view_el), us_scene3_bounds(s, v, bb);
  else v->r[0] = v->u[1] = v->e[2] = 1.0; /* the plane as it is */
  for (int i = 0; s->dim == 2 && i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    for (int k = 0; k < b->nvert; k++) grow_box(bb, b->verts[2 * k], b->verts[2 * k + 1]);
    if (b->nvert == 0) grow_box(bb, b->com[0], b->com[1]);
  }
  for (int c = 0; c < s->ncontact; c++) {
    const double *p = s->contacts[c].p;
    grow_box(bb, p[0] * v->r[0] + p[1] * v->r[1] + p[2] * v->r[2],
             p[0] * v->u[0] + p[1] * v->u[1] + p[2] * v->u[2]);
  }
  if (!(bb[0] <= bb[2])) bb[0] = bb[1] = bb[2] = bb[3] = 0.0; /* nothing to draw */
  if (s->ground && s->dim == 2) grow_box(bb, bb[0], 0.0);
  if (!isfinite(bb[0] + bb[1] + bb[2] + bb[3]))
    return us_error_set(err, US_ERR_INPUT, "render: the structure has non-finite coordinates");
  double span = US_MAX(bb[2] - bb[0], bb[3] - bb[1]);
  if (!(span > 0)) span = 1.0;
  double pad = 0.06 * span;
  v->span = span;
  v->x0 = bb[0] - pad;
  v->y1 = bb[3] + pad;
  v->ww = bb[2] - bb[0] + 2 * pad;
  v->wh = bb[3] - bb[1] + 2 * pad;
  return US_OK;
}

static us_Status size_error(us_Error *err, const char *what, double px, double max_side) {
  return us_error_set(err, US_ERR_USAGE,
                      "render: %s %.0f px is out of range: a picture is 1 to %.0f pixels a side "
                      "in this format", what, px, max_side);
}

/* Picture size and the world-to-pixel map (see the file header). */
static us_Status fit_view(us_Scene *sc, View *v, const us_RenderSettings *r, const Info *in,
                          double max_side, double max_pixels, us_Error *err) {
  double W = round(r->width_px), H = round(r->height_px), bands = in->title_h + in->legend.height;
  if (!(W >= 1 && W <= max_side)) return size_error(err, "width", r->width_px, max_side);
  if (r->height_px != 0 && !(H >= 1 && H <= max_side))
    return size_error(err, "height", r->height_px, max_side);
  if (W * H > max_pixels)
    return us_error_set(err, US_ERR_USAGE, "render: %.0f x %.0f px is over this format's "
                        "limit of %.0f pixels", W, H, max_pixels);
  double room = H > 0 ? H - bands : US_MIN(max_side, floor(max_pixels / W)) - bands;
  if (!(room >= MIN_DRAWING_PX))
    return us_error_set(err, US_ERR_USAGE, "render: no room for the drawing in %.0f x %.0f px "
                        "(the title and legend take %.0f px)", W, H > 0 ? H : max_side, bands);
  v->k = US_MIN(W / v->ww, room / v->wh);
  double dh = H > 0 ? room : v->wh * v->k; /* the drawing's band */
  v->ox = 0.5 * (W - v->ww * v->k);
  v->oy = in->title_h + 0.5 * (dh - v->wh * v->k);
  sc->w = W;
  sc->h = H > 0 ? H : ceil(bands + dh);
  sc->draw_top = in->title_h;
  sc->draw_bottom = in->title_h + dh;
  return US_OK;
}

/* --------------------------------------------------------------- bodies */

/* Width and height in pixels of body b's bounding box (0 without
 * geometry). */
static void body_extent(const View *v, const us_Body *b, double *w, double *h) {
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (int k = 0; k < b->nvert; k++)
    for (int d = 0; d < 2; d++) {
      lo[d] = US_MIN(lo[d], b->verts[2 * k + d]);
      hi[d] = US_MAX(hi[d], b->verts[2 * k + d]);
    }
  *w = b->nvert ? (hi[0] - lo[0]) * v->k : 0.0;
  *h = b->nvert ? (hi[1] - lo[1]) * v->k : 0.0;
}

/* Font size for a label of `len` characters on body b: 45% of the box's
 * height, at most 16 px, shrunk so the text (about 0.6 em per character)
 * fits the box's width; 0 when that would be under 5 px (too small to
 * read: the label is left out). Point bodies get 9 px. */
static double label_size(const View *v, const us_Body *b, size_t len) {
  if (b->nvert == 0) return 9.0;
  double w, h;
  body_extent(v, b, &w, &h);
  double fs = US_MIN(0.45 * h, 16.0);
  fs = US_MIN(fs, 0.9 * w / (0.6 * (double)(len ? len : 1)));
  return fs < 5.0 ? 0.0 : fs;
}

/* Contact dots and body outlines: from the mean body's smaller side in
 * pixels, so that dense scenes stay readable. */
static void line_sizes(us_Scene *sc, const View *v, const us_Structure *s) {
  double sum = 0.0, w, h;
  int n = 0;
  for (int i = 0; i < s->nbody; i++) {
    body_extent(v, &s->bodies[i], &w, &h);
    if (s->bodies[i].nvert) sum += US_MIN(w, h), n++;
  }
  double side = n ? sum / n : 40.0;
  sc->dot_r = side * 0.06 < 0.6 ? 0.6 : (side * 0.06 > 2.0 ? 2.0 : side * 0.06);
  sc->stroke = side * 0.03 < 0.3 ? 0.3 : (side * 0.03 > 1.0 ? 1.0 : side * 0.03);
}

/* Position of removal step `step` (1-based) of n on the ramp. */
static double step_t(int step, int n) {
  return n > 1 ? (double)(step - 1) / (double)(n - 1) : 0.0;
}

/* Not placed yet at this action (a plan with hands): faint, or in 3D left out. */
static int unplaced(const us_Structure *s, const us_RenderSettings *r, int i) {
  return i >= 0 && r->hand_state && r->hand_state[i] == US_HAND_UNPLACED && !s->bodies[i].fixed;
}

static us_Paint body_paint(const us_Structure *s, const us_RenderSettings *r, const Info *in,
                           int i) {
  if (s->bodies[i].fixed) return hatched(US_HATCH_FIXED);
  if (unplaced(s, r, i)) return solid(kUnplaced);
  if (in->step[i] < 0) return hatched(US_HATCH_BLOCKED);
  if (us_scene_removed(r, in->step, i)) return solid(kWhite); /* gone when it falls */
  if (r->norder > 0 && in->step[i]) return solid(us_ramp(step_t(in->step[i], in->nsteps)));
  return solid(r->norder > 0 ? kLeftOut : kSandstone);
}

/* A failure's mark, else held by a hand. */
static int body_mark(const us_RenderSettings *r, const Info *in, int i) {
  int m = us_scene_mark(r, in->step, i, in->falls);
  return !m && r->hand_state && r->hand_state[i] == US_HAND_HELD ? US_MARK_HELD : m;
}

/* Hand marks (rings) at the held bodies' centres of mass, around their
 * labels, sized from the dots; in 3D only where no nearer body covers the
 * ring (src/render/depth3.c). */
static void put_hands(us_Scene *sc, const View *v, const us_Structure *s,
                      const us_RenderSettings *r) {
  sc->hand_color = kHand;
  sc->hand_r = US_MAX(7.0, 6.0 * sc->dot_r);
  for (int i = 0; i < s->nbody; i++)
    if (r->hand_state[i] == US_HAND_HELD && !s->bodies[i].fixed) {
      const double *c = s->bodies[i].com;
      double p[3] = {c[0], c[1], s->dim == 3 ? c[2] : 0.0};
      double *h = &sc->hands[2 * sc->nhand];
      us_scene_px(v, p, &h[0], &h[1]);
      sc->nhand += !us_depth3_covers_box(sc, i, US_GROUND, h[0], h[1], sc->hand_r + 1.25,
                                         sc->hand_r + 1.25); /* 3D: left out when covered */
    }
}

/* Where a body's label goes: its centre of mass once finalized, else the
 * mean of its vertices. */
static void label_point(const us_Structure *s, int i, double *x, double *y) {
  const us_Body *b = &s->bodies[i];
  if (us_structure_is_finalized(s) || b->nvert == 0) {
    *x = b->com[0];
    *y = b->com[1];
    return;
  }
  *x = *y = 0.0;
  for (int k = 0; k < b->nvert; k++) *x += b->verts[2 * k], *y += b->verts[2 * k + 1];
  *x /= (double)b->nvert;
  *y /= (double)b->nvert;
}

/* Step number or id (in->labels), when it fits. */
static void body_label(us_SceneBody *sb, const View *v, const us_Structure *s,
                       const us_RenderSettings *r, const Info *in) {
  const us_Body *b = &s->bodies[sb->body];
  if (unplaced(s, r, sb->body)) return;
  int step = in->step[sb->body], numbered = in->labels == US_LABELS_STEPS && step > 0;
  if (!numbered && in->labels != US_LABELS_IDS) return;
  snprintf(sb->num, sizeof sb->num, "%d", step);
  const char *text = numbered ? sb->num : b->id;
  int light = us_rgb_lightness(sb->paint.fill) < 0.6 && sb->paint.hatch < 0;
  if (s->dim == 3) { /* placed and sized by us_scene3_bodies */
    sb->label = (us_SceneText){text, 0, 0, 0, 0, 1, 0, light ? kWhite : kBlack};
    return;
  }
  double fs = label_size(v, b, strlen(text)), x, y;
  if (fs <= 0) return;
  label_point(s, sb->body, &x, &y);
  sb->label = (us_SceneText){text, px_x(v, x), px_y(v, y), fs, 0, 1, 0, light ? kWhite : kBlack};
}

/* 3D: paints and label texts per body, then the faces (scene3.c); 1 on
 * out of memory. */
static int put_bodies3(us_Scene *sc, const View *v, const us_Structure *s,
                       const us_RenderSettings *r, const Info *in) {
  for (int i = 0; i < s->nbody; i++) {
    in->proto[i].body = i;
    in->proto[i].paint = body_paint(s, r, in, i);
    in->proto[i].mark = body_mark(r, in, i);
    in->proto[i].hidden = unplaced(s, r, i);
    body_label(&in->proto[i], v, s, r, in);
  }
  return us_scene3_bodies(sc, v, s, in->proto);
}

static void put_bodies(us_Scene *sc, const View *v, const us_Structure *s,
                       const us_RenderSettings *r, const Info *in) {
  int first = 0;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    us_SceneBody *sb = &sc->bodies[i];
    sb->body = i;
    sb->first = first;
    sb->npt = b->nvert;
    sb->cx = px_x(v, b->com[0]);
    sb->cy = px_y(v, b->com[1]);
    for (int k = 0; k < b->nvert; k++, first++) {
      sc->pts[2 * first] = px_x(v, b->verts[2 * k]);
      sc->pts[2 * first + 1] = px_y(v, b->verts[2 * k + 1]);
    }
    sb->paint = body_paint(s, r, in, i);
    sb->mark = body_mark(r, in, i);
    body_label(sb, v, s, r, in);
  }
  sc->nbody = s->nbody;
}

/* -------------------------------------------------------- dots, arrows */

/* Contact points, but those of bodies not placed yet and (3D) those a
 * body nearer than both touching ones covers. */
static void put_dots(us_Scene *sc, const View *v, const us_Structure *s,
                     const us_RenderSettings *r) {
  for (int c = 0; c < s->ncontact; c++) {
    const us_Contact *k = &s->contacts[c];
    if (unplaced(s, r, k->a) || unplaced(s, r, k->b)) continue;
    double *d = &sc->dots[2 * sc->ndot];
    us_scene_px(v, k->p, &d[0], &d[1]);
    sc->ndot += !us_depth3_covers_box(sc, k->a, k->b, d[0], d[1], sc->dot_r, sc->dot_r);
  }
  sc->dot_color = (us_Rgb){34, 34, 34};
}

static double norm3(const double *a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

/* The arrows' forces: one per contact, or one per pair (resultants); in
 * f->ncontact entries of d. The count, or -1 on OOM. */
static int drawn_forces(const us_Structure *s, const us_RenderSettings *r, us_DrawnForce *d) {
  const us_Forces *f = r->forces;
  if (r->force_resultants) return us_drawn_resultants(s, f, d);
  for (int k = 0; f && k < f->ncontact; k++) us_drawn_force(s, f, k, &d[k]);
  return f ? f->ncontact : 0;
}

/* Largest finite part (normal or friction) of the n drawn forces (0: none). */
static double force_max(const us_DrawnForce *d, int n) {
  double fmax = 0.0;
  for (int k = 0; k < n; k++) {
    double a = norm3(d[k].normal), b = norm3(d[k].friction);
    if (isfinite(a) && isfinite(b)) fmax = US_MAX(fmax, US_MAX(a, b));
  }
  return fmax;
}

/* One arrow of force d from p along fv (kind 0 normal, 1 friction); under
 * half a pixel (as drawn, after projection) it is left out, and in 3D when
 * a body nearer than both of d's covers it. */
static void put_arrow(us_Scene *sc, const View *v, const us_DrawnForce *d, const double *fv,
                      double scale, unsigned char kind) {
  const double *p = d->p;
  double q[3] = {p[0] + fv[0] * scale, p[1] + fv[1] * scale, p[2] + fv[2] * scale};
  double *a = &sc->arrows[4 * sc->narrow];
  us_scene_px(v, p, &a[0], &a[1]);
  us_scene_px(v, q, &a[2], &a[3]);
  if (hypot(a[2] - a[0], a[3] - a[1]) >= 0.5 &&
      !us_depth3_covers_segment(sc, d->upper, d->lower, a))
    sc->arrow_kind[sc->narrow++] = kind;
}

/* Arrows scaled so the longest part (fmax) is 12% of the view: the normal
 * part, then the friction part, of each drawn force. */
static void put_arrows(us_Scene *sc, const View *v, const us_DrawnForce *d, int n, double fmax) {
  double scale = 0.12 * v->span / fmax;
  for (int k = 0; k < n; k++) {
    if (!isfinite(norm3(d[k].normal)) || !isfinite(norm3(d[k].friction))) continue;
    put_arrow(sc, v, &d[k], d[k].normal, scale, 0);
    put_arrow(sc, v, &d[k], d[k].friction, scale, 1);
  }
}

/* ----------------------------------------------------- title and legend */

/* A line of text in the scene's own buffer. */
static void add_text(us_Scene *sc, double x, double y, double size, int anchor, int bold,
                     const char *text) {
  if (sc->ntext == US_SCENE_TEXTS) return;
  char *buf = sc->text_buf[sc->ntext];
  snprintf(buf, sizeof sc->text_buf[0], "%s", text);
  sc->texts[sc->ntext++] = (us_SceneText){buf, x, y, size, anchor, 0, bold, kBlack};
}

/* The title, its font shrunk (to 8 px at least) so that it fits the width,
 * at about 0.62 em per character of bold sans-serif. */
static void put_title(us_Scene *sc, const char *title) {
  double fit = (sc->w - 20.0) / (0.62 * (double)(strlen(title) ? strlen(title) : 1));
  add_text(sc, 10.0, 18.0, US_MAX(8.0, US_MIN(14.0, fit)), -1, 1, title);
}

/* The legend's lines of text, and where things go. Two columns (the ramp,
 * then the text beside it) when the picture is at least 640 px wide, else
 * the text under the ramp; swatches on a row of their own below. */
static void legend_lines(Legend *lg, const us_Structure *s, const us_RenderSettings *r,
                         const Info *in) {
  char steps[32] = "";
  int n = 0;
  snprintf(lg->line[n++], sizeof lg->line[0], "%d bodies (%d fixed), %d contacts", s->nbody,
           in->nfixed, s->ncontact);
  if (r->norder > 0 && in->nsteps != r->norder) snprintf(steps, sizeof steps, " (%d steps)", in->nsteps);
  if (r->norder > 0 && r->order_builds)
    snprintf(lg->line[n++], sizeof lg->line[0], "%d in the build order%s", r->norder, steps);
  else if (r->norder > 0)
    snprintf(lg->line[n++], sizeof lg->line[0], "%d in the removal order, %d not%s", r->norder,
             s->nbody - in->nfixed - r->norder, steps);
  if (r->failure) us_scene_failure_line(lg->line[n++], sizeof lg->line[0], s, r);
  if (r->hand_state)
    snprintf(lg->line[n++], sizeof lg->line[0], "at this action: %d placed, %d of them held "
             "(hand marks), %d not placed yet (%s)", in->nstate[US_HAND_PLACED] +
             in->nstate[US_HAND_HELD], in->nstate[US_HAND_HELD], in->nstate[US_HAND_UNPLACED],
             s->dim == 3 ? "left out" : "faint");
  if (r->nblocked > 0)
    snprintf(lg->line[n++], sizeof lg->line[0], "%d cannot be removed", r->nblocked);
  if (in->fmax > 0) {
    snprintf(lg->line[n++], sizeof lg->line[0], "arrows: force of the lower body on the upper "
             "one %s: blue normal, orange friction; longest %.4g N",
             r->force_resultants ? "per touching pair" : "at each contact", in->fmax);
    const char *set = r->force_set == US_FORCESET_MARGIN     ? "the largest smallest normal force"
                      : r->force_set == US_FORCESET_MIN_SUM  ? "the least total force"
                      : r->force_set == US_FORCESET_MIN_NORM ? "the least sum of squares"
                                                             : "the solver's";
    snprintf(lg->line[n++], sizeof lg->line[0], "one admissible set of forces (%s; forces are "
             "not unique)", set);
  }
  lg->nline = n;
  lg->ramp = r->norder > 0;
  lg->swatches = (in->nfixed > 0) + (r->nblocked > 0) +
                 ((r->norder > 0 || r->nblocked > 0) && in->nleft > 0);
}

/* Positions relative to the legend's top (y0 = 8 px under the drawing). */
static void legend_layout(Legend *lg, double W) {
  int side = lg->ramp && W >= 640.0;
  double ramp_bottom = lg->ramp ? 30.0 : 0.0;
  lg->text_x = side ? 190.0 : 10.0;
  lg->text_y = side || !lg->ramp ? 10.0 : ramp_bottom + 14.0;
  double text_bottom = lg->text_y + LINE_PX * (lg->nline - 1) + 4.0;
  lg->swatch_y = US_MAX(ramp_bottom, text_bottom) + 6.0;
  lg->height = 8.0 + (lg->swatches ? lg->swatch_y + 12.0 : US_MAX(ramp_bottom, text_bottom)) + 8.0;
}

static double add_swatch(us_Scene *sc, double x, double y, us_Paint p, const char *label) {
  sc->boxes[sc->nbox++] = (us_SceneBox){x, y, 16.0, 12.0, p};
  add_text(sc, x + 22.0, y + 10.0, 11.0, -1, 0, label);
  return x + 22.0 + 6.2 * (double)strlen(label) + 18.0;
}

static void put_swatches(us_Scene *sc, const us_RenderSettings *r, const Info *in, double y) {
  double x = 10.0;
  if (in->nfixed > 0) x = add_swatch(sc, x, y, hatched(US_HATCH_FIXED), "fixed");
  if (r->nblocked > 0) x = add_swatch(sc, x, y, hatched(US_HATCH_BLOCKED), "cannot be removed");
  if (r->norder > 0 && in->nleft > 0) add_swatch(sc, x, y, solid(kLeftOut), "not in the order");
  else if (r->nblocked > 0 && in->nleft > 0) add_swatch(sc, x, y, solid(kSandstone), "buildable");
}

/* The ramp with its ends named (with an order), the lines, swatches. */
static void put_legend(us_Scene *sc, const us_RenderSettings *r, const Info *in) {
  const Legend *lg = &in->legend;
  double y0 = sc->draw_bottom + 8.0;
  if (lg->ramp) {
    sc->has_ramp = 1;
    sc->ramp_box = (us_SceneBox){10.0, y0, 160.0, 12.0, solid(kWhite)};
    for (int i = 0; i < US_RAMP_STOPS; i++) sc->ramp[i] = us_ramp(i / (US_RAMP_STOPS - 1.0));
    add_text(sc, 10.0, y0 + 26.0, 11.0, -1, 0, r->order_builds ? "placed first" : "removed first");
    add_text(sc, 170.0, y0 + 26.0, 11.0, 1, 0, r->order_builds ? "placed last" : "removed last");
  }
  for (int i = 0; i < lg->nline; i++)
    add_text(sc, lg->text_x, y0 + lg->text_y + LINE_PX * i, 11.0, -1, 0, lg->line[i]);
  if (lg->swatches) put_swatches(sc, r, in, y0 + lg->swatch_y);
}

/* ---------------------------------------------------------------- build */

static us_Status alloc_parts(us_Scene *sc, const us_Structure *s, const us_RenderSettings *r,
                             Info *in, us_Error *err) {
  size_t nv = 0, ne = (size_t)s->nbody;
  for (int i = 0; i < s->nbody; i++) nv += (size_t)s->bodies[i].nvert;
  if (s->dim == 3) us_scene3_count(s, &ne, &nv);
  size_t nf = r->forces && r->forces->ncontact > 0 ? (size_t)r->forces->ncontact : 0;
  in->step = us_calloc((size_t)s->nbody + 1, sizeof *in->step);
  in->proto = us_calloc((size_t)s->nbody + 1, sizeof *in->proto);
  sc->bodies = us_calloc(ne + 1, sizeof *sc->bodies);
  sc->lines = us_malloc(4 * US_GRID_LINES * sizeof *sc->lines);
  sc->pts = us_malloc((2 * nv + 1) * sizeof *sc->pts);
  sc->dots = us_malloc((2 * (size_t)s->ncontact + 1) * sizeof *sc->dots);
  sc->arrows = us_malloc((8 * nf + 1) * sizeof *sc->arrows);
  sc->arrow_kind = us_malloc(2 * nf + 1);
  sc->hands = us_malloc((2 * (size_t)s->nbody + 1) * sizeof *sc->hands);
  in->drawn = us_malloc((nf + 1) * sizeof *in->drawn);
  if (in->step && in->proto && sc->bodies && sc->lines && sc->pts && sc->dots && sc->arrows &&
      sc->arrow_kind && sc->hands && in->drawn && !us_scene_alloc_failure(sc, s, r))
    return US_OK;
  return us_error_set(err, US_ERR_NOMEM, "render: out of memory");
}

static us_Status fill_scene(us_Scene *sc, const View *v, const us_Structure *s,
                            const us_RenderSettings *r, const Info *in, us_Error *err) {
  sc->arrow_color = (us_Rgb){31, 78, 156};
  sc->friction_color = (us_Rgb){230, 115, 0};
  sc->arrow_width = 1.5;
  sc->arrow_head = 9.0;
  if (r->title) put_title(sc, r->title);
  int band = s->ground && s->dim == 2; /* 3D: the grid instead */
  sc->ground_y = band ? US_MAX(px_y(v, 0.0), sc->draw_top) : sc->draw_bottom;
  line_sizes(sc, v, s);
  if (s->dim == 3 && put_bodies3(sc, v, s, r, in))
    return us_error_set(err, US_ERR_NOMEM, "render: out of memory");
  if (s->dim == 2) put_bodies(sc, v, s, r, in);
  if (r->show_contacts) put_dots(sc, v, s, r);
  if (in->fmax > 0) put_arrows(sc, v, in->drawn, in->ndrawn, in->fmax);
  if (r->failure) us_scene_mechanism(sc, v, s, r->failure);
  if (r->hand_state) put_hands(sc, v, s, r);
  put_legend(sc, r, in);
  us_depth3_free(sc); /* the order's nodes: only the build needs them */
  return US_OK;
}

/* The bands around the drawing: title and legend. */
static us_Status plan_bands(Info *in, const us_Structure *s, const us_RenderSettings *r,
                            us_Error *err) {
  in->ndrawn = drawn_forces(s, r, in->drawn);
  if (in->ndrawn < 0) return us_error_set(err, US_ERR_NOMEM, "render: out of memory");
  in->fmax = force_max(in->drawn, in->ndrawn);
  in->title_h = r->title ? TITLE_PX : 0.0;
  legend_lines(&in->legend, s, r, in);
  legend_layout(&in->legend, round(r->width_px));
  return US_OK;
}

us_Status us_scene_build(us_Scene *sc, const us_Structure *s, const us_RenderSettings *r,
                         double max_side, double max_pixels, us_Error *err) {
  memset(sc, 0, sizeof *sc);
  Info in = {0};
  View v = {0};
  us_Status st = alloc_parts(sc, s, r, &in, err);
  if (!st) st = check_settings(s, r, &in, err);
  if (!st) st = plan_bands(&in, s, r, err);
  if (!st) st = world_view(s, r, &v, err);
  if (!st) st = fit_view(sc, &v, r, &in, max_side, max_pixels, err);
  if (!st) st = fill_scene(sc, &v, s, r, &in, err);
  us_free(in.step);
  us_free(in.proto);
  us_free(in.drawn);
  if (st) us_scene_free(sc);
  return st;
}

void us_scene_free(us_Scene *sc) {
  us_depth3_free(sc);
  us_free(sc->bodies);
  us_free(sc->pts);
  us_free(sc->dots);
  us_free(sc->arrows);
  us_free(sc->arrow_kind);
  us_free(sc->lines);
  us_free(sc->mech);
  us_free(sc->ghost_start);
  us_free(sc->ghost_pts);
  us_free(sc->hands);
  memset(sc, 0, sizeof *sc);
}
