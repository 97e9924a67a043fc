/* unstack render: draw a structure, optionally with a plan and forces, as SVG. */
#include "options.h"

#include <stdio.h>
#include <string.h>

static const char help[] =
    "usage: unstack render FILE [--plan PLAN.json] [--forces] -o OUT.svg\n"
    "       unstack render FILE [--plan PLAN.json] --html -o OUT.html\n"
    "\n"
    "Draw the structure in FILE as SVG: bodies coloured and numbered by their\n"
    "removal step when a plan is given (with a legend), contact points, and with\n"
    "--forces the certificate forces of the full structure as arrows.\n"
    "\n"
    "options:\n"
    "  -o, --output OUT.svg  output file (required)\n"
    "  --plan PLAN.json      colour and number bodies by removal order\n"
    "  --forces              draw the contact forces that hold the structure\n"
    "  --method M            backend for --forces (default lp)\n"
    "  --no-contacts         do not mark contact points\n"
    "  --no-labels           do not write body ids\n"
    "  --width PX            picture width in pixels (default 800)\n"
    "  --contact-tol T       contact detection tolerance\n"
    "  --html                the interactive viewer, one self-contained page (also\n"
    "                        chosen by an output name ending in .html; docs/viewer.md)\n"
    "\n"
    "exit: 0 written, 1 --forces given but the structure does not stand (picture\n"
    "written without forces), or --html and verify finds the order invalid (page\n"
    "written, the failing step in red), 2 usage or input error (nothing written)\n";

typedef struct {
  const char *file, *out, *plan;
  int forces, html;
  us_RenderSettings r;
} RenderArgs;

static int parse(int argc, char **argv, CliCommon *c, RenderArgs *a) {
  for (int i = 1; i < argc; i++) {
    int r = cli_common_option("render", argc, argv, &i, c);
    const char *v;
    if (r < 0) return CLI_EXIT_ERR;
    if (r) continue;
    if (cli_is_help(argv[i])) return fputs(help, stdout), -1;
    if (!strcmp(argv[i], "-o") || !strcmp(argv[i], "--output")) {
      if (!(a->out = cli_value("render", argc, argv, &i))) return CLI_EXIT_ERR;
    } else if (!strcmp(argv[i], "--plan")) {
      if (!(a->plan = cli_value("render", argc, argv, &i))) return CLI_EXIT_ERR;
    } else if (!strcmp(argv[i], "--html")) {
      a->html = 1;
    } else if (!strcmp(argv[i], "--forces")) {
      a->forces = 1;
    } else if (!strcmp(argv[i], "--no-contacts")) {
      a->r.show_contacts = 0;
    } else if (!strcmp(argv[i], "--no-labels")) {
      a->r.show_labels = 0;
    } else if (!strcmp(argv[i], "--width")) {
      if (!(v = cli_value("render", argc, argv, &i))) return CLI_EXIT_ERR;
      if (cli_parse_double(v, &a->r.width_px) || a->r.width_px < 16 || a->r.width_px > 100000)
        return cli_fail("render", "--width needs a number of pixels in [16, 100000], got '%s'", v);
    } else if (argv[i][0] == '-' && argv[i][1]) {
      return cli_fail("render", "unknown option '%s'", argv[i]);
    } else if (a->file) {
      return cli_fail("render", "more than one FILE given");
    } else {
      a->file = argv[i];
    }
  }
  if (!a->file) return cli_fail("render", "no FILE given (see 'unstack render --help')");
  if (!a->out) return cli_fail("render", "no output given: use -o OUT.svg");
  a->html = a->html || cli_html_name(a->out);
  return 0;
}

/* Forces of the full structure; 1 when it does not stand, -1 on error. */
static int full_forces(const us_Structure *s, const CliCommon *c, us_StabilityResult *res,
                       us_Error *err) {
  us_Stability *w = us_stability_new(s, &c->stab, err);
  int r = -1;
  if (w && us_stability_test_full(w, res, err) == US_OK) r = res->verdict != US_STABLE;
  us_stability_free(w);
  return r;
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
  us_Structure *s = cli_load("render", a.file, &c);
  if (!s) return CLI_EXIT_ERR;
  us_Error err;
  us_error_clear(&err);
  us_PlanFile pf;
  memset(&pf, 0, sizeof pf);
  us_StabilityResult res;
  memset(&res, 0, sizeof res);
  int code = CLI_EXIT_OK, falls = 0;
  if (a.plan && us_plan_read(s, a.plan, &pf, &err)) code = CLI_EXIT_ERR;
  if (code == CLI_EXIT_OK && a.forces && (falls = full_forces(s, &c, &res, &err)) < 0)
    code = CLI_EXIT_ERR;
  if (code == CLI_EXIT_OK) {
    a.r.order = pf.order;
    a.r.norder = pf.n;
    a.r.group_start = pf.ngroups != pf.n ? pf.group_start : NULL;
    a.r.ngroups = pf.ngroups;
    a.r.blocked = pf.blocked;
    a.r.nblocked = pf.nblocked;
    a.r.forces = a.forces && !falls ? &res.forces : NULL;
    if (a.html) code = cli_render_html(s, a.plan, &pf, &c, &a.r, a.file, a.out, &err);
    else if (us_render_svg(s, &a.r, a.out, &err)) code = CLI_EXIT_ERR;
  }
  if (code == CLI_EXIT_ERR) cli_error("render", &err);
  if (code == CLI_EXIT_OK && falls) {
    fprintf(stderr, "unstack render: the structure does not stand: no forces drawn\n");
    code = CLI_EXIT_NO;
  }
  us_stability_result_free(&res);
  us_plan_file_free(&pf);
  us_structure_free(s);
  return code;
}
