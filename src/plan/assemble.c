/* Greedy assembly from the ground: the fast path of the planner.
 *
 * Build from the empty set, adding any body (or group of at most K
 * bodies) that keeps the set standing, lowest first; a body that failed is
 * retried only when the part it would join changed. When it reaches the
 * whole set, its build order reversed is a removal order (every set on the
 * way stood). When it is stuck nothing follows from that alone: buildable
 * sets are not closed under union when they overlap (a post can hold one
 * leaning plank or the other but not both), so a different choice earlier
 * might have gone on; exact.c decides those cases. docs/planning.md has the
 * statements, the counterexample and the proofs.
 *
 * Facts it uses:
 *   - Decoupling: when C stands, C ∪ G stands iff the component W of
 *     C ∪ G that holds G stands (components share no contact). So a step
 *     is tested on W alone (or as the change C -> C ∪ G when the tests
 *     are local, test_step), and a body whose W did not change since it
 *     failed is not tested again. W only grows as C grows, so "W
 *     unchanged" is "|W| unchanged".
 *   - A part that touches no support cannot stand under gravity, so only
 *     bodies touching C or a support are candidates.
 *
 * Data: C = `built`; union-find over C's components with member lists
 * (head/next) so W is listed in O(|W|); a min-heap of ready candidates
 * keyed by height (the lowest point, then the centre, then the index);
 * state[b] NEW (touches nothing yet), READY (in the heap), PARKED (failed
 * with would-be size stamp[b]), DEFERRED (woken, retried last), PLACED or
 * OUT (not in `within`). A parked body waits on the lists of the
 * components it touched. When a neighbour of it is placed it is ready at
 * once; when its part grows elsewhere it is only deferred: it is retried
 * when the heap is empty. (What a body lacks is mostly next to it, a
 * support or a counterweight on it: waking every body of a part at every
 * growth retried them all after each placement, 3.08 n tests on a
 * frictionless source-style stack 14 x 60, seed 3; 1.16 n deferred.) The
 * greedy still stops only when no body, woken, deferred or not, can be
 * added, so what it builds is unchanged in kind, only the order of tests.
 *
 * Groups (K > 1): when no single body can be added, groups of 2..K absent
 * bodies connected through themselves and C's components are tried (a
 * group whose parts fall in different components of C ∪ G is never
 * needed: by decoupling each part stands added alone). A group's W is
 * memoised when it fails.
 *
 * Cost: at most n(n+1)/2 single-body tests (each body fails at most once
 * per growth of its part); about n on stacks built bottom-up, at most
 * 1.21 n on a sweep of source-style stacks (tests/test_assemble.c asserts
 * 2 n). */
#include "assemble.h"

#include "model/model.h"
#include "stability/stability.h"

#include <string.h>

enum { NEW = 0, READY, PARKED, DEFERRED, PLACED, OUT };

typedef struct {
  int *v, n, cap;
} IntVec;

typedef struct Asm {
  us_SearchCtx *ctx;
  const us_Bitset *within;
  us_Assembly *out;
  us_Dsu dsu;
  int *head, *next, *tail; /* member lists of components (valid at roots) */
  unsigned char *state;
  int *stamp;
  double *key;            /* heap key: lowest point of the body */
  int *heap, nheap;
  IntVec *wait;           /* [n] bodies parked on component root r */
  IntVec deferred;        /* woken by a far growth of their part: retried last */
  int *roots;             /* scratch: distinct roots adjacent to a set */
  us_Bitset w;            /* scratch: the would-be component */
  us_Bitset cw;           /* C itself, kept as bodies are placed */
  int synced;             /* the stability workspace's current set is C */
  us_BitsetSet failed;    /* groups: components W known not to stand */
  int nwithin, nplaced;
} Asm;

static int vec_push(IntVec *v, int x) {
  if (US_GROW(v->v, v->cap, v->n + 1)) return -1;
  v->v[v->n++] = x;
  return 0;
}

/* ------------------------------------------------------------------ heap */

static int heap_less(const Asm *a, int x, int y) {
  if (a->key[x] != a->key[y]) return a->key[x] < a->key[y];
  int up = a->ctx->s->dim == 3 ? 2 : 1;
  double cx = a->ctx->s->bodies[x].com[up], cy = a->ctx->s->bodies[y].com[up];
  if (cx != cy) return cx < cy;
  return x < y;
}

static void heap_push(Asm *a, int b) {
  int i = a->nheap++;
  a->heap[i] = b;
  while (i > 0 && heap_less(a, a->heap[i], a->heap[(i - 1) / 2])) {
    int p = (i - 1) / 2, t = a->heap[p];
    a->heap[p] = a->heap[i];
    a->heap[i] = t;
    i = p;
  }
}

static int heap_pop(Asm *a) {
  int top = a->heap[0];
  a->heap[0] = a->heap[--a->nheap];
  for (int i = 0;;) {
    int l = 2 * i + 1, r = l + 1, m = i;
    if (l < a->nheap && heap_less(a, a->heap[l], a->heap[m])) m = l;
    if (r < a->nheap && heap_less(a, a->heap[r], a->heap[m])) m = r;
    if (m == i) break;
    int t = a->heap[m];
    a->heap[m] = a->heap[i];
    a->heap[i] = t;
    i = m;
  }
  return top;
}

static void make_ready(Asm *a, int b) {
  if (a->state[b] != NEW && a->state[b] != PARKED && a->state[b] != DEFERRED) return;
  a->state[b] = READY;
  heap_push(a, b);
}

/* ------------------------------------------------------------- set-up */

static double lowest_point(const us_Structure *s, const us_Body *b) {
  double lo, hi;
  us_body_vertical_range(s, b, &lo, &hi);
  return lo;
}

static void asm_free(Asm *a) {
  int n = a->ctx->s->nbody;
  us_dsu_free(&a->dsu);
  for (int i = 0; a->wait && i < n; i++) us_free(a->wait[i].v);
  us_free(a->wait);
  us_free(a->deferred.v);
  us_free(a->head);
  us_free(a->next);
  us_free(a->tail);
  us_free(a->state);
  us_free(a->stamp);
  us_free(a->key);
  us_free(a->heap);
  us_free(a->roots);
  us_bitset_free(&a->w);
  us_bitset_free(&a->cw);
  us_bitset_set_free(&a->failed);
}

static int asm_alloc(Asm *a, int n) {
  size_t m = (size_t)n + 1;
  a->head = us_malloc(m * sizeof(int));
  a->next = us_malloc(m * sizeof(int));
  a->tail = us_malloc(m * sizeof(int));
  a->state = us_calloc(m, 1);
  a->stamp = us_calloc(m, sizeof(int));
  a->key = us_malloc(m * sizeof(double));
  a->heap = us_malloc(m * sizeof(int));
  a->roots = us_malloc(m * sizeof(int));
  a->wait = us_calloc(m, sizeof(IntVec));
  int bad = !a->head || !a->next || !a->tail || !a->state || !a->stamp || !a->key ||
            !a->heap || !a->roots || !a->wait;
  return bad || us_dsu_init(&a->dsu, n) || us_bitset_init(&a->w, n) || us_bitset_init(&a->cw, n) ||
                 us_bitset_set_init(&a->failed, n)
             ? -1
             : 0;
}

static int asm_init(Asm *a, us_SearchCtx *ctx, const us_Bitset *within, us_Assembly *out) {
  memset(a, 0, sizeof *a);
  a->ctx = ctx;
  a->within = within;
  a->out = out;
  int n = ctx->s->nbody;
  if (asm_alloc(a, n)) return -1;
  for (int i = 0; i < n; i++) {
    a->head[i] = a->tail[i] = i;
    a->next[i] = -1;
    a->key[i] = lowest_point(ctx->s, &ctx->s->bodies[i]);
    a->state[i] = us_bitset_get(within, i) ? NEW : OUT;
    if (a->state[i] == NEW) a->nwithin++;
  }
  for (int i = 0; i < n; i++)
    if (a->state[i] == NEW && ctx->g.grounded[i]) make_ready(a, i);
  return 0;
}

/* ------------------------------------------------- would-be components */

/* Distinct roots of C's components adjacent to the bodies in grp; their
 * count. */
static int adjacent_roots(Asm *a, const int *grp, int ng) {
  const us_Graph *g = &a->ctx->g;
  int nr = 0;
  for (int j = 0; j < ng; j++)
    for (int k = g->start[grp[j]]; k < g->start[grp[j] + 1]; k++) {
      int u = g->adj[k];
      if (a->state[u] != PLACED) continue;
      int r = us_dsu_find(&a->dsu, u), dup = 0;
      for (int q = 0; q < nr && !dup; q++) dup = a->roots[q] == r;
      if (!dup) a->roots[nr++] = r;
    }
  return nr;
}

static int would_be_size(Asm *a, const int *grp, int ng) {
  int nr = adjacent_roots(a, grp, ng), size = ng;
  for (int q = 0; q < nr; q++) size += a->dsu.size[a->roots[q]];
  return size;
}

/* Set (on = 1) or clear the bits of W = grp ∪ adjacent components in a->w. */
static void mark_w(Asm *a, const int *grp, int ng, int on) {
  int nr = adjacent_roots(a, grp, ng);
  for (int j = 0; j < ng; j++) {
    if (on) us_bitset_set(&a->w, grp[j]);
    else us_bitset_clear(&a->w, grp[j]);
  }
  for (int q = 0; q < nr; q++)
    for (int v = a->head[a->roots[q]]; v >= 0; v = a->next[v]) {
      if (on) us_bitset_set(&a->w, v);
      else us_bitset_clear(&a->w, v);
    }
}

/* Test C ∪ grp through its component W: 1 stable, 0 not, < 0 stop. When
 * W is all of C ∪ grp (C connected, as in a wall), or when the workspace
 * tests locally in 2D (then C ∪ grp stands iff W does, by decoupling, and the
 * local test only visits grp's neighbourhood), the test is stated as a
 * change of the stability workspace's current set, kept equal to C
 * (tests by change): O(|grp|) per test instead of O(|W|), and nothing of
 * size n. Else W is marked and tested as a bitset (the full LP then
 * solves W, not all of C), which leaves the workspace's set at W, so C is
 * set again (O(n / 64)) before the next test by change. On stacker
 * stacks of 632 to 1,076 blocks, whose C has many components, testing W
 * as a bitset switched 93 bodies in and out per test and emptied the
 * plumb memo at every switch: 7-13 % more instructions, same plans. Not
 * in 3D (us_stability_tests_locally): piles there hand more tests to the
 * full system, which would then solve all of C instead of W. */
static int test_step(Asm *a, const int *grp, int ng, us_Error *err) {
  us_Stability *w = a->ctx->stab;
  if (us_stability_tests_locally(w) || would_be_size(a, grp, ng) == a->nplaced + ng) {
    if (!a->synced && us_stability_set_current(w, &a->cw, err)) return US_STEP_ERROR;
    a->synced = 1;
    for (int j = 0; j < ng; j++) us_stability_add(w, grp[j], NULL);
    int r = us_plan_test_current(a->ctx, err);
    for (int j = 0; j < ng; j++) us_stability_remove(w, grp[j], NULL);
    return r;
  }
  mark_w(a, grp, ng, 1);
  a->synced = 0;
  int r = us_plan_test(a->ctx, &a->w, err);
  mark_w(a, grp, ng, 0);
  return r;
}

/* ------------------------------------------------------------ placing */

/* Every body parked on root r: its W grew, but not next to it (a placed
 * neighbour makes it ready at once), so it is deferred; empty the list.
 * 0, or -1 out of memory. */
static int wake_list(Asm *a, int r) {
  IntVec *v = &a->wait[r];
  for (int k = 0; k < v->n; k++) {
    int b = v->v[k];
    if (a->state[b] != PARKED) continue;
    a->state[b] = DEFERRED;
    if (vec_push(&a->deferred, b)) return -1;
  }
  v->n = 0;
  return 0;
}

/* The deferred bodies into the heap; 1 if there were any. */
static int wake_deferred(Asm *a) {
  int any = 0;
  for (int k = 0; k < a->deferred.n; k++)
    if (a->state[a->deferred.v[k]] == DEFERRED) make_ready(a, a->deferred.v[k]), any = 1;
  a->deferred.n = 0;
  return any;
}

static int join(Asm *a, int b, int u) {
  int rb = us_dsu_find(&a->dsu, b), ru = us_dsu_find(&a->dsu, u);
  if (rb == ru) return 0;
  if (wake_list(a, ru) || wake_list(a, rb)) return -1;
  int r = us_dsu_union(&a->dsu, rb, ru), o = r == rb ? ru : rb;
  a->next[a->tail[r]] = a->head[o];
  a->tail[r] = a->tail[o];
  return 0;
}

static int place_one(Asm *a, int b, int record) {
  const us_Graph *g = &a->ctx->g;
  a->state[b] = PLACED;
  us_bitset_set(&a->out->built, b);
  us_bitset_set(&a->cw, b);
  if (a->synced) us_stability_add(a->ctx->stab, b, NULL);
  if (record) a->out->seq[a->out->nseq++] = b;
  a->nplaced++;
  for (int k = g->start[b]; k < g->start[b + 1]; k++) {
    int u = g->adj[k];
    if (a->state[u] == PLACED && join(a, b, u)) return -1;
  }
  return 0;
}

/* Place a step (one body or a group) and wake what it affects: its
 * neighbours now, the rest of its part's waiting bodies later. 0, or -1
 * out of memory. */
static int place_step(Asm *a, const int *grp, int ng) {
  const us_Graph *g = &a->ctx->g;
  for (int j = 0; j < ng; j++)
    if (place_one(a, grp[j], 1)) return -1;
  if (wake_list(a, us_dsu_find(&a->dsu, grp[0]))) return -1;
  for (int j = 0; j < ng; j++)
    for (int k = g->start[grp[j]]; k < g->start[grp[j] + 1]; k++) make_ready(a, g->adj[k]);
  a->out->gstart[++a->out->ngroups] = a->out->nseq;
  if (ng > a->out->max_group) a->out->max_group = ng;
  return 0;
}

static int park(Asm *a, int b) {
  a->state[b] = PARKED;
  a->stamp[b] = would_be_size(a, &b, 1);
  int nr = adjacent_roots(a, &b, 1);
  for (int q = 0; q < nr; q++)
    if (vec_push(&a->wait[a->roots[q]], b)) return -1;
  return 0;
}

/* Singles until the heap is empty: 1 something was placed, 0 nothing, <0 stop. */
static int run_singles(Asm *a, us_Error *err) {
  int placed = 0;
  while (a->nheap > 0 || wake_deferred(a)) {
    int b = heap_pop(a);
    if (a->state[b] != READY) continue;
    if (a->stamp[b] && a->stamp[b] == would_be_size(a, &b, 1)) {
      a->ctx->st->retries_skipped++; /* unchanged since it failed */
      if (park(a, b))
        return us_error_set(err, US_ERR_NOMEM, "out of memory in the assembly search"), US_STEP_ERROR;
      continue;
    }
    int r = test_step(a, &b, 1, err);
    if (r < 0) return r;
    if (r == 1) {
      if (place_step(a, &b, 1))
        return us_error_set(err, US_ERR_NOMEM, "out of memory in the assembly search"), US_STEP_ERROR;
      placed = 1;
    } else if (park(a, b)) {
      return us_error_set(err, US_ERR_NOMEM, "out of memory in the assembly search"), US_STEP_ERROR;
    }
  }
  return placed;
}

/* ------------------------------------------------------------- groups */

typedef struct {
  int grp[64];
  int ng, k;
  us_BitsetSet seen;
} GroupEnum;

/* Absent bodies of `within` adjacent to the group or to C's components
 * adjacent to it, into cand (capacity n); their count. */
static int group_frontier(Asm *a, const int *grp, int ng, int *cand) {
  const us_Graph *g = &a->ctx->g;
  int nc = 0, nr = adjacent_roots(a, grp, ng);
  for (int j = 0; j < ng + nr; j++) {
    int first = j < ng ? grp[j] : a->head[a->roots[j - ng]];
    for (int v = first; v >= 0; v = j < ng ? -1 : a->next[v])
      for (int k = g->start[v]; k < g->start[v + 1]; k++) {
        int u = g->adj[k];
        if ((a->state[u] == NEW || a->state[u] == PARKED || a->state[u] == READY ||
             a->state[u] == DEFERRED) &&
            !us_bitset_get(&a->w, u)) {
          us_bitset_set(&a->w, u);
          cand[nc++] = u;
        }
      }
  }
  for (int q = 0; q < nc; q++) us_bitset_clear(&a->w, cand[q]);
  return nc;
}

/* The group as a bitset key in a->w (caller clears). */
static void group_key(Asm *a, const GroupEnum *e, int on) {
  for (int j = 0; j < e->ng; j++) {
    if (on) us_bitset_set(&a->w, e->grp[j]);
    else us_bitset_clear(&a->w, e->grp[j]);
  }
}

/* A complete group of size k: test it unless seen or its W failed before. */
static int try_group(Asm *a, GroupEnum *e, us_Error *err) {
  group_key(a, e, 1);
  int fresh = us_bitset_set_add(&e->seen, &a->w);
  group_key(a, e, 0);
  if (fresh <= 0) return fresh < 0 ? US_STEP_ERROR : 0;
  mark_w(a, e->grp, e->ng, 1);
  int known = us_bitset_set_contains(&a->failed, &a->w);
  mark_w(a, e->grp, e->ng, 0);
  if (known) return a->ctx->st->retries_skipped++, 0;
  int r = test_step(a, e->grp, e->ng, err);
  if (r == 0) {
    mark_w(a, e->grp, e->ng, 1);
    int add = us_bitset_set_add(&a->failed, &a->w);
    mark_w(a, e->grp, e->ng, 0);
    if (add < 0) return US_STEP_ERROR;
  }
  return r;
}

/* Extend the group by one frontier body at a time (depth-first). */
static int extend_group(Asm *a, GroupEnum *e, us_Error *err) {
  if (e->ng == e->k) return try_group(a, e, err);
  int *cand = us_malloc(((size_t)a->ctx->s->nbody + 1) * sizeof(int));
  if (!cand) return US_STEP_ERROR;
  int nc = group_frontier(a, e->grp, e->ng, cand), r = 0;
  for (int q = 0; q < nc && r == 0; q++) {
    int dup = 0;
    for (int j = 0; j < e->ng && !dup; j++) dup = e->grp[j] == cand[q];
    if (dup) continue;
    e->grp[e->ng++] = cand[q];
    r = extend_group(a, e, err);
    if (r != 1) e->ng--; /* a group that stood stays in e->grp */
  }
  us_free(cand);
  return r;
}

/* Try groups of exactly k bodies seeded at bodies touching C or a support;
 * place the first that stands. 1 placed, 0 none, < 0 stop. */
static int run_groups(Asm *a, int k, us_Error *err) {
  GroupEnum e;
  memset(&e, 0, sizeof e);
  e.k = k;
  if (us_bitset_set_init(&e.seen, a->ctx->s->nbody)) return US_STEP_ERROR;
  int r = 0;
  for (int b = 0; b < a->ctx->s->nbody && r == 0; b++) {
    int st = a->state[b];
    if (st == PLACED || st == OUT || st == NEW) continue; /* seeds touch C or a support */
    e.grp[0] = b;
    e.ng = 1;
    r = extend_group(a, &e, err);
  }
  us_bitset_set_free(&e.seen);
  if (r == 1 && place_step(a, e.grp, e.ng)) r = US_STEP_ERROR;
  if (r == US_STEP_ERROR && err && !err->code)
    us_error_set(err, US_ERR_NOMEM, "out of memory in the assembly search");
  return r;
}

/* ---------------------------------------------------------------- driver */

/* Singles, then groups of 2..K; back to singles after every group. */
static int run(Asm *a, int max_group, us_Error *err) {
  for (;;) {
    int r = run_singles(a, err);
    if (r < 0) return r;
    if (a->nplaced == a->nwithin) return 1;
    int placed = 0;
    for (int k = 2; k <= max_group && !placed; k++) {
      r = run_groups(a, k, err);
      if (r < 0) return r;
      placed = r;
    }
    if (!placed) {
      a->out->max_group = max_group;
      return 0;
    }
  }
}

void us_assembly_free(us_Assembly *a) {
  us_bitset_free(&a->built);
  us_free(a->seq);
  us_free(a->gstart);
  memset(a, 0, sizeof *a);
}

/* The start set is in place before the first test (it stands by the
 * caller's word); its absent neighbours become candidates. */
static int place_start(Asm *a, const us_Bitset *start) {
  const us_Graph *g = &a->ctx->g;
  int n = a->ctx->s->nbody;
  for (int i = 0; i < n; i++)
    if (a->state[i] != OUT && us_bitset_get(start, i) && place_one(a, i, 0)) return -1;
  for (int i = 0; i < n; i++)
    if (a->state[i] == PLACED)
      for (int k = g->start[i]; k < g->start[i + 1]; k++) make_ready(a, g->adj[k]);
  return 0;
}

int us_assemble_from(us_SearchCtx *ctx, const us_Bitset *within, const us_Bitset *start,
                     int max_group, us_Assembly *out, us_Error *err) {
  memset(out, 0, sizeof *out);
  size_t m = (size_t)ctx->s->nbody + 1;
  Asm a;
  memset(&a, 0, sizeof a);
  out->seq = us_malloc(m * sizeof(int));
  out->gstart = us_calloc(m + 1, sizeof(int));
  int r = !out->seq || !out->gstart || us_bitset_init(&out->built, ctx->s->nbody) ||
                  asm_init(&a, ctx, within, out)
              ? US_STEP_ERROR
              : 0;
  if (r == 0 && start) r = place_start(&a, start);
  if (r == 0) r = run(&a, max_group, err);
  if (r == US_STEP_ERROR && err && !err->code)
    us_error_set(err, US_ERR_NOMEM, "out of memory in the assembly search");
  if (a.ctx == ctx) asm_free(&a);
  return r;
}

int us_assemble(us_SearchCtx *ctx, const us_Bitset *within, int max_group, us_Assembly *out,
                us_Error *err) {
  return us_assemble_from(ctx, within, NULL, max_group, out, err);
}
