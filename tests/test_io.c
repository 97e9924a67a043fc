/* Tests of src/io: the example structures read and stand (or fall) as their
 * notes say, structures and plans round-trip exactly, every bad input file
 * fails with its documented message, failed writes leave no file, and
 * thousands of random mutations of valid files neither crash nor leak. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */

#include <dirent.h>
#include <jansson.h>
#include <unistd.h>

#include "test.h"

static const char *const good_files[] = {"column3.json",  "cantilever.json", "leaning.json",
                                         "explicit.json", "lean_wall.json",  "lean_wall_mu0.json"};
#define NGOOD ((int)(sizeof good_files / sizeof good_files[0]))

/* ----------------------------------------------------------------- helpers */

static char tmpdir[64];

static void remove_tmpdir(void) { rmdir(tmpdir); }

/* Path of a scratch file in this run's private directory. */
static const char *tmp_path(char *buf, size_t n, const char *name) {
  if (!tmpdir[0]) {
    snprintf(tmpdir, sizeof tmpdir, "/tmp/us_test_io.XXXXXX");
    if (!mkdtemp(tmpdir)) {
      perror("mkdtemp");
      exit(1);
    }
    atexit(remove_tmpdir);
  }
  snprintf(buf, n, "%s/%s", tmpdir, name);
  return buf;
}

static const char *data_path(char *buf, size_t n, const char *name) {
  if (strlen(name) + strlen(US_TEST_DATA) + 2 > n) return "";
  snprintf(buf, n, "%s/%s", US_TEST_DATA, name);
  return buf;
}

static us_Structure *read_data(const char *name, us_Error *err) {
  char p[512];
  return us_structure_read(data_path(p, sizeof p, name), 0, err);
}

/* Whole file as a NUL-terminated string (malloc'd: test scaffolding). */
static char *read_text(const char *path) {
  FILE *fp = fopen(path, "rb");
  if (!fp) return NULL;
  fseek(fp, 0, SEEK_END);
  long n = ftell(fp);
  fseek(fp, 0, SEEK_SET);
  char *t = malloc((size_t)n + 1);
  size_t got = fread(t, 1, (size_t)n, fp);
  t[got] = '\0';
  fclose(fp);
  return t;
}

static void write_text(const char *path, const char *text) {
  FILE *fp = fopen(path, "w");
  fputs(text, fp);
  fclose(fp);
}

/* Verdict of the sub-assembly without the bodies in `absent` (ids), by the
 * LP backend: 1 stable, 0 unstable, -1 error. */
static int stands(const us_Structure *s, const char *const *absent, int nabsent) {
  us_Error err;
  us_StabilitySettings set = us_stability_default_settings();
  us_Stability *w = us_stability_new(s, &set, &err);
  us_Bitset present;
  if (!w || us_bitset_init(&present, s->nbody)) return -1;
  us_bitset_fill(&present);
  for (int k = 0; k < nabsent; k++) us_bitset_clear(&present, us_structure_find_body(s, absent[k]));
  us_StabilityResult res;
  memset(&res, 0, sizeof res);
  int v = us_stability_test(w, &present, &res, &err) != US_OK ? -1 : res.verdict == US_STABLE;
  us_stability_result_free(&res);
  us_bitset_free(&present);
  us_stability_free(w);
  return v;
}

static int count_files_with_prefix(const char *prefix) {
  DIR *d = opendir(tmpdir);
  int n = 0;
  struct dirent *e;
  while (d && (e = readdir(d))) n += strncmp(e->d_name, prefix, strlen(prefix)) == 0;
  if (d) closedir(d);
  return n;
}

/* ------------------------------------------------------------- structures */

static void read_examples(void) {
  for (int i = 0; i < NGOOD; i++) {
    us_Error err;
    us_Structure *s = read_data(good_files[i], &err);
    if (!s) fprintf(stderr, "%s: %s\n", good_files[i], err.msg);
    CHECK(s != NULL);
    CHECK(us_structure_is_finalized(s));
    CHECK_INT(s->ncontact, >, 0);
    us_structure_free(s);
  }
}

static void defaults_and_fields(void) {
  us_Error err;
  us_Structure *s = us_structure_parse(
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[0,1],[1,1],[1,0]]}], \"_c\": 1}", "t", 0,
      &err);
  CHECK(s != NULL);
  CHECK_INT(s->dim, ==, 2);
  CHECK(s->gravity[0] == 0.0 && s->gravity[1] == -9.81);
  CHECK(s->friction == 0.5 && s->ground == 1 && !s->explicit_contacts);
  CHECK(s->bodies[0].density == 1.0 && !s->bodies[0].mass_given && s->bodies[0].friction < 0);
  CHECK_NEAR(s->bodies[0].mass, 1.0, 1e-12);
  us_structure_free(s);

  /* '_' keys are comments at every level */
  s = us_structure_parse(
      "{\"_a\": [1], \"bodies\": [{\"id\": \"p\", \"_b\": {}, \"mass\": 1, \"center\": [0, 1]}],"
      " \"contacts\": [{\"_c\": null, \"a\": \"ground\", \"b\": \"p\", \"point\": [0, 0],"
      " \"normal\": [0, 1]}]}",
      "t", 0, &err);
  CHECK(s != NULL);
  us_structure_free(s);

  s = read_data("lean_wall.json", &err);
  CHECK(s != NULL);
  CHECK(s->bodies[us_structure_find_body(s, "wall")].fixed);
  CHECK(!s->bodies[us_structure_find_body(s, "slab")].fixed);
  us_structure_free(s);
  s = read_data("lean_wall_mu0.json", &err);
  CHECK(s != NULL);
  CHECK(s->friction == 0.0);
  for (int k = 0; k < s->ncontact; k++) CHECK(s->contacts[k].mu == 0.0);
  us_structure_free(s);
}

/* Explicit contacts: kept as given, friction by the rule unless given. */
static void explicit_contacts(void) {
  us_Error err;
  us_Structure *s = read_data("explicit.json", &err);
  CHECK(s != NULL);
  CHECK(s->explicit_contacts);
  CHECK_INT(s->nbody, ==, 2);
  CHECK_INT(s->ncontact, ==, 4);
  CHECK_INT(s->bodies[0].nvert, ==, 0);
  CHECK_INT(s->contacts[0].a, ==, US_GROUND);
  CHECK_INT(s->contacts[2].a, ==, 0);
  CHECK_INT(s->contacts[2].b, ==, 1);
  CHECK(s->contacts[2].mu == 0.3 && s->contacts[3].mu == 0.5);
  CHECK(s->bodies[1].com[0] == 0.1 && s->bodies[1].mass == 1.0);
  us_structure_free(s);
  /* a nearly unit normal is normalized; a given inertia is kept */
  s = us_structure_parse(
      "{\"bodies\": [{\"id\": \"p\", \"mass\": 2, \"center\": [0, 1],"
      " \"inertia\": 0.25}], \"contacts\": [{\"a\": \"ground\", \"b\": \"p\","
      " \"point\": [0, 0], \"normal\": [0, 1.0004]}]}",
      "t", 0, &err);
  CHECK(s != NULL);
  CHECK(s->contacts[0].n[1] == 1.0 && s->bodies[0].inertia == 0.25);
  us_structure_free(s);
}

static void contact_tol_override(void) {
  char p[512];
  us_Error err;
  us_Structure *s = us_structure_read(data_path(p, sizeof p, "column3.json"), 1e-3, &err);
  CHECK(s != NULL);
  CHECK(s->contact_tol == 1e-3);
  us_structure_free(s);
}

/* The physics claimed in each example's _note, checked with the LP. */
static void examples_physics(void) {
  us_Error err;
  us_Structure *s = read_data("column3.json", &err);
  CHECK(s);
  CHECK_INT(stands(s, NULL, 0), ==, 1);
  CHECK_INT(stands(s, (const char *[]){"b3"}, 1), ==, 1);
  CHECK_INT(stands(s, (const char *[]){"b2"}, 1), ==, 0);
  us_structure_free(s);

  s = read_data("cantilever.json", &err);
  CHECK(s);
  CHECK_INT(stands(s, NULL, 0), ==, 1);
  CHECK_INT(stands(s, (const char *[]){"C"}, 1), ==, 0); /* greedy highest-first fails */
  CHECK_INT(stands(s, (const char *[]){"B"}, 1), ==, 0);
  CHECK_INT(stands(s, (const char *[]){"P"}, 1), ==, 0);
  CHECK_INT(stands(s, (const char *[]){"L"}, 1), ==, 1);
  CHECK_INT(stands(s, (const char *[]){"L", "C"}, 2), ==, 1);
  double top = -1e9;
  int highest = -1;
  for (int i = 0; i < s->nbody; i++)
    if (s->bodies[i].com[1] > top) top = s->bodies[i].com[1], highest = i;
  CHECK(!strcmp(s->bodies[highest].id, "C"));
  us_structure_free(s);

  s = read_data("leaning.json", &err);
  CHECK(s);
  CHECK_INT(stands(s, NULL, 0), ==, 1);
  CHECK_INT(stands(s, (const char *[]){"left"}, 1), ==, 0);
  CHECK_INT(stands(s, (const char *[]){"right"}, 1), ==, 0);
  us_structure_free(s);

  s = read_data("lean_wall.json", &err);
  CHECK(s);
  CHECK_INT(stands(s, NULL, 0), ==, 1);
  us_structure_free(s);
  s = read_data("lean_wall_mu0.json", &err);
  CHECK(s);
  CHECK_INT(stands(s, NULL, 0), ==, 0);
  us_structure_free(s);

  s = read_data("explicit.json", &err);
  CHECK(s);
  CHECK_INT(stands(s, NULL, 0), ==, 1);
  CHECK_INT(stands(s, (const char *[]){"top"}, 1), ==, 1);
  us_structure_free(s);
}

/* Same bodies and contacts, bit for bit. */
static int same_structure(const us_Structure *a, const us_Structure *b) {
  if (a->nbody != b->nbody || a->ncontact != b->ncontact || a->ground != b->ground ||
      a->friction != b->friction || a->gravity[0] != b->gravity[0] ||
      a->gravity[1] != b->gravity[1] || a->explicit_contacts != b->explicit_contacts)
    return 0;
  for (int i = 0; i < a->nbody; i++) {
    const us_Body *p = &a->bodies[i], *q = &b->bodies[i];
    if (strcmp(p->id, q->id) || p->nvert != q->nvert || p->fixed != q->fixed ||
        p->friction != q->friction || p->mass_given != q->mass_given || p->com[0] != q->com[0] ||
        p->com[1] != q->com[1] || (!p->fixed && (p->mass != q->mass || p->inertia != q->inertia)))
      return 0;
    for (int k = 0; k < 2 * p->nvert; k++)
      if (p->verts[k] != q->verts[k]) return 0;
  }
  for (int k = 0; k < a->ncontact; k++) {
    const us_Contact *p = &a->contacts[k], *q = &b->contacts[k];
    if (p->a != q->a || p->b != q->b || p->mu != q->mu || memcmp(p->p, q->p, sizeof p->p) ||
        memcmp(p->n, q->n, sizeof p->n))
      return 0;
  }
  return 1;
}

static void round_trip(void) {
  char out[256];
  tmp_path(out, sizeof out, "rt.json");
  for (int i = 0; i < NGOOD; i++) {
    us_Error err;
    us_Structure *s = read_data(good_files[i], &err);
    CHECK(s);
    CHECK_OK(us_structure_write(s, out, &err), &err);
    us_Structure *t = us_structure_read(out, 0, &err);
    if (!t) fprintf(stderr, "%s: %s\n", good_files[i], err.msg);
    CHECK(t);
    CHECK(same_structure(s, t));
    us_structure_free(s);
    us_structure_free(t);
  }
  remove(out);
}

/* Awkward values: ids needing escapes, numbers without short forms, a
 * given mass, density, friction, ground off, gravity sideways. */
static void round_trip_awkward(void) {
  us_Error err;
  const char *text =
      "{\"gravity\": [0.1, -9.80665], \"friction\": 0.3, \"ground\": false, \"bodies\": ["
      "{\"id\": \"fix\", \"fixed\": true, \"mass\": 100, \"polygon\": [[-1, -1], [3, -1], [3, 0], "
      "[-1, 0]]},"
      "{\"id\": \"q\\\"u\\\\o\\nte \\u00e9\", \"density\": 2.5, \"friction\": 0.7,"
      " \"polygon\": [[0, 0], [0.1, 0], [0.30000000000000004, 0.2], [0, 0.2]]},"
      "{\"id\": \"m\", \"mass\": 1e-7, \"polygon\": [[0, 0.2], [0.1, 0.2], [0.1, "
      "0.3333333333333333]]}]}";
  us_Structure *s = us_structure_parse(text, "awkward", 0, &err);
  if (!s) fprintf(stderr, "%s\n", err.msg);
  CHECK(s);
  CHECK(!strcmp(s->bodies[1].id, "q\"u\\o\nte \xc3\xa9"));
  char out[256];
  tmp_path(out, sizeof out, "awkward.json");
  CHECK_OK(us_structure_write(s, out, &err), &err);
  us_Structure *t = us_structure_read(out, 0, &err);
  CHECK(t);
  CHECK(same_structure(s, t));
  CHECK(t->bodies[1].density == 2.5 && t->bodies[2].mass_given && !t->ground);
  CHECK(t->bodies[0].fixed && t->bodies[0].mass == 100.0);
  char *written = read_text(out);
  CHECK(written && strstr(written, "0.30000000000000004") && strstr(written, "[0.1, -9.80665]"));
  free(written);
  us_structure_free(s);
  us_structure_free(t);
  remove(out);
}

/* Every file in tests/data/bad fails with its README fragment. */
static void bad_files(void) {
  char p[1024], line[512];
  FILE *fp = fopen(data_path(p, sizeof p, "bad/README"), "r");
  CHECK(fp);
  int n = 0, failed = 0;
  while (fgets(line, sizeof line, fp)) {
    if (line[0] == '#' || line[0] == '\n') continue;
    line[strcspn(line, "\n")] = '\0';
    char *tab = strchr(line, '\t');
    if (!tab) continue;
    *tab = '\0';
    char name[600];
    snprintf(name, sizeof name, "bad/%s", line);
    us_Error err;
    us_error_clear(&err);
    us_Structure *s = read_data(name, &err);
    int ok = !s && (err.code == US_ERR_PARSE || err.code == US_ERR_INPUT) &&
             strstr(err.msg, tab + 1) && strstr(err.msg, line);
    if (!ok) {
      fprintf(stderr, "%s: expected '%s', got [%s] %s\n", line, tab + 1, us_status_name(err.code),
              err.msg);
      failed++;
    }
    us_structure_free(s);
    n++;
  }
  fclose(fp);
  CHECK_INT(failed, ==, 0);
  CHECK_INT(n, >=, 40);
}

static void read_errors(void) {
  us_Error err;
  CHECK(!us_structure_read("/nonexistent/x.json", 0, &err));
  CHECK_INT(err.code, ==, US_ERR_IO);
  CHECK(strstr(err.msg, "/nonexistent/x.json"));
  CHECK(!us_structure_read(US_TEST_DATA, 0, &err)); /* a directory */
  CHECK_INT(err.code, ==, US_ERR_IO);
  CHECK(!us_structure_parse("{\"bodies\": [1]}", "inline", 0, NULL)); /* err may be NULL */
  CHECK(!us_structure_parse("{\"bodies\": []}x", "inline", 0, &err));
  CHECK_INT(err.code, ==, US_ERR_PARSE);
  CHECK(strstr(err.msg, "inline:1:"));
}

static void failed_write_leaves_no_file(void) {
  us_Error err;
  us_Structure *s = read_data("column3.json", &err);
  CHECK(s);
  CHECK_INT(us_structure_write(s, "/nonexistent/dir/out.json", &err), ==, US_ERR_IO);
  char out[256];
  tmp_path(out, sizeof out, "nan.json");
  s->bodies[1].verts[3] = NAN; /* JSON cannot hold it */
  CHECK_INT(us_structure_write(s, out, &err), ==, US_ERR_INPUT);
  CHECK(strstr(err.msg, out));
  CHECK(access(out, F_OK) != 0);
  CHECK_INT(count_files_with_prefix("nan.json"), ==, 0);
  /* an existing file survives a failed rewrite untouched */
  write_text(out, "old");
  CHECK_INT(us_structure_write(s, out, &err), ==, US_ERR_INPUT);
  char *kept = read_text(out);
  int same = kept && !strcmp(kept, "old");
  free(kept);
  CHECK(same);
  CHECK_INT(count_files_with_prefix("nan.json"), ==, 1);
  /* plans too */
  us_Plan p;
  memset(&p, 0, sizeof p);
  p.stats.time_total = NAN;
  CHECK_INT(us_plan_write(s, &p, NULL, out, &err), ==, US_ERR_INPUT);
  kept = read_text(out);
  same = kept && !strcmp(kept, "old");
  free(kept);
  CHECK(same);
  CHECK_INT(count_files_with_prefix("nan.json"), ==, 1);
  remove(out);
  us_structure_free(s);
}

/* ------------------------------------------------------------------ plans */

/* A plan for column3 (top to bottom) with certificates from the LP. */
static int make_column_plan(const us_Structure *s, us_Plan *p) {
  memset(p, 0, sizeof *p);
  p->status = US_PLAN_FOUND;
  p->nsteps = 3;
  p->order = calloc(3, sizeof *p->order);
  p->certs = us_calloc(4, sizeof *p->certs);
  const char *ids[3] = {"b3", "b2", "b1"};
  us_Error err;
  us_StabilitySettings set = us_stability_default_settings();
  us_Stability *w = us_stability_new(s, &set, &err);
  us_Bitset present;
  if (!w || us_bitset_init(&present, s->nbody)) return -1;
  us_bitset_fill(&present);
  int bad = 0;
  for (int k = 0; k < 3; k++) {
    p->order[k] = us_structure_find_body(s, ids[k]);
    us_StabilityResult res;
    memset(&res, 0, sizeof res);
    bad |= us_stability_test(w, &present, &res, &err) != US_OK || res.verdict != US_STABLE;
    p->certs[k] = res.forces;
    memset(&res.forces, 0, sizeof res.forces);
    us_stability_result_free(&res);
    us_bitset_clear(&present, p->order[k]);
  }
  p->stats.tests = 3;
  p->stats.stable = 3;
  p->stats.time_total = 0.125;
  p->stats.stability.tests = 3;
  us_bitset_free(&present);
  us_stability_free(w);
  return bad ? -1 : 0;
}

static void free_column_plan(us_Plan *p) {
  for (int k = 0; k < 4; k++) us_forces_free(&p->certs[k]);
  us_free(p->certs);
  free(p->order);
}

static void plan_round_trip(void) {
  us_Error err;
  us_Structure *s = read_data("column3.json", &err);
  CHECK(s);
  us_Plan p;
  CHECK_INT(make_column_plan(s, &p), ==, 0);
  us_PlanSettings set;
  memset(&set, 0, sizeof set);
  set.stability = us_stability_default_settings();
  set.stability.method = US_METHOD_LCP_REUSE;
  set.search = US_SEARCH_BFS;
  set.order = US_ORDER_INPUT;
  set.direction = US_DIR_UP;
  char out[256];
  tmp_path(out, sizeof out, "plan.json");
  us_Status st = us_plan_write(s, &p, &set, out, &err);
  free_column_plan(&p);
  CHECK_OK(st, &err);
  us_PlanFile pf;
  CHECK_OK(us_plan_read(s, out, &pf, &err), &err);
  CHECK_INT(pf.status, ==, US_PLAN_FOUND);
  CHECK_INT(pf.n, ==, 3);
  CHECK(pf.order[0] == us_structure_find_body(s, "b3") &&
        pf.order[2] == us_structure_find_body(s, "b1"));
  us_plan_file_free(&pf);
  /* the document itself: names, one step per removal, checks that pass */
  json_error_t je;
  json_t *root = json_load_file(out, 0, &je);
  CHECK(root);
  json_t *steps = json_object_get(root, "steps");
  int ok = json_array_size(steps) == 3 &&
           !strcmp(json_string_value(json_object_get(root, "method")), "lcp-reuse") &&
           !strcmp(json_string_value(json_object_get(root, "search")), "bfs") &&
           !strcmp(json_string_value(json_object_get(root, "order_heuristic")), "input") &&
           !strcmp(json_string_value(json_object_get(root, "direction")), "up") &&
           json_number_value(json_object_get(json_object_get(root, "statistics"), "time_total")) ==
               0.125;
  for (size_t k = 0; ok && k < 3; k++) {
    json_t *cert = json_object_get(json_array_get(steps, k), "certificate");
    ok = json_is_true(json_object_get(json_object_get(cert, "check"), "ok")) &&
         json_array_size(json_object_get(cert, "contacts")) >= 2;
  }
  json_decref(root);
  CHECK(ok);
  remove(out);
  us_structure_free(s);
}

static void plan_without_certificates(void) {
  us_Error err;
  us_Structure *s = read_data("column3.json", &err);
  CHECK(s);
  us_Plan p;
  memset(&p, 0, sizeof p);
  p.status = US_PLAN_NONE;
  char out[256];
  tmp_path(out, sizeof out, "plan0.json");
  CHECK_OK(us_plan_write(s, &p, NULL, out, &err), &err);
  us_PlanFile pf;
  CHECK_OK(us_plan_read(s, out, &pf, &err), &err);
  CHECK_INT(pf.status, ==, US_PLAN_NONE);
  CHECK_INT(pf.n, ==, 0);
  us_plan_file_free(&pf);
  int bad_order[1] = {7};
  p.nsteps = 1;
  p.order = bad_order;
  CHECK_INT(us_plan_write(s, &p, NULL, out, &err), ==, US_ERR_USAGE);
  remove(out);
  us_structure_free(s);
}

static void plan_read_errors(void) {
  static const struct {
    const char *text, *fragment;
    us_Status code;
  } cases[] = {
      {"{\"status\": \"found\", \"order\": [\"slab\",]}", ":1:", US_ERR_PARSE},
      {"{\"order\": [\"slab\"]}", "missing field 'status'", US_ERR_INPUT},
      {"{\"status\": \"great\", \"order\": []}", "status: expected one of", US_ERR_INPUT},
      {"{\"status\": \"found\"}", "missing field 'order'", US_ERR_INPUT},
      {"{\"status\": \"found\", \"order\": [3]}", "order[0]: expected a body id", US_ERR_INPUT},
      {"{\"status\": \"found\", \"order\": [\"nope\"]}", "order[0]: unknown body id 'nope'",
       US_ERR_INPUT},
      {"{\"status\": \"found\", \"order\": [\"wall\"]}", "'wall' is fixed", US_ERR_INPUT},
      {"{\"status\": \"found\", \"order\": [\"slab\", \"slab\"]}", "appears twice", US_ERR_INPUT},
      {"{\"format\": \"svg\", \"status\": \"found\", \"order\": []}", "format:", US_ERR_INPUT},
      {"{\"version\": 2, \"status\": \"found\", \"order\": []}", "version", US_ERR_INPUT},
      {"{\"status\": \"found\", \"order\": [], \"oder\": 1}", "unknown field 'oder'", US_ERR_INPUT},
      {"[]", "expected a JSON object", US_ERR_INPUT},
      /* a plan for another structure: longer than the body count, the
         first unknown id is named (also inside a group) */
      {"{\"status\": \"found\", \"order\": [\"slab\", \"b1\", \"b2\", \"b3\", \"b4\", \"b5\", "
       "\"b6\", \"b7\", \"b8\", \"b9\"]}", "order[1]: unknown body id 'b1' (a plan for another",
       US_ERR_INPUT},
      {"{\"status\": \"found\", \"order\": [[\"slab\", \"q\"], \"b2\", \"b3\", \"b4\", \"b5\", "
       "\"b6\", \"b7\", \"b8\", \"b9\"]}", "order[0][1]: unknown body id 'q'", US_ERR_INPUT},
      {"{\"status\": \"found\", \"order\": [], \"blocked\": [\"slab\", \"b1\", \"b2\", \"b3\", "
       "\"b4\", \"b5\", \"b6\", \"b7\", \"b8\", \"b9\"]}", "blocked[1]: unknown body id 'b1'",
       US_ERR_INPUT},
      {"{\"status\": \"none\", \"order\": [], \"removal\": \"sideways\"}",
       "removal: expected one of \"any\", \"up\", \"free\"", US_ERR_INPUT},
      {"{\"status\": \"found\", \"order\": [\"a\\u001b[2Jb\"]}", "unknown body id 'a\\x1B[2Jb'",
       US_ERR_INPUT},
  };
  us_Error err;
  us_Structure *s = read_data("lean_wall.json", &err);
  CHECK(s);
  char path[256];
  tmp_path(path, sizeof path, "badplan.json");
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    write_text(path, cases[i].text);
    us_PlanFile pf;
    us_Status st = us_plan_read(s, path, &pf, &err);
    if (st != cases[i].code || !strstr(err.msg, cases[i].fragment) || !strstr(err.msg, path))
      fprintf(stderr, "case %zu: [%s] %s\n", i, us_status_name(st), err.msg);
    CHECK_INT(st, ==, cases[i].code);
    CHECK(strstr(err.msg, cases[i].fragment) && strstr(err.msg, path));
    CHECK(pf.order == NULL);
  }
  /* a byte order mark before the JSON is skipped */
  write_text(path, "\xEF\xBB\xBF{\"status\": \"limit\", \"order\": []}");
  us_PlanFile bom;
  CHECK_OK(us_plan_read(s, path, &bom, &err), &err);
  us_plan_file_free(&bom);
  /* a partial order is fine: completeness is for verification */
  write_text(path, "{\"status\": \"limit\", \"order\": [\"slab\"], \"_by\": \"hand\"}");
  us_PlanFile pf;
  CHECK_OK(us_plan_read(s, path, &pf, &err), &err);
  CHECK(pf.status == US_PLAN_LIMIT && pf.n == 1 &&
        pf.order[0] == us_structure_find_body(s, "slab"));
  us_plan_file_free(&pf);
  remove(path);
  CHECK_INT(us_plan_read(s, path, &pf, &err), ==, US_ERR_IO);
  us_structure_free(s);
}

/* ---------------------------------------------------------- robustness */

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static unsigned rnd(unsigned n) {
  rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
  return (unsigned)((rng_state >> 33) % n);
}

/* One random edit: overwrite, delete, duplicate or insert a few bytes. */
static void mutate(char *t, size_t *len, size_t cap) {
  static const char alphabet[] = "{}[],:\"0123456789.-+eE tfnul\\/abxyz_";
  size_t at = *len ? rnd((unsigned)*len) : 0;
  size_t span = 1 + rnd(8);
  switch (rnd(4)) {
    case 0:
      t[at] = rnd(10) ? alphabet[rnd(sizeof alphabet - 1)] : (char)(1 + rnd(255));
      break;
    case 1:
      if (at + span > *len) span = *len - at;
      memmove(t + at, t + at + span, *len - at - span);
      *len -= span;
      break;
    default:
      if (*len + span >= cap || at + span > *len) break;
      memmove(t + at + span, t + at, *len - at);
      for (size_t k = 0; k < span; k++)
        t[at + k] = rnd(2) ? t[at + span + k] : alphabet[rnd(sizeof alphabet - 1)];
      *len += span;
  }
  t[*len] = '\0';
}

static void fuzz_mutations(void) {
  const char *files[] = {"column3.json", "cantilever.json", "explicit.json", "leaning.json"};
  int accepted = 0, total = 0;
  for (int f = 0; f < 4; f++) {
    char p[512];
    char *orig = read_text(data_path(p, sizeof p, files[f]));
    CHECK(orig);
    size_t olen = strlen(orig), cap = olen + 256;
    char *t = malloc(cap);
    for (int round = 0; round < 1000; round++) {
      memcpy(t, orig, olen + 1);
      size_t len = olen;
      int edits = 1 + (int)rnd(4);
      for (int e = 0; e < edits; e++) mutate(t, &len, cap);
      us_Error err;
      us_error_clear(&err);
      us_Structure *s = us_structure_parse(t, "fuzz", 0, &err);
      if (s)
        accepted++;
      else if (err.code == US_OK || !strstr(err.msg, "fuzz")) {
        fprintf(stderr, "no message for:\n%s\n", t);
        free(t), free(orig);
        CHECK(0);
      }
      us_structure_free(s);
      total++;
    }
    free(t);
    free(orig);
  }
  printf("fuzz: %d of %d mutated inputs accepted\n", accepted, total);
  CHECK(accepted > 0 && accepted < total);
}

/* Mutations of a written plan file: an answer or an error, no crash. */
static void fuzz_plan(void) {
  us_Error err;
  us_Structure *s = read_data("column3.json", &err);
  CHECK(s);
  us_Plan p;
  CHECK_INT(make_column_plan(s, &p), ==, 0);
  char path[256];
  tmp_path(path, sizeof path, "fuzzplan.json");
  us_Status st = us_plan_write(s, &p, NULL, path, &err);
  free_column_plan(&p);
  CHECK_OK(st, &err);
  char *orig = read_text(path);
  CHECK(orig);
  size_t olen = strlen(orig), cap = olen + 256;
  char *t = malloc(cap);
  int accepted = 0;
  for (int round = 0; round < 1000; round++) {
    memcpy(t, orig, olen + 1);
    size_t len = olen;
    for (int e = 0, edits = 1 + (int)rnd(3); e < edits; e++) mutate(t, &len, cap);
    write_text(path, t);
    us_PlanFile pf;
    st = us_plan_read(s, path, &pf, &err);
    if (st == US_OK) {
      accepted++;
      for (int k = 0; k < pf.n; k++) CHECK(pf.order[k] >= 0 && pf.order[k] < s->nbody);
    } else {
      CHECK(strstr(err.msg, path) != NULL);
    }
    us_plan_file_free(&pf);
  }
  printf("plan fuzz: %d of 1000 mutated plans accepted\n", accepted);
  free(t);
  free(orig);
  remove(path);
  us_structure_free(s);
  CHECK(accepted > 0 && accepted < 1000);
}

/* Out of memory at every allocation: an error, never a leak or crash. */
static void out_of_memory(void) {
  char p[512];
  const char *files[] = {"cantilever.json", "explicit.json"};
  for (int f = 0; f < 2; f++) {
    char *text = read_text(data_path(p, sizeof p, files[f]));
    CHECK(text);
    int done = 0;
    for (long n = 0; n < 100000 && !done; n++) {
      us_alloc_fail_after(n);
      us_Error err;
      us_error_clear(&err);
      us_Structure *s = us_structure_parse(text, files[f], 0, &err);
      us_alloc_fail_after(-1);
      if (s)
        done = 1;
      else if (err.code != US_ERR_NOMEM) {
        fprintf(stderr, "n=%ld: [%s] %s\n", n, us_status_name(err.code), err.msg);
        free(text);
        CHECK(0);
      }
      us_structure_free(s);
    }
    free(text);
    CHECK(done);
  }
}

/* 10,000 bricks in running bond: written and read back unchanged. The
 * times are printed, not asserted (a busy machine must not fail a test;
 * bench/ measures speed). */
static void large_wall(void) {
  const int rows = 100, cols = 100;
  size_t cap = (size_t)rows * cols * 120 + 100, n = 0;
  char *t = malloc(cap);
  n += (size_t)snprintf(t + n, cap - n, "{\"bodies\": [\n");
  for (int r = 0; r < rows; r++)
    for (int c = 0; c < cols; c++) {
      double x0 = c + (r % 2) * 0.5, y0 = r * 0.5;
      n += (size_t)snprintf(
          t + n, cap - n,
          "%s{\"id\": \"r%dc%d\", \"polygon\": [[%g, %g], [%g, %g], [%g, %g], [%g, %g]]}",
          r || c ? ",\n" : "", r, c, x0, y0, x0 + 1, y0, x0 + 1, y0 + 0.5, x0, y0 + 0.5);
    }
  snprintf(t + n, cap - n, "]}\n");
  us_Error err;
  double t0 = us_now();
  us_Structure *s = us_structure_parse(t, "wall", 0, &err);
  double t1 = us_now();
  free(t);
  CHECK(s);
  CHECK_INT(s->nbody, ==, rows * cols);
  char out[256];
  tmp_path(out, sizeof out, "wall.json");
  double t2 = us_now();
  CHECK_OK(us_structure_write(s, out, &err), &err);
  double t3 = us_now();
  us_Structure *back = us_structure_read(out, 0, &err);
  double t4 = us_now();
  CHECK(back);
  CHECK(same_structure(s, back));
  printf("10,000 bricks: parse+finalize %.3f s, write %.3f s, read back %.3f s\n", t1 - t0, t3 - t2,
         t4 - t3);
  us_structure_free(s);
  us_structure_free(back);
  remove(out);
}

/* Text in structure files: a BOM is skipped; invalid UTF-8 is a parse error
 * naming file and line; an id with an escape sequence or a newline is read,
 * and messages show it escaped (no ESC, no newline). */
static void text_and_ids(void) {
  us_Error err;
  us_Structure *s = us_structure_parse(
      "\xEF\xBB\xBF{\"bodies\": [{\"id\": \"b1\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}]}",
      "bom.json", 0, &err);
  CHECK(s != NULL);
  us_structure_free(s);
  s = us_structure_parse("{\"bodies\": [\n{\"id\": \"b\xff\", \"polygon\": [[0,0],[1,0],[1,1],[0,1]]}]}",
                         "utf.json", 0, &err);
  CHECK(s == NULL && err.code == US_ERR_PARSE && strstr(err.msg, "utf.json:2:"));
  s = us_structure_parse("{\"bodies\": [{\"id\": \"b\\u001b]0;x\\u0007\\n\", \"polygon\": "
                         "[[0,0],[1,0],[1,1],[0,1]]}, {\"id\": \"b\\u001b]0;x\\u0007\\n\", \"polygon\": "
                         "[[0,1],[1,1],[1,2],[0,2]]}]}", "ids.json", 0, &err);
  CHECK(s == NULL && err.code == US_ERR_INPUT);
  CHECK(strstr(err.msg, "duplicate id 'b\\x1B]0;x\\x07\\x0A'") && !strchr(err.msg, 0x1b) &&
        !strchr(err.msg, '\n'));
}

/* An id that is not valid UTF-8 (possible through the C API, not from a
 * file) is refused at write: the file would not read back. Nothing is left. */
static void write_invalid_utf8(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  double xy[8] = {0, 0, 1, 0, 1, 1, 0, 1};
  CHECK(us_structure_add_polygon(s, "b\xff", 4, xy, 1, 0, 0, -1, &err) >= 0);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  char out[256];
  tmp_path(out, sizeof out, "utf8.json");
  CHECK_INT(us_structure_write(s, out, &err), ==, US_ERR_INPUT);
  CHECK(strstr(err.msg, "not valid UTF-8") && strstr(err.msg, out));
  CHECK(access(out, F_OK) != 0);
  us_structure_free(s);
}

/* The fingerprint of a structure given as JSON text; 0 on error. */
static uint64_t fingerprint_of(const char *text) {
  us_Error err;
  us_Structure *s = us_structure_parse(text, "fp.json", 0, &err);
  uint64_t h = 0;
  if (!s || us_structure_fingerprint(s, &h, &err)) h = 0;
  us_structure_free(s);
  return h;
}

/* The same structure spelled differently has one fingerprint; a change in
 * anything that decides verdicts gives another. */
static void fingerprint(void) {
  const char *base = "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[2,0],[2,1],[0,1]]},"
                     "{\"id\": \"b\", \"polygon\": [[0,1],[1,1],[1,2],[0,2]]}]}";
  const char *respelt =
      "{ \"friction\": 0.5, \"bodies\" : [ {\"polygon\": [[2.0, 1], [2e0, 0], [0, 0], [0, 1.0]],"
      " \"id\": \"a\", \"density\": 1}, {\"id\":\"b\",\"polygon\":[[1,2],[0,2],[0,1],[1,1]]}],"
      " \"_comment\": \"x\", \"gravity\": [0, -9.81]}";
  const char *changed[] = {
      /* density, friction, id, gravity, a vertex, fixed, order of bodies */
      "{\"bodies\": [{\"id\": \"a\", \"density\": 2, \"polygon\": [[0,0],[2,0],[2,1],[0,1]]},"
      "{\"id\": \"b\", \"polygon\": [[0,1],[1,1],[1,2],[0,2]]}]}",
      "{\"friction\": 0.4, \"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[2,0],[2,1],[0,1]]},"
      "{\"id\": \"b\", \"polygon\": [[0,1],[1,1],[1,2],[0,2]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[2,0],[2,1],[0,1]]},"
      "{\"id\": \"c\", \"polygon\": [[0,1],[1,1],[1,2],[0,2]]}]}",
      "{\"gravity\": [0.1, -9.81], \"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[2,0],[2,1],[0,1]]},"
      "{\"id\": \"b\", \"polygon\": [[0,1],[1,1],[1,2],[0,2]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"polygon\": [[0,0],[2,0],[2,1],[0,1]]},"
      "{\"id\": \"b\", \"polygon\": [[0,1],[1,1],[1,2.000001],[0,2]]}]}",
      "{\"bodies\": [{\"id\": \"a\", \"fixed\": true, \"polygon\": [[0,0],[2,0],[2,1],[0,1]]},"
      "{\"id\": \"b\", \"polygon\": [[0,1],[1,1],[1,2],[0,2]]}]}",
      "{\"bodies\": [{\"id\": \"b\", \"polygon\": [[0,1],[1,1],[1,2],[0,2]]},"
      "{\"id\": \"a\", \"polygon\": [[0,0],[2,0],[2,1],[0,1]]}]}"};
  uint64_t h = fingerprint_of(base);
  CHECK(h != 0);
  CHECK(fingerprint_of(respelt) == h);
  for (int k = 0; k < 7; k++) {
    uint64_t g = fingerprint_of(changed[k]);
    if (g == 0 || g == h) fprintf(stderr, "changed[%d] keeps the fingerprint\n", k);
    CHECK(g != 0 && g != h);
  }
  char text[US_FINGERPRINT_CHARS];
  us_fingerprint_text(0x0123456789abcdefull, text);
  CHECK(!strcmp(text, "fnv1a64:0123456789abcdef"));
}

/* A plan names its structure: read back against it, refused against
 * another (other_structure), read without a fingerprint; "build". */
static void plan_fingerprint(void) {
  us_Error err;
  us_Structure *s = read_data("column3.json", &err);
  CHECK(s);
  const char *heavy = "{\"bodies\": [{\"id\": \"b1\", \"density\": 3, \"polygon\": "
                      "[[0, 0], [1, 0], [1, 1], [0, 1]]}, {\"id\": \"b2\", \"polygon\": "
                      "[[0, 1], [1, 1], [1, 2], [0, 2]]}, {\"id\": \"b3\", \"polygon\": "
                      "[[0, 2], [1, 2], [1, 3], [0, 3]]}]}";
  us_Structure *other = us_structure_parse(heavy, "heavy.json", 0, &err);
  CHECK(other);
  int build[2] = {0, 1}, start[3] = {0, 1, 2}, blocked[1] = {2};
  us_Plan p;
  memset(&p, 0, sizeof p);
  p.status = US_PLAN_NONE;
  p.buildable = build, p.nbuildable = 2, p.build_start = start, p.nbuild = 2;
  p.blocked = blocked, p.nblocked = 1;
  char out[256], old[256];
  tmp_path(out, sizeof out, "fp-plan.json");
  tmp_path(old, sizeof old, "fp-old.json");
  CHECK_OK(us_plan_write(s, &p, NULL, out, &err), &err);
  us_PlanFile pf;
  CHECK_OK(us_plan_read(s, out, &pf, &err), &err);
  int ok = pf.has_fingerprint && !pf.other_structure && pf.nbuildable == 2 && pf.nbuild == 2 &&
           pf.buildable[0] == 0 && pf.buildable[1] == 1 && pf.nblocked == 1;
  us_plan_file_free(&pf);
  CHECK(ok);
  us_Status st = us_plan_read(other, out, &pf, &err);
  CHECK_INT(st, ==, US_ERR_INPUT);
  CHECK(pf.other_structure && pf.order == NULL);
  CHECK(strstr(err.msg, "another structure") != NULL);
  write_text(old, "{\"status\": \"found\", \"order\": [\"b3\", \"b2\", \"b1\"]}");
  CHECK_OK(us_plan_read(other, old, &pf, &err), &err);
  CHECK(!pf.has_fingerprint && pf.n == 3);
  us_plan_file_free(&pf);
  write_text(old, "{\"fingerprint\": \"sha:1\", \"status\": \"found\", \"order\": []}");
  CHECK_INT(us_plan_read(s, old, &pf, &err), ==, US_ERR_INPUT);
  remove(out);
  remove(old);
  us_structure_free(other);
  us_structure_free(s);
}

US_TEST_MAIN(T(read_examples), T(defaults_and_fields), T(explicit_contacts),
             T(contact_tol_override), T(examples_physics), T(round_trip), T(round_trip_awkward),
             T(bad_files), T(read_errors), T(failed_write_leaves_no_file), T(plan_round_trip),
             T(plan_without_certificates), T(plan_read_errors), T(fuzz_mutations), T(fuzz_plan),
             T(out_of_memory), T(large_wall), T(text_and_ids),
             T(write_invalid_utf8), T(fingerprint), T(plan_fingerprint))
