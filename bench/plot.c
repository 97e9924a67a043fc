/* Log-log plots of the benchmark's CSV, drawn with cairo into SVG.
 *
 * Input (stdin): one point per line, "series x y" separated by spaces or
 * commas; lines starting with '#' are skipped. Each series gets a colour,
 * its points (and, with --lines, a polyline through them in x order), and
 * a least-squares fit of log y against log x over the points with
 * --fit-from <= x <= --fit-to (default: all), whose slope is the fitted exponent shown
 * in the legend and printed on stdout ("series exponent points").
 *
 * OUT ending in .png: a PNG instead.
 *
 * Usage: plot OUT.svg TITLE XLABEL YLABEL [--lines] [--fit-from X] [--fit-to X]
 *        < points
 */
#include <cairo-svg.h>
#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_SERIES 16
#define PI 3.14159265358979323846
#define PLOT_W 480.0 /* the plotting area; the picture grows around it */
#define PLOT_H 400.0
#define ML 80.0
#define MT 40.0
#define MB 60.0
#define LEGEND_ROW 18.0

typedef struct Series {
  char name[64];
  double *x, *y;
  int n, cap;
  double slope;
  int nfit;
  char label[96]; /* the legend's line */
} Series;

typedef struct Plot {
  Series s[MAX_SERIES];
  int ns;
  double lx0, lx1, ly0, ly1; /* decades spanned (log10) */
  int lines;
  double fit_from, fit_to;
  double w, h, mr; /* picture size and right margin (the legend), from layout */
} Plot;

static const double palette[MAX_SERIES][3] = {
    {0.12, 0.47, 0.71}, {0.84, 0.15, 0.16}, {0.17, 0.63, 0.17}, {0.58, 0.40, 0.74},
    {1.00, 0.50, 0.05}, {0.55, 0.34, 0.29}, {0.89, 0.47, 0.76}, {0.50, 0.50, 0.50},
    {0.74, 0.74, 0.13}, {0.09, 0.75, 0.81}, {0.3, 0.3, 0.9},    {0.9, 0.3, 0.3},
    {0.3, 0.7, 0.3},    {0.6, 0.2, 0.6},    {0.2, 0.2, 0.2},    {0.7, 0.5, 0.1}};

static Series *series_of(Plot *p, const char *name) {
  for (int k = 0; k < p->ns; k++)
    if (!strcmp(p->s[k].name, name)) return &p->s[k];
  if (p->ns == MAX_SERIES) return NULL;
  Series *s = &p->s[p->ns++];
  snprintf(s->name, sizeof s->name, "%s", name);
  return s;
}

static int add_point(Series *s, double x, double y) {
  if (s->n == s->cap) {
    s->cap = s->cap ? 2 * s->cap : 64;
    double *nx = realloc(s->x, (size_t)s->cap * sizeof(double));
    if (!nx) return -1;
    s->x = nx;
    double *ny = realloc(s->y, (size_t)s->cap * sizeof(double));
    if (!ny) return -1;
    s->y = ny;
  }
  s->x[s->n] = x;
  s->y[s->n++] = y;
  return 0;
}

static int read_points(Plot *p) {
  char line[512], name[64];
  while (fgets(line, sizeof line, stdin)) {
    if (line[0] == '#') continue;
    for (char *c = line; *c; c++)
      if (*c == ',') *c = ' ';
    double x, y;
    if (sscanf(line, "%63s %lf %lf", name, &x, &y) != 3) continue;
    if (!(x > 0) || !(y > 0) || !isfinite(x) || !isfinite(y)) continue; /* log axes */
    Series *s = series_of(p, name);
    if (!s || add_point(s, x, y)) return -1;
  }
  return 0;
}

/* Least squares of log y on log x over fit_from <= x <= fit_to. */
static void fit(Plot *p, Series *s) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (int i = 0; i < s->n; i++) {
    if (s->x[i] < p->fit_from || s->x[i] > p->fit_to) continue;
    double lx = log10(s->x[i]), ly = log10(s->y[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, n++;
  }
  double d = n * sxx - sx * sx;
  s->nfit = n;
  s->slope = n >= 2 && fabs(d) > 1e-12 ? (n * sxy - sx * sy) / d : NAN;
}

static void ranges(Plot *p) {
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (int k = 0; k < p->ns; k++)
    for (int i = 0; i < p->s[k].n; i++) {
      x0 = fmin(x0, p->s[k].x[i]), x1 = fmax(x1, p->s[k].x[i]);
      y0 = fmin(y0, p->s[k].y[i]), y1 = fmax(y1, p->s[k].y[i]);
    }
  p->lx0 = floor(log10(x0)), p->lx1 = ceil(log10(x1));
  p->ly0 = floor(log10(y0)), p->ly1 = ceil(log10(y1));
  if (p->lx1 <= p->lx0) p->lx1 = p->lx0 + 1;
  if (p->ly1 <= p->ly0) p->ly1 = p->ly0 + 1;
}

static double px(const Plot *p, double x) {
  return ML + (log10(x) - p->lx0) / (p->lx1 - p->lx0) * (p->w - ML - p->mr);
}
static double py(const Plot *p, double y) {
  return p->h - MB - (log10(y) - p->ly0) / (p->ly1 - p->ly0) * (p->h - MT - MB);
}

static void text_at(cairo_t *cr, double x, double y, const char *t, double align) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, t, &e);
  cairo_move_to(cr, x - align * e.width, y);
  cairo_show_text(cr, t);
}

static void axes(cairo_t *cr, const Plot *p, const char *xl, const char *yl, const char *title) {
  char buf[32];
  cairo_set_line_width(cr, 0.5);
  for (double d = p->lx0; d <= p->lx1; d++) {
    double x = px(p, pow(10, d));
    cairo_set_source_rgb(cr, 0.85, 0.85, 0.85);
    cairo_move_to(cr, x, MT), cairo_line_to(cr, x, p->h - MB), cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    snprintf(buf, sizeof buf, "1e%g", d);
    text_at(cr, x, p->h - MB + 16, buf, 0.5);
  }
  for (double d = p->ly0; d <= p->ly1; d++) {
    double y = py(p, pow(10, d));
    cairo_set_source_rgb(cr, 0.85, 0.85, 0.85);
    cairo_move_to(cr, ML, y), cairo_line_to(cr, p->w - p->mr, y), cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    snprintf(buf, sizeof buf, "1e%g", d);
    text_at(cr, ML - 6, y + 4, buf, 1.0);
  }
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, ML, MT, p->w - ML - p->mr, p->h - MT - MB);
  cairo_stroke(cr);
  text_at(cr, (ML + p->w - p->mr) / 2, p->h - 18, xl, 0.5);
  text_at(cr, p->w / 2, 24, title, 0.5); /* the layout made room for it */
  cairo_save(cr);
  cairo_translate(cr, 20, (MT + p->h - MB) / 2);
  cairo_rotate(cr, -PI / 2);
  text_at(cr, 0, 0, yl, 0.5);
  cairo_restore(cr);
}

static int by_x(const void *a, const void *b) {
  const double *u = a, *v = b;
  return (u[0] > v[0]) - (u[0] < v[0]);
}

static void draw_series(cairo_t *cr, const Plot *p, const Series *s, int k) {
  cairo_set_source_rgba(cr, palette[k][0], palette[k][1], palette[k][2], 0.8);
  if (p->lines && s->n > 1) {
    double *xy = malloc((size_t)s->n * 2 * sizeof(double));
    if (xy) {
      for (int i = 0; i < s->n; i++) xy[2 * i] = s->x[i], xy[2 * i + 1] = s->y[i];
      qsort(xy, (size_t)s->n, 2 * sizeof(double), by_x);
      cairo_set_line_width(cr, 1.5);
      for (int i = 0; i < s->n; i++) {
        if (i == 0) cairo_move_to(cr, px(p, xy[0]), py(p, xy[1]));
        else cairo_line_to(cr, px(p, xy[2 * i]), py(p, xy[2 * i + 1]));
      }
      cairo_stroke(cr);
      free(xy);
    }
  }
  double r = p->lines ? 3.0 : 1.6;
  for (int i = 0; i < s->n; i++) {
    cairo_arc(cr, px(p, s->x[i]), py(p, s->y[i]), r, 0, 2 * PI);
    cairo_fill(cr);
  }
  double ly = MT + 14 + LEGEND_ROW * k;
  cairo_rectangle(cr, p->w - p->mr + 12, ly - 8, 10, 10);
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  text_at(cr, p->w - p->mr + 28, ly + 1, s->label, 0.0);
}

/* The picture's size from what it must hold: the legend's widest line
 * right of the plot, all its lines within the height, the title across
 * the top (measured with the font the picture uses). */
static void layout(Plot *p, const char *title) {
  cairo_surface_t *sf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
  cairo_t *cr = cairo_create(sf);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 12);
  double widest = 0;
  cairo_text_extents_t e;
  for (int k = 0; k < p->ns; k++) {
    Series *s = &p->s[k];
    char buf[sizeof s->label]; /* then copied: gcc sees name and label in one object */
    if (isfinite(s->slope)) snprintf(buf, sizeof buf, "%s: slope %.2f", s->name, s->slope);
    else snprintf(buf, sizeof buf, "%s", s->name);
    memcpy(s->label, buf, sizeof buf);
    cairo_text_extents(cr, s->label, &e);
    widest = fmax(widest, e.x_advance);
  }
  p->mr = 28 + widest + 16;
  p->w = ML + PLOT_W + p->mr;
  cairo_text_extents(cr, title, &e);
  p->w = fmax(p->w, e.x_advance + 40);
  p->h = fmax(MT + PLOT_H + MB, MT + 14 + LEGEND_ROW * p->ns + MB);
  cairo_destroy(cr);
  cairo_surface_destroy(sf);
}

int main(int argc, char **argv) {
  if (argc < 5) {
    fprintf(stderr, "usage: plot OUT.svg TITLE XLABEL YLABEL [--lines] [--fit-from X] [--fit-to X] < points\n");
    return 2;
  }
  Plot p;
  memset(&p, 0, sizeof p);
  p.fit_to = INFINITY;
  for (int i = 5; i < argc; i++) {
    if (!strcmp(argv[i], "--lines")) p.lines = 1;
    else if (!strcmp(argv[i], "--fit-from") && i + 1 < argc) p.fit_from = atof(argv[++i]);
    else if (!strcmp(argv[i], "--fit-to") && i + 1 < argc) p.fit_to = atof(argv[++i]);
    else return fprintf(stderr, "plot: unknown option %s\n", argv[i]), 2;
  }
  if (read_points(&p)) return fprintf(stderr, "plot: out of memory\n"), 1;
  if (p.ns == 0) return fprintf(stderr, "plot: no points\n"), 1;
  ranges(&p);
  for (int k = 0; k < p.ns; k++) fit(&p, &p.s[k]);
  layout(&p, argv[2]);
  size_t len = strlen(argv[1]);
  int png = len > 4 && !strcmp(argv[1] + len - 4, ".png");
  cairo_surface_t *sf = png ? cairo_image_surface_create(CAIRO_FORMAT_RGB24, (int)p.w, (int)p.h)
                            : cairo_svg_surface_create(argv[1], p.w, p.h);
  cairo_t *cr = cairo_create(sf);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 12);
  axes(cr, &p, argv[3], argv[4], argv[2]);
  for (int k = 0; k < p.ns; k++) {
    draw_series(cr, &p, &p.s[k], k);
    printf("%s %.3f %d\n", p.s[k].name, p.s[k].slope, p.s[k].nfit);
  }
  cairo_destroy(cr);
  if (png) cairo_surface_write_to_png(sf, argv[1]);
  cairo_surface_finish(sf);
  int bad = cairo_surface_status(sf) != CAIRO_STATUS_SUCCESS;
  cairo_surface_destroy(sf);
  for (int k = 0; k < p.ns; k++) free(p.s[k].x), free(p.s[k].y);
  return bad ? 1 : 0;
}
