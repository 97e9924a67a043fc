/* The plumb-line load path: a stable proof for an added body without an LP
 * (plumb.c; the argument is in docs/local.md, "Plumb lines").
 *
 * Given forces f that hold sub-assembly B (normalized as in
 * equilibrium.h) and bodies added to it, route each added body's weight
 * straight down: along the vertical line through its centre of mass,
 * from body to supporting body, to the ground or a fixed body. Each hop
 * adds a vertical force to the support contacts of the body above, split
 * between two of its contact points by the lever rule (2D), or among the
 * three corners of a triangle of them that holds the line by barycentric
 * weights (3D), so that it acts on the line. Every body on the line then receives and passes on the same
 * vertical force on the same line: its net force and torque do not
 * change. The added forces lie in the cones (each hop's is checked), and
 * cones are convex, so f plus them holds B and the added bodies; the
 * caller re-checks the changed bodies' certificate all the same.
 *
 * Cost: O(path length x contacts per body); no LP. It fails (and changes
 * nothing) when a line meets no support below it at its position (a
 * cantilever, an arch's voussoir), or a support whose cone does not hold
 * the vertical (a steep contact with little friction). In 3D the triangle
 * search costs O(k^3) in a body's k support points, and bodies with more
 * than PLUMB_MAX_TRI of them are left to the LPs.
 */
#ifndef US_STABILITY_PLUMB_H
#define US_STABILITY_PLUMB_H

#include "core/core.h"

typedef struct us_PlumbLine {
  int body;
  double pos[2];         /* horizontal position of the line (1 axis in 2D) */
  double load;           /* its vertical force, in units of the total weight */
} us_PlumbLine;

typedef struct us_PlumbSupport {
  int contact;           /* a support contact point of the body */
  int below;             /* the body on its other side (US_GROUND, fixed, movable) */
  double pos[2];         /* its horizontal position */
} us_PlumbSupport;

typedef struct us_Plumb {
  /* the structure, its incidence (body -> contacts) and frame */
  const us_Structure *s;
  const int *inc_start, *inc;
  double up[3];          /* against gravity */
  int nax;               /* horizontal axes: 1 in 2D, 2 in 3D */
  double hz[2][3];       /* the horizontal axes */
  double mass_total;     /* M: a body's weight is m_i / M in force units */
  /* per body: its support points whose cone holds the vertical
     (sup[sup_start[u] .. sup_start[u + 1])) and its width along hz */
  int *sup_start;
  us_PlumbSupport *sup;
  double *width;
  /* undo log: contact index and its force before each change */
  int *log_c;
  double *log_f;
  int nlog, cap_c, cap_f;
  /* the bodies whose forces changed (the path), marked in mark[] */
  int *path, npath, cap_path;
  unsigned char *mark;   /* [nbody] */
  us_PlumbLine *stack;   /* lines still to route */
  int nstack, cap_stack;
} us_Plumb;

/* 0, or -1 on OOM. up: unit vector against gravity. */
int us_plumb_init(us_Plumb *p, const us_Structure *s, const int *inc_start, const int *inc,
                  const double up[3], double mass_total);
void us_plumb_free(us_Plumb *p);

/* The horizontal coordinates of point x in the frame of p (hz; the second
 * is 0 in 2D). The local tests measure their footprints in it too. */
void us_plumb_horizontal(const us_Plumb *p, const double *x, double out[2]);

/* Route the weights of added[0..nadd) (present in cur) down their plumb
 * lines, adding to f. 1: routed, f changed, p->path lists every body
 * whose forces changed; 0: some line found no admissible support, f
 * unchanged; -1: OOM, f unchanged. */
int us_plumb_route(us_Plumb *p, const us_Bitset *cur, const int *added, int nadd, double *f);

/* Undo the last successful route (f back to its values before it). */
void us_plumb_undo(us_Plumb *p, double *f);

#endif
