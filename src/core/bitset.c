/* Dynamic bitsets (sub-assemblies of any size) and a hash set of them.
 *
 * Invariant: bits at positions >= nbits in the last word are always zero,
 * so equality, hashing and counting may read whole words.
 *
 * The set stores each key's words once in a pool and keeps (hash, pool
 * index) pairs in an open-addressing table at most half full; hash 0 marks
 * an empty slot, so a key whose hash is 0 is stored as hash 1. */
#include "core.h"

#include <string.h>

int us_bitset_init(us_Bitset *b, int nbits) {
  b->nbits = nbits;
  b->nwords = (nbits + 63) / 64;
  b->w = us_calloc((size_t)(b->nwords > 0 ? b->nwords : 1), sizeof(uint64_t));
  return b->w ? 0 : -1;
}

void us_bitset_free(us_Bitset *b) {
  us_free(b->w);
  b->w = NULL;
  b->nbits = b->nwords = 0;
}

int us_bitset_copy(us_Bitset *dst, const us_Bitset *src) {
  if (!dst->w || dst->nwords != src->nwords) {
    us_bitset_free(dst);
    if (us_bitset_init(dst, src->nbits)) return -1;
  }
  dst->nbits = src->nbits;
  memcpy(dst->w, src->w, (size_t)src->nwords * sizeof(uint64_t));
  return 0;
}

int us_bitset_count(const us_Bitset *b) {
  int c = 0;
  for (int i = 0; i < b->nwords; i++) c += __builtin_popcountll(b->w[i]);
  return c;
}

int us_bitset_equal(const us_Bitset *a, const us_Bitset *b) {
  return a->nwords == b->nwords &&
         memcmp(a->w, b->w, (size_t)a->nwords * sizeof(uint64_t)) == 0;
}

static uint64_t mix64(uint64_t x) {
  x ^= x >> 33;
  x *= 0xff51afd7ed558ccdULL;
  x ^= x >> 33;
  x *= 0xc4ceb9fe1a85ec53ULL;
  x ^= x >> 33;
  return x;
}

static uint64_t hash_words(const uint64_t *w, int n) {
  uint64_t h = 0x9e3779b97f4a7c15ULL ^ (uint64_t)n;
  for (int i = 0; i < n; i++) h = mix64(h ^ w[i]) + (uint64_t)i;
  return h ? h : 1;
}

uint64_t us_bitset_hash(const us_Bitset *b) { return hash_words(b->w, b->nwords); }

void us_bitset_fill(us_Bitset *b) {
  for (int i = 0; i < b->nwords; i++) b->w[i] = ~(uint64_t)0;
  int rem = b->nbits & 63;
  if (rem && b->nwords) b->w[b->nwords - 1] = ((uint64_t)1 << rem) - 1;
}

/* ---- hash set ---- */

int us_bitset_set_init(us_BitsetSet *s, int nbits) {
  memset(s, 0, sizeof *s);
  s->nwords = (nbits + 63) / 64;
  if (s->nwords == 0) s->nwords = 1;
  s->cap = 64;
  s->hashes = us_calloc(s->cap, sizeof(uint64_t));
  s->slot_key = us_calloc(s->cap, sizeof(size_t));
  if (!s->hashes || !s->slot_key) {
    us_bitset_set_free(s);
    return -1;
  }
  return 0;
}

void us_bitset_set_free(us_BitsetSet *s) {
  us_free(s->hashes);
  us_free(s->slot_key);
  us_free(s->pool);
  memset(s, 0, sizeof *s);
}

static const uint64_t *key_words(const us_BitsetSet *s, size_t k) {
  return s->pool + k * (size_t)s->nwords;
}

/* Slot holding words w (or the empty slot where it would go). */
static size_t find_slot(const us_BitsetSet *s, const uint64_t *w, uint64_t h) {
  size_t mask = s->cap - 1, i = (size_t)h & mask;
  size_t bytes = (size_t)s->nwords * sizeof(uint64_t);
  while (s->hashes[i]) {
    if (s->hashes[i] == h && memcmp(key_words(s, s->slot_key[i]), w, bytes) == 0) return i;
    i = (i + 1) & mask;
  }
  return i;
}

int us_bitset_set_contains(const us_BitsetSet *s, const us_Bitset *b) {
  if (!s->hashes) return 0;
  uint64_t h = hash_words(b->w, s->nwords);
  return s->hashes[find_slot(s, b->w, h)] != 0;
}

long us_bitset_set_index(const us_BitsetSet *s, const us_Bitset *b) {
  if (!s->hashes) return -1;
  uint64_t h = hash_words(b->w, s->nwords);
  size_t i = find_slot(s, b->w, h);
  return s->hashes[i] ? (long)s->slot_key[i] : -1;
}

static int rehash(us_BitsetSet *s) {
  size_t ncap = s->cap * 2;
  uint64_t *nh = us_calloc(ncap, sizeof(uint64_t));
  size_t *nk = us_calloc(ncap, sizeof(size_t));
  if (!nh || !nk) {
    us_free(nh);
    us_free(nk);
    return -1;
  }
  for (size_t i = 0; i < s->cap; i++) {
    if (!s->hashes[i]) continue;
    size_t j = (size_t)s->hashes[i] & (ncap - 1);
    while (nh[j]) j = (j + 1) & (ncap - 1);
    nh[j] = s->hashes[i];
    nk[j] = s->slot_key[i];
  }
  us_free(s->hashes);
  us_free(s->slot_key);
  s->hashes = nh;
  s->slot_key = nk;
  s->cap = ncap;
  return 0;
}

static int pool_reserve(us_BitsetSet *s) {
  if (s->count < s->pool_cap) return 0;
  size_t ncap = s->pool_cap ? s->pool_cap * 2 : 64;
  uint64_t *p = us_realloc(s->pool, ncap * (size_t)s->nwords * sizeof(uint64_t));
  if (!p) return -1;
  s->pool = p;
  s->pool_cap = ncap;
  return 0;
}

int us_bitset_set_add(us_BitsetSet *s, const us_Bitset *b) {
  if ((s->count + 1) * 2 > s->cap && rehash(s)) return -1;
  if (pool_reserve(s)) return -1;
  uint64_t h = hash_words(b->w, s->nwords);
  size_t i = find_slot(s, b->w, h);
  if (s->hashes[i]) return 0;
  memcpy(s->pool + s->count * (size_t)s->nwords, b->w, (size_t)s->nwords * sizeof(uint64_t));
  s->hashes[i] = h;
  s->slot_key[i] = s->count++;
  return 1;
}

size_t us_bitset_set_bytes(const us_BitsetSet *s) {
  return s->cap * (sizeof(uint64_t) + sizeof(size_t)) +
         s->pool_cap * (size_t)s->nwords * sizeof(uint64_t);
}

int us_bitset_next(const us_Bitset *b, int i) {
  int j = i + 1;
  if (j < 0 || j >= b->nbits) return -1;
  int wi = j >> 6;
  uint64_t m = b->w[wi] & (~0ULL << (j & 63));
  while (!m) {
    if (++wi >= b->nwords) return -1;
    m = b->w[wi];
  }
  j = (wi << 6) + __builtin_ctzll(m);
  return j < b->nbits ? j : -1;
}
