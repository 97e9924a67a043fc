/* Benchmark of removal kinematics (src/contact/kinematics.c): the UP and
 * FREE precomputations (best of 3) on generated structures, the number of
 * (body, blocker) pairs UP stores, and the mean query time over random
 * sub-assemblies (each movable body present with probability 1/2, every
 * body queried). Scenes: a running-bond wall of 100 x 100 (10,050 bricks),
 * the 91-block pyramid, columns of 1,000 and 3,000 blocks (UP stores
 * n(n-1)/2 pairs there: the size of the answer). Usage:
 * bench_kinematics [wall ROWS COLS | column N]. */
#include "contact/kinematics.h"
#include "unstack/unstack.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Best of 3 precomputations in `mode`; the last workspace is kept. */
static double time_new(const us_Structure *s, us_Removal mode, us_Kinematics **out) {
  double best = 1e30;
  *out = NULL;
  for (int r = 0; r < 3; r++) {
    us_kinematics_free(*out);
    us_Error err;
    double t0 = us_now();
    *out = us_kinematics_new(s, mode, &err);
    double t = us_now() - t0;
    if (!*out) {
      fprintf(stderr, "kinematics: %s\n", err.msg);
      return -1;
    }
    best = t < best ? t : best;
  }
  return best;
}

/* Mean seconds per can_remove over `rounds` random sub-assemblies. */
static double time_queries(const us_Structure *s, const us_Kinematics *k, int rounds, long *blocked) {
  us_Bitset p;
  if (us_bitset_init(&p, s->nbody)) return -1;
  unsigned long long x = 88172645463325252ull;
  double t = 0;
  long nq = 0;
  *blocked = 0;
  for (int r = 0; r < rounds; r++) {
    for (int b = 0; b < s->nbody; b++) {
      x ^= x << 13, x ^= x >> 7, x ^= x << 17;
      if (x & 1) us_bitset_set(&p, b); else us_bitset_clear(&p, b);
    }
    double t0 = us_now();
    for (int b = 0; b < s->nbody; b++) *blocked += !us_kinematics_can_remove(k, &p, b);
    t += us_now() - t0;
    nq += s->nbody;
  }
  us_bitset_free(&p);
  return t / (double)nq;
}

static int run(const char *name, us_Structure *s, us_Error *err) {
  if (!s) {
    fprintf(stderr, "%s: %s\n", name, err->msg);
    return 1;
  }
  us_Kinematics *ku, *kf;
  double tu = time_new(s, US_REMOVAL_UP, &ku), tf = time_new(s, US_REMOVAL_FREE, &kf);
  int fails = !ku || !kf;
  if (!fails) {
    long bu, bf;
    double qu = time_queries(s, ku, 20, &bu), qf = time_queries(s, kf, 20, &bf);
    long pairs = us_kinematics_up_pairs(ku);
    printf("%-22s bodies %6d  UP %8.4f s  pairs %9ld (%6.1f MB)  query %6.3f us  |  FREE %8.4f s"
           "  query %6.3f us\n",
           name, s->nbody, tu, pairs, 4e-6 * (double)pairs, 1e6 * qu, tf, 1e6 * qf);
  }
  us_kinematics_free(ku);
  us_kinematics_free(kf);
  us_structure_free(s);
  return fails;
}

int main(int argc, char **argv) {
  us_Error err;
  us_GenSettings g = us_gen_default_settings();
  if (argc == 4 && strcmp(argv[1], "wall") == 0) {
    g.rows = atoi(argv[2]);
    g.cols = atoi(argv[3]);
    return run("wall", us_gen_wall(&g, &err), &err);
  }
  if (argc == 3 && strcmp(argv[1], "column") == 0) {
    g.n = atoi(argv[2]);
    return run("column", us_gen_column(&g, &err), &err);
  }
  int fails = 0;
  g.rows = g.cols = 100;
  fails += run("wall 100x100 (10,050)", us_gen_wall(&g, &err), &err);
  g.rows = 25, g.cols = 40;
  fails += run("wall 25x40 (1,012)", us_gen_wall(&g, &err), &err);
  g.n = 13;
  fails += run("pyramid 13 (91)", us_gen_pyramid(&g, &err), &err);
  g.n = 1000;
  fails += run("column 1,000", us_gen_column(&g, &err), &err);
  g.n = 3000;
  fails += run("column 3,000", us_gen_column(&g, &err), &err);
  return fails ? 1 : 0;
}
