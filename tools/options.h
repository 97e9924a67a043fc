/* Options shared by subcommands (method, search, order, direction,
 * contact tolerance) and structure loading with error reporting. */
#ifndef US_CLI_OPTIONS_H
#define US_CLI_OPTIONS_H

#include "cli.h"

typedef struct CliCommon {
  us_StabilitySettings stab;
  us_PlanSettings plan;
  double contact_tol; /* 0: derived */
} CliCommon;

void cli_common_init(CliCommon *c);
/* "unknown WHAT 'VALUE' (w0, w1, ...)" with the words of an enum listed from
 * its name table; returns CLI_EXIT_ERR. */
typedef const char *(*CliWord)(int i);
int cli_unknown(const char *cmd, const char *what, const char *value, CliWord word);
const char *cli_method_word(int i);
/* A progress line on stderr while the workspace tests, only when stderr
 * is a terminal; _off clears it. */
void cli_progress_on(const char *cmd, CliCommon *c);
void cli_progress_off(const CliCommon *c);
/* --time-limit counts from the command's start (reading the file and
 * finding contacts included): main calls cli_clock_start first, and a
 * command hands the library cli_time_left(limit), the part left (at least
 * 1 ms; limit itself when <= 0). */
void cli_clock_start(void);
double cli_time_left(double limit);
/* The us_now() time limit seconds after the start (0 when limit <= 0). */
double cli_deadline(double limit);
/* --time-limit S into c->stab.time_limit; 0, or -1 (message printed). */
int cli_time_limit(const char *cmd, const char *v, CliCommon *c);
/* The local-test statistics lines of --stats (nothing when none ran). */
void cli_print_local_stats(const us_StabilityInfo *in);
const char *cli_search_word(int i);
const char *cli_order_word(int i);
const char *cli_direction_word(int i);
const char *cli_removal_word(int i);
const char *cli_count_method_word(int i);
int cli_common_option(const char *cmd, int argc, char **argv, int *i, CliCommon *c);
/* Read and finalize a structure within time_limit seconds of the
 * command's start (<= 0: no limit). NULL with the message printed and
 * *code CLI_EXIT_UNDECIDED when the limit cut loading, else CLI_EXIT_ERR. */
us_Structure *cli_load(const char *cmd, const char *path, const CliCommon *c, double time_limit,
                       int *code);

/* render --html (cmd_render_html.c): does the output name end in .html or
 * .htm; the viewer page of s with the plan file `plan` (NULL: none) read
 * into pf, its certificates and a verification. Exit code; err set when
 * CLI_EXIT_ERR. */
int cli_html_name(const char *out);
int cli_render_html(const us_Structure *s, const char *plan, const us_PlanFile *pf, CliCommon *c,
                    const us_RenderSettings *r, const char *file, const char *out, us_Error *err);

#endif
