/* unstack: command-line entry point; dispatches to one file per subcommand. */
#include "batch.h"
#include "cli.h"
#include "options.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The top-level help; generate's kinds come from its table. */
static void usage(FILE *f) {
  fputs("usage: unstack COMMAND [options]\n"
        "\n"
        "Plan how to take a structure of rigid blocks apart so that it never collapses.\n"
        "\n"
        "commands:\n"
        "  check FILE      does the structure stand? (exit 0 stable, 1 unstable)\n"
        "  plan FILE       find a stable unstacking order (exit 0 found, 1 not)\n"
        "  verify FILE PLAN  re-check every step of a plan (exit 0 valid, 1 not)\n"
        "  render FILE     draw the structure (and a plan) as SVG, PNG or an HTML viewer\n"
        "  generate KIND   write a generated structure; KIND:\n                 ", f);
  for (int k = 0, x = 17; strcmp(cli_generator_kind(k), "unknown"); k++) {
    const char *w = cli_generator_kind(k);
    if (k && x + 2 + (int)strlen(w) > 79) fputs(",\n                 ", f), x = 17;
    else if (k) fputs(", ", f), x += 2;
    x += fprintf(f, "%s", w);
  }
  fputs("\n"
        "  count FILE      count the sub-assemblies connected to the ground (exit 0 exact, 1 refused)\n"
        "  classify FILE   stands, friction, top-down, one at a time, smallest group K (exit 0)\n"
        "  import-svg SVG  turn a drawing (Inkscape, Illustrator) into a structure file\n"
        "  import-mesh MESH  turn a mesh (OBJ, STL, PLY, glTF, 3MF, OFF) into a 3D structure\n"
        "  batch INPUTS    plan, check or classify many files: one JSON line each (exit 0 all\n"
        "                  answered, 1 some input failed)\n"
        "\n"
        "Run 'unstack COMMAND --help' for a command's options. Exit code 2: usage or input error.\n",
        f);
}

int main(int argc, char **argv) {
  cli_clock_start();
  static const struct {
    const char *name;
    int (*fn)(int, char **);
  } cmds[] = {{"check", cmd_check}, {"plan", cmd_plan}, {"verify", cmd_verify},
              {"render", cmd_render}, {"generate", cmd_generate},
              {"count", cmd_count}, {"classify", cmd_classify},
              {"import-svg", cmd_import_svg}, {"import-mesh", cmd_import_mesh},
              {"batch", cmd_batch}};
  if (argc < 2) {
    usage(stderr);
    return CLI_EXIT_ERR;
  }
  if (cli_is_help(argv[1])) {
    usage(stdout);
    return CLI_EXIT_OK;
  }
  if (!strcmp(argv[1], "--version")) {
    char mpi[768];
    batch_mpi_version(mpi, sizeof mpi);
    printf("unstack %s\n%s\n", US_VERSION, mpi);
    return CLI_EXIT_OK;
  }
  enum { NCMDS = sizeof cmds / sizeof cmds[0] };
  const char *names[NCMDS];
  for (size_t i = 0; i < NCMDS; i++) {
    if (!strcmp(argv[1], cmds[i].name)) return cmds[i].fn(argc - 1, argv + 1);
    names[i] = cmds[i].name;
  }
  const char *near = cli_nearest(argv[1], names, NCMDS);
  fprintf(stderr, "unstack: unknown command '%s'", argv[1]);
  if (near) fprintf(stderr, " (did you mean '%s'?)", near);
  fputs("\n\n", stderr);
  usage(stderr);
  return CLI_EXIT_ERR;
}
