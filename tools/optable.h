/* Option tables: each command describes its options once, in one array of
 * CliOpt, and that array both parses argv and prints the options part of
 * `--help`, so the help cannot list an option the parser refuses or miss
 * one it accepts.
 *
 * Adding an option is one line in the command's table (see cmd_plan.c):
 *
 *   CLI_REAL("--scale", "F", &set.scale, "lengths multiplied by F (default 1)"),
 *
 * The macros below give the common kinds (flag, integer, real, text, enum
 * word, or a setter function for anything else); range checks and the
 * "needs ..." phrase of the error message are optional fields set with
 * designated initializers, e.g.
 *
 *   CLI_LONG("--max-tests", "N", &n, "stop after N tests", CLI_ATLEAST(1)),
 *   CLI_REAL("--contact-tol", "T", &tol, "contact tolerance", CLI_POSITIVE,
 *            .need = "a positive number"),
 *
 * Any option with a value may also be written "--name=value". A flag
 * that may take a value ("--forces" or "--forces=resultants") is a
 * CLI_CALL with value name NULL and .optional = 1.
 *
 * Options every command shares (--method, --local, --contact-tol, --search,
 * --order, --direction, --time-limit) are the CLI_OPT_* entries of
 * options.h. Help texts are wrapped at 80 columns; a '\n' in one starts a
 * new line, indented under the first. The table ends with CLI_END. */
#ifndef US_CLI_OPTABLE_H
#define US_CLI_OPTABLE_H

#include <stddef.h>
#include <stdio.h>

typedef enum CliKind {
  CLI_K_END = 0,
  CLI_K_FLAG,  /* no value: *(int *)dst = flag */
  CLI_K_INT,   /* integer into an int, in [lo, hi] (hi 0: INT_MAX) */
  CLI_K_LONG,  /* integer into a long, in [lo, hi] (hi 0: LONG_MAX) */
  CLI_K_ULONG, /* integer >= lo into an unsigned long (seeds) */
  CLI_K_REAL,  /* finite number into a double, >= lo (> lo with open), <= hi */
  CLI_K_TEXT,  /* the value itself into a const char * */
  CLI_K_ENUM,  /* a word of a name table, through parse (message lists words) */
  CLI_K_CALL   /* set(value, dst, cmd): anything else; 0 ok, else message printed
                  (value NULL: a flag, or an optional value not given) */
} CliKind;

typedef const char *(*CliWordFn)(int i); /* enum word i, "unknown" past the end */

typedef struct CliOpt {
  const char *name;  /* "--method" */
  const char *alias; /* "-o", or NULL */
  CliKind kind;
  const char *value; /* value name in the help ("M", "on|off"); NULL for flags */
  const char *help;  /* help text; '\n' starts an indented continuation line */
  void *dst;         /* where the value goes */
  int *given;        /* optional: set to 1 when the option is given */
  int flag;          /* CLI_K_FLAG: the value stored */
  int ranged;        /* numbers: lo (and hi when > 0) are checked */
  double lo, hi;     /* the range */
  int open;          /* CLI_K_REAL: lo itself is refused */
  int inf_ok;        /* CLI_K_REAL: the word 'infinite' gives INFINITY */
  const char *need;  /* "needs NEED, got 'v'" (default "a number" or "an integer") */
  int (*parse)(const char *v, void *dst);              /* CLI_K_ENUM: 0 ok */
  CliWordFn word;                                      /* CLI_K_ENUM: its words */
  const char *what;                                    /* CLI_K_ENUM: "method" */
  int (*set)(const char *v, void *dst, const char *cmd); /* CLI_K_CALL */
  int takes_value;   /* CLI_K_CALL: 1 when it takes a value (else a flag) */
  int optional;      /* CLI_K_CALL without a value: "--name=value" may still give
                        one (set gets it, else NULL): --forces[=resultants] */
  const char *next_words; /* optional: "a|b": the next argument is taken as the
                        value when it is one of these words (--forces resultants) */
} CliOpt;

#define CLI_FLAG(n, d, h, ...) {.name = n, .kind = CLI_K_FLAG, .help = h, .dst = d, .flag = 1, __VA_ARGS__}
/* A flag that stores `val` (0: --no-contacts clears show_contacts). */
#define CLI_FLAG_VAL(n, d, val, h, ...) {.name = n, .kind = CLI_K_FLAG, .help = h, .dst = d, .flag = val, __VA_ARGS__}
#define CLI_INT(n, v, d, h, ...) {.name = n, .kind = CLI_K_INT, .value = v, .help = h, .dst = d, __VA_ARGS__}
#define CLI_LONG(n, v, d, h, ...) {.name = n, .kind = CLI_K_LONG, .value = v, .help = h, .dst = d, __VA_ARGS__}
#define CLI_ULONG(n, v, d, h, ...) {.name = n, .kind = CLI_K_ULONG, .value = v, .help = h, .dst = d, __VA_ARGS__}
#define CLI_REAL(n, v, d, h, ...) {.name = n, .kind = CLI_K_REAL, .value = v, .help = h, .dst = d, __VA_ARGS__}
#define CLI_TEXT(n, v, d, h, ...) {.name = n, .kind = CLI_K_TEXT, .value = v, .help = h, .dst = d, __VA_ARGS__}
#define CLI_ENUM(n, v, d, h, ...) {.name = n, .kind = CLI_K_ENUM, .value = v, .help = h, .dst = d, __VA_ARGS__}
#define CLI_CALL(n, v, d, fn, h, ...) \
  {.name = n, .kind = CLI_K_CALL, .value = v, .help = h, .dst = d, .set = fn, .takes_value = (v) != NULL, __VA_ARGS__}
#define CLI_END {.name = NULL}
/* Ranges, inside an entry: CLI_INT(..., CLI_ATLEAST(1)) */
#define CLI_ATLEAST(x) .ranged = 1, .lo = (x)
#define CLI_POSITIVE .ranged = 1, .lo = 0, .open = 1
#define CLI_RANGE(a, b) .ranged = 1, .lo = (a), .hi = (b)

/* A command's command line: its table, the words of its help around the
 * table, and its positional arguments. */
typedef struct CliSpec {
  const char *cmd;      /* "plan" */
  const char *head;     /* help before "options:" (usage line and description) */
  const char *tail;     /* help after the options (exit codes), or NULL */
  const CliOpt *opts;
  const char **pos;     /* positional arguments go here, in order */
  int maxpos;           /* how many there may be */
  const char *too_many; /* message when there are more; NULL: "unknown option 'ARG'" */
} CliSpec;

/* Parse argv[1..argc-1] by the table: 0 parsed; -1 help printed (exit 0);
 * CLI_EXIT_ERR with the message printed (unknown option, with the closest
 * name when one is near; missing or bad value). */
int cli_parse(const CliSpec *spec, int argc, char **argv);
/* The whole help: head, "options:" and the table, tail. */
void cli_print_help(const CliSpec *spec, FILE *f);

/* Did-you-mean: the candidate nearest to `word` by edit distance when it is
 * near (at most a third of the word's length, and at least 1 and at most
 * 3 edits), else NULL. */
const char *cli_nearest(const char *word, const char *const *cands, int n);
/* The same over an enum's name table. */
const char *cli_nearest_word(const char *word, CliWordFn fn);

#endif
