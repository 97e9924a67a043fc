/* The one pseudo-random generator of the library: splitmix64 (Steele, Lea,
 * Flood 2014), a full-period 64-bit generator, our own code, so a seed gives
 * the same numbers on every platform (never rand()). Used by the random
 * generators and the planner's random search. */
#include "core.h"

uint64_t us_rng_next(uint64_t *s) {
  uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/* Rejection of the top partial range keeps the draw free of modulo bias. */
long us_rng_below(uint64_t *s, long m) {
  uint64_t um = (uint64_t)m, limit = UINT64_MAX - UINT64_MAX % um;
  uint64_t v;
  do v = us_rng_next(s);
  while (v >= limit);
  return (long)(v % um);
}
