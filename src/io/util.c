/* Reading helpers shared by the structure and plan readers: whole-file
 * input, JSON parsing with file:line:column syntax errors, and typed field
 * readers whose messages name the file, the JSON path and the field.
 *
 * Numbers: documents are parsed with JSON_DECODE_INT_AS_REAL, so every
 * number is a double; jansson itself rejects NaN, Infinity and numbers that
 * overflow a double, as syntax errors with a position. Duplicate keys in an
 * object are syntax errors too (JSON_REJECT_DUPLICATES). A UTF-8 byte order
 * mark at the start of a file (some Windows editors write one) is skipped.
 *
 * Text: jansson rejects invalid UTF-8, lone surrogates (\uD800) and NUL
 * (\u0000) in strings as syntax errors with the line, so ids read from files
 * are valid UTF-8. Control characters (\u001b, newlines) are accepted in ids;
 * every message quotes ids through us_id_text and the SVG writer replaces
 * what XML cannot hold, so they never reach a terminal or a file raw. */
#define _POSIX_C_SOURCE 200809L /* fileno */
#include <errno.h>
#include <stdint.h>
#include <sys/stat.h>
#include <math.h>
#include <stdarg.h>
#include <string.h>

#include "io.h"

us_Status us_io_bad(const us_IoCtx *c, const char *where, const char *fmt, ...) {
  char detail[400];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(detail, sizeof detail, fmt, ap);
  va_end(ap);
  if (where && *where)
    return us_error_set(c->err, US_ERR_INPUT, "%s: %s: %s", c->name, where, detail);
  return us_error_set(c->err, US_ERR_INPUT, "%s: %s", c->name, detail);
}

/* The text fed to jansson, stopped once past the deadline (the clock is
 * read after each MB). */
typedef struct Feed {
  const char *text;
  size_t len, at, check;
  double deadline;
  int late;
} Feed;

static size_t feed(void *buf, size_t n, void *data) {
  Feed *f = data;
  if (f->at >= f->check && (f->check += (size_t)1 << 20) && us_past(f->deadline))
    return f->late = 1, (size_t)-1;
  size_t k = US_MIN(n, f->len - f->at);
  memcpy(buf, f->text + f->at, k);
  f->at += k;
  return k;
}

json_t *us_io_parse_json(const us_IoCtx *c, const char *text, size_t len) {
  return us_io_parse_json_until(c, text, len, 0.0);
}

json_t *us_io_parse_json_until(const us_IoCtx *c, const char *text, size_t len, double deadline) {
  json_error_t je;
  if (len >= 3 && !memcmp(text, "\xEF\xBB\xBF", 3)) text += 3, len -= 3; /* UTF-8 BOM */
  size_t flags = US_IO_JSON_FLAGS;
  Feed f = {text, len, 0, (size_t)1 << 20, deadline, 0};
  json_t *root = deadline > 0 ? json_load_callback(feed, &f, flags, &je) : json_loadb(text, len, flags, &je);
  if (root) return root;
  if (f.late) {
    us_error_set(c->err, US_ERR_TIME_LIMIT, "%s: time limit reached parsing the file", c->name);
    return NULL;
  }
  if (je.line > 0)
    us_error_set(c->err, US_ERR_PARSE, "%s:%d:%d: %s", c->name, je.line, je.column, je.text);
  else
    us_error_set(c->err, US_ERR_PARSE, "%s: %s", c->name, je.text);
  return NULL;
}

char *us_io_slurp(const char *path, size_t *len, us_Error *err) {
  FILE *fp = fopen(path, "rb");
  if (!fp) {
    us_error_set(err, US_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    return NULL;
  }
  size_t n = 0, cap = 1 << 16;
  struct stat st; /* a regular file is read in one go into a block of its size */
  if (fstat(fileno(fp), &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0 &&
      (uintmax_t)st.st_size < SIZE_MAX / 2)
    cap = (size_t)st.st_size + 2;
  char *buf = us_malloc(cap);
  while (buf) {
    n += fread(buf + n, 1, cap - 1 - n, fp);
    if (n < cap - 1) break; /* end of file or an error, told apart below */
    char *bigger = us_realloc(buf, cap * 2);
    if (!bigger) us_free(buf);
    buf = bigger;
    cap *= 2;
  }
  int bad = buf ? ferror(fp) : 0;
  int e = errno;
  fclose(fp);
  if (!buf) {
    us_error_set(err, US_ERR_NOMEM, "%s: out of memory reading the file", path);
    return NULL;
  }
  if (bad) {
    us_free(buf);
    us_error_set(err, US_ERR_IO, "%s: cannot read: %s", path, strerror(e));
    return NULL;
  }
  buf[n] = '\0';
  *len = n;
  return buf;
}

us_Status us_io_check_keys(const us_IoCtx *c, const char *where, json_t *obj,
                           const char *const *allowed) {
  const char *key;
  json_t *v;
  json_object_foreach(obj, key, v) {
    if (key[0] == '_') continue;
    int known = 0;
    for (int i = 0; allowed[i] && !known; i++) known = strcmp(key, allowed[i]) == 0;
    if (!known) return us_io_bad(c, where, "unknown field '%s'", us_id_text(key).s);
  }
  return US_OK;
}

us_Status us_io_number(const us_IoCtx *c, const char *where, const char *field, json_t *v,
                       double *out) {
  if (!json_is_number(v)) return us_io_bad(c, where, "%s: expected a number", field);
  double x = json_number_value(v);
  if (!isfinite(x)) return us_io_bad(c, where, "%s: number is not finite", field);
  *out = x;
  return US_OK;
}

us_Status us_io_sign_number(const us_IoCtx *c, const char *where, const char *field, json_t *v,
                            int positive, double *out) {
  us_Status st = us_io_number(c, where, field, v, out);
  if (st) return st;
  if (positive && !(*out > 0)) return us_io_bad(c, where, "%s: must be > 0 (got %g)", field, *out);
  if (!positive && !(*out >= 0))
    return us_io_bad(c, where, "%s: must be >= 0 (got %g)", field, *out);
  return US_OK;
}

us_Status us_io_vec2(const us_IoCtx *c, const char *where, const char *field, json_t *v,
                     double out[2]) {
  if (!json_is_array(v) || json_array_size(v) != 2 || !json_is_number(json_array_get(v, 0)) ||
      !json_is_number(json_array_get(v, 1)))
    return us_io_bad(c, where, "%s: expected [x, y] with 2 numbers", field);
  out[0] = json_number_value(json_array_get(v, 0));
  out[1] = json_number_value(json_array_get(v, 1));
  if (!isfinite(out[0]) || !isfinite(out[1]))
    return us_io_bad(c, where, "%s: number is not finite", field);
  return US_OK;
}

us_Status us_io_vecn(const us_IoCtx *c, const char *where, const char *field, json_t *v, int n,
                     double *out) {
  static const char *const shape[] = {"", "", "[x, y]", "[x, y, z]", "[w, x, y, z]"};
  int ok = json_is_array(v) && json_array_size(v) == (size_t)n;
  for (int k = 0; ok && k < n; k++) ok = json_is_number(json_array_get(v, (size_t)k));
  if (!ok) return us_io_bad(c, where, "%s: expected %s with %d numbers", field, shape[n], n);
  for (int k = 0; k < n; k++) {
    out[k] = json_number_value(json_array_get(v, (size_t)k));
    if (!isfinite(out[k])) return us_io_bad(c, where, "%s: number is not finite", field);
  }
  return US_OK;
}

us_Status us_io_bool(const us_IoCtx *c, const char *where, const char *field, json_t *v, int *out) {
  if (!json_is_boolean(v)) return us_io_bad(c, where, "%s: expected true or false", field);
  *out = json_is_true(v);
  return US_OK;
}
