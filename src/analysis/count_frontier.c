/* The frontier (path-decomposition) dynamic programme: counts the sets S
 * of vertices such that S + G is connected, deciding one vertex at a time
 * along an order and remembering only how the decided vertices that still
 * have undecided neighbours (the frontier) are connected.
 *
 * State: for each frontier vertex in slot order, 0 when it is out of S, 1
 * when it is in S and joined to G through decided vertices of S, and a
 * label >= 2 naming its component otherwise. Labels >= 2 are canonical:
 * renumbered 2, 3, ... in order of first appearance, so two partial sets
 * that any completion treats alike have the same key. A layer maps each
 * key to the number of partial sets with that key (exact, in limbs).
 *
 * Step: v (the next vertex) is out (its label 0) or in; in merges the
 * components of its decided neighbours in S (all on the frontier, since
 * their last neighbour v is not yet decided), and G when v touches G. Then
 * every vertex whose last neighbour was v leaves the frontier (v too, when
 * it has no later neighbour). Invariant: no decided vertex of S lies in a
 * component without G that has left the frontier entirely; such a
 * component can never reach G, so a step that would leave one drops the
 * state. At the end the frontier is empty and the one key left (all
 * components joined to G) holds the count. The empty S is the all-out
 * path, counted once.
 *
 * Size: a layer holds at most the number of labelled set partitions of
 * its frontier; on planar graphs (walls, pyramids) the partitions are
 * non-crossing, about 4^w for width w. The order is chosen among a few
 * candidates (rows by y, columns by x, breadth first from G) for the
 * smallest largest frontier, each swept part by part (the parts of the
 * graph without G touch only through supports). Counts after t vertices
 * are at most 2^t, so a layer's limbs per count are fixed, t / 64 + 1. */
#include "analysis/count.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_WIDTH 250 /* labels fit in a byte: at most width + 2 */

/* ------------------------------------------------------------------ layer */

/* One layer: keys of w bytes, counts of nw limbs, open addressing over
 * state indices at load at most 1/2. A slot holds the state's index + 1
 * in its low 32 bits (0: empty) and the top 32 bits of the key's hash in
 * its high bits, so a probe reads one word and compares keys only when
 * the tags agree (each access is a cache miss on big layers); the full
 * hashes are kept for rehashing. */
#define SLOT_TAG(h) ((h) & 0xffffffff00000000ull)
#define MAX_STATES 0xfffffffeu

typedef struct Layer {
  int w, nw;
  size_t n, kcap, cap;
  uint64_t *slot;
  uint64_t *hash;
  unsigned char *key;
  uint64_t *val;
} Layer;

static void layer_free(Layer *L) {
  us_free(L->slot);
  us_free(L->hash);
  us_free(L->key);
  us_free(L->val);
  memset(L, 0, sizeof *L);
}

/* An empty layer with room for about `expect` states without rehashing. */
static int layer_init(Layer *L, int w, int nw, size_t expect) {
  memset(L, 0, sizeof *L);
  L->w = w;
  L->nw = nw;
  L->cap = 16;
  while (L->cap < 2 * expect && L->cap < ((size_t)1 << 40)) L->cap *= 2;
  L->slot = us_calloc(L->cap, sizeof(uint64_t));
  return L->slot ? 0 : -1;
}

static double layer_bytes(const Layer *L) {
  return (double)L->cap * sizeof(uint64_t) +
         (double)L->kcap * ((double)L->w + (double)(L->nw + 1) * sizeof(uint64_t));
}

/* 8 bytes at a time through a multiply-xorshift mix. */
static uint64_t key_hash(const unsigned char *k, int w) {
  uint64_t h = (uint64_t)w * 0x9e3779b97f4a7c15ull;
  for (int i = 0; i < w; i += 8) {
    uint64_t x = 0;
    memcpy(&x, k + i, (size_t)US_MIN(8, w - i));
    h = (h ^ x) * 0xbf58476d1ce4e5b9ull;
    h ^= h >> 31;
  }
  h *= 0x94d049bb133111ebull;
  return h ^ (h >> 29);
}

/* The slot of key k (hash h): where it is, or the empty slot where it
 * would go. */
static size_t layer_find(const Layer *L, const unsigned char *k, uint64_t h) {
  size_t m = L->cap - 1, i = (size_t)h & m;
  for (uint64_t e; (e = L->slot[i]) != 0; i = (i + 1) & m) {
    size_t j = (size_t)(uint32_t)e - 1;
    if (SLOT_TAG(e) == SLOT_TAG(h) && !memcmp(L->key + j * (size_t)L->w, k, (size_t)L->w)) break;
  }
  return i;
}

static int layer_rehash(Layer *L) {
  size_t cap = 2 * L->cap, m = cap - 1;
  uint64_t *slot = us_calloc(cap, sizeof(uint64_t));
  if (!slot) return -1;
  for (size_t j = 0; j < L->n; j++) {
    size_t i = (size_t)L->hash[j] & m;
    while (slot[i]) i = (i + 1) & m;
    slot[i] = SLOT_TAG(L->hash[j]) | (uint64_t)(j + 1);
  }
  us_free(L->slot);
  L->slot = slot;
  L->cap = cap;
  return 0;
}

/* Room for one more state; -1 out of memory (or past MAX_STATES). */
static int layer_reserve(Layer *L) {
  if (L->n >= MAX_STATES) return -1;
  if (2 * (L->n + 1) > L->cap && layer_rehash(L)) return -1;
  if (L->n < L->kcap) return 0;
  size_t kcap = L->kcap ? 2 * L->kcap : 64;
  unsigned char *key = us_realloc(L->key, kcap * (size_t)L->w + 1);
  if (!key) return -1;
  L->key = key;
  uint64_t *hash = us_realloc(L->hash, kcap * sizeof(uint64_t));
  if (!hash) return -1;
  L->hash = hash;
  uint64_t *val = us_realloc(L->val, kcap * (size_t)L->nw * sizeof(uint64_t));
  if (!val) return -1;
  L->val = val;
  L->kcap = kcap;
  return 0;
}

/* dst (nw limbs) += src (ns <= nw limbs) */
static void add_limbs(uint64_t *dst, int nw, const uint64_t *src, int ns) {
  uint64_t carry = 0;
  for (int i = 0; i < nw && (i < ns || carry); i++) {
    uint64_t x = i < ns ? src[i] : 0, s = dst[i] + x;
    uint64_t c1 = s < x;
    dst[i] = s + carry;
    carry = c1 | (dst[i] < s);
  }
}

/* Add count c (ns limbs) to key k. 0, or -1 out of memory. */
static int layer_add(Layer *L, const unsigned char *k, const uint64_t *c, int ns) {
  if (layer_reserve(L)) return -1;
  uint64_t h = key_hash(k, L->w);
  size_t i = layer_find(L, k, h);
  if (!L->slot[i]) {
    memcpy(L->key + L->n * (size_t)L->w, k, (size_t)L->w);
    memset(L->val + L->n * (size_t)L->nw, 0, (size_t)L->nw * sizeof(uint64_t));
    L->hash[L->n] = h;
    L->slot[i] = SLOT_TAG(h) | (uint64_t)++L->n;
  }
  add_limbs(L->val + ((size_t)(uint32_t)L->slot[i] - 1) * (size_t)L->nw, L->nw, c, ns);
  return 0;
}

/* ------------------------------------------------------------------ order */

/* Every candidate order is component-major: the parts of the graph
 * without G (bodies touching only through supports) are swept one after
 * the other, so their frontiers never add up; within a part the order
 * follows the candidate's rule. */

/* comp[v] = the part of v (numbered by lowest vertex); queue is scratch
 * of n ints. Returns the number of parts. */
static int parts(const us_CGraph *g, int *comp, int *queue) {
  int k = 0;
  for (int v = 0; v < g->n; v++) comp[v] = -1;
  for (int v0 = 0; v0 < g->n; v0++) {
    if (comp[v0] >= 0) continue;
    int tail = 0;
    comp[v0] = k, queue[tail++] = v0;
    for (int h = 0; h < tail; h++)
      for (int e = g->start[queue[h]]; e < g->start[queue[h] + 1]; e++)
        if (comp[g->adj[e]] < 0) comp[g->adj[e]] = k, queue[tail++] = g->adj[e];
    k++;
  }
  return k;
}

typedef struct SortItem {
  int c;
  double k1, k2;
  int v;
} SortItem;

static int cmp_item(const void *a, const void *b) {
  const SortItem *x = a, *y = b;
  if (x->c != y->c) return x->c < y->c ? -1 : 1;
  if (x->k1 != y->k1) return x->k1 < y->k1 ? -1 : 1;
  if (x->k2 != y->k2) return x->k2 < y->k2 ? -1 : 1;
  return (x->v > y->v) - (x->v < y->v);
}

/* ord = vertices by part, then centre coordinate `axis`, then the other. */
static int order_by_axis(const us_CGraph *g, const us_Structure *s, const int *comp, int axis,
                         int *ord) {
  SortItem *it = us_malloc((size_t)g->n * sizeof *it + 1);
  if (!it) return -1;
  for (int v = 0; v < g->n; v++) {
    const double *c = s->bodies[g->body[v]].com;
    it[v] = (SortItem){comp[v], c[axis], c[1 - axis], v};
  }
  qsort(it, (size_t)g->n, sizeof *it, cmp_item);
  for (int v = 0; v < g->n; v++) ord[v] = it[v].v;
  us_free(it);
  return 0;
}

/* ord = breadth-first order from G, part by part: the multi-source
 * breadth-first order, stably sorted by part (restricted to one part it is
 * that part's own breadth-first order). bfs and cnt: scratch of n + 1. */
static void order_bfs(const us_CGraph *g, const int *comp, int k, int *ord, int *bfs, int *cnt) {
  int tail = 0;
  for (int v = 0; v < g->n; v++) ord[v] = 0; /* seen marks */
  for (int v = 0; v < g->n; v++)
    if (g->gadj[v]) ord[v] = 1, bfs[tail++] = v;
  for (int head = 0; head < tail; head++)
    for (int e = g->start[bfs[head]]; e < g->start[bfs[head] + 1]; e++)
      if (!ord[g->adj[e]]) ord[g->adj[e]] = 1, bfs[tail++] = g->adj[e];
  memset(cnt, 0, ((size_t)k + 1) * sizeof(int));
  for (int v = 0; v < g->n; v++) cnt[comp[v] + 1]++;
  for (int c = 0; c < k; c++) cnt[c + 1] += cnt[c];
  for (int i = 0; i < tail; i++) ord[cnt[comp[bfs[i]]]++] = bfs[i];
}

/* pos (inverse of ord) and last[v] = the last step with v on the
 * frontier's input: the largest position among v and its neighbours. */
static void order_last(const us_CGraph *g, const int *ord, int *pos, int *last) {
  for (int t = 0; t < g->n; t++) pos[ord[t]] = t;
  for (int v = 0; v < g->n; v++) {
    last[v] = pos[v];
    for (int k = g->start[v]; k < g->start[v + 1]; k++) last[v] = US_MAX(last[v], pos[g->adj[k]]);
  }
}

/* The largest frontier of an order (*sum: the sum over steps, to break
 * ties); diff is scratch of n + 1 ints. */
static int order_width(const us_CGraph *g, const int *pos, const int *last, int *diff, long *sum) {
  memset(diff, 0, ((size_t)g->n + 1) * sizeof(int));
  for (int v = 0; v < g->n; v++)
    if (last[v] > pos[v]) diff[pos[v]]++, diff[last[v]]--;
  int w = 0, cur = 0;
  *sum = 0;
  for (int t = 0; t < g->n; t++) cur += diff[t], w = US_MAX(w, cur), *sum += cur;
  return w;
}

/* ----------------------------------------------------------- programme */

typedef struct Frontier {
  const us_CGraph *g;
  us_CountRun *run;
  int *ord, *pos, *last;
  int width;
  int *fr, f;          /* frontier vertices in slot order */
  int *slot_of;        /* [n] slot of a frontier vertex, else -1 */
  int *keep, vslot, f2;/* step: new slot of each old slot (-1 leaves), of v */
  int *nb, nnb;        /* step: old slots of v's decided neighbours */
  int *comp, *tmp;     /* order choice: part of each vertex, scratch */
  unsigned char lab[MAX_WIDTH + 4], key2[MAX_WIDTH + 4], map[MAX_WIDTH + 4];
  int cnt[MAX_WIDTH + 4];
  Layer cur, next;
} Frontier;

static void frontier_free(Frontier *F) {
  us_free(F->ord);
  us_free(F->pos);
  us_free(F->last);
  us_free(F->fr);
  us_free(F->slot_of);
  us_free(F->keep);
  us_free(F->nb);
  us_free(F->comp);
  us_free(F->tmp);
  layer_free(&F->cur);
  layer_free(&F->next);
}

static int frontier_alloc(Frontier *F, int n) {
  size_t m = (size_t)n + 1;
  F->ord = us_malloc(m * sizeof(int));
  F->pos = us_malloc(m * sizeof(int));
  F->last = us_malloc(m * sizeof(int));
  F->fr = us_malloc(m * sizeof(int));
  F->slot_of = us_malloc(m * sizeof(int));
  F->keep = us_malloc(m * sizeof(int));
  F->nb = us_malloc(m * sizeof(int));
  F->comp = us_malloc(m * sizeof(int));
  F->tmp = us_malloc(m * sizeof(int));
  if (!F->ord || !F->pos || !F->last || !F->fr || !F->slot_of || !F->keep || !F->nb ||
      !F->comp || !F->tmp)
    return -1;
  for (int v = 0; v < n; v++) F->slot_of[v] = -1;
  return 0;
}

/* Try the candidate orders; keep the narrowest in F->ord, pos, last. */
static int choose_order(Frontier *F, const us_Structure *s) {
  const us_CGraph *g = F->g;
  static const char *const names[] = {"rows (by y)", "columns (by x)", "breadth first from G"};
  int best = -1, bw = 0;
  long bsum = 0, sum;
  int k = parts(g, F->comp, F->tmp);
  for (int c = 0; c < 3; c++) {
    if (c < 2 && order_by_axis(g, s, F->comp, 1 - c, F->keep)) return -1;
    if (c == 2) order_bfs(g, F->comp, k, F->keep, F->tmp, F->nb);
    order_last(g, F->keep, F->pos, F->last);
    int w = order_width(g, F->pos, F->last, F->fr, &sum);
    if (best < 0 || w < bw || (w == bw && sum < bsum)) {
      best = c, bw = w, bsum = sum;
      memcpy(F->ord, F->keep, (size_t)g->n * sizeof(int));
    }
  }
  order_last(g, F->ord, F->pos, F->last);
  F->width = bw;
  snprintf(F->run->out->note, sizeof F->run->out->note, "order: %s, width %d", names[best], bw);
  return 0;
}

/* Step set-up for vertex v at position t: where each old slot goes, v's
 * slot, the slots of v's decided neighbours. */
static void plan_step(Frontier *F, int v, int t) {
  const us_CGraph *g = F->g;
  F->f2 = 0;
  for (int i = 0; i < F->f; i++) F->keep[i] = F->last[F->fr[i]] > t ? F->f2++ : -1;
  F->vslot = F->last[v] > t ? F->f2++ : -1;
  F->nnb = 0;
  for (int k = g->start[v]; k < g->start[v + 1]; k++)
    if (F->pos[g->adj[k]] < t) F->nb[F->nnb++] = F->slot_of[g->adj[k]];
}

/* Move the frontier on after the step. */
static void commit_step(Frontier *F, int v) {
  int f2 = 0;
  for (int i = 0; i < F->f; i++) {
    int u = F->fr[i];
    F->slot_of[u] = F->keep[i];
    if (F->keep[i] >= 0) F->fr[f2++] = u;
  }
  if (F->vslot >= 0) F->fr[f2++] = v, F->slot_of[v] = F->vslot;
  F->f = f2;
}

/* lab[0..f) old slots, lab[f] = v: 1 when some component would be cut off
 * from both G and the frontier (the state dies). */
static int cut_off(Frontier *F) {
  int f = F->f, dead = 0;
  for (int i = 0; i < f; i++)
    if (F->keep[i] >= 0) F->cnt[F->lab[i]]++;
  if (F->vslot >= 0) F->cnt[F->lab[f]]++;
  for (int i = 0; i <= f && !dead; i++) {
    int leaves = i < f ? F->keep[i] < 0 : F->vslot < 0;
    dead = leaves && F->lab[i] >= 2 && F->cnt[F->lab[i]] == 0;
  }
  memset(F->cnt, 0, ((size_t)f + 3) * sizeof(int));
  return dead;
}

/* key2 = lab moved to the new slots, labels >= 2 renumbered canonically. */
static void make_key(Frontier *F) {
  int f = F->f, next = 2;
  for (int i = 0; i < f; i++)
    if (F->keep[i] >= 0) F->key2[F->keep[i]] = F->lab[i];
  if (F->vslot >= 0) F->key2[F->vslot] = F->lab[f];
  memset(F->map, 0, (size_t)f + 3);
  for (int j = 0; j < F->f2; j++) {
    unsigned char l = F->key2[j];
    if (l < 2) continue;
    if (!F->map[l]) F->map[l] = (unsigned char)next++;
    F->key2[j] = F->map[l];
  }
}

/* v in S: merge the components of its neighbours in S (and G if v
 * touches it) into one label, v's. */
static void merge_in(Frontier *F, int v) {
  int f = F->f, ground = F->g->gadj[v], low = f + 2;
  unsigned char *in = F->map; /* labels to merge */
  memset(in, 0, (size_t)f + 3);
  for (int k = 0; k < F->nnb; k++) {
    unsigned char l = F->lab[F->nb[k]];
    if (l) in[l] = 1, low = US_MIN(low, (int)l);
  }
  unsigned char nl = (unsigned char)(ground ? 1 : low);
  for (int i = 0; i < f; i++)
    if (F->lab[i] && in[F->lab[i]]) F->lab[i] = nl;
  F->lab[f] = nl;
}

/* Both successors of one state (key k, count c of ns limbs). */
static int expand(Frontier *F, int v, const unsigned char *k, const uint64_t *c, int ns) {
  for (int pass = 0; pass < 2; pass++) {
    memcpy(F->lab, k, (size_t)F->f);
    F->lab[F->f] = 0;
    if (pass == 1) merge_in(F, v);
    if (cut_off(F)) continue;
    make_key(F);
    if (layer_add(&F->next, F->key2, c, ns)) return -1;
  }
  return 0;
}

/* One step: every state of cur into next. 0, 1 refused, -1 OOM. */
static int step(Frontier *F, int t) {
  int v = F->ord[t];
  plan_step(F, v, t);
  if (layer_init(&F->next, F->f2, (t + 1) / 64 + 1, F->cur.n)) return -1;
  us_CountRun *run = F->run;
  for (size_t i = 0; i < F->cur.n; i++) {
    if (us_count_tick(run)) return 1;
    if ((i & 1023) == 0 && us_count_over_memory(run, layer_bytes(&F->cur) + layer_bytes(&F->next)))
      return 1;
    if (F->next.n + 2 > MAX_STATES)
      return us_count_refuse(run, US_COUNT_REFUSED_MEMORY, "more than 2^32 - 2 states in a layer"), 1;
    const unsigned char *k = F->cur.key + i * (size_t)F->cur.w;
    if (expand(F, v, k, F->cur.val + i * (size_t)F->cur.nw, F->cur.nw)) return -1;
  }
  run->out->peak = US_MAX(run->out->peak, (long)F->next.n);
  commit_step(F, v);
  layer_free(&F->cur);
  F->cur = F->next;
  memset(&F->next, 0, sizeof F->next);
  return 0;
}

/* The first layer: the empty frontier, one way (nothing decided). */
static int start(Frontier *F) {
  uint64_t one = 1;
  return layer_init(&F->cur, 0, 1, 1) || layer_add(&F->cur, F->key2, &one, 1) ? -1 : 0;
}

us_Status us_count_frontier(const us_CGraph *g, us_CountRun *run, us_Big *out, us_Error *err) {
  Frontier F;
  memset(&F, 0, sizeof F);
  F.g = g;
  F.run = run;
  int rc = frontier_alloc(&F, g->n) || choose_order(&F, run->s) ? -1 : 0;
  run->out->width = F.width;
  if (!rc && F.width > MAX_WIDTH) {
    char msg[96];
    snprintf(msg, sizeof msg, "frontier width %d is more than %d", F.width, MAX_WIDTH);
    us_count_refuse(run, US_COUNT_REFUSED_SIZE, msg);
    rc = 1;
  }
  if (!rc) rc = start(&F);
  for (int t = 0; t < g->n && !rc; t++) rc = step(&F, t);
  if (!rc && us_big_set_words(out, F.cur.val, F.cur.nw)) rc = -1;
  frontier_free(&F);
  if (rc < 0) return us_error_set(err, US_ERR_NOMEM, "count: out of memory in the frontier programme");
  return US_OK;
}
