/* What the subcommands share: the common option-table entries (method,
 * local, search, order, direction, contact tolerance, time limit, stats),
 * the progress line, statistics lines, and structure loading with error
 * reporting. */
#ifndef US_CLI_OPTIONS_H
#define US_CLI_OPTIONS_H

#include "cli.h"
#include "optable.h"

/* The progress line's state (cli_progress_on): what the command knows of
 * the whole job, so the line can show a total and a percentage. */
typedef enum CliProgressMode {
  CLI_PROGRESS_BUILD,  /* bodies reached by a search that builds up (the most tested) */
  CLI_PROGRESS_REMOVE, /* bodies removed by a search that takes apart (fewest left) */
  CLI_PROGRESS_STEPS   /* tests of a fixed list of steps (verify: one per step) */
} CliProgressMode;

typedef struct CliProgress {
  const char *cmd;
  CliProgressMode mode;
  int total;  /* movable bodies, or steps for CLI_PROGRESS_STEPS */
  int reached; /* bodies built or removed so far: only grows */
} CliProgress;

typedef struct CliCommon {
  us_StabilitySettings stab;
  us_PlanSettings plan;
  double contact_tol; /* 0: derived */
  CliProgress progress;
} CliCommon;

void cli_common_init(CliCommon *c);
const char *cli_method_word(int i);
/* A progress line on stderr while the workspace tests, only when stderr
 * is a terminal: "plan: 45/91 bodies reached (49%), 1234 tests, ..." with
 * `total` bodies (or steps); _off clears it. */
void cli_progress_on(const char *cmd, CliCommon *c, CliProgressMode mode, int total);
void cli_progress_off(const CliCommon *c);
/* The line itself, for a progress report p (the callback's body). */
void cli_progress_line(char *buf, size_t n, const CliProgress *pr, const us_Progress *p);
/* --time-limit counts from the command's start (reading the file and
 * finding contacts included): main calls cli_clock_start first, and a
 * command hands the library cli_time_left(limit), the part left (at least
 * 1 ms; limit itself when <= 0). */
void cli_clock_start(void);
double cli_time_left(double limit);
double cli_elapsed(void); /* seconds since cli_clock_start */
/* The local-test statistics lines of --stats (nothing when none ran). */
void cli_print_local_stats(const us_StabilityInfo *in);
/* The solver lines of --stats: pivots, fallbacks, reuse, cone Lemke. */
void cli_print_solver_stats(const us_StabilityInfo *in);
const char *cli_search_word(int i);
const char *cli_order_word(int i);
const char *cli_direction_word(int i);
const char *cli_removal_word(int i);
const char *cli_count_method_word(int i);

/* Enum values for the option tables (optable.h): name -> *(enum *)dst. */
int cli_parse_method(const char *v, void *dst);
int cli_parse_search(const char *v, void *dst);
int cli_parse_order(const char *v, void *dst);
int cli_parse_direction(const char *v, void *dst);
int cli_parse_removal(const char *v, void *dst);
int cli_parse_count_method(const char *v, void *dst);
int cli_set_local(const char *v, void *dst, const char *cmd); /* on|off -> 1 or -1 */

/* Table entries shared by the commands (optable.h): one line in a table. */
#define CLI_OPT_METHOD(c)                                                                      \
  CLI_ENUM("--method", "M", &(c)->stab.method,                                                 \
           "auto (default), lp (CLP), lpsolve, lcp, lcp-reuse, lp-lcp", .parse = cli_parse_method, \
           .word = cli_method_word, .what = "method")
#define CLI_OPT_LOCAL(c)                                                                       \
  CLI_CALL("--local", "on|off", &(c)->stab.local, cli_set_local,                               \
           "exact local tests for lp and auto (default on)")
#define CLI_OPT_CONTACT_TOL(c)                                                                 \
  CLI_REAL("--contact-tol", "T", &(c)->contact_tol,                                            \
           "one contact detection tolerance for every pair (default: per pair, 1e-6 x the "    \
           "smaller body's size)", CLI_POSITIVE,                                               \
           .need = "a positive number")
#define CLI_OPT_SEARCH(c)                                                                      \
  CLI_ENUM("--search", "S", &(c)->plan.search,                                                 \
           "assemble (default): greedy assembly from the ground (at most n(n+1)/2 tests when " \
           "it places every body); where it is stuck, an exact decision over connected "       \
           "sub-assemblies (docs/planning.md, Theorem 2; at most --exact-tests tests) makes "   \
           "'none' a proof; dfs, bfs: the source's searches of the disassembly graph; random: " \
           "DFS with random order and restarts (--seed)",                                       \
           .parse = cli_parse_search, .word = cli_search_word, .what = "search")
#define CLI_OPT_ORDER(c)                                                                       \
  CLI_ENUM("--order", "O", &(c)->plan.order, "graph searches: highest (default), lowest, input", \
           .parse = cli_parse_order, .word = cli_order_word, .what = "order")
#define CLI_OPT_DIRECTION(c)                                                                   \
  CLI_ENUM("--direction", "D", &(c)->plan.direction,                                           \
           "graph searches: down (disassembly, default) or up (assembly; the plan is its "     \
           "reverse)",                                                                          \
           .parse = cli_parse_direction, .word = cli_direction_word, .what = "direction")
/* --time-limit S > 0 into *dst, with the command's words on what stops. */
#define CLI_OPT_TIME_LIMIT(dst, help, ...)                                                     \
  CLI_REAL("--time-limit", "S", dst, help, CLI_POSITIVE,                                       \
           .need = "a positive number of seconds", __VA_ARGS__)
#define CLI_OPT_STATS(dst, help) CLI_FLAG("--stats", dst, help)

/* generate's kinds, from its table (cmd_generate.c): kind i, "unknown" past
 * the end (the top-level help lists them). */
const char *cli_generator_kind(int i);

/* Read and finalize a structure; prints the error and returns NULL. */
us_Structure *cli_load(const char *cmd, const char *path, const CliCommon *c);

/* Read the plan file `plan` for the structure s read from `file`
 * (cmd_verify.c): 0, or -1 with err set; another structure's plan (its
 * fingerprint) is refused naming both files; a plan without a fingerprint
 * is read with a note on stderr. */
int cli_read_plan(const char *cmd, const us_Structure *s, const char *file, const char *plan,
                  us_PlanFile *pf, us_Error *err);

/* Verify a found plan's order as `unstack verify` does, with the progress
 * line (cmd_verify.c; render and render --html): 1 the order is invalid,
 * 0 valid or undecided (rep says which), -1 error (err set). */
int cli_verify_plan(const us_Structure *s, const us_PlanFile *pf, CliCommon *c,
                    us_VerifyReport *rep, us_Error *err);

/* render --html (cmd_render_html.c): does the output name end in .html or
 * .htm; the viewer page of s with the plan file `plan` (NULL: none) read
 * into pf, its certificates and a verification. Exit code; err set when
 * CLI_EXIT_ERR. */
int cli_html_name(const char *out);
int cli_render_html(const us_Structure *s, const char *plan, const us_PlanFile *pf, CliCommon *c,
                    const us_RenderSettings *r, const char *file, const char *out, us_Error *err);

#endif
