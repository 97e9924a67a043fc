/* The PNG writer: a scene (src/render/scene.c) drawn with cairo on an
 * ARGB32 image surface, then encoded as PNG into the caller's stream. It
 * decides nothing about what is drawn; it only spells the scene's shapes
 * in cairo calls, in the SVG writer's order (back to front: ground or the
 * 3D ground grid, bodies (3D: faces in the painter's order, each body's
 * label right after its last face), labels (2D), contact dots, arrows,
 * legend).
 *
 * Colours are the scene's bytes: a solid fill with full alpha lands in the
 * image unchanged, so the pixel inside a body is exactly its scene colour
 * (and the SVG's). Hatches are drawn as lines clipped to the shape, on a
 * lattice anchored at the page's origin so neighbouring bodies' lines
 * continue into each other. Text uses cairo's "toy" font API with the
 * system's sans-serif face; user text is cleaned to valid UTF-8 without
 * control characters first (cairo refuses invalid UTF-8 and would put the
 * whole context in an error state). A cairo error is US_ERR_NOMEM when it
 * ran out of memory, US_ERR_IO when the encoder's writes failed, and
 * otherwise US_ERR_SOLVER (the library failed: none is expected). */
#include "render/render.h"

#include <cairo.h>
#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846

static void set_rgb(cairo_t *cr, us_Rgb c) {
  cairo_set_source_rgb(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0);
}

/* ------------------------------------------------------------- paths */

static void body_path(cairo_t *cr, const us_Scene *sc, const us_SceneBody *b) {
  if (b->npt == 0) {
    cairo_new_sub_path(cr);
    cairo_arc(cr, b->cx, b->cy, US_POINT_BODY_PX, 0.0, 2.0 * PI);
    return;
  }
  const double *p = sc->pts + 2 * b->first;
  cairo_move_to(cr, p[0], p[1]);
  for (int k = 1; k < b->npt; k++) cairo_line_to(cr, p[2 * k], p[2 * k + 1]);
  cairo_close_path(cr);
}

/* Hatch lines over the current clip: direction (cos a, -sin a) on the
 * page, at offsets j * gap along the normal (sin a, cos a). */
static void hatch_lines(cairo_t *cr, const us_Hatch *h) {
  double x0, y0, x1, y1, a = h->angle * (PI / 180.0);
  cairo_clip_extents(cr, &x0, &y0, &x1, &y1);
  double dx = cos(a), dy = -sin(a), nx = sin(a), ny = cos(a);
  double lo = INFINITY, hi = -INFINITY, cx[4] = {x0, x1, x0, x1}, cy[4] = {y0, y0, y1, y1};
  for (int i = 0; i < 4; i++) {
    lo = US_MIN(lo, cx[i] * nx + cy[i] * ny);
    hi = US_MAX(hi, cx[i] * nx + cy[i] * ny);
  }
  double len = (x1 - x0) + (y1 - y0) + 1.0, mx = 0.5 * (x0 + x1), my = 0.5 * (y0 + y1);
  double along = mx * dx + my * dy; /* the lines' points nearest the box centre */
  for (double o = floor(lo / h->gap) * h->gap; o <= hi; o += h->gap) {
    double px = o * nx + along * dx, py = o * ny + along * dy;
    cairo_move_to(cr, px - len * dx, py - len * dy);
    cairo_line_to(cr, px + len * dx, py + len * dy);
  }
  set_rgb(cr, h->line);
  cairo_set_line_width(cr, h->width);
  cairo_stroke(cr);
}

/* Fill the current path with p, keeping the path. */
static void fill_paint(cairo_t *cr, us_Paint p) {
  set_rgb(cr, p.fill);
  if (p.hatch < 0) {
    cairo_fill_preserve(cr);
    return;
  }
  cairo_fill_preserve(cr);
  cairo_save(cr);
  cairo_clip_preserve(cr);
  cairo_path_t *path = cairo_copy_path(cr);
  cairo_new_path(cr);
  hatch_lines(cr, &us_hatches[p.hatch]);
  cairo_restore(cr);
  cairo_new_path(cr);
  cairo_append_path(cr, path);
  cairo_path_destroy(path);
}

/* --------------------------------------------------------------- text */

/* Valid UTF-8 without control characters, at most n - 1 bytes (cut at a
 * character boundary); anything else becomes U+FFFD: malformed bytes, and
 * what cairo refuses besides (UTF-16 surrogates, the noncharacters
 * U+FDD0..U+FDEF and U+xxFFFE, U+xxFFFF). */
static void clean_utf8(const char *in, char *out, size_t n) {
  size_t o = 0;
  while (*in) {
    uint32_t c;
    int k = us_utf8_next(in, &c);
    int ok = c >= 0x20 && c != 0x7F && !(c >= 0x80 && c < 0xA0) && c <= 0x10FFFF &&
             !(c >= 0xD800 && c <= 0xDFFF) && !(c >= 0xFDD0 && c <= 0xFDEF) &&
             (c & 0xFFFE) != 0xFFFE; /* c <= 0x10FFFF also drops US_UTF8_INVALID */
    const char *src = ok ? in : "\xEF\xBF\xBD";
    size_t len = ok ? (size_t)k : 3;
    if (o + len >= n) break;
    memcpy(out + o, src, len);
    o += len;
    in += k;
  }
  out[o] = 0;
}

static void draw_text(cairo_t *cr, const us_SceneText *t) {
  char buf[256];
  clean_utf8(t->text, buf, sizeof buf);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         t->bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, t->size);
  cairo_text_extents_t te;
  cairo_font_extents_t fe;
  cairo_text_extents(cr, buf, &te);
  cairo_font_extents(cr, &fe);
  double x = t->x - 0.5 * (t->anchor + 1) * te.x_advance;
  double y = t->centred ? t->y + 0.5 * (fe.ascent - fe.descent) : t->y;
  set_rgb(cr, t->color);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, buf);
}

/* -------------------------------------------------------------- pieces */

static void draw_ground(cairo_t *cr, const us_Scene *sc) {
  cairo_rectangle(cr, 0, sc->ground_y, sc->w, sc->draw_bottom - sc->ground_y);
  fill_paint(cr, (us_Paint){us_hatches[US_HATCH_GROUND].base, US_HATCH_GROUND});
  cairo_new_path(cr);
  cairo_move_to(cr, 0, sc->ground_y);
  cairo_line_to(cr, sc->w, sc->ground_y);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1.5);
  cairo_stroke(cr);
}

static void draw_grid(cairo_t *cr, const us_Scene *sc) {
  set_rgb(cr, sc->line_color);
  cairo_set_line_width(cr, sc->line_width);
  for (int k = 0; k < sc->nline; k++) {
    cairo_move_to(cr, sc->lines[4 * k], sc->lines[4 * k + 1]);
    cairo_line_to(cr, sc->lines[4 * k + 2], sc->lines[4 * k + 3]);
  }
  cairo_stroke(cr);
}

/* A marked body's outline (failure.c), as the SVG writer's. */
static void mark_stroke(cairo_t *cr, const us_Scene *sc, int mark) {
  static const double dash[2] = {6.0, 3.0};
  set_rgb(cr, mark == US_MARK_HELD ? sc->hand_color : sc->mark_color);
  cairo_set_line_width(cr, US_MAX(2.5, 3.0 * sc->stroke));
  if (mark == US_MARK_STEP) cairo_set_dash(cr, dash, 2, 0.0);
}

static void draw_bodies(cairo_t *cr, const us_Scene *sc) {
  for (int i = 0; i < sc->nbody; i++) {
    const us_SceneBody *b = &sc->bodies[i];
    body_path(cr, sc, b);
    fill_paint(cr, b->paint);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, b->npt ? sc->stroke : 1.0);
    if (b->mark) mark_stroke(cr, sc, b->mark);
    cairo_stroke(cr);
    cairo_set_dash(cr, NULL, 0, 0.0);
    if (sc->labels_in_order && b->label.text) draw_text(cr, &b->label); /* 3D */
  }
  for (int i = 0; !sc->labels_in_order && i < sc->nbody; i++)
    if (sc->bodies[i].label.text) draw_text(cr, &sc->bodies[i].label);
}

static void draw_dots(cairo_t *cr, const us_Scene *sc) {
  set_rgb(cr, sc->dot_color);
  for (int c = 0; c < sc->ndot; c++) {
    cairo_new_sub_path(cr);
    cairo_arc(cr, sc->dots[2 * c], sc->dots[2 * c + 1], sc->dot_r, 0.0, 2.0 * PI);
  }
  cairo_fill(cr);
}

/* A line and a filled head ending at (x2, y2). */
static void draw_arrow(cairo_t *cr, const us_Scene *sc, const double *a) {
  double dx = a[2] - a[0], dy = a[3] - a[1], len = hypot(dx, dy);
  double head = US_MIN(sc->arrow_head, 0.6 * len), ux = dx / len, uy = dy / len;
  double bx = a[2] - head * ux, by = a[3] - head * uy;
  cairo_move_to(cr, a[0], a[1]);
  cairo_line_to(cr, bx, by);
  cairo_stroke(cr);
  cairo_move_to(cr, a[2], a[3]);
  cairo_line_to(cr, bx - 0.5 * head * uy, by + 0.5 * head * ux);
  cairo_line_to(cr, bx + 0.5 * head * uy, by - 0.5 * head * ux);
  cairo_close_path(cr);
  cairo_fill(cr);
}

static void draw_arrows(cairo_t *cr, const us_Scene *sc) {
  cairo_set_line_width(cr, sc->arrow_width);
  for (int k = 0; k < sc->narrow; k++) {
    set_rgb(cr, sc->arrow_kind[k] ? sc->friction_color : sc->arrow_color);
    draw_arrow(cr, sc, &sc->arrows[4 * k]);
  }
}

/* The mechanism (failure.c): dashed ghosts, then the velocity arrows. */
static void draw_mechanism(cairo_t *cr, const us_Scene *sc) {
  static const double dash[2] = {4.0, 3.0};
  set_rgb(cr, sc->mark_color);
  cairo_set_line_width(cr, 1.5);
  cairo_set_dash(cr, dash, 2, 0.0);
  for (int g = 0; g < sc->nghost; g++) {
    for (int k = sc->ghost_start[g]; k < sc->ghost_start[g + 1]; k++)
      cairo_line_to(cr, sc->ghost_pts[2 * k], sc->ghost_pts[2 * k + 1]);
    cairo_close_path(cr);
    cairo_stroke(cr);
  }
  cairo_set_dash(cr, NULL, 0, 0.0);
  for (int k = 0; k < sc->nmech; k++) draw_arrow(cr, sc, &sc->mech[4 * k]);
}

/* Hand marks, as the SVG writer's: rings around the held bodies' labels. */
static void draw_hands(cairo_t *cr, const us_Scene *sc) {
  cairo_set_line_width(cr, 2.5);
  set_rgb(cr, sc->hand_color);
  for (int k = 0; k < sc->nhand; k++) {
    cairo_new_sub_path(cr);
    cairo_arc(cr, sc->hands[2 * k], sc->hands[2 * k + 1], sc->hand_r, 0.0, 2.0 * PI);
  }
  cairo_stroke(cr);
}

static void draw_box(cairo_t *cr, const us_SceneBox *b) {
  cairo_rectangle(cr, b->x, b->y, b->w, b->h);
  fill_paint(cr, b->paint);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 0.5);
  cairo_stroke(cr);
}

/* The ramp strip: a gradient through the scene's stops. */
static void draw_ramp(cairo_t *cr, const us_Scene *sc) {
  const us_SceneBox *b = &sc->ramp_box;
  cairo_pattern_t *g = cairo_pattern_create_linear(b->x, 0, b->x + b->w, 0);
  for (int i = 0; i < US_RAMP_STOPS; i++)
    cairo_pattern_add_color_stop_rgb(g, i / (US_RAMP_STOPS - 1.0), sc->ramp[i].r / 255.0,
                                     sc->ramp[i].g / 255.0, sc->ramp[i].b / 255.0);
  cairo_rectangle(cr, b->x, b->y, b->w, b->h);
  cairo_set_source(cr, g);
  cairo_fill_preserve(cr);
  cairo_pattern_destroy(g);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 0.5);
  cairo_stroke(cr);
}

static void draw_scene(cairo_t *cr, const us_Scene *sc) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  if (sc->ground_y < sc->draw_bottom) draw_ground(cr, sc);
  if (sc->nline) draw_grid(cr, sc);
  draw_bodies(cr, sc);
  if (sc->ndot) draw_dots(cr, sc);
  if (sc->narrow) draw_arrows(cr, sc);
  if (sc->nmech || sc->nghost) draw_mechanism(cr, sc);
  if (sc->nhand) draw_hands(cr, sc);
  if (sc->has_ramp) draw_ramp(cr, sc);
  for (int i = 0; i < sc->nbox; i++) draw_box(cr, &sc->boxes[i]);
  for (int i = 0; i < sc->ntext; i++) draw_text(cr, &sc->texts[i]);
}

/* ------------------------------------------------------------- encode */

static cairo_status_t write_stream(void *closure, const unsigned char *data, unsigned int n) {
  return fwrite(data, 1, n, (FILE *)closure) == n ? CAIRO_STATUS_SUCCESS
                                                  : CAIRO_STATUS_WRITE_ERROR;
}

us_Status us_scene_write_png(FILE *fp, const us_Scene *sc, const char *path, us_Error *err) {
  cairo_surface_t *img =
      cairo_image_surface_create(CAIRO_FORMAT_ARGB32, (int)sc->w, (int)sc->h);
  cairo_t *cr = cairo_create(img);
  draw_scene(cr, sc);
  cairo_status_t cs = cairo_status(cr);
  cairo_destroy(cr);
  if (cs == CAIRO_STATUS_SUCCESS) cs = cairo_surface_write_to_png_stream(img, write_stream, fp);
  cairo_surface_destroy(img);
  if (cs == CAIRO_STATUS_SUCCESS) return US_OK;
  us_Status code = cs == CAIRO_STATUS_WRITE_ERROR  ? US_ERR_IO
                   : cs == CAIRO_STATUS_NO_MEMORY ? US_ERR_NOMEM
                                                  : US_ERR_SOLVER; /* a cairo failure */
  return us_error_set(err, code,
                      "%s: cannot draw the %.0f x %.0f px picture: %s", path, sc->w, sc->h,
                      cairo_status_to_string(cs));
}
