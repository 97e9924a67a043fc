/* Tests of the SVG import (src/io/svg_*.c, docs/svg.md): every element
 * kind, every transform against coordinates worked out by hand, nested
 * transforms, viewBox and units, the y flip and the ground, relative path
 * commands, curves within their tolerance (measured against the exact
 * curve), unique ids, fixed marks and materials, snapping, skipped
 * elements, the example drawings, bad input with line numbers, and
 * out-of-memory at every allocation. */
#include <stdarg.h>

#include "test.h"

#define PI 3.14159265358979323846
#define SVG_OPEN "<svg xmlns='http://www.w3.org/2000/svg'>\n"
#define SVG(body) SVG_OPEN body "</svg>\n"

static int nwarn;
static char lastwarn[512];

static void count_warning(const char *msg, void *user) {
  (void)user;
  nwarn++;
  snprintf(lastwarn, sizeof lastwarn, "%s", msg);
}

/* Coordinates as in the file's user units, y flipped about y = 0 of the
 * drawing (so y_out = -y), no ground, no snapping: every number below is
 * the hand-computed image of the drawing's coordinates. */
static us_SvgSettings raw(void) {
  us_SvgSettings s = us_svg_default_settings();
  s.unit = "user";
  s.snap = 0;
  s.ground = 0;
  s.ground_at_set = 1;
  s.ground_at = 0;
  s.warn = count_warning;
  return s;
}

static us_Structure *imp(const char *svg, const us_SvgSettings *set, us_SvgInfo *info,
                         us_Error *err) {
  nwarn = 0;
  lastwarn[0] = '\0';
  us_error_clear(err);
  return us_structure_parse_svg(svg, strlen(svg), "t.svg", set, info, err);
}

/* Does body b have a vertex at (x, y)? */
static int has_vertex(const us_Body *b, double x, double y, double tol) {
  for (int k = 0; k < b->nvert; k++)
    if (fabs(b->verts[2 * k] - x) <= tol && fabs(b->verts[2 * k + 1] - y) <= tol) return 1;
  return 0;
}

/* Every point of xy[2n] is a vertex of body `id`, and it has n vertices. */
static int body_is(const us_Structure *s, const char *id, const double *xy, int n, double tol) {
  int i = us_structure_find_body(s, id);
  if (i < 0 || s->bodies[i].nvert != n) {
    fprintf(stderr, "body %s: %s, %d vertices (want %d)\n", id, i < 0 ? "missing" : "found",
            i < 0 ? 0 : s->bodies[i].nvert, n);
    return 0;
  }
  for (int k = 0; k < n; k++)
    if (!has_vertex(&s->bodies[i], xy[2 * k], xy[2 * k + 1], tol)) {
      fprintf(stderr, "body %s: no vertex (%g, %g)\n", id, xy[2 * k], xy[2 * k + 1]);
      for (int j = 0; j < s->bodies[i].nvert; j++)
        fprintf(stderr, "  (%.12g, %.12g)\n", s->bodies[i].verts[2 * j], s->bodies[i].verts[2 * j + 1]);
      return 0;
    }
  return 1;
}

/* Import one element wrapped in an svg and check its single body. */
static int one_body(const char *svg, const double *xy, int n) {
  us_SvgSettings set = raw();
  us_Error err;
  us_Structure *s = imp(svg, &set, NULL, &err);
  if (!s) {
    fprintf(stderr, "import failed: %s\n", err.msg);
    return 0;
  }
  int ok = s->nbody == 1 && body_is(s, s->bodies[0].id, xy, n, 1e-9);
  us_structure_free(s);
  return ok;
}

/* Import that must fail with `code` and a message holding each of the
 * NULL-terminated strings. */
static int fails_with(const char *svg, const us_SvgSettings *set, us_Status code, ...) {
  us_Error err;
  us_Structure *s = imp(svg, set, NULL, &err);
  int ok = !s && err.code == code;
  va_list ap;
  va_start(ap, code);
  for (const char *w; (w = va_arg(ap, const char *)) != NULL;)
    if (!strstr(err.msg, w)) ok = 0;
  va_end(ap);
  if (!ok) fprintf(stderr, "got %s: %s\n", s ? "a structure" : us_status_name(err.code), err.msg);
  us_structure_free(s);
  return ok;
}

/* ------------------------------------------------------------ elements */

static void rect_element(void) {
  double want[] = {1, -2, 4, -2, 4, -7, 1, -7};
  CHECK(one_body(SVG("<rect x='1' y='2' width='3' height='5'/>"), want, 4));
}

static void polygon_element(void) {
  double want[] = {0, 0, 4, 0, 1, -3};
  CHECK(one_body(SVG("<polygon points='0,0 4,0 1,3'/>"), want, 3));
  CHECK(one_body(SVG("<polygon points='0 0,4 0 1 3'/>"), want, 3));
}

static void polyline_closed_or_skipped(void) {
  double want[] = {0, 0, 4, 0, 1, -3};
  CHECK(one_body(SVG("<polyline points='0,0 4,0 1,3 0,0'/>"), want, 3));
  us_SvgSettings set = raw();
  /* an open polyline is skipped with a warning: nothing left to import */
  CHECK(fails_with(SVG("<polyline id='open' points='0,0 4,0 1,3'/>"), &set, US_ERR_INPUT,
                   "no shapes", NULL));
  CHECK_INT(nwarn, ==, 1);
  CHECK(strstr(lastwarn, "t.svg:2: <polyline id='open'>: skipped (an open polyline"));
}

static void path_absolute(void) {
  double want[] = {0, 0, 10, 0, 10, -5, 0, -5};
  CHECK(one_body(SVG("<path d='M 0 0 L 10 0 L 10 5 L 0 5 Z'/>"), want, 4));
  CHECK(one_body(SVG("<path d='M0,0H10V5H0Z'/>"), want, 4));
  /* a path whose last point returns to the first is closed without Z */
  CHECK(one_body(SVG("<path d='M0 0 10 0 10 5 0 5 0 0'/>"), want, 4));
}

static void path_relative(void) {
  double want[] = {2, -1, 12, -1, 12, -6, 2, -6};
  CHECK(one_body(SVG("<path d='m 2,1 h 10 v 5 h -10 z'/>"), want, 4));
  /* implicit lineto after m, numbers packed as SVG allows */
  CHECK(one_body(SVG("<path d='m2 1 10 0 0 5-10 0z'/>"), want, 4));
  CHECK(one_body(SVG("<path d='M2 1l10 0l0 5L2 6z'/>"), want, 4));
  /* after z the current point is the subpath's start: two squares */
  us_SvgSettings set = raw();
  us_Error err;
  us_Structure *s = imp(SVG("<path id='p' d='m 0,0 h 1 v 1 h -1 z m 2,0 h 1 v 1 h -1 z'/>"), &set,
                        NULL, &err);
  CHECK(s);
  double a[] = {0, 0, 1, 0, 1, -1, 0, -1}, b[] = {2, 0, 3, 0, 3, -1, 2, -1};
  int ok = s->nbody == 2 && body_is(s, "p", a, 4, 1e-12) && body_is(s, "p-2", b, 4, 1e-12);
  us_structure_free(s);
  CHECK(ok);
}

static void circle_and_ellipse(void) {
  us_SvgSettings set = raw();
  us_Error err;
  us_Structure *s = imp(SVG("<circle id='c' cx='10' cy='-20' r='5'/>"
                            "<ellipse id='e' cx='30' cy='-20' rx='6' ry='3'/>"), &set, NULL, &err);
  CHECK(s);
  int c = us_structure_find_body(s, "c"), e = us_structure_find_body(s, "e");
  CHECK(c >= 0 && e >= 0);
  const us_Body *bc = &s->bodies[c], *be = &s->bodies[e];
  int ok = bc->nvert >= 16 && be->nvert >= 16;
  for (int k = 0; k < bc->nvert; k++)
    ok &= fabs(hypot(bc->verts[2 * k] - 10, bc->verts[2 * k + 1] - 20) - 5) < 1e-9;
  for (int k = 0; k < be->nvert; k++) {
    double u = (be->verts[2 * k] - 30) / 6, v = (be->verts[2 * k + 1] - 20) / 3;
    ok &= fabs(u * u + v * v - 1) < 1e-9;
  }
  /* an inscribed polygon within the tolerance: area between (1 - 2 f) and 1 of the circle's */
  double area = 0;
  for (int k = 0; k < bc->nvert; k++) {
    int j = (k + 1) % bc->nvert;
    area += bc->verts[2 * k] * bc->verts[2 * j + 1] - bc->verts[2 * j] * bc->verts[2 * k + 1];
  }
  area = fabs(area) / 2;
  ok &= area < PI * 25 && area > PI * 25 * (1 - 2 * set.flatten);
  us_structure_free(s);
  CHECK(ok);
}

/* ----------------------------------------------------------- transforms */

/* The triangle (0,0) (2,0) (0,1) under transform t must land on the
 * drawing points want (y down, as in the file). */
static int transformed(const char *t, const double *want_drawing) {
  char svg[512];
  snprintf(svg, sizeof svg, SVG("<polygon points='0,0 2,0 0,1' transform='%s'/>"), t);
  double want[6];
  for (int k = 0; k < 3; k++) want[2 * k] = want_drawing[2 * k], want[2 * k + 1] = -want_drawing[2 * k + 1];
  int ok = one_body(svg, want, 3);
  if (!ok) fprintf(stderr, "transform '%s'\n", t);
  return ok;
}

static void transform_each_kind(void) {
  double tr[] = {3, 4, 5, 4, 3, 5};
  CHECK(transformed("translate(3 4)", tr));
  double tx[] = {3, 0, 5, 0, 3, 1};
  CHECK(transformed("translate(3)", tx));
  double sc[] = {0, 0, 4, 0, 0, 3};
  CHECK(transformed("scale(2,3)", sc));
  double su[] = {0, 0, 4, 0, 0, 2};
  CHECK(transformed("scale(2)", su));
  /* rotate(90): (x, y) -> (-y, x) */
  double r90[] = {0, 0, 0, 2, -1, 0};
  CHECK(transformed("rotate(90)", r90));
  /* rotate(90, 1, 1): about (1, 1): (x, y) -> (1 - (y - 1), 1 + (x - 1)) */
  double rc[] = {2, 0, 2, 2, 1, 0};
  CHECK(transformed("rotate(90 1 1)", rc));
  /* skewX(45): (x + y, y); skewY(45): (x, y + x) */
  double kx[] = {0, 0, 2, 0, 1, 1};
  CHECK(transformed("skewX(45)", kx));
  double ky[] = {0, 0, 2, 2, 0, 1};
  CHECK(transformed("skewY(45)", ky));
  /* matrix(1 2 3 4 5 6): (x + 3y + 5, 2x + 4y + 6) */
  double mx[] = {5, 6, 7, 10, 8, 10};
  CHECK(transformed("matrix(1,2,3,4,5,6)", mx));
}

static void transform_lists(void) {
  /* the last transform of a list applies first */
  double a[] = {10, 0, 14, 0, 10, 2};
  CHECK(transformed("translate(10 0) scale(2)", a));
  double b[] = {20, 0, 24, 0, 20, 2};
  CHECK(transformed("scale(2) translate(10 0)", b));
  double c[] = {1, 5, 1, 7, 0, 5};
  CHECK(transformed(" translate(1,5) ,rotate(90) ", c));
}

static void nested_groups(void) {
  /* g translate(10 0) > g scale(2) > polygon rotate(90): x -> 10 + 2 * (-y), y -> 2x */
  double want[] = {10, 0, 10, -4, 8, 0};
  CHECK(one_body(SVG("<g transform='translate(10 0)'><g transform='scale(2)'>"
                     "<polygon points='0,0 2,0 0,1' transform='rotate(90)'/></g></g>"),
                 want, 3));
  /* a nested svg: x, y and its viewBox into its width and height */
  double ns[] = {5, -5, 7, -5, 5, -6};
  CHECK(one_body(SVG("<svg x='5' y='5' width='20' height='20' viewBox='0 0 40 40'>"
                     "<polygon points='0,0 4,0 0,2'/></svg>"),
                 ns, 3));
}

/* ------------------------------------------------------- units and ground */

static double body_width(const us_Structure *s, const char *id) {
  const us_Body *b = &s->bodies[us_structure_find_body(s, id)];
  double lo = INFINITY, hi = -INFINITY;
  for (int k = 0; k < b->nvert; k++) lo = fmin(lo, b->verts[2 * k]), hi = fmax(hi, b->verts[2 * k]);
  return hi - lo;
}

static double width_in(const char *svg, const char *unit, double scale) {
  us_SvgSettings set = us_svg_default_settings();
  set.unit = unit;
  set.scale = scale;
  us_Error err;
  us_Structure *s = imp(svg, &set, NULL, &err);
  if (!s) {
    fprintf(stderr, "%s\n", err.msg);
    return NAN;
  }
  double w = body_width(s, "r");
  us_structure_free(s);
  return w;
}

static void units_and_viewbox(void) {
  /* 100 mm over a viewBox 200 wide: a user unit is 0.5 mm */
  const char *mm = "<svg xmlns='http://www.w3.org/2000/svg' width='100mm' height='50mm' "
                   "viewBox='0 0 200 100'><rect id='r' width='10' height='4'/></svg>";
  CHECK_NEAR(width_in(mm, "mm", 1), 5, 1e-12);
  CHECK_NEAR(width_in(mm, "m", 1), 0.005, 1e-15);
  CHECK_NEAR(width_in(mm, "cm", 1), 0.5, 1e-13);
  CHECK_NEAR(width_in(mm, "in", 1), 5 / 25.4, 1e-13);
  CHECK_NEAR(width_in(mm, "user", 1), 10, 0);
  CHECK_NEAR(width_in(mm, "mm", 50), 250, 1e-10); /* a drawing at 1:50 */
  /* no viewBox: user units are px, 96 to the inch */
  const char *px = "<svg xmlns='http://www.w3.org/2000/svg' width='400' height='300'>"
                   "<rect id='r' width='96' height='4'/></svg>";
  CHECK_NEAR(width_in(px, "in", 1), 1, 1e-14);
  CHECK_NEAR(width_in(px, "pt", 1), 72, 1e-12);
  CHECK_NEAR(width_in(px, "px", 1), 96, 1e-12);
  /* lengths with units inside the drawing */
  const char *el = "<svg xmlns='http://www.w3.org/2000/svg'><rect id='r' width='10mm' height='4'/></svg>";
  CHECK_NEAR(width_in(el, "mm", 1), 10, 1e-12);
  /* width in inches, viewBox in tenths */
  const char *in = "<svg xmlns='http://www.w3.org/2000/svg' width='2in' height='1in' "
                   "viewBox='0 0 20 10'><rect id='r' width='5' height='1'/></svg>";
  CHECK_NEAR(width_in(in, "in", 1), 0.5, 1e-14);
  /* preserveAspectRatio none: x and y scaled apart */
  const char *none = "<svg xmlns='http://www.w3.org/2000/svg' width='100mm' height='100mm' "
                     "viewBox='0 0 100 50' preserveAspectRatio='none'>"
                     "<rect id='r' width='10' height='10'/></svg>";
  us_SvgSettings set = us_svg_default_settings();
  set.unit = "mm";
  us_Error err;
  us_Structure *s = imp(none, &set, NULL, &err);
  CHECK(s);
  double want[] = {0, 0, 10, 0, 10, 20, 0, 20};
  int ok = body_is(s, "r", want, 4, 1e-12);
  us_structure_free(s);
  CHECK(ok);
}

static void flip_and_ground(void) {
  /* a small block drawn above a big one: the lowest point is the ground */
  const char *svg = SVG("<rect id='low' x='0' y='20' width='10' height='10'/>"
                        "<rect id='high' x='2' y='14' width='6' height='6'/>");
  us_SvgSettings set = us_svg_default_settings();
  set.unit = "user";
  us_Error err;
  us_Structure *s = imp(svg, &set, NULL, &err);
  CHECK(s);
  double low[] = {0, 0, 10, 0, 10, 10, 0, 10}, high[] = {2, 10, 8, 10, 8, 16, 2, 16};
  int ok = body_is(s, "low", low, 4, 0) && body_is(s, "high", high, 4, 0);
  /* the contacts: low on the ground, high on low */
  ok &= s->ncontact == 4;
  us_structure_free(s);
  CHECK(ok);
  /* --ground-at below the drawing: it floats 5 above */
  set.ground_at_set = 1;
  set.ground_at = 35;
  s = imp(svg, &set, NULL, &err);
  CHECK(s);
  double low5[] = {0, 5, 10, 5, 10, 15, 0, 15};
  ok = body_is(s, "low", low5, 4, 0);
  us_structure_free(s);
  CHECK(ok);
  /* the ground line through the drawing: a body below it */
  set.ground_at = 25;
  CHECK(fails_with(svg, &set, US_ERR_INPUT, "t.svg: ", "'low' is below the ground",
                   "'low' is <rect> at line 2", NULL));
}

/* ------------------------------------------------------------- curves */

/* Largest distance of the dense samples (x, y) of a curve from the
 * polygon boundary of body 0. */
static double max_gap(const us_Structure *s, const double *pts, int n) {
  const us_Body *b = &s->bodies[0];
  double worst = 0;
  for (int i = 0; i < n; i++) {
    double best = INFINITY;
    for (int k = 0; k < b->nvert; k++) {
      int j = (k + 1) % b->nvert;
      double ax = b->verts[2 * k], ay = b->verts[2 * k + 1];
      double ex = b->verts[2 * j] - ax, ey = b->verts[2 * j + 1] - ay;
      double t = ((pts[2 * i] - ax) * ex + (pts[2 * i + 1] - ay) * ey) / (ex * ex + ey * ey);
      t = t < 0 ? 0 : t > 1 ? 1 : t;
      best = fmin(best, hypot(pts[2 * i] - ax - t * ex, pts[2 * i + 1] - ay - t * ey));
    }
    worst = fmax(worst, best);
  }
  return worst;
}

static void curves_within_tolerance(void) {
  /* a cubic dome (0,0) (0,-10) (30,-10) (30,0), closed by its base */
  double flat[] = {1e-2, 1e-3, 1e-4};
  int prev = 0;
  for (int f = 0; f < 3; f++) {
    us_SvgSettings set = raw();
    set.flatten = flat[f];
    us_Error err;
    us_Structure *s = imp(SVG("<path d='M0 0 C 0 -10 30 -10 30 0 Z'/>"), &set, NULL, &err);
    CHECK(s);
    double pts[2 * 2001];
    for (int i = 0; i <= 2000; i++) {
      double t = i / 2000.0, u = 1 - t;
      pts[2 * i] = 3 * u * t * t * 30 + t * t * t * 30;
      pts[2 * i + 1] = 10 * (3 * u * u * t + 3 * u * t * t); /* y flipped */
    }
    double size = hypot(30, 10), gap = max_gap(s, pts, 2001);
    int nv = s->bodies[0].nvert;
    us_structure_free(s);
    CHECK(gap <= flat[f] * size);
    CHECK(gap > 0.05 * flat[f] * size); /* not needlessly fine */
    CHECK(nv > prev);
    prev = nv;
  }
}

static void arc_and_smooth_curves(void) {
  us_SvgSettings set = raw();
  us_Error err;
  /* half a disc of radius 5 on (0,0)-(10,0), bulging up (sweep 1) */
  us_Structure *s = imp(SVG("<path d='M 0 0 A 5 5 0 0 1 10 0 Z'/>"), &set, NULL, &err);
  CHECK(s);
  const us_Body *b = &s->bodies[0];
  int ok = b->nvert > 8;
  double top = -INFINITY;
  for (int k = 0; k < b->nvert; k++) {
    ok &= fabs(hypot(b->verts[2 * k] - 5, b->verts[2 * k + 1]) - 5) < 1e-9;
    top = fmax(top, b->verts[2 * k + 1]);
  }
  us_structure_free(s);
  CHECK(ok);
  CHECK_NEAR(top, 5, 5 * set.flatten);
  /* radii too small are scaled up: the same half disc */
  s = imp(SVG("<path d='M 0 0 a 1 1 0 0 1 10 0 z'/>"), &set, NULL, &err);
  CHECK(s);
  b = &s->bodies[0];
  for (int k = 0; k < b->nvert; k++) ok &= fabs(hypot(b->verts[2 * k] - 5, b->verts[2 * k + 1]) - 5) < 1e-9;
  us_structure_free(s);
  CHECK(ok);
  /* S reflects the previous control point; T likewise for quadratics */
  const char *pairs[][2] = {
      {"M0 0 C 0 -10 10 -10 10 -5 S 20 -10 20 0 Z", "M0 0 C 0 -10 10 -10 10 -5 C 10 0 20 -10 20 0 Z"},
      {"M0 0 Q 5 -10 10 -5 T 20 0 Z", "M0 0 Q 5 -10 10 -5 Q 15 0 20 0 Z"},
      {"M0 0 c 0 -10 10 -10 10 -5 s 10 -5 10 5 z", "M0 0 C 0 -10 10 -10 10 -5 C 10 0 20 -10 20 0 Z"},
      {"M0 0 q 5 -10 10 -5 t 10 5 z", "M0 0 Q 5 -10 10 -5 Q 15 0 20 0 Z"}};
  for (int k = 0; k < 4; k++) {
    char a[200], c[200];
    snprintf(a, sizeof a, SVG("<path id='x' d='%s'/>"), pairs[k][0]);
    snprintf(c, sizeof c, SVG("<path id='x' d='%s'/>"), pairs[k][1]);
    us_Structure *sa = imp(a, &set, NULL, &err), *sc = imp(c, &set, NULL, &err);
    int same = sa && sc && sa->bodies[0].nvert == sc->bodies[0].nvert &&
               body_is(sa, "x", sc->bodies[0].verts, sc->bodies[0].nvert, 1e-9);
    us_structure_free(sa);
    us_structure_free(sc);
    if (!same) fprintf(stderr, "case %d: '%s'\n", k, pairs[k][0]);
    CHECK(same);
  }
}

static void curves_after_transforms(void) {
  /* a circle squashed by scale(1, 0.5) and skewed: still an ellipse's image,
     every vertex on the mapped circle */
  us_SvgSettings set = raw();
  us_Error err;
  us_Structure *s = imp(SVG("<circle cx='0' cy='0' r='4' transform='skewX(30) scale(1 0.5)'/>"),
                        &set, NULL, &err);
  CHECK(s);
  const us_Body *b = &s->bodies[0];
  double t = tan(30 * PI / 180);
  int ok = 1;
  for (int k = 0; k < b->nvert; k++) {
    double y = -b->verts[2 * k + 1], x = b->verts[2 * k] - t * y; /* undo the skew */
    ok &= fabs(hypot(x, 2 * y) - 4) < 1e-9;
  }
  us_structure_free(s);
  CHECK(ok);
}

/* ------------------------------------------------------------ ids, marks */

static void unique_ids(void) {
  us_SvgSettings set = raw();
  us_SvgInfo info;
  us_Error err;
  us_Structure *s = imp(SVG("<rect id='a' x='0' width='1' height='1'/>"
                            "<rect id='a' x='2' width='1' height='1'/>"
                            "<rect x='4' width='1' height='1'/>"
                            "<rect id='ground' x='6' width='1' height='1'/>"
                            "<rect id='a-2' x='8' width='1' height='1'/>"
                            "<polygon points='10,0 11,0 11,1'/>"
                            "<rect x='12' width='1' height='1'/>"
                            "<rect id='' x='14' width='1' height='1'/>"),
                        &set, &info, &err);
  CHECK(s);
  const char *want[] = {"a", "a-3", "rect-1", "ground-2", "a-2", "polygon-1", "rect-2", "rect-3"};
  for (int k = 0; k < 8; k++) {
    int i = us_structure_find_body(s, want[k]);
    if (i != k) fprintf(stderr, "%s: body %d, want %d\n", want[k], i, k);
    CHECK(i == k || (us_structure_free(s), 0));
  }
  CHECK_INT(info.ids_renamed, ==, 2);
  CHECK_INT(info.ids_generated, ==, 4);
  us_structure_free(s);
}

static void fixed_marks(void) {
  us_SvgSettings set = raw();
  us_Error err;
  us_Structure *s = imp(
      "<svg xmlns='http://www.w3.org/2000/svg' "
      "xmlns:inkscape='http://www.inkscape.org/namespaces/inkscape'>"
      "<rect id='c' class='stone Fixed' width='1' height='1'/>"
      "<rect id='d' data-fixed='true' x='2' width='1' height='1'/>"
      "<rect id='dn' data-fixed='false' x='4' width='1' height='1'/>"
      "<rect id='l' inkscape:label='fixed pier' x='6' width='1' height='1'/>"
      "<rect id='ln' inkscape:label='not fixed' x='8' width='1' height='1'/>"
      "<g class='fixed'><g><rect id='g' x='10' width='1' height='1'/></g></g>"
      "<g inkscape:groupmode='layer' inkscape:label='FIXED'><rect id='layer' x='12' width='1' height='1'/></g>"
      "<rect id='cn' class='unfixed' x='14' width='1' height='1'/>"
      "<g id='fixed_1_'><rect id='ai' x='16' width='1' height='1'/></g>"
      "<rect id='fixedness' x='18' width='1' height='1'/>"
      "</svg>",
      &set, NULL, &err);
  CHECK(s);
  const char *fixed[] = {"c", "d", "l", "g", "layer", "ai"}, *movable[] = {"dn", "ln", "cn", "fixedness"};
  int ok = 1;
  for (int k = 0; k < 6; k++) ok &= s->bodies[us_structure_find_body(s, fixed[k])].fixed == 1;
  for (int k = 0; k < 4; k++) ok &= s->bodies[us_structure_find_body(s, movable[k])].fixed == 0;
  us_structure_free(s);
  CHECK(ok);
}

static void materials(void) {
  us_SvgSettings set = raw();
  us_Error err;
  us_Structure *s = imp("<svg xmlns='http://www.w3.org/2000/svg' data-friction='0.7'>"
                        "<g data-density='2' data-friction='0.3'>"
                        "<rect id='a' width='2' height='1'/>"
                        "<rect id='b' x='3' width='1' height='1' data-mass='5' data-friction='infinite'/>"
                        "</g><rect id='c' x='5' width='1' height='1'/></svg>",
                        &set, NULL, &err);
  CHECK(s);
  const us_Body *a = &s->bodies[0], *b = &s->bodies[1], *c = &s->bodies[2];
  CHECK_NEAR(s->friction, 0.7, 0);
  CHECK_NEAR(a->density, 2, 0);
  CHECK_NEAR(a->mass, 4, 1e-12);
  CHECK_NEAR(a->friction, 0.3, 0);
  CHECK(b->mass_given && b->mass == 5 && isinf(b->friction));
  CHECK(c->friction < 0 && c->density == 1);
  us_structure_free(s);
  set.friction = 0.2; /* the option wins over the drawing */
  s = imp("<svg xmlns='http://www.w3.org/2000/svg' data-friction='0.7'><rect width='1' height='1'/></svg>",
          &set, NULL, &err);
  CHECK(s);
  CHECK_NEAR(s->friction, 0.2, 0);
  us_structure_free(s);
  CHECK(fails_with(SVG("<rect data-density='-1' width='1' height='1'/>"), &set, US_ERR_INPUT,
                   "t.svg:2: <rect>: data-density must be a number > 0", NULL));
  CHECK(fails_with(SVG("<rect data-friction='lots' width='1' height='1'/>"), &set, US_ERR_INPUT,
                   "data-friction", NULL));
}

/* ------------------------------------------------------------- snapping */

/* Contacts between bodies i and j (either way). */
static int contacts_between(const us_Structure *s, int i, int j) {
  int n = 0;
  for (int k = 0; k < s->ncontact; k++)
    n += (s->contacts[k].a == i && s->contacts[k].b == j) || (s->contacts[k].a == j && s->contacts[k].b == i);
  return n;
}

static void snapping(void) {
  /* b is drawn 0.004 above a and 0.003 right of its left edge; c floats
     0.002 above the ground beside a */
  const char *svg = SVG("<rect id='a' x='0' y='10' width='10' height='10'/>"
                        "<rect id='b' x='0.003' y='4' width='6' height='5.996'/>"
                        "<rect id='c' x='12' y='10' width='5' height='9.998'/>");
  us_SvgSettings set = us_svg_default_settings();
  set.unit = "user";
  set.snap = 0;
  us_Error err;
  us_SvgInfo info;
  us_Structure *s = imp(svg, &set, &info, &err);
  CHECK(s);
  CHECK_INT(contacts_between(s, 0, 1), ==, 0);
  CHECK_INT(contacts_between(s, US_GROUND, 2), ==, 0);
  CHECK_INT(info.snapped, ==, 0);
  us_structure_free(s);
  /* default: 1e-3 of the smaller diagonal (b: 0.0085, c: 0.0112) */
  set.snap = -1;
  s = imp(svg, &set, &info, &err);
  CHECK(s);
  CHECK_INT(contacts_between(s, 0, 1), ==, 2);
  CHECK_INT(contacts_between(s, US_GROUND, 2), ==, 2);
  /* b's bottom corners moved onto a's top: (0, 10) is a's corner, (6.003, 10) on its edge */
  double b_want[] = {0, 10, 6.003, 10, 6.003, 16, 0.003, 16};
  CHECK(body_is(s, "b", b_want, 4, 1e-12) || (us_structure_free(s), 0));
  CHECK_INT(info.snapped, ==, 4);
  us_structure_free(s);
  /* an absolute tolerance smaller than the gaps snaps nothing */
  set.snap = 0.001;
  s = imp(svg, &set, &info, &err);
  CHECK(s);
  CHECK_INT(info.snapped, ==, 0);
  CHECK_INT(contacts_between(s, 0, 1), ==, 0);
  us_structure_free(s);
  /* one larger than the gaps snaps them, in drawing units whatever the output unit */
  set.snap = 0.005;
  set.unit = "mm";
  s = imp(svg, &set, &info, &err);
  CHECK(s);
  CHECK_INT(contacts_between(s, 0, 1), ==, 2);
  CHECK_INT(contacts_between(s, US_GROUND, 2), ==, 2);
  us_structure_free(s);
}

static void snapping_corners_meet(void) {
  /* four blocks whose corners nearly meet at one point: every corner ends
     on one common point, and the blocks touch along their joints */
  const char *svg = SVG("<rect id='p' x='0' y='10' width='10' height='10'/>"
                        "<rect id='q' x='10.004' y='10.003' width='10' height='9.997'/>"
                        "<rect id='r' x='0.002' y='0' width='9.998' height='9.996'/>"
                        "<rect id='t' x='10.001' y='0' width='10' height='10.002'/>");
  us_SvgSettings set = us_svg_default_settings();
  set.unit = "user";
  us_Error err;
  us_Structure *s = imp(svg, &set, NULL, &err);
  CHECK(s);
  /* the corner of p near (10, 10), within the tolerance (1e-3 x 14.1) */
  const us_Body *p = &s->bodies[0];
  double cx = NAN, cy = NAN;
  for (int k = 0; k < p->nvert; k++)
    if (hypot(p->verts[2 * k] - 10, p->verts[2 * k + 1] - 10) < 0.0142)
      cx = p->verts[2 * k], cy = p->verts[2 * k + 1];
  int ok = !isnan(cx);
  for (int i = 1; i < 4; i++) ok &= has_vertex(&s->bodies[i], cx, cy, 0);
  ok &= contacts_between(s, 0, 2) >= 2 && contacts_between(s, 1, 3) >= 2;
  us_structure_free(s);
  CHECK(ok);
}

/* A thin plank (2000 x 1): its diagonal would allow a 2-unit snap, which
 * would put its top on the ground; the tolerance is capped by a twentieth
 * of its thickness (about 1), with the default and with --snap. */
static void snapping_thin_plank(void) {
  us_SvgSettings set = us_svg_default_settings();
  set.unit = "user";
  const double want[] = {0, 0, 2000, 0, 2000, 1, 0, 1};
  for (int k = 0; k < 2; k++) {
    set.snap = k ? 5 : -1;
    us_SvgInfo info;
    us_Error err;
    us_Structure *s = imp(SVG("<rect id='plank' y='99' width='2000' height='1'/>"), &set, &info, &err);
    if (!s) fprintf(stderr, "%s\n", err.msg);
    CHECK(s);
    CHECK(body_is(s, "plank", want, 4, 0) || (us_structure_free(s), 0));
    CHECK_INT(contacts_between(s, US_GROUND, 0), ==, 2);
    CHECK_INT(info.snapped, ==, 0);
    us_structure_free(s);
  }
  /* drawn 0.02 above the ground line: the bottom snaps down (0.02 <
     0.05 x 0.9995), the top stays */
  set.snap = -1;
  set.ground_at_set = 1;
  set.ground_at = 100;
  us_SvgInfo info;
  us_Error err;
  us_Structure *s = imp(SVG("<rect id='plank' y='98.98' width='2000' height='1'/>"), &set, &info, &err);
  if (!s) fprintf(stderr, "%s\n", err.msg);
  CHECK(s);
  const double lifted[] = {0, 0, 2000, 0, 2000, 1.02, 0, 1.02};
  CHECK(body_is(s, "plank", lifted, 4, 1e-9) || (us_structure_free(s), 0));
  CHECK_INT(info.snapped, ==, 2);
  us_structure_free(s);
}

/* ------------------------------------------------------- skipped elements */

static void skipped_elements(void) {
  us_SvgSettings set = raw();
  us_SvgInfo info;
  us_Error err;
  us_Structure *s = imp(
      "<svg xmlns='http://www.w3.org/2000/svg' xmlns:sodipodi='http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd'>\n"
      "<sodipodi:namedview id='nv'><rect width='9' height='9'/></sodipodi:namedview>\n"
      "<defs><rect id='d' width='9' height='9'/></defs>\n"
      "<clipPath><rect width='9' height='9'/></clipPath>\n"
      "<g style='display:none'><rect width='9' height='9'/></g>\n"
      "<rect display='none' width='9' height='9'/>\n"
      "<g visibility='hidden'><rect id='h' width='9' height='9'/>"
      "<rect id='v' visibility='visible' width='1' height='1'/></g>\n"
      "<text x='0' y='0'>label</text><image width='4' height='4'/><line x2='5' y2='5'/>\n"
      "<use href='#d'/><title>t</title><desc>d</desc>\n"
      "<rect id='kept' x='3' width='1' height='1'/>\n"
      "</svg>",
      &set, &info, &err);
  CHECK(s);
  CHECK_INT(s->nbody, ==, 2);
  CHECK(us_structure_find_body(s, "kept") >= 0 && us_structure_find_body(s, "v") >= 0);
  CHECK_INT(info.skipped, ==, 7); /* g, rect, hidden rect, text, image, line, use */
  CHECK_INT(nwarn, ==, 7);
  CHECK(strstr(lastwarn, "t.svg:9: <use>: skipped"));
  us_structure_free(s);
}

static void rounded_rect_warns(void) {
  us_SvgSettings set = raw();
  us_SvgInfo info;
  us_Error err;
  us_Structure *s = imp(SVG("<rect id='r' rx='1' width='4' height='4'/>"), &set, &info, &err);
  CHECK(s);
  CHECK_INT(s->bodies[0].nvert, ==, 4);
  CHECK_INT(nwarn, ==, 1);
  CHECK_INT(info.skipped, ==, 0);
  CHECK(strstr(lastwarn, "rounded corners"));
  us_structure_free(s);
}

/* Adobe Illustrator 10's export: the SVG namespace and the styles come
 * through internal entities, layers are groups named by id. */
static void illustrator_entities(void) {
  const char *svg =
      "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
      "<!DOCTYPE svg PUBLIC \"-//W3C//DTD SVG 1.0//EN\" "
      "\"http://www.w3.org/TR/2001/REC-SVG-20010904/DTD/svg10.dtd\" [\n"
      "  <!ENTITY ns_svg \"http://www.w3.org/2000/svg\">\n"
      "  <!ENTITY st0 \"fill:#C8B88A;display:inline\">\n"
      "  <!ENTITY hide \"display:none\">\n"
      "]>\n"
      "<svg version=\"1.0\" id=\"Layer_1\" xmlns=\"&ns_svg;\" width=\"200px\" height=\"100px\"\n"
      "  viewBox=\"0 0 200 100\" xml:space=\"preserve\">\n"
      "<g id=\"fixed\"><rect x=\"10\" y=\"80\" style=\"&st0;\" width=\"180\" height=\"20\"/></g>\n"
      "<g id=\"blocks\"><rect id=\"_x31_\" x=\"50\" y=\"50\" style=\"&st0;\" width=\"40\" height=\"30\"/>\n"
      "<path style=\"&hide;\" d=\"M100,80h40V50h-40V80z\"/></g>\n"
      "</svg>\n";
  us_SvgSettings set = us_svg_default_settings();
  set.unit = "px";
  set.warn = count_warning;
  us_Error err;
  us_SvgInfo info;
  us_Structure *s = imp(svg, &set, &info, &err);
  if (!s) fprintf(stderr, "%s\n", err.msg);
  CHECK(s);
  int n = s->nbody, fixed = s->bodies[0].fixed;
  double want[] = {50, 20, 90, 20, 90, 50, 50, 50};
  int ok = body_is(s, "_x31_", want, 4, 1e-12);
  us_structure_free(s);
  CHECK_INT(n, ==, 2);
  CHECK(fixed && ok);
  CHECK_INT(nwarn, ==, 1); /* the path hidden through its style entity */
  CHECK_INT((long)info.entity_bytes, ==, 2 * (27 + 1) + 12 + 1); /* st0 twice, hide once: each + 1 */
}

/* An internal entity of `size` bytes referenced `refs` times in the class
 * of each of `rects` rects (line 4 on): the text, us_malloc'ed. */
static char *entity_bomb(size_t size, int refs, int rects) {
  size_t cap = size + (size_t)rects * ((size_t)refs * 4 + 80) + 256, len = 0;
  char *t = us_malloc(cap);
  len += (size_t)snprintf(t, cap, "<?xml version='1.0'?>\n<!DOCTYPE svg [<!ENTITY e '");
  memset(t + len, 'x', size);
  len += size;
  len += (size_t)snprintf(t + len, cap - len, "'>]>\n<svg xmlns='http://www.w3.org/2000/svg'>\n");
  for (int r = 0; r < rects; r++) {
    len += (size_t)snprintf(t + len, cap - len, "<rect class='");
    for (int k = 0; k < refs; k++) memcpy(t + len, "&e; ", 4), len += 4;
    len += (size_t)snprintf(t + len, cap - len, "' x='%d' width='10' height='10'/>\n", 20 * r);
  }
  snprintf(t + len, cap - len, "</svg>\n");
  return t;
}

static us_Structure *imp_len(const char *svg, us_SvgInfo *info, us_Error *err) {
  us_SvgSettings set = raw();
  return imp(svg, &set, info, err);
}

/* Entity references in attribute values: bounded in all by 1 MiB + 4 x
 * the file's size, the count checked before the walk. */
static void entity_bombs(void) {
  /* the reproducer: one 20 kB entity 6,000 times in one class
     (120 MB expanded), refused at its element with the work bounded */
  char *t = entity_bomb(20000, 6000, 1);
  size_t budget = ((size_t)1 << 20) + 4 * strlen(t);
  us_SvgInfo info;
  us_Error err;
  us_Structure *s = imp_len(t, &info, &err);
  CHECK(!s && err.code == US_ERR_INPUT);
  CHECK(strstr(err.msg, "t.svg:4: <rect>: attribute 'class': entity references expand past"));
  CHECK(info.entity_bytes <= budget);
  CHECK(info.entity_bytes > budget - 20001); /* refused as soon as it passed */
  us_free(t);
  /* many moderate ones: the budget is the document's, not each value's
     (1 kB 60 times = 60 kB a rect; the 21st rect passes 1 MiB + 4 x 150 kB) */
  t = entity_bomb(1000, 60, 400);
  budget = ((size_t)1 << 20) + 4 * strlen(t);
  s = imp_len(t, &info, &err);
  CHECK(!s && err.code == US_ERR_INPUT);
  CHECK_INT((long)info.entity_bytes, <=, (long)budget);
  size_t line = 4 + budget / (60 * 1001); /* the rect whose class passes the budget */
  char want[64];
  snprintf(want, sizeof want, "t.svg:%zu: <rect>: attribute 'class'", line);
  if (!strstr(err.msg, want)) fprintf(stderr, "want %s: %s\n", want, err.msg);
  CHECK(strstr(err.msg, want));
  us_free(t);
  /* the same entity a few times is fine */
  t = entity_bomb(1000, 3, 3);
  s = imp_len(t, &info, &err);
  CHECK(s);
  CHECK_INT((long)info.entity_bytes, ==, 3 * (3 * (1000 + 1) + 3)); /* + the 3 spaces */
  us_structure_free(s);
  us_free(t);
}

/* Vertices in all at most 1 Mi + 4 per byte: 300 circles of 4096
 * segments (the finest --flatten) pass it at the 257th. */
static void vertex_budget(void) {
  size_t cap = 300 * 64 + 128, len = 0;
  char *t = us_malloc(cap);
  len += (size_t)snprintf(t, cap, SVG_OPEN);
  for (int k = 0; k < 300; k++) len += (size_t)snprintf(t + len, cap - len, "<circle cx='%d' r='1'/>\n", 3 * k);
  snprintf(t + len, cap - len, "</svg>\n");
  us_SvgSettings set = raw();
  set.flatten = 1e-12;
  int most = (1 << 20) + 4 * (int)strlen(t), line = 2 + most / 4096;
  char want[96];
  snprintf(want, sizeof want, "t.svg:%d: <circle>: the drawing makes more than %d vertices", line, most);
  CHECK(fails_with(t, &set, US_ERR_INPUT, want, NULL));
  us_free(t);
}

/* Attribute defaults declared in the DTD are not read (their values
 * would escape the entity budget): the rect is not fixed. */
static void dtd_defaults_ignored(void) {
  us_SvgSettings set = raw();
  us_Error err;
  us_Structure *s = imp("<!DOCTYPE svg [<!ATTLIST rect class CDATA 'fixed'>]>\n" SVG_OPEN
                        "<rect width='1' height='1'/><rect x='2' class='fixed' width='1' height='1'/></svg>\n",
                        &set, NULL, &err);
  CHECK(s);
  CHECK(!s->bodies[0].fixed && s->bodies[1].fixed);
  us_structure_free(s);
}

/* Billion laughs: libxml2's own guard refuses nested entities that
 * multiply, in attributes and in text, before the walk. */
static void billion_laughs(void) {
  char ents[2048] = "<!ENTITY l0 'lol'>";
  for (int i = 1; i <= 9; i++) {
    size_t n = strlen(ents);
    n += (size_t)snprintf(ents + n, sizeof ents - n, "<!ENTITY l%d '", i);
    for (int k = 0; k < 10; k++) n += (size_t)snprintf(ents + n, sizeof ents - n, "&l%d;", i - 1);
    snprintf(ents + n, sizeof ents - n, "'>");
  }
  const char *uses[] = {"<rect class='&l9;' width='1' height='1'/>",
                        "<rect width='1' height='1'/><text>&l9;</text>"};
  us_SvgSettings set = raw();
  for (int u = 0; u < 2; u++) {
    char svg[4096];
    snprintf(svg, sizeof svg, "<!DOCTYPE svg [%s]>\n" SVG_OPEN "%s</svg>\n", ents, uses[u]);
    CHECK(fails_with(svg, &set, US_ERR_PARSE, "t.svg:", "malformed XML", "entities that expand too much",
                     NULL));
  }
}

/* ------------------------------------------------------------ examples */

static us_Structure *example(const char *name, us_SvgInfo *info, us_Error *err) {
  char path[512];
  snprintf(path, sizeof path, "%s/../../examples/%s", US_TEST_DATA, name);
  us_SvgSettings set = us_svg_default_settings();
  set.unit = "mm";
  return us_structure_read_svg(path, &set, info, err);
}

static void inkscape_example(void) {
  us_SvgInfo info;
  us_Error err;
  us_error_clear(&err);
  us_Structure *s = example("inkscape_trilithon.svg", &info, &err);
  if (!s) fprintf(stderr, "%s\n", err.msg);
  CHECK(s);
  CHECK_INT(s->nbody, ==, 6);
  CHECK_INT(info.skipped, ==, 2); /* the hidden sketch layer and the text */
  CHECK_INT(info.fixed, ==, 1);
  CHECK(s->bodies[us_structure_find_body(s, "plinth")].fixed);
  /* the right post, drawn with relative commands in a translated layer */
  double post[] = {108, 5, 120, 5, 120, 50, 108, 50};
  int ok = body_is(s, "post-right", post, 4, 1e-12);
  /* the lintel (rotated 180 degrees in a translated group) rests on both posts */
  double lintel[] = {24, 50, 126, 50, 126, 60, 24, 60};
  ok &= body_is(s, "lintel", lintel, 4, 1e-12);
  int l = us_structure_find_body(s, "lintel");
  ok &= contacts_between(s, us_structure_find_body(s, "post-left"), l) == 2;
  ok &= contacts_between(s, us_structure_find_body(s, "post-right"), l) == 2;
  us_structure_free(s);
  CHECK(ok);
}

static void figure1_examples(void) {
  const char *names[] = {"column.svg", "cantilever.svg", "arch.svg"};
  int bodies[] = {3, 4, 9};
  for (int k = 0; k < 3; k++) {
    us_Error err;
    us_error_clear(&err);
    us_Structure *s = example(names[k], NULL, &err);
    if (!s) fprintf(stderr, "%s: %s\n", names[k], err.msg);
    CHECK(s);
    int n = s->nbody;
    us_structure_free(s);
    CHECK_INT(n, ==, bodies[k]);
  }
}

/* ------------------------------------------------------------ bad input */

static void malformed_xml(void) {
  us_SvgSettings set = raw();
  CHECK(fails_with("<svg xmlns='http://www.w3.org/2000/svg'>\n<rect width='1'\n height=1/>\n</svg>\n",
                   &set, US_ERR_PARSE, "t.svg:3: malformed XML", NULL));
  CHECK(fails_with("<svg xmlns='http://www.w3.org/2000/svg'>\n<rect width='1' height='1'>\n</svg>\n",
                   &set, US_ERR_PARSE, "t.svg:4: malformed XML: Premature end of data", NULL));
  CHECK(fails_with("", &set, US_ERR_PARSE, "t.svg:", NULL));
  CHECK(fails_with("<html><rect width='1' height='1'/></html>", &set, US_ERR_PARSE,
                   "t.svg:1: <html>: not an SVG drawing", NULL));
  CHECK(fails_with(SVG(""), &set, US_ERR_INPUT, "no shapes", NULL));
}

static void bad_path_data(void) {
  us_SvgSettings set = raw();
  CHECK(fails_with(SVG("<g>\n<path id='p' d='M 0 0 L 1 0 X 3 4 Z'/></g>"), &set, US_ERR_PARSE,
                   "t.svg:3: <path id='p'>: path data: unknown command 'X'", NULL));
  CHECK(fails_with(SVG("<path d='L 0 0 L 1 0 Z'/>"), &set, US_ERR_PARSE, "must start with M", NULL));
  CHECK(fails_with(SVG("<path d='M 0 0 C 1 1 2'/>"), &set, US_ERR_PARSE, "command 'C' needs 6 numbers",
                   NULL));
  CHECK(fails_with(SVG("<path d='M 0 0 L 1 0 1 1 Z 5'/>"), &set, US_ERR_PARSE,
                   "number without a command", NULL));
  CHECK(fails_with(SVG("<path d='M 0 0 A 1 1 0 2 1 3 3 Z'/>"), &set, US_ERR_PARSE, "'A' needs 7",
                   NULL));
  CHECK(fails_with(SVG("<path/>"), &set, US_ERR_INPUT, "<path>: no path data", NULL));
}

static void non_finite_numbers(void) {
  us_SvgSettings set = raw();
  CHECK(fails_with(SVG("<path d='M 0 0 L 1e999 0 L 1 1 Z'/>"), &set, US_ERR_PARSE, "t.svg:2:",
                   "not finite", NULL));
  CHECK(fails_with(SVG("<rect width='1e400' height='1'/>"), &set, US_ERR_PARSE, "width is not finite", NULL));
  CHECK(fails_with(SVG("<rect width='inf' height='1'/>"), &set, US_ERR_PARSE, "width is not a length", NULL));
  CHECK(fails_with(SVG("<polygon points='0,0 nan,1 1,1'/>"), &set, US_ERR_PARSE, "points", NULL));
  CHECK(fails_with(SVG("<rect width='1' height='1' transform='scale(1e300) scale(1e300)'/>"), &set,
                   US_ERR_PARSE, "not finite", NULL));
  CHECK(fails_with(SVG("<rect x='1e300' width='1e300' height='1' transform='scale(1e10)'/>"), &set,
                   US_ERR_INPUT, "not finite", NULL));
  /* overflow, named as such with the element and its line (issue 24) */
  CHECK(fails_with(SVG("\n<rect id='r' x='1e308' width='1' height='1' transform='scale(10)'/>"), &set,
                   US_ERR_INPUT, "t.svg:3: <rect id='r'>: a coordinate overflows after the transforms", NULL));
  CHECK(fails_with(SVG("<path d='M0 0 L 1e308 0 L 1e308 1e308 Z' transform='scale(10)'/>"), &set,
                   US_ERR_INPUT, "t.svg:2: <path>: a coordinate overflows", NULL));
  CHECK(fails_with(SVG("<rect width='1e200' height='1e200'/>"), &set, US_ERR_INPUT,
                   "t.svg:2: <rect>: coordinates too large: the shape's area or inertia overflows", NULL));
  CHECK(fails_with(SVG("<rect width='1e307' height='1e307' transform='scale(10)'/>"), &set, US_ERR_INPUT,
                   "<rect>: coordinates too large", NULL));
  set.unit = "mm"; /* finite in the drawing, not in the output units */
  set.scale = 1e300;
  CHECK(fails_with(SVG("<rect width='1e10' height='1'/>"), &set, US_ERR_INPUT,
                   "t.svg:2: <rect>: a coordinate overflows in the output units", NULL));
}

static void degenerate_shapes(void) {
  us_SvgSettings set = raw();
  CHECK(fails_with(SVG("\n<polygon id='flat' points='0,0 1,1 2,2'/>"), &set, US_ERR_INPUT,
                   "t.svg:3: <polygon id='flat'>: degenerate shape (no area)", NULL));
  CHECK(fails_with(SVG("<polygon id='two' points='0,0 1,1 0,0'/>"), &set, US_ERR_INPUT,
                   "fewer than 3 distinct points", NULL));
  CHECK(fails_with(SVG("<rect width='0' height='1'/>"), &set, US_ERR_INPUT, "degenerate: width is 0", NULL));
  CHECK(fails_with(SVG("<rect width='-2' height='1'/>"), &set, US_ERR_INPUT, "degenerate", NULL));
  CHECK(fails_with(SVG("<circle r='0'/>"), &set, US_ERR_INPUT, "degenerate", NULL));
  CHECK(fails_with(SVG("<rect height='1'/>"), &set, US_ERR_INPUT, "width is missing", NULL));
  CHECK(fails_with(SVG("<polygon points='0,0 1,0 1'/>"), &set, US_ERR_PARSE, "x,y pairs", NULL));
  CHECK(fails_with(SVG("<rect width='50%' height='1'/>"), &set, US_ERR_PARSE, "relative units", NULL));
}

static void bad_transforms(void) {
  us_SvgSettings set = raw();
  CHECK(fails_with(SVG("<rect transform='rotate(1,2)' width='1' height='1'/>"), &set, US_ERR_PARSE,
                   "t.svg:2: <rect>: transform: rotate takes 1 or 3 arguments, got 2", NULL));
  CHECK(fails_with(SVG("<g transform='spin(3)'><rect width='1' height='1'/></g>"), &set, US_ERR_PARSE,
                   "<g>: transform: unknown operation", NULL));
  CHECK(fails_with(SVG("<rect transform='translate(1 2' width='1' height='1'/>"), &set, US_ERR_PARSE,
                   "bad argument list", NULL));
}

static void overlapping_shapes(void) {
  us_SvgSettings set = us_svg_default_settings();
  /* refused after snapping moved vertices (c's bottom onto the ground):
     the message says so and how to do without */
  CHECK(fails_with(SVG("<rect id='a' y='-10' width='10' height='10'/>\n"
                       "<rect id='b' x='5' y='-10' width='10' height='10'/>\n"
                       "<rect id='c' x='20' y='-10.005' width='10' height='10'/>"),
                   &set, US_ERR_INPUT, "bodies 'a' and 'b' overlap",
                   "; snapping moved 2 vertices before this check (--snap 0: none", NULL));
  CHECK(fails_with(SVG("<rect id='one' width='10' height='10'/>\n"
                       "<rect id='two' x='5' y='5' width='10' height='10'/>"),
                   &set, US_ERR_INPUT, "t.svg: bodies 'one' and 'two' overlap",
                   "'one' is <rect> at line 2", "'two' is <rect> at line 3", NULL));
}

static void bad_settings(void) {
  us_SvgSettings set = raw();
  set.unit = "furlong";
  CHECK(fails_with(SVG("<rect width='1' height='1'/>"), &set, US_ERR_USAGE, "unknown unit", NULL));
  set = raw();
  set.flatten = 0;
  CHECK(fails_with(SVG("<rect width='1' height='1'/>"), &set, US_ERR_USAGE, "curve tolerance", NULL));
  set = raw();
  set.scale = -1;
  CHECK(fails_with(SVG("<rect width='1' height='1'/>"), &set, US_ERR_USAGE, "scale", NULL));
  us_Error err;
  us_error_clear(&err);
  CHECK(!us_structure_read_svg("/nonexistent/x.svg", NULL, NULL, &err) && err.code == US_ERR_IO);
}

/* --------------------------------------------------------- out of memory */

static void out_of_memory(void) {
  const char *svg = SVG("<g transform='translate(1 0)'><rect id='a' y='-10' width='10' height='10'/>"
                        "<rect id='a' x='0.001' y='-14' width='4' height='4'/></g>"
                        "<path d='M 20 0 A 5 5 0 0 1 30 0 Z m 20 0 h 5 v -5 h -5 z'/>"
                        "<circle cx='60' cy='-3' r='3'/>");
  us_SvgSettings set = us_svg_default_settings();
  long live0 = us_alloc_live();
  int done = 0;
  for (long n = 0; n < 100000 && !done; n++) {
    us_Error err;
    us_error_clear(&err);
    us_alloc_fail_after(n);
    us_Structure *s = us_structure_parse_svg(svg, strlen(svg), "t.svg", &set, NULL, &err);
    us_alloc_fail_after(-1);
    if (s) done = 1;
    else if (err.code != US_ERR_NOMEM) {
      fprintf(stderr, "n=%ld: [%s] %s\n", n, us_status_name(err.code), err.msg);
      CHECK(0);
    }
    us_structure_free(s);
    CHECK_INT(us_alloc_live(), ==, live0);
  }
  CHECK(done);
}

US_TEST_MAIN(T(rect_element), T(polygon_element), T(polyline_closed_or_skipped), T(path_absolute),
             T(path_relative), T(circle_and_ellipse), T(transform_each_kind), T(transform_lists),
             T(nested_groups), T(units_and_viewbox), T(flip_and_ground),
             T(curves_within_tolerance), T(arc_and_smooth_curves), T(curves_after_transforms),
             T(unique_ids), T(fixed_marks), T(materials), T(snapping), T(snapping_corners_meet), T(snapping_thin_plank),
             T(skipped_elements), T(rounded_rect_warns), T(illustrator_entities), T(entity_bombs), T(dtd_defaults_ignored), T(billion_laughs), T(vertex_budget),
             T(inkscape_example), T(figure1_examples),
             T(malformed_xml), T(bad_path_data), T(non_finite_numbers), T(degenerate_shapes),
             T(bad_transforms), T(overlapping_shapes), T(bad_settings), T(out_of_memory))
