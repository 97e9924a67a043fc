/* unstack: command-line entry point; dispatches to one file per subcommand. */
#include "cli.h"
#include "options.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char usage[] =
    "usage: unstack COMMAND [options]\n"
    "\n"
    "Plan how to take a structure of rigid blocks apart so that it never collapses.\n"
    "\n"
    "commands:\n"
    "  check FILE      does the structure stand? (exit 0 stable, 1 unstable)\n"
    "  plan FILE       find a stable unstacking order (exit 0 found, 1 not)\n"
    "  verify FILE PLAN  re-check every step of a plan (exit 0 valid, 1 not)\n"
    "  render FILE     draw the structure (and a plan) as SVG\n"
    "  generate KIND   write a generated structure (column, pyramid, wall, arch, random)\n"
    "  count FILE      count the sub-assemblies connected to the ground (exit 0 exact, 1 refused)\n"
    "  classify FILE   stands, friction, top-down, one at a time, smallest group K (exit 0)\n"
    "  import-svg SVG  turn a drawing (Inkscape, Illustrator) into a structure file\n"
    "\n"
    "Run 'unstack COMMAND --help' for a command's options. Exit code 2: usage or input error.\n";

int main(int argc, char **argv) {
  cli_clock_start();
  static const struct {
    const char *name;
    int (*fn)(int, char **);
  } cmds[] = {{"check", cmd_check}, {"plan", cmd_plan}, {"verify", cmd_verify},
              {"render", cmd_render}, {"generate", cmd_generate},
              {"count", cmd_count}, {"classify", cmd_classify},
              {"import-svg", cmd_import_svg}};
  if (argc < 2) {
    fputs(usage, stderr);
    return CLI_EXIT_ERR;
  }
  if (cli_is_help(argv[1])) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (!strcmp(argv[1], "--version")) {
    printf("unstack %s\n", US_VERSION);
    return CLI_EXIT_OK;
  }
  for (size_t i = 0; i < sizeof cmds / sizeof cmds[0]; i++)
    if (!strcmp(argv[1], cmds[i].name)) return cmds[i].fn(argc - 1, argv + 1);
  fprintf(stderr, "unstack: unknown command '%s'\n\n%s", argv[1], usage);
  return CLI_EXIT_ERR;
}
