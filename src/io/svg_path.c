/* Rings from SVG path data and ellipses, with curves flattened
 * (docs/svg.md, "Paths and curves").
 *
 * A path is read command by command (M L H V Z C S Q T A, upper case
 * absolute, lower case relative to the current point; a command letter
 * may be left out before repeated arguments, M's repeats being L). Each
 * subpath becomes one ring; a ring is kept when it is closed by Z or its
 * last point comes back to its first, otherwise it is dropped and counted
 * (SVG fills it, but an open outline is more often a stroke). After Z the
 * current point is the subpath's start, and a drawing command without M
 * starts a new subpath there.
 *
 * Flattening. Curves are mapped to root coordinates first and flattened
 * there, so the tolerance is met in the drawing whatever the transforms:
 * a Bezier curve is affine-invariant (its control points are mapped), and
 * an arc is an affine image of a circle. The tolerance is relative to the
 * curve's own size (the diagonal of a Bezier's control-point box, an
 * ellipse's larger radius): with n uniform steps in t the chord error of
 * a curve B is at most max|B''| / (8 n^2), and |B''| <= 6 max|P0 - 2P1 +
 * P2|, |P1 - 2P2 + P3| for a cubic, 2 |P0 - 2P1 + P2| for a quadratic;
 * for an arc a step of angle h leaves r (1 - cos(h/2)) <= flatten * r.
 * n is the smallest count meeting the bound, at most US_SVG_MAX_SEG.
 *
 * Rings are cleaned when closed: points within 1e-9 of the ring's size
 * of the previous kept point are dropped (so a relative path that returns
 * to its start up to rounding closes exactly), and the last point when it
 * repeats the first. */
#include "svg.h"

#include "geometry/geometry.h"

#include <math.h>
#include <string.h>

#define US_SVG_MAX_SEG 4096
#define SAME_REL 1e-9
#define PI 3.14159265358979323846

/* ---------------------------------------------------------------- rings */

void us_svg_rings_free(us_SvgRings *r) {
  us_free(r->xy);
  us_free(r->start);
  memset(r, 0, sizeof *r);
}

int us_svg_ring_begin(us_SvgRings *r) {
  if (US_GROW(r->start, r->cap_start, r->nring + 2)) return -1;
  r->start[r->nring] = r->npt;
  return 0;
}

static int push_root(us_SvgRings *r, double x, double y) {
  if (!isfinite(x) || !isfinite(y)) return -2;
  int n = r->npt;
  if (n > r->start[r->nring] && r->xy[2 * n - 2] == x && r->xy[2 * n - 1] == y) return 0;
  if (n >= r->max_pt) return -3;
  if (US_GROW(r->xy, r->cap_pt, 2 * n + 2)) return -1;
  r->xy[2 * n] = x;
  r->xy[2 * n + 1] = y;
  r->npt++;
  return 0;
}

int us_svg_ring_point(us_SvgRings *r, const us_SvgMatrix *m, double x, double y) {
  double q[2];
  us_svg_apply(m, x, y, q);
  return push_root(r, q[0], q[1]);
}

us_Status us_svg_ring_error(const us_SvgRings *r, int rc, us_Error *err) {
  if (rc == -2) return us_error_set(err, US_ERR_INPUT, "a coordinate overflows after the transforms (not finite)");
  if (rc == -3)
    return us_error_set(err, US_ERR_INPUT, "the drawing makes more than %d vertices, the limit for "
                        "its size (docs/svg.md; curves give fewer with a larger --flatten)", r->max_pt);
  return us_error_set(err, US_ERR_NOMEM, "out of memory");
}

/* Drop points within eps of the previous kept one; returns the count. */
static int dedupe(double *xy, int n, double eps) {
  int k = n ? 1 : 0;
  for (int i = 1; i < n; i++) {
    if (fabs(xy[2 * i] - xy[2 * k - 2]) <= eps && fabs(xy[2 * i + 1] - xy[2 * k - 1]) <= eps)
      continue;
    xy[2 * k] = xy[2 * i];
    xy[2 * k + 1] = xy[2 * i + 1];
    k++;
  }
  return k;
}

int us_svg_ring_end(us_SvgRings *r, int closed) {
  int s = r->start[r->nring], n = r->npt - s;
  double *xy = r->xy + 2 * s;
  double eps = SAME_REL * us_poly_diameter(xy, n);
  n = dedupe(xy, n, eps);
  if (n >= 2 && fabs(xy[0] - xy[2 * n - 2]) <= eps && fabs(xy[1] - xy[2 * n - 1]) <= eps)
    n--, closed = 1;
  r->npt = s + n;
  if (!closed) {
    r->npt = s;
    return 0;
  }
  r->start[++r->nring] = r->npt;
  return 1;
}

void us_svg_rings_truncate(us_SvgRings *r, int k) {
  if (k >= r->nring) return;
  r->nring = k;
  r->npt = r->start[k];
}

/* ---------------------------------------------------------------- curves */

static int seg_count(double ratio) {
  if (!(ratio > 0)) return 1;
  double n = ceil(sqrt(ratio));
  return n >= US_SVG_MAX_SEG ? US_SVG_MAX_SEG : n < 1 ? 1 : (int)n;
}

/* Diagonal of the box of k points p[2k]. */
static double box_diag(const double *p, int k) { return us_poly_diameter(p, k); }

static double second_diff(const double *p, int i) {
  return hypot(p[2 * i] - 2 * p[2 * i + 2] + p[2 * i + 4],
               p[2 * i + 1] - 2 * p[2 * i + 3] + p[2 * i + 5]);
}

/* A Bezier curve of degree deg (2 or 3) with root control points p:
 * points for t in (0, 1]. */
static int bezier(us_SvgRings *r, const double *p, int deg, double flatten) {
  double m2 = second_diff(p, 0), size = box_diag(p, deg + 1);
  if (deg == 3) m2 = US_MAX(m2, second_diff(p, 1));
  int n = size > 0 ? seg_count((deg == 3 ? 0.75 : 0.25) * m2 / (flatten * size)) : 1;
  for (int k = 1; k <= n; k++) {
    double t = (double)k / n, u = 1 - t, w[4];
    if (deg == 3) w[0] = u * u * u, w[1] = 3 * u * u * t, w[2] = 3 * u * t * t, w[3] = t * t * t;
    else w[0] = u * u, w[1] = 2 * u * t, w[2] = t * t;
    double x = 0, y = 0;
    for (int j = 0; j <= deg; j++) x += w[j] * p[2 * j], y += w[j] * p[2 * j + 1];
    if (k == n) x = p[2 * deg], y = p[2 * deg + 1];
    int rc = push_root(r, x, y);
    if (rc) return rc;
  }
  r->curves++;
  return 0;
}

static double arc_step(double flatten) { return 2.0 * acos(1.0 - US_MIN(flatten, 0.5)); }

/* An ellipse arc in local coordinates: centre c, radii rx ry, x axis at
 * angle phi; from angle t0 through dt; points after the start. */
typedef struct Arc {
  double cx, cy, rx, ry, phi, t0, dt;
} Arc;

static int arc_points(us_SvgRings *r, const us_SvgMatrix *m, const Arc *a, double flatten,
                      int skip_last) {
  int n = seg_count(pow(fabs(a->dt) / arc_step(flatten), 2));
  double cp = cos(a->phi), sp = sin(a->phi);
  for (int k = 1; k <= n - skip_last; k++) {
    double t = a->t0 + a->dt * k / n, x = a->rx * cos(t), y = a->ry * sin(t);
    int rc = us_svg_ring_point(r, m, a->cx + x * cp - y * sp, a->cy + x * sp + y * cp);
    if (rc) return rc;
  }
  r->curves++;
  return 0;
}

/* SVG's endpoint arc (p0 to p1) to centre form (SVG 1.1, F.6.5), radii
 * scaled up when too small. */
static Arc arc_centre(const double *p0, const double *v, const double *p1) {
  Arc a = {0, 0, fabs(v[0]), fabs(v[1]), v[2] * (PI / 180.0), 0, 0};
  double cp = cos(a.phi), sp = sin(a.phi), dx = (p0[0] - p1[0]) / 2, dy = (p0[1] - p1[1]) / 2;
  double x1 = cp * dx + sp * dy, y1 = -sp * dx + cp * dy;
  double lam = x1 * x1 / (a.rx * a.rx) + y1 * y1 / (a.ry * a.ry);
  if (lam > 1) a.rx *= sqrt(lam), a.ry *= sqrt(lam);
  double rx2 = a.rx * a.rx, ry2 = a.ry * a.ry, den = rx2 * y1 * y1 + ry2 * x1 * x1;
  double sq = den > 0 ? (rx2 * ry2 - den) / den : 0, coef = sqrt(sq > 0 ? sq : 0);
  if ((v[3] != 0) == (v[4] != 0)) coef = -coef;
  double cx1 = coef * a.rx * y1 / a.ry, cy1 = -coef * a.ry * x1 / a.rx;
  a.cx = cp * cx1 - sp * cy1 + (p0[0] + p1[0]) / 2;
  a.cy = sp * cx1 + cp * cy1 + (p0[1] + p1[1]) / 2;
  double ux = (x1 - cx1) / a.rx, uy = (y1 - cy1) / a.ry, wx = (-x1 - cx1) / a.rx,
         wy = (-y1 - cy1) / a.ry;
  a.t0 = atan2(uy, ux);
  a.dt = atan2(ux * wy - uy * wx, ux * wx + uy * wy);
  if (v[4] == 0 && a.dt > 0) a.dt -= 2 * PI;
  if (v[4] != 0 && a.dt < 0) a.dt += 2 * PI;
  return a;
}

us_Status us_svg_ellipse(us_SvgRings *r, const us_SvgMatrix *m, double cx, double cy, double rx,
                         double ry, double flatten, us_Error *err) {
  Arc a = {cx, cy, rx, ry, 0, 0, 2 * PI};
  int rc = us_svg_ring_begin(r);
  if (!rc) rc = us_svg_ring_point(r, m, cx + rx, cy);
  if (!rc) rc = arc_points(r, m, &a, flatten, 1);
  if (rc) return us_svg_ring_error(r, rc, err);
  us_svg_ring_end(r, 1);
  return US_OK;
}

/* ---------------------------------------------------------------- paths */

/* The state of a path being read; positions are local (before m). */
typedef struct Path {
  us_SvgRings *r;
  const us_SvgMatrix *m;
  us_SvgPathOpts *o;
  const char *d;    /* the whole data, for offsets in messages */
  double cur[2], start[2], ctrl[2];
  char prev;        /* the previous command (upper case), 0 at the start */
  int open;         /* a ring is being built */
  int rc;           /* -1 OOM, -2 not finite */
} Path;

static void path_point(Path *p, double x, double y) {
  if (!p->rc) p->rc = us_svg_ring_point(p->r, p->m, x, y);
  p->cur[0] = x, p->cur[1] = y;
}

static void path_end(Path *p, int closed) {
  if (p->open && !us_svg_ring_end(p->r, closed)) p->o->open_rings++;
  p->open = 0;
}

/* Make sure a ring is open (after Z a drawing command starts one at the
 * current point). */
static void path_need_ring(Path *p) {
  if (p->open) return;
  if (!p->rc) p->rc = us_svg_ring_begin(p->r);
  p->open = 1;
  path_point(p, p->cur[0], p->cur[1]);
}

static void path_curve(Path *p, const double *local, int deg) {
  double q[8];
  us_svg_apply(p->m, p->cur[0], p->cur[1], q);
  for (int j = 0; j < deg; j++) us_svg_apply(p->m, local[2 * j], local[2 * j + 1], q + 2 * j + 2);
  if (!p->rc) p->rc = bezier(p->r, q, deg, p->o->flatten);
  p->ctrl[0] = local[2 * deg - 4], p->ctrl[1] = local[2 * deg - 3];
  p->cur[0] = local[2 * deg - 2], p->cur[1] = local[2 * deg - 1];
}

static void path_arc(Path *p, const double *v) {
  double p1[2] = {v[5], v[6]};
  if (p1[0] == p->cur[0] && p1[1] == p->cur[1]) return;
  if (v[0] == 0 || v[1] == 0) {
    path_point(p, p1[0], p1[1]);
    return;
  }
  Arc a = arc_centre(p->cur, v, p1);
  if (!p->rc) p->rc = arc_points(p->r, p->m, &a, p->o->flatten, 1);
  path_point(p, p1[0], p1[1]);
}

/* Reflection of the last control point when the previous command was of
 * the same family, else the current point. */
static void reflected(const Path *p, int smooth_of, double out[2]) {
  int same = smooth_of == 3 ? (p->prev == 'C' || p->prev == 'S') : (p->prev == 'Q' || p->prev == 'T');
  out[0] = same ? 2 * p->cur[0] - p->ctrl[0] : p->cur[0];
  out[1] = same ? 2 * p->cur[1] - p->ctrl[1] : p->cur[1];
}

/* Carry out command c (upper case) with absolute arguments v. */
static void path_do(Path *p, char c, double *v) {
  double q[6];
  if (c == 'M') {
    path_end(p, 0);
    p->start[0] = v[0], p->start[1] = v[1];
    p->cur[0] = v[0], p->cur[1] = v[1];
    path_need_ring(p);
    return;
  }
  if (c == 'Z') {
    path_end(p, 1);
    p->cur[0] = p->start[0], p->cur[1] = p->start[1];
    return;
  }
  path_need_ring(p);
  switch (c) {
  case 'L': path_point(p, v[0], v[1]); break;
  case 'H': path_point(p, v[0], p->cur[1]); break;
  case 'V': path_point(p, p->cur[0], v[0]); break;
  case 'C': path_curve(p, v, 3); break;
  case 'Q': path_curve(p, v, 2); break;
  case 'S': reflected(p, 3, q), memcpy(q + 2, v, 4 * sizeof *v), path_curve(p, q, 3); break;
  case 'T': reflected(p, 2, q), memcpy(q + 2, v, 2 * sizeof *v), path_curve(p, q, 2); break;
  default: path_arc(p, v); break;
  }
}

/* Arguments per command (upper case), and which are x / y coordinates
 * (made absolute for a relative command): 'x', 'y', or '-' (other). */
static const char *arg_kinds(char c) {
  switch (c) {
  case 'M': case 'L': case 'T': return "xy";
  case 'H': return "x";
  case 'V': return "y";
  case 'C': return "xyxyxy";
  case 'S': case 'Q': return "xyxy";
  case 'A': return "--->>xy"; /* rx ry angle large-arc sweep x y; '>' a flag */
  case 'Z': return "";
  default: return NULL;
  }
}

/* A flag of an arc: one character 0 or 1 (SVG lets "11" be two flags). */
static int read_flag(const char **s, double *out) {
  const char *q = us_svg_skip_ws(*s);
  if (*q != '0' && *q != '1') return 0;
  *out = *q - '0';
  *s = q + 1;
  return 1;
}

static us_Status read_args(Path *p, const char **s, char c, int rel, double *v, us_Error *err) {
  const char *k = arg_kinds(c);
  for (int i = 0; k[i]; i++) {
    if (i) *s = us_svg_skip_sep(*s);
    int r = k[i] == '>' ? read_flag(s, &v[i]) : us_svg_number(s, &v[i]);
    if (r < 0)
      return us_error_set(err, US_ERR_PARSE, "path data: a number is not finite (offset %ld)",
                          (long)(*s - p->d));
    if (r == 0)
      return us_error_set(err, US_ERR_PARSE, "path data: command '%c' needs %d %s (offset %ld)",
                          rel ? c + 32 : c, (int)strlen(k), c == 'A' ? "values" : "numbers",
                          (long)(*s - p->d));
    if (rel && k[i] == 'x') v[i] += p->cur[0];
    if (rel && k[i] == 'y') v[i] += p->cur[1];
  }
  return US_OK;
}

static int is_number_start(char ch) {
  return (ch >= '0' && ch <= '9') || ch == '.' || ch == '-' || ch == '+';
}

/* The next command letter at *s, or the implicit repeat of the previous
 * one; 0 at the end; '?' on an error (err set). */
static char next_command(const Path *p, const char **s, char *letter, us_Error *err) {
  *s = us_svg_skip_sep(*s);
  char ch = **s;
  if (!ch) return 0;
  if (is_number_start(ch)) {
    if (!*letter || *letter == 'Z' || *letter == 'z') {
      us_error_set(err, US_ERR_PARSE, "path data: number without a command (offset %ld)",
                   (long)(*s - p->d));
      return '?';
    }
    if (*letter == 'M' || *letter == 'm') *letter = *letter == 'M' ? 'L' : 'l';
    return *letter;
  }
  char up = ch >= 'a' && ch <= 'z' ? (char)(ch - 32) : ch;
  if (!arg_kinds(up) || (ch >= '0' && ch <= '9')) {
    us_error_set(err, US_ERR_PARSE, "path data: unknown command '%c' (offset %ld)", ch,
                 (long)(*s - p->d));
    return '?';
  }
  if (!*letter && up != 'M') {
    us_error_set(err, US_ERR_PARSE, "path data must start with M or m, not '%c'", ch);
    return '?';
  }
  (*s)++;
  return *letter = ch;
}

us_Status us_svg_path(us_SvgRings *r, const char *d, const us_SvgMatrix *m, us_SvgPathOpts *o,
                      us_Error *err) {
  Path p = {r, m, o, d, {0, 0}, {0, 0}, {0, 0}, 0, 0, 0};
  char letter = 0, c;
  const char *s = d;
  while ((c = next_command(&p, &s, &letter, err)) != 0) {
    if (c == '?') return US_ERR_PARSE;
    int rel = c >= 'a' && c <= 'z';
    char up = rel ? (char)(c - 32) : c;
    double v[7];
    if (read_args(&p, &s, up, rel, v, err)) return US_ERR_PARSE;
    path_do(&p, up, v);
    p.prev = up;
    if (p.rc) break;
  }
  if (!p.rc) path_end(&p, 0);
  if (p.rc) return us_svg_ring_error(r, p.rc, err);
  return US_OK;
}
