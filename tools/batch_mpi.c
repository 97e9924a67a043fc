/* unstack batch over MPI ranks: rank 0 hands out one input at a time to
 * whichever rank asks (dynamic work sharing: a rank that finishes early
 * asks again) and writes OUT in input order; the other ranks run the task.
 * MPI comes from modules/mpi.so, loaded with RTLD_GLOBAL only here, so no
 * other command maps libmpi (docs/batch.md). */
#define _GNU_SOURCE
#include "batch.h"
#include "core/module.h"
#include "module/mpi_api.h"

#include <dlfcn.h>
#include <libgen.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

enum { TAG_RESULT = 1, TAG_WORK = 2 };

/* A message's head: the input's index (-1: none yet / stop) and, for a
 * result, whether its line is an error line; the text follows. */
typedef struct Head {
  int32_t index, failed;
} Head;

int batch_mpi_ranks(void) {
  const char *v = getenv("OMPI_COMM_WORLD_SIZE"); /* mpirun (Open MPI) */
  if (!v) v = getenv("PMI_SIZE");                 /* MPICH, srun --mpi=pmi2 */
  if (!v && getenv("PMIX_RANK")) v = getenv("SLURM_NTASKS"); /* srun --mpi=pmix */
  return v ? atoi(v) : 0;
}

/* modules/mpi.so beside the executable (or where an installed one keeps
 * its modules), opened RTLD_GLOBAL; NULL with why. */
static const us_MpiApi *load(char *why, size_t n) {
#ifndef US_HAVE_MPI
  snprintf(why, n, "this unstack was built without MPI (no libopenmpi-dev at build time, or -DUS_MPI=OFF)");
  return NULL;
#else
  char exe[4096], dir[4096], file[4200];
  ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (len <= 0) return snprintf(why, n, "cannot find the executable"), NULL;
  exe[len] = '\0';
  snprintf(why, n, "modules/mpi.so not found beside %.300s", exe);
  char *d = dirname(exe);
  for (int k = 0; us_module_dir(d, k, dir, sizeof dir); k++) {
    snprintf(file, sizeof file, "%s/mpi.so", dir);
    if (access(file, R_OK)) continue;
    void *h = dlopen(file, RTLD_NOW | RTLD_GLOBAL);
    us_MpiEntry entry = h ? (us_MpiEntry)dlsym(h, "us_module_mpi") : NULL;
    const us_MpiApi *api = entry ? entry() : NULL;
    if (api && api->abi == US_MPI_ABI) return api;
    snprintf(why, n, "%.300s: %.150s", file, h ? "not this build's MPI module" : dlerror());
  }
  return NULL;
#endif
}

void batch_mpi_version(char *buf, size_t n) {
  char why[512], v[256];
  const us_MpiApi *m = load(why, sizeof why);
  if (m) m->version(v, sizeof v);
  if (m) snprintf(buf, n, "mpi: yes (modules/mpi.so, %s; `mpirun -n R unstack batch ...`)", v);
  else snprintf(buf, n, "mpi: no (%s)", why);
}

/* Send a head and text (NULL: none). */
static int send_msg(const us_MpiApi *m, int dest, int tag, Head h, const char *text) {
  size_t len = text ? strlen(text) : 0;
  char *buf = malloc(sizeof h + len);
  if (!buf) return -1;
  memcpy(buf, &h, sizeof h);
  if (len) memcpy(buf + sizeof h, text, len);
  int r = m->send(buf, (int)(sizeof h + len), dest, tag);
  free(buf);
  return r;
}

/* Take a message of `len` bytes: its head, and its text in *text (malloc'd). */
static int take_msg(const us_MpiApi *m, int src, int tag, int len, Head *h, char **text) {
  char *buf = malloc((size_t)len + 1);
  if (!buf || len < (int)sizeof *h || m->recv(buf, len, src, tag)) return free(buf), -1;
  memcpy(h, buf, sizeof *h);
  memmove(buf, buf + sizeof *h, (size_t)len - sizeof *h);
  buf[len - (int)sizeof *h] = '\0';
  *text = buf;
  return 0;
}

/* The next input not answered yet, or -1. */
static int next_input(int *next, int n, const unsigned char *skip) {
  while (*next < n && skip[*next]) ++*next;
  return *next < n ? (*next)++ : -1;
}

/* Rank 0: serve requests until every worker has been told to stop. Polls
 * and sleeps 0.2 ms between polls, so it leaves its core to a worker. */
static int serve(const us_MpiApi *m, int size, char *const *inputs, int n,
                 const unsigned char *skip, BatchSink *k) {
  int next = 0, active = size - 1, r = 0;
  while (active > 0) {
    int src, tag, len;
    if (!m->poll(&src, &tag, &len)) {
      nanosleep(&(struct timespec){0, 200000}, NULL);
      continue;
    }
    Head h;
    char *line;
    if (take_msg(m, src, tag, len, &h, &line)) return cli_fail("batch", "MPI: a message was lost");
    if (h.index >= 0 && h.index < n && k) batch_sink_put(k, h.index, line, h.failed);
    else free(line);
    int i = k ? next_input(&next, n, skip) : -1;
    if (send_msg(m, src, TAG_WORK, (Head){i, 0}, i >= 0 ? inputs[i] : NULL))
      r = cli_fail("batch", "MPI: cannot send to rank %d", src);
    active -= i < 0;
  }
  return r;
}

/* Other ranks: ask, run, answer, until told to stop. */
static int work(const Batch *b, const us_MpiApi *m) {
  Head h = {-1, 0};
  char *line = NULL;
  for (;;) {
    int len;
    char *path;
    if (send_msg(m, 0, TAG_RESULT, h, line) || m->probe(0, TAG_WORK, &len) ||
        take_msg(m, 0, TAG_WORK, len, &h, &path))
      return free(line), m->abort(CLI_EXIT_ERR), CLI_EXIT_ERR;
    free(line), line = NULL;
    if (h.index < 0) return free(path), 0;
    int failed = 0;
    line = batch_run_one(b, path, &failed);
    free(path);
    if (!line) m->abort(CLI_EXIT_ERR);
    h.failed = failed;
  }
}

/* Rank 0: prepare, serve (also when preparing failed: the workers must be
 * told to stop), close, print the summary. */
static int lead(const Batch *b, const us_MpiApi *m, int size, char *const *raw, int nraw) {
  char **inputs = NULL;
  unsigned char *skip = NULL;
  int n = 0;
  BatchSink k;
  int r = batch_prepare(b, raw, nraw, &inputs, &n, &skip, &k);
  double t0 = us_now();
  int rs = serve(m, size, inputs, n, skip, r ? NULL : &k);
  if (r) return r;
  long todo = k.todo, failed = k.failed;
  if (batch_sink_close(&k) || rs) r = CLI_EXIT_ERR;
  FILE *info = strcmp(b->out, "-") ? stdout : stderr;
  fprintf(info, "batch %s: %d inputs, %ld answered now (%ld error%s), %ld kept from %s, %.3f s, "
          "%d MPI ranks (1 leading) -> %s\n", batch_task_name(b->task), n, todo, failed,
          failed == 1 ? "" : "s", n - todo, b->out, us_now() - t0, size, b->out);
  batch_inputs_free(inputs, n), free(skip);
  return r ? r : failed ? CLI_EXIT_NO : CLI_EXIT_OK;
}

int batch_mpi_run(const Batch *b, char *const *raw, int nraw) {
  char why[512];
  const us_MpiApi *m = load(why, sizeof why);
  if (!m) return cli_fail("batch", "launched with several MPI ranks, but %s", why);
  int rank, size;
  if (m->init(&rank, &size)) return cli_fail("batch", "MPI_Init failed");
  int r = size < 2 ? cli_fail("batch", "MPI gives 1 rank: run without mpirun")
          : rank == 0 ? lead(b, m, size, raw, nraw)
                      : work(b, m);
  m->finalize();
  return r;
}
