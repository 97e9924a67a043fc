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
 * `bad_text`: the file would not read back, so the caller abandons it.
 *
 * Speed (a 100,000-block file has 800,000 numbers): a number that is a
 * short binary fraction (an integer, 0.5, 12.375: a multiple of 2^-16
 * below 10^15 with at most 15 significant digits) has an exact decimal
 * form, which is what "%.15g" prints and reads back to the same double;
 * it is written digit by digit, the same bytes without printf and strtod.
 * Strings are written in runs of plain characters, not byte by byte. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io.h"

/* Decimal digits of v (v < 10^19) into out, most significant first, at
 * least `width` of them (leading zeros); returns their count. */
static int put_digits(uint64_t v, int width, char *out) {
  char tmp[24];
  int n = 0;
  do tmp[n++] = (char)('0' + v % 10), v /= 10;
  while (v || n < width);
  for (int k = 0; k < n; k++) out[k] = tmp[n - 1 - k];
  return n;
}

/* x as "%.15g" writes it, when x is a short binary fraction (see the file
 * head): its exact decimal form, [-]int[.frac]; 0 when x is not such. */
static int exact_short(double x, char *buf) {
  double a = fabs(x);
  if (!(a < 1e15) || (a < 1e-4 && a != 0) || (x == 0 && signbit(x))) return 0;
  double ip = floor(a), f = a - ip; /* both exact: a < 2^53 */
  int m = 0;
  while (f != floor(f) && m < 16) f *= 2, m++; /* exact: doubling */
  if (f != floor(f)) return 0;
  uint64_t frac = (uint64_t)f, five = 1;
  for (int k = 0; k < m; k++) five *= 5;
  frac *= five; /* the fraction is frac / 10^m, frac < 2^16 * 5^16 < 10^19 */
  while (m > 0 && frac % 10 == 0) frac /= 10, m--;
  char ds[24], fs[24];
  int ni = ip > 0 ? put_digits((uint64_t)ip, 1, ds) : 0;
  int nf = m > 0 ? put_digits(frac, m, fs) : 0;
  int lead = 0; /* zeros after the point before the first significant digit */
  while (ni == 0 && lead < nf && fs[lead] == '0') lead++;
  if (ni + nf - lead > 15) return 0;
  int n = 0;
  if (x < 0) buf[n++] = '-';
  if (ni == 0) buf[n++] = '0';
  for (int k = 0; k < ni; k++) buf[n++] = ds[k];
  if (nf) buf[n++] = '.';
  for (int k = 0; k < nf; k++) buf[n++] = fs[k];
  buf[n] = '\0';
  return 1;
}

void us_jo_number(us_JsonOut *o, double x) {
  char buf[40];
  if (exact_short(x, buf)) {
    fputs(buf, o->fp);
    return;
  }
  if (!isfinite(x)) {
    o->bad = 1;
    fputs("null", o->fp);
    return;
  }
  for (int digits = 15; digits <= 17; digits++) {
    snprintf(buf, sizeof buf, "%.*g", digits, x);
    if (strtod(buf, NULL) == x) break;
  }
  fputs(buf, o->fp);
}

/* Length of the run of printable ASCII at s that needs no escape. */
static size_t plain_run(const char *s) {
  size_t n = 0;
  while (s[n] >= 0x20 && s[n] < 0x7f && s[n] != '"' && s[n] != '\\') n++;
  return n;
}

void us_jo_string(us_JsonOut *o, const char *s) {
  fputc('"', o->fp);
  while (*s) {
    size_t run = plain_run(s);
    if (run) {
      fwrite(s, 1, run, o->fp);
      s += run;
      continue;
    }
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
