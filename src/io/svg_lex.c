/* SVG attribute text -> values: numbers, lengths with units, transform
 * lists and style properties (docs/svg.md).
 *
 * Numbers follow SVG's grammar only: an optional sign, digits with an
 * optional fraction (or a fraction alone), an optional exponent whose
 * 'e' is followed by digits (so "1em" is 1 and the unit em). The scanner
 * finds the number's end first and hands a copy of exactly those
 * characters to strtod, so strtod's extensions (hex, "inf", "nan") never
 * get in, and "1-2" or "1.5.5" split as SVG says (1, -2; 1.5, .5). A value
 * that overflows to infinity is reported apart from a syntax error.
 *
 * A transform list "t1 t2 ... tn" maps a point by tn first: the result is
 * the product t1 * t2 * ... * tn, built left to right. Angles are in
 * degrees; rotate(a, cx, cy) turns about (cx, cy). */
#include "svg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NUM_MAX 500 /* characters in one number */
#define PI 3.14159265358979323846

us_SvgMatrix us_svg_identity(void) { return (us_SvgMatrix){1, 0, 0, 1, 0, 0}; }

us_SvgMatrix us_svg_mul(us_SvgMatrix m, us_SvgMatrix n) {
  return (us_SvgMatrix){m.a * n.a + m.c * n.b, m.b * n.a + m.d * n.b,
                        m.a * n.c + m.c * n.d, m.b * n.c + m.d * n.d,
                        m.a * n.e + m.c * n.f + m.e, m.b * n.e + m.d * n.f + m.f};
}

void us_svg_apply(const us_SvgMatrix *m, double x, double y, double out[2]) {
  out[0] = m->a * x + m->c * y + m->e;
  out[1] = m->b * x + m->d * y + m->f;
}

static int is_ws(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f'; }
static int is_digit(char c) { return c >= '0' && c <= '9'; }

const char *us_svg_skip_ws(const char *p) {
  while (is_ws(*p)) p++;
  return p;
}

const char *us_svg_skip_sep(const char *p) {
  p = us_svg_skip_ws(p);
  if (*p == ',') p = us_svg_skip_ws(p + 1);
  return p;
}

static const char *digits(const char *p) {
  while (is_digit(*p)) p++;
  return p;
}

/* End of the number starting at p, or p when there is none. */
static const char *number_end(const char *p) {
  const char *q = p;
  if (*q == '+' || *q == '-') q++;
  const char *m = digits(q);
  int whole = m > q;
  if (*m == '.' && is_digit(m[1])) m = digits(m + 1);
  else if (*m == '.' && whole) m++; /* "1." */
  else if (!whole) return p;
  if (*m == 'e' || *m == 'E') {
    const char *e = m + 1;
    if (*e == '+' || *e == '-') e++;
    if (is_digit(*e)) m = digits(e);
  }
  return m;
}

int us_svg_number(const char **p, double *out) {
  const char *s = us_svg_skip_ws(*p), *e = number_end(s);
  if (e == s) return 0;
  size_t n = (size_t)(e - s);
  if (n > NUM_MAX) return -1;
  char buf[NUM_MAX + 1];
  memcpy(buf, s, n);
  buf[n] = '\0';
  *out = strtod(buf, NULL);
  *p = e;
  return isfinite(*out) ? 1 : -1;
}

static const struct {
  const char *name;
  double metres;
} units[] = {{"m", 1.0},         {"cm", 0.01},          {"mm", 0.001},
             {"in", 0.0254},     {"pt", 0.0254 / 72},   {"pc", 0.0254 / 6},
             {"px", 0.0254 / 96}, {"q", 0.00025}};

double us_svg_unit_metres(const char *unit, size_t len) {
  for (size_t k = 0; k < sizeof units / sizeof units[0]; k++)
    if (strlen(units[k].name) == len && !strncmp(units[k].name, unit, len)) return units[k].metres;
  return 0;
}

int us_svg_length_unit(const char *s, double *num, double *unit_m) {
  const char *p = s;
  int r = us_svg_number(&p, num);
  if (r <= 0) return r ? -3 : -1;
  const char *u = p;
  while ((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || *p == '%') p++;
  size_t len = (size_t)(p - u);
  if (*us_svg_skip_ws(p)) return -1;
  *unit_m = len ? us_svg_unit_metres(u, len) : 0.0254 / 96;
  if (*unit_m <= 0 || (len == 1 && *u == 'm')) return -2; /* "m" is no SVG unit */
  return 0;
}

int us_svg_length(const char *s, double *out) {
  double num, um;
  int r = us_svg_length_unit(s, &num, &um);
  if (r) return r;
  *out = um == 0.0254 / 96 ? num : num * (um / (0.0254 / 96));
  return isfinite(*out) ? 0 : -3;
}

/* ------------------------------------------------------------ transforms */

typedef struct Op {
  const char *name;
  int nmin, nmax, n3; /* argument counts accepted: nmin .. nmax, and n3 */
  const char *counts; /* the same in words */
} Op;

static const Op ops[] = {{"matrix", 6, 6, 6, "6"},      {"translate", 1, 2, 2, "1 or 2"},
                         {"scale", 1, 2, 2, "1 or 2"},  {"rotate", 1, 1, 3, "1 or 3"},
                         {"skewX", 1, 1, 1, "1"},       {"skewY", 1, 1, 1, "1"}};

/* Quarter turns exactly (rotate(180) is common in drawings, and cos(pi)
 * in floating point leaves sin = 1.2e-16). */
static us_SvgMatrix rotation(double deg) {
  double q = fmod(deg, 360.0) / 90.0, r = deg * (PI / 180.0), c = cos(r), s = sin(r);
  if (q == floor(q)) {
    static const double qc[] = {1, 0, -1, 0}, qs[] = {0, 1, 0, -1};
    int k = ((int)q % 4 + 4) % 4;
    c = qc[k], s = qs[k];
  }
  return (us_SvgMatrix){c, s, -s, c, 0, 0};
}

static us_SvgMatrix op_matrix(int k, const double *v, int n) {
  us_SvgMatrix t = us_svg_identity(), m;
  switch (k) {
  case 0: return (us_SvgMatrix){v[0], v[1], v[2], v[3], v[4], v[5]};
  case 1: t.e = v[0], t.f = n > 1 ? v[1] : 0; return t;
  case 2: t.a = v[0], t.d = n > 1 ? v[1] : v[0]; return t;
  case 3:
    m = rotation(v[0]);
    if (n < 3) return m;
    t.e = v[1], t.f = v[2];
    m = us_svg_mul(t, m);
    t.e = -v[1], t.f = -v[2];
    return us_svg_mul(m, t);
  case 4: t.c = tan(v[0] * (PI / 180.0)); return t;
  default: t.b = tan(v[0] * (PI / 180.0)); return t;
  }
}

static int op_find(const char **p) {
  for (int k = 0; k < (int)(sizeof ops / sizeof ops[0]); k++) {
    size_t len = strlen(ops[k].name);
    if (!strncmp(*p, ops[k].name, len)) {
      *p += len;
      return k;
    }
  }
  return -1;
}

/* "(v, v, ...)" after a transform's name: its values, count in *n. */
static us_Status op_args(const char **pp, const char *name, double *v, int *n, us_Error *err) {
  const char *p = us_svg_skip_ws(*pp);
  if (*p != '(') return us_error_set(err, US_ERR_PARSE, "transform: '(' expected after %s", name);
  p = us_svg_skip_ws(p + 1);
  for (*n = 0; *p != ')'; p = us_svg_skip_sep(p)) {
    double x;
    int r = us_svg_number(&p, &x);
    if (r < 0) return us_error_set(err, US_ERR_PARSE, "transform: %s: a number is not finite", name);
    if (r == 0 || *n == 6)
      return us_error_set(err, US_ERR_PARSE, "transform: %s: bad argument list", name);
    v[(*n)++] = x;
  }
  *pp = p + 1;
  return US_OK;
}

us_Status us_svg_transform(const char *s, us_SvgMatrix *out, us_Error *err) {
  *out = us_svg_identity();
  for (const char *p = us_svg_skip_ws(s); *p; p = us_svg_skip_sep(p)) {
    int k = op_find(&p), n = 0;
    if (k < 0) return us_error_set(err, US_ERR_PARSE, "transform: unknown operation at '%.20s'", p);
    double v[6];
    if (op_args(&p, ops[k].name, v, &n, err)) return US_ERR_PARSE;
    if ((n < ops[k].nmin || n > ops[k].nmax) && n != ops[k].n3)
      return us_error_set(err, US_ERR_PARSE, "transform: %s takes %s arguments, got %d",
                          ops[k].name, ops[k].counts, n);
    *out = us_svg_mul(*out, op_matrix(k, v, n));
  }
  const double *m = &out->a;
  for (int k = 0; k < 6; k++)
    if (!isfinite(m[k])) return us_error_set(err, US_ERR_PARSE, "transform: the result is not finite");
  return US_OK;
}

/* ---------------------------------------------------------------- style */

/* Copy [a, b) trimmed into buf. */
static void copy_trimmed(const char *a, const char *b, char *buf, size_t cap) {
  a = us_svg_skip_ws(a);
  while (b > a && is_ws(b[-1])) b--;
  size_t n = US_MIN((size_t)(b - a), cap - 1);
  memcpy(buf, a, n);
  buf[n] = '\0';
}

int us_svg_style_get(const char *style, const char *name, char *buf, size_t cap) {
  size_t len = strlen(name);
  for (const char *p = style; *p;) {
    const char *end = strchr(p, ';'), *colon = strchr(p, ':');
    if (!end) end = p + strlen(p);
    if (colon && colon < end) {
      char key[64];
      copy_trimmed(p, colon, key, sizeof key);
      if (strlen(key) == len && !strcmp(key, name)) {
        copy_trimmed(colon + 1, end, buf, cap);
        return 1;
      }
    }
    p = *end ? end + 1 : end;
  }
  return 0;
}
