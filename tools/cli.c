/* The tool's shared helpers (cli.h): messages, exit codes for errors, the
 * output check and strict number parsing, used by every subcommand file
 * and by options.c, so they sit below all of them. */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cli_fail(const char *cmd, const char *fmt, ...) {
  fprintf(stderr, "unstack %s: ", cmd);
  va_list ap;
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fputc('\n', stderr);
  return CLI_EXIT_ERR;
}

void cli_error_text(char *buf, size_t n, const char *cmd, const us_Error *err) {
  snprintf(buf, n, "unstack %s: %s: %s", cmd, us_status_name(err->code), err->msg);
}

int cli_error(const char *cmd, const us_Error *err) {
  char line[sizeof err->msg + 128];
  cli_error_text(line, sizeof line, cmd, err);
  fprintf(stderr, "%s\n", line);
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
