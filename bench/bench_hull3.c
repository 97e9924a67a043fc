/* The 3D hull under finalize: one body of n points (on a sphere, in a
 * ball, on a cube's faces in a grid, so many coplanar and collinear
 * points, and a thin slab 1e-3 thick), n = 1,000 to SIZE; prints the
 * seconds of us_structure_finalize (hull, mass properties, contacts with
 * the ground), best of 3 below 100,000 points. Usage: bench_hull3 [SIZE]
 * (default 1000000). */
#include "unstack/unstack.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* A 64-bit LCG's top bits: uniform in [0, 1). */
static double uniform(uint64_t *s) {
  *s = *s * 6364136223846793005u + 1442695040888963407u;
  return (double)(*s >> 11) * 0x1.0p-53;
}

/* Point i of n of the given kind, into p (z >= 0: resting on the ground). */
static void point(int kind, int i, int n, uint64_t *rng, double *p) {
  double z = 2 * uniform(rng) - 1, t = 6.283185307179586 * uniform(rng), r = sqrt(1 - z * z);
  if (kind == 0) p[0] = r * cos(t), p[1] = r * sin(t), p[2] = z + 1;
  if (kind == 1) {
    double k = cbrt(uniform(rng));
    p[0] = k * r * cos(t), p[1] = k * r * sin(t), p[2] = k * z + 1;
  }
  if (kind == 2) { /* a grid on the cube's six faces */
    int side = (int)ceil(sqrt(n / 6.0)), f = i % 6, j = i / 6;
    double a = (double)(j % side) / side, b = (double)(j / side % side) / side;
    int ax = f / 2;
    p[ax] = (double)(f & 1), p[(ax + 1) % 3] = a, p[(ax + 2) % 3] = b;
  }
  if (kind == 3) p[0] = r * cos(t), p[1] = r * sin(t), p[2] = 1e-3 * uniform(rng);
}

static double run(int kind, int n) {
  double *xyz = malloc((size_t)n * 3 * sizeof *xyz), best = 1e30;
  uint64_t rng = 42;
  for (int i = 0; i < n; i++) point(kind, i, n, &rng, xyz + 3 * i);
  for (int rep = 0; rep < (n < 100000 ? 3 : 1); rep++) {
    us_Structure *s = us_structure_new(3);
    us_BodyDef d = us_default_body_def();
    us_Error err;
    d.id = "b", d.nvert = n, d.xyz = xyz;
    double t0 = us_now();
    if (us_structure_add_body(s, &d, &err) < 0 || us_structure_finalize(s, &err)) {
      fprintf(stderr, "bench_hull3: %s\n", err.msg);
      exit(1);
    }
    double t = us_now() - t0;
    best = t < best ? t : best;
    us_structure_free(s);
  }
  free(xyz);
  return best;
}

int main(int argc, char **argv) {
  int top = argc > 1 ? atoi(argv[1]) : 1000000;
  static const char *const kinds[] = {"sphere", "ball", "cube grid", "slab"};
  printf("%-10s %10s %10s\n", "points", "kind", "finalize s");
  for (int n = 1000; n <= top; n = n == 10000 ? 50000 : n == 50000 ? 1000000 : n * 10)
    for (int k = 0; k < 4; k++) printf("%-10d %10s %10.3f\n", n, kinds[k], run(k, n));
  return 0;
}
