/* SVG picture of a structure: bodies, ground, contacts, contact forces and
 * a removal order, written atomically (no partial file on error).
 *
 * Drawing: world coordinates (y up) map to pixels by X = m + (x - x0) k,
 * Y = m + (y1 - y) k (y flipped), with k chosen so the picture is
 * r->width_px wide; the view is the bounding box of all geometry, centres,
 * contacts (and y = 0 with a ground) plus a margin of 6% of its larger
 * side. A legend strip sits under the drawing.
 *
 * Content, back to front: a hatched half-plane under y = 0 when s->ground;
 * bodies as filled polygons (point bodies, without geometry, as circles at
 * their centre), fixed bodies grey and hatched; with an order, each body in
 * it coloured by its removal step on a viridis-like ramp (dark = removed
 * first) and numbered (1 = removed first; with steps of several bodies
 * all bodies of a step share its number), bodies not in it light grey,
 * bodies named as blocked (a plan with status none) light red;
 * without an order, body ids as labels (show_labels); contact points as
 * dots (show_contacts); r->forces as arrows from each contact point along
 * the force on body b of the contact (f_n n + f_t t), the longest 12% of
 * the view's larger side. Every body has a <title> with its id (XML-escaped)
 * so viewers show it on hover; labels and numbers are sized to fit their
 * body and left out when they would be too small to read, and contact dots
 * and outlines thin out with the typical body size, so a wall of a
 * thousand bricks stays legible.
 *
 * Errors: bad settings (order or force indices out of range, repeated
 * bodies in the order, non-positive width) are US_ERR_USAGE and are found
 * before the file is opened; a file that cannot be written is US_ERR_IO. */
#include "core/core.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define LEGEND_PX 56.0

typedef struct View {
  double x0, y1;   /* world left and top edges of the view */
  double k;        /* pixels per world unit */
  double m;        /* pixel margin */
  double w, h;     /* drawing size in pixels (without the legend) */
  double span;     /* larger side of the world view */
  double dot;      /* contact dot radius, pixels */
  double stroke;   /* body outline width, pixels */
} View;

/* ------------------------------------------------------------- colours */

/* Samples of a perceptually uniform ramp (after matplotlib's viridis, at
 * t = 0, 0.1, ..., 1), interpolated linearly. */
static const unsigned char kRamp[11][3] = {
    {68, 1, 84},    {72, 36, 117},  {65, 68, 135},  {53, 95, 141},
    {42, 120, 142}, {33, 145, 140}, {34, 168, 132}, {68, 191, 112},
    {122, 209, 81}, {189, 223, 38}, {253, 231, 37}};

static void ramp(double t, char out[8]) {
  t = t < 0 ? 0 : (t > 1 ? 1 : t);
  double u = t * 10.0;
  int i = (int)floor(u);
  if (i > 9) i = 9;
  double f = u - (double)i;
  int c[3];
  for (int j = 0; j < 3; j++)
    c[j] = (int)lround((1.0 - f) * kRamp[i][j] + f * kRamp[i + 1][j]);
  snprintf(out, 8, "#%02x%02x%02x", c[0], c[1], c[2]);
}

/* Position of removal step `step` (1-based) of n on the ramp. */
static double step_t(int step, int n) { return n > 1 ? (double)(step - 1) / (double)(n - 1) : 0.0; }

/* Steps of the order: its groups, or one body each. */
static int nsteps(const us_RenderSettings *r) { return r->group_start ? r->ngroups : r->norder; }

/* ----------------------------------------------------------- utilities */

/* U+FFFE and U+FFFF (UTF-8 EF BF BE / EF BF BF): valid UTF-8, which the
 * reader accepts, but not XML 1.0 characters. */
static int xml_nonchar(const unsigned char *s) {
  return s[0] == 0xEF && s[1] == 0xBF && (s[2] == 0xBE || s[2] == 0xBF);
}

/* Write s with the five XML special characters escaped; other control
 * characters and U+FFFE/U+FFFF (not allowed in XML 1.0) become '?'. */
static void put_escaped(FILE *fp, const char *s) {
  for (; *s; s++) {
    unsigned char c = (unsigned char)*s;
    if (xml_nonchar((const unsigned char *)s)) {
      fputc('?', fp);
      s += 2;
    } else if (c == '&') fputs("&amp;", fp);
    else if (c == '<') fputs("&lt;", fp);
    else if (c == '>') fputs("&gt;", fp);
    else if (c == '"') fputs("&quot;", fp);
    else if (c == '\'') fputs("&apos;", fp);
    else if (c < 0x20 && c != '\t' && c != '\n' && c != '\r') fputc('?', fp);
    else fputc(c, fp);
  }
}

static double px_x(const View *v, double x) { return v->m + (x - v->x0) * v->k; }
static double px_y(const View *v, double y) { return v->m + (v->y1 - y) * v->k; }

/* Where a body's label goes: its centre of mass once finalized, else the
 * mean of its vertices. */
static void label_point(const us_Structure *s, int i, double *x, double *y) {
  const us_Body *b = &s->bodies[i];
  if (s->finalized || b->nvert == 0) {
    *x = b->com[0];
    *y = b->com[1];
    return;
  }
  *x = *y = 0.0;
  for (int k = 0; k < b->nvert; k++) *x += b->verts[2 * k], *y += b->verts[2 * k + 1];
  *x /= (double)b->nvert;
  *y /= (double)b->nvert;
}

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
 * read: the label is left out, the <title> still names the body). Point
 * bodies get 9 px. */
static double label_size(const View *v, const us_Body *b, size_t len) {
  if (b->nvert == 0) return 9.0;
  double w, h;
  body_extent(v, b, &w, &h);
  double fs = US_MIN(0.45 * h, 16.0);
  fs = US_MIN(fs, 0.9 * w / (0.6 * (double)(len ? len : 1)));
  return fs < 5.0 ? 0.0 : fs;
}

/* Size of the contact dots and body outlines: from the median body's
 * smaller side in pixels, so that dense scenes stay readable. */
static double typical_side(const View *v, const us_Structure *s) {
  double sum = 0.0;
  int n = 0;
  for (int i = 0; i < s->nbody; i++) {
    double w, h;
    body_extent(v, &s->bodies[i], &w, &h);
    if (s->bodies[i].nvert) sum += US_MIN(w, h), n++;
  }
  return n ? sum / n : 40.0;
}

/* --------------------------------------------------------------- checks */

/* Validate r against s; fills step[i] (1-based removal step, 0 if not in
 * the order, -1 when named as blocked). */
static us_Status check_settings(const us_Structure *s, const us_RenderSettings *r, int *step,
                                us_Error *err) {
  if (s->dim != 2)
    return us_error_set(err, US_ERR_USAGE, "render: only 2D structures can be drawn (dim %d)",
                        s->dim);
  if (!(r->width_px > 0) || !isfinite(r->width_px) || r->width_px > 1e6)
    return us_error_set(err, US_ERR_USAGE, "render: width_px must be in (0, 1e6], got %g",
                        r->width_px);
  if (r->norder < 0 || (r->norder > 0 && !r->order))
    return us_error_set(err, US_ERR_USAGE, "render: bad order (%d entries)", r->norder);
  for (int k = 0; k < r->norder; k++) {
    int i = r->order[k];
    if (i < 0 || i >= s->nbody)
      return us_error_set(err, US_ERR_USAGE, "render: order entry %d is body %d, not in 0..%d",
                          k, i, s->nbody - 1);
    if (step[i])
      return us_error_set(err, US_ERR_USAGE, "render: body '%s' appears twice in the order",
                          s->bodies[i].id);
    step[i] = k + 1;
  }
  if (r->group_start) {
    if (r->ngroups < 0 || r->group_start[0] != 0 || r->group_start[r->ngroups] != r->norder)
      return us_error_set(err, US_ERR_USAGE, "render: steps do not cover the order");
    for (int g = 0; g < r->ngroups; g++)
      for (int k = r->group_start[g]; k < r->group_start[g + 1]; k++) step[r->order[k]] = g + 1;
  }
  for (int k = 0; k < r->nblocked; k++) {
    int i = r->blocked ? r->blocked[k] : -1;
    if (i < 0 || i >= s->nbody || step[i])
      return us_error_set(err, US_ERR_USAGE, "render: blocked entry %d is not a body outside "
                          "the order", k);
    step[i] = -1;
  }
  const us_Forces *f = r->forces;
  if (f && (f->ncontact < 0 || (f->ncontact > 0 && (!f->contact || !f->f))))
    return us_error_set(err, US_ERR_USAGE, "render: bad forces (%d contacts)", f->ncontact);
  for (int k = 0; f && k < f->ncontact; k++)
    if (f->contact[k] < 0 || f->contact[k] >= s->ncontact)
      return us_error_set(err, US_ERR_USAGE, "render: force %d names contact %d, not in 0..%d",
                          k, f->contact[k], s->ncontact - 1);
  return US_OK;
}

/* ----------------------------------------------------------------- view */

static void grow_box(double *bb, double x, double y) {
  bb[0] = US_MIN(bb[0], x);
  bb[1] = US_MIN(bb[1], y);
  bb[2] = US_MAX(bb[2], x);
  bb[3] = US_MAX(bb[3], y);
}

static us_Status make_view(const us_Structure *s, double width_px, View *v, us_Error *err) {
  double bb[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    for (int k = 0; k < b->nvert; k++) grow_box(bb, b->verts[2 * k], b->verts[2 * k + 1]);
    if (b->nvert == 0) grow_box(bb, b->com[0], b->com[1]);
  }
  for (int c = 0; c < s->ncontact; c++) grow_box(bb, s->contacts[c].p[0], s->contacts[c].p[1]);
  if (!(bb[0] <= bb[2])) bb[0] = bb[1] = bb[2] = bb[3] = 0.0; /* nothing to draw */
  if (s->ground) grow_box(bb, bb[0], 0.0);
  if (!isfinite(bb[0] + bb[1] + bb[2] + bb[3]))
    return us_error_set(err, US_ERR_INPUT, "render: the structure has non-finite coordinates");
  double span = US_MAX(bb[2] - bb[0], bb[3] - bb[1]);
  if (!(span > 0)) span = 1.0;
  double pad = 0.06 * span;
  v->span = span;
  v->x0 = bb[0] - pad;
  v->y1 = bb[3] + pad;
  v->m = 0.0;
  v->k = width_px / (bb[2] - bb[0] + 2 * pad);
  v->w = width_px;
  v->h = (bb[3] - bb[1] + 2 * pad) * v->k;
  double side = typical_side(v, s);
  v->dot = side * 0.06 < 0.6 ? 0.6 : (side * 0.06 > 2.0 ? 2.0 : side * 0.06);
  v->stroke = side * 0.03 < 0.3 ? 0.3 : (side * 0.03 > 1.0 ? 1.0 : side * 0.03);
  return US_OK;
}

/* --------------------------------------------------------------- pieces */

static void put_header(FILE *fp, const View *v) {
  double H = v->h + LEGEND_PX;
  fprintf(fp,
          "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
          "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
          "viewBox=\"0 0 %.2f %.2f\" font-family=\"sans-serif\">\n",
          v->w, H, v->w, H);
  fputs("<defs>\n"
        "<pattern id=\"hatch\" width=\"8\" height=\"8\" patternUnits=\"userSpaceOnUse\" "
        "patternTransform=\"rotate(45)\"><line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"8\" "
        "stroke=\"#555\" stroke-width=\"1.5\"/></pattern>\n"
        "<pattern id=\"fixed\" width=\"8\" height=\"8\" patternUnits=\"userSpaceOnUse\" "
        "patternTransform=\"rotate(45)\"><rect width=\"8\" height=\"8\" fill=\"#a0a0a0\"/>"
        "<line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"8\" stroke=\"#444\" stroke-width=\"1.5\"/>"
        "</pattern>\n"
        "<marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" markerWidth=\"6\" "
        "markerHeight=\"6\" orient=\"auto\"><path d=\"M0,0 L10,5 L0,10 z\" "
        "fill=\"#d62728\"/></marker>\n",
        fp);
  fputs("<linearGradient id=\"ramp\" x1=\"0\" y1=\"0\" x2=\"1\" y2=\"0\">\n", fp);
  for (int i = 0; i <= 10; i++)
    fprintf(fp, "<stop offset=\"%.1f\" stop-color=\"#%02x%02x%02x\"/>\n", 0.1 * i, kRamp[i][0],
            kRamp[i][1], kRamp[i][2]);
  fputs("</linearGradient>\n</defs>\n", fp);
  fprintf(fp, "<rect x=\"0\" y=\"0\" width=\"%.2f\" height=\"%.2f\" fill=\"white\"/>\n", v->w, H);
}

static void put_ground(FILE *fp, const View *v) {
  double y = px_y(v, 0.0);
  if (y >= v->h) return;
  fprintf(fp,
          "<g class=\"ground\"><rect x=\"0\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" "
          "fill=\"url(#hatch)\"/><line x1=\"0\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" "
          "stroke=\"black\" stroke-width=\"1.5\"/></g>\n",
          y, v->w, v->h - y, y, v->w, y);
}

/* Fill colour of body i: by removal step, fixed, or neutral. */
static void body_fill(const us_Structure *s, const us_RenderSettings *r, const int *step, int i,
                      char out[16]) {
  if (s->bodies[i].fixed) snprintf(out, 16, "url(#fixed)");
  else if (step[i] < 0) snprintf(out, 16, "#e8847a"); /* blocked: cannot be removed */
  else if (r->norder > 0 && step[i]) ramp(step_t(step[i], nsteps(r)), out);
  else if (r->norder > 0) snprintf(out, 16, "#e4e4e4");
  else snprintf(out, 16, "#d9c7a3"); /* sandstone */
}

static void put_shape(FILE *fp, const View *v, const us_Body *b, const char *fill) {
  if (b->nvert == 0) {
    fprintf(fp, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"6\" fill=\"%s\" stroke=\"black\"/>",
            px_x(v, b->com[0]), px_y(v, b->com[1]), fill);
    return;
  }
  fputs("<polygon points=\"", fp);
  for (int k = 0; k < b->nvert; k++)
    fprintf(fp, "%s%.2f,%.2f", k ? " " : "", px_x(v, b->verts[2 * k]),
            px_y(v, b->verts[2 * k + 1]));
  fprintf(fp, "\" fill=\"%s\" stroke=\"black\" stroke-width=\"%.2f\"/>", fill, v->stroke);
}

/* Step number (with an order) or id (labels, no order) at the body, when
 * it fits (label_size). */
static void put_label(FILE *fp, const View *v, const us_Structure *s,
                      const us_RenderSettings *r, const int *step, int i) {
  const us_Body *b = &s->bodies[i];
  int numbered = r->norder > 0 && step[i] > 0;
  if (!numbered && !(r->norder == 0 && r->show_labels)) return;
  char num[16];
  snprintf(num, sizeof num, "%d", step[i]);
  double fs = label_size(v, b, strlen(numbered ? num : b->id)), x, y;
  if (fs <= 0) return;
  label_point(s, i, &x, &y);
  int dark = numbered && step_t(step[i], nsteps(r)) < 0.6;
  fprintf(fp, "<text x=\"%.2f\" y=\"%.2f\" font-size=\"%.1f\" text-anchor=\"middle\" "
          "dominant-baseline=\"central\" fill=\"%s\">", px_x(v, x), px_y(v, y), fs,
          dark ? "white" : "black");
  put_escaped(fp, numbered ? num : b->id);
  fputs("</text>", fp);
}

static void put_bodies(FILE *fp, const View *v, const us_Structure *s,
                       const us_RenderSettings *r, const int *step) {
  fputs("<g class=\"bodies\">\n", fp);
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    char fill[16];
    body_fill(s, r, step, i, fill);
    fputs("<g><title>", fp);
    put_escaped(fp, b->id);
    fputs("</title>", fp);
    put_shape(fp, v, b, fill);
    put_label(fp, v, s, r, step, i);
    fputs("</g>\n", fp);
  }
  fputs("</g>\n", fp);
}

static void put_contacts(FILE *fp, const View *v, const us_Structure *s) {
  fputs("<g class=\"contacts\" fill=\"#222\">\n", fp);
  for (int c = 0; c < s->ncontact; c++)
    fprintf(fp, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\"/>\n", px_x(v, s->contacts[c].p[0]),
            px_y(v, s->contacts[c].p[1]), v->dot);
  fputs("</g>\n", fp);
}

/* Force on body b of contact k of f, in world coordinates. */
static void force_vec(const us_Structure *s, const us_Forces *f, int k, double *fx, double *fy) {
  const us_Contact *c = &s->contacts[f->contact[k]];
  int dim = s->dim > 0 ? s->dim : 2;
  double fn = f->f[dim * k], ft = f->f[dim * k + 1];
  *fx = fn * c->n[0] + ft * c->t[0][0];
  *fy = fn * c->n[1] + ft * c->t[0][1];
}

/* Arrows, scaled so the longest is 12% of the view; returns the largest
 * magnitude (0 when nothing was drawn). */
static double put_forces(FILE *fp, const View *v, const us_Structure *s, const us_Forces *f) {
  double fmax = 0.0, fx, fy;
  for (int k = 0; k < f->ncontact; k++) {
    force_vec(s, f, k, &fx, &fy);
    if (isfinite(fx) && isfinite(fy)) fmax = US_MAX(fmax, hypot(fx, fy));
  }
  if (!(fmax > 0)) return 0.0;
  double scale = 0.12 * v->span / fmax;
  fputs("<g class=\"forces\" stroke=\"#d62728\" stroke-width=\"1.5\">\n", fp);
  for (int k = 0; k < f->ncontact; k++) {
    force_vec(s, f, k, &fx, &fy);
    if (!isfinite(fx) || !isfinite(fy) || hypot(fx, fy) * scale * v->k < 0.5) continue;
    const double *p = s->contacts[f->contact[k]].p;
    fprintf(fp, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" "
            "marker-end=\"url(#arrow)\"/>\n", px_x(v, p[0]), px_y(v, p[1]),
            px_x(v, p[0] + fx * scale), px_y(v, p[1] + fy * scale));
  }
  fputs("</g>\n", fp);
  return fmax;
}

/* Legend strip: the ramp with its ends named (with an order) and counts. */
static void put_legend(FILE *fp, const View *v, const us_Structure *s,
                       const us_RenderSettings *r, double fmax) {
  int nfixed = s->nbody - us_structure_movable_count(s);
  double y = v->h + 8.0, x = 10.0;
  fprintf(fp, "<g class=\"legend\" font-size=\"11\">\n");
  if (r->norder > 0) {
    fprintf(fp, "<rect x=\"%.2f\" y=\"%.2f\" width=\"160\" height=\"12\" fill=\"url(#ramp)\" "
            "stroke=\"black\" stroke-width=\"0.5\"/>\n", x, y);
    fprintf(fp, "<text x=\"%.2f\" y=\"%.2f\">removed first</text>\n", x, y + 26.0);
    fprintf(fp, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"end\">removed last</text>\n",
            x + 160.0, y + 26.0);
    x += 180.0;
  }
  fprintf(fp, "<text x=\"%.2f\" y=\"%.2f\">%d bodies (%d fixed), %d contacts", x, y + 10.0,
          s->nbody, nfixed, s->ncontact);
  if (r->norder > 0)
    fprintf(fp, "; %d in the removal order, %d not", r->norder, s->nbody - nfixed - r->norder);
  if (r->norder > 0 && nsteps(r) != r->norder) fprintf(fp, " (%d steps)", nsteps(r));
  if (r->nblocked > 0)
    fprintf(fp, "; %d cannot be removed (red)", r->nblocked);
  fputs("</text>\n", fp);
  if (fmax > 0)
    fprintf(fp, "<text x=\"%.2f\" y=\"%.2f\">arrows: contact forces on body b of each "
            "contact, longest %.4g N</text>\n", x, y + 26.0, fmax);
  fputs("</g>\n", fp);
}

/* ---------------------------------------------------------------- driver */

us_RenderSettings us_render_default_settings(void) {
  us_RenderSettings r;
  memset(&r, 0, sizeof r);
  r.show_contacts = 1;
  r.show_labels = 1;
  r.width_px = 800.0;
  return r;
}

static void put_all(FILE *fp, const View *v, const us_Structure *s, const us_RenderSettings *r,
                    const int *step) {
  put_header(fp, v);
  if (s->ground) put_ground(fp, v);
  put_bodies(fp, v, s, r, step);
  if (r->show_contacts) put_contacts(fp, v, s);
  double fmax = r->forces ? put_forces(fp, v, s, r->forces) : 0.0;
  put_legend(fp, v, s, r, fmax);
  fputs("</svg>\n", fp);
}

us_Status us_render_svg(const us_Structure *s, const us_RenderSettings *r, const char *path,
                        us_Error *err) {
  us_Error local;
  if (!err) err = &local; /* the steps below read err->code */
  if (!s || !path) return us_error_set(err, US_ERR_USAGE, "render: no structure or no path");
  us_RenderSettings def = us_render_default_settings();
  if (!r) r = &def;
  int *step = us_calloc((size_t)(s->nbody > 0 ? s->nbody : 1), sizeof *step);
  if (!step) return us_error_set(err, US_ERR_NOMEM, "render: out of memory");
  View v = {0};
  us_Status st = check_settings(s, r, step, err);
  if (!st) st = make_view(s, r->width_px, &v, err);
  us_AtomicFile *af = st ? NULL : us_atomic_open(path, err);
  if (!st && !af) st = err->code;
  if (af) {
    put_all((FILE *)us_atomic_stream(af), &v, s, r, step);
    st = us_atomic_commit(af, err);
  }
  us_free(step);
  return st;
}
