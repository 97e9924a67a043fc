/* Each body's edge grid for the narrow phases (overlap.c, pair.c), built
 * on first use with the body's own tolerance as padding (none in the
 * reference mode, which pads without limit). Below both narrow phases and
 * the detection driver (detect.c) that owns the us_Detect context. */
#include "contact.h"

#include <math.h>

/* A small polygon's slot: its own if it holds one, else the least
 * recently used one (initializing a small one allocates nothing). */
static us_EdgeGrid *small_grid(us_Detect *d, int i, double pad) {
  const us_Body *b = &d->s->bodies[i];
  int k = d->slot_body[0] == i ? 0 : d->slot_body[1] == i ? 1 : 1 - d->slot_last;
  if (d->slot_body[k] != i) {
    us_edge_grid_init(&d->slot[k], b->verts, b->nvert, pad);
    d->slot_body[k] = i;
  }
  d->slot_last = k;
  return &d->slot[k];
}

us_EdgeGrid *us_detect_grid(us_Detect *d, int i) {
  const us_Body *b = &d->s->bodies[i];
  double pad = d->reference ? INFINITY : d->tol[i];
  if (b->nvert <= US_EDGE_GRID_MIN) return small_grid(d, i, pad);
  if (!d->built[i] && us_edge_grid_init(&d->grid[i], b->verts, b->nvert, pad)) return NULL;
  d->built[i] = 1;
  return &d->grid[i];
}

/* The message of a detection cut by its deadline (detect.c, detect3.c). */
us_Status us_detect_timeout(int done, int total, us_Error *err) {
  return us_error_set(err, US_ERR_TIME_LIMIT,
                      "time limit reached during contact detection (%d of %d pairs of bodies)",
                      done, total);
}
