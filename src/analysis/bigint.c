/* Unsigned big integers: the few operations exact counting needs (add,
 * multiply by a limb or by a big number, decimal output).
 *
 * Limbs are 64-bit, little-endian, normalized (w[n - 1] != 0; zero has
 * n == 0). Products of two limbs go through a 128-bit integer. Schoolbook
 * multiplication is enough: the counts multiply only in the tree formula,
 * where a factor of one limb (the common case) costs one pass.
 *
 * Decimal output divides a copy, viewed as 32-bit halves from the top, by
 * 10^9 repeatedly: the remainder stays below 10^9, so remainder * 2^32 +
 * half fits in 64 bits and the compiler turns the division by a constant
 * into a multiplication. Each pass yields 9 digits, least significant
 * first. */
#include "analysis/bigint.h"

#include <stdio.h>
#include <string.h>

__extension__ typedef unsigned __int128 us_u128;

void us_big_init(us_Big *a) { memset(a, 0, sizeof *a); }

void us_big_free(us_Big *a) {
  us_free(a->w);
  us_big_init(a);
}

/* room for `need` limbs; the value is unchanged */
static int reserve(us_Big *a, int need) {
  if (need <= a->cap) return 0;
  int cap = a->cap > 0 ? a->cap : 2;
  while (cap < need) cap *= 2;
  uint64_t *w = us_realloc(a->w, (size_t)cap * sizeof(uint64_t));
  if (!w) return -1;
  a->w = w;
  a->cap = cap;
  return 0;
}

static void normalize(us_Big *a) {
  while (a->n > 0 && a->w[a->n - 1] == 0) a->n--;
}

int us_big_set_u64(us_Big *a, uint64_t v) { return us_big_set_words(a, &v, 1); }

int us_big_set_words(us_Big *a, const uint64_t *w, int n) {
  while (n > 0 && w[n - 1] == 0) n--;
  if (reserve(a, n)) return -1;
  if (n > 0) memmove(a->w, w, (size_t)n * sizeof(uint64_t));
  a->n = n;
  return 0;
}

int us_big_copy(us_Big *dst, const us_Big *src) {
  if (dst == src) return 0;
  return us_big_set_words(dst, src->w, src->n);
}

int us_big_add(us_Big *a, const us_Big *b) {
  int n = US_MAX(a->n, b->n);
  if (reserve(a, n + 1)) return -1;
  const uint64_t *bw = b->w; /* after reserve: b may be a */
  for (int i = a->n; i < n + 1; i++) a->w[i] = 0;
  uint64_t carry = 0;
  for (int i = 0; i < n; i++) {
    uint64_t x = i < b->n ? bw[i] : 0;
    uint64_t s = a->w[i] + x;
    uint64_t c1 = s < x;
    a->w[i] = s + carry;
    carry = c1 | (a->w[i] < s);
  }
  a->w[n] = carry;
  a->n = n + 1;
  normalize(a);
  return 0;
}

int us_big_add_u64(us_Big *a, uint64_t v) {
  us_Big b = {1, 1, &v};
  return us_big_add(a, &b);
}

int us_big_mul_u64(us_Big *a, uint64_t v) {
  if (reserve(a, a->n + 1)) return -1;
  uint64_t carry = 0;
  for (int i = 0; i < a->n; i++) {
    us_u128 p = (us_u128)a->w[i] * v + carry;
    a->w[i] = (uint64_t)p;
    carry = (uint64_t)(p >> 64);
  }
  a->w[a->n++] = carry;
  normalize(a);
  return 0;
}

/* r[0 .. na + nb) = a * b (schoolbook); r is zeroed here */
static void mul_words(uint64_t *r, const uint64_t *a, int na, const uint64_t *b, int nb) {
  memset(r, 0, (size_t)(na + nb) * sizeof(uint64_t));
  for (int i = 0; i < na; i++) {
    uint64_t carry = 0;
    for (int j = 0; j < nb; j++) {
      us_u128 p = (us_u128)a[i] * b[j] + r[i + j] + carry;
      r[i + j] = (uint64_t)p;
      carry = (uint64_t)(p >> 64);
    }
    r[i + nb] = carry;
  }
}

int us_big_mul(us_Big *dst, const us_Big *a, const us_Big *b) {
  if (a->n == 0 || b->n == 0) {
    dst->n = 0;
    return 0;
  }
  int n = a->n + b->n;
  uint64_t *r = us_malloc((size_t)n * sizeof(uint64_t));
  if (!r) return -1;
  mul_words(r, a->w, a->n, b->w, b->n);
  us_free(dst->w); /* a and b are read: dst may be one of them */
  dst->w = r;
  dst->cap = dst->n = n;
  normalize(dst);
  return 0;
}

int us_big_cmp(const us_Big *a, const us_Big *b) {
  if (a->n != b->n) return a->n < b->n ? -1 : 1;
  for (int i = a->n - 1; i >= 0; i--)
    if (a->w[i] != b->w[i]) return a->w[i] < b->w[i] ? -1 : 1;
  return 0;
}

int us_big_to_u64(const us_Big *a, uint64_t *v) {
  if (a->n > 1) return 0;
  *v = a->n ? a->w[0] : 0;
  return 1;
}

/* h[0 .. nh) (32-bit halves, most significant last) /= 10^9; returns the
 * remainder; *nh drops leading zero halves */
static uint32_t div_1e9(uint32_t *h, int *nh) {
  uint64_t rem = 0;
  for (int i = *nh - 1; i >= 0; i--) {
    uint64_t cur = (rem << 32) | h[i];
    h[i] = (uint32_t)(cur / 1000000000u);
    rem = cur % 1000000000u;
  }
  while (*nh > 0 && h[*nh - 1] == 0) (*nh)--;
  return (uint32_t)rem;
}

/* write the chunks (9 digits each, least significant first) as decimal */
static void print_chunks(char *out, const uint32_t *chunk, int nchunk) {
  int k = sprintf(out, "%u", (unsigned)chunk[nchunk - 1]);
  for (int i = nchunk - 2; i >= 0; i--) k += sprintf(out + k, "%09u", (unsigned)chunk[i]);
}

char *us_big_to_dec(const us_Big *a) {
  int nh = 2 * a->n, maxchunk = nh * 32 / 29 + 2; /* 10^9 > 2^29 */
  uint32_t *h = us_malloc((size_t)(nh + 1) * sizeof(uint32_t));
  uint32_t *chunk = us_malloc((size_t)maxchunk * sizeof(uint32_t));
  char *out = us_malloc((size_t)maxchunk * 9 + 1);
  if (!h || !chunk || !out) {
    us_free(h);
    us_free(chunk);
    us_free(out);
    return NULL;
  }
  for (int i = 0; i < a->n; i++) {
    h[2 * i] = (uint32_t)a->w[i];
    h[2 * i + 1] = (uint32_t)(a->w[i] >> 32);
  }
  while (nh > 0 && h[nh - 1] == 0) nh--;
  int nchunk = 0;
  do chunk[nchunk++] = div_1e9(h, &nh);
  while (nh > 0);
  print_chunks(out, chunk, nchunk);
  us_free(h);
  us_free(chunk);
  return out;
}
