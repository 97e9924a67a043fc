/* unstack render: draw a structure, optionally with a plan and forces, as
 * SVG or PNG (docs/render.md), or as the interactive HTML viewer
 * (--html, cmd_render_html.c, docs/viewer.md). 3D structures are drawn
 * axonometrically (--view AZ,EL) as SVG or PNG; the viewer is 2D only.
 *
 * The flow: parse, check the output can be written, pick the format
 * (--format or --html, else the output's extension), load the structure
 * and the plan, test the full structure when a picture's title needs its
 * verdict (no plan) or --forces needs its forces, compose the title, write
 * with the format's writer (write_output: one branch per format). */
#include "options.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static const char help[] =
    "usage: unstack render FILE [--plan PLAN.json] [--forces] -o OUT.svg|OUT.png\n"
    "       unstack render FILE [--plan PLAN.json] --html -o OUT.html\n"
    "\n"
    "Draw the structure in FILE as SVG or PNG (a 3D one in an axonometric view,\n"
    "--view): a title with the plan's status (or, without a plan, whether the\n"
    "structure stands), bodies coloured and numbered by their removal step when a\n"
    "plan is given (with a legend), bodies that cannot be removed (a plan with\n"
    "status none) hatched red, contact points, and with --forces the certificate\n"
    "forces of the full structure as arrows scaled to the largest.\n"
    "\n"
    "options:\n"
    "  -o, --output OUT      output file (required); .svg or .png picks the format\n"
    "  --format svg|png|html the format, whatever the output's name\n"
    "  --html                the interactive viewer, one self-contained page (also\n"
    "                        chosen by an output name ending in .html; docs/viewer.md)\n"
    "  --plan PLAN.json      colour and number bodies by removal order\n"
    "  --forces              draw the contact forces that hold the structure\n"
    "  --method M            backend for the stability test (default auto)\n"
    "  --time-limit S        limit of the stability test (default 10 s)\n"
    "  --title TEXT          the title line (default: file, bodies, status)\n"
    "  --no-contacts         do not mark contact points\n"
    "  --no-labels           do not write body ids\n"
    "  --width PX            picture width in pixels (default 800; PNG at most 16384)\n"
    "  --height PX           picture height (default: as the drawing needs; a PNG\n"
    "                        stays within 16384 px a side and 64 million pixels)\n"
    "  --view AZ,EL          3D: azimuth and elevation of the view in degrees\n"
    "                        (default 35,25; EL in [-90, 90]; docs/render.md)\n"
    "  --contact-tol T       contact detection tolerance\n"
    "\n"
    "exit: 0 written, 1 --forces given but the structure does not stand, or --html\n"
    "and verify finds the order invalid (page written, the failing step in red),\n"
    "3 --forces given but the test is undecided (1 and 3: written without forces),\n"
    "2 usage or input error (nothing written)\n";

typedef enum Format { FMT_NONE = 0, FMT_SVG, FMT_PNG, FMT_HTML } Format;

/* Formats by name and by the output's extension. */
static const struct {
  const char *name, *ext;
  Format f;
} kFormats[] = {{"svg", ".svg", FMT_SVG},
                {"png", ".png", FMT_PNG},
                {"html", ".html", FMT_HTML},
                {"html", ".htm", FMT_HTML}};
#define NFORMATS ((int)(sizeof kFormats / sizeof kFormats[0]))

typedef struct {
  const char *file, *out, *plan, *title;
  int forces, time_limit_given;
  Format format;
  us_RenderSettings r;
} RenderArgs;

static int size_option(const char *opt, const char *v, double *out) {
  if (cli_parse_double(v, out) || *out < 16 || *out > 100000)
    return cli_fail("render", "%s needs a number of pixels in [16, 100000], got '%s'", opt, v);
  return 0;
}

/* --view AZ,EL: two numbers, the elevation in [-90, 90]. */
static int view_option(const char *v, us_RenderSettings *r) {
  char buf[64];
  const char *comma = strchr(v, ',');
  size_t n = comma ? (size_t)(comma - v) : 0;
  if (comma && n < sizeof buf) memcpy(buf, v, n), buf[n] = 0;
  if (!comma || n >= sizeof buf || cli_parse_double(buf, &r->view_az) ||
      cli_parse_double(comma + 1, &r->view_el) || !(fabs(r->view_az) <= 3600.0) ||
      !(fabs(r->view_el) <= 90.0))
    return cli_fail("render", "--view needs AZ,EL in degrees (azimuth in [-3600, 3600], "
                    "elevation in [-90, 90]), got '%s'", v);
  return 0;
}

static int format_option(const char *v, Format *f) {
  for (int i = 0; i < NFORMATS; i++)
    if (!strcmp(v, kFormats[i].name)) return *f = kFormats[i].f, 0;
  return cli_fail("render", "unknown --format '%s' (svg, png, html)", v);
}

/* Options with a value; 1 when argv[*i] is not one of them. */
static int value_option(int argc, char **argv, int *i, CliCommon *c, RenderArgs *a) {
  const char *o = argv[*i], *v;
  if (strcmp(o, "-o") && strcmp(o, "--output") && strcmp(o, "--plan") && strcmp(o, "--width") &&
      strcmp(o, "--height") && strcmp(o, "--format") && strcmp(o, "--title") &&
      strcmp(o, "--time-limit") && strcmp(o, "--view"))
    return 1;
  if (!(v = cli_value("render", argc, argv, i))) return CLI_EXIT_ERR;
  if (!strcmp(o, "-o") || !strcmp(o, "--output")) a->out = v;
  else if (!strcmp(o, "--plan")) a->plan = v;
  else if (!strcmp(o, "--title")) a->title = v;
  else if (!strcmp(o, "--width")) return size_option(o, v, &a->r.width_px);
  else if (!strcmp(o, "--height")) return size_option(o, v, &a->r.height_px);
  else if (!strcmp(o, "--format")) return format_option(v, &a->format);
  else if (!strcmp(o, "--view")) return view_option(v, &a->r);
  else if (cli_time_limit("render", v, c)) return CLI_EXIT_ERR;
  else a->time_limit_given = 1;
  return 0;
}

static int parse(int argc, char **argv, CliCommon *c, RenderArgs *a) {
  for (int i = 1; i < argc; i++) {
    int r = cli_common_option("render", argc, argv, &i, c);
    if (r < 0) return CLI_EXIT_ERR;
    if (r) continue;
    if (cli_is_help(argv[i])) return fputs(help, stdout), -1;
    if ((r = value_option(argc, argv, &i, c, a)) != 1) {
      if (r) return r;
    } else if (!strcmp(argv[i], "--html")) {
      a->format = FMT_HTML;
    } else if (!strcmp(argv[i], "--forces")) {
      a->forces = 1;
    } else if (!strcmp(argv[i], "--no-contacts")) {
      a->r.show_contacts = 0;
    } else if (!strcmp(argv[i], "--no-labels")) {
      a->r.show_labels = 0;
    } else if (argv[i][0] == '-' && argv[i][1]) {
      return cli_fail("render", "unknown option '%s'", argv[i]);
    } else if (a->file) {
      return cli_fail("render", "more than one FILE given");
    } else {
      a->file = argv[i];
    }
  }
  if (!a->file) return cli_fail("render", "no FILE given (see 'unstack render --help')");
  if (!a->out) return cli_fail("render", "no output given: use -o OUT.svg or -o OUT.png");
  return 0;
}

/* Equal but for ASCII case. */
static int same_ext(const char *a, const char *b) {
  for (; *a && *b; a++, b++)
    if (tolower((unsigned char)*a) != tolower((unsigned char)*b)) return 0;
  return !*a && !*b;
}

/* --format, else the output's extension; no extension (/dev/stdout): SVG. */
static int pick_format(RenderArgs *a) {
  if (a->format) return 0;
  const char *base = strrchr(a->out, '/'), *dot = strrchr(base ? base : a->out, '.');
  if (!dot) return a->format = FMT_SVG, 0;
  for (int i = 0; i < NFORMATS; i++)
    if (same_ext(dot, kFormats[i].ext)) return a->format = kFormats[i].f, 0;
  return cli_fail("render", "cannot tell the picture format from '%s': name it .svg, .png or "
                  ".html, or give --format svg|png|html", a->out);
}

/* Test the full structure, within --time-limit or 10 s: 0 done
 * (res->verdict), -1 error. */
static int full_test(const us_Structure *s, const RenderArgs *a, const CliCommon *c,
                     us_StabilityResult *res, us_Error *err) {
  us_StabilitySettings set = c->stab;
  if (!a->time_limit_given) set.time_limit = 10.0;
  us_Stability *w = us_stability_new(s, &set, err);
  int r = w && us_stability_test_full(w, res, err) == US_OK ? 0 : -1;
  us_stability_free(w);
  return r;
}

/* "pyramid.json — 91 bodies, plan found, 91 steps" */
static void make_title(char *buf, size_t n, const RenderArgs *a, const us_Structure *s,
                       const us_PlanFile *pf, const us_StabilityResult *res) {
  const char *base = strrchr(a->file, '/');
  char what[96];
  if (a->plan && pf->status == US_PLAN_FOUND)
    snprintf(what, sizeof what, "plan found, %d steps", pf->ngroups);
  else if (a->plan && pf->status == US_PLAN_NONE)
    snprintf(what, sizeof what, "plan status none, %d bodies cannot be removed", pf->nblocked);
  else if (a->plan)
    snprintf(what, sizeof what, "plan status %s", us_plan_status_name(pf->status));
  else
    snprintf(what, sizeof what, "%s", res->verdict == US_STABLE     ? "stands"
                                      : res->verdict == US_UNSTABLE ? "does not stand"
                                                                    : "stability undecided");
  snprintf(buf, n, "%s \xE2\x80\x94 %d bodies, %s", base ? base + 1 : a->file, s->nbody, what);
}

/* The format's writer; an exit code. */
static int write_output(const RenderArgs *a, const us_Structure *s, const us_PlanFile *pf,
                        CliCommon *c, us_Error *err) {
  us_Status st;
  switch (a->format) {
  case FMT_HTML: return cli_render_html(s, a->plan, pf, c, &a->r, a->file, a->out, err);
  case FMT_PNG: st = us_render_png(s, &a->r, a->out, err); break;
  default: st = us_render_svg(s, &a->r, a->out, err); break;
  }
  return st ? CLI_EXIT_ERR : CLI_EXIT_OK;
}

/* Settings from the plan, forces and title; then the output. */
static int draw(RenderArgs *a, const us_Structure *s, const us_PlanFile *pf,
                const us_StabilityResult *res, CliCommon *c, us_Error *err) {
  char title[512];
  make_title(title, sizeof title, a, s, pf, res);
  a->r.order = pf->order;
  a->r.norder = pf->n;
  a->r.group_start = pf->ngroups != pf->n ? pf->group_start : NULL;
  a->r.ngroups = pf->ngroups;
  a->r.blocked = pf->blocked;
  a->r.nblocked = pf->nblocked;
  a->r.forces = a->forces && res->verdict == US_STABLE ? &res->forces : NULL;
  a->r.title = a->title ? a->title : title;
  return write_output(a, s, pf, c, err);
}

/* Exit code once the picture is written: --forces that could not be drawn. */
static int forces_outcome(const RenderArgs *a, const us_StabilityResult *res) {
  if (!a->forces || res->verdict == US_STABLE) return CLI_EXIT_OK;
  if (res->verdict == US_UNSTABLE) {
    fprintf(stderr, "unstack render: the structure does not stand: no forces drawn\n");
    return CLI_EXIT_NO;
  }
  fprintf(stderr, "unstack render: stability undecided (%s): no forces drawn\n", res->note);
  return CLI_EXIT_UNDECIDED;
}

int cmd_render(int argc, char **argv) {
  CliCommon c;
  cli_common_init(&c);
  RenderArgs a;
  memset(&a, 0, sizeof a);
  a.r = us_render_default_settings();
  int r = parse(argc, argv, &c, &a);
  if (r) return r < 0 ? CLI_EXIT_OK : r;
  const char *inputs[2] = {a.file, a.plan};
  if (cli_check_output("render", a.out, inputs, a.plan ? 2 : 1)) return CLI_EXIT_ERR;
  if (pick_format(&a)) return CLI_EXIT_ERR;
  int load;
  us_Structure *s = cli_load("render", a.file, &c, c.stab.time_limit, &load);
  if (!s) return load;
  us_Error err;
  us_error_clear(&err);
  us_PlanFile pf;
  memset(&pf, 0, sizeof pf);
  us_StabilityResult res;
  us_stability_result_init(&res);
  res.verdict = US_UNDECIDED;
  int code = CLI_EXIT_OK;
  if (a.plan && us_plan_read(s, a.plan, &pf, &err)) code = CLI_EXIT_ERR;
  int verdict_needed = a.forces || (!a.plan && a.format != FMT_HTML);
  if (!code && verdict_needed && full_test(s, &a, &c, &res, &err)) code = CLI_EXIT_ERR;
  if (!code) code = draw(&a, s, &pf, &res, &c, &err);
  if (code == CLI_EXIT_ERR) cli_error("render", &err);
  else if (code == CLI_EXIT_OK) code = forces_outcome(&a, &res);
  us_stability_result_free(&res);
  us_plan_file_free(&pf);
  us_structure_free(s);
  return code;
}
