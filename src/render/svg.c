/* The SVG writer: a scene (src/render/scene.c) as SVG text. It decides
 * nothing about what is drawn; it only spells the scene's shapes in SVG.
 *
 * We write SVG ourselves rather than through cairo's SVG surface because
 * the file is meant to be read as well as looked at: every body is a <g>
 * holding a <title> with its id (viewers show it on hover) and one
 * <polygon> (a <circle> for a point body; in 3D a <g> per visible face in
 * the painter's order, a body's label in its last face's <g>, so nearer
 * faces cover it, the ground grid as <line>s in class grid), the groups
 * carry class names
 * (ground, bodies, contacts, forces, legend), hatches are named <pattern>s
 * and arrows share one <marker>; cairo's SVG surface would give glyph
 * outlines and anonymous paths, none of which a test, a script or the
 * HTML viewer could find again. Colours are the scene's bytes, so the SVG
 * and the PNG agree pixel for pixel on every body's fill.
 *
 * Text: ids are user data. Markup characters become entities; characters
 * XML 1.0 cannot hold (controls, U+FFFE, U+FFFF, invalid UTF-8) become
 * U+FFFD, so the document always parses. */
#include "render/render.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* ----------------------------------------------------------- utilities */

/* XML 1.0 can hold tab, LF, CR, U+0020..U+D7FF, U+E000..U+FFFD and
 * U+10000..U+10FFFF, nothing else, not even as a character reference. */
static int xml_char(uint32_t c) {
  return c == 0x9 || c == 0xA || c == 0xD || (c >= 0x20 && c <= 0xD7FF) ||
         (c >= 0xE000 && c <= 0xFFFD) || (c >= 0x10000 && c <= 0x10FFFF);
}

/* User text as XML character data or attribute value. */
static void put_escaped(FILE *fp, const char *s) {
  while (*s) {
    uint32_t c;
    int n = us_utf8_next(s, &c);
    if (c == '&') fputs("&amp;", fp);
    else if (c == '<') fputs("&lt;", fp);
    else if (c == '>') fputs("&gt;", fp);
    else if (c == '"') fputs("&quot;", fp);
    else if (c == '\'') fputs("&apos;", fp);
    else if (c == US_UTF8_INVALID || !xml_char(c)) fputs("\xEF\xBF\xBD", fp);
    else fwrite(s, 1, (size_t)n, fp);
    s += n;
  }
}

static void put_rgb(FILE *fp, us_Rgb c) { fprintf(fp, "#%02x%02x%02x", c.r, c.g, c.b); }

/* fill="..." of a paint: the colour, or its hatch pattern. */
static void put_fill(FILE *fp, us_Paint p) {
  fputs("fill=\"", fp);
  if (p.hatch >= 0) fprintf(fp, "url(#%s)", us_hatches[p.hatch].name);
  else put_rgb(fp, p.fill);
  fputc('"', fp);
}

static void put_text(FILE *fp, const us_SceneText *t) {
  static const char *const anchor[3] = {"start", "middle", "end"};
  fprintf(fp, "<text x=\"%.2f\" y=\"%.2f\" font-size=\"%.1f\"", t->x, t->y, t->size);
  if (t->anchor) fprintf(fp, " text-anchor=\"%s\"", anchor[t->anchor + 1]);
  if (t->centred) fputs(" dominant-baseline=\"central\"", fp);
  if (t->bold) fputs(" font-weight=\"bold\"", fp);
  if (t->color.r || t->color.g || t->color.b) fputs(" fill=\"", fp), put_rgb(fp, t->color),
      fputc('"', fp);
  fputc('>', fp);
  put_escaped(fp, t->text);
  fputs("</text>", fp);
}

/* ------------------------------------------------------------- header */

/* A hatch as a pattern: a gap x gap tile with its base and one line,
 * rotated so the line runs at the hatch's angle (SVG's rotate turns
 * clockwise on the page, and the tile's line is vertical: 90 - angle). */
static void put_pattern(FILE *fp, const us_Hatch *h) {
  fprintf(fp, "<pattern id=\"%s\" width=\"%g\" height=\"%g\" patternUnits=\"userSpaceOnUse\" "
          "patternTransform=\"rotate(%g)\"><rect width=\"%g\" height=\"%g\" fill=\"",
          h->name, h->gap, h->gap, 90.0 - h->angle, h->gap, h->gap);
  put_rgb(fp, h->base);
  fprintf(fp, "\"/><line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"%g\" stroke=\"", h->gap);
  put_rgb(fp, h->line);
  fprintf(fp, "\" stroke-width=\"%g\"/></pattern>\n", h->width);
}

static void put_mech_marker(FILE *fp, const us_Scene *sc) {
  fputs("<marker id=\"mech-arrow\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" "
        "markerWidth=\"6\" markerHeight=\"6\" orient=\"auto\"><path d=\"M0,0 L10,5 L0,10 z\" "
        "fill=\"", fp);
  put_rgb(fp, sc->mark_color);
  fputs("\"/></marker>\n", fp);
}

static void put_header(FILE *fp, const us_Scene *sc) {
  fprintf(fp,
          "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
          "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
          "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\">\n<defs>\n",
          sc->w, sc->h, sc->w, sc->h);
  for (int i = 0; i < US_NHATCH; i++) put_pattern(fp, &us_hatches[i]);
  /* the head is arrow_head px long: 6 marker units of stroke width 1.5 */
  for (int kind = 0; kind < 2; kind++) {
    fprintf(fp, "<marker id=\"arrow%s\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" "
            "markerWidth=\"6\" markerHeight=\"6\" orient=\"auto\"><path d=\"M0,0 L10,5 "
            "L0,10 z\" fill=\"", kind ? "-friction" : "");
    put_rgb(fp, kind ? sc->friction_color : sc->arrow_color);
    fputs("\"/></marker>\n", fp);
  }
  if (sc->nmech) put_mech_marker(fp, sc);
  fputs("<linearGradient id=\"ramp\" x1=\"0\" y1=\"0\" x2=\"1\" y2=\"0\">\n", fp);
  for (int i = 0; sc->has_ramp && i < US_RAMP_STOPS; i++) {
    fprintf(fp, "<stop offset=\"%.3f\" stop-color=\"", i / (US_RAMP_STOPS - 1.0));
    put_rgb(fp, sc->ramp[i]);
    fputs("\"/>\n", fp);
  }
  fputs("</linearGradient>\n</defs>\n", fp);
  fprintf(fp, "<rect x=\"0\" y=\"0\" width=\"%.0f\" height=\"%.0f\" fill=\"white\"/>\n", sc->w,
          sc->h);
}

/* -------------------------------------------------------------- pieces */

static void put_ground(FILE *fp, const us_Scene *sc) {
  double y = sc->ground_y;
  fprintf(fp,
          "<g class=\"ground\"><rect x=\"0\" y=\"%.2f\" width=\"%.0f\" height=\"%.2f\" "
          "fill=\"url(#%s)\"/><line x1=\"0\" y1=\"%.2f\" x2=\"%.0f\" y2=\"%.2f\" "
          "stroke=\"black\" stroke-width=\"1.5\"/></g>\n",
          y, sc->w, sc->draw_bottom - y, us_hatches[US_HATCH_GROUND].name, y, sc->w, y);
}

/* The outline of a marked body (failure.c): thick, in the mark colour;
 * dashed for the failing step's bodies. Closes the element. */
static void put_mark_stroke(FILE *fp, const us_Scene *sc, int mark) {
  fputs(" stroke=\"", fp);
  put_rgb(fp, mark == US_MARK_HELD ? sc->hand_color : sc->mark_color);
  fprintf(fp, "\" stroke-width=\"%.2f\"%s/>", US_MAX(2.5, 3.0 * sc->stroke),
          mark == US_MARK_STEP ? " stroke-dasharray=\"6 3\"" : "");
}

static const char *mark_class(int mark) {
  return mark == US_MARK_FALLS ? "falls" : mark == US_MARK_STEP ? "failing-step"
         : mark == US_MARK_HELD ? "held-body" : "";
}

static void put_shape(FILE *fp, const us_Scene *sc, const us_SceneBody *b) {
  if (b->npt == 0) {
    fprintf(fp, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%g\" ", b->cx, b->cy, US_POINT_BODY_PX);
    put_fill(fp, b->paint);
    if (b->mark) put_mark_stroke(fp, sc, b->mark);
    else fputs(" stroke=\"black\"/>", fp);
    return;
  }
  fputs("<polygon points=\"", fp);
  const double *p = sc->pts + 2 * b->first;
  for (int k = 0; k < b->npt; k++) fprintf(fp, "%s%.2f,%.2f", k ? " " : "", p[2 * k], p[2 * k + 1]);
  fputs("\" ", fp);
  put_fill(fp, b->paint);
  if (b->mark) put_mark_stroke(fp, sc, b->mark);
  else fprintf(fp, " stroke=\"black\" stroke-width=\"%.2f\"/>", sc->stroke);
}

static void put_bodies(FILE *fp, const us_Scene *sc, const us_Structure *s) {
  fputs("<g class=\"bodies\">\n", fp);
  for (int i = 0; i < sc->nbody; i++) {
    const us_SceneBody *b = &sc->bodies[i];
    if (b->mark) fprintf(fp, "<g class=\"%s\"><title>", mark_class(b->mark));
    else fputs("<g><title>", fp);
    put_escaped(fp, s->bodies[b->body].id);
    fputs("</title>", fp);
    put_shape(fp, sc, b);
    if (b->label.text) put_text(fp, &b->label); /* 3D: covered by later faces */
    fputs("</g>\n", fp);
  }
  fputs("</g>\n", fp);
}

static void put_grid(FILE *fp, const us_Scene *sc) {
  fputs("<g class=\"grid\" stroke=\"", fp);
  put_rgb(fp, sc->line_color);
  fprintf(fp, "\" stroke-width=\"%g\">\n", sc->line_width);
  for (int k = 0; k < sc->nline; k++) {
    const double *l = &sc->lines[4 * k];
    fprintf(fp, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>\n", l[0], l[1], l[2],
            l[3]);
  }
  fputs("</g>\n", fp);
}

static void put_dots(FILE *fp, const us_Scene *sc) {
  fputs("<g class=\"contacts\" fill=\"", fp);
  put_rgb(fp, sc->dot_color);
  fputs("\">\n", fp);
  for (int c = 0; c < sc->ndot; c++)
    fprintf(fp, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\"/>\n", sc->dots[2 * c],
            sc->dots[2 * c + 1], sc->dot_r);
  fputs("</g>\n", fp);
}

/* One group per kind: normal parts (class forces), friction parts. */
static void put_arrows(FILE *fp, const us_Scene *sc) {
  for (int kind = 0; kind < 2; kind++) {
    fprintf(fp, "<g class=\"%s\" stroke=\"", kind ? "forces friction" : "forces");
    put_rgb(fp, kind ? sc->friction_color : sc->arrow_color);
    fprintf(fp, "\" stroke-width=\"%g\">\n", sc->arrow_width);
    for (int k = 0; k < sc->narrow; k++) {
      const double *a = &sc->arrows[4 * k];
      if (sc->arrow_kind[k] == kind)
        fprintf(fp, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" "
                "marker-end=\"url(#arrow%s)\"/>\n",
                a[0], a[1], a[2], a[3], kind ? "-friction" : "");
    }
    fputs("</g>\n", fp);
  }
}

static void put_box(FILE *fp, const us_SceneBox *b, const char *fill) {
  fprintf(fp, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" ", b->x, b->y, b->w,
          b->h);
  if (fill) fprintf(fp, "fill=\"%s\"", fill);
  else put_fill(fp, b->paint);
  fputs(" stroke=\"black\" stroke-width=\"0.5\"/>\n", fp);
}

/* The mechanism (failure.c): velocity arrows and 2D ghosts, dashed. */
static void put_mechanism(FILE *fp, const us_Scene *sc) {
  fputs("<g class=\"mechanism\" fill=\"none\" stroke=\"", fp);
  put_rgb(fp, sc->mark_color);
  fputs("\" stroke-width=\"1.5\">\n", fp);
  for (int g = 0; g < sc->nghost; g++) {
    fputs("<polygon class=\"ghost\" stroke-dasharray=\"4 3\" points=\"", fp);
    for (int k = sc->ghost_start[g]; k < sc->ghost_start[g + 1]; k++)
      fprintf(fp, "%s%.2f,%.2f", k > sc->ghost_start[g] ? " " : "", sc->ghost_pts[2 * k],
              sc->ghost_pts[2 * k + 1]);
    fputs("\"/>\n", fp);
  }
  for (int k = 0; k < sc->nmech; k++) {
    const double *a = &sc->mech[4 * k];
    fprintf(fp, "<line class=\"velocity\" x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" "
            "marker-end=\"url(#mech-arrow)\"/>\n", a[0], a[1], a[2], a[3]);
  }
  fputs("</g>\n", fp);
}

/* Hand marks: a ring in the hand colour around each held body's label. */
static void put_hands(FILE *fp, const us_Scene *sc) {
  fputs("<g class=\"hands\" fill=\"none\" stroke=\"", fp);
  put_rgb(fp, sc->hand_color);
  fputs("\" stroke-width=\"2.5\">\n", fp);
  for (int k = 0; k < sc->nhand; k++)
    fprintf(fp, "<circle class=\"held\" cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\"/>\n",
            sc->hands[2 * k], sc->hands[2 * k + 1], sc->hand_r);
  fputs("</g>\n", fp);
}

/* Title and legend: the ramp strip, swatches, lines of text. */
static void put_texts(FILE *fp, const us_Scene *sc) {
  fputs("<g class=\"legend\">\n", fp);
  if (sc->has_ramp) put_box(fp, &sc->ramp_box, "url(#ramp)");
  for (int i = 0; i < sc->nbox; i++) put_box(fp, &sc->boxes[i], NULL);
  for (int i = 0; i < sc->ntext; i++) put_text(fp, &sc->texts[i]), fputc('\n', fp);
  fputs("</g>\n", fp);
}

void us_scene_write_svg(FILE *fp, const us_Scene *sc, const us_Structure *s) {
  put_header(fp, sc);
  if (sc->ground_y < sc->draw_bottom) put_ground(fp, sc);
  if (sc->nline) put_grid(fp, sc);
  put_bodies(fp, sc, s);
  if (sc->ndot) put_dots(fp, sc);
  if (sc->narrow) put_arrows(fp, sc);
  if (sc->nmech || sc->nghost) put_mechanism(fp, sc);
  if (sc->nhand) put_hands(fp, sc);
  put_texts(fp, sc);
  fputs("</svg>\n", fp);
}
