/* unstack: command-line entry point; dispatches to one file per subcommand. */
#define _POSIX_C_SOURCE 200809L /* setenv */
#include "batch.h"
#include "cli.h"
#include "options.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

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

/* Process-wide settings that only the program may choose (a library must
 * not write the environment or the allocator's policy; docs/local.md,
 * "Process settings", has the figures):
 * - OpenBLAS (CLP's LAPACK on Debian) starts a thread per core when it is
 *   loaded, each spinning on sched_yield before it sleeps, for LPs far too
 *   small to share; asked for one before any module is loaded, it never
 *   makes them (src/module/clp.c asks again once loaded, for library
 *   users). A user's own choice of threads is kept.
 * - glibc gives the top of its heap back to the kernel whenever 128 KB of
 *   it is free, and every LP allocates and frees its work arrays: a plan
 *   of a 876-block stack made 7,800 brk calls and 250,000 page faults,
 *   a third of its time in the kernel. Kept, the heap is reused; its peak
 *   is unchanged. A user's GLIBC_TUNABLES wins. */
static void process_settings(void) {
  if (!getenv("OPENBLAS_NUM_THREADS") && !getenv("GOTO_NUM_THREADS") && !getenv("OMP_NUM_THREADS"))
    setenv("OPENBLAS_NUM_THREADS", "1", 0);
#ifdef __GLIBC__
  if (!getenv("GLIBC_TUNABLES")) {
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
    mallopt(M_TOP_PAD, 16 << 20);
  }
#endif
}

int main(int argc, char **argv) {
  cli_clock_start();
  process_settings();
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
