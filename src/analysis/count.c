/* The number of connected sub-assemblies containing the ground: builds the
 * contact graph, picks the algorithm and turns the big count into decimal.
 *
 * Contact graph: one node per movable body and one node G for the ground,
 * the ground half-plane and every fixed body merged into G (supports are
 * always present, so a body touching any of them touches G). An edge joins
 * two nodes when at least one contact joins them; contacts inside G are
 * dropped, parallel contacts give one edge. Only G's connected component
 * matters: a body outside it is in no counted set.
 *
 * Choice (docs/count.md): when G's component is a tree (n movable nodes,
 * n edges) the tree formula counts in linear time; otherwise the frontier
 * programme (count_frontier.c), or deletion-contraction when asked for.
 * Limits are outcomes: more bodies than the settings allow, the time limit
 * or the memory bound give status REFUSED_* and no value. */
#include "analysis/count.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const method_names[US_COUNT_METHOD_COUNT] = {"auto", "tree", "frontier",
                                                                "contract"};
static const char *const status_names[US_COUNT_STATUS_COUNT] = {"exact", "refused-size",
                                                                "refused-time", "refused-memory"};

const char *us_count_method_name(us_CountMethod m) {
  return (int)m >= 0 && m < US_COUNT_METHOD_COUNT ? method_names[m] : "unknown";
}

int us_count_method_parse(const char *name, us_CountMethod *out) {
  for (int i = 0; i < US_COUNT_METHOD_COUNT; i++)
    if (!strcmp(name, method_names[i])) {
      *out = (us_CountMethod)i;
      return 0;
    }
  return -1;
}

const char *us_count_status_name(us_CountStatus s) {
  return (int)s >= 0 && s < US_COUNT_STATUS_COUNT ? status_names[s] : "unknown";
}

us_CountSettings us_count_default_settings(void) {
  us_CountSettings set;
  set.method = US_COUNT_AUTO;
  set.max_tree_bodies = 1000000;
  set.max_bodies = 10000;
  set.time_limit = 10.0;
  set.max_memory_mb = 2048.0;
  return set;
}

void us_count_free(us_Count *c) {
  if (!c) return;
  us_free(c->value);
  c->value = NULL;
}

/* --------------------------------------------------------- contact graph */

/* The graph node of body b: -1 for G (ground or fixed), else b. */
static int node_of(const us_Structure *s, int b) {
  return b == US_GROUND || s->bodies[b].fixed ? -1 : b;
}

static int cmp_int(const void *a, const void *b) {
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

/* Every contact between two movable bodies, both ways, into CSR over body
 * indices (duplicates kept); gadj[b] for movable b touching G. */
static int full_pairs(const us_Structure *s, us_CGraph *g) {
  int nb = s->nbody;
  g->n = nb;
  g->start = us_calloc((size_t)nb + 1, sizeof(int));
  g->gadj = us_calloc((size_t)nb + 1, 1);
  if (!g->start || !g->gadj) return -1;
  for (int k = 0; k < s->ncontact; k++) {
    int a = node_of(s, s->contacts[k].a), b = node_of(s, s->contacts[k].b);
    if (a >= 0 && b >= 0 && a != b) g->start[a + 1]++, g->start[b + 1]++;
    else if (a != b) g->gadj[a < 0 ? b : a] = 1;
  }
  for (int i = 0; i < nb; i++) g->start[i + 1] += g->start[i];
  g->adj = us_malloc((size_t)g->start[nb] * sizeof(int) + 1);
  int *fill = us_malloc((size_t)nb * sizeof(int) + 1);
  if (!g->adj || !fill) return us_free(fill), -1;
  memcpy(fill, g->start, (size_t)nb * sizeof(int));
  for (int k = 0; k < s->ncontact; k++) {
    int a = node_of(s, s->contacts[k].a), b = node_of(s, s->contacts[k].b);
    if (a >= 0 && b >= 0 && a != b) g->adj[fill[a]++] = b, g->adj[fill[b]++] = a;
  }
  us_free(fill);
  return 0;
}

/* Sort every row and drop repeats, compacting the CSR in place. */
static void dedup_rows(us_CGraph *g) {
  int w = 0;
  for (int v = 0; v < g->n; v++) {
    int r0 = g->start[v], r1 = g->start[v + 1];
    qsort(g->adj + r0, (size_t)(r1 - r0), sizeof(int), cmp_int);
    g->start[v] = w;
    for (int k = r0; k < r1; k++)
      if (k == r0 || g->adj[k] != g->adj[k - 1]) g->adj[w++] = g->adj[k];
  }
  g->start[g->n] = w;
}

/* Edges of the whole graph: half the adjacency entries plus G's. */
static long count_edges(const us_CGraph *g, const us_Structure *s) {
  long e = g->start[g->n] / 2;
  for (int b = 0; b < g->n; b++) e += g->gadj[b] && !s->bodies[b].fixed;
  return e;
}

/* Mark the bodies reachable from G (breadth first); returns how many. */
static int reach_from_ground(const us_CGraph *f, unsigned char *seen, int *queue) {
  int head = 0, tail = 0;
  for (int b = 0; b < f->n; b++)
    if (f->gadj[b]) seen[b] = 1, queue[tail++] = b;
  while (head < tail) {
    int v = queue[head++];
    for (int k = f->start[v]; k < f->start[v + 1]; k++)
      if (!seen[f->adj[k]]) seen[f->adj[k]] = 1, queue[tail++] = f->adj[k];
  }
  return tail;
}

/* g = the full graph f restricted to the bodies marked in seen, renumbered
 * in body order (id[] is scratch of f->n ints). */
static int restrict_graph(const us_CGraph *f, const unsigned char *seen, int n, int *id,
                          us_CGraph *g) {
  g->n = n;
  g->start = us_calloc((size_t)n + 1, sizeof(int));
  g->gadj = us_calloc((size_t)n + 1, 1);
  g->body = us_malloc((size_t)n * sizeof(int) + 1);
  g->adj = us_malloc((size_t)f->start[f->n] * sizeof(int) + 1);
  if (!g->start || !g->gadj || !g->body || !g->adj) return -1;
  for (int b = 0, v = 0; b < f->n; b++) id[b] = seen[b] ? v++ : -1;
  int w = 0;
  for (int b = 0; b < f->n; b++) {
    if (!seen[b]) continue;
    int v = id[b];
    g->body[v] = b;
    g->gadj[v] = f->gadj[b];
    g->nedge += f->gadj[b];
    g->start[v] = w;
    for (int k = f->start[b]; k < f->start[b + 1]; k++) g->adj[w++] = id[f->adj[k]];
  }
  g->start[n] = w;
  g->nedge += g->start[n] / 2;
  return 0;
}

/* Build G's component; *nedge_all = edges of the whole contact graph. */
static us_Status build_graph(const us_Structure *s, us_CGraph *g, int *nedge_all, us_Error *err) {
  us_CGraph f;
  memset(&f, 0, sizeof f);
  unsigned char *seen = us_calloc((size_t)s->nbody + 1, 1);
  int *scratch = us_malloc((size_t)s->nbody * sizeof(int) + 1);
  int rc = !seen || !scratch || full_pairs(s, &f);
  if (!rc) {
    dedup_rows(&f);
    *nedge_all = (int)count_edges(&f, s);
    int n = reach_from_ground(&f, seen, scratch);
    rc = restrict_graph(&f, seen, n, scratch, g);
  }
  us_cgraph_free(&f);
  us_free(seen);
  us_free(scratch);
  if (rc) return us_error_set(err, US_ERR_NOMEM, "count: out of memory building the contact graph");
  return US_OK;
}

/* ---------------------------------------------------------------- driver */

static us_Status check_args(const us_Structure *s, const us_CountSettings *set, us_Error *err) {
  if (!s) return us_error_set(err, US_ERR_USAGE, "count: no structure given");
  if ((int)set->method < 0 || set->method >= US_COUNT_METHOD_COUNT)
    return us_error_set(err, US_ERR_USAGE, "count: unknown method %d", (int)set->method);
  if (isnan(set->time_limit) || isnan(set->max_memory_mb))
    return us_error_set(err, US_ERR_USAGE, "count: time limit and memory bound must be numbers");
  if (s->ncontact > 0 && !s->contacts)
    return us_error_set(err, US_ERR_USAGE, "count: the structure has no contact list");
  return US_OK;
}

/* The algorithm to run, or an error for TREE on a graph with a cycle. */
static us_Status pick_method(const us_CountSettings *set, us_Count *out, us_Error *err) {
  us_CountMethod m = set->method;
  if (m == US_COUNT_TREE && !out->is_tree)
    return us_error_set(err, US_ERR_USAGE,
                        "count: the contact graph has a cycle at the ground's component (%d "
                        "bodies); the tree method needs a tree: use auto, frontier or contract",
                        out->nconnected);
  out->method = m == US_COUNT_AUTO ? (out->is_tree ? US_COUNT_TREE : US_COUNT_FRONTIER) : m;
  return US_OK;
}

/* REFUSED_SIZE when the chosen algorithm's body limit is passed. */
static int size_refused(us_CountRun *run, int n) {
  int tree = run->out->method == US_COUNT_TREE;
  int lim = tree ? run->set->max_tree_bodies : run->set->max_bodies;
  if (lim <= 0 || n <= lim) return 0;
  char msg[128];
  snprintf(msg, sizeof msg, "%d bodies connected to the ground; the %s limit is %d", n,
           tree ? "tree formula's" : "general algorithms'", lim);
  us_count_refuse(run, US_COUNT_REFUSED_SIZE, msg);
  return 1;
}

static us_Status run_method(const us_CGraph *g, us_CountRun *run, us_Big *val, us_Error *err) {
  switch (run->out->method) {
  case US_COUNT_TREE:
    run->out->work = g->n + 1;
    return us_count_tree(g, NULL, NULL, val, err);
  case US_COUNT_CONTRACT:
    return us_count_contract(g, run, val, err);
  default:
    return us_count_frontier(g, run, val, err);
  }
}

us_Status us_count_subgraphs(const us_Structure *s, const us_CountSettings *set, us_Count *out,
                             us_Error *err) {
  if (!out) return us_error_set(err, US_ERR_USAGE, "count: no result given");
  memset(out, 0, sizeof *out);
  us_CountSettings def = us_count_default_settings();
  us_CountRun run = {s, set ? set : &def, us_now(), out};
  us_Status st = check_args(s, run.set, err);
  us_CGraph g;
  memset(&g, 0, sizeof g);
  us_Big val;
  us_big_init(&val);
  if (!st) st = build_graph(s, &g, &out->nedge, err);
  if (!st) {
    out->nbody = us_structure_movable_count(s);
    out->nconnected = g.n;
    out->is_tree = g.nedge == g.n;
    st = pick_method(run.set, out, err);
  }
  if (!st && !size_refused(&run, g.n)) st = run_method(&g, &run, &val, err);
  if (!st && out->status == US_COUNT_EXACT && !(out->value = us_big_to_dec(&val)))
    st = us_error_set(err, US_ERR_NOMEM, "count: out of memory writing the count");
  out->seconds = us_now() - run.t0;
  us_big_free(&val);
  us_cgraph_free(&g);
  return st;
}
