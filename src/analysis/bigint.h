/* Unsigned big integers for exact counts (src/analysis/bigint.c): the
 * number of connected sub-assemblies outgrows 64 bits at about 64 bodies.
 *
 * Representation: value = sum_i w[i] 2^(64 i), little-endian 64-bit limbs;
 * n limbs are in use and w[n - 1] != 0 (n == 0 is zero, w may be NULL).
 * A zeroed us_Big is a valid zero. Every call that may allocate returns 0,
 * or -1 when out of memory, and then leaves its output a valid number
 * (unchanged, except for us_big_mul whose output is left as it was too). */
#ifndef US_ANALYSIS_BIGINT_H
#define US_ANALYSIS_BIGINT_H

#include "core/core.h"

typedef struct us_Big {
  int n;        /* limbs in use */
  int cap;      /* limbs allocated */
  uint64_t *w;  /* [cap] */
} us_Big;

void us_big_init(us_Big *a); /* zero, no allocation */
void us_big_free(us_Big *a); /* back to zero */
int us_big_set_u64(us_Big *a, uint64_t v);
/* a = the number whose n limbs are w (leading zero limbs allowed). */
int us_big_set_words(us_Big *a, const uint64_t *w, int n);
int us_big_copy(us_Big *dst, const us_Big *src);
int us_big_add(us_Big *a, const us_Big *b); /* a += b; b may be a */
int us_big_add_u64(us_Big *a, uint64_t v);
int us_big_mul_u64(us_Big *a, uint64_t v);
/* dst = a * b; dst may be a or b. */
int us_big_mul(us_Big *dst, const us_Big *a, const us_Big *b);
int us_big_cmp(const us_Big *a, const us_Big *b); /* -1, 0, 1 */
/* 1 and *v set when the value fits in 64 bits, else 0. */
int us_big_to_u64(const us_Big *a, uint64_t *v);
/* The decimal digits (no sign, no leading zeros; "0" for zero), from
 * us_malloc; NULL when out of memory. */
char *us_big_to_dec(const us_Big *a);

#endif
