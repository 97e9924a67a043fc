/* The random stacker: blocks dropped at random rows and offsets, each kept
 * only if the whole structure still stands, until one is kept in the top
 * row.
 *
 * Settings: g->width is the structure's width W in blocks (blocks are 1
 * wide and g->height high, so W = 1 gives a column), g->rows the number of
 * rows R, g->seed the seed, g->max_tries the attempts allowed between two
 * rises of the highest occupied row.
 *
 * Algorithm: with `top` the highest occupied row (-1 at first), each attempt
 * draws a row r uniformly in 0..min(top + 1, R - 1) and a left edge x
 * uniformly among the quarter-block positions 0, 1/4, ..., <= W - 1 (a
 * discrete offset keeps all coordinates exact binary fractions, so blocks
 * touch exactly or not at all). The block [x, x + 1] x [r h, (r + 1) h] is
 * rejected at once when it overlaps a block of its row or has no block of
 * row r - 1 under it (overlap of positive length; row 0 rests on the
 * ground): such a block could not stand anyway. Otherwise the structure of
 * the kept blocks plus the candidate is built, finalized and tested with the
 * default stability settings (the LP); the candidate is kept when the
 * verdict is stable. The run stops when a block is kept in row R - 1, and
 * fails with US_ERR_INPUT after max_tries attempts without the highest row
 * rising.
 *
 * Randomness: splitmix64 seeded with g->seed (our own generator, never
 * rand()), so a seed gives the same structure on every platform. Bodies are
 * named "b1", "b2", ... in the order they were kept.
 *
 * Cost: an attempt that passes the quick checks rebuilds the structure from
 * scratch: finalize (contact detection, O(k log k) for k blocks) plus one
 * LP over k bodies; the LP dominates. The quick checks are O(k). Measured
 * (Release, seed 1): W 6 x 10 rows, 29 blocks in 0.01 s; W 10 x 20 rows,
 * 126 blocks in 0.5 s; W 20 x 30 rows, 373 blocks in 9 s. Larger runs would
 * want an incremental structure and a workspace that can grow. */
#include "gen.h"

#include <math.h>

typedef struct Stacker {
  const us_GenSettings *g;
  uint64_t rng;  /* splitmix64 state */
  long nq;       /* number of quarter-block offsets */
  int n, cap;    /* kept blocks */
  int *row;      /* [n] row of each kept block */
  long *q;       /* [n] left edge in quarter blocks */
  int top;       /* highest occupied row, -1 when empty */
} Stacker;

static us_Status check_random(const us_GenSettings *g, us_Error *err) {
  us_Status st = us_gen_check_common(g, "random", err);
  if (!st) st = us_gen_check_positive(g->height, "random", "block height", err);
  if (!st && !(g->width >= 1.0 && g->width <= 1e6))
    st = us_error_set(err, US_ERR_USAGE,
                      "random: width (in blocks) must be in [1, 1e6], got %g", g->width);
  if (!st && g->rows < 1)
    st = us_error_set(err, US_ERR_USAGE, "random: rows must be >= 1, got %d", g->rows);
  if (!st && g->max_tries < 1)
    st = us_error_set(err, US_ERR_USAGE, "random: max_tries must be >= 1, got %d", g->max_tries);
  return st;
}

/* Does block (r, q) fit: no overlap in its row, something under it? */
static int fits(const Stacker *k, int r, long q) {
  int supported = r == 0;
  for (int i = 0; i < k->n; i++) {
    long d = k->q[i] > q ? k->q[i] - q : q - k->q[i];
    if (d >= 4) continue;
    if (k->row[i] == r) return 0;
    if (k->row[i] == r - 1) supported = 1;
  }
  return supported;
}

/* Add block number i at (r, q) to s. */
static us_Status add_block(us_Structure *s, const Stacker *k, int i, int r, long q,
                           us_Error *err) {
  double x0 = (double)q * 0.25, y0 = (double)r * k->g->height;
  return us_gen_add_box(s, k->g, i, x0, y0, x0 + 1.0, (double)(r + 1) * k->g->height, err);
}

/* The finalized structure of the kept blocks plus (r, q), or NULL. */
static us_Structure *build(const Stacker *k, int r, long q, us_Error *err) {
  us_Structure *s = us_gen_begin(k->g, err);
  us_Status st = s ? US_OK : US_ERR_NOMEM;
  for (int i = 0; !st && i < k->n; i++) st = add_block(s, k, i, k->row[i], k->q[i], err);
  if (!st) st = add_block(s, k, k->n, r, q, err);
  if (st) {
    us_structure_free(s);
    return NULL;
  }
  return us_gen_finish(s, k->g, err);
}

/* Append block (r, q) to the kept blocks. */
static us_Status keep(Stacker *k, int r, long q, us_Error *err) {
  if (k->n == k->cap) {
    int cap = k->cap ? 2 * k->cap : 16;
    int *row = us_realloc(k->row, (size_t)cap * sizeof *row);
    if (row) k->row = row; /* grown even if q fails below: cap stays valid */
    long *qs = row ? us_realloc(k->q, (size_t)cap * sizeof *qs) : NULL;
    if (!qs) return us_error_set(err, US_ERR_NOMEM, "random: out of memory");
    k->q = qs;
    k->cap = cap;
  }
  k->row[k->n] = r;
  k->q[k->n++] = q;
  if (r > k->top) k->top = r;
  return US_OK;
}

/* One attempt: draw a block, keep it if it fits and stands. *out becomes
 * the structure with the block when kept (the previous one is freed). */
static us_Status attempt(Stacker *k, us_Structure **out, int *kept, us_Error *err) {
  int rmax = US_MIN(k->top + 1, k->g->rows - 1);
  int r = (int)us_rng_below(&k->rng, (long)rmax + 1);
  long q = us_rng_below(&k->rng, k->nq);
  *kept = 0;
  if (!fits(k, r, q)) return US_OK;
  us_Structure *s = build(k, r, q, err);
  if (!s) return err->code;
  int stable = 0;
  us_Status st = us_gen_stands(s, &stable, err);
  if (!st && stable) st = keep(k, r, q, err);
  if (st || !stable) {
    us_structure_free(s);
    return st;
  }
  us_structure_free(*out);
  *out = s;
  *kept = 1;
  return US_OK;
}

us_Structure *us_gen_random(const us_GenSettings *g, us_Error *err) {
  us_Error local;
  if (!err) err = &local; /* the steps below read err->code */
  if (check_random(g, err)) return NULL;
  Stacker k = {g, (uint64_t)g->seed, (long)floor(4.0 * (g->width - 1.0)) + 1, 0, 0, NULL, NULL, -1};
  us_Structure *s = NULL;
  us_Status st = US_OK;
  int tries = 0, top_before = -1;
  while (!st && k.top < g->rows - 1) {
    if (tries++ >= g->max_tries) {
      st = us_error_set(err, US_ERR_INPUT,
                        "random: gave up after %d attempts without a new highest row "
                        "(highest row %d of 0..%d, %d blocks kept)",
                        g->max_tries, k.top, g->rows - 1, k.n);
      break;
    }
    if (us_past(g->deadline)) {
      st = us_error_set(err, US_ERR_TIME_LIMIT, "random: time limit reached (%d blocks kept)", k.n);
      break;
    }
    int kept = 0;
    st = attempt(&k, &s, &kept, err);
    if (kept && k.top > top_before) top_before = k.top, tries = 0;
  }
  us_free(k.row);
  us_free(k.q);
  if (st) {
    us_structure_free(s);
    return NULL;
  }
  return s;
}
