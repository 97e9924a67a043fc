/* Private core utilities shared by every module: small math helpers, the
 * hash set of sub-assemblies and a growable array macro. Public pieces
 * (errors, allocation, bitsets) live in include/unstack/unstack.h. */
#ifndef US_CORE_H
#define US_CORE_H

#include "unstack/unstack.h"

#include <stdint.h>
#include <stdio.h>

#define US_MIN(a, b) ((a) < (b) ? (a) : (b))
#define US_MAX(a, b) ((a) > (b) ? (a) : (b))
#define US_UNUSED(x) ((void)(x))

/* Grow *arr (element type T) so that it holds at least `need` elements.
 * Returns 0 or -1 on OOM (then *arr is unchanged). */
int us_grow(void **arr, int *cap, int need, size_t elem);
#define US_GROW(arr, cap, need) us_grow((void **)&(arr), &(cap), (need), sizeof(*(arr)))

/* One UTF-8 character at s (text.c): its code point in *cp and its length
 * in bytes; a malformed sequence is one byte with *cp = US_UTF8_INVALID. */
#define US_UTF8_INVALID 0xFFFFFFFFu
int us_utf8_next(const char *s, uint32_t *cp);

/* splitmix64 (rng.c): the next 64 random bits of state *s, and a uniform
 * integer in [0, m) for m >= 1. */
uint64_t us_rng_next(uint64_t *s);
long us_rng_below(uint64_t *s, long m);

/* Hash set of bitsets of one fixed width (the failed-node memo of the
 * planner). Open addressing with linear probing; keys are copied into one
 * growing word pool, so a set of k keys of w words costs about
 * k * (w * 8 + 16) bytes. */
typedef struct us_BitsetSet {
  int nwords;            /* words per key */
  size_t count;          /* keys stored */
  size_t cap;            /* slots, power of two */
  uint64_t *hashes;      /* cap entries, 0 = empty (hash 0 is remapped) */
  size_t *slot_key;      /* cap entries: index of key in pool */
  uint64_t *pool;        /* count * nwords words */
  size_t pool_cap;       /* keys the pool can hold */
} us_BitsetSet;

/* The first set bit of b after bit i (i = -1: from the start), or -1:
 * O(words skipped), for loops over a sparse sub-assembly of a large
 * structure. */
int us_bitset_next(const us_Bitset *b, int i);

int us_bitset_set_init(us_BitsetSet *s, int nbits);
void us_bitset_set_free(us_BitsetSet *s);
int us_bitset_set_contains(const us_BitsetSet *s, const us_Bitset *b);
/* 1 added, 0 already present, -1 OOM */
int us_bitset_set_add(us_BitsetSet *s, const us_Bitset *b);
/* Keys are numbered 0, 1, ... in the order they were added (so callers can
 * keep values in a parallel array): the number of b, or -1 when absent. */
long us_bitset_set_index(const us_BitsetSet *s, const us_Bitset *b);
size_t us_bitset_set_bytes(const us_BitsetSet *s);

/* Hash map from borrowed strings to non-negative ints (body ids to
 * indices); grows as needed. A zeroed map is empty and valid. */
typedef struct us_IdSlot {
  const char *key; /* NULL = empty slot */
  uint32_t hash;   /* of key: most probes end without reading another key */
  int val;
} us_IdSlot;
typedef struct us_IdMap {
  size_t cap; /* power of two, at least twice the count; 0 = unset */
  size_t count;
  us_IdSlot *slots;
} us_IdMap;
int us_idmap_init(us_IdMap *m, int expected); /* 0 or -1 on OOM */
void us_idmap_free(us_IdMap *m);
int us_idmap_get(const us_IdMap *m, const char *key); /* value or -1 */
/* Insert key -> val: 0 done, -1 the key exists (nothing changed), -2 OOM. */
int us_idmap_put(us_IdMap *m, const char *key, int val);

/* Has the clock passed deadline (a us_now() time; 0: never)? */
static inline int us_past(double deadline) { return deadline > 0 && us_now() > deadline; }

#endif
