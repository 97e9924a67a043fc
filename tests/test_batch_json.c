/* batch's JSON line writer (tools/batch_json.c) against jansson, the
 * independent reference: the same object dumped by json_dumps with batch's
 * former flags must be the same text, for random strings (controls,
 * quotes, backslashes, bytes that are not UTF-8, valid multi-byte
 * sequences and jansson's refused ones) and reals of every magnitude. */
#include "../tools/batch_json.c"

#include <jansson.h>

#include "test.h"

/* The string batch_run.c gave jansson before: '?' for every byte from
 * 0x80 when the text is not UTF-8. */
static json_t *ref_text(const char *s) {
  json_t *j = json_string(s);
  if (j) return j;
  char *c = strdup(s);
  for (unsigned char *p = (unsigned char *)c; *p; p++)
    if (*p >= 0x80) *p = '?';
  j = json_string(c);
  free(c);
  return j;
}

/* {"file": text, "time": x} both ways; 1 if equal (printed if not). */
static int same(const char *text, double x) {
  json_t *o = json_object();
  json_object_set_new(o, "file", ref_text(text));
  json_object_set_new(o, "time", json_real(x));
  char *a = json_dumps(o, JSON_COMPACT | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(9));
  json_decref(o);
  JLine l;
  jl_open(&l);
  jl_key(&l, "file"), jl_str(&l, text);
  jl_key(&l, "time"), jl_real(&l, x);
  char *b = jl_close(&l);
  int ok = a && b && strlen(b) > 0 && !strncmp(a, b, strlen(b) - 1) && strlen(a) == strlen(b) - 1;
  if (!ok) fprintf(stderr, "  jansson %s\n  ours    %s", a ? a : "(null)", b ? b : "(null)\n");
  free(a), free(b);
  return ok;
}

static void fixed_cases(void) {
  const char *text[] = {"set/random-001.json", "\xc3\xa9t\xc3\xa9", "\xF0\x9F\x98\x80",
                        "\xED\xA0\x80", "\xC0\xAF", "\xE0\x80\xAF", "\xF4\x90\x80\x80",
                        "a\x7f\x1f/\\\"\b\f\n\r\t", "\xF4\x8F\xBF\xBF", "\xC2\x80\xDF\xBF",
                        "\xc3\xa9\xff", ""};
  const double x[] = {0.0, -0.0, 1e-5, 1.5e-7, 123456789.0, 1e21, 1e-300, 5e-324, 0.000051,
                      1.0, 100.0, 1e9, 1.23456789012e10, -2.5e-12};
  for (size_t i = 0; i < sizeof text / sizeof text[0]; i++)
    for (size_t k = 0; k < sizeof x / sizeof x[0]; k++) CHECK(same(text[i], x[k]));
}

static void random_cases(void) {
  unsigned long long st = 88172645463325252ULL;
  int bad = 0;
  for (int it = 0; it < 200000 && bad < 5; it++) {
    char text[12];
    int n = 1 + (int)(test_rnd(&st) * 10);
    for (int k = 0; k < n; k++) {
      int c = 1 + (int)(test_rnd(&st) * 255); /* any byte but NUL */
      text[k] = (char)(test_rnd(&st) < 0.5 ? c & 0x7F ? c & 0x7F : 'b' : c);
    }
    text[n] = '\0';
    double x = ldexp(test_rnd(&st), (int)(test_rnd(&st) * 120) - 60);
    if (test_rnd(&st) < 0.3) x = round(x * 1e6) / 1e6;
    if (test_rnd(&st) < 0.2) x = -floor(x * 1e4);
    bad += !same(text, x);
  }
  CHECK_INT(bad, ==, 0);
}

US_TEST_MAIN(T(fixed_cases), T(random_cases))
