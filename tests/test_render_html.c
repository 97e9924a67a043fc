/* Tests of the HTML plan viewer's writer (src/render/html.c) and of the
 * reader of a plan file's certificates (src/io/plan_certs.c). The page's
 * embedded JSON is cut out of the file and parsed back with jansson: one
 * entry per body with its id, one per step of the order, the forces of
 * every position as world vectors equal to f_n n + f_t t recomputed here
 * from the structure's own tangent basis. Hostile ids (script end tags,
 * comment openers, quotes, U+2028, controls, invalid UTF-8) leave no '<'
 * in the data and read back exactly (invalid bytes as U+FFFD). A 3D page
 * carries each body's convex parts (vertices and faces as in the
 * structure), 3D contacts and forces (normal and both tangent parts), the
 * view and the 3D script, which a 2D page does not carry. Bad input
 * (4D, a bad 3D view, bad order, bad forces) is refused before any file is written, an
 * allocation failure at any point leaves no file, and certificates read
 * back from a written plan equal the planner's. The page in a browser is
 * tests/browser (ctest browser.viewer). */
#define _POSIX_C_SOURCE 200809L
#include "scenes.h"
#include "test.h"
#include "tmpfiles.h"

#include <jansson.h>
#include <unistd.h>



static int spit(const char *path, const char *text) {
  FILE *fp = fopen(path, "wb");
  if (!fp) return -1;
  fputs(text, fp);
  return fclose(fp);
}

#define DATA_OPEN "<script id=\"us-data\" type=\"application/json\">"

/* The data element's content of a page (us_malloc'd), or NULL. */
static char *data_of(const char *page) {
  const char *a = strstr(page, DATA_OPEN);
  if (!a) return NULL;
  a += strlen(DATA_OPEN);
  const char *b = strstr(a, "</script>");
  if (!b) return NULL;
  char *d = us_malloc((size_t)(b - a) + 1);
  if (d) memcpy(d, a, (size_t)(b - a)), d[b - a] = 0;
  return d;
}

/* Write the page and parse its data back; NULL on any failure. */
static json_t *page_data(const us_Structure *s, const us_RenderSettings *r,
                         const us_HtmlSettings *h, const char *name, char **page_out) {
  char path[128];
  us_Error err;
  if (us_render_html(s, r, h, test_tmp_path(name, path, sizeof path), &err)) {
    fprintf(stderr, "us_render_html: %s\n", err.msg);
    return NULL;
  }
  char *page = test_slurp(path), *data = page ? data_of(page) : NULL;
  json_error_t je;
  json_t *root = data ? json_loads(data, 0, &je) : NULL;
  if (data && !root) fprintf(stderr, "data does not parse: %s\n", je.text);
  us_free(data);
  if (page_out) *page_out = page;
  else us_free(page);
  unlink(path);
  return root;
}

static us_Structure *pyramid(int rows) {
  us_GenSettings g = us_gen_default_settings();
  g.n = rows;
  return us_gen_pyramid(&g, NULL);
}

static us_Structure *pyramid3d(int rows) {
  us_GenSettings g = us_gen_default_settings();
  g.n = rows;
  return us_gen_pyramid3d(&g, NULL);
}

static us_Status plan_with_certs(const us_Structure *s, us_Plan *p) {
  us_PlanSettings set = us_plan_default_settings();
  set.certificates = 1;
  return us_plan(s, &set, p, NULL);
}

static us_RenderSettings order_of(const us_Plan *p) {
  us_RenderSettings r = us_render_default_settings();
  r.order = p->order;
  r.norder = p->nsteps;
  r.group_start = p->group_start;
  r.ngroups = p->ngroups;
  return r;
}

/* forces[k] = [contact, nx, ny, tx, ty, ...]: the force on the upper body
 * of each contact (b when the normal n, from a into b, points up, or
 * right on a vertical joint; else a, which receives -(f_n n + f_t t)),
 * normal part f_n n and friction part f_t t with that sign. */
static int forces_match(const us_Structure *s, json_t *list, const us_Forces *f) {
  if (json_array_size(list) != 5 * (size_t)f->ncontact) return 0;
  for (int j = 0; j < f->ncontact; j++) {
    const us_Contact *c = &s->contacts[f->contact[j]];
    double sg = c->n[1] > 1e-9 || (fabs(c->n[1]) <= 1e-9 && c->n[0] > 0) ? 1.0 : -1.0;
    double want[4] = {sg * f->f[2 * j] * c->n[0], sg * f->f[2 * j] * c->n[1],
                      sg * f->f[2 * j + 1] * c->t[0][0], sg * f->f[2 * j + 1] * c->t[0][1]};
    double tol = 1e-7 * (fabs(f->f[2 * j]) + fabs(f->f[2 * j + 1]) + 1e-12);
    if (json_number_value(json_array_get(list, 5 * (size_t)j)) != f->contact[j]) return 0;
    for (int q = 0; q < 4; q++)
      if (fabs(json_number_value(json_array_get(list, 5 * (size_t)j + 1 + (size_t)q)) - want[q]) > tol)
        return 0;
  }
  return 1;
}

/* certs[k].ok of the page's data. */
static int cert_ok(json_t *d, int k) {
  return json_is_true(json_object_get(json_array_get(json_object_get(d, "certs"), (size_t)k), "ok"));
}

/* ------------------------------------------------------------ cases */

static void json_parses_back(void) {
  us_Structure *s = pyramid(4);
  CHECK(s);
  us_Plan p;
  memset(&p, 0, sizeof p);
  us_Error err;
  CHECK_OK(plan_with_certs(s, &p), &err);
  CHECK_INT(p.status, ==, US_PLAN_FOUND);
  us_RenderSettings r = order_of(&p);
  us_HtmlSettings h = us_html_default_settings();
  h.certs = p.certs;
  h.title = "pyramid";
  char *page = NULL;
  json_t *d = page_data(s, &r, &h, "p.html", &page);
  int nsteps = p.group_start ? p.ngroups : p.nsteps;
  int ok = d && page && !strstr(page, "@US_DATA@") && strstr(page, "<meta name=\"viewport\"") &&
           !strstr(page, "function view3") && !strstr(page, "@US_VIEW3@");
  ok = ok && json_array_size(json_object_get(d, "bodies")) == (size_t)s->nbody;
  ok = ok && json_array_size(json_object_get(d, "contacts")) == (size_t)s->ncontact;
  ok = ok && json_array_size(json_object_get(d, "steps")) == (size_t)nsteps;
  ok = ok && json_array_size(json_object_get(d, "forces")) == (size_t)nsteps + 1;
  ok = ok && !strcmp(json_string_value(json_object_get(d, "status")), "found");
  ok = ok && json_is_null(json_object_get(d, "verify"));
  for (int i = 0; ok && i < s->nbody; i++) {
    json_t *b = json_array_get(json_object_get(d, "bodies"), (size_t)i);
    ok = !strcmp(json_string_value(json_object_get(b, "id")), s->bodies[i].id) &&
         json_array_size(json_object_get(b, "xy")) == 2 * (size_t)s->bodies[i].nvert &&
         fabs(json_number_value(json_object_get(b, "m")) - s->bodies[i].mass) <= 1e-8 * s->bodies[i].mass;
  }
  for (int k = 0; ok && k < nsteps; k++) {
    json_t *st = json_array_get(json_object_get(d, "steps"), (size_t)k);
    int a = p.group_start ? p.group_start[k] : k, b = p.group_start ? p.group_start[k + 1] : k + 1;
    ok = json_array_size(st) == (size_t)(b - a);
    for (int q = a; ok && q < b; q++)
      ok = json_number_value(json_array_get(st, (size_t)(q - a))) == p.order[q];
  }
  for (int k = 0; ok && k <= nsteps; k++)
    ok = forces_match(s, json_array_get(json_object_get(d, "forces"), (size_t)k), &p.certs[k]) &&
         cert_ok(d, k);
  json_decref(d);
  us_free(page);
  us_plan_free(&p);
  us_structure_free(s);
  CHECK(ok);
}

/* forces[k] of a 3D page = [contact, normal (3), friction (3), ...]: as
 * forces_match, up being +z and the friction f_t1 t1 + f_t2 t2. */
static int forces_match3(const us_Structure *s, json_t *list, const us_Forces *f) {
  if (json_array_size(list) != 7 * (size_t)f->ncontact) return 0;
  for (int j = 0; j < f->ncontact; j++) {
    const us_Contact *c = &s->contacts[f->contact[j]];
    const double *fc = f->f + 3 * j;
    double sg = c->n[2] > 1e-9 || (fabs(c->n[2]) <= 1e-9 && (c->n[0] > 1e-9 ||
                (fabs(c->n[0]) <= 1e-9 && c->n[1] > 0))) ? 1.0 : -1.0;
    double tol = 1e-7 * (fabs(fc[0]) + fabs(fc[1]) + fabs(fc[2]) + 1e-12);
    if (json_number_value(json_array_get(list, 7 * (size_t)j)) != f->contact[j]) return 0;
    for (int q = 0; q < 3; q++) {
      double n = sg * fc[0] * c->n[q], t = sg * (fc[1] * c->t[0][q] + fc[2] * c->t[1][q]);
      if (fabs(json_number_value(json_array_get(list, 7 * (size_t)j + 1 + (size_t)q)) - n) > tol ||
          fabs(json_number_value(json_array_get(list, 7 * (size_t)j + 4 + (size_t)q)) - t) > tol)
        return 0;
    }
  }
  return 1;
}

/* A body's parts in the page: every vertex and every face as in s. */
static int parts_match(const us_Body *b, json_t *parts) {
  if (json_array_size(parts) != (size_t)b->npart) return 0;
  for (int p = 0; p < b->npart; p++) {
    const us_Polyhedron *h = &b->parts[p];
    json_t *v = json_object_get(json_array_get(parts, (size_t)p), "v");
    json_t *f = json_object_get(json_array_get(parts, (size_t)p), "f");
    if (json_array_size(v) != 3 * (size_t)h->nvert || json_array_size(f) != (size_t)h->nface) return 0;
    for (int q = 0; q < 3 * h->nvert; q++)
      if (fabs(json_number_value(json_array_get(v, (size_t)q)) - h->verts[q]) > 1e-8 * (1 + fabs(h->verts[q])))
        return 0;
    for (int k = 0; k < h->nface; k++) {
      json_t *face = json_array_get(f, (size_t)k);
      int a = h->face_start[k], n = h->face_start[k + 1] - a;
      if (json_array_size(face) != (size_t)n) return 0;
      for (int q = 0; q < n; q++)
        if (json_number_value(json_array_get(face, (size_t)q)) != h->face_vert[a + q]) return 0;
    }
  }
  return 1;
}

/* A 3D plan's page: parts, 3D contacts and forces, the view, the 3D
 * script; every step's forces pass the re-check. */
static void json_parses_back_3d(void) {
  us_Structure *s = pyramid3d(3);
  CHECK(s);
  us_Plan p;
  memset(&p, 0, sizeof p);
  us_Error err;
  CHECK_OK(plan_with_certs(s, &p), &err);
  CHECK_INT(p.status, ==, US_PLAN_FOUND);
  us_RenderSettings r = order_of(&p);
  r.view_az = 120, r.view_el = 40;
  us_HtmlSettings h = us_html_default_settings();
  h.certs = p.certs;
  char *page = NULL;
  json_t *d = page_data(s, &r, &h, "p3.html", &page);
  int nsteps = p.group_start ? p.ngroups : p.nsteps;
  json_t *view = json_object_get(d, "view");
  int ok = d && page && strstr(page, "function view3") && !strstr(page, "@US_VIEW3@") &&
           json_integer_value(json_object_get(d, "dim")) == 3 &&
           json_number_value(json_array_get(view, 0)) == 120 && json_number_value(json_array_get(view, 1)) == 40;
  ok = ok && json_array_size(json_object_get(d, "bodies")) == (size_t)s->nbody &&
       json_array_size(json_object_get(d, "forces")) == (size_t)nsteps + 1;
  for (int i = 0; ok && i < s->nbody; i++) {
    json_t *b = json_array_get(json_object_get(d, "bodies"), (size_t)i);
    ok = !strcmp(json_string_value(json_object_get(b, "id")), s->bodies[i].id) &&
         !json_object_get(b, "xy") && json_array_size(json_object_get(b, "c")) == 3 &&
         parts_match(&s->bodies[i], json_object_get(b, "parts"));
  }
  for (int c = 0; ok && c < s->ncontact; c++) {
    json_t *k = json_array_get(json_object_get(d, "contacts"), (size_t)c);
    ok = json_array_size(k) == 8 && json_number_value(json_array_get(k, 4)) == s->contacts[c].p[2] &&
         json_number_value(json_array_get(k, 7)) == s->contacts[c].n[2];
  }
  for (int k = 0; ok && k <= nsteps; k++)
    ok = forces_match3(s, json_array_get(json_object_get(d, "forces"), (size_t)k), &p.certs[k]) &&
         cert_ok(d, k);
  json_decref(d);
  us_free(page);
  us_plan_free(&p);
  us_structure_free(s);
  CHECK(ok);
}

/* Forces edited after planning (a negative normal force, a 1e308 force)
 * fail the page's own re-check at their step and only there. */
static void tampered_forces_flagged(void) {
  us_Structure *s = pyramid(3);
  CHECK(s);
  us_Plan p;
  memset(&p, 0, sizeof p);
  us_Error err;
  CHECK_OK(plan_with_certs(s, &p), &err);
  CHECK_INT(p.status, ==, US_PLAN_FOUND);
  int nsteps = p.group_start ? p.ngroups : p.nsteps;
  CHECK(nsteps >= 3 && p.certs[0].ncontact > 0 && p.certs[1].ncontact > 0);
  p.certs[0].f[0] = -p.certs[0].f[0] - 1.0;
  p.certs[1].f[0] = 1e308;
  us_RenderSettings r = order_of(&p);
  us_HtmlSettings h = us_html_default_settings();
  h.certs = p.certs;
  char *page = NULL;
  json_t *d = page_data(s, &r, &h, "t.html", &page);
  CHECK(d != NULL);
  int flags = 0;
  for (int k = 0; d && k <= nsteps; k++) flags += !cert_ok(d, k);
  CHECK(d && !cert_ok(d, 0) && !cert_ok(d, 1) && cert_ok(d, 2));
  CHECK_INT(flags, ==, 2);
  json_decref(d);
  us_free(page);
  us_plan_free(&p);
  us_structure_free(s);
}

/* Ids that try to leave the data element, through the C API. */
static const char *const kHostile[] = {
    "</script><script>alert(1)</script>", "<!-- x", "</SCRIPT >\"q\" 'a' & \\",
    "line\xe2\x80\xa8sep\x01", "bad\xff" "byte"};

static void hostile_ids_escaped(void) {
  us_Structure *s = us_structure_new(2);
  for (int i = 0; i < 5; i++) scene_box(s, kHostile[i], 0, i, 1, 1, 1);
  CHECK(scene_seal(s));
  char *page = NULL;
  json_t *d = page_data(s, NULL, NULL, "ids.html", &page);
  char *data = page ? data_of(page) : NULL;
  int ok = d && data && !strchr(data, '<') && !strchr(data, '>');
  /* the page closes exactly its own two script elements */
  int closes = 0;
  for (const char *q = page; ok && (q = strstr(q, "</script")); q++) closes++;
  ok = ok && closes == 2;
  for (int i = 0; ok && i < 4; i++)
    ok = !strcmp(json_string_value(json_object_get(json_array_get(json_object_get(d, "bodies"), (size_t)i), "id")),
                 kHostile[i]);
  ok = ok && !strcmp(json_string_value(json_object_get(json_array_get(json_object_get(d, "bodies"), 4), "id")),
                     "bad\xef\xbf\xbd" "byte");
  ok = ok && json_is_null(json_object_get(d, "status")) && json_array_size(json_object_get(d, "steps")) == 0;
  json_decref(d);
  us_free(data);
  us_free(page);
  us_structure_free(s);
  CHECK(ok);
}

/* Steps of several bodies, blocked bodies, a verify report: as given. */
static void steps_and_verify(void) {
  us_Structure *s = scene_column(5);
  CHECK(s);
  int order[4] = {4, 3, 2, 1}, groups[3] = {0, 3, 4}, blocked[1] = {0};
  us_RenderSettings r = us_render_default_settings();
  r.order = order, r.norder = 4, r.group_start = groups, r.ngroups = 2;
  r.blocked = blocked, r.nblocked = 1;
  us_HtmlSettings h = us_html_default_settings();
  h.status = US_PLAN_NONE;
  h.verified = 1;
  h.verify.failed_step = 1;
  h.verify.unstable_body = 0;
  h.verify.remaining = 1;
  snprintf(h.verify.note, sizeof h.verify.note, "note </script>");
  json_t *d = page_data(s, &r, &h, "g.html", NULL);
  json_t *st = json_object_get(d, "steps"), *v = json_object_get(d, "verify");
  int ok = d && json_array_size(st) == 2 && json_array_size(json_array_get(st, 0)) == 3 &&
           json_number_value(json_array_get(json_array_get(st, 1), 0)) == 1 &&
           json_number_value(json_array_get(json_object_get(d, "blocked"), 0)) == 0 &&
           !strcmp(json_string_value(json_object_get(d, "status")), "none") &&
           json_number_value(json_object_get(v, "failed_step")) == 1 &&
           json_number_value(json_object_get(v, "unstable_body")) == 0 &&
           json_is_false(json_object_get(v, "ok")) &&
           !strcmp(json_string_value(json_object_get(v, "note")), "note </script>") &&
           json_is_null(json_object_get(d, "forces"));
  json_decref(d);
  us_structure_free(s);
  CHECK(ok);
}

/* Refused before the file is opened: nothing at the path afterwards. */
static void refused(const us_Structure *s, const us_RenderSettings *r, const us_HtmlSettings *h,
                    us_Status want, int *bad) {
  char path[128];
  us_Error err;
  us_error_clear(&err);
  test_tmp_path("refused.html", path, sizeof path);
  us_Status st = us_render_html(s, r, h, path, &err);
  if (st != want || access(path, F_OK) == 0 || !err.msg[0]) {
    fprintf(stderr, "refused: got %s (%s), wanted %s\n", us_status_name(st), err.msg,
            us_status_name(want));
    *bad = 1;
  }
  unlink(path);
}

static void bad_input_refused(void) {
  us_Structure *s = scene_column(3);
  CHECK(s);
  int bad = 0, twice[2] = {2, 2}, fixed_out[1] = {7};
  us_RenderSettings r = us_render_default_settings();
  r.order = twice, r.norder = 2;
  refused(s, &r, NULL, US_ERR_USAGE, &bad);     /* a body twice */
  r.order = fixed_out, r.norder = 1;
  refused(s, &r, NULL, US_ERR_USAGE, &bad);     /* not a body */
  int contact[1] = {999};
  double f[2] = {1, 0};
  us_Forces cert = {1, 1, contact, f};
  us_HtmlSettings h = us_html_default_settings();
  h.certs = &cert;
  refused(s, NULL, &h, US_ERR_USAGE, &bad);     /* a force on no contact */
  contact[0] = 0, f[0] = NAN;
  refused(s, NULL, &h, US_ERR_INPUT, &bad);     /* a non-finite force */
  h = us_html_default_settings();
  h.verified = 1, h.verify.failed_step = 5;
  refused(s, NULL, &h, US_ERR_USAGE, &bad);     /* a step the order does not have */
  s->dim = 4;
  refused(s, NULL, NULL, US_ERR_INPUT, &bad);   /* neither 2D nor 3D */
  s->dim = 2;
  us_structure_free(s);
  s = pyramid3d(2);
  CHECK(s);
  r = us_render_default_settings();
  r.view_el = 95;
  refused(s, &r, NULL, US_ERR_USAGE, &bad);     /* a 3D view past the pole */
  r.view_el = 25, r.view_az = NAN;
  refused(s, &r, NULL, US_ERR_USAGE, &bad);     /* a 3D view not a number */
  s->bodies[1].parts[0].verts[4] = INFINITY;
  refused(s, NULL, NULL, US_ERR_INPUT, &bad);   /* a 3D vertex not finite */
  us_structure_free(s);
  CHECK(!bad);
}

/* Every allocation failing in turn: no file, until the page is written;
 * *ok is cleared on any file left by a failure or no page at the end. */
static void oom_sweep(const us_Structure *s, const us_Plan *p, const char *path, int *ok) {
  for (int with_plan = 0; with_plan <= 1; with_plan++) {
    us_RenderSettings r = order_of(p);
    us_HtmlSettings h = us_html_default_settings();
    h.certs = p->certs; /* the per-step re-check allocates too */
    us_Status st = US_ERR_NOMEM;
    for (int n = 0; st == US_ERR_NOMEM && n < 1000; n++) {
      us_alloc_fail_after(n);
      st = with_plan ? us_render_html(s, &r, &h, path, NULL) : us_render_html(s, NULL, NULL, path, NULL);
      us_alloc_fail_after(-1);
      if (st == US_ERR_NOMEM && access(path, F_OK) == 0) *ok = 0;
    }
    if (st != US_OK || access(path, F_OK) != 0) *ok = 0;
    unlink(path);
  }
}

/* The sweep on a 2D column and a 3D pyramid, each with its plan. */
static void out_of_memory_leaves_nothing(void) {
  char path[128];
  test_tmp_path("oom.html", path, sizeof path);
  int ok = 1;
  for (int dim = 2; dim <= 3; dim++) {
    us_Structure *s = dim == 2 ? scene_column(3) : pyramid3d(2);
    us_Plan p;
    memset(&p, 0, sizeof p);
    if (!s || plan_with_certs(s, &p)) ok = 0;
    else oom_sweep(s, &p, path, &ok);
    us_plan_free(&p);
    us_structure_free(s);
  }
  CHECK(ok);
}

/* ------------------------------------------------ plan certificates */

static int same_forces(const us_Forces *a, const us_Forces *b, int dim) {
  if (a->ncontact != b->ncontact) return 0;
  for (int j = 0; j < a->ncontact; j++) {
    if (a->contact[j] != b->contact[j]) return 0;
    for (int d = 0; d < dim; d++)
      if (a->f[dim * j + d] != b->f[dim * j + d]) return 0;
  }
  return 1;
}

/* Write p with its certificates, read order and certificates back. */
static us_Status round_trip(const us_Structure *s, const us_Plan *p, const char *name,
                            us_Forces **certs, int *ngroups, us_Error *err) {
  char path[128];
  test_tmp_path(name, path, sizeof path);
  us_PlanSettings set = us_plan_default_settings();
  us_PlanFile pf;
  us_Status st = us_plan_write(s, p, &set, path, err);
  if (!st) st = us_plan_read(s, path, &pf, err);
  if (st) return st;
  *ngroups = pf.ngroups;
  st = us_plan_read_certs(s, path, &pf, certs, err);
  us_plan_file_free(&pf);
  unlink(path);
  return st;
}

static void certs_check_round_trip(const us_Structure *s, int *ok) {
  us_Plan p;
  memset(&p, 0, sizeof p);
  us_Error err;
  us_Forces *certs = NULL;
  int n = 0;
  *ok = plan_with_certs(s, &p) == US_OK && p.status == US_PLAN_FOUND &&
        round_trip(s, &p, "certs.json", &certs, &n, &err) == US_OK && certs;
  for (int k = 0; *ok && k <= n; k++) *ok = same_forces(&certs[k], &p.certs[k], s->dim);
  us_certs_free(certs, n + 1);
  us_plan_free(&p);
}

static void certs_read_back(void) {
  us_Structure *s = pyramid(5);
  CHECK(s);
  int ok = 0;
  certs_check_round_trip(s, &ok);
  us_structure_free(s);
  CHECK(ok);
}

/* 3D certificates (three components a contact) read back exactly. */
static void certs_read_back_3d(void) {
  us_Structure *s = pyramid3d(3);
  CHECK(s);
  int ok = 0;
  certs_check_round_trip(s, &ok);
  us_structure_free(s);
  CHECK(ok);
}

/* The stacker has contacts that share a point between the same bodies
 * (a corner on two faces): each is matched by its normal. */
static void certs_shared_points(void) {
  us_GenSettings g = us_gen_default_settings();
  g.rows = 14, g.width = 12, g.seed = 3;
  us_Structure *s = us_gen_stacker(&g, NULL);
  CHECK(s);
  int shared = 0;
  for (int i = 0; i < s->ncontact && !shared; i++)
    for (int j = i + 1; j < s->ncontact && !shared; j++)
      shared = s->contacts[i].a == s->contacts[j].a && s->contacts[i].b == s->contacts[j].b &&
               s->contacts[i].p[0] == s->contacts[j].p[0] && s->contacts[i].p[1] == s->contacts[j].p[1];
  int ok = 0;
  certs_check_round_trip(s, &ok);
  us_structure_free(s);
  CHECK(shared); /* the case this test is for */
  CHECK(ok);
}

/* A plan without steps gives no certificates; tampered steps are refused. */
static void certs_absent_or_tampered(void) {
  us_Structure *s = scene_column(2);
  CHECK(s);
  char path[128];
  test_tmp_path("t.json", path, sizeof path);
  us_PlanFile pf;
  us_Error err;
  us_Forces dummy, *certs = &dummy;
  spit(path, "{\"status\": \"found\", \"order\": [\"c1\", \"c0\"]}");
  CHECK_OK(us_plan_read(s, path, &pf, &err), &err);
  us_Status none = us_plan_read_certs(s, path, &pf, &certs, &err);
  int absent = none == US_OK && certs == NULL;
  const char *bad[] = {
      /* one step for two */
      "{\"status\": \"found\", \"order\": [\"c1\", \"c0\"], \"steps\": [{\"remove\": \"c1\", "
      "\"certificate\": {\"contacts\": []}}]}",
      /* the steps in another order */
      "{\"status\": \"found\", \"order\": [\"c1\", \"c0\"], \"steps\": [{\"remove\": \"c0\", "
      "\"certificate\": {\"contacts\": []}}, {\"remove\": \"c1\", \"certificate\": {\"contacts\": []}}]}",
      /* a contact the structure does not have */
      "{\"status\": \"found\", \"order\": [\"c1\", \"c0\"], \"steps\": [{\"remove\": \"c1\", "
      "\"certificate\": {\"contacts\": [{\"a\": \"ground\", \"b\": \"c1\", \"point\": [0, 0], "
      "\"normal\": [0, 1], \"force\": [1, 0]}]}}, {\"remove\": \"c0\", \"certificate\": "
      "{\"contacts\": []}}]}"};
  int refused_all = 1;
  for (int i = 0; i < 3; i++) {
    spit(path, bad[i]);
    us_error_clear(&err);
    us_Status st = us_plan_read_certs(s, path, &pf, &certs, &err);
    if (st != US_ERR_INPUT || certs || !strstr(err.msg, "steps")) {
      fprintf(stderr, "tampered %d: %s: %s\n", i, us_status_name(st), err.msg);
      refused_all = 0;
    }
  }
  s->dim = 3; /* a 2D certificate (two components) on a 3D structure */
  us_Status three = us_plan_read_certs(s, path, &pf, &certs, &err);
  s->dim = 2;
  us_plan_file_free(&pf);
  unlink(path);
  us_structure_free(s);
  CHECK(absent);
  CHECK(refused_all);
  CHECK_INT(three, ==, US_ERR_INPUT);
}

US_TEST_MAIN(T(json_parses_back), T(json_parses_back_3d), T(tampered_forces_flagged), T(hostile_ids_escaped), T(steps_and_verify), T(bad_input_refused),
             T(out_of_memory_leaves_nothing), T(certs_read_back), T(certs_read_back_3d), T(certs_shared_points),
             T(certs_absent_or_tampered))
