/* Minimal test harness: typed asserts that print both operands, one
 * executable per module, each case a function. Register cases with
 * US_TEST_MAIN; `./test_x name` runs one case, `./test_x --list` lists the
 * cases (CMake registers each as the ctest entry <module>.<case>), no
 * argument runs all. A
 * case fails on the first failed check; leaks of the allocation funnel are
 * checked after each case. */
#ifndef US_TEST_H
#define US_TEST_H

#include "unstack/unstack.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

extern int us_test_failed;

#define CHECK(cond)                                                            \
  do {                                                                         \
    if (!(cond)) {                                                             \
      fprintf(stderr, "%s:%d: CHECK(%s) failed\n", __FILE__, __LINE__, #cond); \
      us_test_failed = 1;                                                      \
      return;                                                                  \
    }                                                                          \
  } while (0)

#define CHECK_INT(a, op, b)                                                       \
  do {                                                                            \
    long long va_ = (long long)(a), vb_ = (long long)(b);                         \
    if (!(va_ op vb_)) {                                                          \
      fprintf(stderr, "%s:%d: CHECK_INT(%s %s %s) failed: %lld vs %lld\n", __FILE__, \
              __LINE__, #a, #op, #b, va_, vb_);                                   \
      us_test_failed = 1;                                                         \
      return;                                                                     \
    }                                                                             \
  } while (0)

#define CHECK_NEAR(a, b, tol)                                                       \
  do {                                                                              \
    double va_ = (double)(a), vb_ = (double)(b);                                    \
    if (!(fabs(va_ - vb_) <= (tol))) {                                              \
      fprintf(stderr, "%s:%d: CHECK_NEAR(%s, %s) failed: %.12g vs %.12g (tol %g)\n", \
              __FILE__, __LINE__, #a, #b, va_, vb_, (double)(tol));                 \
      us_test_failed = 1;                                                           \
      return;                                                                       \
    }                                                                               \
  } while (0)

#define CHECK_OK(expr, errp)                                                   \
  do {                                                                         \
    us_Status st_ = (expr);                                                    \
    if (st_ != US_OK) {                                                        \
      fprintf(stderr, "%s:%d: %s failed: %s: %s\n", __FILE__, __LINE__, #expr, \
              us_status_name(st_), (errp)->msg);                               \
      us_test_failed = 1;                                                      \
      return;                                                                  \
    }                                                                          \
  } while (0)

typedef struct us_TestCase {
  const char *name;
  void (*fn)(void);
} us_TestCase;

int us_test_run(const us_TestCase *cases, int n, int argc, char **argv);

#define US_TEST_MAIN(...)                                                  \
  int us_test_failed = 0;                                                  \
  int main(int argc, char **argv) {                                        \
    static const us_TestCase cases_[] = {__VA_ARGS__};                     \
    return us_test_run(cases_, (int)(sizeof cases_ / sizeof cases_[0]), argc, argv); \
  }                                                                        \
  int us_test_run(const us_TestCase *cases, int n, int argc, char **argv) { \
    int fails = 0, ran = 0;                                                \
    if (argc > 1 && strcmp(argv[1], "--list") == 0) {                      \
      for (int i = 0; i < n; i++) printf("%s\n", cases[i].name);          \
      return 0;                                                            \
    }                                                                      \
    for (int i = 0; i < n; i++) {                                          \
      if (argc > 1 && strcmp(argv[1], cases[i].name) != 0) continue;      \
      long live0 = us_alloc_live();                                        \
      us_test_failed = 0;                                                  \
      cases[i].fn();                                                       \
      us_alloc_fail_after(-1);                                             \
      if (!us_test_failed && us_alloc_live() != live0) {                   \
        fprintf(stderr, "%s: leaked %ld allocations\n", cases[i].name,     \
                us_alloc_live() - live0);                                  \
        us_test_failed = 1;                                                \
      }                                                                    \
      printf("%s %s\n", us_test_failed ? "FAIL" : "ok  ", cases[i].name);  \
      fails += us_test_failed;                                             \
      ran++;                                                               \
    }                                                                      \
    printf("%d passed, %d failed\n", ran - fails, fails);                  \
    return fails || ran == 0 ? 1 : 0;                                      \
  }

#define T(fn) {#fn, fn}

/* xorshift64: the tests' reproducible uniform numbers in [0, 1). */
static inline double test_rnd(unsigned long long *state) {
  *state ^= *state << 13;
  *state ^= *state >> 7;
  *state ^= *state << 17;
  return (double)(*state >> 11) * (1.0 / 9007199254740992.0);
}

/* The 64-bit linear congruential generator (Knuth's MMIX constants) in
 * [0, 1): the other stream some tests were tuned on, kept so that their
 * samples stay the same. */
static inline double test_lcg(unsigned long long *state) {
  *state = *state * 6364136223846793005ull + 1442695040888963407ull;
  return (double)(*state >> 11) * (1.0 / 9007199254740992.0);
}

#endif
