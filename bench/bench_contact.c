/* Benchmark of contact detection: running-bond walls of 1,000 and 10,000
 * bricks (odd rows shifted by half a brick), an aligned column of 10,000
 * blocks, a comb of 20,000 and of 100,000 vertices under a plate (one
 * polygon with many vertices: detection was quadratic in them, 8.8 s and
 * more than 5 minutes) and an arch of 20,000 voussoirs (thin blocks at
 * every angle, whose boxes overlap thousands of others), built with the
 * builder API and the generator. Prints, per scene, the time of
 * us_structure_finalize (validation + mass properties + detection), the
 * time of a second detection alone (best of a few runs) and the contact
 * count. Usage: bench_contact [rows cols]. */
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

/* A comb of `nv` vertices (teeth 1 wide, pitch 2) on the ground and a
 * plate resting on its teeth. */
static us_Structure *comb(int nv, us_Error *err) {
  int teeth = (nv - 2) / 4, n = 2 + 4 * teeth;
  double w = 2.0 * teeth - 1.0, *xy = malloc((size_t)n * 2 * sizeof *xy), *p = xy;
  us_Structure *s = us_structure_new(2);
  if (!xy || !s) {
    free(xy);
    us_structure_free(s);
    return NULL;
  }
  *p++ = 0, *p++ = 0, *p++ = w, *p++ = 0;
  for (int t = teeth - 1; t >= 0; t--) {
    double x = 2.0 * t;
    *p++ = x + 1, *p++ = 1, *p++ = x + 1, *p++ = 2, *p++ = x, *p++ = 2, *p++ = x, *p++ = 1;
  }
  double plate[8] = {0, 2, w, 2, w, 3, 0, 3};
  us_BodyDef d = us_default_body_def();
  d.id = "comb", d.nvert = n, d.xy = xy;
  int ok = us_structure_add_body(s, &d, err) >= 0;
  d.id = "plate", d.nvert = 4, d.xy = plate;
  ok = ok && us_structure_add_body(s, &d, err) >= 0;
  free(xy);
  if (!ok) {
    us_structure_free(s);
    return NULL;
  }
  return s;
}

/* The generator's arch finalizes itself: its detection time is measured
 * by run() as the re-detection only (finalize shows as 0). */
static us_Structure *arch(int n, us_Error *err) {
  us_GenSettings g = us_gen_default_settings();
  g.n = n;
  return us_gen_arch(&g, err);
}

static int run(const char *name, us_Structure *s, us_Error *err) {
  if (!s) {
    fprintf(stderr, "%s: %s\n", name, err->msg);
    return 1;
  }
  double t0 = us_now();
  us_Status st = us_structure_is_finalized(s) ? US_OK : us_structure_finalize(s, err);
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
  fails += run("comb 20,000 vertices", comb(20002, &err), &err);
  fails += run("comb 100,000 vertices", comb(100002, &err), &err);
  fails += run("arch 20,000", arch(20000, &err), &err);
  return fails ? 1 : 0;
}
