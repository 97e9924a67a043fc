/* The random stacker in 3D: boxes dropped at random positions over a square
 * area, each resting on the highest boxes under it, kept only while the
 * whole structure still stands.
 *
 * Settings: g->n boxes wanted; boxes are 1 x 1 (x, y) and g->height high;
 * g->width is the side W of the square area in boxes (W = 1: a column);
 * g->seed the seed; g->max_tries the drops in a row that may be discarded
 * before the generator stops with fewer boxes.
 *
 * Algorithm: positions are quarter-box steps, so the area is a grid of
 * G x G cells of side 1/4 (G = 4 (W - 1) + 4, W rounded down to a quarter)
 * and a box covers 4 x 4 cells. The grid is a height map: each cell holds
 * the number of box heights stacked over it (its top level). A drop draws
 * a corner cell (qx, qy) uniformly; the box's level is the highest top over
 * its 16 cells, so it rests on every box of that level under it (a face
 * contact of positive area) and overlaps nothing: finding its support
 * costs 16 cell reads, whatever the number of boxes. All coordinates are
 * multiples of 1/4 and of h, so contacts are exact.
 *
 * Keeping a drop: a box on the ground (level 0) is kept without a test (the
 * previous structure's forces plus the ground under the new box hold
 * everything). Otherwise the box alone, its neighbours held still, must
 * stand (candidate_alone: a necessary condition, one tiny LP); then the
 * structure of the kept boxes plus the new one
 * is built, finalized and tested whole with the default stability settings
 * (the LP); the box is kept iff the verdict is stable, and the height map
 * is raised over its cells. The run stops when n boxes are kept, or after
 * max_tries discarded drops in a row: the structure then has fewer boxes
 * (s->nbody says how many), never an error.
 *
 * Cost: a tested drop rebuilds and finalizes the structure (contact
 * detection, O(k log k) for k boxes) and solves one LP over k bodies; the
 * LP dominates, so a run is about quadratic in n (measured figures in
 * docs/format.md). g->deadline (a us_now() time; 0: none) is read before
 * every drop: past it, US_ERR_TIME_LIMIT. Randomness: splitmix64 seeded with g->seed, so a seed
 * gives the same structure on every platform. Bodies "b1", "b2", ... in the
 * order they were kept. */
#include "gen.h"

#include <math.h>
#include <stdlib.h>

typedef struct Drops {
  const us_GenSettings *g;
  uint64_t rng;
  long nq;          /* corner positions per axis: 4 (W - 1) + 1 */
  long side;        /* cells per axis: nq + 3 */
  int *top;         /* [side * side] top level of each cell */
  int n;            /* boxes kept */
  long *q;          /* [2 * n_wanted] corner cells (qx, qy) of the kept boxes */
  int *level;       /* [n_wanted] level of each kept box */
} Drops;

static us_Status check_random3d(const us_GenSettings *g, us_Error *err) {
  us_Status st = us_gen_check_common(g, "random3d", err);
  if (!st) st = us_gen_check_positive(g->height, "random3d", "block height", err);
  if (!st && !(g->width >= 1.0 && g->width <= 256.0))
    st = us_error_set(err, US_ERR_USAGE, "random3d: width (in boxes) must be in [1, 256], got %g",
                      g->width);
  if (!st && (g->n < 1 || g->n > 100000))
    st = us_error_set(err, US_ERR_USAGE, "random3d: blocks must be in 1..100000, got %d", g->n);
  if (!st && g->max_tries < 1)
    st = us_error_set(err, US_ERR_USAGE, "random3d: max_tries must be >= 1, got %d", g->max_tries);
  return st;
}

/* The highest top level over the 4 x 4 cells from corner (qx, qy). */
static int support_level(const Drops *d, long qx, long qy) {
  int lv = 0;
  for (long y = qy; y < qy + 4; y++)
    for (long x = qx; x < qx + 4; x++) lv = US_MAX(lv, d->top[y * d->side + x]);
  return lv;
}

/* Box i of the kept boxes, or the candidate when i == d->n. */
static us_Status add_drop(us_Structure *s, const Drops *d, int i, us_Error *err) {
  double x0 = 0.25 * (double)d->q[2 * i], y0 = 0.25 * (double)d->q[2 * i + 1];
  double h = d->g->height;
  return us_gen_add_box3(s, d->g, i, x0, y0, (double)d->level[i] * h, x0 + 1.0, y0 + 1.0,
                         (double)(d->level[i] + 1) * h, err);
}

/* The finalized structure of boxes 0..count-1, or NULL. */
static us_Structure *build(const Drops *d, int count, us_Error *err) {
  us_Structure *s = us_gen_begin_dim(d->g, 3, err);
  us_Status st = s ? US_OK : US_ERR_NOMEM;
  for (int i = 0; !st && i < count; i++) st = add_drop(s, d, i, err);
  if (st) {
    us_structure_free(s);
    return NULL;
  }
  return us_gen_finish(s, err);
}

/* Can the candidate (box d->n) stand with every box that could touch it
 * held still (its level and the ones below and above, footprints within
 * one box: a box above may touch its top edges)? A
 * necessary condition: forces that held the whole would, restricted to
 * the candidate's contacts, hold it against supports that do not move. So
 * a candidate that fails here is discarded without the whole's LP (most
 * discarded drops are: they overhang). One LP of 6 rows. */
static us_Status candidate_alone(const Drops *d, int *stable, us_Error *err) {
  us_Structure *s = us_gen_begin_dim(d->g, 3, err);
  us_Status st = s ? US_OK : US_ERR_NOMEM;
  long qx = d->q[2 * d->n], qy = d->q[2 * d->n + 1];
  int lv = d->level[d->n], k = 0;
  for (int i = 0; !st && i < d->n; i++) {
    if (d->level[i] < lv - 1 || d->level[i] > lv + 1) continue;
    if (labs(d->q[2 * i] - qx) > 4 || labs(d->q[2 * i + 1] - qy) > 4) continue;
    st = add_drop(s, d, i, err);
    if (!st) s->bodies[k++].fixed = 1;
  }
  if (!st) st = add_drop(s, d, d->n, err);
  if (st) {
    us_structure_free(s);
    return st;
  }
  s = us_gen_finish(s, err);
  if (!s) return err->code;
  st = us_gen_stands(s, stable, err);
  us_structure_free(s);
  return st;
}

/* Does the candidate (box d->n, already written into q and level) keep
 * the whole standing? Boxes on the ground always do; a candidate that
 * cannot stand with its neighbours held still never does. */
static us_Status candidate_stands(const Drops *d, int *stable, us_Error *err) {
  *stable = 1;
  if (d->level[d->n] == 0) return US_OK;
  us_Status st0 = candidate_alone(d, stable, err);
  if (st0 || !*stable) return st0;
  us_Structure *s = build(d, d->n + 1, err);
  if (!s) return err->code;
  us_Status st = us_gen_stands(s, stable, err);
  us_structure_free(s);
  return st;
}

/* One drop: *kept = 1 when the box was kept (height map raised). */
static us_Status drop(Drops *d, int *kept, us_Error *err) {
  long qx = us_rng_below(&d->rng, d->nq), qy = us_rng_below(&d->rng, d->nq);
  d->q[2 * d->n] = qx, d->q[2 * d->n + 1] = qy;
  d->level[d->n] = support_level(d, qx, qy);
  us_Status st = candidate_stands(d, kept, err);
  if (st || !*kept) return st;
  for (long y = qy; y < qy + 4; y++)
    for (long x = qx; x < qx + 4; x++) d->top[y * d->side + x] = d->level[d->n] + 1;
  d->n++;
  return US_OK;
}

static us_Status run(Drops *d, us_Error *err) {
  us_Status st = US_OK;
  for (int failed = 0; !st && d->n < d->g->n && failed < d->g->max_tries;) {
    int kept = 0;
    if (us_past(d->g->deadline))
      return us_error_set(err, US_ERR_TIME_LIMIT, "random3d: time limit reached (%d of %d boxes placed)",
                          d->n, d->g->n);
    st = drop(d, &kept, err);
    failed = kept ? 0 : failed + 1;
  }
  return st;
}

us_Structure *us_gen_random3d(const us_GenSettings *g, us_Error *err) {
  us_Error local;
  if (!err) err = &local; /* the steps below read err->code */
  if (check_random3d(g, err)) return NULL;
  Drops d = {g, (uint64_t)g->seed, (long)floor(4.0 * (g->width - 1.0)) + 1, 0, NULL, 0, NULL, NULL};
  d.side = d.nq + 3;
  d.top = us_calloc((size_t)(d.side * d.side), sizeof *d.top);
  d.q = us_malloc((size_t)g->n * 2 * sizeof *d.q);
  d.level = us_malloc((size_t)g->n * sizeof *d.level);
  us_Status st = d.top && d.q && d.level ? run(&d, err)
                                         : us_error_set(err, US_ERR_NOMEM, "random3d: out of memory");
  us_Structure *s = st ? NULL : build(&d, d.n, err);
  us_free(d.top);
  us_free(d.q);
  us_free(d.level);
  return s;
}
