/* Tests of "friction": "infinite" in structure files (docs/format.md): read
 * at the top level, on a body and on an explicit contact as mu = INFINITY,
 * written back as "infinite" and read back identical; other strings are
 * rejected with a message naming the field. */
#define _POSIX_C_SOURCE 200809L /* mkstemp */
#include <stdlib.h>
#include <unistd.h>

#include "scenes.h"
#include "test.h"

static const char *const text =
    "{\"friction\": \"infinite\", \"bodies\": [\n"
    "  {\"id\": \"a\", \"polygon\": [[0, 0], [1, 0], [1, 1], [0, 1]], \"friction\": 0.25},\n"
    "  {\"id\": \"b\", \"polygon\": [[0, 1], [1, 1], [1, 2], [0, 2]], \"friction\": \"infinite\"}\n"
    "]}\n";

static const char *const contacts_text =
    "{\"friction\": 0.5, \"bodies\": [\n"
    "  {\"id\": \"w\", \"center\": [0, 1], \"fixed\": true},\n"
    "  {\"id\": \"p\", \"center\": [0, 1], \"mass\": 2}],\n"
    " \"contacts\": [{\"a\": \"w\", \"b\": \"p\", \"point\": [0, 1], \"normal\": [1, 0],\n"
    "                \"friction\": \"infinite\"}]}\n";

/* Write s to a temporary file and read it back; NULL on failure. */
static us_Structure *round_trip(const us_Structure *s) {
  char path[] = "/tmp/us_test_io_friction.XXXXXX";
  int fd = mkstemp(path);
  if (fd < 0) return NULL;
  close(fd);
  us_Error err;
  us_Structure *t = NULL;
  if (us_structure_write(s, path, &err) == US_OK) t = us_structure_read(path, 0, &err);
  if (!t) fprintf(stderr, "round trip: %s\n", err.msg);
  unlink(path);
  return t;
}

static void reads_and_writes_infinite(void) {
  us_Error err;
  us_Structure *s = us_structure_parse(text, "inf.json", 0, &err);
  CHECK(s);
  CHECK(isinf(s->friction) && s->friction > 0);
  CHECK_NEAR(s->bodies[0].friction, 0.25, 0);
  CHECK(isinf(s->bodies[1].friction));
  int ninf = 0;
  for (int k = 0; k < s->ncontact; k++) ninf += isinf(s->contacts[k].mu) != 0;
  /* a-ground: min(0.25, inf); a-b: min(0.25, inf); only none is infinite */
  CHECK_INT(ninf, ==, 0);
  us_Structure *t = round_trip(s);
  CHECK(t);
  CHECK(isinf(t->friction) && isinf(t->bodies[1].friction));
  CHECK_NEAR(t->bodies[0].friction, 0.25, 0);
  CHECK_INT(t->ncontact, ==, s->ncontact);
  for (int k = 0; k < s->ncontact; k++) CHECK(t->contacts[k].mu == s->contacts[k].mu);
  us_structure_free(t);
  us_structure_free(s);
}

static void explicit_contact_infinite(void) {
  us_Error err;
  us_Structure *s = us_structure_parse(contacts_text, "peg.json", 0, &err);
  CHECK(s);
  CHECK_INT(s->ncontact, ==, 1);
  CHECK(isinf(s->contacts[0].mu));
  us_Structure *t = round_trip(s);
  CHECK(t);
  CHECK_INT(t->ncontact, ==, 1);
  CHECK(isinf(t->contacts[0].mu));
  /* the peg hangs only with infinite friction */
  us_Stability *w = us_stability_new(t, NULL, &err);
  CHECK(w);
  us_StabilityResult res;
  us_stability_result_init(&res);
  us_Status st = us_stability_test_full(w, &res, &err);
  us_Verdict v = res.verdict;
  us_stability_result_free(&res);
  us_stability_free(w);
  us_structure_free(t);
  us_structure_free(s);
  CHECK_OK(st, &err);
  CHECK_INT(v, ==, US_STABLE);
}

static void rejects_other_strings(void) {
  us_Error err;
  us_error_clear(&err);
  us_Structure *s = us_structure_parse("{\"friction\": \"inf\", \"bodies\": []}", "bad.json", 0,
                                       &err);
  CHECK(!s);
  CHECK_INT(err.code, ==, US_ERR_INPUT);
  CHECK(strstr(err.msg, "bad.json") && strstr(err.msg, "friction") &&
        strstr(err.msg, "infinite"));
}

US_TEST_MAIN(T(reads_and_writes_infinite), T(explicit_contact_infinite),
             T(rejects_other_strings))
