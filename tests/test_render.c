/* Tests of the SVG renderer (src/render): the file is well-formed XML (a
 * small tag-nesting checker), one <polygon> per polygon body, ids escaped,
 * order numbers and legend present, force arrows pointing along the force
 * on body b, bad settings rejected before any file is written, and a write
 * into a missing directory failing with US_ERR_IO without leaving a file.
 * Ids holding characters XML cannot hold (controls, U+FFFE, U+FFFF, invalid
 * UTF-8) give a document libxml2 parses (libxml2 from scripts/deps.sh; the
 * case fails when the build did not find it). */
#define _POSIX_C_SOURCE 200809L
#include "scenes.h"
#include "test.h"

#include <unistd.h>
#ifdef US_HAVE_LIBXML2
#include <libxml/parser.h>
#endif

static char g_dir[64];

/* A fresh temporary directory for this run's files. */
static const char *tmp_path(const char *name, char *buf, size_t n) {
  if (!g_dir[0]) {
    snprintf(g_dir, sizeof g_dir, "/tmp/us_test_render_XXXXXX");
    if (!mkdtemp(g_dir)) return NULL;
  }
  snprintf(buf, n, "%s/%s", g_dir, name);
  return buf;
}

/* Whole file as a string (us_malloc'd) or NULL. */
static char *slurp(const char *path) {
  FILE *fp = fopen(path, "rb");
  if (!fp) return NULL;
  fseek(fp, 0, SEEK_END);
  long n = ftell(fp);
  fseek(fp, 0, SEEK_SET);
  char *s = us_malloc((size_t)n + 1);
  if (s && fread(s, 1, (size_t)n, fp) != (size_t)n) us_free(s), s = NULL;
  if (s) s[n] = 0;
  fclose(fp);
  return s;
}

static int count(const char *hay, const char *needle) {
  int n = 0;
  for (const char *p = hay; (p = strstr(p, needle)); p += strlen(needle)) n++;
  return n;
}

/* Minimal well-formedness: tags nest and match, every '&' starts an entity,
 * no '<' inside attribute values or text, one root element. */
static int well_formed(const char *s) {
  char stack[64][32];
  int depth = 0, roots = 0;
  for (const char *p = s; *p; p++) {
    if (*p == '&') {
      const char *e = strchr(p, ';');
      if (!e || e - p > 6 || e == p + 1) return 0;
      continue;
    }
    if (*p != '<') continue;
    if (p[1] == '?') { p = strstr(p, "?>"); if (!p) return 0; continue; }
    const char *end = p + 1;
    char quote = 0;
    for (; *end && (quote || *end != '>'); end++) {
      if (quote && *end == '<') return 0;
      if (*end == '"') quote = quote ? 0 : '"';
    }
    if (!*end) return 0;
    int closing = p[1] == '/', selfclose = end[-1] == '/';
    const char *nm = p + 1 + closing;
    size_t len = strcspn(nm, " \t\n/>");
    if (len == 0 || len >= 32) return 0;
    if (closing) {
      if (depth == 0 || strncmp(stack[depth - 1], nm, len) || stack[depth - 1][len]) return 0;
      depth--;
    } else {
      roots += depth == 0;
      if (selfclose) { p = end; continue; }
      if (depth == 64) return 0;
      memcpy(stack[depth], nm, len);
      stack[depth++][len] = 0;
    }
    p = end;
  }
  return depth == 0 && roots == 1;
}

/* Three stacked boxes (ids with XML specials), and a fixed pier beside. */
static us_Structure *scene(us_Error *err) {
  us_Structure *s = us_structure_new(2);
  const char *ids[3] = {"low", "a&<b>\"q'", "top"};
  for (int i = 0; i < 3; i++) {
    double y0 = 0.5 * i, xy[8] = {0, y0, 1, y0, 1, y0 + 0.5, 0, y0 + 0.5};
    if (us_structure_add_body(s,
                              &(us_BodyDef){.id = ids[i],
                                            .nvert = 4,
                                            .xy = xy,
                                            .density = 1,
                                            .friction = -1},
                              err) < 0)
      goto fail;
  }
  double pier[8] = {1, 0, 2, 0, 2, 1.5, 1, 1.5};
  if (us_structure_add_body(s,
                            &(us_BodyDef){.id = "pier",
                                          .nvert = 4,
                                          .xy = pier,
                                          .density = 1,
                                          .fixed = 1,
                                          .friction = -1},
                            err) < 0)
    goto fail;
  if (us_structure_finalize(s, err)) goto fail;
  return s;
fail:
  us_structure_free(s);
  return NULL;
}

static void plain(void) {
  us_Error err;
  char path[128];
  us_Structure *s = scene(&err);
  CHECK(s != NULL);
  CHECK(tmp_path("plain.svg", path, sizeof path));
  us_RenderSettings r = us_render_default_settings();
  CHECK_NEAR(r.width_px, 800, 0);
  CHECK_OK(us_render_svg(s, &r, path, &err), &err);
  char *svg = slurp(path);
  us_structure_free(s);
  CHECK(svg != NULL);
  int ok = well_formed(svg) && count(svg, "<polygon") == 4 &&
           count(svg, "a&amp;&lt;b&gt;&quot;q&apos;") == 2 && /* title + label */
           !strstr(svg, "a&<b") && strstr(svg, ">low</text>") &&
           strstr(svg, "width=\"800\"") && strstr(svg, "url(#fixed)") &&
           strstr(svg, "class=\"ground\"") && strstr(svg, "4 bodies (1 fixed)") &&
           !strstr(svg, "removed first");
  int dots = count(svg, "r=\"2.00\"/>");
  us_free(svg);
  CHECK(ok);
  CHECK(dots > 0);
  remove(path);
}

/* With an order: numbers 1..3 on the ramp, legend, no id labels. */
static void with_order(void) {
  us_Error err;
  char path[128];
  us_Structure *s = scene(&err);
  CHECK(s != NULL);
  CHECK(tmp_path("order.svg", path, sizeof path));
  int order[3] = {2, 1, 0};
  us_RenderSettings r = us_render_default_settings();
  r.order = order;
  r.norder = 3;
  r.show_contacts = 0;
  CHECK_OK(us_render_svg(s, &r, path, &err), &err);
  char *svg = slurp(path);
  us_structure_free(s);
  CHECK(svg != NULL);
  int ok = well_formed(svg) && count(svg, "<polygon") == 4 && strstr(svg, "removed first") &&
           strstr(svg, "removed last") && strstr(svg, "3 in the removal order") &&
           strstr(svg, ">1</text>") && strstr(svg, ">3</text>") && !strstr(svg, ">low</text>") &&
           !strstr(svg, "r=\"2.00\"/>");
  /* step 1 (body "top") gets the dark end of the ramp, step 3 the light */
  const char *top = strstr(svg, "<title>top</title>"), *low = strstr(svg, "<title>low</title>");
  ok = ok && top && low && !strncmp(strstr(top, "fill=\"") + 6, "#440154", 7) &&
       !strncmp(strstr(low, "fill=\"") + 6, "#fde725", 7);
  us_free(svg);
  CHECK(ok);
  remove(path);
}

/* Forces: one arrow per non-zero force, along the force on body b. */
static void with_forces(void) {
  us_Error err;
  char path[128];
  us_Structure *s = scene(&err);
  CHECK(s != NULL);
  CHECK(tmp_path("forces.svg", path, sizeof path));
  int nc = s->ncontact, idx[64];
  double f[128];
  CHECK(nc <= 64);
  int g0 = -1;
  for (int k = 0; k < nc; k++) {
    idx[k] = k;
    f[2 * k] = 1.0 + k;
    f[2 * k + 1] = 0.0;
    if (g0 < 0 && s->contacts[k].a == US_GROUND) g0 = k;
  }
  CHECK(g0 >= 0);
  us_Forces fo = {nc, nc, idx, f};
  us_RenderSettings r = us_render_default_settings();
  r.forces = &fo;
  CHECK_OK(us_render_svg(s, &r, path, &err), &err);
  char *svg = slurp(path);
  CHECK(svg != NULL);
  int ok = well_formed(svg) && count(svg, "marker-end=\"url(#arrow)\"") == nc &&
           strstr(svg, "arrows: contact forces");
  /* the ground pushes b up: the arrow of contact g0 goes up the page */
  const char *line = strstr(svg, "class=\"forces\"");
  for (int k = 0; line && k <= g0; k++) line = strstr(line + 1, "<line");
  double x1, y1, x2, y2;
  ok = ok && line &&
       sscanf(line, "<line x1=\"%lf\" y1=\"%lf\" x2=\"%lf\" y2=\"%lf\"", &x1, &y1, &x2, &y2) == 4 &&
       y2 < y1 && fabs(x2 - x1) < 1e-9;
  us_free(svg);
  us_structure_free(s);
  CHECK(ok);
  remove(path);
}

static int exists(const char *path) { return access(path, F_OK) == 0; }

/* Bad orders / forces / widths are usage errors and write nothing; a
 * missing directory is an I/O error and leaves no file. */
static void errors(void) {
  us_Error err;
  char path[128], bad[160];
  us_Structure *s = scene(&err);
  CHECK(s != NULL);
  CHECK(tmp_path("bad.svg", path, sizeof path));
  us_RenderSettings r = us_render_default_settings();
  int order[2] = {0, 7};
  r.order = order, r.norder = 2;
  us_Status st1 = us_render_svg(s, &r, path, &err);
  order[1] = 0; /* twice */
  us_Status st2 = us_render_svg(s, &r, path, &err);
  int twice = strstr(err.msg, "'low'") != NULL;
  r.norder = 0;
  int idx = 99;
  double f[2] = {1, 0};
  us_Forces fo = {1, 1, &idx, f};
  r.forces = &fo;
  us_Status st3 = us_render_svg(s, &r, path, &err);
  r.forces = NULL;
  r.width_px = 0;
  us_Status st4 = us_render_svg(s, &r, path, &err);
  int wrote = exists(path);
  r.width_px = 300;
  snprintf(bad, sizeof bad, "%s/no_such_dir/x.svg", g_dir);
  us_Status st5 = us_render_svg(s, &r, bad, &err);
  int bad_exists = exists(bad), io_msg = strstr(err.msg, "no_such_dir") != NULL;
  s->dim = 3;
  us_Status st7 = us_render_svg(s, NULL, path, &err);
  int wrote3d = exists(path);
  s->dim = 2;
  us_Status st6 = us_render_svg(s, NULL, path, &err); /* NULL: defaults */
  us_structure_free(s);
  CHECK_INT(st1, ==, US_ERR_USAGE);
  CHECK_INT(st2, ==, US_ERR_USAGE);
  CHECK(twice);
  CHECK_INT(st3, ==, US_ERR_USAGE);
  CHECK_INT(st4, ==, US_ERR_USAGE);
  CHECK(!wrote);
  CHECK_INT(st5, ==, US_ERR_IO);
  CHECK(io_msg);
  CHECK(!bad_exists);
  CHECK_INT(st7, ==, US_ERR_USAGE);
  CHECK(!wrote3d);
  CHECK_INT(st6, ==, US_OK);
  CHECK(exists(path));
  remove(path);
}

/* Bodies without geometry are circles; an unfinalized structure renders. */
static void point_bodies(void) {
  us_Error err;
  char path[128];
  us_Structure *s = us_structure_new(2);
  CHECK(s != NULL);
  double c1[3] = {0, 1, 0}, c2[3] = {2, 1, 0};
  double sq[8] = {3, 0, 4, 0, 4, 1, 3, 1};
  int ok =
      us_structure_add_point_body(s, "p1", 1, c1, 0, &err) >= 0 &&
      us_structure_add_point_body(s, "p2", 1, c2, 0, &err) >= 0 &&
      scene_polygon(s, "sq", 4, sq, 0) >= 0;
  us_RenderSettings r = us_render_default_settings();
  us_Status st = tmp_path("points.svg", path, sizeof path) ? us_render_svg(s, &r, path, &err)
                                                           : US_ERR_IO;
  us_structure_free(s);
  CHECK(ok);
  CHECK_OK(st, &err);
  char *svg = slurp(path);
  CHECK(svg != NULL);
  ok = well_formed(svg) && count(svg, "r=\"6\"") == 2 && count(svg, "<polygon") == 1 &&
       strstr(svg, ">sq</text>") && strstr(svg, ">p2</text>");
  us_free(svg);
  CHECK(ok);
  remove(path);
}

/* An empty structure still gives a valid picture (ground and legend). */
static void empty(void) {
  us_Error err;
  char path[128];
  us_Structure *s = us_structure_new(2);
  CHECK(s != NULL);
  us_Status st = tmp_path("empty.svg", path, sizeof path) ? us_render_svg(s, NULL, path, &err)
                                                          : US_ERR_IO;
  us_structure_free(s);
  CHECK_OK(st, &err);
  char *svg = slurp(path);
  CHECK(svg != NULL);
  int ok = well_formed(svg) && !strstr(svg, "<polygon") && strstr(svg, "0 bodies (0 fixed)") &&
           !strstr(svg, "nan") && !strstr(svg, "inf");
  us_free(svg);
  CHECK(ok);
  remove(path);
}

/* 1 when libxml2 parses the file as XML 1.0 without any error. */
static int libxml_parses(const char *path) {
#ifdef US_HAVE_LIBXML2
  xmlDocPtr doc = xmlReadFile(path, NULL, XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
  int ok = doc != NULL;
  xmlFreeDoc(doc);
  xmlCleanupParser();
  return ok;
#else
  fprintf(stderr, "libxml2 was not found at configure time: run scripts/deps.sh\n");
  US_UNUSED(path);
  return 0;
#endif
}

/* Ids with characters XML 1.0 cannot hold still give valid XML, with the
 * characters replaced by U+FFFD; ordinary UTF-8 and specials pass. */
static void hostile_ids(void) {
  us_Error err;
  char path[128];
  const char *ids[] = {"esc\x1b[31m\x07", "nl\nx", "\xef\xbf\xbe\xef\xbf\xbf", "bad\xff\xc0",
                       "\xed\xa0\x80sur", "caf\xc3\xa9 <&>"};
  us_Structure *s = us_structure_new(2);
  for (int i = 0; i < 6; i++) {
    double y0 = i, xy[8] = {0, y0, 1, y0, 1, y0 + 1, 0, y0 + 1};
    CHECK(us_structure_add_polygon(s, ids[i], 4, xy, 1, 0, 0, -1, &err) >= 0);
  }
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK(tmp_path("hostile.svg", path, sizeof path));
  us_RenderSettings r = us_render_default_settings();
  CHECK_OK(us_render_svg(s, &r, path, &err), &err);
  us_structure_free(s);
  char *svg = slurp(path);
  CHECK(svg != NULL);
  int ok = well_formed(svg) && !strchr(svg, 0x1b) && !strchr(svg, 0x07) &&
           !strstr(svg, "\xef\xbf\xbe") && !strstr(svg, "\xef\xbf\xbf") && !strstr(svg, "\xff") &&
           strstr(svg, "caf\xc3\xa9 &lt;&amp;&gt;") && strstr(svg, "esc\xef\xbf\xbd[31m\xef\xbf\xbd");
  us_free(svg);
  CHECK(ok);
  CHECK(libxml_parses(path));
  remove(path);
}

/* The checker itself rejects broken documents. */
static void checker(void) {
  CHECK(well_formed("<a><b/></a>"));
  CHECK(!well_formed("<a><b></a>"));
  CHECK(!well_formed("<a>x & y</a>"));
  CHECK(!well_formed("<a t=\"<\"/>"));
  CHECK(!well_formed("<a/><b/>"));
}

static void cleanup(void) {
  if (g_dir[0]) CHECK(rmdir(g_dir) == 0);
}

US_TEST_MAIN(T(checker), T(plain), T(with_order), T(with_forces), T(errors), T(point_bodies), T(empty),
             T(hostile_ids),
             T(cleanup))
