/* Private helpers shared by the structure generators (src/gen): settings
 * checks, building blocks with generated ids, and sealing a structure. */
#ifndef US_GEN_H
#define US_GEN_H

#include "core/core.h"

/* Upper bound on the bodies one generator call may create (memory guard). */
#define US_GEN_MAX_BODIES 10000000L

/* Check the settings every generator reads (g not NULL, friction finite and
 * >= 0, density finite and > 0). `what` names the generator in messages. */
us_Status us_gen_check_common(const us_GenSettings *g, const char *what, us_Error *err);

/* Check that v is finite and > 0; message "<what>: <name> must be ...". */
us_Status us_gen_check_positive(double v, const char *what, const char *name, us_Error *err);

/* A new empty 2D structure on the ground with the settings' friction. */
us_Structure *us_gen_begin(const us_GenSettings *g, us_Error *err);
/* The same in dimension dim (2 or 3). */
us_Structure *us_gen_begin_dim(const us_GenSettings *g, int dim, us_Error *err);

/* Add polygon number `k` (0-based) with id "b<k+1>", density g->density,
 * movable, default friction. 0 or an error status. */
us_Status us_gen_add(us_Structure *s, const us_GenSettings *g, int k, int nvert,
                     const double *xy, us_Error *err);

/* Axis-aligned box [x0, x1] x [y0, y1] as polygon number k. */
us_Status us_gen_add_box(us_Structure *s, const us_GenSettings *g, int k, double x0, double y0,
                         double x1, double y1, us_Error *err);

/* 3D: the convex hull of n points (3n coordinates) as body number k. */
us_Status us_gen_add_solid(us_Structure *s, const us_GenSettings *g, int k, int n,
                           const double *xyz, us_Error *err);
/* 3D: a prism over a quadrilateral footprint (xy[8]) from z0 to z1; an
 * axis-aligned box when the footprint is [x0, x1] x [y0, y1]. Corner
 * coordinates are used as given, so faces computed from the same numbers
 * coincide bit for bit. */
us_Status us_gen_add_prism(us_Structure *s, const us_GenSettings *g, int k, const double *xy,
                           double z0, double z1, us_Error *err);
us_Status us_gen_add_box3(us_Structure *s, const us_GenSettings *g, int k, double x0, double y0,
                          double z0, double x1, double y1, double z1, us_Error *err);

/* Finalize s, stopped past g->deadline (US_ERR_TIME_LIMIT); on error free
 * it and return NULL (err set). */
us_Structure *us_gen_finish(us_Structure *s, const us_GenSettings *g, us_Error *err);
/* *stable = 1 when the whole of the finalized s stands (default stability
 * settings: the generators that keep a drop only while all stands). */
us_Status us_gen_stands(const us_Structure *s, int *stable, us_Error *err);

/* The stacker (stacker.c) with reference = 1: every row test an LP of the
 * whole structure, nothing carried from row to row (the tests compare the
 * default with it: the same verdicts, so the same structures). */
us_Structure *us_gen_stacker_ref(const us_GenSettings *g, int reference, us_Error *err);

/* Forces carried from one generated structure to the next (random3d.c,
 * stacker.c). A generator that grows a structure tests each stage on a new
 * structure; the next stage has the same bodies under the same indices
 * and more, so the contacts among the old bodies are the same (maybe in
 * another order). The forces of the last stage that stood are kept with
 * its contacts and the set that stood; the next stage's workspace takes
 * them as its local tests' base (us_stability_seed re-checks them), and
 * its tests are decided on regions around what was added since. */
typedef struct us_GenCarry {
  us_Contact *c;   /* [n] the contacts that carried force, sorted */
  double *f;       /* [n * dim] their forces (newtons) */
  int n, dim;
  int *body, nbody; /* the set that stood */
} us_GenCarry;

/* Keep forces f (a certificate of `present` on s). 0, or US_ERR_NOMEM. */
us_Status us_gen_carry_keep(us_GenCarry *k, const us_Structure *s, const us_Bitset *present,
                            const us_Forces *f, us_Error *err);
/* Seed w (a workspace on s) with the kept forces: `present` gets the kept
 * set; *taken is 1 when every kept contact is one of s's (same bodies,
 * point, normal and tangents; friction may differ, the re-check uses s's)
 * and the forces passed w's check, else 0 (nothing kept, another
 * structure below, or a failed check: the tests go as without). */
us_Status us_gen_carry_seed(const us_GenCarry *k, const us_Structure *s, us_Stability *w,
                            us_Bitset *present, int *taken, us_Error *err);
void us_gen_carry_free(us_GenCarry *k);

/* The masonry grid (regular.c, corner.c): the coordinate of half-block
 * index q, q * (w / 2), and of course boundary k, k * h. One expression
 * each, so a face shared by two blocks has bit-identical coordinates. */
static inline double us_gen_half(const us_GenSettings *g, long q) { return (double)q * (0.5 * g->width); }
static inline double us_gen_course(const us_GenSettings *g, int k) { return (double)k * g->height; }

/* Checks shared by the block generators (regular.c): common settings,
 * block size, a count `n` named `nname` >= 1, and `total` bodies within
 * the limit. */
us_Status us_gen_check_blocks(const us_GenSettings *g, const char *what, int n, const char *nname,
                              long total, us_Error *err);

/* wall3d with g->returns != 0: the wall with corner returns (corner.c). */
us_Structure *us_gen_wall3d_returns(const us_GenSettings *g, us_Error *err);

/* random3d with its counters (tests): whole tests (drops no cheap test
 * settled), those that started from carried forces, and those that went
 * to the full system (an LP over every box); reference = 1 tests each
 * whole from scratch, the full system every time (the slow path). */
typedef struct us_Random3dStats {
  long whole_tests, seeded, full_lps;
  int cone_rounds_max; /* the most 3D cone refinement rounds one test ran */
} us_Random3dStats;

/* The 3D cone refinement budget of random3d's whole tests (rounds; the
 * stability default is 60): an undecided drop is discarded anyway. */
#define US_RANDOM3D_CONE_ROUNDS 2
us_Structure *us_gen_random3d_stats(const us_GenSettings *g, int reference, us_Random3dStats *stats,
                                    us_Error *err);

/* Random numbers: us_rng_next / us_rng_below (src/core/rng.c), seeded
 * with g->seed, so a seed gives the same structure on every platform. */

#endif
