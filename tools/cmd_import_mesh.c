/* unstack import-mesh: a mesh file (OBJ, STL, PLY, glTF, 3MF, OFF, ...
 * read by Assimp) -> a 3D structure file (docs/mesh.md). */
#include "options.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const char head[] =
    "usage: unstack import-mesh MESH -o FILE.json [options]\n"
    "\n"
    "Turn a mesh file (OBJ, STL ASCII or binary, PLY, glTF/GLB, 3MF, OFF and what\n"
    "else Assimp reads) into a 3D structure: one body per named object (OBJ o, with\n"
    "its g groups; a glTF or 3MF node), one per connected shell where the file names\n"
    "none (STL, PLY, OFF). Each shell must be closed and convex; a named object of\n"
    "several convex shells becomes one compound body. The ground is the plane\n"
    "through the lowest point. Ids are the objects' names, made valid and unique\n"
    "(repeats become NAME-2, NAME-3; an unnamed file's shells NAME-1, NAME-2, ...\n"
    "after the STL solid's name, else the file's name without its extension).\n"
    "See docs/mesh.md.\n";
static const char tail[] =
    "exit: 0 written, 2 usage or input error (nothing written; the message names\n"
    "the file and the object), 3 cut by --time-limit (nothing written)\n";

typedef struct MeshArgs {
  const char *file, *out, *up;
  double time_limit;
  int no_ground;
} MeshArgs;

/* The command line, by import-mesh's option table (optable.h). */
static int parse(int argc, char **argv, us_MeshSettings *s, MeshArgs *a) {
  /* One entry per option, in --help's order; optable.h says how to add one. */
  const CliOpt opts[] = {
      CLI_TEXT("--output", "FILE", &a->out, "structure file to write (required)", .alias = "-o"),
      CLI_TEXT("--up", "z|y", &a->up, "the file's up axis (default z); y-up files (glTF, many "
               "OBJ exports) are turned so that y becomes z"),
      CLI_REAL("--scale", "S", &s->scale, "lengths multiplied by S (default 1)", CLI_POSITIVE,
               .need = "a positive number"),
      CLI_REAL("--friction", "MU", &s->friction, "Coulomb coefficient of every contact "
               "(default 0.5; 'infinite': no sliding)", CLI_ATLEAST(0), .inf_ok = 1,
               .need = "a number >= 0"),
      CLI_REAL("--density", "RHO", &s->density, "every body's density (default 1)",
               CLI_POSITIVE, .need = "a positive number"),
      CLI_TEXT("--fixed", "PATTERN", &s->fixed, "bodies whose ids match the shell pattern "
               "(fnmatch: *, ?, [...]) are fixed, e.g. --fixed 'ground*'"),
      CLI_FLAG("--no-ground", &a->no_ground, "no ground: fixed bodies must hold the structure"),
      CLI_REAL("--contact-tol", "T", &s->contact_tol, "one contact detection tolerance for "
               "every pair (default: per pair, 1e-6 x the smaller body's size)", CLI_POSITIVE,
               .need = "a positive number"),
      CLI_OPT_TIME_LIMIT(&a->time_limit, "stop after S seconds (reading, checks and contacts); "
                         "exit 3, nothing written"),
      CLI_END};
  const CliSpec spec = {"import-mesh", head, tail, opts, &a->file, 1, "more than one MESH given"};
  int r = cli_parse(&spec, argc, argv);
  if (r) return r;
  if (!a->file) return cli_fail("import-mesh", "no MESH given (see 'unstack import-mesh --help')");
  if (!a->out) return cli_fail("import-mesh", "no output given: use -o FILE");
  if (strcmp(a->up, "z") && strcmp(a->up, "y"))
    return cli_fail("import-mesh", "--up needs z or y");
  s->up = a->up[0];
  s->ground = !a->no_ground;
  return 0;
}

static void report(const char *out, const us_Structure *s, const us_MeshInfo *in) {
  printf("wrote %s: %d bodies (%d fixed, %d compound), %d shells, %d contacts; "
         "%ld faces read, %d ids renamed\n",
         out, in->bodies, in->fixed, in->compounds, in->shells, s->ncontact, in->faces,
         in->ids_renamed);
}

int cmd_import_mesh(int argc, char **argv) {
  us_MeshSettings set = us_mesh_default_settings();
  MeshArgs a = {NULL, NULL, "z", 0, 0};
  int r = parse(argc, argv, &set, &a);
  if (r) return r < 0 ? CLI_EXIT_OK : r;
  const char *inputs[] = {a.file};
  if (cli_check_output("import-mesh", a.out, inputs, 1)) return CLI_EXIT_ERR;
  set.deadline = cli_deadline(a.time_limit);
  us_Error err;
  us_error_clear(&err);
  us_MeshInfo info;
  us_Structure *s = us_structure_read_mesh(a.file, &set, &info, &err);
  if (!s && err.code == US_ERR_TIME_LIMIT) { /* an outcome: nothing decided, nothing written */
    printf("undecided: the import was cut by the time limit (--time-limit %g): %s\n",
           a.time_limit, err.msg);
    return CLI_EXIT_UNDECIDED;
  }
  if (!s || us_structure_write(s, a.out, &err)) {
    us_structure_free(s);
    return cli_error("import-mesh", &err);
  }
  report(a.out, s, &info);
  us_structure_free(s);
  return CLI_EXIT_OK;
}
