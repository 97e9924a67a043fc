/* One JSON line written straight into a growing buffer, for batch's
 * per-input lines: the text jansson's json_dumps gives for the same object
 * with JSON_COMPACT | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(9), without
 * building the object (for inputs of 20 blocks, building and dumping it
 * was 3-4 % of the batch's CPU).
 *
 * The rules copied from jansson 2.14 (dump.c, strconv.c, utf8.c), which
 * tests/test_batch_json.c holds against it: strings escape '"', '\\' and
 * controls (\b \f \n \r \t by name, the rest \u00XX in capitals) and pass
 * other UTF-8 through; text that is not UTF-8 (jansson's check: no
 * overlong forms, surrogates or code points past U+10FFFF) is written with
 * '?' for every byte from 0x80 (as batch_run.c did before, since jansson
 * refuses it); reals are "%.9g", with ".0" added when neither '.' nor 'e'
 * shows, and the exponent without '+' or leading zeros. */
#define _POSIX_C_SOURCE 200809L
#include "batch.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Room for n more bytes and the final NUL; 0 or -1 (oom set). */
static int room(JLine *l, size_t n) {
  if (l->oom) return -1;
  if (l->len + n + 1 <= l->cap) return 0;
  size_t cap = l->cap ? l->cap : 256;
  while (cap < l->len + n + 1) cap *= 2;
  char *s = realloc(l->s, cap);
  if (!s) return l->oom = 1, -1;
  l->s = s, l->cap = cap;
  return 0;
}

static void put(JLine *l, const char *text, size_t n) {
  if (room(l, n)) return;
  memcpy(l->s + l->len, text, n);
  l->len += n;
  l->s[l->len] = '\0';
}

/* The length of the UTF-8 sequence at s (1 to 4), or 0 if it is none. */
static int utf8_seq(const unsigned char *s) {
  unsigned c = s[0];
  int n = c < 0x80 ? 1 : c < 0xC2 ? 0 : c < 0xE0 ? 2 : c < 0xF0 ? 3 : c < 0xF5 ? 4 : 0;
  if (n <= 1) return n;
  unsigned long v = c & (0x3Fu >> (n - 1));
  for (int k = 1; k < n; k++) {
    if ((s[k] & 0xC0) != 0x80) return 0;
    v = (v << 6) | (s[k] & 0x3Fu);
  }
  if ((n == 3 && v < 0x800) || (n == 4 && v < 0x10000)) return 0; /* overlong */
  if ((v >= 0xD800 && v <= 0xDFFF) || v > 0x10FFFF) return 0;
  return n;
}

static int is_utf8(const char *s) {
  for (const unsigned char *p = (const unsigned char *)s; *p;) {
    int n = utf8_seq(p);
    if (!n) return 0;
    p += n;
  }
  return 1;
}

void jl_str(JLine *l, const char *text) {
  int valid = is_utf8(text);
  put(l, "\"", 1);
  for (const unsigned char *p = (const unsigned char *)text; *p; p++) {
    const char *esc = *p == '"' ? "\\\"" : *p == '\\' ? "\\\\" : *p == '\b' ? "\\b"
                    : *p == '\f' ? "\\f" : *p == '\n' ? "\\n" : *p == '\r' ? "\\r"
                    : *p == '\t' ? "\\t" : NULL;
    char u[8];
    if (!esc && *p < 0x20) snprintf(u, sizeof u, "\\u%04X", (unsigned)*p), esc = u;
    if (esc) put(l, esc, strlen(esc));
    else put(l, !valid && *p >= 0x80 ? "?" : (const char *)p, 1);
  }
  put(l, "\"", 1);
}

void jl_key(JLine *l, const char *key) {
  if (l->len > 1) put(l, ",", 1);
  jl_str(l, key);
  put(l, ":", 1);
}

void jl_raw(JLine *l, const char *text) { put(l, text, strlen(text)); }

void jl_int(JLine *l, long long v) {
  char b[32];
  int n = snprintf(b, sizeof b, "%lld", v);
  put(l, b, (size_t)n);
}

void jl_real(JLine *l, double x) {
  if (!isfinite(x)) return jl_raw(l, "null");
  char b[48];
  int n = snprintf(b, sizeof b, "%.9g", x);
  if (n < 0 || n >= (int)sizeof b - 3) return jl_raw(l, "null");
  if (!strchr(b, '.') && !strchr(b, 'e')) memcpy(b + n, ".0", 3), n += 2;
  char *e = strchr(b, 'e');
  if (e) { /* e+05 -> e5, e-05 -> e-5 */
    char *start = e + 1, *end = start + 1;
    if (*start == '-') start++;
    while (*end == '0') end++;
    memmove(start, end, strlen(end) + 1);
    n = (int)strlen(b);
  }
  put(l, b, (size_t)n);
}

void jl_open(JLine *l) {
  memset(l, 0, sizeof *l);
  put(l, "{", 1);
}

char *jl_close(JLine *l) {
  put(l, "}\n", 2);
  if (l->oom) return free(l->s), NULL;
  return l->s;
}
