/* Splitting a structure file's text at its bodies, so that the reader can
 * parse one body at a time (structure_read.c) instead of building the
 * whole document's JSON tree: a 100,000-body file is 1.5 million jansson
 * values, 140 MB of small blocks that the allocator must later consolidate.
 *
 * The split is a scan of the top-level object that only follows strings
 * (with their escapes) and bracket depth; it validates nothing. It finds
 * the value of the top-level key "bodies" when that is an array, and the
 * byte span of each element, trimmed of JSON whitespace, with exactly one
 * comma between elements. The reader then has jansson parse the rest of
 * the document with the array emptied ("bodies": []) and each element
 * alone. If those parses all succeed, the whole text was valid JSON with
 * the same values: the pieces are valid, and the separators between them
 * were checked here. Whenever anything goes differently (no such array, a
 * second "bodies" key, an element that does not parse), the reader falls
 * back to parsing the whole text, whose messages (file:line:column) are
 * the reference; the split never decides that a file is bad. */
#include <string.h>

#include "io.h"

typedef struct Scan {
  const char *t;
  size_t n, at;
} Scan;

static int is_ws(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

static void skip_ws(Scan *s) {
  while (s->at < s->n && is_ws(s->t[s->at])) s->at++;
}

/* Past a string starting at s->at ('"'); 0 when it does not end. */
static int skip_string(Scan *s) {
  for (s->at++; s->at < s->n; s->at++) {
    char c = s->t[s->at];
    if (c == '\\') s->at++;
    else if (c == '"') return ++s->at, 1;
  }
  return 0;
}

/* Past one value (a string, a bracketed value with everything nested in
 * it, or a scalar up to the next delimiter); 0 when the text ends first. */
static int skip_value(Scan *s) {
  int depth = 0;
  while (s->at < s->n) {
    char c = s->t[s->at];
    if (c == '"') {
      if (!skip_string(s)) return 0;
      if (depth == 0) return 1;
      continue;
    }
    if (c == '[' || c == '{') depth++;
    else if (c == ']' || c == '}') {
      if (depth == 0) return 1; /* a scalar ended by its container */
      if (--depth == 0) return ++s->at, 1;
    } else if (depth == 0 && (c == ',' || is_ws(c)))
      return 1;
    s->at++;
  }
  return depth == 0;
}

/* The elements of the array at s->at ('['), each span recorded; the scan
 * ends past its ']'. 1, 0 (not a plain array), -1 out of memory. */
static int split_array(Scan *s, us_BodySpans *out) {
  s->at++;
  skip_ws(s);
  if (s->at < s->n && s->t[s->at] == ']') return ++s->at, 1;
  for (;;) {
    size_t from = s->at;
    if (!skip_value(s) || s->at == from) return 0;
    if (US_GROW(out->el, out->cap, out->n + 1)) return -1;
    out->el[out->n++] = (us_JsonSpan){from, s->at - from};
    skip_ws(s);
    if (s->at >= s->n) return 0;
    char c = s->t[s->at++];
    if (c == ']') return 1;
    if (c != ',') return 0;
    skip_ws(s);
  }
}

/* Is the string at [from, to) (quotes included) the key "bodies"? */
static int is_bodies_key(const char *t, size_t from, size_t to) {
  return to - from == 8 && !memcmp(t + from, "\"bodies\"", 8);
}

int us_io_split_bodies(const char *text, size_t len, us_BodySpans *out) {
  Scan s = {text, len, 0};
  memset(out, 0, sizeof *out);
  skip_ws(&s);
  if (s.at >= s.n || text[s.at] != '{') return 0;
  for (s.at++;;) {
    skip_ws(&s);
    if (s.at >= s.n || text[s.at] != '"') return 0;
    size_t key = s.at;
    if (!skip_string(&s)) return 0;
    int bodies = is_bodies_key(text, key, s.at);
    skip_ws(&s);
    if (s.at >= s.n || text[s.at++] != ':') return 0;
    skip_ws(&s);
    if (bodies && (out->arr_len || s.at >= s.n || text[s.at] != '[')) return 0;
    size_t from = s.at;
    int r = bodies ? split_array(&s, out) : skip_value(&s);
    if (r != 1) return r;
    if (bodies) out->arr_off = from, out->arr_len = s.at - from;
    skip_ws(&s);
    if (s.at >= s.n) return 0;
    char c = text[s.at++];
    if (c == '}') return out->arr_len > 0;
    if (c != ',') return 0;
  }
}

void us_io_spans_free(us_BodySpans *b) {
  us_free(b->el);
  memset(b, 0, sizeof *b);
}

/* The polygon lane. A body's "polygon" is most of its values (13 of 17 for
 * a block), so the reader takes plain polygons from the text itself and
 * gives jansson the body with "polygon": []. Plain means: an array of at
 * least 3 and at most `cap` arrays of two numbers, JSON whitespace between
 * tokens, numbers without exponent and with at most 15 significant digits
 * (at most 22 after the point). Such a number is M / 10^k with M < 2^53
 * and 10^k exact, so one division gives the correctly rounded value, the
 * one strtod (jansson) gives. Anything else is left to jansson. */
#define MAX_DIGITS 15

static const double pow10_exact[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                       1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                       1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

static int is_digit(char c) { return c >= '0' && c <= '9'; }

/* Digits at s->at into *m (significant ones counted in *sig, all in
 * *count); 0 when there are too many significant digits. */
static int read_digits(Scan *s, uint64_t *m, int *sig, int *count) {
  for (*count = 0; s->at < s->n && is_digit(s->t[s->at]); s->at++, (*count)++) {
    int d = s->t[s->at] - '0';
    if (*m == 0 && d == 0) continue; /* leading zeros are not significant */
    if (++*sig > MAX_DIGITS) return 0;
    *m = *m * 10 + (uint64_t)d;
  }
  return 1;
}

/* A plain number (see above) at s->at into *out; 0 when not plain. */
static int plain_number(Scan *s, double *out) {
  int neg = s->at < s->n && s->t[s->at] == '-', sig = 0, ni = 0, nf = 0;
  uint64_t m = 0;
  s->at += (size_t)neg;
  if (s->at >= s->n || !is_digit(s->t[s->at])) return 0;
  if (s->t[s->at] == '0' && s->at + 1 < s->n && is_digit(s->t[s->at + 1])) return 0;
  if (!read_digits(s, &m, &sig, &ni)) return 0;
  if (s->at < s->n && s->t[s->at] == '.') {
    s->at++;
    if (!read_digits(s, &m, &sig, &nf) || nf == 0 || nf > 22) return 0;
  }
  if (s->at < s->n && (s->t[s->at] == 'e' || s->t[s->at] == 'E')) return 0;
  double v = (double)m / pow10_exact[nf];
  *out = neg ? -v : v;
  return 1;
}

/* Is the next token the character c? Consumed when it is. */
static int token(Scan *s, char c) {
  skip_ws(s);
  if (s->at >= s->n || s->t[s->at] != c) return 0;
  s->at++;
  return 1;
}

/* [x, y] at s->at into xy. */
static int plain_pair(Scan *s, double *xy) {
  if (!token(s, '[')) return 0;
  skip_ws(s);
  if (!plain_number(s, &xy[0]) || !token(s, ',')) return 0;
  skip_ws(s);
  return plain_number(s, &xy[1]) && token(s, ']');
}

/* A plain polygon at s->at into xy (at most cap vertices): their count, or
 * 0 when not plain. */
static int plain_polygon(Scan *s, double *xy, int cap) {
  int n = 0;
  if (!token(s, '[')) return 0;
  do {
    if (n == cap || !plain_pair(s, xy + 2 * n)) return 0;
    n++;
  } while (token(s, ','));
  return token(s, ']') && n >= 3 ? n : 0;
}

/* A plain id: a string of printable ASCII without escapes, its characters
 * into lb (at most US_LANE_ID - 1 of them). */
static int plain_id(Scan *s, us_LaneBody *lb) {
  if (!token(s, '"')) return 0;
  size_t from = s->at;
  while (s->at < s->n && s->t[s->at] >= 0x20 && s->t[s->at] < 0x7f && s->t[s->at] != '"' &&
         s->t[s->at] != '\\')
    s->at++;
  size_t n = s->at - from;
  if (!token(s, '"') || n >= US_LANE_ID) return 0;
  memcpy(lb->id, s->t + from, n);
  lb->id[n] = '\0';
  return 1;
}

/* true or false, as a whole token. */
static int plain_bool(Scan *s, int *out) {
  skip_ws(s);
  int t = s->n - s->at >= 4 && !memcmp(s->t + s->at, "true", 4);
  int f = s->n - s->at >= 5 && !memcmp(s->t + s->at, "false", 5);
  if (!t && !f) return 0;
  s->at += t ? 4 : 5;
  *out = t;
  return s->at >= s->n || is_ws(s->t[s->at]) || s->t[s->at] == ',' || s->t[s->at] == '}';
}

/* The lane's keys, quotes included: 0 "id", 1 "polygon", 2 "fixed"; -1. */
static int key_index(const char *k, size_t n) {
  static const char *const keys[] = {"\"id\"", "\"polygon\"", "\"fixed\""};
  for (int i = 0; i < 3; i++)
    if (n == strlen(keys[i]) && !memcmp(k, keys[i], n)) return i;
  return -1;
}

int us_io_lane_body(const char *text, size_t len, double *xy, int cap, us_LaneBody *lb) {
  Scan s = {text, len, 0};
  int seen[3] = {0, 0, 0}; /* id, polygon, fixed */
  lb->fixed = 0, lb->nv = 0;
  if (!token(&s, '{')) return 0;
  do {
    skip_ws(&s);
    size_t key = s.at;
    if (s.at >= s.n || text[s.at] != '"' || !skip_string(&s)) return 0;
    int k = key_index(text + key, s.at - key);
    if (k < 0 || seen[k]++ || !token(&s, ':')) return 0; /* another key, or a repeated one */
    if (k == 0 && !plain_id(&s, lb)) return 0;
    if (k == 1 && !(lb->nv = plain_polygon(&s, xy, cap))) return 0;
    if (k == 2 && !plain_bool(&s, &lb->fixed)) return 0;
  } while (token(&s, ','));
  if (!token(&s, '}')) return 0;
  skip_ws(&s);
  return s.at == s.n && seen[0] && seen[1];
}

int us_io_split_polygon(const char *text, size_t len, us_JsonSpan *val, double *xy, int cap) {
  Scan s = {text, len, 0};
  int found = 0;
  if (!token(&s, '{')) return 0;
  if (token(&s, '}')) return 0;
  do {
    skip_ws(&s);
    size_t key = s.at;
    if (s.at >= s.n || text[s.at] != '"' || !skip_string(&s)) return 0;
    int poly = s.at - key == 9 && !memcmp(text + key, "\"polygon\"", 9);
    if (!token(&s, ':')) return 0;
    skip_ws(&s);
    size_t from = s.at;
    if (poly && found) return 0; /* a repeated key: jansson says so */
    int n = poly ? plain_polygon(&s, xy, cap) : skip_value(&s);
    if (!n) return 0;
    if (poly) found = n, *val = (us_JsonSpan){from, s.at - from};
  } while (token(&s, ','));
  return token(&s, '}') ? found : 0;
}
