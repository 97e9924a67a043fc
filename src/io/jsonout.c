/* Streaming JSON output for the writers, and the words used for enums in
 * plan files.
 *
 * Numbers are printed with the fewest significant digits, 15 to 17, that
 * read back (strtod) to exactly the same double, so files round-trip
 * bit-exactly and stay readable (0.1, not 0.10000000000000001). JSON has no
 * NaN or infinity: such a number sets `bad` and prints null, and the caller
 * then abandons the file. Strings are escaped per RFC 8259 (quote,
 * backslash, control characters); other characters pass through as UTF-8.
 * A string that is not valid UTF-8 (an id given through the C API) sets
 * `bad_text`: the file would not read back, so the caller abandons it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io.h"

void us_jo_number(us_JsonOut *o, double x) {
  if (!isfinite(x)) {
    o->bad = 1;
    fputs("null", o->fp);
    return;
  }
  char buf[40];
  for (int digits = 15; digits <= 17; digits++) {
    snprintf(buf, sizeof buf, "%.*g", digits, x);
    if (strtod(buf, NULL) == x) break;
  }
  fputs(buf, o->fp);
}

void us_jo_string(us_JsonOut *o, const char *s) {
  fputc('"', o->fp);
  while (*s) {
    uint32_t c;
    int n = us_utf8_next(s, &c);
    if (c == '"' || c == '\\')
      fprintf(o->fp, "\\%c", (char)c);
    else if (c < 0x20)
      fprintf(o->fp, "\\u%04x", (unsigned)c);
    else if (c == US_UTF8_INVALID)
      o->bad_text = 1, fputs("\\ufffd", o->fp);
    else
      fwrite(s, 1, (size_t)n, o->fp);
    s += n;
  }
  fputc('"', o->fp);
}

void us_jo_vec2(us_JsonOut *o, const double *v) {
  fputc('[', o->fp);
  us_jo_number(o, v[0]);
  fputs(", ", o->fp);
  us_jo_number(o, v[1]);
  fputc(']', o->fp);
}

void us_jo_vecn(us_JsonOut *o, const double *v, int n) {
  fputc('[', o->fp);
  for (int k = 0; k < n; k++) {
    if (k) fputs(", ", o->fp);
    us_jo_number(o, v[k]);
  }
  fputc(']', o->fp);
}

void us_jo_raw(us_JsonOut *o, const char *s) { fputs(s, o->fp); }


void us_jo_contact_fields(us_JsonOut *o, const us_Structure *s, const us_Contact *c) {
  us_jo_raw(o, "\"a\": ");
  us_jo_string(o, c->a == US_GROUND ? "ground" : s->bodies[c->a].id);
  us_jo_raw(o, ", \"b\": ");
  us_jo_string(o, s->bodies[c->b].id);
  us_jo_raw(o, ", \"point\": ");
  us_jo_vecn(o, c->p, s->dim == 3 ? 3 : 2);
  us_jo_raw(o, ", \"normal\": ");
  us_jo_vecn(o, c->n, s->dim == 3 ? 3 : 2);
}

void us_jo_cert_contact(us_JsonOut *o, const us_Structure *s, const us_Forces *f, int j) {
  const us_Contact *c = &s->contacts[f->contact[j]];
  const double *fc = f->f + (size_t)s->dim * (size_t)j;
  double w[3];
  for (int k = 0; k < 3; k++)
    w[k] = fc[0] * c->n[k] + fc[1] * c->t[0][k] + (s->dim == 3 ? fc[2] * c->t[1][k] : 0.0);
  us_jo_raw(o, "{");
  us_jo_contact_fields(o, s, c);
  us_jo_raw(o, ", \"force\": ");
  us_jo_vecn(o, fc, s->dim);
  us_jo_raw(o, ", \"force_xyz\": ");
  us_jo_vecn(o, w, s->dim);
  us_jo_raw(o, "}");
}
