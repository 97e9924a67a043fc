/* Exact buildability: can a sub-assembly be emptied in steps of at most K
 * bodies, every intermediate standing? (docs/planning.md has the proofs.)
 *
 * The decision splits over components (the contact graph's classes, with
 * supports not joining anything):
 *   - X stands iff each component of X stands (decoupling: the equilibrium
 *     rows of two components share no contact);
 *   - X can be emptied iff each component of X can: build the components
 *     one after another (a component never touches the others, so every
 *     intermediate is a disjoint, non-touching union of standing parts), and
 *     conversely restrict an order of X to one component Y (every
 *     intermediate Q ∩ Y is a union of components of Q, so it stands).
 * So for a connected set C: C can be emptied iff C stands and some step G
 * (1 <= |G| <= K) leaves C \ G whose components can all be emptied. The
 * answers are memoised per connected set, so the work is bounded by the
 * number of connected sub-assemblies (what `unstack count` counts) times
 * the steps tried, not by the number of subsets.
 *
 * Fast path: greedy assembly (assemble.c) inside C. When it rebuilds C its
 * order, reversed, empties C and nothing else is searched. When it is stuck
 * nothing follows from that alone (buildable sets are not closed under
 * union when they overlap: two bodies may each be holdable by a third but
 * not both together), so the exhaustive step above decides.
 *
 * Budget: one decision may run at most set->max_exact_tests stability
 * tests (the recursion is exponential in the worst case); past it the
 * plan ends in `limit`, never in a guess.
 *
 * Storage: every decided connected set is a key of `keys`; ok[i] its
 * answer and, when it can be emptied, its removal order as a slice of
 * `body` with step ends marked in `end`. Orders of a set are concatenations
 * of its parts' orders, so a whole plan is read off the memo. */
#include "assemble.h"
#include "exact.h"
#include "hook.h"
#include "order.h"

#include "model/massprops.h"

#include <string.h>

typedef struct {
  int *body;          /* removal orders */
  unsigned char *end; /* 1 where a step ends */
  long n, cap;
} Pool;

struct us_Exact {
  int K;
  us_BitsetSet keys;
  signed char *ok;    /* [key] 1 can be emptied, 0 not */
  long *off;          /* [key] start of its order in store */
  int *len;           /* [key] bodies in it */
  long nkey_cap;
  Pool store;         /* orders of the memoised sets, append only */
  Pool work;          /* orders under construction, a stack */
};

static void pool_free(Pool *p) {
  us_free(p->body);
  us_free(p->end);
}

void us_exact_free(us_Exact *e) {
  if (!e) return;
  us_bitset_set_free(&e->keys);
  us_free(e->ok);
  us_free(e->off);
  us_free(e->len);
  pool_free(&e->store);
  pool_free(&e->work);
  us_free(e);
}

us_Exact *us_exact_new(int nbody, int K) {
  us_Exact *e = us_calloc(1, sizeof *e);
  if (!e) return NULL;
  e->K = K;
  if (us_bitset_set_init(&e->keys, nbody)) return us_exact_free(e), NULL;
  return e;
}

size_t us_exact_bytes(const us_Exact *e) {
  return us_bitset_set_bytes(&e->keys) + (size_t)e->nkey_cap * 13 +
         (size_t)(e->store.cap + e->work.cap) * 5;
}

/* ------------------------------------------------------------- memo */

static int pool_reserve(Pool *p, long extra) {
  if (p->n + extra <= p->cap) return 0;
  long ncap = p->cap ? p->cap : 1024;
  while (ncap < p->n + extra) ncap *= 2;
  int *b = us_realloc(p->body, (size_t)ncap * sizeof(int));
  if (!b) return -1;
  p->body = b;
  unsigned char *en = us_realloc(p->end, (size_t)ncap);
  if (!en) return -1;
  p->end = en;
  p->cap = ncap;
  return 0;
}

/* Append len entries of src starting at off to dst. */
static int pool_copy(Pool *dst, const Pool *src, long off, long len) {
  if (len <= 0) return 0;
  if (pool_reserve(dst, len)) return -1;
  memcpy(dst->body + dst->n, src->body + off, (size_t)len * sizeof(int));
  memcpy(dst->end + dst->n, src->end + off, (size_t)len);
  dst->n += len;
  return 0;
}

static int grow_keys(us_Exact *e) {
  long ncap = e->nkey_cap ? 2 * e->nkey_cap : 256;
  signed char *o = us_realloc(e->ok, (size_t)ncap);
  if (!o) return -1;
  e->ok = o;
  long *f = us_realloc(e->off, (size_t)ncap * sizeof(long));
  if (!f) return -1;
  e->off = f;
  int *l = us_realloc(e->len, (size_t)ncap * sizeof(int));
  if (!l) return -1;
  e->len = l;
  e->nkey_cap = ncap;
  return 0;
}

/* Record key `set` with answer ok; its order (if ok) is work[from ..n),
 * moved to the store; the work stack is popped back to from. */
static int memo_put(us_Exact *e, const us_Bitset *set, int ok, long from) {
  long i = (long)e->keys.count;
  if (i + 1 > e->nkey_cap && grow_keys(e)) return -1;
  long len = ok ? e->work.n - from : 0;
  if (pool_copy(&e->store, &e->work, from, len)) return -1;
  if (us_bitset_set_add(&e->keys, set) != 1) return -1;
  e->ok[i] = (signed char)ok;
  e->off[i] = e->store.n - len;
  e->len[i] = (int)len;
  e->work.n = from;
  return 0;
}

/* Append the memoised order of key i to the work stack. */
static int append_order(us_Exact *e, long i) {
  return pool_copy(&e->work, &e->store, e->off[i], e->len[i]);
}

static int append_step(us_Exact *e, const int *g, int ng) {
  if (pool_reserve(&e->work, ng)) return -1;
  for (int j = 0; j < ng; j++) {
    e->work.body[e->work.n] = g[j];
    e->work.end[e->work.n++] = (unsigned char)(j == ng - 1);
  }
  return 0;
}

/* ---------------------------------------------------------- solving */

typedef struct {
  us_SearchCtx *ctx;
  us_Exact *e;
  us_Error *err;
  int depth;
} Solver;

static int solve(Solver *sv, const us_Bitset *comp);

/* Bodies of `set` listed component by component (order[first[c] ..
 * first[c + 1])); returns the number of components or -1 on OOM. */
static int split(const us_SearchCtx *ctx, const us_Bitset *set, int **order, int **first) {
  int n = ctx->s->nbody, *comp = us_malloc(((size_t)n + 1) * sizeof(int)),
      *stack = us_malloc(((size_t)n + 1) * sizeof(int));
  *order = us_malloc(((size_t)n + 1) * sizeof(int));
  *first = us_calloc((size_t)n + 2, sizeof(int));
  int k = -1;
  if (comp && stack && *order && *first) {
    k = us_graph_components(&ctx->g, set, comp, stack);
    for (int i = 0; i < n; i++)
      if (comp[i] >= 0) (*first)[comp[i] + 1]++;
    for (int c = 0; c < k; c++) (*first)[c + 1] += (*first)[c];
    for (int i = 0; i < n; i++)
      if (comp[i] >= 0) (*order)[(*first)[comp[i]]++] = i;
    for (int c = k; c > 0; c--) (*first)[c] = (*first)[c - 1];
    (*first)[0] = 0;
  }
  us_free(comp);
  us_free(stack);
  return k;
}

/* Solve every component of `set` (its bodies in order/first); on success
 * append their orders. 1, 0, < 0. */
static int solve_parts(Solver *sv, us_Bitset *scratch, const int *order, const int *first,
                       int k) {
  for (int c = 0; c < k; c++) {
    for (int q = first[c]; q < first[c + 1]; q++) us_bitset_set(scratch, order[q]);
    int r = solve(sv, scratch);
    long i = r == 1 ? us_bitset_set_index(&sv->e->keys, scratch) : -1;
    for (int q = first[c]; q < first[c + 1]; q++) us_bitset_clear(scratch, order[q]);
    if (r != 1) return r;
    if (append_order(sv->e, i)) return US_STEP_ERROR;
  }
  return 1;
}

/* Try step g out of comp: the rest's components must all be emptied. */
static int try_step(Solver *sv, const us_Bitset *comp, const int *g, int ng) {
  us_Bitset rest = {0};
  if (us_bitset_copy(&rest, comp)) return US_STEP_ERROR;
  for (int j = 0; j < ng; j++) us_bitset_clear(&rest, g[j]);
  int *order = NULL, *first = NULL, k = split(sv->ctx, &rest, &order, &first), r = US_STEP_ERROR;
  long from = sv->e->work.n;
  if (k >= 0 && !append_step(sv->e, g, ng)) {
    memset(rest.w, 0, (size_t)rest.nwords * sizeof(uint64_t));
    r = solve_parts(sv, &rest, order, first, k);
  }
  if (r != 1) sv->e->work.n = from;
  us_free(order);
  us_free(first);
  us_bitset_free(&rest);
  return r;
}

/* Steps of 1..K bodies out of comp (highest bodies first), as combinations
 * of positions in list[0..m). 1 found (its order appended), 0 none, < 0. */
static int exhaust(Solver *sv, const us_Bitset *comp, int *list, int m) {
  if (us_plan_sort_highest(sv->ctx->s, list, m)) return US_STEP_ERROR;
  int idx[64], g[64], r = 0;
  for (int k = 1; k <= sv->e->K && k <= m && r == 0; k++) {
    for (int j = 0; j < k; j++) idx[j] = j;
    for (;;) {
      for (int j = 0; j < k; j++) g[j] = list[idx[j]];
      r = try_step(sv, comp, g, k);
      if (r != 0) break;
      int j = k - 1;
      while (j >= 0 && idx[j] == m - k + j) j--;
      if (j < 0) break;
      idx[j]++;
      for (int q = j + 1; q < k; q++) idx[q] = idx[q - 1] + 1;
    }
  }
  return r;
}

/* ---------------------------------------------------------------- cut */

/* The cut (docs/planning.md): a proof, from the greedy's stuck set B,
 * that a connected set C cannot be built. Call a connected group H of at
 * most K bodies of C outside a set R "startable on R" when H can stand
 * with every body of R held still. Grow R from B by startable groups
 * until none is left. Claim: no build of C ever places a body outside
 * the final R. The first step that would places some G and finds in
 * place only bodies X ⊆ R; the bodies of G outside R form parts (their
 * components among themselves) that each stand with X held, hence with R
 * held (holding more bodies only adds contacts with free forces): a
 * startable group outside R, which the growth would have taken. So
 * R ≠ C proves C unbuildable. "Cannot stand held" is a mechanism checked
 * against the true cones; a group touching neither R nor a support has no
 * force against its weight. A group is tried again only when a body it
 * touches joined R (its seeds are re-queued), and one cut tries at most
 * 16 n + 1024 groups, past which it proves nothing and the exhaustive
 * search decides. */
typedef struct {
  Solver *sv;
  const us_Bitset *comp;
  us_Bitset reach;         /* R */
  us_Bitset grp_bits;      /* the group under test */
  us_BitsetSet seen;       /* groups met from the current seed */
  int grp[64], ng;
  int *queue, nq;          /* seeds: bodies of C \ R touching R or a support */
  unsigned char *queued;
  long left;               /* groups still allowed */
} Cut;

static int outside(const Cut *c, int b) {
  return us_bitset_get(c->comp, b) && !us_bitset_get(&c->reach, b);
}

static int touches_reach(const Cut *c, int b) {
  const us_Graph *g = &c->sv->ctx->g;
  if (g->grounded[b]) return 1;
  for (int k = g->start[b]; k < g->start[b + 1]; k++)
    if (us_bitset_get(&c->reach, g->adj[k])) return 1;
  return 0;
}

static void enqueue(Cut *c, int b) {
  if (!outside(c, b) || c->queued[b] || !touches_reach(c, b)) return;
  c->queued[b] = 1;
  c->queue[c->nq++] = b;
}

/* The group grp[0..ng): 1 it cannot stand on R held (proven), 0 it may. */
static int cut_group(Cut *c) {
  int touching = 0;
  for (int j = 0; j < c->ng && !touching; j++) touching = touches_reach(c, c->grp[j]);
  if (!touching) /* only its own contacts: nothing holds its weight, if it has one */
    return us_gravity_norm(c->sv->ctx->s->gravity) > 0 ? 1 : 0;
  us_SearchCtx *ctx = c->sv->ctx;
  if (us_plan_limit_reached(ctx)) return US_STEP_LIMIT;
  for (int j = 0; j < c->ng; j++) us_bitset_set(&c->reach, c->grp[j]);
  us_Status st = us_plan_held_test(ctx->stab, &c->reach, c->grp, c->ng, &ctx->res, c->sv->err);
  for (int j = 0; j < c->ng; j++) us_bitset_clear(&c->reach, c->grp[j]);
  ctx->st->held_tests++;
  return st ? US_STEP_ERROR : ctx->res.verdict == US_UNSTABLE;
}

/* The groups of C \ R that extend grp[0..ng): 1 none can stand, 0 one
 * may (left in grp), US_STEP_CUT_SPENT out of groups, another us_Step stop. */
static int cut_extend(Cut *c) {
  if (c->left-- <= 0) return US_STEP_CUT_SPENT;
  int r = cut_group(c);
  if (r != 1 || c->ng >= c->sv->e->K) return r;
  const us_Graph *g = &c->sv->ctx->g;
  for (int j = 0; j < c->ng; j++) {
    int u = c->grp[j];
    for (int k = g->start[u]; k < g->start[u + 1]; k++) {
      int v = g->adj[k];
      if (!outside(c, v) || us_bitset_get(&c->grp_bits, v)) continue;
      us_bitset_set(&c->grp_bits, v);
      int fresh = us_bitset_set_add(&c->seen, &c->grp_bits);
      if (fresh == 1) {
        c->grp[c->ng++] = v;
        r = cut_extend(c);
        if (r != 1) return r;
        c->ng--;
      }
      us_bitset_clear(&c->grp_bits, v);
      if (fresh < 0) return US_STEP_ERROR;
    }
  }
  return 1;
}

/* The groups containing `seed`: 1 none can stand, 0 one joined R. */
static int cut_seed(Cut *c, int seed) {
  c->grp[0] = seed;
  c->ng = 1;
  us_bitset_set(&c->grp_bits, seed);
  int r = 0;
  if (c->sv->e->K > 1) {
    us_bitset_set_free(&c->seen);
    r = us_bitset_set_init(&c->seen, c->sv->ctx->s->nbody) ||
                us_bitset_set_add(&c->seen, &c->grp_bits) < 0
            ? US_STEP_ERROR
            : 0;
  }
  if (r == 0) r = cut_extend(c);
  for (int j = 0; j < c->ng; j++) us_bitset_clear(&c->grp_bits, c->grp[j]);
  if (r != 0) return r;
  for (int j = 0; j < c->ng; j++) us_bitset_set(&c->reach, c->grp[j]);
  const us_Graph *g = &c->sv->ctx->g;
  for (int j = 0; j < c->ng; j++)
    for (int k = g->start[c->grp[j]]; k < g->start[c->grp[j] + 1]; k++) enqueue(c, g->adj[k]);
  return 0;
}

/* 1 C proven unbuildable by the cut from `built`, 0 not proven, < 0 stop. */
static int cut(Solver *sv, const us_Bitset *comp, const us_Bitset *built) {
  if (sv->e->K > 64) return 0;
  int n = sv->ctx->s->nbody, r = 0;
  Cut c;
  memset(&c, 0, sizeof c);
  c.sv = sv;
  c.comp = comp;
  c.left = 16L * n + 1024;
  c.queue = us_malloc(((size_t)n + 1) * sizeof(int));
  c.queued = us_calloc((size_t)n + 1, 1);
  if (!c.queue || !c.queued || us_bitset_copy(&c.reach, built) ||
      us_bitset_init(&c.grp_bits, n) || us_bitset_set_init(&c.seen, n))
    r = US_STEP_ERROR;
  for (int b = 0; b < n && r == 0; b++) enqueue(&c, b);
  int spent = 0;
  while (r == 0 && c.nq > 0) {
    int b = c.queue[--c.nq];
    c.queued[b] = 0;
    int q = outside(&c, b) ? cut_seed(&c, b) : 1;
    if (q == US_STEP_CUT_SPENT) spent = 1;
    else if (q < 0) r = q;
    if (spent) break;
  }
  if (r == 0 && !spent) r = us_bitset_count(&c.reach) < us_bitset_count(comp); /* R ⊆ C */
  if (r == US_STEP_ERROR && !sv->err->code) us_error_set(sv->err, US_ERR_NOMEM, "out of memory in the search");
  us_free(c.queue);
  us_free(c.queued);
  us_bitset_free(&c.reach);
  us_bitset_free(&c.grp_bits);
  us_bitset_set_free(&c.seen);
  if (r == 1) sv->ctx->st->cuts++;
  return r;
}

/* Greedy fast path: 1 with comp's reversed build order appended, 0 stuck
 * (then the cut may prove comp unbuildable: *proven = 1). */
static int greedy(Solver *sv, const us_Bitset *comp, int *proven) {
  us_Assembly a;
  int r = us_assemble(sv->ctx, comp, sv->e->K, &a, sv->err);
  *proven = 0;
  if (r == 1) {
    for (int k = a.ngroups - 1; r == 1 && k >= 0; k--)
      if (append_step(sv->e, a.seq + a.gstart[k], a.gstart[k + 1] - a.gstart[k])) r = US_STEP_ERROR;
  } else if (r == 0) {
    int c = cut(sv, comp, &a.built);
    if (c < 0) r = c;
    *proven = c == 1;
  }
  us_assembly_free(&a);
  return r;
}

/* A connected set: stands?, then greedy (and the cut), then exhaustive. */
static int decide(Solver *sv, const us_Bitset *comp) {
  int proven = 0, r = us_plan_test(sv->ctx, comp, sv->err);
  if (r == 1) r = greedy(sv, comp, &proven);
  else return r; /* does not stand (0) or stop */
  if (r != 0 || proven) return r;
  sv->ctx->st->exhaustive++;
  int n = sv->ctx->s->nbody, m = 0, *list = us_malloc(((size_t)n + 1) * sizeof(int));
  if (!list) return US_STEP_ERROR;
  for (int i = 0; i < n; i++)
    if (us_bitset_get(comp, i)) list[m++] = i;
  r = exhaust(sv, comp, list, m);
  us_free(list);
  return r;
}

static int solve(Solver *sv, const us_Bitset *comp) {
  long i = us_bitset_set_index(&sv->e->keys, comp);
  if (i >= 0) return sv->e->ok[i];
  if (sv->depth > 4096) return US_STEP_LIMIT; /* deeper than any search could finish */
  sv->depth++;
  long from = sv->e->work.n;
  int r = decide(sv, comp);
  sv->depth--;
  if (r < 0) {
    sv->e->work.n = from;
    return r;
  }
  return memo_put(sv->e, comp, r, from) ? US_STEP_ERROR : r;
}

int us_exact_solve(us_SearchCtx *ctx, us_Exact *e, const us_Bitset *set, int *order,
                   unsigned char *step_end, int *n, us_Error *err) {
  Solver sv = {ctx, e, err, 0};
  long budget = ctx->set->max_exact_tests;
  int outer = ctx->exact_end > 0; /* nested in another decision: its budget holds */
  if (!outer && budget > 0) ctx->exact_end = ctx->st->tests + budget;
  int *list = NULL, *first = NULL, k = split(ctx, set, &list, &first), r = US_STEP_ERROR;
  us_Bitset scratch = {0};
  long from = e->work.n;
  if (k >= 0 && !us_bitset_init(&scratch, ctx->s->nbody))
    r = solve_parts(&sv, &scratch, list, first, k);
  if (r == 1 && order) {
    *n = (int)(e->work.n - from);
    if (*n > 0) memcpy(order, e->work.body + from, (size_t)*n * sizeof(int));
    if (*n > 0 && step_end) memcpy(step_end, e->work.end + from, (size_t)*n);
  }
  e->work.n = from;
  if (!outer) ctx->exact_end = 0;
  us_bitset_free(&scratch);
  us_free(list);
  us_free(first);
  if (r == US_STEP_ERROR && err && !err->code)
    us_error_set(err, US_ERR_NOMEM, "out of memory in the search");
  return r;
}
