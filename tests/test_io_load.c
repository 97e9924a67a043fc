/* Tests of the fast paths of loading and writing (src/io/structure_split.c,
 * the streamed reader in structure_read.c, the number writer in jsonout.c):
 * each is compared with the plain path it replaces, which stays the
 * reference: the streamed reader with the reader of one JSON tree (same
 * structure bit for bit, or the same error and message), the polygon lane
 * with strtod, the short-number writer with printf's shortest round trip. */
#define _POSIX_C_SOURCE 200809L /* fmemopen */

#include "io/io.h"
#include "test.h"

#include <stdint.h>

/* ----------------------------------------------------------------- helpers */

static uint64_t rng = 0x9e3779b97f4a7c15ull;

static uint64_t next(void) {
  rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
  return rng;
}

static int below(int m) { return (int)(next() % (uint64_t)m); }

static int same_bits(const void *a, const void *b, size_t n) { return !memcmp(a, b, n); }

/* Both readers on text: 1 when they agree (structure or error). */
static int readers_agree(const char *text) {
  us_Error e1, e2;
  us_Structure *a = us_structure_parse(text, "t.json", 0, &e1);
  us_Structure *b = us_io_parse_whole(text, "t.json", 0, &e2);
  int ok = !a == !b;
  if (ok && !a) ok = e1.code == e2.code && !strcmp(e1.msg, e2.msg);
  if (ok && a) ok = a->nbody == b->nbody && a->ncontact == b->ncontact;
  for (int i = 0; ok && a && i < a->nbody; i++) {
    const us_Body *p = &a->bodies[i], *q = &b->bodies[i];
    ok = !strcmp(p->id, q->id) && p->nvert == q->nvert && p->fixed == q->fixed &&
         same_bits(&p->mass, &q->mass, sizeof p->mass) && same_bits(p->com, q->com, sizeof p->com) &&
         same_bits(&p->friction, &q->friction, sizeof p->friction) &&
         (!p->nvert || same_bits(p->verts, q->verts, (size_t)p->nvert * 2 * sizeof(double)));
  }
  for (int k = 0; ok && a && k < a->ncontact; k++)
    ok = same_bits(&a->contacts[k], &b->contacts[k], sizeof(us_Contact));
  if (!ok)
    fprintf(stderr, "readers differ on:\n%s\nstreamed: %s\nwhole: %s\n", text,
            a ? "ok" : e1.msg, b ? "ok" : e2.msg);
  us_structure_free(a);
  us_structure_free(b);
  return ok;
}

static const char *const base_doc =
    "{\"friction\": 0.6, \"bodies\": [\n"
    "  {\"id\": \"a\", \"polygon\": [[0, 0], [2, 0], [2, 1], [0, 1]]},\n"
    "  {\"id\": \"b [x]\", \"polygon\": [[0.5, 1], [1.5, 1], [1.5, 1.25], [0.5, 1.25]],"
    " \"density\": 2},\n"
    "  {\"polygon\": [[-1, 0], [-0.0, 0], [0e0, 1], [-1, 1]], \"id\": \"c\\\"q\\\\\"},\n"
    "  {\"id\": \"d\", \"fixed\": true, \"polygon\": [[2, 0], [3.000000000000001, 0], "
    "[3, 1.5], [2, 1.5]]},\n"
    "  {\"id\": \"e\", \"fixed\": false, \"polygon\": [[3, 0], [4, 0], [4, 1], [3, 1]]}\n"
    "], \"_note\": \"{[\\\"]}\"}\n";

/* ------------------------------------------------------------------ cases */

/* Hand-picked documents: valid ones and the traps of a text split
 * (escaped keys, repeated keys, brackets in strings, syntax errors after
 * a bad body, non-plain numbers). */
static void streamed_equals_whole(void) {
  static const char *const docs[] = {
      "{\"bodies\": []}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}]}",
      "\xEF\xBB\xBF{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}]}",
      "{\"\\u0062odies\": [{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}]}",
      "{\"bodies\": [], \"bodies\": []}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]], "
      "\"polygon\": [[0,0],[1,0],[1,1]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"p\\u006flygon\": [[0,0],[1,0],[1,1],[0,1]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[1e0,0],[1,1E0],[0,1]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]},]}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]} {}]}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[01,0],[1,1],[0,1]]}]}",
      "{\"bodies\": [{\"id\": 5}, {\"id\": \"b\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]] x}]}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]},"
      " {\"id\": \"a\", \"polygon\": [[0,2],[1,2],[1,3],[0,3]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]},"
      " {\"id\": \"b\", \"polygon\": [[0.5,0.5],[1.5,0.5],[1.5,1.5],[0.5,1.5]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}], \"dimension\": 3}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[1,0]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1],[0,1,2]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}]} trailing",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0.12345678901234567,0],[1,0],[1,1],[0,1]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[-0,0],[1,-0.0],[1,1],[0,1]]}]}",
      "{\"bodies\": {\"id\": \"a\"}}",
      "[1, 2]",
      "{\"bodies\": [\"a\\\"]\", 3]}",
      base_doc,
      /* the whole-body lane: plain id, polygon, fixed, and its near misses */
      "{\"bodies\": [{\"id\": \"a\", \"fixed\": true, \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"fixed\": 1, \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"fixed\": truex, \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}]}",
      "{\"bodies\": [{\"id\": \"ground\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}]}",
      "{\"bodies\": [{\"id\": \"\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"id\": \"b\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}]}",
      "{\"bodies\": [{\"id\": \"\\u0067round\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}]}",
      "{\"bodies\": [{\"id\": \"\xC3\xA9t\xC3\xA9\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}], \"dimension\": 3}",
      "{\"dimension\": 2, \"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]},"
      " {\"id\": \"a\", \"polygon\": [[2,0],[3,0],[3,1],[2,1]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]},"
      " {\"id\": \"b\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}]}",
      "{\"ground\": false, \"bodies\": [{\"id\": \"a\", \"polygon\": [[0,-1],[1,-1],[1,1],[0,1]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,-1],[1,-1],[1,1],[0,1]]}]}",
  };
  for (size_t k = 0; k < sizeof docs / sizeof docs[0]; k++) CHECK(readers_agree(docs[k]));
}

/* Random edits of a valid document (JSON's structural characters, digits,
 * quotes and escapes inserted, deleted or replaced): both readers agree on
 * every one, error messages included. */
static void streamed_equals_whole_mutations(void) {
  static const char alphabet[] = "[]{}\",:.-+eE0123456789 \n\\u";
  size_t n = strlen(base_doc);
  char *buf = malloc(n + 8);
  CHECK(buf);
  int rounds = 4000, failed = 0;
  for (int r = 0; r < rounds && !failed; r++) {
    memcpy(buf, base_doc, n + 1);
    size_t len = n;
    for (int e = 0; e < 1 + below(3); e++) {
      size_t at = (size_t)below((int)len);
      char c = alphabet[below((int)sizeof alphabet - 1)];
      int op = below(3);
      if (op == 0) buf[at] = c;
      else if (op == 1) memmove(buf + at, buf + at + 1, len - at), len--;
      else if (len < n + 4) memmove(buf + at + 1, buf + at, len - at + 1), buf[at] = c, len++;
    }
    failed = !readers_agree(buf);
  }
  free(buf);
  CHECK(!failed);
}

/* Plain numbers read by the lane are strtod's values, bit for bit. */
static void polygon_lane_numbers(void) {
  for (int r = 0; r < 20000; r++) {
    char num[6][40], text[400];
    for (int k = 0; k < 6; k++) {
      int ni = below(8), nf = below(9), p = 0;
      if (below(4) == 0) num[k][p++] = '-';
      if (ni == 0 || below(5) == 0) num[k][p++] = '0';
      else
        for (int d = 0; d < ni; d++) num[k][p++] = (char)('0' + (d ? below(10) : 1 + below(9)));
      if (nf) num[k][p++] = '.';
      for (int d = 0; d < nf; d++) num[k][p++] = (char)('0' + below(10));
      num[k][p] = '\0';
    }
    snprintf(text, sizeof text, "{\"id\": \"x\", \"polygon\": [[%s, %s],[%s,%s] , [ %s ,%s ]]}",
             num[0], num[1], num[2], num[3], num[4], num[5]);
    double xy[8];
    us_JsonSpan v;
    CHECK_INT(us_io_split_polygon(text, strlen(text), &v, xy, 4), ==, 3);
    CHECK(text[v.off] == '[' && text[v.off + v.len - 1] == ']');
    for (int k = 0; k < 6; k++) {
      double ref = strtod(num[k], NULL);
      if (!same_bits(&xy[k], &ref, sizeof ref)) {
        fprintf(stderr, "%s: lane %.17g, strtod %.17g\n", num[k], xy[k], ref);
        CHECK(0);
      }
    }
  }
}

/* What is not plain is left to jansson (0). */
static void polygon_lane_refuses(void) {
  static const char *const docs[] = {
      "{\"polygon\": [[1e0,0],[1,0],[1,1]]}",          /* exponent */
      "{\"polygon\": [[01,0],[1,0],[1,1]]}",           /* leading zero */
      "{\"polygon\": [[1.,0],[1,0],[1,1]]}",           /* no fraction digits */
      "{\"polygon\": [[.5,0],[1,0],[1,1]]}",           /* no integer digits */
      "{\"polygon\": [[1234567890.123456,0],[1,0],[1,1]]}", /* 16 significant digits */
      "{\"polygon\": [[0,0],[1,0]]}",                  /* 2 vertices */
      "{\"polygon\": [[0,0,0],[1,0],[1,1]]}",          /* 3 numbers */
      "{\"polygon\": [[0,0],[1,0],[1,1],]}",           /* trailing comma */
      "{\"polygon\": [[0,0],[1,0],[1,1]], \"polygon\": []}", /* repeated key */
      "{\"polygon\": [[0,0],[1,0],[1,1]] \"id\": 1}",  /* missing comma */
      "{\"polygon\": [[0,0],[1,0],[1,\"1\"]]}",        /* a string */
      "{\"id\": \"a\"}",                               /* no polygon */
      "{\"polygon\": [[0,0],[1,0],[1,1],[0,1],[0,0.5]]}", /* more than cap (4) */
  };
  for (size_t k = 0; k < sizeof docs / sizeof docs[0]; k++) {
    double xy[8];
    us_JsonSpan v;
    if (us_io_split_polygon(docs[k], strlen(docs[k]), &v, xy, 4) != 0) {
      fprintf(stderr, "taken: %s\n", docs[k]);
      CHECK(0);
    }
  }
  double xy[8];
  us_JsonSpan v;
  const char *ok = "{\"polygon\":[[0,0],[0.000125,-2],[123456789012345,1]]}";
  CHECK_INT(us_io_split_polygon(ok, strlen(ok), &v, xy, 4), ==, 3);
  CHECK(xy[2] == 0.000125 && xy[3] == -2 && xy[4] == 123456789012345.0);
}

/* The whole-body lane takes only id, polygon and fixed, each once and
 * plain; it reads the id and the flag as jansson would. */
static void lane_body(void) {
  double xy[8];
  us_LaneBody lb;
  const char *ok = " { \"fixed\" : true , \"polygon\":[[0,0],[1,0],[1,1]], \"id\": \"b 7\" } ";
  CHECK_INT(us_io_lane_body(ok, strlen(ok), xy, 4, &lb), ==, 1);
  CHECK(!strcmp(lb.id, "b 7") && lb.fixed == 1 && lb.nv == 3 && xy[4] == 1);
  static const char *const refused[] = {
      "{\"id\": \"a\"}",                                         /* no polygon */
      "{\"polygon\": [[0,0],[1,0],[1,1]]}",                        /* no id */
      "{\"id\": \"a\\n\", \"polygon\": [[0,0],[1,0],[1,1]]}",     /* an escape */
      "{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1]], \"mass\": 1}", /* another key */
      "{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1]], \"fixed\": null}",
      "{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1]], \"fixed\": true, \"fixed\": true}",
      "{\"id\": \"a\", \"polygon\": [[0,0],[1,0],[1,1]]} x",
      "{\"id\": 3, \"polygon\": [[0,0],[1,0],[1,1]]}",
      "{\"id\": \"0123456789012345678901234567890123456789012345678901234567890123\", "
      "\"polygon\": [[0,0],[1,0],[1,1]]}", /* 64 characters */
  };
  for (size_t k = 0; k < sizeof refused / sizeof refused[0]; k++)
    if (us_io_lane_body(refused[k], strlen(refused[k]), xy, 4, &lb) != 0) {
      fprintf(stderr, "taken: %s\n", refused[k]);
      CHECK(0);
    }
}

/* The split follows strings and nesting, and gives up on what is not a
 * plain top-level "bodies" array. */
static void split_spans(void) {
  us_BodySpans b;
  const char *t = "{\"a\": \"]\\\"[\", \"bodies\" : [ {\"id\": \"}\"} , [1, [2]], \"x,\" ,3 ] }";
  CHECK_INT(us_io_split_bodies(t, strlen(t), &b), ==, 1);
  CHECK_INT(b.n, ==, 4);
  CHECK(!strncmp(t + b.el[0].off, "{\"id\": \"}\"}", b.el[0].len));
  CHECK(!strncmp(t + b.el[1].off, "[1, [2]]", b.el[1].len));
  CHECK(!strncmp(t + b.el[2].off, "\"x,\"", b.el[2].len));
  CHECK(!strncmp(t + b.el[3].off, "3", b.el[3].len));
  CHECK(t[b.arr_off] == '[' && t[b.arr_off + b.arr_len - 1] == ']');
  us_io_spans_free(&b);
  static const char *const refused[] = {"{\"bodies\": 3}", "{\"bodies\": [1,]}", "{\"x\": 1}",
                                        "{\"bodies\": [1], \"bodies\": [2]}", "[]",
                                        "{\"bodies\": [1 2]}", "{\"bodies\": [1"};
  for (size_t k = 0; k < sizeof refused / sizeof refused[0]; k++) {
    int r = us_io_split_bodies(refused[k], strlen(refused[k]), &b);
    us_io_spans_free(&b);
    if (r == 1 && !strcmp(refused[k], "{\"bodies\": [1 2]}")) continue; /* jansson refuses "1 2" */
    CHECK_INT(r, ==, 0);
  }
}

/* The number writer: printf's shortest round trip (15 to 17 digits), byte
 * for byte, for short binary fractions (the fast path) and any double. */
static void number_writer(void) {
  for (int r = 0; r < 40000; r++) {
    double x;
    int kind = below(4);
    if (kind == 0) x = (double)((int64_t)(next() >> below(64)) >> below(20)) / (double)(1 << below(17));
    else if (kind == 1) x = (double)(int64_t)(next() % 2000001) / 8.0 - 125000.0;
    else if (kind == 2) x = ldexp((double)(next() >> 11), below(120) - 100);
    else {
      uint64_t bits = next();
      memcpy(&x, &bits, sizeof x);
      if (!isfinite(x)) x = 0.1 * below(1000);
    }
    if (below(3) == 0) x = -x;
    char ref[40], got[64] = {0};
    for (int digits = 15; digits <= 17; digits++) {
      snprintf(ref, sizeof ref, "%.*g", digits, x);
      if (strtod(ref, NULL) == x) break;
    }
    FILE *fp = fmemopen(got, sizeof got - 1, "w");
    CHECK(fp);
    us_JsonOut o = {fp, 0, 0};
    us_jo_number(&o, x);
    fclose(fp);
    if (strcmp(ref, got)) {
      fprintf(stderr, "%.17g: writer '%s', printf '%s'\n", x, got, ref);
      CHECK(0);
    }
  }
}

US_TEST_MAIN(T(streamed_equals_whole), T(streamed_equals_whole_mutations), T(polygon_lane_numbers),
             T(polygon_lane_refuses), T(lane_body), T(split_spans), T(number_writer))
