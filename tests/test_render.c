/* Tests of the renderer (src/render): SVG and PNG pictures of one scene.
 *
 * SVG: the file is well-formed XML (a small tag-nesting checker), one
 * <polygon> per polygon body, ids escaped, order numbers and legend
 * present, force arrows pointing into the upper body, resultants, bad settings
 * rejected before any file is written, and a write into a missing
 * directory failing with US_ERR_IO without leaving a file. Ids holding
 * characters XML cannot hold (controls, U+FFFE, U+FFFF, invalid UTF-8) give
 * a document libxml2 parses (libxml2 from scripts/deps.sh; the case fails
 * when the build did not find it).
 *
 * PNG: structures from the generators, planned by the planner, drawn, and
 * decoded again with cairo. A body's pixels are read at a point inside it
 * found from the SVG of the same settings (the mean of its polygon's
 * vertices, moved down by 30% of its height so that the step number
 * written at its centre is not under it), and must be the ramp colour of
 * its removal step, computed here from the plan (step / (steps - 1)), and
 * the same as the SVG's fill. The ramp's lightness is checked with CIE L*
 * (from relative luminance), not with the OKLab lightness the ramp is
 * built in. */
#define _POSIX_C_SOURCE 200809L
#include "render/render.h"
#include "scenes.h"
#include "test.h"
#include "pngread.h"
#include "tmpfiles.h"

#include <cairo.h>
#include <dirent.h>
#include <unistd.h>
#ifdef US_HAVE_LIBXML2
#include <libxml/parser.h>
#endif



static void hex(us_Rgb c, char out[8]) { snprintf(out, 8, "#%02x%02x%02x", c.r, c.g, c.b); }


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
  CHECK(test_tmp_path("plain.svg", path, sizeof path));
  us_RenderSettings r = us_render_default_settings();
  CHECK_NEAR(r.width_px, 800, 0);
  CHECK_OK(us_render_svg(s, &r, path, &err), &err);
  char *svg = test_slurp(path);
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
  CHECK(test_tmp_path("order.svg", path, sizeof path));
  int order[3] = {2, 1, 0};
  us_RenderSettings r = us_render_default_settings();
  r.order = order;
  r.norder = 3;
  r.show_contacts = 0;
  CHECK_OK(us_render_svg(s, &r, path, &err), &err);
  char *svg = test_slurp(path);
  us_structure_free(s);
  CHECK(svg != NULL);
  int ok = well_formed(svg) && count(svg, "<polygon") == 4 && strstr(svg, "removed first") &&
           strstr(svg, "removed last") && strstr(svg, "3 in the removal order") &&
           strstr(svg, ">1</text>") && strstr(svg, ">3</text>") && !strstr(svg, ">low</text>") &&
           !strstr(svg, "r=\"2.00\"/>");
  /* step 1 (body "top") gets the dark end of the ramp, step 3 the light */
  const char *top = strstr(svg, "<title>top</title>"), *low = strstr(svg, "<title>low</title>");
  char first[8], last[8];
  hex(us_ramp(0.0), first);
  hex(us_ramp(1.0), last);
  ok = ok && top && low && !strncmp(strstr(top, "fill=\"") + 6, first, 7) &&
       !strncmp(strstr(low, "fill=\"") + 6, last, 7);
  us_free(svg);
  CHECK(ok);
  remove(path);
}

/* Forces: one arrow per non-zero force; each normal part points into the
 * upper body: up the page, or right on a vertical joint (the convention
 * of src/render/forces.c); the legend names the convention. */
static void with_forces(void) {
  us_Error err;
  char path[128];
  us_Structure *s = scene(&err);
  CHECK(s != NULL);
  CHECK(test_tmp_path("forces.svg", path, sizeof path));
  int nc = s->ncontact, idx[64];
  double f[128];
  CHECK(nc <= 64);
  for (int k = 0; k < nc; k++) {
    idx[k] = k;
    f[2 * k] = 1.0 + k;
    f[2 * k + 1] = 0.0;
  }
  us_Forces fo = {nc, nc, idx, f};
  us_RenderSettings r = us_render_default_settings();
  r.forces = &fo;
  CHECK_OK(us_render_svg(s, &r, path, &err), &err);
  char *svg = test_slurp(path);
  CHECK(svg != NULL);
  int ok = well_formed(svg) && count(svg, "marker-end=\"url(#arrow)\"") == nc &&
           count(svg, "url(#arrow-friction)\"/>") == 0 && strstr(svg, "force of the lower body");
  const char *line = strstr(svg, "class=\"forces\"");
  int up_or_right = 0;
  double x1, y1, x2, y2;
  for (int k = 0; line && k < nc; k++) {
    line = strstr(line + 1, "<line");
    if (line && sscanf(line, "<line x1=\"%lf\" y1=\"%lf\" x2=\"%lf\" y2=\"%lf\"", &x1, &y1, &x2,
                       &y2) == 4)
      up_or_right += y2 < y1 - 0.1 || (fabs(y2 - y1) <= 0.1 && x2 > x1);
  }
  us_free(svg);
  CHECK(ok);
  CHECK_INT(up_or_right, ==, nc);
  /* resultants: one normal arrow per touching pair (either order) */
  int pairs = 0;
  for (int k = 0; k < nc; k++) {
    int first = 1;
    for (int j = 0; j < k; j++)
      first &= !((s->contacts[j].a == s->contacts[k].a && s->contacts[j].b == s->contacts[k].b) ||
                 (s->contacts[j].a == s->contacts[k].b && s->contacts[j].b == s->contacts[k].a));
    pairs += first;
  }
  r.force_resultants = 1;
  CHECK_OK(us_render_svg(s, &r, path, &err), &err);
  svg = test_slurp(path);
  CHECK(svg != NULL);
  CHECK_INT(count(svg, "marker-end=\"url(#arrow)\""), ==, pairs);
  CHECK(pairs < nc);
  CHECK(strstr(svg, "per touching pair") != NULL);
  us_free(svg);
  us_structure_free(s);
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
  CHECK(test_tmp_path("bad.svg", path, sizeof path));
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
  snprintf(bad, sizeof bad, "%s/no_such_dir/x.svg", test_dir);
  us_Status st5 = us_render_svg(s, &r, bad, &err);
  int bad_exists = exists(bad), io_msg = strstr(err.msg, "no_such_dir") != NULL;
  s->dim = 4; /* no such dimension */
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
  us_Status st = test_tmp_path("points.svg", path, sizeof path) ? us_render_svg(s, &r, path, &err)
                                                           : US_ERR_IO;
  us_structure_free(s);
  CHECK(ok);
  CHECK_OK(st, &err);
  char *svg = test_slurp(path);
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
  us_Status st = test_tmp_path("empty.svg", path, sizeof path) ? us_render_svg(s, NULL, path, &err)
                                                          : US_ERR_IO;
  us_structure_free(s);
  CHECK_OK(st, &err);
  char *svg = test_slurp(path);
  CHECK(svg != NULL);
  int ok = well_formed(svg) && !strstr(svg, "<polygon") && strstr(svg, "0 bodies (0 fixed)") &&
           !strstr(svg, "nan") && !strstr(svg, "inf");
  us_free(svg);
  CHECK(ok);
  remove(path);
}

/* ------------------------------------------------------------------ PNG */





static int near_rgb(us_Rgb a, us_Rgb b, int tol) {
  return abs(a.r - b.r) <= tol && abs(a.g - b.g) <= tol && abs(a.b - b.b) <= tol;
}

/* CIE L* from sRGB (D65 relative luminance): independent of the OKLab
 * lightness the ramp is built with. */
static double cie_lstar(us_Rgb c) {
  double v[3] = {c.r / 255.0, c.g / 255.0, c.b / 255.0};
  for (int i = 0; i < 3; i++) v[i] = v[i] <= 0.04045 ? v[i] / 12.92 : pow((v[i] + 0.055) / 1.055, 2.4);
  double y = 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2];
  return y > 216.0 / 24389.0 ? 116.0 * cbrt(y) - 16.0 : y * 24389.0 / 27.0;
}

/* p as a blend (1 - a) x + a y of two colours (antialiased lines): a, or
 * -1 when p is more than 3 levels off every blend. */
static double blend(us_Rgb p, us_Rgb x, us_Rgb y) {
  double d[3] = {y.r - x.r, y.g - x.g, y.b - x.b}, q[3] = {p.r - x.r, p.g - x.g, p.b - x.b};
  double a = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  a = a < 0 ? 0 : (a > 1 ? 1 : a);
  for (int i = 0; i < 3; i++)
    if (fabs(q[i] - a * d[i]) > 3.0) return -1;
  return a;
}

/* A body as the SVG draws it: mean of its polygon's vertices, pixel
 * bounding box, fill attribute. */
typedef struct BodyPx {
  double cx, cy, w, h;
  char fill[32];
} BodyPx;

static int svg_body(const char *svg, const char *id, BodyPx *b) {
  char key[80];
  snprintf(key, sizeof key, "<title>%s</title><polygon points=\"", id);
  const char *p = strstr(svg, key);
  if (!p) return 0;
  p += strlen(key);
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY}, x, y;
  int n = 0, used;
  b->cx = b->cy = 0;
  while (sscanf(p, "%lf,%lf%n", &x, &y, &used) == 2) {
    b->cx += x, b->cy += y, n++;
    lo[0] = fmin(lo[0], x), lo[1] = fmin(lo[1], y), hi[0] = fmax(hi[0], x), hi[1] = fmax(hi[1], y);
    p += used;
  }
  const char *f = strstr(p, "fill=\"");
  if (!n || !f) return 0;
  b->cx /= n, b->cy /= n, b->w = hi[0] - lo[0], b->h = hi[1] - lo[1];
  snprintf(b->fill, sizeof b->fill, "%.*s", (int)strcspn(f + 6, "\""), f + 6);
  return 1;
}

/* A number attribute of the first element after `at` (NAN if none). */
static double attr(const char *at, const char *name) {
  char key[32];
  snprintf(key, sizeof key, " %s=\"", name);
  const char *p = at ? strstr(at, key) : NULL;
  return p ? strtod(p + strlen(key), NULL) : NAN;
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
  CHECK(test_tmp_path("hostile.svg", path, sizeof path));
  us_RenderSettings r = us_render_default_settings();
  CHECK_OK(us_render_svg(s, &r, path, &err), &err);
  char png_path[128];
  us_Status png_st = us_render_png(s, &r, test_tmp_path("hostile.png", png_path, sizeof png_path), &err);
  us_structure_free(s);
  CHECK_OK(png_st, &err); /* cairo gets cleaned text: no error state */
  Png png = {0};
  CHECK(png_open(&png, png_path));
  png_close(&png);
  remove(png_path);
  char *svg = test_slurp(path);
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

/* Render s with r as name.png and name.svg; the SVG text (us_malloc'd). */
static char *render_both(const us_Structure *s, const us_RenderSettings *r, const char *name,
                         char *png_path, size_t n) {
  char svg_path[128], file[64];
  us_Error err;
  snprintf(file, sizeof file, "%s.svg", name);
  if (!test_tmp_path(file, svg_path, sizeof svg_path) || us_render_svg(s, r, svg_path, &err)) return NULL;
  snprintf(file, sizeof file, "%s.png", name);
  if (!test_tmp_path(file, png_path, n) || us_render_png(s, r, png_path, &err)) {
    fprintf(stderr, "render_both: %s\n", err.msg);
    return NULL;
  }
  char *svg = test_slurp(svg_path);
  remove(svg_path);
  return svg;
}

static us_Structure *pyramid(int rows) {
  us_GenSettings g = us_gen_default_settings();
  g.n = rows;
  us_Error err;
  return us_gen_pyramid(&g, &err);
}

/* step[i]: 1-based removal step of body i in plan p (0: not in it). */
static void plan_steps(const us_Plan *p, int *step) {
  for (int g = 0; g < p->ngroups; g++) {
    int a = p->group_start ? p->group_start[g] : g, b = p->group_start ? p->group_start[g + 1] : g + 1;
    for (int k = a; k < b; k++) step[p->order[k]] = g + 1;
  }
}

static void settings_from_plan(us_RenderSettings *r, const us_Plan *p) {
  r->order = p->order;
  r->norder = p->nsteps;
  r->group_start = p->group_start;
  r->ngroups = p->ngroups;
  r->blocked = p->blocked;
  r->nblocked = p->nblocked;
}

/* Every body of a planned pyramid has, in the PNG, the ramp colour of its
 * removal step, and the SVG's fill is the same colour; sizes and title. */
static void png_plan_colours(void) {
  us_Error err;
  us_Structure *s = pyramid(5);
  CHECK(s != NULL);
  us_PlanSettings ps = us_plan_default_settings();
  us_Plan plan;
  memset(&plan, 0, sizeof plan);
  CHECK_OK(us_plan(s, &ps, &plan, &err), &err);
  CHECK_INT(plan.status, ==, US_PLAN_FOUND);
  us_RenderSettings r = us_render_default_settings();
  settings_from_plan(&r, &plan);
  r.title = "pyramid \xE2\x80\x94 15 bodies, plan found";
  char png_path[128];
  char *svg = render_both(s, &r, "plan", png_path, sizeof png_path);
  Png png = {0};
  int opened = svg && png_open(&png, png_path), step[64] = {0}, bad = 0, title_ink = 0;
  plan_steps(&plan, step);
  double svg_h = attr(svg, "height");
  for (int i = 0; opened && i < s->nbody; i++) {
    BodyPx b;
    char want[8];
    us_Rgb c = us_ramp(plan.ngroups > 1 ? (step[i] - 1.0) / (plan.ngroups - 1.0) : 0.0);
    hex(c, want);
    us_Rgb got = pixel(&png, b.cx, svg_body(svg, s->bodies[i].id, &b) ? b.cy + 0.3 * b.h : -1);
    if (!near_rgb(got, c, 1) || strcmp(b.fill, want) || step[i] == 0) {
      fprintf(stderr, "body %s step %d: png %d,%d,%d svg %s, want %s\n", s->bodies[i].id, step[i],
              got.r, got.g, got.b, b.fill, want);
      bad++;
    }
  }
  for (int x = 0; opened && x < png.w; x++)
    for (int y = 0; y < 24; y++) title_ink += cie_lstar(pixel(&png, x, y)) < 30;
  int w = png.w, h = png.h;
  png_close(&png);
  us_free(svg);
  us_plan_free(&plan);
  us_structure_free(s);
  CHECK(opened);
  CHECK_INT(bad, ==, 0);
  CHECK_INT(w, ==, 800);
  CHECK_NEAR(h, svg_h, 0);
  CHECK(title_ink > 50);
  remove(png_path);
}

/* The ramp grows in lightness (CIE L*) from dark to light, and so does
 * the legend's strip in the PNG. */
static void ramp_lightness(void) {
  double prev = -1;
  for (int i = 0; i <= 100; i++) {
    double l = cie_lstar(us_ramp(i / 100.0));
    CHECK(l > prev + 0.2);
    prev = l;
  }
  CHECK(cie_lstar(us_ramp(0)) < 25 && cie_lstar(us_ramp(1)) > 85);
  us_Structure *col = scene_column(3);
  CHECK(col != NULL);
  int order[3] = {2, 1, 0};
  us_RenderSettings r = us_render_default_settings();
  r.order = order, r.norder = 3;
  char png_path[128];
  char *svg = render_both(col, &r, "ramp", png_path, sizeof png_path);
  us_structure_free(col);
  const char *strip = svg ? strstr(svg, "fill=\"url(#ramp)\"") : NULL;
  while (strip && strip > svg && strncmp(strip, "<rect", 5)) strip--;
  double x = attr(strip, "x"), y = attr(strip, "y"), w = attr(strip, "width"), h = attr(strip, "height");
  us_free(svg);
  Png png = {0};
  int opened = png_open(&png, png_path), drops = 0;
  double first = cie_lstar(pixel(&png, x + 2, y + h / 2)), last = first;
  for (double px = x + 2; opened && px < x + w - 2; px++) {
    double l = cie_lstar(pixel(&png, px, y + h / 2));
    drops += l < last - 0.5;
    last = l;
  }
  png_close(&png);
  CHECK(opened && isfinite(x + y + w + h));
  CHECK_INT(drops, ==, 0);
  CHECK(last - first > 50);
  remove(png_path);
}

/* --forces draws arrows: pixels of the arrow colour appear in the drawing
 * where there were none. */
static void png_forces_arrows(void) {
  us_Error err;
  us_Structure *s = pyramid(4);
  CHECK(s != NULL);
  us_StabilitySettings set = us_stability_default_settings();
  us_Stability *w = us_stability_new(s, &set, &err);
  us_StabilityResult res;
  us_stability_result_init(&res);
  us_Status st = w ? us_stability_test_full(w, &res, &err) : US_ERR_NOMEM;
  us_stability_free(w);
  us_RenderSettings r = us_render_default_settings();
  char plain[128], forced[128], file[32];
  us_Status st1 = st, st2 = st;
  if (!st) st1 = us_render_png(s, &r, test_tmp_path("noforces.png", plain, sizeof plain), &err);
  r.forces = &res.forces;
  snprintf(file, sizeof file, "forces.png");
  if (!st) st2 = us_render_png(s, &r, test_tmp_path(file, forced, sizeof forced), &err);
  int verdict = res.verdict;
  us_stability_result_free(&res);
  us_structure_free(s);
  CHECK_OK(st, &err);
  CHECK_INT(verdict, ==, US_STABLE);
  CHECK_OK(st1, &err);
  CHECK_OK(st2, &err);
  Png a = {0}, b = {0};
  int ok = png_open(&a, plain) && png_open(&b, forced), diff = 0, red_a = 0, red_b = 0, white = 1;
  us_Rgb red = {31, 78, 156}; /* the normal parts' blue */
  int rows = ok ? US_MIN(a.h, b.h) - 80 : 0; /* the drawing, not the legend */
  for (int y = 0; ok && y < rows; y++)
    for (int x = 0; x < a.w; x++) {
      us_Rgb p = pixel(&a, x, y), q = pixel(&b, x, y);
      diff += !near_rgb(p, q, 0);
      red_a += near_rgb(p, red, 1);
      red_b += near_rgb(q, red, 1);
      if (y < 3) white &= near_rgb(p, (us_Rgb){255, 255, 255}, 0); /* no title band */
    }
  int wb = b.w;
  png_close(&a);
  png_close(&b);
  CHECK(ok);
  CHECK_INT(wb, ==, 800);
  CHECK_INT(red_a, ==, 0);
  CHECK(red_b > 100);
  CHECK(diff >= red_b);
  CHECK(white);
  remove(plain);
  remove(forced);
}

/* A plan with status none: the blocked voussoirs are hatched (both hatch
 * colours inside each), the others keep the neutral fill; the SVG names
 * the pattern and the legend says "cannot be removed". */
static void png_none_blocked(void) {
  us_Error err;
  us_GenSettings g = us_gen_default_settings();
  g.n = 7;
  us_Structure *s = us_gen_arch(&g, &err);
  CHECK(s != NULL);
  us_PlanSettings ps = us_plan_default_settings();
  us_Plan plan;
  memset(&plan, 0, sizeof plan);
  us_Status st = us_plan(s, &ps, &plan, &err);
  us_RenderSettings r = us_render_default_settings();
  settings_from_plan(&r, &plan);
  r.show_labels = 0; /* ids would be written where the pixels are read */
  char png_path[128];
  char *svg = st ? NULL : render_both(s, &r, "none", png_path, sizeof png_path);
  Png png = {0};
  int opened = svg && png_open(&png, png_path), bad = 0, nblocked = plan.nblocked;
  const us_Hatch *h = &us_hatches[US_HATCH_BLOCKED];
  int *blocked = us_calloc((size_t)s->nbody, sizeof *blocked);
  for (int k = 0; blocked && k < plan.nblocked; k++) blocked[plan.blocked[k]] = 1;
  for (int i = 0; opened && blocked && i < s->nbody; i++) {
    BodyPx b;
    int found = svg_body(svg, s->bodies[i].id, &b), base = 0, line = 0, other = 0;
    for (int dx = -4; found && dx <= 4; dx++)
      for (int dy = -4; dy <= 4; dy++) {
        double a = blend(pixel(&png, b.cx + dx, b.cy + dy), h->base, h->line);
        base += a >= 0 && a < 0.1, line += a > 0.5, other += a < 0;
      }
    int hatched = base > 0 && line > 0 && other == 0;
    us_Rgb c = pixel(&png, b.cx, b.cy);
    char got[8];
    hex(c, got);
    if (!found || (blocked[i] ? !hatched || strcmp(b.fill, "url(#blocked)")
                              : hatched || strcmp(b.fill, got))) {
      fprintf(stderr, "body %s (blocked %d): base %d line %d other %d, svg %s, png %s\n",
              s->bodies[i].id, blocked[i], base, line, other, b.fill, got);
      bad++;
    }
  }
  int legend = svg && strstr(svg, ">cannot be removed</text>") && strstr(svg, ">5 cannot be removed</text>");
  png_close(&png);
  us_free(blocked);
  us_free(svg);
  us_PlanStatus status = plan.status;
  us_plan_free(&plan);
  us_structure_free(s);
  CHECK_OK(st, &err);
  CHECK_INT(status, ==, US_PLAN_NONE);
  CHECK_INT(nblocked, ==, 5);
  CHECK(opened);
  CHECK_INT(bad, ==, 0);
  CHECK(legend);
  remove(png_path);
}

/* Sizes: the width asked for; a height asked for is the height; too large
 * or too small is a usage error before any file; a tall structure at an
 * automatic height stays within the limits, the drawing shrunk to fit. */
static void png_sizes(void) {
  us_Error err;
  us_Structure *s = scene_column(40);
  CHECK(s != NULL);
  char path[128], none[128];
  test_tmp_path("size.png", path, sizeof path);
  test_tmp_path("nothing.png", none, sizeof none);
  us_RenderSettings r = us_render_default_settings();
  r.width_px = 300;
  us_Status st1 = us_render_png(s, &r, path, &err);
  Png a = {0};
  int ok1 = !st1 && png_open(&a, path), w1 = a.w, h1 = a.h;
  png_close(&a);
  r.height_px = 200;
  us_Status st2 = us_render_png(s, &r, path, &err);
  int ok2 = !st2 && png_open(&a, path), w2 = a.w, h2 = a.h;
  png_close(&a);
  r.height_px = 0, r.width_px = 20000;
  us_Status big_w = us_render_png(s, &r, none, &err);
  r.width_px = 800, r.height_px = 20000;
  us_Status big_h = us_render_png(s, &r, none, &err);
  r.height_px = 60, r.title = "t"; /* title and legend take more */
  us_Status small_h = us_render_png(s, &r, none, &err);
  int wrote = access(none, F_OK) == 0;
  /* the limits themselves, small: 400 px wide, at most 1000 a side and
     300,000 pixels: the column (about 8 times as tall as wide) gets 750 */
  us_Scene sc;
  r = us_render_default_settings();
  r.width_px = 400;
  us_Status st3 = us_scene_build(&sc, s, &r, 1000, 300000, &err);
  int inside = 1;
  for (int k = 0; !st3 && k < 2 * 4 * 40; k += 2)
    inside &= sc.pts[k] >= 0 && sc.pts[k] <= sc.w && sc.pts[k + 1] >= sc.draw_top &&
              sc.pts[k + 1] <= sc.draw_bottom;
  double sw = sc.w, sh = sc.h;
  if (!st3) us_scene_free(&sc);
  us_structure_free(s);
  CHECK_OK(st1, &err);
  CHECK(ok1 && w1 == 300 && h1 > 1000);
  CHECK_OK(st2, &err);
  CHECK(ok2 && w2 == 300 && h2 == 200);
  CHECK_INT(big_w, ==, US_ERR_USAGE);
  CHECK_INT(big_h, ==, US_ERR_USAGE);
  CHECK_INT(small_h, ==, US_ERR_USAGE);
  CHECK(!wrote);
  CHECK_OK(st3, &err);
  CHECK_NEAR(sw, 400, 0);
  CHECK_NEAR(sh, 750, 0);
  CHECK(inside);
  remove(path);
}

/* Nothing is written on an error: an existing file keeps its content
 * after a bad order, a missing directory is US_ERR_IO, and every failed
 * allocation is US_ERR_NOMEM with the old file untouched. */
static void png_errors(void) {
  us_Error err;
  us_Structure *s = scene_column(3);
  CHECK(s != NULL);
  char path[128], bad[160];
  test_tmp_path("old.png", path, sizeof path);
  FILE *fp = fopen(path, "w");
  CHECK(fp != NULL);
  fputs("old", fp);
  fclose(fp);
  us_RenderSettings r = us_render_default_settings();
  int order[2] = {0, 9};
  r.order = order, r.norder = 2;
  us_Status st1 = us_render_png(s, &r, path, &err);
  r.norder = 0;
  snprintf(bad, sizeof bad, "%s/no_such_dir/x.png", test_dir);
  us_Status st2 = us_render_png(s, &r, bad, &err);
  int nomem_only = 1, done = 0;
  for (long n = 0; n < 1000 && !done; n++) {
    us_alloc_fail_after(n);
    us_Status st = us_render_png(s, &r, path, &err);
    us_alloc_fail_after(-1);
    char *text = st ? test_slurp(path) : NULL;
    if (st && (st != US_ERR_NOMEM || !text || strcmp(text, "old"))) nomem_only = 0;
    us_free(text);
    done = st == US_OK;
  }
  Png png = {0};
  int decoded = png_open(&png, path);
  png_close(&png);
  us_structure_free(s);
  CHECK_INT(st1, ==, US_ERR_USAGE);
  CHECK_INT(st2, ==, US_ERR_IO);
  CHECK(access(bad, F_OK) != 0);
  CHECK(nomem_only);
  CHECK(done);
  CHECK(decoded);
  remove(path);
}

/* The SVG of s under r (us_malloc'd), or NULL. */
static char *svg_of(const us_Structure *s, const us_RenderSettings *r, const char *name) {
  char path[128];
  us_Error err;
  if (!test_tmp_path(name, path, sizeof path) || us_render_svg(s, r, path, &err)) return NULL;
  char *svg = test_slurp(path);
  remove(path);
  return svg;
}

/* The <g class="bodies"> part of an SVG: labels of bodies only. */
static int body_texts(const char *svg) {
  const char *a = strstr(svg, "<g class=\"bodies\">"), *b = a ? strstr(a, "</g>\n</g>") : NULL;
  int n = 0;
  for (const char *p = a; p && (p = strstr(p, "<text")) && p < b; p++) n++;
  return n;
}

/* --labels: ids, steps or none, with an order; steps without one. */
static void labels(void) {
  us_Error err;
  us_Structure *s = scene(&err);
  CHECK(s != NULL);
  int order[3] = {2, 1, 0};
  us_RenderSettings r = us_render_default_settings();
  r.order = order, r.norder = 3;
  r.labels = US_LABELS_IDS;
  char *ids = svg_of(s, &r, "l_ids.svg");
  r.labels = US_LABELS_STEPS;
  char *steps = svg_of(s, &r, "l_steps.svg");
  r.labels = US_LABELS_NONE;
  char *none = svg_of(s, &r, "l_none.svg");
  r.labels = (us_Labels)7;
  us_Status bad = us_render_svg(s, &r, "/nonexistent/x.svg", &err);
  char png[128];
  r.labels = US_LABELS_IDS;
  char *both = render_both(s, &r, "l_png", png, sizeof png);
  us_structure_free(s);
  CHECK(ids && steps && none && both);
  CHECK(strstr(ids, ">low</text>") && strstr(ids, ">top</text>") && !strstr(ids, ">1</text>"));
  CHECK(strstr(steps, ">1</text>") && strstr(steps, ">3</text>") && !strstr(steps, ">low</text>"));
  CHECK_INT(body_texts(ids), ==, 4); /* the pier too */
  CHECK_INT(body_texts(steps), ==, 3);
  CHECK_INT(body_texts(none), ==, 0);
  CHECK_INT(bad, ==, US_ERR_USAGE);
  us_free(ids), us_free(steps), us_free(none), us_free(both);
  remove(png);
}

/* A top block overhanging its base: it does not stand. */
static us_Structure *overhang(void) {
  us_Structure *s = us_structure_new(2);
  if (scene_box(s, "base", 0, 0, 1, 1, 1) < 0 || scene_box(s, "top", 0.6, 1, 1.2, 0.4, 1) < 0)
    return us_structure_free(s), NULL;
  return scene_seal(s);
}

/* An unstable structure's picture: the falling body in class "falls",
 * the mechanism's arrows and the ghost of the moving body. */
static void unstable_marked(void) {
  us_Error err;
  us_Structure *s = overhang();
  CHECK(s != NULL);
  us_StabilitySettings set = us_stability_default_settings();
  us_Stability *w = us_stability_new(s, &set, &err);
  us_StabilityResult res;
  us_stability_result_init(&res);
  CHECK(w != NULL);
  CHECK_OK(us_stability_test_full(w, &res, &err), &err);
  us_RenderFailure f = {0, res.unstable_body, &res.mechanism};
  us_RenderSettings r = us_render_default_settings();
  r.failure = &f;
  char png[128];
  char *svg = render_both(s, &r, "unstable", png, sizeof png);
  int top = us_structure_find_body(s, "top"), verdict = res.verdict;
  f.body = s->nbody; /* out of range */
  us_Status bad = us_render_svg(s, &r, "/nonexistent/x.svg", &err);
  us_stability_result_free(&res);
  us_stability_free(w);
  us_structure_free(s);
  CHECK_INT(verdict, ==, US_UNSTABLE);
  CHECK(svg != NULL && well_formed(svg));
  CHECK_INT(count(svg, "class=\"falls\""), ==, 1);
  CHECK(top >= 0);
  CHECK(strstr(svg, "<g class=\"falls\"><title>top</title>") != NULL);
  CHECK(strstr(svg, "class=\"mechanism\"") != NULL);
  CHECK_INT(count(svg, "class=\"ghost\""), ==, 1);   /* only the top moves */
  CHECK_INT(count(svg, "class=\"velocity\""), >=, 1);
  CHECK(strstr(svg, "does not stand") != NULL);
  CHECK_INT(bad, ==, US_ERR_USAGE);
  us_free(svg);
  remove(png);
}

/* An order failing at step 1: that step's body dashed and white, the
 * body named as falling marked, no mechanism given: none drawn. */
static void failing_step(void) {
  us_Error err;
  us_Structure *s = scene(&err);
  CHECK(s != NULL);
  int order[3] = {0, 1, 2};
  us_RenderFailure f = {1, 1, NULL};
  us_RenderSettings r = us_render_default_settings();
  r.order = order, r.norder = 3, r.failure = &f;
  char *svg = svg_of(s, &r, "failing.svg");
  f.step = 4; /* past the order */
  us_Status bad = us_render_svg(s, &r, "/nonexistent/x.svg", &err);
  us_structure_free(s);
  CHECK(svg != NULL && well_formed(svg));
  CHECK(strstr(svg, "<g class=\"failing-step\"><title>low</title>") != NULL);
  CHECK_INT(count(svg, "class=\"falls\""), ==, 1);
  CHECK_INT(count(svg, "class=\"failing-step\""), ==, 1);
  CHECK(!strstr(svg, "class=\"mechanism\""));
  const char *low = strstr(svg, "<title>low</title>");
  CHECK(low && !strncmp(strstr(low, "fill=\"") + 6, "#ffffff", 7));
  CHECK(strstr(svg, "fails at step 1") != NULL);
  CHECK_INT(bad, ==, US_ERR_USAGE);
  us_free(svg);
}

/* A build order (a none plan's buildable part): numbered, "placed first". */
static void build_order(void) {
  us_Error err;
  us_Structure *s = scene(&err);
  CHECK(s != NULL);
  int order[2] = {0, 1}, blocked[1] = {2};
  us_RenderSettings r = us_render_default_settings();
  r.order = order, r.norder = 2, r.order_builds = 1;
  r.blocked = blocked, r.nblocked = 1;
  char *svg = svg_of(s, &r, "build.svg");
  us_structure_free(s);
  CHECK(svg != NULL);
  CHECK(strstr(svg, "placed first") && strstr(svg, "2 in the build order"));
  CHECK(strstr(svg, ">1</text>") && strstr(svg, ">2</text>") && !strstr(svg, ">3</text>"));
  CHECK(strstr(svg, "url(#blocked)") != NULL);
  us_free(svg);
}

/* Hand states (a plan with hands at one action; the fixed pier ignores
 * its own): one hand mark per held body, a held outline, the unplaced body
 * faint and unlabelled, the legend's counts; a state out of range is
 * US_ERR_USAGE. */
static void hands(void) {
  us_Error err;
  us_Structure *s = scene(&err);
  CHECK(s != NULL);
  int order[3] = {0, 1, 2};
  unsigned char state[4] = {US_HAND_PLACED, US_HAND_HELD, US_HAND_UNPLACED, US_HAND_UNPLACED};
  us_RenderSettings r = us_render_default_settings();
  r.order = order, r.norder = 3, r.order_builds = 1, r.hand_state = state;
  char *svg = svg_of(s, &r, "hands.svg");
  CHECK(svg != NULL);
  CHECK_INT(count(svg, "class=\"held\""), ==, 1);
  CHECK_INT(count(svg, "class=\"held-body\""), ==, 1);
  CHECK(strstr(svg, "2 placed, 1 of them held") && strstr(svg, "1 not placed yet"));
  CHECK(strstr(svg, ">2</text>") && !strstr(svg, ">3</text>"));
  CHECK(strstr(svg, "fill=\"#f6f6f6\"") != NULL);
  us_free(svg);
  state[2] = US_HAND_HELD;
  svg = svg_of(s, &r, "hands2.svg");
  CHECK(svg && count(svg, "class=\"held\"") == 2);
  us_free(svg);
  state[0] = 7;
  char path[128];
  CHECK(test_tmp_path("hands-bad.svg", path, sizeof path));
  CHECK_INT(us_render_svg(s, &r, path, &err), ==, US_ERR_USAGE);
  CHECK(access(path, F_OK) != 0);
  us_structure_free(s);
}

US_TEST_MAIN(T(checker), T(plain), T(with_order), T(with_forces), T(errors), T(point_bodies), T(empty), T(hostile_ids),
             T(png_plan_colours), T(ramp_lightness), T(png_forces_arrows), T(png_none_blocked),
             T(png_sizes), T(png_errors), T(labels), T(unstable_marked), T(failing_step),
             T(build_order), T(hands))
