/* Deletion-contraction (SUBGRAPHS): the general count as a recursion on
 * the neighbours of the merged ground node, with memo, components and the
 * tree formula at trees.
 *
 * A sub-problem is (R, A): R the undecided vertices, A those of R adjacent
 * to the merged ground node G' (G plus every vertex already contracted into
 * it). count(R, A) = the number of T in R with T + G' connected. Pick v in
 * A (the lowest index, a sweep from the first body):
 *   count(R, A) = count(R - v, A - v)                      v not in T
 *               + count(R - v, (A + N(v) & R) - v)         v in T: contract v into G'
 * Reductions before branching, each exact:
 *   - vertices of R not reachable from A inside R are in no T: dropped;
 *   - A empty: 1 (T empty);
 *   - R splits into components (without G'): they choose independently,
 *     the count is the product;
 *   - G' + R is a tree (|A| + edges inside R == |R|): the tree formula;
 *   - (R, A) seen before: the memo (keys R and A as bitsets).
 * Each level removes one vertex, so the depth is at most n: past
 * MAX_DEPTH vertices the method refuses (the C stack). */
#include "analysis/count.h"

#include <stdio.h>
#include <string.h>

#define MAX_DEPTH 4096

/* ------------------------------------------------------------------- memo */

typedef struct Memo {
  int kw;            /* words per key: R then A */
  size_t n, cap, kcap;
  size_t *slot;      /* [cap] entry + 1, 0 empty */
  uint64_t *key;     /* [kcap * kw] */
  us_Big *val;       /* [kcap] */
  double bytes;
} Memo;

static void memo_free(Memo *m) {
  for (size_t i = 0; i < m->n; i++) us_big_free(&m->val[i]);
  us_free(m->slot);
  us_free(m->key);
  us_free(m->val);
  memset(m, 0, sizeof *m);
}

static uint64_t key_hash(const uint64_t *k, int kw) {
  uint64_t h = 0x9e3779b97f4a7c15ull;
  for (int i = 0; i < kw; i++) h = (h ^ k[i]) * 0xff51afd7ed558ccdull, h ^= h >> 32;
  return h;
}

static size_t memo_find(const Memo *m, const uint64_t *k) {
  size_t mask = m->cap - 1, i = (size_t)key_hash(k, m->kw) & mask;
  size_t kb = (size_t)m->kw * sizeof(uint64_t);
  while (m->slot[i] && memcmp(m->key + (m->slot[i] - 1) * (size_t)m->kw, k, kb)) i = (i + 1) & mask;
  return i;
}

static int memo_rehash(Memo *m) {
  size_t ncap = m->cap ? 2 * m->cap : 64, *old = m->slot, ocap = m->cap;
  size_t *slot = us_calloc(ncap, sizeof(size_t));
  if (!slot) return -1;
  m->slot = slot;
  m->cap = ncap;
  for (size_t i = 0; i < ocap; i++)
    if (old[i]) m->slot[memo_find(m, m->key + (old[i] - 1) * (size_t)m->kw)] = old[i];
  us_free(old);
  return 0;
}

static int memo_reserve(Memo *m) {
  if (2 * (m->n + 1) > m->cap && memo_rehash(m)) return -1;
  if (m->n < m->kcap) return 0;
  size_t kcap = m->kcap ? 2 * m->kcap : 64;
  uint64_t *key = us_realloc(m->key, kcap * (size_t)m->kw * sizeof(uint64_t));
  if (!key) return -1;
  m->key = key;
  us_Big *val = us_realloc(m->val, kcap * sizeof(us_Big));
  if (!val) return -1;
  m->val = val;
  m->kcap = kcap;
  return 0;
}

/* ------------------------------------------------------------- recursion */

typedef struct Contract {
  const us_CGraph *g;
  us_CountRun *run;
  int nw;            /* words per bitset */
  int *queue;        /* [n] */
  int *comp;         /* [n] component of a vertex in the current call, -1 none */
  uint64_t *kbuf;    /* [2 nw] memo key */
  Memo memo;
} Contract;

/* A sub-problem's sets. */
typedef struct Sub {
  us_Bitset R, A;
} Sub;

static void sub_free(Sub *s) {
  us_bitset_free(&s->R);
  us_bitset_free(&s->A);
}

static int sub_init(Sub *s, int n) {
  memset(s, 0, sizeof *s);
  return us_bitset_init(&s->R, n) || us_bitset_init(&s->A, n) ? -1 : 0;
}

/* Label the components of R reachable from A (comp[], from 0); every
 * other vertex gets -1. Returns the number of components. */
static int label_components(Contract *C, const Sub *p) {
  const us_CGraph *g = C->g;
  int k = 0;
  for (int v = 0; v < g->n; v++) C->comp[v] = -1;
  for (int a = 0; a < g->n; a++) {
    if (!us_bitset_get(&p->A, a) || C->comp[a] >= 0) continue;
    int tail = 0;
    C->comp[a] = k, C->queue[tail++] = a;
    for (int h = 0; h < tail; h++)
      for (int e = g->start[C->queue[h]]; e < g->start[C->queue[h] + 1]; e++) {
        int u = g->adj[e];
        if (us_bitset_get(&p->R, u) && C->comp[u] < 0) C->comp[u] = k, C->queue[tail++] = u;
      }
    k++;
  }
  return k;
}

/* parts[c] = component c of p (R and A restricted to it). */
static int split(Contract *C, const Sub *p, Sub *parts, int k) {
  for (int c = 0; c < k; c++)
    if (sub_init(&parts[c], C->g->n)) return -1;
  for (int v = 0; v < C->g->n; v++) {
    int c = C->comp[v];
    if (c < 0) continue;
    us_bitset_set(&parts[c].R, v);
    if (us_bitset_get(&p->A, v)) us_bitset_set(&parts[c].A, v);
  }
  return 0;
}

/* 1 when G' + R is a tree (R connected through G', as after split). */
static int is_tree(const Contract *C, const Sub *p) {
  const us_CGraph *g = C->g;
  long nv = 0, ne = us_bitset_count(&p->A), half = 0;
  for (int v = 0; v < g->n; v++) {
    if (!us_bitset_get(&p->R, v)) continue;
    nv++;
    for (int e = g->start[v]; e < g->start[v + 1]; e++) half += us_bitset_get(&p->R, g->adj[e]);
  }
  return ne + half / 2 == nv;
}

static int first_bit(const us_Bitset *b) {
  for (int i = 0; i < b->nwords; i++)
    if (b->w[i]) return i * 64 + __builtin_ctzll(b->w[i]);
  return -1;
}

static int count_sub(Contract *C, const Sub *p, us_Big *out);

/* The two branches at v: deleted, and contracted into G'. */
static int branch(Contract *C, const Sub *p, us_Big *out) {
  const us_CGraph *g = C->g;
  int v = first_bit(&p->A), rc;
  Sub d, c;
  memset(&d, 0, sizeof d), memset(&c, 0, sizeof c);
  us_Big x;
  us_big_init(&x);
  rc = sub_init(&d, g->n) || sub_init(&c, g->n) || us_bitset_copy(&d.R, &p->R) ||
               us_bitset_copy(&d.A, &p->A) || us_bitset_copy(&c.R, &p->R) ||
               us_bitset_copy(&c.A, &p->A) ? -1 : 0;
  if (!rc) {
    for (int e = g->start[v]; e < g->start[v + 1]; e++)
      if (us_bitset_get(&p->R, g->adj[e])) us_bitset_set(&c.A, g->adj[e]);
    us_bitset_clear(&d.R, v), us_bitset_clear(&d.A, v);
    us_bitset_clear(&c.R, v), us_bitset_clear(&c.A, v);
    rc = count_sub(C, &d, out);
  }
  if (!rc) rc = count_sub(C, &c, &x);
  if (!rc && us_big_add(out, &x)) rc = -1;
  us_big_free(&x);
  sub_free(&d);
  sub_free(&c);
  return rc;
}

/* The memo key of p: R's words, then A's. */
static const uint64_t *make_key(Contract *C, const Sub *p) {
  memcpy(C->kbuf, p->R.w, (size_t)C->nw * sizeof(uint64_t));
  memcpy(C->kbuf + C->nw, p->A.w, (size_t)C->nw * sizeof(uint64_t));
  return C->kbuf;
}

static int memo_put(Contract *C, const Sub *p, const us_Big *val) {
  Memo *m = &C->memo;
  if (us_count_over_memory(C->run, m->bytes)) return 1;
  if (memo_reserve(m)) return -1;
  size_t i = memo_find(m, make_key(C, p));
  if (m->slot[i]) return 0;
  us_big_init(&m->val[m->n]);
  if (us_big_copy(&m->val[m->n], val)) return -1;
  memcpy(m->key + m->n * (size_t)m->kw, C->kbuf, (size_t)m->kw * sizeof(uint64_t));
  m->slot[i] = ++m->n;
  m->bytes += (double)m->kw * 8.0 + (double)val->cap * 8.0 + sizeof(us_Big) + 2 * sizeof(size_t);
  C->run->out->peak = (long)m->n;
  return 0;
}

/* One connected sub-problem (a single component): memo, tree, branch. */
static int count_connected(Contract *C, const Sub *p, us_Big *out) {
  Memo *m = &C->memo;
  if (m->cap) {
    size_t i = memo_find(m, make_key(C, p));
    if (m->slot[i]) return us_big_copy(out, &m->val[m->slot[i] - 1]) ? -1 : 0;
  }
  int rc;
  if (is_tree(C, p)) rc = us_count_tree(C->g, &p->R, &p->A, out, NULL) ? -1 : 0;
  else rc = branch(C, p, out);
  return rc ? rc : memo_put(C, p, out);
}

/* count(R, A) into out: 0, 1 refused, -1 out of memory. */
static int count_sub(Contract *C, const Sub *p, us_Big *out) {
  if (us_count_tick(C->run)) return 1;
  int k = label_components(C, p);
  if (k == 0) return us_big_set_u64(out, 1) ? -1 : 0;
  Sub *parts = us_calloc((size_t)k, sizeof(Sub));
  int rc = !parts || split(C, p, parts, k) ? -1 : 0;
  us_Big x;
  us_big_init(&x);
  if (!rc) rc = count_connected(C, &parts[0], out);
  for (int c = 1; c < k && !rc; c++) {
    rc = count_connected(C, &parts[c], &x);
    if (!rc && us_big_mul(out, out, &x)) rc = -1;
  }
  us_big_free(&x);
  for (int c = 0; parts && c < k; c++) sub_free(&parts[c]);
  us_free(parts);
  return rc;
}

static void contract_free(Contract *C) {
  us_free(C->queue);
  us_free(C->comp);
  us_free(C->kbuf);
  memo_free(&C->memo);
}

/* The root problem: every vertex, A = the vertices touching G. */
static int root(const us_CGraph *g, Sub *p) {
  if (sub_init(p, g->n)) return -1;
  us_bitset_fill(&p->R);
  for (int v = 0; v < g->n; v++)
    if (g->gadj[v]) us_bitset_set(&p->A, v);
  return 0;
}

us_Status us_count_contract(const us_CGraph *g, us_CountRun *run, us_Big *out, us_Error *err) {
  if (g->n > MAX_DEPTH) {
    char msg[96];
    snprintf(msg, sizeof msg, "deletion-contraction recurses once per body: at most %d, not %d",
             MAX_DEPTH, g->n);
    us_count_refuse(run, US_COUNT_REFUSED_SIZE, msg);
    return US_OK;
  }
  Contract C;
  memset(&C, 0, sizeof C);
  C.g = g;
  C.run = run;
  C.nw = (g->n + 63) / 64 > 0 ? (g->n + 63) / 64 : 1;
  C.memo.kw = 2 * C.nw;
  C.queue = us_malloc((size_t)g->n * sizeof(int) + 1);
  C.comp = us_malloc((size_t)g->n * sizeof(int) + 1);
  C.kbuf = us_malloc((size_t)C.memo.kw * sizeof(uint64_t));
  Sub p;
  memset(&p, 0, sizeof p);
  int rc = !C.queue || !C.comp || !C.kbuf || root(g, &p) ? -1 : 0;
  if (!rc) rc = count_sub(&C, &p, out);
  sub_free(&p);
  contract_free(&C);
  if (rc < 0) return us_error_set(err, US_ERR_NOMEM, "count: out of memory in deletion-contraction");
  return US_OK;
}
