/* Each body's edge grid for the narrow phases (overlap.c, pair.c), built
 * on first use with the body's own tolerance as padding (none in the
 * reference mode, which pads without limit). Below both narrow phases and
 * the detection driver (detect.c) that owns the us_Detect context. */
#include "contact.h"

#include <math.h>

us_EdgeGrid *us_detect_grid(us_Detect *d, int i) {
  const us_Body *b = &d->s->bodies[i];
  double pad = d->reference ? INFINITY : d->tol[i];
  if (!d->built[i] && us_edge_grid_init(&d->grid[i], b->verts, b->nvert, pad)) return NULL;
  d->built[i] = 1;
  return &d->grid[i];
}
