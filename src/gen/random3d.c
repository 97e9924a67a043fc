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
 * Two cheaper tests come first for a box above the ground. A plumb line
 * (sufficient, no LP): the vertical through the box's centre is carried
 * down, at each level by a box below whose footprint contains it (closed),
 * or split among three corners of the contact patches below whose
 * triangle contains it, each corner's line carried on in turn, down to
 * the ground. The weight then travels as vertical forces at patch corners
 * (normal: contacts are horizontal, so inside every cone) whose resultant
 * on each box stays on the line, leaving every box's balance unchanged;
 * the kept structure stood with some forces, and those plus these hold it
 * with the new box (cones are convex; no box can lie on the new one, its
 * level is the top of its cells): kept, as the full LP would. Otherwise
 * two necessary tests (any part of a standing whole stands with the rest
 * held still): the box alone, then the box with the boxes under it
 * (transitively) movable; each failure discards the drop after an LP over
 * those boxes only. So the outputs are the same as testing every drop
 * whole.
 *
 * Whole tests start from forces: the last whole that stood left its
 * checked forces; they are carried to the new structure (same boxes, same
 * contacts) and handed to its workspace as the local tests' base
 * (us_stability_seed re-checks them), the boxes kept since without a
 * whole test (plumb lines, the ground) are added one by one, then the
 * candidate: each test is decided on a region around what it adds
 * (docs/local.md), exactly, and goes to the full system only when the
 * region cannot decide (about one whole test in four on W = 8).
 *
 * Cost: a drop the cheap tests do not settle rebuilds and finalizes the
 * structure (contact detection, O(k log k) for k boxes); its region LPs
 * are small, and the full-system LPs over k bodies that remain dominate.
 * Past about 150 boxes on W = 8 some of them sit on the boundary of the
 * friction cones: the 3D cone refinement (docs/cones3d.md) would run its
 * 60 rounds over the whole (10 to 50 s each) and end undecided. A drop
 * needs no proof of falling, so whole tests refine at most
 * US_RANDOM3D_CONE_ROUNDS (2) rounds (us_stability_set_cone_rounds): past
 * them the outer polygons' forces are the claim, kept only if their
 * certificate passes, else the drop is undecided and discarded. A budget
 * decides a few drops otherwise than 60 rounds would (kept or discarded,
 * never kept uncertified); measured figures in docs/format.md. g->deadline (a us_now() time;
 * 0: none) is read before every drop: past it, US_ERR_TIME_LIMIT.
 * Randomness: splitmix64 seeded with g->seed, so a seed gives the same
 * structure on every platform. Bodies "b1", "b2", ... in the
 * order they were kept. */
#include "gen.h"
#include "stability/stability.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct Drops {
  const us_GenSettings *g;
  uint64_t rng;
  long nq;          /* corner positions per axis: 4 (W - 1) + 1 */
  long side;        /* cells per axis: nq + 3 */
  int *top;         /* [side * side] top level of each cell */
  int n;            /* boxes kept */
  long *q;          /* [2 * n_wanted] corner cells (qx, qy) of the kept boxes */
  int *level;       /* [n_wanted] level of each kept box */
  int *owner;       /* [side * side] the box on top of each cell, or -1 */
  int *below;       /* [16 * n_wanted] per box and cell: the box under it in
                       contact (its top at the box's level), or -1 */
  int reference;    /* 1: every whole test from scratch (no carried forces) */
  us_Random3dStats *stats; /* counters, or NULL */
  /* the last whole test that stood: its forces (the boxes 0..kn-1) */
  int kn;
  us_GenCarry carry;
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

/* Box i's cells: the boxes under them in contact (from the height map as
 * it is before box i is placed). */
static void note_below(Drops *d, int i) {
  long qx = d->q[2 * i], qy = d->q[2 * i + 1];
  for (int k = 0; k < 16; k++) {
    long c = (qy + k / 4) * d->side + qx + k % 4;
    d->below[16 * i + k] = d->level[i] > 0 && d->top[c] == d->level[i] ? d->owner[c] : -1;
  }
}

/* Support points of box b: the corners of its contact patches with the
 * boxes under it (overlaps of footprints), each with that box; returns
 * the count (at most 64). Coordinates in quarter boxes. */
static int supports(const Drops *d, int b, long pt[][2], int *box) {
  int m = 0;
  for (int k = 0; k < 16; k++) {
    int j = d->below[16 * b + k], seen = 0;
    for (int r = 0; r < k; r++) seen |= d->below[16 * b + r] == j;
    if (j < 0 || seen) continue;
    long x0 = US_MAX(d->q[2 * b], d->q[2 * j]), y0 = US_MAX(d->q[2 * b + 1], d->q[2 * j + 1]);
    long x1 = US_MIN(d->q[2 * b], d->q[2 * j]) + 4, y1 = US_MIN(d->q[2 * b + 1], d->q[2 * j + 1]) + 4;
    for (int c = 0; c < 4; c++, m++)
      pt[m][0] = c & 1 ? x1 : x0, pt[m][1] = c & 2 ? y1 : y0, box[m] = j;
  }
  return m;
}

static long cross(const long a[2], const long b[2], long px, long py) {
  return (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0]);
}

/* Is (px, py) in the closed triangle a b c (of non-zero area)? Exact. */
static int in_triangle(const long a[2], const long b[2], const long c[2], long px, long py) {
  long s1 = cross(a, b, px, py), s2 = cross(b, c, px, py), s3 = cross(c, a, px, py);
  long area = cross(a, b, c[0], c[1]);
  if (area == 0) return 0;
  return area > 0 ? s1 >= 0 && s2 >= 0 && s3 >= 0 : s1 <= 0 && s2 <= 0 && s3 <= 0;
}

/* Can a vertical load on box b at (px, py) be carried to the ground: the
 * point is a support point, or in a triangle of them, whose lines can be
 * carried on (docs/local.md, "Plumb lines")? *budget bounds the work (the
 * search may branch at every level); when it runs out: no. */
static int route(const Drops *d, int b, long px, long py, long *budget) {
  if (d->level[b] == 0) return 1;
  if (--*budget < 0) return 0;
  long pt[64][2];
  int box[64], m = supports(d, b, pt, box);
  for (int k = 0; k < m; k++) /* a patch containing the point */
    if (d->q[2 * box[k]] <= px && px <= d->q[2 * box[k]] + 4 && d->q[2 * box[k] + 1] <= py &&
        py <= d->q[2 * box[k] + 1] + 4)
      return route(d, box[k], px, py, budget);
  for (int a = 0; a < m; a++)
    for (int e = a + 1; e < m; e++)
      for (int c = e + 1; c < m && *budget >= 0; c++)
        if (in_triangle(pt[a], pt[e], pt[c], px, py) && route(d, box[a], pt[a][0], pt[a][1], budget) &&
            route(d, box[e], pt[e][0], pt[e][1], budget) && route(d, box[c], pt[c][0], pt[c][1], budget))
          return 1;
  return 0;
}

/* The plumb line of box i from its centre (a sufficient test, no LP). */
static int plumb_line(const Drops *d, int i) {
  long budget = 4096;
  return route(d, i, d->q[2 * i] + 2, d->q[2 * i + 1] + 2, &budget);
}

/* Box i of the kept boxes, or the candidate when i == d->n. */
static us_Status add_drop(us_Structure *s, const Drops *d, int i, us_Error *err) {
  double x0 = 0.25 * (double)d->q[2 * i], y0 = 0.25 * (double)d->q[2 * i + 1];
  double h = d->g->height;
  return us_gen_add_box3(s, d->g, i, x0, y0, (double)d->level[i] * h, x0 + 1.0, y0 + 1.0,
                         (double)(d->level[i] + 1) * h, err);
}

/* The finalized structure of boxes 0..count-1, or NULL; with `movable`,
 * the boxes it marks 0 are fixed. */
static us_Structure *build(const Drops *d, int count, const char *movable, us_Error *err) {
  us_Structure *s = us_gen_begin_dim(d->g, 3, err);
  us_Status st = s ? US_OK : US_ERR_NOMEM;
  for (int i = 0; !st && i < count; i++) {
    st = add_drop(s, d, i, err);
    if (!st && movable) s->bodies[i].fixed = !movable[i];
  }
  if (st) {
    us_structure_free(s);
    return NULL;
  }
  return us_gen_finish(s, d->g, err);
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
  s = us_gen_finish(s, d->g, err);
  if (!s) return err->code;
  st = us_gen_stands(s, stable, err);
  us_structure_free(s);
  return st;
}

/* Can the candidate and the boxes under it (transitively, through the
 * contacts in `below`) stand with every other box held still? Necessary,
 * as candidate_alone is (forces that held the whole hold any part of it
 * against the rest held still), with a larger part: the supports that
 * give way under the new load are found by an LP over them only. */
static us_Status candidate_column(const Drops *d, int *stable, us_Error *err) {
  char *in = us_calloc((size_t)d->n + 1, 1);
  int *stack = us_malloc(((size_t)d->n + 1) * sizeof *stack), ns = 0;
  if (in && stack) stack[ns++] = d->n, in[d->n] = 1;
  while (ns > 0) /* the closure below the candidate */
    for (int b = stack[--ns], k = 0; k < 16; k++) {
      int j = d->below[16 * b + k];
      if (j >= 0 && !in[j]) in[j] = 1, stack[ns++] = j;
    }
  us_Structure *s = in && stack ? build(d, d->n + 1, in, err) : NULL;
  us_Status st = s ? us_gen_stands(s, stable, err)
                   : in && stack ? err->code : us_error_set(err, US_ERR_NOMEM, "random3d: out of memory");
  us_structure_free(s);
  us_free(in);
  us_free(stack);
  return st;
}

/* Does the whole (the kept boxes plus the candidate) stand? The kept
 * boxes 0..kn-1 of the last whole test that stood are handed to the
 * workspace with that test's forces (re-checked there) as the local
 * tests' base, so the test is decided on a region around what was added
 * since (docs/local.md): the boxes kept by plumb lines or on the ground,
 * and the candidate. Exact either way; the full system when the region
 * cannot decide. */
static us_Status whole_stands(Drops *d, int *stable, us_Error *err) {
  us_Structure *s = build(d, d->n + 1, NULL, err);
  if (!s) return err->code;
  us_StabilitySettings set = us_stability_default_settings();
  set.local = d->reference ? -1 : 1;
  us_Stability *w = us_stability_new(s, &set, err);
  us_stability_set_cone_rounds(w, US_RANDOM3D_CONE_ROUNDS); /* undecided: discarded */
  us_Bitset all = {0};
  us_StabilityResult res;
  us_stability_result_init(&res);
  us_Status st = w ? US_OK : err->code;
  if (!st && us_bitset_init(&all, s->nbody)) st = us_error_set(err, US_ERR_NOMEM, "random3d: out of memory");
  int taken = 0;
  if (!st && !d->reference && d->kn > 0) st = us_gen_carry_seed(&d->carry, s, w, &all, &taken, err);
  /* the boxes kept since without a whole test (plumb lines, the ground)
     one by one, so that the candidate's test adds it alone */
  for (int i = d->kn; !st && taken && i < d->n; i++) {
    us_bitset_set(&all, i);
    st = us_stability_test(w, &all, &res, err);
  }
  for (int i = 0; !st && i < s->nbody; i++) us_bitset_set(&all, i);
  if (!st) st = us_stability_test(w, &all, &res, err);
  *stable = !st && res.verdict == US_STABLE;
  if (!st && d->stats) {
    d->stats->whole_tests++, d->stats->seeded += taken;
    d->stats->full_lps += d->reference ? 1 : us_stability_info(w)->local_global;
    int r = us_stability_cone_rounds_max(w);
    if (r > d->stats->cone_rounds_max) d->stats->cone_rounds_max = r;
  }
  if (!st && *stable && !d->reference) {
    for (int i = 0; i < s->nbody; i++) us_bitset_set(&all, i);
    st = us_gen_carry_keep(&d->carry, s, &all, &res.forces, err);
    d->kn = d->n + 1;
  }
  us_stability_result_free(&res);
  us_bitset_free(&all);
  us_stability_free(w);
  us_structure_free(s);
  return st;
}

/* Does the candidate (box d->n, already written into q and level) keep
 * the whole standing? Boxes on the ground always do; a candidate that
 * cannot stand with its neighbours held still never does. */
static us_Status candidate_stands(Drops *d, int *stable, us_Error *err) {
  *stable = 1;
  if (d->level[d->n] == 0 || plumb_line(d, d->n)) return US_OK;
  us_Status st0 = candidate_alone(d, stable, err);
  if (!st0 && *stable) st0 = candidate_column(d, stable, err);
  if (st0 || !*stable) return st0;
  return whole_stands(d, stable, err);
}

/* One drop: *kept = 1 when the box was kept (height map raised). */
static us_Status drop(Drops *d, int *kept, us_Error *err) {
  long qx = us_rng_below(&d->rng, d->nq), qy = us_rng_below(&d->rng, d->nq);
  d->q[2 * d->n] = qx, d->q[2 * d->n + 1] = qy;
  d->level[d->n] = support_level(d, qx, qy);
  note_below(d, d->n);
  us_Status st = candidate_stands(d, kept, err);
  if (st || !*kept) return st;
  for (long y = qy; y < qy + 4; y++)
    for (long x = qx; x < qx + 4; x++)
      d->top[y * d->side + x] = d->level[d->n] + 1, d->owner[y * d->side + x] = d->n;
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
  return us_gen_random3d_stats(g, 0, NULL, err);
}

us_Structure *us_gen_random3d_stats(const us_GenSettings *g, int reference, us_Random3dStats *stats,
                                    us_Error *err) {
  us_Error local;
  if (!err) err = &local; /* the steps below read err->code */
  if (check_random3d(g, err)) return NULL;
  if (stats) memset(stats, 0, sizeof *stats);
  Drops d = {g, (uint64_t)g->seed, (long)floor(4.0 * (g->width - 1.0)) + 1, 0, NULL, 0, NULL, NULL,
             NULL, NULL, reference, stats, 0, {0}};
  d.side = d.nq + 3;
  d.top = us_calloc((size_t)(d.side * d.side), sizeof *d.top);
  d.owner = us_malloc((size_t)(d.side * d.side) * sizeof *d.owner);
  d.q = us_malloc((size_t)g->n * 2 * sizeof *d.q);
  d.level = us_malloc((size_t)g->n * sizeof *d.level);
  d.below = us_malloc((size_t)g->n * 16 * sizeof *d.below);
  for (long c = 0; d.owner && c < d.side * d.side; c++) d.owner[c] = -1;
  us_Status st = d.top && d.owner && d.q && d.level && d.below
                     ? run(&d, err)
                     : us_error_set(err, US_ERR_NOMEM, "random3d: out of memory");
  us_Structure *s = st ? NULL : build(&d, d.n, NULL, err);
  us_free(d.top);
  us_free(d.q);
  us_free(d.level);
  us_free(d.owner);
  us_free(d.below);
  us_gen_carry_free(&d.carry);
  return s;
}
