/* The cores of plan, check and classify, shared by the single commands and
 * by `unstack batch` (tools/cmd_batch.c): each command's option table, a
 * quiet structure loader, and the step from a loaded structure and settings
 * to the result and its exit code. Both callers go through these, so a
 * batch line's status is the single command's by construction. */
#ifndef US_CLI_TASK_H
#define US_CLI_TASK_H

#include "options.h"

/* The longest option table of the three, CLI_END included. */
#define CLI_TABLE_MAX 32

typedef struct PlanArgs {
  const char *file, *out;
  int stats, print;
} PlanArgs;

typedef struct CheckArgs {
  const char *file;
  int forces, stats;
} CheckArgs;

typedef struct ClassifyArgs {
  CliCommon common;
  us_ClassifySettings set;
  const char *file;
  int json;
} ClassifyArgs;

/* Each command's option table, copied into out[CLI_TABLE_MAX] (the
 * entries point into c and a). */
void cli_plan_table(CliCommon *c, PlanArgs *a, CliOpt *out);
void cli_check_table(CliCommon *c, CheckArgs *a, CliOpt *out);
void cli_classify_table(ClassifyArgs *a, CliOpt *out);

/* Read and finalize a structure by the command's settings, loading cut at
 * `deadline` (us_now() time, 0: none); NULL with err set, printing
 * nothing (err->code US_ERR_TIME_LIMIT: cut, an outcome). */
us_Structure *cli_load_quiet(const char *path, const CliCommon *c, double deadline, us_Error *err);

/* plan: the settings the options give, `time_limit` seconds (<= 0: none)
 * for the search; exit code of a plan's status. */
us_Status cli_plan_run(const us_Structure *s, const CliCommon *c, double time_limit, us_Plan *p,
                       us_Error *err);
int cli_plan_exit(const us_Plan *p);

/* check: one full stability test; what it cost comes back in out. */
typedef struct CliCheckOutcome {
  us_StabilityResult res;
  us_StabilityInfo info;
  double t_setup, t_test;
} CliCheckOutcome;
us_Status cli_check_run(const us_Structure *s, const CliCommon *c, double time_limit,
                        CliCheckOutcome *out, us_Error *err);
int cli_check_exit(us_Verdict v);

/* classify: the classes by the settings a->set (with its stability). */
us_Status cli_classify_run(const us_Structure *s, const ClassifyArgs *a, us_Classification *c,
                           us_Error *err);
int cli_classify_exit(const us_Classification *c);

#endif
