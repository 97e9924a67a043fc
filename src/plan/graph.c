/* The planner's contact graph (graph.h): CSR adjacency built in
 * O(contacts log contacts), components by iterative depth-first search,
 * union-find for the assembly search. */
#include "graph.h"

#include <stdlib.h>
#include <string.h>

static int cmp_int(const void *a, const void *b) {
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

/* Count (pass 0) or store (pass 1) the movable-movable half edges.
 * fixed[i + 1]: body i is a support (fixed[0]: the ground), a byte table
 * so that the passes read the contacts in order and touch no body. */
static void fill_edges(us_Graph *g, const us_Structure *s, const unsigned char *fixed, int *fill) {
  for (int k = 0; k < s->ncontact; k++) {
    int a = s->contacts[k].a, b = s->contacts[k].b;
    int sa = fixed[a < 0 ? 0 : a + 1], sb = fixed[b < 0 ? 0 : b + 1];
    if (sa && !sb) g->grounded[b] = 1;
    if (sb && !sa) g->grounded[a] = 1;
    if (sa || sb || a == b) continue;
    if (fill) {
      g->adj[fill[a]++] = b;
      g->adj[fill[b]++] = a;
    } else {
      g->start[a + 1]++;
      g->start[b + 1]++;
    }
  }
}

/* Sort a row: insertion for the short rows of most bodies, else qsort. */
static void sort_row(int *v, int n) {
  if (n > 16) {
    qsort(v, (size_t)n, sizeof(int), cmp_int);
    return;
  }
  for (int i = 1; i < n; i++) {
    int x = v[i], j = i;
    for (; j > 0 && v[j - 1] > x; j--) v[j] = v[j - 1];
    v[j] = x;
  }
}

/* Sort each row and drop repeated neighbours (several contacts per pair). */
static void dedup_rows(us_Graph *g) {
  int out = 0;
  for (int i = 0; i < g->n; i++) {
    int b = g->start[i], e = g->start[i + 1];
    sort_row(g->adj + b, e - b);
    g->start[i] = out;
    for (int k = b; k < e; k++)
      if (k == b || g->adj[k] != g->adj[k - 1]) g->adj[out++] = g->adj[k];
  }
  g->start[g->n] = out;
}

int us_graph_init(us_Graph *g, const us_Structure *s) {
  memset(g, 0, sizeof *g);
  g->n = s->nbody;
  g->start = us_calloc((size_t)g->n + 1, sizeof(int));
  g->grounded = us_calloc((size_t)g->n + 1, 1);
  unsigned char *fixed = us_malloc((size_t)g->n + 1);
  if (!g->start || !g->grounded || !fixed) return us_free(fixed), us_graph_free(g), -1;
  fixed[0] = 1;
  for (int i = 0; i < g->n; i++) fixed[i + 1] = s->bodies[i].fixed != 0;
  fill_edges(g, s, fixed, NULL);
  for (int i = 0; i < g->n; i++) g->start[i + 1] += g->start[i];
  int *fill = us_malloc(((size_t)g->n + 1) * sizeof(int));
  g->adj = us_malloc(((size_t)g->start[g->n] + 1) * sizeof(int));
  if (!fill || !g->adj) {
    us_free(fill);
    us_free(fixed);
    return us_graph_free(g), -1;
  }
  memcpy(fill, g->start, (size_t)g->n * sizeof(int));
  fill_edges(g, s, fixed, fill);
  us_free(fill);
  us_free(fixed);
  dedup_rows(g);
  return 0;
}

void us_graph_free(us_Graph *g) {
  us_free(g->start);
  us_free(g->adj);
  us_free(g->grounded);
  memset(g, 0, sizeof *g);
}

int us_dsu_init(us_Dsu *d, int n) {
  d->parent = us_malloc(((size_t)n + 1) * sizeof(int));
  d->size = us_malloc(((size_t)n + 1) * sizeof(int));
  if (!d->parent || !d->size) return us_dsu_free(d), -1;
  for (int i = 0; i < n; i++) d->parent[i] = i, d->size[i] = 1;
  return 0;
}

void us_dsu_free(us_Dsu *d) {
  us_free(d->parent);
  us_free(d->size);
  d->parent = d->size = NULL;
}

int us_dsu_find(us_Dsu *d, int x) {
  while (d->parent[x] != x) x = d->parent[x] = d->parent[d->parent[x]];
  return x;
}

int us_dsu_union(us_Dsu *d, int a, int b) {
  a = us_dsu_find(d, a);
  b = us_dsu_find(d, b);
  if (a == b) return a;
  if (d->size[a] < d->size[b]) {
    int t = a;
    a = b;
    b = t;
  }
  d->parent[b] = a;
  d->size[a] += d->size[b];
  return a;
}

/* Label every body reachable from `root` inside `node` with `label`. */
static void flood(const us_Graph *g, const us_Bitset *node, int root, int label, int *comp,
                  int *stack) {
  int top = 0;
  stack[top++] = root;
  comp[root] = label;
  while (top > 0) {
    int v = stack[--top];
    for (int k = g->start[v]; k < g->start[v + 1]; k++) {
      int u = g->adj[k];
      if (comp[u] < 0 && us_bitset_get(node, u)) {
        comp[u] = label;
        stack[top++] = u;
      }
    }
  }
}

int us_graph_components(const us_Graph *g, const us_Bitset *node, int *comp, int *stack) {
  for (int i = 0; i < g->n; i++) comp[i] = -1;
  int k = 0;
  for (int i = 0; i < g->n; i++)
    if (comp[i] < 0 && us_bitset_get(node, i)) flood(g, node, i, k++, comp, stack);
  return k;
}

int us_graph_all_grounded(const us_Graph *g, const us_Bitset *node, unsigned char *mark,
                          int *stack) {
  int top = 0, need = 0, seen = 0;
  for (int i = 0; i < g->n; i++) {
    mark[i] = 0;
    if (!us_bitset_get(node, i)) continue;
    need++;
    if (g->grounded[i]) mark[i] = 1, stack[top++] = i;
  }
  while (top > 0) {
    int v = stack[--top];
    seen++;
    for (int k = g->start[v]; k < g->start[v + 1]; k++) {
      int u = g->adj[k];
      if (!mark[u] && us_bitset_get(node, u)) mark[u] = 1, stack[top++] = u;
    }
  }
  return seen == need;
}
