/* unstack batch's output file: lines written in input order, each whole
 * with one write(2) on a descriptor opened for appending, so a killed run
 * leaves whole lines, at most the last one cut; --resume cuts that one and
 * skips the inputs the others answer. fsync every BATCH_SYNC_LINES lines
 * and at the end: a killed process loses nothing written (the kernel has
 * it), a machine that loses power loses at most the lines since the last
 * fsync, which --resume computes again. */
#define _POSIX_C_SOURCE 200809L
#include "batch.h"

#include <errno.h>
#include <fcntl.h>
#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int batch_sink_open(BatchSink *k, const char *out, int resume, int n, const unsigned char *skip) {
  memset(k, 0, sizeof *k);
  k->n = n, k->skip = skip, k->t0 = us_now(), k->tty = isatty(STDERR_FILENO);
  for (int i = 0; i < n; i++) k->todo += !(skip && skip[i]);
  k->line = calloc((size_t)(n > 0 ? n : 1), sizeof *k->line);
  if (!k->line) return cli_fail("batch", "out of memory");
  k->fd = !strcmp(out, "-") ? STDOUT_FILENO
          : open(out, O_WRONLY | O_CREAT | O_APPEND | (resume ? 0 : O_TRUNC), 0666);
  if (k->fd < 0) return free(k->line), cli_fail("batch", "%s: cannot write: %s", out, strerror(errno));
  return 0;
}

/* The whole line with write(2), again after a short write or a signal. */
static int write_line(int fd, const char *s) {
  size_t len = strlen(s);
  while (len > 0) {
    ssize_t w = write(fd, s, len);
    if (w < 0 && errno == EINTR) continue;
    if (w < 0) return errno;
    s += w, len -= (size_t)w;
  }
  return 0;
}

/* "batch: 120/400 inputs, 2 errors, 35.2/s, 8 s left", at most 4 a second. */
static void progress(BatchSink *k, int last) {
  double now = us_now();
  if (!k->tty || (!last && now - k->shown < 0.25)) return;
  k->shown = now;
  double el = now - k->t0, rate = el > 0 ? (double)k->written / el : 0.0;
  if (last) fprintf(stderr, "\r\033[K");
  else
    fprintf(stderr, "\rbatch: %ld/%ld inputs, %ld error%s, %.1f/s, %.0f s left\033[K", k->written,
            k->todo, k->failed, k->failed == 1 ? "" : "s", rate,
            rate > 0 ? (double)(k->todo - k->written) / rate : 0.0);
  fflush(stderr);
}

void batch_sink_put(BatchSink *k, int i, char *line, int failed) {
  k->line[i] = line;
  k->failed += failed;
  for (; k->next < k->n && ((k->skip && k->skip[k->next]) || k->line[k->next]); k->next++) {
    char *l = k->line[k->next];
    if (!l) continue;
    int e = k->write_error ? 0 : write_line(k->fd, l);
    if (e) k->write_error = e;
    free(l), k->line[k->next] = NULL, k->written++;
    if (++k->unsynced >= BATCH_SYNC_LINES && k->fd != STDOUT_FILENO) fsync(k->fd), k->unsynced = 0;
  }
  progress(k, 0);
}

int batch_sink_close(BatchSink *k) {
  progress(k, 1);
  int e = k->write_error;
  if (!e && k->fd != STDOUT_FILENO && fsync(k->fd) && errno != EINVAL) e = errno;
  if (k->fd >= 0 && k->fd != STDOUT_FILENO && close(k->fd) && !e) e = errno;
  for (int i = 0; i < k->n; i++) free(k->line[i]);
  free(k->line);
  k->fd = -1;
  return e ? cli_fail("batch", "writing the output: %s", strerror(e)) : 0;
}

/* ------------------------------------------------------------- --resume */

static int cmp_str(const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

/* OUT's text up to its last newline; a cut last line is removed from the
 * file. NULL with *len 0 when OUT does not exist. */
static int read_whole_lines(const char *out, char **text, size_t *len) {
  *text = NULL, *len = 0;
  FILE *f = fopen(out, "rb");
  if (!f) return errno == ENOENT ? 0 : cli_fail("batch", "%s: cannot read: %s", out, strerror(errno));
  struct stat st;
  size_t size = !fstat(fileno(f), &st) && st.st_size > 0 ? (size_t)st.st_size : 0;
  char *t = malloc(size + 1);
  size_t got = t ? fread(t, 1, size, f) : 0;
  fclose(f);
  if (!t || got != size) return free(t), cli_fail("batch", "%s: cannot read it whole", out);
  while (got > 0 && t[got - 1] != '\n') got--;
  t[got] = '\0';
  if (got < size && truncate(out, (off_t)got))
    return free(t), cli_fail("batch", "%s: cannot cut its incomplete last line: %s", out, strerror(errno));
  *text = t, *len = got;
  return 0;
}

/* The "file" of each line, in *files (pointers into text, sorted). */
static int answered_files(const char *out, char *text, char ***files, int *nf) {
  int cap = 0, n = 0;
  char **v = NULL;
  int lineno = 0;
  for (char *l = text, *e; l && *l; l = e ? e + 1 : NULL) {
    e = strchr(l, '\n');
    if (e) *e = '\0';
    lineno++;
    json_t *o = json_loads(l, 0, NULL);
    const char *f = json_string_value(json_object_get(o, "file"));
    if (!f) {
      json_decref(o), free(v);
      return cli_fail("batch", "%s:%d: not a batch line (no \"file\"); --resume needs the file "
                      "a batch wrote", out, lineno);
    }
    if (n == cap && !(v = realloc(v, (size_t)(cap = 2 * cap + 64) * sizeof *v)))
      return json_decref(o), cli_fail("batch", "out of memory");
    strcpy(l, f); /* a JSON string is never longer than its text */
    v[n++] = l;
    json_decref(o);
  }
  if (n) qsort(v, (size_t)n, sizeof *v, cmp_str);
  *files = v, *nf = n;
  return 0;
}

int batch_resume_scan(const char *out, char *const *inputs, int n, unsigned char *skip) {
  char *text, **files = NULL;
  size_t len;
  int nf = 0;
  if (read_whole_lines(out, &text, &len)) return CLI_EXIT_ERR;
  if (text && answered_files(out, text, &files, &nf)) return free(text), CLI_EXIT_ERR;
  for (int i = 0; i < n; i++)
    skip[i] = nf && bsearch(&inputs[i], files, (size_t)nf, sizeof *files, cmp_str) != NULL;
  free(files), free(text);
  return 0;
}
