/* Shared by the differential tests (stability_lcp, stability_lp_lcp,
 * stability_local): a random walk over sub-assemblies and the generated
 * structures they walk. Header-only (static inline) like scenes.h; the
 * generators need the whole library (those tests link `unstack`). */
#ifndef US_TEST_WALKS_H
#define US_TEST_WALKS_H

#include "test.h"

/* The differential tests of the local tests (stability_local,
 * stability_local3d): CLP with local tests on (local = 1) or off, local
 * tests from the smallest sub-assembly on. */
static inline us_StabilitySettings local_settings(int local) {
  us_StabilitySettings set = us_stability_default_settings();
  set.method = US_METHOD_LP;
  set.local = local ? 1 : -1;
  set.local_min_bodies = 1;
  return set;
}

/* One step of a walk from a random body: in the first half remove one
 * while more than one is left (else add one), in the second add one back
 * (or remove one when all are present); a single-body structure stays. */
static inline void walk_step(us_Bitset *sub, int nbody, int first_half, unsigned long long *rng) {
  int i = (int)(test_rnd(rng) * nbody), left = us_bitset_count(sub);
  int removing = first_half ? left > 1 : left == nbody;
  if (!removing && left == nbody) return;
  while (us_bitset_get(sub, i) != removing) i = (i + 1) % nbody;
  if (removing)
    us_bitset_clear(sub, i);
  else
    us_bitset_set(sub, i);
}

/* A generated structure by kind: 0 a size x size wall, 1 a pyramid of size
 * rows, 2 an arch of size + arch_extra voussoirs with arch_loose loose
 * blocks, else the stacker's stack of size rows in a width of 12. */
static inline us_Structure *walk_generated(int kind, double mu, int size, unsigned long seed,
                                           int arch_extra, int arch_loose) {
  us_GenSettings g = us_gen_default_settings();
  g.friction = mu;
  g.seed = seed;
  us_Error err;
  switch (kind) {
  case 0: g.rows = size, g.cols = size; return us_gen_wall(&g, &err);
  case 1: g.n = size; return us_gen_pyramid(&g, &err);
  case 2: g.n = size + arch_extra, g.loose = arch_loose; return us_gen_arch(&g, &err);
  default: g.rows = size, g.width = 12; return us_gen_stacker(&g, &err);
  }
}

#endif
