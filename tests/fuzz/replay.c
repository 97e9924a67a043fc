/* Replays fuzz inputs without libFuzzer: every argument is a file or a
 * directory (its regular files, in name order), each passed once to the
 * target's LLVMFuzzerTestOneInput. ctest runs it over tests/fuzz/corpus/
 * <target>/ so the corpus stays a regression suite in every build (gcc,
 * Release and ASan). A finding aborts; otherwise prints the count. */
#define _POSIX_C_SOURCE 200809L
#include "fuzz.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static int run_file(const char *path) {
  size_t n = 0;
  char *b = fz_slurp(path, &n);
  if (!b) {
    fprintf(stderr, "replay: cannot read %s\n", path);
    return 1;
  }
  if (getenv("FZ_REPLAY_VERBOSE")) fprintf(stderr, "replay: %s\n", path);
  LLVMFuzzerTestOneInput((const uint8_t *)b, n);
  free(b);
  return 0;
}

static int by_name(const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

static int run_dir(const char *dir, int *count) {
  DIR *d = opendir(dir);
  if (!d) return 1;
  int n = 0, cap = 0, bad = 0;
  char **names = NULL;
  struct dirent *e;
  while ((e = readdir(d)) != NULL) {
    if (e->d_name[0] == '.') continue;
    if (n == cap) names = realloc(names, (size_t)(cap = cap ? 2 * cap : 64) * sizeof *names);
    if (!names || !(names[n++] = strdup(e->d_name))) abort();
  }
  closedir(d);
  qsort(names, (size_t)n, sizeof *names, by_name);
  for (int k = 0; k < n; k++) {
    char p[4096];
    snprintf(p, sizeof p, "%s/%s", dir, names[k]);
    struct stat st;
    if (stat(p, &st) == 0 && S_ISREG(st.st_mode)) {
      bad |= run_file(p);
      (*count)++;
    }
    free(names[k]);
  }
  free(names);
  return bad;
}

int main(int argc, char **argv) {
  int count = 0, bad = 0;
  for (int i = 1; i < argc; i++) {
    struct stat st;
    if (stat(argv[i], &st) != 0) {
      fprintf(stderr, "replay: no such file or directory: %s\n", argv[i]);
      bad = 1;
    } else if (S_ISDIR(st.st_mode)) {
      bad |= run_dir(argv[i], &count);
    } else {
      bad |= run_file(argv[i]);
      count++;
    }
  }
  printf("replayed %d inputs\n", count);
  return bad || count == 0;
}
