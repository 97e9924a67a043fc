/* unstack import-svg: a drawing (SVG from Inkscape, Illustrator, ...) ->
 * a structure file (docs/svg.md). */
#include "options.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const char help[] =
    "usage: unstack import-svg DRAWING.svg -o FILE.json [options]\n"
    "\n"
    "Turn a drawing into a structure: every rect, polygon, closed polyline,\n"
    "closed path, circle and ellipse becomes a block (curves flattened), through\n"
    "groups, transforms, viewBox and units; y is flipped so that up is up, and\n"
    "the drawing's lowest point is on the ground. Text, images, lines, open\n"
    "outlines and hidden elements are skipped with a warning. Blocks are fixed\n"
    "(piers, terrain) with class=\"fixed\", data-fixed=\"true\", an Inkscape label\n"
    "(layer or object) whose first word is 'fixed', or an id 'fixed' (Illustrator's\n"
    "layer; also fixed_1_, fixed-2), on the element or a group around it;\n"
    "data-density, data-mass and data-friction set materials.\n"
    "Ids are kept (repeats become ID-2, ID-3; missing ones rect-1, path-1, ...).\n"
    "See docs/svg.md.\n"
    "\n"
    "options:\n"
    "  -o, --output FILE   structure file to write (required)\n"
    "  --unit U            output length unit: m (default), cm, mm, in, pt, pc, px,\n"
    "                      or user (the drawing's viewBox units as they are)\n"
    "  --scale F           the drawing is at 1:F: lengths multiplied by F (default 1)\n"
    "  --ground-at Y       the ground is the drawing's line y = Y (viewBox units,\n"
    "                      y down as in the file); default: the lowest point\n"
    "  --no-ground         no ground: fixed blocks must hold the structure\n"
    "  --snap TOL          move vertices within TOL (viewBox units) of another\n"
    "                      block or the ground onto it; default: 1e-3 of the\n"
    "                      pair's smaller block size; 0: off\n"
    "  --flatten R         curves: polyline within R x the curve's size (default 1e-3)\n"
    "  --friction MU       default Coulomb coefficient (default: the root's\n"
    "                      data-friction, else 0.5; 'infinite': no sliding)\n"
    "  --contact-tol T     contact detection tolerance (default 1e-6 x size)\n"
    "  -q, --quiet         no warnings about skipped elements\n"
    "\n"
    "exit: 0 written, 2 usage or input error (nothing written; the message names\n"
    "the file, the line and the element)\n";

static void print_warning(const char *msg, void *user) {
  (void)user;
  fprintf(stderr, "unstack import-svg: warning: %s\n", msg);
}

/* A number option: 0, or the message printed and CLI_EXIT_ERR. */
static int number(const char *name, const char *v, double *out, int inf_ok) {
  if (inf_ok && v && !strcmp(v, "infinite")) return *out = INFINITY, 0;
  if (!v) return CLI_EXIT_ERR;
  if (cli_parse_double(v, out)) return cli_fail("import-svg", "%s needs a number, got '%s'", name, v);
  return 0;
}

/* One option at argv[*i]: 0 taken, 1 not an option, CLI_EXIT_ERR. */
static int parse_option(int argc, char **argv, int *i, us_SvgSettings *s, const char **out,
                        int *quiet) {
  const char *a = argv[*i];
  int rc = 0;
  if (!strcmp(a, "-o") || !strcmp(a, "--output")) rc = (*out = cli_value("import-svg", argc, argv, i)) ? 0 : CLI_EXIT_ERR;
  else if (!strcmp(a, "--unit")) rc = (s->unit = cli_value("import-svg", argc, argv, i)) ? 0 : CLI_EXIT_ERR;
  else if (!strcmp(a, "--scale")) rc = number(a, cli_value("import-svg", argc, argv, i), &s->scale, 0);
  else if (!strcmp(a, "--ground-at")) rc = number(a, cli_value("import-svg", argc, argv, i), &s->ground_at, 0), s->ground_at_set = 1;
  else if (!strcmp(a, "--no-ground")) s->ground = 0;
  else if (!strcmp(a, "--snap")) rc = number(a, cli_value("import-svg", argc, argv, i), &s->snap, 0);
  else if (!strcmp(a, "--flatten")) rc = number(a, cli_value("import-svg", argc, argv, i), &s->flatten, 0);
  else if (!strcmp(a, "--friction")) rc = number(a, cli_value("import-svg", argc, argv, i), &s->friction, 1);
  else if (!strcmp(a, "--contact-tol")) rc = number(a, cli_value("import-svg", argc, argv, i), &s->contact_tol, 0);
  else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) *quiet = 1;
  else return 1;
  return rc;
}

/* Options left NAN were not given: the library's defaults. */
static int check_values(us_SvgSettings *s) {
  if (!isnan(s->snap) && s->snap < 0) return cli_fail("import-svg", "--snap needs a distance >= 0");
  if (!isnan(s->friction) && s->friction < 0) return cli_fail("import-svg", "--friction needs a number >= 0");
  if (s->contact_tol < 0) return cli_fail("import-svg", "--contact-tol needs a number >= 0");
  if (isnan(s->snap)) s->snap = -1;
  if (isnan(s->friction)) s->friction = -1;
  return 0;
}

static void report(const char *out, const us_Structure *s, const us_SvgInfo *in) {
  printf("wrote %s: %d bodies (%d fixed), %d contacts; %d vertices snapped, %d curves "
         "flattened, %d elements skipped, %d ids generated, %d renamed; 1 drawing unit = %.6g\n",
         out, in->bodies, in->fixed, s->ncontact, in->snapped, in->curves, in->skipped,
         in->ids_generated, in->ids_renamed, in->unit);
}

int cmd_import_svg(int argc, char **argv) {
  us_SvgSettings set = us_svg_default_settings();
  set.snap = set.friction = NAN; /* not given */
  const char *file = NULL, *out = NULL;
  int quiet = 0;
  for (int i = 1; i < argc; i++) {
    if (cli_is_help(argv[i])) return fputs(help, stdout), CLI_EXIT_OK;
    int r = parse_option(argc, argv, &i, &set, &out, &quiet);
    if (r == CLI_EXIT_ERR) return r;
    if (!r) continue;
    if (argv[i][0] == '-' && argv[i][1]) return cli_fail("import-svg", "unknown option '%s'", argv[i]);
    if (file) return cli_fail("import-svg", "more than one DRAWING given");
    file = argv[i];
  }
  if (!file) return cli_fail("import-svg", "no DRAWING given (see 'unstack import-svg --help')");
  if (!out) return cli_fail("import-svg", "no output given: use -o FILE");
  if (check_values(&set)) return CLI_EXIT_ERR;
  const char *inputs[] = {file};
  if (cli_check_output("import-svg", out, inputs, 1)) return CLI_EXIT_ERR;
  set.warn = quiet ? NULL : print_warning;
  us_Error err;
  us_error_clear(&err);
  us_SvgInfo info;
  us_Structure *s = us_structure_read_svg(file, &set, &info, &err);
  if (!s || us_structure_write(s, out, &err)) {
    us_structure_free(s);
    return cli_error("import-svg", &err);
  }
  report(out, s, &info);
  us_structure_free(s);
  return CLI_EXIT_OK;
}
