/* Benchmark of contact detection: running-bond walls of 1,000 and 10,000
 * bricks (odd rows shifted by half a brick) and an aligned column of 10,000
 * blocks,
 * built with the builder API. Prints, per scene, the time of
 * us_structure_finalize (validation + mass properties + detection), the
 * time of a second us_detect_contacts alone (best of a few runs) and the
 * contact count. Usage: bench_contact [rows cols]. */
#include "unstack/unstack.h"

#include <stdio.h>
#include <stdlib.h>

static us_Structure *wall(int rows, int cols, double shift, us_Error *err) {
  us_Structure *s = us_structure_new(2);
  if (!s) return NULL;
  double w = 2.0, h = 1.0;
  for (int r = 0; r < rows; r++)
    for (int c = 0; c < cols; c++) {
      char id[32];
      snprintf(id, sizeof id, "b%d_%d", r, c);
      double x0 = c * w + (r % 2) * shift * w, y0 = r * h;
      double xy[8] = {x0, y0, x0 + w, y0, x0 + w, y0 + h, x0, y0 + h};
      if (us_structure_add_body(s,
                                &(us_BodyDef){.id = id,
                                              .nvert = 4,
                                              .xy = xy,
                                              .density = 1.0,
                                              .friction = -1.0},
                                err) < 0) {
        us_structure_free(s);
        return NULL;
      }
    }
  return s;
}

static int run(const char *name, us_Structure *s, us_Error *err) {
  if (!s) {
    fprintf(stderr, "%s: %s\n", name, err->msg);
    return 1;
  }
  double t0 = us_now();
  us_Status st = us_structure_finalize(s, err);
  double t_fin = us_now() - t0;
  if (st != US_OK) {
    fprintf(stderr, "%s: %s\n", name, err->msg);
    us_structure_free(s);
    return 1;
  }
  double best = 1e30;
  us_ContactSettings cs = {s->contact_tol, 0};
  for (int k = 0; k < 3 && st == US_OK; k++) {
    t0 = us_now();
    st = us_structure_detect_contacts(s, &cs, err);
    double t = us_now() - t0;
    best = t < best ? t : best;
  }
  printf("%-22s bodies %6d  contacts %6d  finalize %8.4f s  detect %8.4f s\n", name, s->nbody,
         s->ncontact, t_fin, best);
  us_structure_free(s);
  return st != US_OK;
}

int main(int argc, char **argv) {
  us_Error err;
  int fails = 0;
  if (argc == 3) {
    int rows = atoi(argv[1]), cols = atoi(argv[2]);
    return run("wall", wall(rows, cols, 0.5, &err), &err);
  }
  fails += run("wall 10x100 (1,000)", wall(10, 100, 0.5, &err), &err);
  fails += run("wall 100x100 (10,000)", wall(100, 100, 0.5, &err), &err);
  fails += run("column 10,000", wall(10000, 1, 0.0, &err), &err);
  return fails ? 1 : 0;
}
