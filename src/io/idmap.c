/* Hash map from body ids to body indices, so that reading contacts and
 * plans costs O(1) per id lookup instead of a linear scan (10,000-body
 * files stay near-linear).
 *
 * Open addressing with linear probing, FNV-1a hashes, capacity a power of
 * two at least twice the expected count (load <= 1/2, so probes are short
 * and a free slot always exists). Keys are borrowed, never copied. */
#include <string.h>

#include "io.h"

static size_t hash_str(const char *s) {
  uint64_t h = 1469598103934665603ull;
  for (; *s; s++) h = (h ^ (unsigned char)*s) * 1099511628211ull;
  return (size_t)(h ^ (h >> 29));
}

int us_idmap_init(us_IdMap *m, int expected) {
  size_t cap = 16;
  while (cap < 2 * (size_t)(expected > 0 ? expected : 0) + 2) cap *= 2;
  m->cap = cap;
  m->keys = us_calloc(cap, sizeof *m->keys);
  m->vals = us_calloc(cap, sizeof *m->vals);
  if (!m->keys || !m->vals) {
    us_idmap_free(m);
    return -1;
  }
  return 0;
}

void us_idmap_free(us_IdMap *m) {
  us_free(m->keys);
  us_free(m->vals);
  m->keys = NULL;
  m->vals = NULL;
  m->cap = 0;
}

/* Slot holding key, or the empty slot where it would go. */
static size_t find_slot(const us_IdMap *m, const char *key) {
  size_t mask = m->cap - 1, i = hash_str(key) & mask;
  while (m->keys[i] && strcmp(m->keys[i], key) != 0) i = (i + 1) & mask;
  return i;
}

int us_idmap_get(const us_IdMap *m, const char *key) {
  size_t i = find_slot(m, key);
  return m->keys[i] ? m->vals[i] : -1;
}

int us_idmap_put(us_IdMap *m, const char *key, int val) {
  size_t i = find_slot(m, key);
  if (m->keys[i]) return -1;
  m->keys[i] = key;
  m->vals[i] = val;
  return 0;
}

int us_idmap_bodies(us_IdMap *m, const us_Structure *s) {
  if (us_idmap_init(m, s->nbody)) return -1;
  for (int i = 0; i < s->nbody; i++) us_idmap_put(m, s->bodies[i].id, i);
  return 0;
}
