/* Streaming JSON output for the writers, and the words used for enums in
 * plan files.
 *
 * Numbers are printed with the fewest significant digits, 15 to 17, that
 * read back (strtod) to exactly the same double, so files round-trip
 * bit-exactly and stay readable (0.1, not 0.10000000000000001). JSON has no
 * NaN or infinity: such a number sets `bad` and prints null, and the caller
 * then abandons the file. Strings are escaped per RFC 8259 (quote,
 * backslash, control characters); other bytes pass through as UTF-8. */
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
  for (; *s; s++) {
    unsigned char ch = (unsigned char)*s;
    if (ch == '"' || ch == '\\')
      fprintf(o->fp, "\\%c", ch);
    else if (ch < 0x20)
      fprintf(o->fp, "\\u%04x", ch);
    else
      fputc(ch, o->fp);
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

void us_jo_raw(us_JsonOut *o, const char *s) { fputs(s, o->fp); }

static const char *const status_words[] = {"found", "none", "unstable", "limit"};
static const char *const method_words[] = {"lp", "lpsolve", "lcp", "lcp-reuse"};
static const char *const search_words[] = {"dfs", "bfs"};
static const char *const order_words[] = {"highest", "lowest", "input"};
static const char *const direction_words[] = {"down", "up"};

/* Table lookup with a fallback for out-of-range values. */
static const char *word(const char *const *table, int n, int v) {
  return v >= 0 && v < n ? table[v] : "unknown";
}

const char *us_io_plan_status_word(us_PlanStatus s) { return word(status_words, 4, (int)s); }
const char *us_io_method_word(us_Method m) { return word(method_words, 4, (int)m); }
const char *us_io_search_word(us_Search s) { return word(search_words, 2, (int)s); }
const char *us_io_order_word(us_Order o) { return word(order_words, 3, (int)o); }
const char *us_io_direction_word(us_Direction d) { return word(direction_words, 2, (int)d); }

int us_io_plan_status_parse(const char *w, us_PlanStatus *out) {
  for (int i = 0; i < 4; i++)
    if (!strcmp(w, status_words[i])) {
      *out = (us_PlanStatus)i;
      return 0;
    }
  return -1;
}

void us_jo_contact_fields(us_JsonOut *o, const us_Structure *s, const us_Contact *c) {
  us_jo_raw(o, "\"a\": ");
  us_jo_string(o, c->a == US_GROUND ? "ground" : s->bodies[c->a].id);
  us_jo_raw(o, ", \"b\": ");
  us_jo_string(o, s->bodies[c->b].id);
  us_jo_raw(o, ", \"point\": ");
  us_jo_vec2(o, c->p);
  us_jo_raw(o, ", \"normal\": ");
  us_jo_vec2(o, c->n);
}
