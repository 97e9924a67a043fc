/* The tree formula (TREESUBGRAPHS): connected sub-graphs containing the
 * root of a tree, in one pass from the leaves up.
 *
 * Rooted at G, a connected set containing a node v is v plus, for every
 * child c independently, either nothing of c's subtree or a connected set
 * containing c: f(v) = prod over children c of (1 + f(c)), a leaf has
 * f = 1, and the count is f(G).
 *
 * A breadth-first pass from G gives parents and an order in which every
 * node comes after its parent; walking that order backwards, each node's
 * product is complete when the node is reached, and (1 + f(v)) is folded
 * into the parent's product at once, so no f is kept longer than needed.
 * A product keeps its one-limb factors in a 64-bit pending factor until
 * the next one would overflow it: a star of k leaves costs k / 63 passes
 * over its big product instead of k, and a node whose f fits one limb
 * allocates nothing. An empty product (acc.n == 0) means 1; products are
 * never 0, so that mark is unambiguous. */
#include "analysis/count.h"

#include <string.h>

typedef struct TreeWork {
  int *order;      /* breadth-first order of the reached vertices */
  int *parent;     /* [n] parent vertex, or n for G */
  unsigned char *seen;
  us_Big *acc;     /* [n + 1] products so far (index n: G) */
  uint64_t *pend;  /* [n + 1] pending one-limb factors */
} TreeWork;

static void tree_work_free(TreeWork *t, int n) {
  if (t->acc)
    for (int i = 0; i <= n; i++) us_big_free(&t->acc[i]);
  us_free(t->order);
  us_free(t->parent);
  us_free(t->seen);
  us_free(t->acc);
  us_free(t->pend);
}

static int tree_work_init(TreeWork *t, int n) {
  size_t m = (size_t)n + 1;
  t->order = us_malloc(m * sizeof(int));
  t->parent = us_malloc(m * sizeof(int));
  t->seen = us_calloc(m, 1);
  t->acc = us_calloc(m, sizeof(us_Big));
  t->pend = us_malloc(m * sizeof(uint64_t));
  if (!t->order || !t->parent || !t->seen || !t->acc || !t->pend) return -1;
  for (size_t i = 0; i < m; i++) t->pend[i] = 1;
  return 0;
}

static int in_set(const us_Bitset *b, int v) { return !b || us_bitset_get(b, v); }

/* Breadth-first from G over the vertices of R; returns how many. */
static int tree_bfs(const us_CGraph *g, const us_Bitset *R, const us_Bitset *A, TreeWork *t) {
  int tail = 0;
  for (int v = 0; v < g->n; v++)
    if (in_set(R, v) && (A ? us_bitset_get(A, v) : g->gadj[v]))
      t->seen[v] = 1, t->parent[v] = g->n, t->order[tail++] = v;
  for (int head = 0; head < tail; head++) {
    int v = t->order[head];
    for (int k = g->start[v]; k < g->start[v + 1]; k++) {
      int u = g->adj[k];
      if (in_set(R, u) && !t->seen[u]) t->seen[u] = 1, t->parent[u] = v, t->order[tail++] = u;
    }
  }
  return tail;
}

/* Move the pending factor into the big product. */
static int flush(us_Big *acc, uint64_t *pend) {
  int rc = acc->n == 0 ? us_big_set_u64(acc, *pend) : us_big_mul_u64(acc, *pend);
  if (!rc) *pend = 1;
  return rc;
}

/* Product *= x. */
static int fold(us_Big *acc, uint64_t *pend, const us_Big *x) {
  uint64_t x0, p;
  if (us_big_to_u64(x, &x0)) {
    if (!__builtin_mul_overflow(*pend, x0, &p)) return *pend = p, 0;
    if (flush(acc, pend)) return -1;
    *pend = x0;
    return 0;
  }
  return acc->n == 0 ? us_big_copy(acc, x) : us_big_mul(acc, acc, x);
}

/* x = 1 + f(v), f(v) being v's finished product (consumed). */
static int finish(us_Big *acc, uint64_t *pend, us_Big *x) {
  if (flush(acc, pend)) return -1;
  us_big_free(x);
  *x = *acc; /* the product moves into x */
  us_big_init(acc);
  return us_big_add_u64(x, 1);
}

us_Status us_count_tree(const us_CGraph *g, const us_Bitset *R, const us_Bitset *A, us_Big *out,
                        us_Error *err) {
  TreeWork t;
  memset(&t, 0, sizeof t);
  us_Big x;
  us_big_init(&x);
  int rc = tree_work_init(&t, g->n);
  int cnt = rc ? 0 : tree_bfs(g, R, A, &t);
  for (int i = cnt - 1; i >= 0 && !rc; i--) {
    int v = t.order[i], p = t.parent[v];
    uint64_t x1 = t.pend[v] + 1;
    us_Big small = {1, 1, &x1}; /* f(v) + 1 in one limb: no allocation */
    if (t.acc[v].n == 0 && x1 != 0) rc = fold(&t.acc[p], &t.pend[p], &small);
    else rc = finish(&t.acc[v], &t.pend[v], &x) || fold(&t.acc[p], &t.pend[p], &x);
  }
  if (!rc) rc = flush(&t.acc[g->n], &t.pend[g->n]) || us_big_copy(out, &t.acc[g->n]);
  us_big_free(&x);
  tree_work_free(&t, g->n);
  if (rc) return us_error_set(err, US_ERR_NOMEM, "count: out of memory in the tree formula");
  return US_OK;
}
