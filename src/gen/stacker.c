/* The source-style stacker: rows of blocks at random offsets in which some
 * blocks are cantilevers, held up only by a counterweight placed on them in
 * the next row; only the finished structure has to stand.
 *
 * Settings: g->width is the structure's width W in blocks, g->rows the
 * number of rows R, g->height the row height h, g->seed the seed,
 * g->max_tries the row attempts allowed in all (default 10000).
 *
 * Geometry: x is counted in quarter blocks (q), so every coordinate is an
 * exact binary fraction and blocks touch exactly or not at all. The
 * structure spans [0, Q] with Q = floor(4 W); row r spans [r h, (r + 1) h].
 * A block is 1 to 2 blocks wide (4 to 8 q; counterweights up to 3). Bodies are named "b1", "b2",
 * ... row by row from the bottom, left to right in a row.
 *
 * Rows: a row is drawn by a walk across it, left to right or right to left
 * (a coin flip per row, so the structure has no handedness). The walk
 * starts at the edge; before each further block it leaves a gap of 0
 * (probability 1/2) or 1 to 6 q. A block must rest on the row below with
 * positive overlap, have its centre of mass strictly inside the x-extent
 * of its contacts below, and pass the probe (below); the width drawn is
 * taken if it does, else one drawn among those that do, and when none does
 * the walk moves on by a quarter. A row that can end exactly at the far
 * edge does, so the structure keeps its width. Row 0 stands on the ground.
 *
 * Cantilevers: a cantilever C rests on one block A of the row below, over
 * L q from the joint j (C's inner edge) to A's corner, with nothing below
 * the rest of it, and 2 L < w for its width w: C's centre of mass lies
 * beyond A's corner, so C tips alone. Its neighbour B on the inner side
 * (at most 1 q away) and C are placed as a pair: B first and C hanging
 * ahead of the walk, or C hanging behind and B right after it; B may also
 * be the block the walk placed last. C is held by a counterweight D in the
 * next row: a block of even width w_d centred on the joint and longer by
 * one block on B's side (kCwTail; a cantilever is made only where it fits), resting
 * on B and C, so that its centre of mass lies over B: D stands on B alone,
 * and the structure can be built B, D, then C slid in under D's end, and
 * taken apart cantilever first, one block at a time. D's weight can go wholly into C's inner corner (arm L about A's
 * corner) while C's weight acts w/2 - L beyond it, so D holds C when
 * w_d L >= w (w/2 - L) (weights go with widths). C is made only when
 * w_d = 3 w (w - 2 L) / (4 L) (1.5 times that, rounded up to even) is at
 * most 2 blocks, A's contacts below reach under both j and its corner, and
 * C with that counterweight passes the probe; D's width is drawn from there
 * to 8 q. C's overhang, and the part of D above it, carry no block of the
 * next row; C clears the next block below by a quarter (a touching corner
 * would support it); two joints of a row are at least 4 blocks apart, so
 * counterweights (up to 3 blocks long) never collide. Each walk step takes a pair when one fits
 * there (drawn among all that do). The top row makes no cantilevers. Until
 * its counterweight is placed a cantilever is pending.
 *
 * Probe (a cheap filter, no LP): a new block's weight (or a cantilever's
 * with its counterweight's) is carried down row by row, at each block with
 * that block's weight added, split between the two contact points that
 * bracket the resultant most closely (lever rule). It fails when a
 * resultant lies outside its block's contacts: a block that would tip
 * under the new load if nothing else leant on it. Other loads are ignored,
 * so passing proves nothing; it spares the LP most rows that would fail.
 *
 * Test per row: with P_r the pending cantilevers of row r, the structure
 * T_r of rows 0..r without P_r must stand, and so must T_r without P_{r-1}
 * (the counterweights of row r without the cantilevers they hold: with
 * that, taking each cantilever out first leaves a standing structure).
 * Both are tested once per row (r >= 1) without friction, with the
 * default stability settings: a structure that stands without friction
 * stands with any, and frictionless LPs are several times faster. The
 * finished structure (T of the top row, which has no cantilevers) is
 * tested with the structure's own friction. The structure tested holds
 * every kept block (body i is block i), and T_r is a set of it. The forces
 * of T_{r-1} (frictionless: they hold with any friction) are carried over
 * as the local tests' base (us_gen_carry_seed, re-checked there), and T_r
 * is reached from T_{r-1} one block at a time (tests by change, each
 * decided on a region around the block: docs/local.md), then tested
 * itself; a block that fails first waits for a second pass, and one whose
 * failure left a mechanism that also moves T_r (checked on T_r) decides
 * T_r at once. Exact either way: the verdicts, hence the structures, are
 * those of one whole-structure LP per test (before 2026-12-02, which cost
 * 60 x 60: 1.1-1.6 s, now 0.4-0.5 s; 80 x 100: 7.3-8.1 s, now 4.1 s;
 * 100 x 60, seed 3: 17 s, now 13 s, where rows that fail, whose proof
 * still takes an LP of the whole, dominate). The structure of rows 0..r
 * with its pending cantilevers (an intermediate build stage) does not stand
 * when row r has one (in the tests, 34 of 78 stages of 14 x 12 piles); the
 * finished one does.
 *
 * Repair: a row that fails (its test, or no block at all) is redrawn,
 * without new cantilevers after kTriesCant failures; kTriesRow failures of
 * a row drop the row below, which counts as a failure of that row, so
 * trouble climbs down. The run fails with US_ERR_INPUT after g->max_tries
 * row attempts in all.
 *
 * Figures (Release, friction 0.5, this project's 2-core machine; printed
 * by tests/test_gen_stacker.c, stacker_sizes; seed 1):
 *   rows x width   blocks   cantilevers   time
 *   14 x 12            78       6 (8 %)    0.01 s
 *   30 x 30           263      29 (11 %)   0.15 s
 *   60 x 60           861     118 (14 %)   1.2 s
 * Seeds 1-10 of 14 x 12 give 57 to 84 blocks. About 8 to 14 % of the blocks
 * are cantilevers (more in taller structures; fewer than before the
 * counterweights got their tail over B, which needs room). The count is roughly 0.3 R W
 * for tall structures (rows thin out where no block passes) and 0.45 R W
 * for low ones. The cost is a local test per block and row test, one LP
 * of the whole structure per row that fails, and the probes, O(rows)
 * each.
 *
 * Randomness: one splitmix64 stream (us_rng_next) seeded with g->seed,
 * so a seed gives the same structure on every platform. */
#include "gen.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

enum {
  kQMin = 4,      /* narrowest block, quarters */
  kQMax = 8,      /* widest block */
  kGapMax = 6,    /* widest gap drawn */
  kJointGap = 16, /* least distance between two cantilever joints of a row */
  kCwTail = 4,    /* a counterweight's extra length over B (see place_counterweights) */
  kTriesCant = 2, /* attempts of a row with new cantilevers */
  kTriesRow = 4,  /* attempts of a row before the row below is redrawn */
  kWidths = kQMax - kQMin + 1,
  kPickMax = kWidths * (1 + 4 * kWidths) /* pair candidates of one walk step */
};

/* Upper bound on rows x width (a row that fails runs an LP of the whole
 * structure: 80 x 400 gives 5,796 blocks in about 2.5 minutes on this
 * project's machine). */
#define STACKER_MAX_AREA 100000.0

typedef struct Blk {
  long q0, q1;      /* extent, quarters */
  long s0, s1;      /* x-extent of its contacts below (a cantilever's: from
                       its joint to A's corner) */
  long a0, a1;      /* the part that may carry blocks of the next row */
  signed char side; /* cantilever overhanging to +x (1) or -x (-1); 0: none */
  long wd;          /* cantilever: its counterweight's width, quarters */
} Blk;

/* A stretch in walk coordinates: a support segment of the row below (the
 * part that may carry) with its block's contact extent, or an obstacle of
 * the row being drawn (cw: a counterweight; else a cantilever's overhang). */
typedef struct Seg {
  long lo, hi;
  long s0, s1;
  int cw;
} Seg;

/* Probe: a load P with moment M (x in quarters) on kept block i. */
typedef struct Load {
  int i;
  double P, M;
} Load;

typedef struct Stk {
  const us_GenSettings *g;
  uint64_t rng;
  long Q;          /* width in quarters */
  int dir;         /* walk direction of the row being drawn: +1 or -1 */
  Blk *b;          /* kept blocks, row by row, left to right */
  int n, cap;
  int *start;      /* [rows + 1]: first block of each kept row */
  int *fails;      /* [rows]: failed attempts per row (see run) */
  int rows;        /* rows kept */
  Blk *cur;        /* the row being drawn, absolute coordinates */
  int ncur;
  Seg *seg, *obs;  /* support segments and obstacles (walk coordinates) */
  int nseg, nobs, rowcap;
  Load *front, *next; /* probe scratch */
  int cant_ok;     /* this attempt may make cantilevers */
  /* the forces of T of the top kept row (frictionless), carried to the
     next row's tests, and those of the row on trial until it is kept */
  us_GenCarry carry, trial;
  int trial_ok;
  int reference;   /* 1: every test an LP of the whole T, nothing carried */
} Stk;

/* ---------------------------------------------------------------- settings */

static us_Status check_stacker(const us_GenSettings *g, us_Error *err) {
  us_Status st = us_gen_check_common(g, "stacker", err);
  if (!st) st = us_gen_check_positive(g->height, "stacker", "block height", err);
  if (!st && !(g->width >= 1.0 && g->width <= STACKER_MAX_AREA))
    st = us_error_set(err, US_ERR_USAGE, "stacker: width (in blocks) must be in [1, %g], got %g",
                      STACKER_MAX_AREA, g->width);
  if (!st && g->rows < 1)
    st = us_error_set(err, US_ERR_USAGE, "stacker: rows must be >= 1, got %d", g->rows);
  if (!st && (double)g->rows * g->width > STACKER_MAX_AREA)
    st = us_error_set(err, US_ERR_USAGE,
                      "stacker: rows x width = %d x %g is more than the limit of %g", g->rows,
                      g->width, STACKER_MAX_AREA);
  if (!st && g->max_tries < 1)
    st = us_error_set(err, US_ERR_USAGE, "stacker: max_tries must be >= 1, got %d",
                      g->max_tries);
  return st;
}

/* ------------------------------------------------------------------ memory */

static us_Status stk_init(Stk *k, const us_GenSettings *g, us_Error *err) {
  size_t cap;
  k->g = g;
  k->rng = (uint64_t)g->seed;
  k->Q = (long)(4.0 * g->width);
  k->rowcap = (int)(k->Q / kQMin) + 2;
  cap = (size_t)k->rowcap;
  k->start = us_calloc((size_t)g->rows + 1, sizeof *k->start);
  k->fails = us_calloc((size_t)g->rows, sizeof *k->fails);
  k->cur = us_malloc(cap * sizeof *k->cur);
  k->seg = us_malloc(cap * sizeof *k->seg);
  k->obs = us_malloc(2 * cap * sizeof *k->obs);
  k->front = us_malloc(cap * sizeof *k->front);
  k->next = us_malloc(cap * sizeof *k->next);
  if (!k->start || !k->fails || !k->cur || !k->seg || !k->obs || !k->front || !k->next)
    return us_error_set(err, US_ERR_NOMEM, "stacker: out of memory");
  return US_OK;
}

static void stk_free(Stk *k) {
  us_gen_carry_free(&k->carry);
  us_gen_carry_free(&k->trial);
  us_free(k->b);
  us_free(k->start);
  us_free(k->fails);
  us_free(k->cur);
  us_free(k->seg);
  us_free(k->obs);
  us_free(k->front);
  us_free(k->next);
}

/* Blocks of kept row r: *n of them. */
static Blk *row_blocks(const Stk *k, int r, int *n) {
  *n = k->start[r + 1] - k->start[r];
  return &k->b[k->start[r]];
}

/* First of the n kept blocks (sorted, disjoint) ending after x. */
static int blk_after(const Blk *b, int n, long x) {
  int lo = 0, hi = n;
  while (lo < hi) {
    int mid = (lo + hi) / 2;
    if (b[mid].q1 > x) hi = mid;
    else lo = mid + 1;
  }
  return lo;
}

/* ------------------------------------------------------------------- probe */

/* Add load f at x on kept block i to the n loads of out (merged by block). */
static void add_load(Load *out, int *n, int i, double f, double x) {
  int t = 0;
  while (t < *n && out[t].i != i) t++;
  if (t == *n) out[(*n)++] = (Load){i, 0, 0};
  out[t].P += f, out[t].M += f * x;
}

/* Split P at c over the contacts of [q0, q1] on kept row r into out: the
 * two contact points bracketing c most closely, by the lever rule. */
static int split_onto(const Stk *k, int r, long q0, long q1, double P, double c, Load *out,
                      int *n) {
  int nlow, lo_i = -1, hi_i = -1;
  const Blk *low = row_blocks(k, r, &nlow);
  long lo_x = LONG_MIN, hi_x = LONG_MAX;
  for (int i = blk_after(low, nlow, q0); i < nlow && low[i].q0 < q1; i++) {
    long ends[2] = {US_MAX(low[i].q0, q0), US_MIN(low[i].q1, q1)};
    for (int e = 0; e < 2; e++) {
      if ((double)ends[e] <= c + 1e-9 && ends[e] > lo_x) lo_x = ends[e], lo_i = i;
      if ((double)ends[e] >= c - 1e-9 && ends[e] < hi_x) hi_x = ends[e], hi_i = i;
    }
  }
  if (lo_i < 0 || hi_i < 0) return 0;
  double f_lo = hi_x == lo_x ? P : P * ((double)hi_x - c) / (double)(hi_x - lo_x);
  add_load(out, n, k->start[r] + lo_i, f_lo, (double)lo_x);
  add_load(out, n, k->start[r] + hi_i, P - f_lo, (double)hi_x);
  return 1;
}

/* Carry a load P at c from [q0, q1] (absolute) in the drawn row down to the
 * ground; 0 when a block on the way tips. */
static int probe(Stk *k, long q0, long q1, double P, double c) {
  int n = 0;
  if (k->rows == 0) return 1;
  if (!split_onto(k, k->rows - 1, q0, q1, P, c, k->front, &n)) return 0;
  for (int r = k->rows - 1; r > 0; r--) {
    int m = 0;
    for (int t = 0; t < n; t++) {
      const Blk *z = &k->b[k->front[t].i];
      double w = (double)(z->q1 - z->q0), Pz = k->front[t].P + w;
      double cz = (k->front[t].M + w * 0.5 * (double)(z->q0 + z->q1)) / Pz;
      if (!split_onto(k, r - 1, z->q0, z->q1, Pz, cz, k->next, &m)) return 0;
    }
    Load *tmp = k->front;
    k->front = k->next, k->next = tmp, n = m;
  }
  return 1;
}

/* ---------------------------------------------------------- walk geometry */

/* [a, b] in absolute quarters to walk coordinates (and back: an involution). */
static void to_walk(const Stk *k, long a, long b, long *lo, long *hi) {
  if (k->dir > 0) *lo = a, *hi = b;
  else *lo = k->Q - b, *hi = k->Q - a;
}

/* x in walk coordinates to absolute (and back). */
static long walk_x(const Stk *k, long x) { return k->dir > 0 ? x : k->Q - x; }

/* First of the n stretches (sorted, disjoint) with hi > x. */
static int seg_after(const Seg *s, int n, long x) {
  int lo = 0, hi = n;
  while (lo < hi) {
    int mid = (lo + hi) / 2;
    if (s[mid].hi > x) hi = mid;
    else lo = mid + 1;
  }
  return lo;
}

/* Does [x0, x0 + w] (walk) rest on the segments (positive overlap, centre
 * strictly inside its contacts) and pass the probe? */
static int fits(Stk *k, long x0, long w) {
  long h0 = LONG_MAX, h1 = LONG_MIN, x1 = x0 + w;
  for (int i = seg_after(k->seg, k->nseg, x0); i < k->nseg && k->seg[i].lo < x1; i++) {
    h0 = US_MIN(h0, US_MAX(k->seg[i].lo, x0));
    h1 = US_MAX(h1, US_MIN(k->seg[i].hi, x1));
  }
  if (!(h0 < h1 && 2 * h0 < x0 + x1 && x0 + x1 < 2 * h1)) return 0;
  long a, b;
  to_walk(k, x0, x1, &a, &b);
  return probe(k, a, b, (double)w, 0.5 * (double)(a + b));
}

/* Least even counterweight width holding a cantilever of width w with L
 * quarters supported (1.5 x the torque balance; see the file head). */
static long counterweight_need(long w, long L) {
  long need = (3 * w * (w - 2 * L) + 4 * L - 1) / (4 * L);
  need = US_MAX(need, (long)kQMin);
  return need + (need & 1);
}

/* --------------------------------------------------------- the row below */

/* Support segments of the row below in walk order; the ground is one. */
static void lower_segments(Stk *k) {
  int nlow;
  k->nseg = 0;
  if (k->rows == 0) {
    k->seg[k->nseg++] = (Seg){0, k->Q, 0, k->Q, 0};
    return;
  }
  Blk *low = row_blocks(k, k->rows - 1, &nlow);
  for (int t = 0; t < nlow; t++) {
    const Blk *a = &low[k->dir > 0 ? t : nlow - 1 - t];
    Seg *s = &k->seg[k->nseg++];
    to_walk(k, a->a0, a->a1, &s->lo, &s->hi);
    to_walk(k, a->s0, a->s1, &s->s0, &s->s1);
    s->cw = 0;
  }
}

static int cmp_seg(const void *x, const void *y) {
  const Seg *a = x, *b = y;
  return a->lo < b->lo ? -1 : a->lo > b->lo;
}

static int cmp_blk(const void *x, const void *y) {
  const Blk *a = x, *b = y;
  return a->q0 < b->q0 ? -1 : a->q0 > b->q0;
}

static void add_obstacle(Stk *k, long a, long b, int cw) {
  Seg *s = &k->obs[k->nobs++];
  to_walk(k, a, b, &s->lo, &s->hi);
  s->s0 = 1, s->s1 = 0;
  s->cw = cw;
}

/* Counterweights for the cantilevers of the row below (placed first); the
 * obstacles of this row are the counterweights and the overhangs. */
static void place_counterweights(Stk *k) {
  int nlow;
  k->nobs = 0;
  if (k->rows == 0) return;
  const Blk *low = row_blocks(k, k->rows - 1, &nlow);
  for (int i = 0; i < nlow; i++) {
    const Blk *c = &low[i];
    if (!c->side) continue;
    long w = c->wd;
    long j = c->side > 0 ? c->q0 : c->q1; /* the joint: C's inner edge */
    /* centred on the joint, and longer by kCwTail on B's side, so that its
       centre of mass lies over B: D stands on B alone, and the structure
       can be built B, D, C (C slid in under D) and taken apart C first */
    long d0 = j - w / 2, d1 = j + w / 2;
    if (c->side > 0) d0 -= kCwTail; /* room checked by cantilever_ok */
    else d1 += kCwTail;
    Blk *d = &k->cur[k->ncur++];
    *d = (Blk){d0, d1, 0, 0, d0, d1, 0, 0};
    if (c->side > 0) d->a1 = US_MIN(d1, c->s1), add_obstacle(k, c->s1, c->q1, 0);
    else d->a0 = US_MAX(d0, c->s0), add_obstacle(k, c->q0, c->s0, 0);
    add_obstacle(k, d0, d1, 1);
  }
  qsort(k->obs, (size_t)k->nobs, sizeof *k->obs, cmp_seg);
}

/* ------------------------------------------------------------- cantilevers */

typedef struct Walk {
  long u;          /* cursor: nothing is placed at or after u yet */
  long prev_end;   /* walk end of the last block that may serve as B */
  long last_joint; /* joint of the last cantilever of this row */
  int prev_ok;     /* prev_end names a block that is not a cantilever */
  int slid;        /* the last step placed nothing: no gap before the next */
} Walk;

/* A candidate pair (walk coordinates): cantilever [c0, c1] hanging ahead
 * (side 1) or behind (-1) with a counterweight of width wd; block B
 * [b0, b1] (b0 == b1: B is already placed). */
typedef struct Pair {
  long c0, c1, b0, b1, wd;
  int side;
} Pair;

/* The obstacles end before x (a cantilever's overhang a quarter before,
 * so the two do not touch) and none overlaps [x, y]. */
static int clear_between(const Stk *k, long x, long y) {
  for (int t = 0; t < k->nobs; t++)
    if (k->obs[t].lo < y + !k->obs[t].cw && k->obs[t].hi + !k->obs[t].cw > x) return 0;
  return 1;
}

/* Does cantilever [c0, c1] (walk), hanging to `side`, rest on one block A
 * of the row below as described in the file head? *L: its supported
 * length; *wd: its counterweight's width, drawn. */
static int cantilever_ok(Stk *k, long c0, long c1, int side, long *L, long *wd) {
  long j = side > 0 ? c0 : c1, w = c1 - c0, a, b, ja = walk_x(k, j);
  int i = seg_after(k->seg, k->nseg, side > 0 ? j : j - 1);
  if (c0 < 0 || c1 > k->Q || i >= k->nseg) return 0;
  const Seg *s = &k->seg[i];
  long corner = side > 0 ? s->hi : s->lo, bare0 = side > 0 ? s->hi : c0,
       bare1 = side > 0 ? c1 : s->lo; /* the overhang */
  *L = side > 0 ? s->hi - j : j - s->lo;
  if (*L < 1 || 2 * *L >= w || (side > 0 ? s->lo > j : s->hi < j)) return 0;
  if (corner < s->s0 || corner > s->s1 || j < s->s0 || j > s->s1) return 0;
  long need = counterweight_need(w, *L);
  if (need > kQMax) return 0;
  if (side > 0 && i + 1 < k->nseg && k->seg[i + 1].lo <= bare1) return 0;
  if (side < 0 && i > 0 && k->seg[i - 1].hi >= bare0) return 0;
  if (!clear_between(k, c0, c1) || !(bare0 < bare1)) return 0;
  *wd = need + 2 * us_rng_below(&k->rng, (kQMax - need) / 2 + 1);
  /* room for the counterweight's tail over B (it must stand on B alone) */
  if (side > 0 ? j - *wd / 2 - kCwTail < 0 : j + *wd / 2 + kCwTail > k->Q) return 0;
  double P = (double)(w + *wd);
  to_walk(k, c0, c1, &a, &b);
  return probe(k, a, b, P, (0.5 * (double)(a + b) * (double)w + (double)(*wd * ja)) / P);
}

/* Collect the pairs that may start at x0 (B's room limited by wmax). */
static int collect_pairs(Stk *k, const Walk *wk, long x0, long wmax, Pair *p) {
  int n = 0;
  long L, wd;
  for (long w = kQMin; w <= kQMax; w++) /* B already placed, C ahead */
    if (wk->prev_ok && x0 - wk->prev_end <= 1 && x0 - wk->last_joint >= kJointGap &&
        cantilever_ok(k, x0, x0 + w, 1, &L, &wd))
      p[n++] = (Pair){x0, x0 + w, x0, x0, wd, 1};
  for (long wb = kQMin; wb <= wmax; wb++) {
    if (!fits(k, x0, wb)) continue;
    for (long gap = 0; gap <= 1; gap++)
      for (long w = kQMin; w <= kQMax; w++) { /* B, then C ahead */
        long j = x0 + wb + gap;
        if (j - wk->last_joint >= kJointGap && cantilever_ok(k, j, j + w, 1, &L, &wd))
          p[n++] = (Pair){j, j + w, x0, x0 + wb, wd, 1};
      }
  }
  for (long w = kQMin; w <= kQMax; w++) { /* C behind, then B */
    long j = x0 + w;
    if (j - wk->last_joint < kJointGap || !cantilever_ok(k, x0, j, -1, &L, &wd)) continue;
    for (long gap = 0; gap <= 1; gap++)
      for (long wb = kQMin; wb <= kQMax; wb++)
        if (j + gap + wb <= k->Q && clear_between(k, j + gap, j + gap + wb) &&
            fits(k, j + gap, wb))
          p[n++] = (Pair){x0, j, j + gap, j + gap + wb, wd, -1};
  }
  return n;
}

/* Append a block [lo, hi] (walk) to the row. */
static Blk *put(Stk *k, long lo, long hi) {
  Blk *b = &k->cur[k->ncur++];
  *b = (Blk){0, 0, 0, 0, 0, 0, 0, 0};
  to_walk(k, lo, hi, &b->q0, &b->q1);
  b->a0 = b->q0, b->a1 = b->q1;
  return b;
}

/* Place pair p: B (unless already placed) and the cantilever. */
static void put_pair(Stk *k, Walk *wk, const Pair *p) {
  long j = p->side > 0 ? p->c0 : p->c1;
  if (p->b1 > p->b0) put(k, p->b0, p->b1);
  Blk *c = put(k, p->c0, p->c1);
  c->side = (signed char)(p->side * k->dir);
  c->wd = p->wd;
  wk->last_joint = j, wk->slid = 0;
  wk->u = US_MAX(p->c1, p->b1);
  wk->prev_ok = p->side < 0, wk->prev_end = p->b1;
}

/* ---------------------------------------------------------------- the walk */

/* A width for a block at x0: w if it fits, else one drawn among those up
 * to wmax that do; 0 when none does. A row that can end exactly at the
 * edge does. */
static long block_width(Stk *k, long x0, long w, long wmax, int free_end) {
  long fit[kQMax + 1], nfit = 0, rest = k->Q - x0;
  if (free_end && rest <= wmax && fits(k, x0, rest)) return rest;
  if (free_end && rest > kQMax && rest < kQMax + kQMin) wmax = US_MIN(wmax, rest - kQMin);
  if (w <= wmax && fits(k, x0, w)) return w;
  for (long c = kQMin; c <= wmax; c++)
    if (c != w && fits(k, x0, c)) fit[nfit++] = c;
  return nfit ? fit[us_rng_below(&k->rng, nfit)] : 0;
}

/* Move the cursor past obstacle i; a counterweight may serve as B. */
static void pass_obstacle(Stk *k, Walk *wk, int i) {
  wk->u = k->obs[i].hi;
  wk->prev_ok = k->obs[i].cw;
  wk->prev_end = k->obs[i].hi;
  wk->slid = 0;
}

/* One step of the walk: place a pair or a block, or move the cursor on. */
static void walk_step(Stk *k, Walk *wk, Pair *pairs) {
  long x0 = wk->u, w = kQMin + us_rng_below(&k->rng, kQMax - kQMin + 1);
  if (wk->u > 0 && !wk->slid && us_rng_below(&k->rng, 2))
    x0 += 1 + us_rng_below(&k->rng, kGapMax);
  x0 = US_MAX(wk->u, US_MIN(x0, k->Q - kQMin)); /* the last gap fits the edge */
  long wmax = US_MIN((long)kQMax, k->Q - x0);    /* room before an obstacle */
  int ob = -1;
  for (int i = 0; i < k->nobs && ob < 0 && k->obs[i].lo < x0 + wmax; i++)
    if (k->obs[i].hi > x0) ob = i;
  if (ob >= 0 && k->obs[ob].lo - x0 < kQMin) {
    pass_obstacle(k, wk, ob);
    return;
  }
  if (ob >= 0) wmax = k->obs[ob].lo - x0;
  int np = k->cant_ok ? collect_pairs(k, wk, x0, wmax, pairs) : 0;
  if (np) {
    put_pair(k, wk, &pairs[us_rng_below(&k->rng, np)]);
    return;
  }
  if (!(w = block_width(k, x0, w, wmax, ob < 0))) {
    wk->u = x0 + 1, wk->slid = 1;
    return;
  }
  put(k, x0, x0 + w);
  wk->u = x0 + w, wk->prev_end = x0 + w, wk->prev_ok = 1, wk->slid = 0;
}

/* ------------------------------------------------------------ row attempts */

/* The x-extent of block c's contacts on the kept row below (the block
 * itself on the ground). */
static void support_extent(const Stk *k, Blk *c) {
  int nlow;
  if (k->rows == 0) {
    c->s0 = c->q0, c->s1 = c->q1;
    return;
  }
  const Blk *low = row_blocks(k, k->rows - 1, &nlow);
  c->s0 = c->q1, c->s1 = c->q0;
  for (int i = blk_after(low, nlow, c->q0); i < nlow && low[i].q0 < c->q1; i++) {
    c->s0 = US_MIN(c->s0, US_MAX(low[i].q0, c->q0));
    c->s1 = US_MAX(c->s1, US_MIN(low[i].q1, c->q1));
  }
}

/* Draw row k->rows into k->cur (sorted left to right); 0 when empty. */
static int draw_row(Stk *k) {
  Pair pairs[kPickMax];
  Walk wk = {0, LONG_MIN / 2, LONG_MIN / 2, 0, 0};
  k->dir = us_rng_below(&k->rng, 2) ? 1 : -1;
  k->ncur = 0;
  lower_segments(k);
  place_counterweights(k);
  while (wk.u + kQMin <= k->Q) walk_step(k, &wk, pairs);
  qsort(k->cur, (size_t)k->ncur, sizeof *k->cur, cmp_blk);
  for (int i = 0; i < k->ncur; i++) {
    Blk *c = &k->cur[i];
    support_extent(k, c);
    if (c->side) c->a0 = c->s0, c->a1 = c->s1; /* only its supported part carries */
  }
  return k->ncur > 0;
}

/* Append the drawn row to the kept blocks. */
static us_Status keep_row(Stk *k, us_Error *err) {
  if (US_GROW(k->b, k->cap, k->n + k->ncur))
    return us_error_set(err, US_ERR_NOMEM, "stacker: out of memory");
  for (int i = 0; i < k->ncur; i++) k->b[k->n++] = k->cur[i];
  k->start[++k->rows] = k->n;
  return US_OK;
}

/* Drop the top kept row. */
static void drop_row(Stk *k) {
  k->rows--;
  k->n = k->start[k->rows];
}

/* Add block b of row r to s as body number (*id)++. */
static us_Status add_blk(us_Structure *s, const Stk *k, const Blk *b, int r, int *id,
                         us_Error *err) {
  const us_GenSettings *g = k->g;
  return us_gen_add_box(s, g, (*id)++, (double)b->q0 * 0.25, (double)r * g->height,
                        (double)b->q1 * 0.25, (double)(r + 1) * g->height, err);
}

/* Is block i of kept row r out of T: a pending cantilever of the top row
 * or, with `bare`, a cantilever of the row below it? */
static int left_out(const Stk *k, int i, int r, int bare) {
  return k->b[i].side && (r == k->rows - 1 || (bare && r == k->rows - 2));
}

/* The kept rows, every block (body i is block i, or, with `only_t`, the
 * blocks of T alone, as the finished structure is), finalized;
 * frictionless when `smooth`. */
static us_Structure *build(const Stk *k, int smooth, int only_t, us_Error *err) {
  us_Structure *s = us_gen_begin(k->g, err);
  us_Status st = s ? US_OK : US_ERR_NOMEM;
  int id = 0;
  if (s && smooth) s->friction = 0;
  for (int r = 0; !st && r < k->rows; r++)
    for (int i = k->start[r]; !st && i < k->start[r + 1]; i++)
      if (!(only_t && left_out(k, i, r, 0))) st = add_blk(s, k, &k->b[i], r, &id, err);
  if (st) {
    us_structure_free(s);
    return NULL;
  }
  return us_gen_finish(s, k->g, err);
}

/* The bodies of T, or of T without the cantilevers of the row below
 * (bare), as a set over the structure of every kept block. */
static void mark_t(const Stk *k, int bare, us_Bitset *t) {
  memset(t->w, 0, (size_t)t->nwords * sizeof(uint64_t));
  for (int r = 0; r < k->rows; r++)
    for (int i = k->start[r]; i < k->start[r + 1]; i++)
      if (!left_out(k, i, r, bare)) us_bitset_set(t, i);
}

/* From the carried set (current in w) towards target, one body at a time
 * (tests by change), higher rows first: counterweights before the
 * cantilevers under them. A body whose test fails waits for the second
 * pass (a block on a cantilever that is not there yet); only a way to
 * move the local tests' base in small steps, so the caller tests target
 * itself after it, unless a failure already decided target: the
 * mechanism that moves the failed set, checked on target (the bodies
 * still to come held still), shows target falls too (*fell = 1; res
 * keeps it). */
static us_Status grow_towards(us_Stability *w, const us_Structure *s, const us_Bitset *target,
                              int *pend, us_StabilityResult *res, int *fell, us_Error *err) {
  const us_Bitset *cur = us_stability_current(w);
  int np = 0;
  *fell = 0;
  for (int i = target->nbits - 1; i >= 0; i--)
    if (us_bitset_get(target, i) && !us_bitset_get(cur, i)) pend[np++] = i;
  for (int pass = 0, added = 1; pass < 2 && added && np > 0; pass++) {
    added = 0;
    int keep = 0;
    for (int q = 0; q < np; q++) {
      long global = us_stability_info(w)->local_global;
      us_Status st = us_stability_add(w, pend[q], err);
      if (!st) st = us_stability_test_current(w, res, err);
      if (st) return st;
      if (res->verdict == US_STABLE) {
        added++;
        continue;
      }
      if ((st = us_stability_remove(w, pend[q], err))) return st;
      if (res->verdict == US_UNSTABLE && res->mechanism.nbody > 0 && res->mechanism.ok &&
          us_mechanism_check(s, target, &res->mechanism, us_stability_default_settings().cert_tol))
        return *fell = 1, US_OK;
      /* a failure only the whole structure's LP decided: target's own
         test next (its LP starts where that one ended) */
      if (us_stability_info(w)->local_global > global) return US_OK;
      pend[keep++] = pend[q];
    }
    np = keep;
  }
  return US_OK;
}

/* Test T (frictionless when `smooth`; without the row below's
 * cantilevers when `bare`) with the default settings: *stable = 1 if it
 * stands. The structure holds every kept block; T is a set of it. The
 * forces of the last T that stood (the row below's, frictionless, which
 * hold with any friction) start the local tests, and T is reached from
 * there a body at a time, then tested itself: exact, and each step is
 * decided on a region around the body it adds (docs/local.md) instead of
 * an LP of the whole structure. A frictionless T that stands leaves its
 * forces on trial for the next row. */
static us_Status test_T(Stk *k, int smooth, int bare, int *stable, us_Error *err) {
  us_StabilitySettings set = us_stability_default_settings();
  if (k->reference) set.local = -1;
  us_StabilityResult res;
  us_stability_result_init(&res);
  us_Structure *s = build(k, smooth, 0, err);
  if (!s) return err->code;
  us_Stability *w = us_stability_new(s, &set, err);
  if (w) us_stability_set_deadline(w, k->g->deadline);
  us_Bitset t = {0}, seed = {0};
  int *pend = us_malloc((size_t)(s->nbody > 0 ? s->nbody : 1) * sizeof *pend);
  us_Status st = !w ? err->code
                 : !pend || us_bitset_init(&t, s->nbody) || us_bitset_init(&seed, s->nbody)
                     ? us_error_set(err, US_ERR_NOMEM, "stacker: out of memory")
                     : US_OK;
  int taken = 0, fell = 0;
  if (!st) {
    mark_t(k, bare, &t);
    if (!k->reference) st = us_gen_carry_seed(&k->carry, s, w, &seed, &taken, err);
  }
  if (!st && taken) st = grow_towards(w, s, &t, pend, &res, &fell, err);
  if (!st && !fell) st = us_stability_test(w, &t, &res, err);
  /* past the deadline a verdict may be "undecided": none is used */
  if (!st && us_past(k->g->deadline))
    st = us_error_set(err, US_ERR_TIME_LIMIT, "stacker: time limit reached (%d of %d rows kept)",
                      k->rows - 1, k->g->rows);
  *stable = !st && res.verdict == US_STABLE;
  k->trial_ok = 0;
  if (*stable && smooth && !bare) {
    st = us_gen_carry_keep(&k->trial, s, &t, &res.forces, err);
    k->trial_ok = !st;
  }
  us_stability_result_free(&res);
  us_bitset_free(&t);
  us_bitset_free(&seed);
  us_free(pend);
  us_stability_free(w);
  us_structure_free(s);
  return st;
}

static int row_has_cantilevers(const Stk *k, int r) {
  for (int i = k->start[r]; i < k->start[r + 1]; i++)
    if (k->b[i].side) return 1;
  return 0;
}

/* One attempt at the next row; *kept = 1 when it is kept. The finished
 * structure goes to *out. */
static us_Status attempt_row(Stk *k, us_Structure **out, int *kept, us_Error *err) {
  int stable = 1, top = k->rows + 1 == k->g->rows;
  us_Status st;
  *kept = 0;
  if (!draw_row(k)) return US_OK;
  if ((st = keep_row(k, err))) return st;
  int carried = 0; /* T's forces are on trial */
  if (top) st = test_T(k, 0, 0, &stable, err);
  else if (k->rows > 1) st = test_T(k, 1, 0, &stable, err), carried = k->trial_ok;
  /* the counterweights must stand without their cantilevers too, so that
     the structure has a one-at-a-time order (cantilever first) */
  if (!st && stable && k->rows > 1 && row_has_cantilevers(k, k->rows - 2))
    st = test_T(k, 1, 1, &stable, err);
  if (st || !stable) drop_row(k);
  *kept = !st && stable;
  if (*kept && carried) { /* the kept row's T starts the next row's tests */
    us_GenCarry c = k->carry;
    k->carry = k->trial;
    k->trial = c;
  }
  /* the finished structure, once every test of the top row passed (it was
     kept before the last test and leaked when that one failed) */
  if (*kept && top && out && !(*out = build(k, 0, 1, err))) return err->code ? err->code : US_ERR_NOMEM;
  return st;
}

/* Row attempts with backtracking: fails[r] counts the failed attempts at
 * row r since row r - 1 was drawn; kTriesRow of them drop row r - 1, which
 * counts as a failed attempt at row r - 1. */
static us_Status run(Stk *k, us_Structure **out, us_Error *err) {
  const us_GenSettings *g = k->g;
  for (long attempts = 0; k->rows < g->rows; attempts++) {
    int r = k->rows, kept = 0;
    if (us_past(g->deadline))
      return us_error_set(err, US_ERR_TIME_LIMIT, "stacker: time limit reached (%d of %d rows kept)",
                          k->rows, g->rows);
    if (attempts >= g->max_tries)
      return us_error_set(err, US_ERR_INPUT,
                          "stacker: gave up after %d row attempts (%d of %d rows kept)",
                          g->max_tries, k->rows, g->rows);
    k->cant_ok = r < g->rows - 1 && k->fails[r] < kTriesCant;
    us_Status st = attempt_row(k, out, &kept, err);
    if (st) return st;
    if (kept && r + 1 < g->rows) k->fails[r + 1] = 0;
    else if (!kept && ++k->fails[r] >= kTriesRow && r > 0)
      drop_row(k), k->fails[r] = 0, k->fails[r - 1]++;
  }
  return US_OK;
}

us_Structure *us_gen_stacker_ref(const us_GenSettings *g, int reference, us_Error *err) {
  us_Error local;
  if (!err) err = &local; /* the steps below read err->code */
  if (check_stacker(g, err)) return NULL;
  Stk k = {0};
  k.reference = reference;
  us_Structure *s = NULL;
  us_Status st = stk_init(&k, g, err);
  if (!st) st = run(&k, &s, err);
  stk_free(&k);
  if (st) {
    us_structure_free(s);
    return NULL;
  }
  return s;
}

us_Structure *us_gen_stacker(const us_GenSettings *g, us_Error *err) {
  return us_gen_stacker_ref(g, 0, err);
}
