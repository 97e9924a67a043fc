/* The one allocation funnel. Every allocation of the library goes through
 * here so that tests can count live blocks (leak checks) and make the N-th
 * allocation fail (out-of-memory paths), as Lua's ltests.c does.
 *
 * Threads: the live count is one atomic counter for the process (a block
 * may be freed by another thread than the one that allocated it; relaxed
 * order is enough, since it is read only for leak checks after the
 * threads are joined). The failure hook is per thread: a test that makes
 * its own N-th allocation fail never fails another thread's. Both are on
 * the short list of the library's writable globals (tests/globals.sh).
 *
 * Big blocks (the contacts of a 100,000-block wall are 67 MB) are marked
 * for transparent huge pages where the kernel offers them on request
 * (Linux, "madvise" mode, Debian's default): the pages of such a block
 * are then faulted in 2 MB at a time instead of 4 KB. A 100,014-block
 * wall's `plan` took 57,000 page faults and a third of its time in the
 * kernel (docs/local.md, "Process settings"). It is advice about our own
 * blocks only: the allocator's policy is untouched. */
#define _DEFAULT_SOURCE /* madvise, MADV_HUGEPAGE */
#include "core.h"

#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#define BIG_BLOCK (2u << 20) /* blocks from this size on ask for huge pages */
#define HUGE_PAGE (2u << 20)

static void *big_pages(void *p, size_t n) {
#ifdef MADV_HUGEPAGE
  if (p && n >= BIG_BLOCK) { /* the whole huge pages inside the block */
    uintptr_t a = ((uintptr_t)p + HUGE_PAGE - 1) & ~(uintptr_t)(HUGE_PAGE - 1);
    uintptr_t b = ((uintptr_t)p + n) & ~(uintptr_t)(HUGE_PAGE - 1);
    if (b > a) (void)madvise((void *)a, b - a, MADV_HUGEPAGE); /* advice: ignore failure */
  }
#else
  (void)n;
#endif
  return p;
}

static _Thread_local long fail_after = -1; /* < 0: never fail */
static atomic_long live;

static int should_fail(void) {
  if (fail_after < 0) return 0;
  if (fail_after == 0) return 1;
  fail_after--;
  return 0;
}

void *us_malloc(size_t n) {
  if (should_fail()) return NULL;
  void *p = malloc(n ? n : 1);
  if (p) atomic_fetch_add_explicit(&live, 1, memory_order_relaxed);
  return big_pages(p, n);
}

void *us_calloc(size_t count, size_t size) {
  if (should_fail()) return NULL;
  void *p = calloc(count ? count : 1, size ? size : 1);
  if (p) atomic_fetch_add_explicit(&live, 1, memory_order_relaxed);
  return big_pages(p, count * size); /* calloc checked count * size */
}

void *us_realloc(void *p, size_t n) {
  if (!p) return us_malloc(n);
  if (should_fail()) return NULL;
  return big_pages(realloc(p, n ? n : 1), n);
}

void us_free(void *p) {
  if (!p) return;
  atomic_fetch_sub_explicit(&live, 1, memory_order_relaxed);
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
  return us_alloc_live();
}

long us_alloc_live(void) { return atomic_load_explicit(&live, memory_order_relaxed); }

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
