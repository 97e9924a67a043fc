/* Atomic output files and the clock. A writer gets a stream on a temporary
 * file in the destination's directory; commit renames it over the target,
 * abort removes it, so a failed run never leaves a partial output file. */
#define _POSIX_C_SOURCE 200809L
#include "core.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>
#include <unistd.h>

struct us_AtomicFile {
  FILE *fp;
  char *path;
  char *tmp;
};

us_AtomicFile *us_atomic_open(const char *path, us_Error *err) {
  us_AtomicFile *af = us_calloc(1, sizeof *af);
  size_t n = strlen(path);
  if (af) af->path = us_strdup(path);
  if (af) af->tmp = us_malloc(n + 16);
  if (!af || !af->path || !af->tmp) {
    if (af) us_free(af->path), us_free(af->tmp), us_free(af);
    us_error_set(err, US_ERR_NOMEM, "%s: out of memory", path);
    return NULL;
  }
  snprintf(af->tmp, n + 16, "%s.tmp.XXXXXX", path);
  int fd = mkstemp(af->tmp);
  if (fd >= 0) {
    /* mkstemp creates 0600; output files get the usual 0666 less umask */
    mode_t mask = umask(0);
    umask(mask);
    fchmod(fd, 0666 & ~mask);
    af->fp = fdopen(fd, "w");
  }
  if (!af->fp) {
    us_error_set(err, US_ERR_IO, "%s: cannot write: %s", path, strerror(errno));
    if (fd >= 0) close(fd), remove(af->tmp);
    us_free(af->path), us_free(af->tmp), us_free(af);
    return NULL;
  }
  return af;
}

void *us_atomic_stream(us_AtomicFile *af) { return af->fp; }

static void atomic_release(us_AtomicFile *af) {
  us_free(af->path);
  us_free(af->tmp);
  us_free(af);
}

us_Status us_atomic_commit(us_AtomicFile *af, us_Error *err) {
  int bad = ferror(af->fp);
  if (fclose(af->fp) != 0) bad = 1;
  if (!bad && rename(af->tmp, af->path) != 0) bad = 1;
  if (bad) {
    remove(af->tmp);
    us_error_set(err, US_ERR_IO, "%s: cannot write: %s", af->path, strerror(errno));
    atomic_release(af);
    return US_ERR_IO;
  }
  atomic_release(af);
  return US_OK;
}

void us_atomic_abort(us_AtomicFile *af) {
  if (!af) return;
  fclose(af->fp);
  remove(af->tmp);
  atomic_release(af);
}

double us_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
