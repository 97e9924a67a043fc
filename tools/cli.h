/* Shared pieces of the command-line tool: one entry per subcommand, option
 * parsing helpers, exit codes. Exit 0: success (stable / plan found);
 * 1: negative outcome (unstable / no plan / verify failed); 2: usage or
 * input error, with a message on stderr; 3: undecided (the answer depends
 * on a stability test that could not be decided). */
#ifndef US_CLI_H
#define US_CLI_H

#include "unstack/unstack.h"

#define CLI_EXIT_OK 0
#define CLI_EXIT_NO 1
#define CLI_EXIT_ERR 2
#define CLI_EXIT_UNDECIDED 3

int cmd_check(int argc, char **argv);
int cmd_plan(int argc, char **argv);
int cmd_verify(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_generate(int argc, char **argv);
int cmd_count(int argc, char **argv);
int cmd_classify(int argc, char **argv);
int cmd_import_svg(int argc, char **argv);
int cmd_batch(int argc, char **argv);
int cmd_import_mesh(int argc, char **argv);

/* Print "unstack CMD: message" to stderr and return CLI_EXIT_ERR. */
int cli_fail(const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
int cli_error(const char *cmd, const us_Error *err); /* exit code for err */
/* The line cli_error prints for err, without the newline (batch lines). */
void cli_error_text(char *buf, size_t n, const char *cmd, const us_Error *err);
/* Before any work: can `out` be written, and is it none of the inputs?
 * 0, or the message printed and CLI_EXIT_ERR. */
int cli_check_output(const char *cmd, const char *out, const char *const *inputs, int n);
int cli_is_help(const char *arg);
/* Parse numbers strictly: whole string, finite. 0 ok, -1 bad. */
int cli_parse_double(const char *s, double *out);
int cli_parse_long(const char *s, long *out);
/* Fetch the value of option argv[*i] (advances *i); NULL and message if missing. */
const char *cli_value(const char *cmd, int argc, char **argv, int *i);

#endif
