/* unstack import-svg: a drawing (SVG from Inkscape, Illustrator, ...) ->
 * a structure file (docs/svg.md). */
#include "options.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const char head[] =
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
    "See docs/svg.md.\n";
static const char tail[] =
    "exit: 0 written, 2 usage or input error (nothing written; the message names\n"
    "the file, the line and the element)\n";

static void print_warning(const char *msg, void *user) {
  (void)user;
  fprintf(stderr, "unstack import-svg: warning: %s\n", msg);
}

typedef struct SvgArgs {
  const char *file, *out;
  int quiet;
} SvgArgs;

/* The command line, by import-svg's option table (optable.h). */
static int parse(int argc, char **argv, us_SvgSettings *s, SvgArgs *a) {
  /* One entry per option, in --help's order; optable.h says how to add one. */
  const CliOpt opts[] = {
      CLI_TEXT("--output", "FILE", &a->out, "structure file to write (required)", .alias = "-o"),
      CLI_TEXT("--unit", "U", &s->unit, "output length unit: m (default), cm, mm, in, pt, pc, "
               "px, or user (the drawing's viewBox units as they are)"),
      CLI_REAL("--scale", "F", &s->scale, "the drawing is at 1:F: lengths multiplied by F "
               "(default 1)"),
      CLI_REAL("--ground-at", "Y", &s->ground_at, "the ground is the drawing's line y = Y "
               "(viewBox units, y down as in the file); default: the lowest point",
               .given = &s->ground_at_set),
      CLI_FLAG_VAL("--no-ground", &s->ground, 0, "no ground: fixed blocks must hold the "
                   "structure"),
      CLI_REAL("--snap", "TOL", &s->snap, "move vertices within TOL (viewBox units) of another "
               "block or the ground onto it; default: 1e-3 of the pair's smaller block size; 0: "
               "off"),
      CLI_REAL("--flatten", "R", &s->flatten, "curves: polyline within R x the curve's size "
               "(default 1e-3)"),
      CLI_REAL("--friction", "MU", &s->friction, "default Coulomb coefficient (default: the "
               "root's data-friction, else 0.5; 'infinite': no sliding)", .inf_ok = 1),
      CLI_REAL("--contact-tol", "T", &s->contact_tol, "one contact detection tolerance for every "
               "pair (default: per pair, 1e-6 x the smaller body's size)"),
      CLI_FLAG("--quiet", &a->quiet, "no warnings about skipped elements", .alias = "-q"),
      CLI_END};
  const CliSpec spec = {"import-svg", head, tail, opts, &a->file, 1, "more than one DRAWING given"};
  int r = cli_parse(&spec, argc, argv);
  if (r) return r;
  if (!a->file) return cli_fail("import-svg", "no DRAWING given (see 'unstack import-svg --help')");
  if (!a->out) return cli_fail("import-svg", "no output given: use -o FILE");
  return 0;
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
  SvgArgs a = {NULL, NULL, 0};
  int r = parse(argc, argv, &set, &a);
  if (r) return r < 0 ? CLI_EXIT_OK : r;
  const char *file = a.file, *out = a.out;
  if (check_values(&set)) return CLI_EXIT_ERR;
  const char *inputs[] = {file};
  if (cli_check_output("import-svg", out, inputs, 1)) return CLI_EXIT_ERR;
  set.warn = a.quiet ? NULL : print_warning;
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
