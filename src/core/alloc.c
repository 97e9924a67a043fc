/* The one allocation funnel. Every allocation of the library goes through
 * here so that tests can count live blocks (leak checks) and make the N-th
 * allocation fail (out-of-memory paths), as Lua's ltests.c does. The
 * counters are process-global and not thread-safe: the hook is for tests. */
#include "core.h"

#include <stdlib.h>
#include <string.h>

static long fail_after = -1; /* < 0: never fail */
static long live = 0;

static int should_fail(void) {
  if (fail_after < 0) return 0;
  if (fail_after == 0) return 1;
  fail_after--;
  return 0;
}

void *us_malloc(size_t n) {
  if (should_fail()) return NULL;
  void *p = malloc(n ? n : 1);
  if (p) live++;
  return p;
}

void *us_calloc(size_t count, size_t size) {
  if (should_fail()) return NULL;
  void *p = calloc(count ? count : 1, size ? size : 1);
  if (p) live++;
  return p;
}

void *us_realloc(void *p, size_t n) {
  if (!p) return us_malloc(n);
  if (should_fail()) return NULL;
  return realloc(p, n ? n : 1);
}

void us_free(void *p) {
  if (!p) return;
  live--;
  free(p);
}

char *us_strdup(const char *s) {
  size_t n = strlen(s) + 1;
  char *d = us_malloc(n);
  if (d) memcpy(d, s, n);
  return d;
}

long us_alloc_fail_after(long n) {
  fail_after = n;
  return live;
}

long us_alloc_live(void) { return live; }

int us_grow(void **arr, int *cap, int need, size_t elem) {
  if (need <= *cap) return 0;
  int ncap = *cap > 0 ? *cap : 8;
  while (ncap < need) {
    if (ncap > (1 << 29)) return -1;
    ncap *= 2;
  }
  void *p = us_realloc(*arr, (size_t)ncap * elem);
  if (!p) return -1;
  *arr = p;
  *cap = ncap;
  return 0;
}
