/* unstack batch's pieces (docs/batch.md): the parsed command (one task and
 * its settings, the inputs, the output), what one input gives (a JSON line,
 * batch_run.c), the ordered output with --resume (batch_out.c), and the run
 * over MPI ranks (batch_mpi.c). */
#ifndef US_CLI_BATCH_H
#define US_CLI_BATCH_H

#include "task.h"

typedef enum BatchTask { BATCH_PLAN, BATCH_CHECK, BATCH_CLASSIFY } BatchTask;

/* The command, read-only once parsed: every worker thread or rank reads
 * it and nothing writes it. */
typedef struct Batch {
  BatchTask task;
  CliCommon common;     /* plan and check settings */
  PlanArgs plan_args;
  CheckArgs check_args;
  ClassifyArgs classify; /* classify settings (its own CliCommon inside) */
  double time_limit;    /* per input, from its start, loading included (<= 0: none) */
  long jobs;            /* worker threads */
  int resume;
  const char *out;
} Batch;

const char *batch_task_name(BatchTask t);

/* One JSON line built in place (batch_json.c): jl_open, then jl_key and a
 * value in turn (jl_raw for brackets, commas and literals), then jl_close
 * for the malloc'd line with "}\n" (NULL when out of memory). */
typedef struct JLine {
  char *s;
  size_t len, cap;
  int oom;
} JLine;
void jl_open(JLine *l);
void jl_key(JLine *l, const char *key);
void jl_str(JLine *l, const char *text);
void jl_int(JLine *l, long long v);
void jl_real(JLine *l, double x);
void jl_raw(JLine *l, const char *text);
char *jl_close(JLine *l);

/* One input's JSON line, newline included (malloc'd; NULL only when out of
 * memory). *failed is set when the line is an error line. */
char *batch_run_one(const Batch *b, const char *path, int *failed);

/* The output: lines are handed in by input index in any order and written
 * in input order, each whole line with one write(2) on a file opened for
 * appending; fsync every BATCH_SYNC_LINES lines and at the end. Not
 * thread-safe: callers hold their own lock. */
#define BATCH_SYNC_LINES 1000
typedef struct BatchSink {
  int fd;               /* -1: not open */
  int n, next;          /* inputs, next index to write */
  char **line;          /* [n] lines waiting for their turn */
  const unsigned char *skip; /* [n] inputs already answered (--resume), or NULL */
  long unsynced, written, failed, todo;
  int write_error;      /* errno of the first failed write, 0 */
  int tty;              /* progress line on stderr */
  double t0, shown;
} BatchSink;

/* Open OUT (truncated, or appended to with resume) for n inputs. 0, or
 * the message printed and CLI_EXIT_ERR. */
int batch_sink_open(BatchSink *k, const char *out, int resume, int n, const unsigned char *skip);
/* Hand in input i's line (taken over); writes every line now due. */
void batch_sink_put(BatchSink *k, int i, char *line, int failed);
/* Flush, fsync, close; 0 or the message printed and CLI_EXIT_ERR. */
int batch_sink_close(BatchSink *k);

/* The inputs named on the command line, expanded: a file as given, a
 * directory's *.json files (sorted by name), '-' the paths on stdin (one a
 * line). *out is malloc'd strings; 0, or the message printed and
 * CLI_EXIT_ERR. */
int batch_inputs(char *const *raw, int nraw, char ***out, int *n);
void batch_inputs_free(char **v, int n);
/* Everything before the work: expand the inputs, check OUT is none of
 * them, scan it with --resume, open it. 0, or the message printed and
 * CLI_EXIT_ERR (OUT then untouched). *skip is malloc'd. */
int batch_prepare(const Batch *b, char *const *raw, int nraw, char ***inputs, int *n,
                  unsigned char **skip, BatchSink *k);

/* --resume: the inputs already answered in OUT (skip[i] = 1), after
 * cutting a last line left incomplete by a killed run. A missing OUT
 * answers nothing. 0, or the message printed and CLI_EXIT_ERR. */
int batch_resume_scan(const char *out, char *const *inputs, int n, unsigned char *skip);

/* Under mpirun (or srun) with more than one rank: how many, else 0. */
int batch_mpi_ranks(void);
/* The run over MPI ranks: rank 0 hands out inputs one at a time to the
 * ranks that ask and writes OUT in input order; the others work. Exit code
 * (rank 0: as a local run; other ranks 0). raw: the command line's
 * inputs, expanded by rank 0 only (stdin is rank 0's). */
int batch_mpi_run(const Batch *b, char *const *raw, int nraw);
/* "mpi: ..." for --version: the module and the MPI library, or why not. */
void batch_mpi_version(char *buf, size_t n);

#endif
