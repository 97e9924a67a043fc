/* unstack batch: plan, check or classify many structure files, one JSON
 * line per input in input order, on worker threads of one process or over
 * MPI ranks (docs/batch.md). */
#define _POSIX_C_SOURCE 200809L
#include "batch.h"

#include <jansson.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char head[] =
    "usage: unstack batch INPUTS... -o OUT.jsonl [--jobs N] [--task plan|check|classify]\n"
    "                    [the task's options]\n"
    "\n"
    "Run one task over many structure files and write one JSON line per input\n"
    "to OUT, in input order whatever --jobs: the file as given, the status (plan,\n"
    "classify) or verdict (check) with the single command's exit code, tests,\n"
    "time, and the task's key results (plan: the order, a list of steps of ids).\n"
    "A file the single command refuses gives a line with \"error\", the message\n"
    "that command prints, and the batch goes on. INPUTS: files, directories\n"
    "(their *.json, sorted by name), '-' (paths on stdin, one a line). Under\n"
    "mpirun or srun with several ranks, rank 0 hands out the inputs and writes\n"
    "OUT; the lines are the same (docs/batch.md).\n";
static const char tail[] =
    "exit: 0 every input answered (whatever its status), 1 some input gave an\n"
    "error line (the others are answered), 2 usage error or OUT cannot be\n"
    "written (a usage error writes nothing)\n";

static int set_task(const char *v, void *dst, const char *cmd) {
  for (int t = BATCH_PLAN; t <= BATCH_CLASSIFY; t++)
    if (!strcmp(v, batch_task_name((BatchTask)t))) return *(BatchTask *)dst = (BatchTask)t, 0;
  return cli_fail(cmd, "--task takes plan, check or classify (got '%s')", v);
}

/* --task before the table is built: the task's options join it (a bad
 * word is left to the parser's message). */
static BatchTask find_task(int argc, char **argv) {
  BatchTask t = BATCH_PLAN;
  for (int i = 1; i < argc; i++) {
    const char *v = !strcmp(argv[i], "--task") && i + 1 < argc ? argv[i + 1]
                    : !strncmp(argv[i], "--task=", 7)          ? argv[i] + 7
                                                               : NULL;
    for (int k = BATCH_PLAN; v && k <= BATCH_CLASSIFY; k++)
      if (!strcmp(v, batch_task_name((BatchTask)k))) t = (BatchTask)k;
  }
  return t;
}

/* The single command's options that write its own outputs or bound its
 * own run: batch has its own --output and --time-limit. */
static int left_out(const char *name) {
  static const char *const own[] = {"--output", "--print", "--stats", "--forces", "--json",
                                    "--time-limit"};
  for (size_t k = 0; k < sizeof own / sizeof own[0]; k++)
    if (!strcmp(name, own[k])) return 1;
  return 0;
}

/* The command line: batch's table, then the task's (task.h) less
 * left_out's. Inputs into raw[]. */
static int parse(int argc, char **argv, Batch *b, char **raw, int *nraw) {
  b->task = find_task(argc, argv);
  /* One entry per option, in --help's order; optable.h says how to add one. */
  const CliOpt own[] = {
      CLI_TEXT("--output", "OUT", &b->out, "the JSON lines file (required; '-': stdout)", .alias = "-o"),
      CLI_CALL("--task", "T", &b->task, set_task, "plan (default), check or classify; the "
               "task's options follow (see 'unstack T --help')"),
      CLI_LONG("--jobs", "N", &b->jobs, "worker threads (default: the cores online)",
               CLI_RANGE(1, 4096)),
      CLI_OPT_TIME_LIMIT(&b->time_limit, "per input, from its start, loading included; a cut "
                         "input is undecided (classify: each of its searches)"),
      CLI_FLAG("--resume", &b->resume, "keep OUT's whole lines and skip the inputs they answer "
               "(a cut last line is removed)"),
  };
  CliOpt task[CLI_TABLE_MAX], opts[CLI_TABLE_MAX + 8];
  if (b->task == BATCH_PLAN) cli_plan_table(&b->common, &b->plan_args, task);
  else if (b->task == BATCH_CHECK) cli_check_table(&b->common, &b->check_args, task);
  else cli_classify_table(&b->classify, task);
  int n = 0;
  for (size_t k = 0; k < sizeof own / sizeof own[0]; k++) opts[n++] = own[k];
  for (int k = 0; task[k].name; k++)
    if (!left_out(task[k].name)) opts[n++] = task[k];
  opts[n] = (CliOpt)CLI_END;
  const CliSpec spec = {"batch", head, tail, opts, (const char **)raw, argc, NULL};
  int r = cli_parse(&spec, argc, argv);
  for (*nraw = 0; !r && *nraw < argc && raw[*nraw];) ++*nraw;
  if (!r && !*nraw) return cli_fail("batch", "no INPUTS given (see 'unstack batch --help')");
  if (!r && !b->out) return cli_fail("batch", "no output given: use -o OUT.jsonl");
  b->classify.set.stability = b->classify.common.stab;
  if (b->task == BATCH_CLASSIFY && b->time_limit > 0) b->classify.set.time_limit = b->time_limit;
  return r;
}

/* ---------------------------------------------------------- local run */

/* The worker threads' shared state: the next input to claim and the
 * output, both under mu. */
typedef struct Shared {
  const Batch *b;
  char *const *inputs;
  const unsigned char *skip;
  int n, claim, oom;
  BatchSink *sink;
  pthread_mutex_t mu;
} Shared;

static int claim(Shared *sh) {
  pthread_mutex_lock(&sh->mu);
  while (sh->claim < sh->n && sh->skip[sh->claim]) sh->claim++;
  int i = sh->claim < sh->n && !sh->oom ? sh->claim++ : -1;
  pthread_mutex_unlock(&sh->mu);
  return i;
}

static void *worker(void *arg) {
  Shared *sh = arg;
  for (int i; (i = claim(sh)) >= 0;) {
    int failed = 0;
    char *line = batch_run_one(sh->b, sh->inputs[i], &failed);
    pthread_mutex_lock(&sh->mu);
    if (line) batch_sink_put(sh->sink, i, line, failed);
    else sh->oom = 1; /* the lines before it are written; --resume goes on */
    pthread_mutex_unlock(&sh->mu);
  }
  return NULL;
}

/* Threads over the inputs; 0 or CLI_EXIT_ERR (out of memory). */
static int run_threads(const Batch *b, char *const *inputs, int n, const unsigned char *skip,
                       BatchSink *k) {
  Shared sh = {b, inputs, skip, n, 0, 0, k, PTHREAD_MUTEX_INITIALIZER};
  long nt = b->jobs < k->todo ? b->jobs : k->todo;
  pthread_t *t = calloc((size_t)(nt > 0 ? nt : 1), sizeof *t);
  long started = 0;
  if (!t) return cli_fail("batch", "out of memory");
  while (started < nt && !pthread_create(&t[started], NULL, worker, &sh)) started++;
  if (started == 0 && nt > 0) worker(&sh); /* no thread could start: work here */
  for (long i = 0; i < started; i++) pthread_join(t[i], NULL);
  free(t);
  pthread_mutex_destroy(&sh.mu);
  return sh.oom ? cli_fail("batch", "out of memory: OUT holds the lines before it (--resume)") : 0;
}

static int run_local(const Batch *b, char *const *raw, int nraw) {
  char **inputs;
  unsigned char *skip;
  int n;
  BatchSink k;
  if (batch_prepare(b, raw, nraw, &inputs, &n, &skip, &k)) return CLI_EXIT_ERR;
  long todo = k.todo, kept = n - todo;
  double t0 = us_now();
  int r = run_threads(b, inputs, n, skip, &k);
  long failed = k.failed;
  if (batch_sink_close(&k)) r = CLI_EXIT_ERR;
  FILE *info = strcmp(b->out, "-") ? stdout : stderr;
  fprintf(info, "batch %s: %d inputs, %ld answered now (%ld error%s), %ld kept from %s, %.3f s, "
          "%ld job%s -> %s\n", batch_task_name(b->task), n, todo, failed, failed == 1 ? "" : "s",
          kept, b->out, us_now() - t0, b->jobs, b->jobs == 1 ? "" : "s", b->out);
  batch_inputs_free(inputs, n), free(skip);
  return r ? r : failed ? CLI_EXIT_NO : CLI_EXIT_OK;
}

int cmd_batch(int argc, char **argv) {
  Batch b;
  memset(&b, 0, sizeof b);
  cli_common_init(&b.common);
  cli_common_init(&b.classify.common);
  b.classify.set = us_classify_default_settings();
  long cores = sysconf(_SC_NPROCESSORS_ONLN);
  b.jobs = cores > 0 ? cores : 1;
  char **raw = calloc((size_t)argc + 1, sizeof *raw);
  if (!raw) return cli_fail("batch", "out of memory");
  int nraw, r = parse(argc, argv, &b, raw, &nraw);
  if (r) return free(raw), r < 0 ? CLI_EXIT_OK : r;
  /* one BLAS thread per input: main() has set OPENBLAS_NUM_THREADS */
  json_object_seed(0); /* jansson's hash seed, once, before any thread */
  r = batch_mpi_ranks() > 1 ? batch_mpi_run(&b, raw, nraw) : run_local(&b, raw, nraw);
  free(raw);
  return r;
}
