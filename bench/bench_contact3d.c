/* Contact detection in 3D on the generators' structures of about 10,000
 * bodies: prints bodies, contacts and the seconds of us_detect_contacts
 * (the structure is generated and finalized first, untimed). Usage:
 * bench_contact3d [SIZE] (pyramid3d courses; the wall and tower follow:
 * a wall of (10 SIZE / 3)^2 bricks, a tower of 11 SIZE^2 boxes turned up to 30 degrees). Default 30. */
#include "unstack/unstack.h"

#include <stdio.h>
#include <stdlib.h>

static void run(const char *name, us_Structure *s, us_Error *err) {
  if (!s) {
    fprintf(stderr, "%s: %s\n", name, err->msg);
    exit(1);
  }
  us_ContactList l = {NULL, 0, 0};
  us_ContactSettings cs = {0, 0};
  double best = 1e30;
  for (int rep = 0; rep < 3; rep++) {
    double t0 = us_now();
    if (us_detect_contacts(s, &cs, &l, err)) exit(1);
    double t = us_now() - t0;
    best = t < best ? t : best;
  }
  printf("%-10s %6d bodies %7d contacts  detect %.3f s (best of 3)\n", name, s->nbody, l.n, best);
  us_contact_list_free(&l);
  us_structure_free(s);
}

int main(int argc, char **argv) {
  int n = argc > 1 ? atoi(argv[1]) : 30;
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  g.n = n;
  run("pyramid3d", us_gen_pyramid3d(&g, &err), &err);
  g.rows = g.cols = n * 10 / 3;
  run("wall3d", us_gen_wall3d(&g, &err), &err);
  g.n = 11 * n * n, g.jitter = 30;
  run("tower", us_gen_tower(&g, &err), &err);
  return 0;
}
