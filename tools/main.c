/* unstack: command-line entry point; dispatches to one file per subcommand. */
#include "cli.h"
#include "options.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
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

int cli_fail(const char *cmd, const char *fmt, ...) {
  fprintf(stderr, "unstack %s: ", cmd);
  va_list ap;
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fputc('\n', stderr);
  return CLI_EXIT_ERR;
}

int cli_error(const char *cmd, const us_Error *err) {
  fprintf(stderr, "unstack %s: %s: %s\n", cmd, us_status_name(err->code), err->msg);
  return CLI_EXIT_ERR;
}

int cli_check_output(const char *cmd, const char *out, const char *const *inputs, int n) {
  us_Error err;
  us_error_clear(&err);
  return us_output_check(out, inputs, n, &err) ? cli_error(cmd, &err) : 0;
}

int cli_is_help(const char *arg) { return !strcmp(arg, "--help") || !strcmp(arg, "-h"); }

int cli_parse_double(const char *s, double *out) {
  char *end;
  errno = 0;
  double v = strtod(s, &end);
  if (end == s || *end || errno || !isfinite(v)) return -1;
  *out = v;
  return 0;
}

int cli_parse_long(const char *s, long *out) {
  char *end;
  errno = 0;
  long v = strtol(s, &end, 10);
  if (end == s || *end || errno) return -1;
  *out = v;
  return 0;
}

const char *cli_value(const char *cmd, int argc, char **argv, int *i) {
  if (*i + 1 >= argc) {
    cli_fail(cmd, "option %s needs a value", argv[*i]);
    return NULL;
  }
  return argv[++*i];
}

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
