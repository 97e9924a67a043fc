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

/* A memoised line (lazy routing): a load on `body` at `pos` takes the
 * hop (k, w) and goes on as the child lines (child, cw): the children's
 * shares of the load). level: 1 + the children's largest (0: none), so a
 * line is always above its children. pending: load not yet added to f. */
typedef struct us_PlumbEntry {
  int body;
  double pos[2];
  int n, k[3];
  double w[3];
  int nchild, child[3];
  double cw[3];
  int level;
  long slot;             /* its slot in the hash table */
  double pending;
  int in_heap;
} us_PlumbEntry;

/* A support point (its contact) of a body that a route may not use. */
typedef struct us_PlumbExcl {
  int body, contact;
} us_PlumbExcl;

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
  /* signed routes: each body's summed force and moment, a max-heap of
     the bodies with some, by height (plumb.c, route_signed) */
  double *sgF, *sgM;
  unsigned char *sg_in;
  int *sg_heap, nsg;
  int *sg_skip;          /* a presser's release does not rest on its cantilever */
  int tipped;            /* us_plumb_lever found its body beyond its supports
                            with nothing pressing it (the caller clears it) */
  /* lazy routing: the memo of checked lines, valid while every body of
     dep is present; the lines with pending load in a max-heap by level */
  us_PlumbEntry *ent;
  int nent, cap_ent;
  long *tab, tab_cap;    /* hash (body, pos) -> entry + 1, 0 empty */
  us_Bitset dep;
  int *heap, nheap, cap_heap;
  int *added_e, nadded_e, cap_added_e; /* this route's entries, to take back */
  double *added_l;       /* their pending loads before it */
  int cap_added_l;
  struct us_PlumbFrame *frames; /* the lazy route's stack of lines being built */
  int cap_frames;
  us_PlumbExcl *excl;    /* the lazy route's excluded support points */
  int nexcl, cap_excl;
  int nnew;              /* lines the last lazy route checked (new entries) */
  double worst_line;     /* their largest hop residual (relative) */
} us_Plumb;

/* 0, or -1 on OOM. up: unit vector against gravity. */
int us_plumb_init(us_Plumb *p, const us_Structure *s, const int *inc_start, const int *inc,
                  const double up[3], double mass_total);
void us_plumb_free(us_Plumb *p);

/* The horizontal coordinates of point x in the frame of p (hz; the second
 * is 0 in 2D). The local tests measure their footprints in it too. */
void us_plumb_horizontal(const us_Plumb *p, const double *x, double out[2]);

/* The eager routing, each path written out at once: the local tests use
 * the lazy routing below; this one is its reference in the tests.
 * Route the weights of added[0..nadd) (present in cur) down their plumb
 * lines, adding to f. 1: routed, f changed, p->path lists every body
 * whose forces changed; 0: some line found no admissible support, f
 * unchanged; -1: OOM, f unchanged. */
int us_plumb_route(us_Plumb *p, const us_Bitset *cur, const int *added, int nadd, double *f);

/* The same routes as a region LP's starting point (local.c): each added
 * body's lines as far as they find hops, kept in f (logged) where a line
 * stops. f then holds no certificate: the caller takes the route back with
 * us_plumb_undo once the LP has read it. 0, or -1 on OOM (undo still
 * restores f). */
int us_plumb_route_hint(us_Plumb *p, const us_Bitset *cur, const int *added, int nadd,
                        double *f);

/* The lever (2D, docs/local.md "Levers"): added body a whose centre lies
 * beyond its outermost support s (a cantilever) and a body d resting on a
 * across s (its counterweight), at point q: d pushes a down at q with
 * load = w (c - s) / (s - q), a's line at s carries w + load down, and d
 * releases load from its other supports at q (a negative line, which may
 * take a load off a support and put part of it on another; no line rests
 * on a). Without a presser, a's own line (a within its supports; else it
 * sets p->tipped). The signed lines merge per body (a force and a moment,
 * each body routed once, highest first), and a load beyond a cantilever's
 * support below takes the same rule with that cantilever's presser when
 * its own far support has no room for the extended rule's release.
 * Eager, into f (logged: us_plumb_undo takes it back); p->path lists
 * every body whose forces changed (every changed contact has both sides
 * there, or a held body). Nothing is proven here: a release may leave a
 * contact outside its cone, so the caller re-checks the path's bodies. 1
 * routed, 0 no lever or no route (f unchanged), -1 OOM (f unchanged). */
int us_plumb_lever(us_Plumb *p, const us_Bitset *cur, int a, double *f);
/* Undo the last successful route (f back to its values before it). */
void us_plumb_undo(us_Plumb *p, double *f);

/* Lazy routing (docs/local.md, "Plumb lines, memoised"): the same lines,
 * but each (body, position) is routed and checked once and memoised, and
 * the added loads wait on the first line as pending load. A line's hop
 * holds any positive load (its forces scale, the cones are cones) and
 * stays valid while the bodies it rests on are present (more bodies only
 * add contacts with zero force), so f plus the pending loads pushed down
 * the memoised lines is a certificate. Cost per added body: its new lines
 * only (amortised O(1) on walls, whose lines repeat), not its path.
 * us_plumb_lazy_valid: cur holds every body the memo rests on. Route: 1
 * routed (p->nnew new lines, each checked: present sides, unit force in
 * its cone, weights >= 0 summing to 1, resultant on the line; worst
 * relative residual in p->worst_line), 0 no route (no pending load
 * changed), -1 OOM. Materialize pushes every pending load into f in
 * level order, each line once (0 or -1 OOM); drop forgets them (f was
 * replaced by a full certificate); flush empties the memo (nothing may be
 * pending). */
int us_plumb_lazy_valid(const us_Plumb *p, const us_Bitset *cur);
int us_plumb_route_lazy(us_Plumb *p, const us_Bitset *cur, const int *added, int nadd,
                        double tol);
int us_plumb_materialize(us_Plumb *p, double *f);
void us_plumb_drop(us_Plumb *p);
void us_plumb_flush(us_Plumb *p);

#endif
