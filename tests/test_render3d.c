/* Tests of the 3D pictures (src/render/scene3.c): axonometric PNG and SVG
 * of boxes, decoded again with cairo.
 *
 * Where to look is computed here, independently of the renderer: the view
 * direction by rotating the front view (looking along +y, x right, z up)
 * down by the elevation about x, then about z by the azimuth, and the
 * picture's fit from the documented rule (bounding box of the projected
 * vertices plus 6% of its larger side, scaled to the width; no ground, no
 * title, so no grid and no bands above the drawing). Checks: the top face
 * of a tower's top box is, at its projected centre, exactly the ramp colour
 * of its step, and its two visible sides are that colour times one factor
 * each (shading is a pure lightness factor), the side towards the picture's
 * left the lighter, and only the faces turned to the viewer are drawn
 * (three of each box); with one box straight in front of another along the
 * view, the nearer box's colour wins at the overlap, whichever order the
 * bodies are in; the picture is not blank, has its ground grid, and
 * changes with the view; the SVG parses as XML; bad views are refused.
 * Depth order and covered marks: a box hidden behind a nearer one has its
 * faces first in the SVG and no label; a box on the far end of a long beam
 * is drawn over the beam's top face; a hidden contact's dots and arrows, a
 * hidden held body's ring and a hidden mechanism's arrow are left out and
 * drawn from the other side; a cycle of three sticks is drawn, right at two
 * of its three crossings; every failed allocation is US_ERR_NOMEM. */
#define _POSIX_C_SOURCE 200809L
#include "render/render.h"
#include "test.h"
#include "pngread.h"
#include "tmpfiles.h"

#include <cairo.h>
#include <unistd.h>
#ifdef US_HAVE_LIBXML2
#include <libxml/parser.h>
#endif

#define DEG (3.14159265358979323846 / 180.0)

/* ----------------------------------------------------------- the view */

typedef struct Axes {
  double r[3], u[3], e[3];
} Axes;

/* v rotated by a about the x axis, then by b about the z axis. */
static void rot(const double v[3], double a, double b, double out[3]) {
  double y = v[1] * cos(a) - v[2] * sin(a), z = v[1] * sin(a) + v[2] * cos(a), x = v[0];
  out[0] = x * cos(b) - y * sin(b);
  out[1] = x * sin(b) + y * cos(b);
  out[2] = z;
}

/* The front view's right (x), up (z) and toward-the-viewer (-y) axes,
 * tilted down by el (the viewer rises) and turned by az. */
static Axes axes(double az, double el) {
  Axes A;
  const double x[3] = {1, 0, 0}, z[3] = {0, 0, 1}, my[3] = {0, -1, 0};
  rot(x, -el * DEG, az * DEG, A.r);
  rot(z, -el * DEG, az * DEG, A.u);
  rot(my, -el * DEG, az * DEG, A.e);
  return A;
}

static double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Pixel map of the documented fit (no ground, no title). */
typedef struct Fit {
  Axes A;
  double x0, y1, k;
} Fit;

static Fit fit(const us_Structure *s, double az, double el, double width) {
  Fit f = {axes(az, el), INFINITY, -INFINITY, 0};
  double xmax = -INFINITY, ymin = INFINITY;
  for (int i = 0; i < s->nbody; i++)
    for (int p = 0; p < s->bodies[i].npart; p++)
      for (int k = 0; k < s->bodies[i].parts[p].nvert; k++) {
        const double *v = s->bodies[i].parts[p].verts + 3 * k;
        f.x0 = US_MIN(f.x0, dot(v, f.A.r)), xmax = US_MAX(xmax, dot(v, f.A.r));
        ymin = US_MIN(ymin, dot(v, f.A.u)), f.y1 = US_MAX(f.y1, dot(v, f.A.u));
      }
  double pad = 0.06 * US_MAX(xmax - f.x0, f.y1 - ymin);
  f.x0 -= pad, f.y1 += pad;
  f.k = width / (xmax - f.x0 + pad);
  return f;
}

static void to_px(const Fit *f, const double p[3], double *X, double *Y) {
  *X = (dot(p, f->A.r) - f->x0) * f->k;
  *Y = (f->y1 - dot(p, f->A.u)) * f->k;
}

/* ----------------------------------------------------------- structures */

/* Axis-aligned boxes (lo[i], lo[i] + size[i]), ids b0, b1, ...; no ground;
 * box i fixed when bit i of `fixed` is set. */
static us_Structure *boxes_fixed(int n, const double (*lo)[3], const double (*size)[3],
                                 unsigned fixed) {
  us_Error err;
  us_Structure *s = us_structure_new(3);
  s->ground = 0;
  for (int i = 0; i < n; i++) {
    double xyz[24];
    char id[16];
    for (int c = 0; c < 8; c++)
      for (int d = 0; d < 3; d++) xyz[3 * c + d] = lo[i][d] + ((c >> d) & 1) * size[i][d];
    snprintf(id, sizeof id, "b%d", i);
    us_BodyDef def = us_default_body_def();
    def.id = id, def.nvert = 8, def.xyz = xyz, def.fixed = (int)((fixed >> i) & 1u);
    if (us_structure_add_body(s, &def, &err) < 0) return us_structure_free(s), NULL;
  }
  if (us_structure_finalize(s, &err)) return us_structure_free(s), NULL;
  return s;
}

static us_Structure *boxes(int n, const double (*lo)[3], const double (*size)[3]) {
  return boxes_fixed(n, lo, size, 0u);
}

/* ------------------------------------------------------------------ PNG */

static int png_render(Png *p, const us_Structure *s, const us_RenderSettings *r, const char *name) {
  char path[128];
  us_Error err;
  p->img = NULL;
  if (!test_tmp_path(name, path, sizeof path) || us_render_png(s, r, path, &err)) return 0;
  int ok = png_open(p, path);
  remove(path);
  return ok;
}



static us_Rgb pixel_at(const Png *p, const Fit *f, double x, double y, double z) {
  double X, Y, q[3] = {x, y, z};
  to_px(f, q, &X, &Y);
  return pixel(p, X, Y);
}

static int near_rgb(us_Rgb a, us_Rgb b, int tol) {
  return abs(a.r - b.r) <= tol && abs(a.g - b.g) <= tol && abs(a.b - b.b) <= tol;
}

/* The factor f with c = base * f (each byte rounded), or -1 if none: the
 * colour is base made darker or lighter, not another hue. */
static double factor(us_Rgb c, us_Rgb base) {
  int m = US_MAX(base.r, US_MAX(base.g, base.b));
  double f = (m == base.r ? c.r : m == base.g ? c.g : c.b) / (double)m;
  us_Rgb want = {(unsigned char)lround(base.r * f), (unsigned char)lround(base.g * f),
                 (unsigned char)lround(base.b * f)};
  return near_rgb(c, want, 2) ? f : -1.0;
}

/* ---------------------------------------------------------------- cases */

/* A tower of three unit boxes, removed top first: the top box's top face
 * is ramp(0) at its projected centre, its front (-y) and right (+x) sides
 * the same colour darkened, the front (towards the picture's left) less. */
static void tower_top_face(void) {
  const double lo[3][3] = {{0, 0, 0}, {0, 0, 1}, {0, 0, 2}}, sz[3][3] = {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}};
  us_Structure *s = boxes(3, lo, sz);
  CHECK(s != NULL);
  int order[3] = {2, 1, 0};
  us_RenderSettings r = us_render_default_settings();
  r.order = order, r.norder = 3, r.width_px = 400;
  Png png;
  int ok = png_render(&png, s, &r, "tower.png");
  Fit f = fit(s, 35, 25, 400);
  us_Rgb top = pixel_at(&png, &f, 0.5, 0.5, 3.0), want = us_ramp(0.0);
  us_Rgb front = pixel_at(&png, &f, 0.2, 0.0, 2.2), right = pixel_at(&png, &f, 1.0, 0.2, 2.2);
  us_Rgb mid_top = pixel_at(&png, &f, 0.5, 0.5, 2.0); /* hidden under the top box */
  double ff = factor(front, want), fr = factor(right, want);
  fprintf(stderr, "top %d,%d,%d want %d,%d,%d; front f %.3f right f %.3f\n", top.r, top.g,
          top.b, want.r, want.g, want.b, ff, fr);
  char path[128];
  us_Error err;
  int svg_ok = test_tmp_path("tower.svg", path, sizeof path) && !us_render_svg(s, &r, path, &err);
  char *svg = svg_ok ? test_slurp(path) : NULL;
  int npoly = 0; /* three faces of each box turn to a viewer above, in front, right */
  for (const char *q = svg; q && (q = strstr(q, "<polygon")); q++) npoly++;
  remove(path);
  us_free(svg);
  png_close(&png);
  us_structure_free(s);
  CHECK(ok && svg_ok);
  CHECK_INT(npoly, ==, 9);
  CHECK(near_rgb(top, want, 1));
  CHECK(ff > 0.25 && ff < 0.95);
  CHECK(fr > 0.25 && fr < 0.95);
  CHECK(ff > fr + 0.05);
  CHECK(!near_rgb(mid_top, us_ramp(0.5), 8)); /* the middle box's top face is covered */
}

/* Box n(ear) straight in front of box a along the view: at a point of
 * their common silhouette, n's colour (yellow, last step) wins over a's
 * (purple, first), whether n is body 0 or body 1. */
static void nearer_wins(void) {
  Axes A = axes(35, 25);
  for (int nfirst = 0; nfirst < 2; nfirst++) {
    double lo[2][3], sz[2][3] = {{1, 1, 1}, {1, 1, 1}};
    for (int d = 0; d < 3; d++) {
      lo[1 - nfirst][d] = 0.0;                 /* the far box */
      lo[nfirst][d] = 3.0 * A.e[d];            /* the near one */
    }
    us_Structure *s = boxes(2, lo, sz);
    CHECK(s != NULL);
    int order[2] = {1 - nfirst, nfirst}; /* far first (purple), near last (yellow) */
    us_RenderSettings r = us_render_default_settings();
    r.order = order, r.norder = 2, r.width_px = 400;
    Png png;
    int ok = png_render(&png, s, &r, "near.png");
    Fit f = fit(s, 35, 25, 400);
    /* a point of the far box's front face, away from the labels */
    us_Rgb c = pixel_at(&png, &f, 0.25, 0.0, 0.25);
    double fnear = factor(c, us_ramp(1.0)), ffar = factor(c, us_ramp(0.0));
    fprintf(stderr, "near first %d: %d,%d,%d near f %.3f far f %.3f\n", nfirst, c.r, c.g, c.b,
            fnear, ffar);
    png_close(&png);
    us_structure_free(s);
    CHECK(ok);
    CHECK(fnear > 0.25);
    CHECK(ffar < 0);
  }
}

static int ink(const Png *p) {
  int n = 0;
  for (int y = 30; y < p->h; y++)
    for (int x = 0; x < p->w; x++) {
      us_Rgb c = pixel(p, x, y);
      n += c.r < 250 || c.g < 250 || c.b < 250;
    }
  return n;
}

static int differing(const Png *a, const Png *b) {
  int n = 0;
  for (int y = 0; y < US_MIN(a->h, b->h); y++)
    for (int x = 0; x < US_MIN(a->w, b->w); x++) n += !near_rgb(pixel(a, x, y), pixel(b, x, y), 0);
  return n;
}

/* A generated pyramid3d on the ground: not blank, a grid in the SVG
 * (which parses as XML), and another view gives another picture. */
static void pyramid_views(void) {
  us_Error err;
  us_GenSettings g = us_gen_default_settings();
  g.n = 3;
  us_Structure *s = us_gen_pyramid3d(&g, &err);
  CHECK(s != NULL);
  us_RenderSettings r = us_render_default_settings();
  r.title = "pyramid3d";
  Png a, b;
  int oka = png_render(&a, s, &r, "p1.png");
  r.view_az = 120, r.view_el = 50;
  int okb = png_render(&b, s, &r, "p2.png");
  char path[128];
  int svg_ok = test_tmp_path("p.svg", path, sizeof path) && us_render_svg(s, &r, path, &err) == 0;
  char *svg = svg_ok ? test_slurp(path) : NULL;
  int grid = svg && strstr(svg, "<g class=\"grid\"") && strstr(svg, "</text></g>");
#ifdef US_HAVE_LIBXML2
  xmlDocPtr doc = svg_ok ? xmlReadFile(path, NULL, XML_PARSE_NONET | XML_PARSE_NOERROR) : NULL;
  int parses = doc != NULL;
  if (doc) xmlFreeDoc(doc);
#else
  int parses = 0; /* the build must find libxml2 for this case */
#endif
  r.view_el = 91;
  us_Status bad = us_render_svg(s, &r, path, &err);
  int ia = oka ? ink(&a) : 0, diff = oka && okb ? differing(&a, &b) : 0;
  fprintf(stderr, "ink %d of %d, %d pixels differ\n", ia, oka ? a.w * a.h : 0, diff);
  png_close(&a);
  png_close(&b);
  us_free(svg);
  remove(path);
  us_structure_free(s);
  CHECK(oka && okb && svg_ok);
  CHECK(ia > a.w * a.h / 20);
  CHECK(diff > 1000);
  CHECK(grid);
  CHECK(parses);
  CHECK_INT(bad, ==, US_ERR_USAGE);
}

/* 3D: labels by id or step, and an unstable pair's falling body and
 * mechanism arrows in the SVG (no ghosts in 3D). */
static void labels_and_failure(void) {
  us_Error err;
  const double lo[2][3] = {{0, 0, 0}, {0.6, 0, 1}}, size[2][3] = {{1, 1, 1}, {1.2, 1, 0.4}};
  us_Structure *s = boxes(2, lo, size); /* no ground: both fall */
  CHECK(s != NULL);
  us_StabilitySettings set = us_stability_default_settings();
  us_Stability *w = us_stability_new(s, &set, &err);
  us_StabilityResult res;
  us_stability_result_init(&res);
  CHECK(w != NULL);
  CHECK_OK(us_stability_test_full(w, &res, &err), &err);
  int verdict = res.verdict;
  us_RenderFailure f = {0, res.unstable_body, &res.mechanism};
  int order[2] = {1, 0};
  us_RenderSettings r = us_render_default_settings();
  r.order = order, r.norder = 2, r.labels = US_LABELS_IDS, r.failure = &f;
  char path[128];
  int ok = test_tmp_path("fail3.svg", path, sizeof path) && us_render_svg(s, &r, path, &err) == 0;
  char *ids = ok ? test_slurp(path) : NULL;
  r.labels = US_LABELS_STEPS;
  r.failure = NULL;
  ok = ok && us_render_svg(s, &r, path, &err) == 0;
  char *steps = ok ? test_slurp(path) : NULL;
  remove(path);
  us_stability_result_free(&res);
  us_stability_free(w);
  us_structure_free(s);
  CHECK_INT(verdict, ==, US_UNSTABLE);
  CHECK(ids && steps);
  CHECK(strstr(ids, ">b1</text>") && !strstr(ids, ">1</text>"));
  CHECK(strstr(steps, ">1</text>") && strstr(steps, ">2</text>") && !strstr(steps, ">b1</text>"));
  CHECK(strstr(ids, "<g class=\"falls\"><title>") != NULL);
  CHECK(strstr(ids, "class=\"velocity\"") && !strstr(ids, "class=\"ghost\""));
  CHECK(!strstr(steps, "class=\"falls\""));
  us_free(ids), us_free(steps);
}

/* ------------------------------------------------- depth order and marks */

/* The SVG of s under r (us_free it), or NULL. */
static char *svg_of(const us_Structure *s, const us_RenderSettings *r, const char *name) {
  char path[128];
  us_Error err;
  if (!test_tmp_path(name, path, sizeof path) || us_render_svg(s, r, path, &err)) return NULL;
  char *text = test_slurp(path);
  remove(path);
  return text;
}

/* Offset of the first (last: 1) face of body id in the SVG, -1 if none. */
static long title_at(const char *svg, const char *id, int last) {
  char key[64];
  snprintf(key, sizeof key, "<title>%s</title>", id);
  long at = -1;
  for (const char *q = svg; q && (q = strstr(q, key)); q++) {
    at = q - svg;
    if (!last) break;
  }
  return at;
}

/* The faces of body `back` all before those of body `front` in the SVG. */
static int drawn_before(const char *svg, const char *back, const char *front) {
  long b = title_at(svg, back, 1), f = title_at(svg, front, 0);
  return b >= 0 && f >= 0 && b < f;
}

static int occurrences(const char *svg, const char *needle) {
  int n = 0;
  for (const char *q = svg; q && (q = strstr(q, needle)); q++) n++;
  return n;
}

/* A small box b0 straight behind a big one b1 (the near box's inscribed
 * ball covers the small box's circumscribed one in the picture): b0's
 * faces all come before b1's in the SVG, b0's label is left out and b1's
 * is there. From the other side (azimuth + 180) b0 is in front: its faces
 * come after b1's and both labels are drawn. */
static void near_hides_far(void) {
  Axes A = axes(35, 25);
  double lo[2][3], sz[2][3] = {{0.5, 0.5, 0.5}, {3, 3, 3}};
  for (int d = 0; d < 3; d++) {
    lo[0][d] = 0.0;
    lo[1][d] = 0.25 + 5.0 * A.e[d] + 1.0 * A.r[d] - 1.5; /* centre off b0's line of sight by 1 */
  }
  us_Structure *s = boxes(2, lo, sz);
  CHECK(s != NULL);
  us_RenderSettings r = us_render_default_settings();
  r.labels = US_LABELS_IDS, r.width_px = 400;
  char *front = svg_of(s, &r, "hide.svg");
  r.view_az = 215;
  char *back = svg_of(s, &r, "hide2.svg");
  us_structure_free(s);
  CHECK(front && back);
  CHECK(!strstr(front, ">b0</text>"));
  CHECK(strstr(front, ">b1</text>") != NULL);
  CHECK(drawn_before(front, "b0", "b1"));
  CHECK(strstr(back, ">b0</text>") && strstr(back, ">b1</text>"));
  CHECK(drawn_before(back, "b1", "b0"));
  us_free(front), us_free(back);
}

/* A box resting on the far end of a long beam: the beam's top face has its
 * centroid nearer the viewer than any face of the box, yet the box is in
 * front of it where they overlap (the order by centroids got this wrong).
 * The box's faces come after the beam's in the SVG, and in the PNG a point
 * of the box's front face just above the beam has the box's colour (box
 * removed first: ramp 0; beam: ramp 1), not the beam's. */
static void box_on_beam(void) {
  const double lo[2][3] = {{0, 0, 0}, {0, 8, 1}}, sz[2][3] = {{1, 10, 1}, {1, 1, 1}};
  us_Structure *s = boxes(2, lo, sz);
  CHECK(s != NULL);
  int order[2] = {1, 0};
  us_RenderSettings r = us_render_default_settings();
  r.order = order, r.norder = 2, r.width_px = 400, r.show_labels = 0, r.show_contacts = 0;
  Png png;
  int ok = png_render(&png, s, &r, "beam.png");
  Fit f = fit(s, 35, 25, 400);
  us_Rgb c = ok ? pixel_at(&png, &f, 0.5, 8.0, 1.2) : (us_Rgb){0, 0, 0};
  double fbox = factor(c, us_ramp(0.0)), fbeam = factor(c, us_ramp(1.0));
  fprintf(stderr, "box front %d,%d,%d: box f %.3f beam f %.3f\n", c.r, c.g, c.b, fbox, fbeam);
  char *svg = svg_of(s, &r, "beam.svg");
  png_close(&png);
  us_structure_free(s);
  CHECK(ok && svg);
  CHECK(fbox > 0.25);
  CHECK(fbeam < 0);
  CHECK(drawn_before(svg, "b0", "b1"));
  us_free(svg);
}

/* A box b1 on a fixed base b0, both straight behind a big fixed box b2:
 * the contacts' dots and force arrows, b1's hand ring (held) and its label
 * are left out, b2's label is drawn. Seen from the other side (b2 behind
 * them) the dots, arrows, ring and label are all there. */
static void hidden_marks(void) {
  us_Error err;
  Axes A = axes(35, 25);
  double lo[3][3] = {{0, 0, 0}, {0, 0, 0.5}, {0}};
  const double sz[3][3] = {{1, 1, 0.5}, {1, 1, 0.5}, {4, 4, 4}};
  for (int d = 0; d < 3; d++) lo[2][d] = 0.5 + 6.0 * A.e[d] - 2.0;
  us_Structure *s = boxes_fixed(3, lo, sz, 5u);
  CHECK(s != NULL);
  us_StabilitySettings set = us_stability_default_settings();
  us_Stability *w = us_stability_new(s, &set, &err);
  us_StabilityResult res;
  us_stability_result_init(&res);
  CHECK(w != NULL);
  CHECK_OK(us_stability_test_full(w, &res, &err), &err);
  const unsigned char hands[3] = {US_HAND_PLACED, US_HAND_HELD, US_HAND_PLACED};
  us_RenderSettings r = us_render_default_settings();
  r.labels = US_LABELS_IDS, r.width_px = 400, r.forces = &res.forces, r.hand_state = hands;
  char *front = res.verdict == US_STABLE ? svg_of(s, &r, "marks.svg") : NULL;
  r.view_az = 215;
  char *back = res.verdict == US_STABLE ? svg_of(s, &r, "marks2.svg") : NULL;
  int nforce = res.forces.ncontact;
  us_stability_result_free(&res);
  us_stability_free(w);
  us_structure_free(s);
  CHECK(front && back);
  CHECK_INT(nforce, >, 0);
  CHECK_INT(occurrences(front, "marker-end=\"url(#arrow"), ==, 0);
  CHECK(!strstr(front, "class=\"contacts\"") && !strstr(front, "class=\"held\""));
  CHECK(!strstr(front, ">b1</text>") && strstr(front, ">b2</text>"));
  CHECK_INT(occurrences(back, "marker-end=\"url(#arrow"), >, 0);
  CHECK(strstr(back, "class=\"contacts\"") && strstr(back, "class=\"held\""));
  CHECK(strstr(back, ">b1</text>") != NULL);
  us_free(front), us_free(back);
}

/* A box b1 overhanging a fixed base b0 (it tips), both straight behind a
 * big fixed box b2: b1 is marked as falling, its mechanism's velocity
 * arrow is left out (a nearer body covers it); from the other side it is
 * drawn. */
static void hidden_mechanism(void) {
  us_Error err;
  Axes A = axes(35, 25);
  double lo[3][3] = {{0, 0, 0}, {0.6, 0, 0.5}, {0}};
  const double sz[3][3] = {{1, 1, 0.5}, {1.2, 1, 0.3}, {4, 4, 4}};
  for (int d = 0; d < 3; d++) lo[2][d] = 0.6 + 6.0 * A.e[d] - 2.0;
  us_Structure *s = boxes_fixed(3, lo, sz, 5u);
  CHECK(s != NULL);
  us_StabilitySettings set = us_stability_default_settings();
  us_Stability *w = us_stability_new(s, &set, &err);
  us_StabilityResult res;
  us_stability_result_init(&res);
  CHECK(w != NULL);
  CHECK_OK(us_stability_test_full(w, &res, &err), &err);
  us_RenderFailure f = {0, res.unstable_body, &res.mechanism};
  us_RenderSettings r = us_render_default_settings();
  r.width_px = 400, r.failure = &f;
  int unstable = res.verdict == US_UNSTABLE && res.mechanism.nbody > 0;
  char *front = unstable ? svg_of(s, &r, "mech.svg") : NULL;
  r.view_az = 215;
  char *back = unstable ? svg_of(s, &r, "mech2.svg") : NULL;
  us_stability_result_free(&res);
  us_stability_free(w);
  us_structure_free(s);
  CHECK(front && back);
  CHECK(strstr(front, "<g class=\"falls\"><title>b1</title>") != NULL);
  CHECK(!strstr(front, "class=\"velocity\""));
  CHECK(strstr(back, "class=\"velocity\"") != NULL);
  us_free(front), us_free(back);
}

/* Three tilted sticks in a triangle, each lying over the next at a corner
 * (seen from above): a cycle, which no painter's order draws right. The
 * order breaks it at one node: every stick is drawn (its top face), and
 * at two of the three corners the upper stick's colour is on top. */
static void stick_cycle(void) {
  us_Error err;
  us_Structure *s = us_structure_new(3);
  s->ground = 0;
  double V[3][2];
  for (int k = 0; k < 3; k++)
    V[k][0] = 2.0 * cos((90.0 + 120.0 * k) * DEG), V[k][1] = 2.0 * sin((90.0 + 120.0 * k) * DEG);
  for (int i = 0; i < 3; i++) { /* stick i: 0.2 high at V[i], 1.2 at V[i + 1], ends 0.5 beyond */
    const double *a = V[i], *b = V[(i + 1) % 3];
    double d[2] = {b[0] - a[0], b[1] - a[1]}, len = hypot(d[0], d[1]), xyz[24];
    double t[2] = {d[0] / len, d[1] / len}, nrm[2] = {-t[1] * 0.15, t[0] * 0.15};
    for (int c = 0; c < 8; c++) {
      double f = (c & 1) ? 1.0 + 0.5 / len : -0.5 / len, side = (c & 2) ? 1.0 : -1.0;
      xyz[3 * c] = a[0] + f * d[0] + side * nrm[0];
      xyz[3 * c + 1] = a[1] + f * d[1] + side * nrm[1];
      xyz[3 * c + 2] = 0.2 + f * 1.0 + ((c & 4) ? 0.3 : 0.0);
    }
    char id[32];
    snprintf(id, sizeof id, "s%d", i);
    us_BodyDef def = us_default_body_def();
    def.id = id, def.nvert = 8, def.xyz = xyz;
    CHECK(us_structure_add_body(s, &def, &err) >= 0);
  }
  CHECK_OK(us_structure_finalize(s, &err), &err);
  int order[3] = {0, 1, 2}; /* colours ramp 0, 0.5, 1 */
  us_RenderSettings r = us_render_default_settings();
  r.order = order, r.norder = 3, r.width_px = 400, r.view_el = 90, r.view_az = 0;
  r.show_labels = 0, r.show_contacts = 0;
  Png png;
  int ok = png_render(&png, s, &r, "sticks.png"), right = 0;
  char *svg = svg_of(s, &r, "sticks.svg");
  Fit f = fit(s, 0, 90, 400);
  for (int i = 0; ok && i < 3; i++) { /* at corner V[i + 1], stick i is the upper one */
    const double *c = V[(i + 1) % 3];
    us_Rgb px = pixel_at(&png, &f, c[0], c[1], 1.5);
    right += factor(px, us_ramp(0.5 * i)) > 0.25;
    fprintf(stderr, "corner %d: %d,%d,%d, upper stick f %.3f\n", i, px.r, px.g, px.b,
            factor(px, us_ramp(0.5 * i)));
  }
  if (ok) png_close(&png);
  us_structure_free(s);
  CHECK(ok && svg);
  CHECK_INT(occurrences(svg, "<polygon"), ==, 3);
  CHECK_INT(right, ==, 2);
  us_free(svg);
}

/* Every failed allocation while a 3D picture with forces and hands is
 * drawn is US_ERR_NOMEM, writes nothing and leaks nothing (the case's leak
 * check); with enough memory the SVG is written. */
static void out_of_memory(void) {
  us_Error err;
  us_GenSettings g = us_gen_default_settings();
  g.n = 3;
  us_Structure *s = us_gen_pyramid3d(&g, &err);
  CHECK(s != NULL);
  us_StabilitySettings set = us_stability_default_settings();
  us_Stability *w = us_stability_new(s, &set, &err);
  us_StabilityResult res;
  us_stability_result_init(&res);
  CHECK(w != NULL);
  CHECK_OK(us_stability_test_full(w, &res, &err), &err);
  unsigned char hands[14];
  for (int i = 0; i < 14; i++) hands[i] = i == 4 || i == 13 ? US_HAND_HELD : US_HAND_PLACED;
  us_RenderSettings r = us_render_default_settings();
  r.forces = &res.forces, r.hand_state = hands, r.labels = US_LABELS_IDS;
  char path[128];
  test_tmp_path("oom3.svg", path, sizeof path);
  remove(path);
  int nomem_only = 1, done = 0;
  for (long n = 0; n < 2000 && !done; n++) {
    us_alloc_fail_after(n);
    us_Status st = us_render_svg(s, &r, path, &err);
    us_alloc_fail_after(-1);
    if (st && (st != US_ERR_NOMEM || access(path, F_OK) == 0)) nomem_only = 0;
    done = st == US_OK;
  }
  remove(path);
  us_stability_result_free(&res);
  us_stability_free(w);
  us_structure_free(s);
  CHECK(nomem_only);
  CHECK(done);
}

US_TEST_MAIN(T(tower_top_face), T(nearer_wins), T(pyramid_views), T(labels_and_failure),
             T(near_hides_far), T(box_on_beam), T(hidden_marks),
             T(hidden_mechanism), T(stick_cycle), T(out_of_memory))
