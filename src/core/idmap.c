/* Hash map from strings (body ids) to body indices, so that finding a body
 * by id costs O(1) and building or reading a 10,000-body structure stays
 * near-linear.
 *
 * Open addressing with linear probing and FNV-1a hashes; the capacity is a
 * power of two kept at least twice the count (load <= 1/2: probes stay
 * short and a free slot always exists), doubling when needed. A slot holds
 * the key, its hash and the value together (one cache line per probe; the
 * hash spares reading other keys). Keys are borrowed, never copied: they
 * must outlive the map (body ids do). */
#include "core.h"

#include <string.h>

static size_t hash_str(const char *s) {
  uint64_t h = 1469598103934665603ull;
  for (; *s; s++) h = (h ^ (unsigned char)*s) * 1099511628211ull;
  return (size_t)(h ^ (h >> 29));
}

int us_idmap_init(us_IdMap *m, int expected) {
  size_t cap = 16;
  while (cap < 2 * (size_t)(expected > 0 ? expected : 0) + 2) cap *= 2;
  m->cap = cap;
  m->count = 0;
  m->slots = us_calloc(cap, sizeof *m->slots);
  if (!m->slots) {
    us_idmap_free(m);
    return -1;
  }
  return 0;
}

void us_idmap_free(us_IdMap *m) {
  us_free(m->slots);
  m->slots = NULL;
  m->cap = m->count = 0;
}

/* Slot holding key (hash h), or the empty slot where it would go. */
static size_t find_slot(const us_IdSlot *slots, size_t cap, const char *key, size_t h) {
  size_t mask = cap - 1, i = h & mask;
  while (slots[i].key && (slots[i].hash != (uint32_t)h || strcmp(slots[i].key, key) != 0))
    i = (i + 1) & mask;
  return i;
}

int us_idmap_get(const us_IdMap *m, const char *key) {
  if (!m->cap) return -1;
  size_t i = find_slot(m->slots, m->cap, key, hash_str(key));
  return m->slots[i].key ? m->slots[i].val : -1;
}

static int grow(us_IdMap *m) {
  us_IdMap n;
  if (us_idmap_init(&n, (int)(m->cap))) return -1;
  for (size_t i = 0; i < m->cap; i++) {
    const us_IdSlot *o = &m->slots[i];
    if (!o->key) continue;
    size_t j = o->hash & (n.cap - 1);
    while (n.slots[j].key) j = (j + 1) & (n.cap - 1);
    n.slots[j] = *o;
  }
  n.count = m->count;
  us_idmap_free(m);
  *m = n;
  return 0;
}

int us_idmap_put(us_IdMap *m, const char *key, int val) {
  if (!m->cap && us_idmap_init(m, 8)) return -2;
  if (2 * (m->count + 1) > m->cap && grow(m)) return -2;
  size_t h = hash_str(key), i = find_slot(m->slots, m->cap, key, h);
  if (m->slots[i].key) return -1;
  m->slots[i] = (us_IdSlot){key, (uint32_t)h, val};
  m->count++;
  return 0;
}
