/* The tests' scratch files: one temporary directory per test program
 * (created on first use, removed at exit with whatever a failed case left
 * in it) and whole-file reads. */
#ifndef US_TESTS_TMPFILES_H
#define US_TESTS_TMPFILES_H

#include "core/core.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

static char test_dir[64];

static void test_remove_dir(void) {
  DIR *d = opendir(test_dir);
  struct dirent *e;
  char path[400];
  while (d && (e = readdir(d)))
    if (e->d_name[0] != '.') snprintf(path, sizeof path, "%s/%s", test_dir, e->d_name), remove(path);
  if (d) closedir(d);
  rmdir(test_dir);
}

/* buf = the directory / name, or NULL if the directory cannot be made. */
static inline const char *test_tmp_path(const char *name, char *buf, size_t n) {
  if (!test_dir[0]) {
    snprintf(test_dir, sizeof test_dir, "/tmp/us_test_XXXXXX");
    if (!mkdtemp(test_dir)) return NULL;
    atexit(test_remove_dir);
  }
  snprintf(buf, n, "%s/%s", test_dir, name);
  return buf;
}

/* The whole file as a string (us_malloc'd), or NULL. */
static inline char *test_slurp(const char *path) {
  FILE *fp = fopen(path, "rb");
  if (!fp) return NULL;
  fseek(fp, 0, SEEK_END);
  long n = ftell(fp);
  fseek(fp, 0, SEEK_SET);
  char *s = n >= 0 ? us_malloc((size_t)n + 1) : NULL;
  if (s && fread(s, 1, (size_t)n, fp) != (size_t)n) us_free(s), s = NULL;
  if (s) s[n] = 0;
  fclose(fp);
  return s;
}

#endif
