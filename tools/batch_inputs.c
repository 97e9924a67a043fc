/* unstack batch's inputs: files as given, a directory's *.json sorted by
 * name, '-' the paths on stdin; and what comes before the work (the output
 * checked, --resume's scan, the output opened), shared by the local and the
 * MPI run. */
#define _POSIX_C_SOURCE 200809L
#include "batch.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

typedef struct List {
  char **v;
  int n, cap;
} List;

static int push(List *l, char *s) {
  if (!s) return cli_fail("batch", "out of memory");
  if (l->n == l->cap) {
    int cap = 2 * l->cap + 64;
    char **v = realloc(l->v, (size_t)cap * sizeof *v);
    if (!v) return free(s), cli_fail("batch", "out of memory");
    l->v = v, l->cap = cap;
  }
  l->v[l->n++] = s;
  return 0;
}

static int cmp_str(const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

static int is_json_name(const char *name) {
  size_t len = strlen(name);
  return name[0] != '.' && len > 5 && !strcmp(name + len - 5, ".json");
}

/* A directory's *.json (not its sub-directories), sorted by name. */
static int add_dir(List *l, const char *dir) {
  DIR *d = opendir(dir);
  if (!d) return cli_fail("batch", "%s: cannot read the directory: %s", dir, strerror(errno));
  int first = l->n, r = 0;
  size_t dl = strlen(dir);
  const char *sep = dl && dir[dl - 1] == '/' ? "" : "/";
  for (struct dirent *e; !r && (e = readdir(d));) {
    if (!is_json_name(e->d_name)) continue;
    char *p = malloc(dl + strlen(e->d_name) + 2);
    if (p) sprintf(p, "%s%s%s", dir, sep, e->d_name);
    struct stat st;
    if (p && !stat(p, &st) && S_ISDIR(st.st_mode)) free(p);
    else r = push(l, p);
  }
  closedir(d);
  if (l->n > first) qsort(l->v + first, (size_t)(l->n - first), sizeof *l->v, cmp_str);
  return r;
}

/* Paths on stdin, one a line; empty lines skipped. */
static int add_stdin(List *l) {
  char *buf = NULL;
  size_t cap = 0;
  ssize_t len;
  int r = 0;
  while (!r && (len = getline(&buf, &cap, stdin)) >= 0) {
    while (len > 0 && (buf[len - 1] == '\n' || buf[len - 1] == '\r')) buf[--len] = '\0';
    if (len) r = push(l, strdup(buf));
  }
  free(buf);
  return r;
}

int batch_inputs(char *const *raw, int nraw, char ***out, int *n) {
  List l = {NULL, 0, 0};
  int r = 0, stdin_used = 0;
  for (int i = 0; !r && i < nraw; i++) {
    struct stat st;
    if (!strcmp(raw[i], "-") && stdin_used++)
      r = cli_fail("batch", "'-' (paths on stdin) given twice");
    else if (!strcmp(raw[i], "-")) r = add_stdin(&l);
    else if (!stat(raw[i], &st) && S_ISDIR(st.st_mode)) r = add_dir(&l, raw[i]);
    else r = push(&l, strdup(raw[i])); /* a missing file is that input's error line */
  }
  if (r) return batch_inputs_free(l.v, l.n), r;
  *out = l.v, *n = l.n;
  return 0;
}

void batch_inputs_free(char **v, int n) {
  for (int i = 0; i < n; i++) free(v[i]);
  free(v);
}

int batch_prepare(const Batch *b, char *const *raw, int nraw, char ***inputs, int *n,
                  unsigned char **skip, BatchSink *k) {
  *inputs = NULL, *n = 0, *skip = NULL;
  if (batch_inputs(raw, nraw, inputs, n)) return CLI_EXIT_ERR;
  int r = strcmp(b->out, "-") ? cli_check_output("batch", b->out, (const char *const *)*inputs, *n) : 0;
  if (!r && b->resume && !strcmp(b->out, "-")) r = cli_fail("batch", "--resume needs an output file, not '-'");
  if (!r && !(*skip = calloc((size_t)(*n > 0 ? *n : 1), 1))) r = cli_fail("batch", "out of memory");
  if (!r && b->resume) r = batch_resume_scan(b->out, *inputs, *n, *skip);
  if (!r) r = batch_sink_open(k, b->out, b->resume, *n, *skip);
  if (r) batch_inputs_free(*inputs, *n), free(*skip), *inputs = NULL, *skip = NULL;
  return r;
}
