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
