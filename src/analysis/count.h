/* Private interface of the sub-graph count (docs/count.md): the contact
 * graph as the counters see it, the per-run limits, and the three
 * algorithms (count_tree.c, count_frontier.c, count_contract.c) that
 * count.c chooses from. */
#ifndef US_ANALYSIS_COUNT_H
#define US_ANALYSIS_COUNT_H

#include "analysis/bigint.h"

/* The connected component of the ground node G in the contact graph, G
 * left implicit. Vertices 0..n-1 are the movable bodies connected to G, in
 * ascending body order; adjacency excludes G, lists each neighbour once,
 * ascending; gadj marks the vertices adjacent to G (touching the ground or
 * a fixed body). A tree iff nedge == n (n + 1 nodes with G). */
typedef struct us_CGraph {
  int n;
  int *start;          /* [n + 1] CSR offsets into adj */
  int *adj;
  unsigned char *gadj; /* [n] */
  int *body;           /* [n] body index in the structure */
  long nedge;          /* edges of the component, those at G included */
} us_CGraph;

void us_cgraph_free(us_CGraph *g); /* count_run.c */

/* One count in progress: the structure (for coordinates), the settings,
 * the start time and the result, whose work / peak / status / note the
 * algorithms fill. A refusal sets out->status and out->note, and the
 * algorithm then returns US_OK without a value. */
typedef struct us_CountRun {
  const us_Structure *s;
  const us_CountSettings *set;
  double t0;
  us_Count *out;
} us_CountRun;

/* The run limits (count_run.c). Refuse: out->status = st, out->note = why. */
void us_count_refuse(us_CountRun *run, us_CountStatus st, const char *why);
/* One unit of work (out->work++); every 1024 units the clock is read. 1
 * when the time limit is reached (status and note set), else 0. */
int us_count_tick(us_CountRun *run);
/* 1 (status and note set) when `bytes` of tables pass max_memory_mb. */
int us_count_over_memory(us_CountRun *run, double bytes);

/* The tree formula f(v) = prod over children c (1 + f(c)), rooted at G,
 * on the sub-graph induced by R (NULL: every vertex) whose vertices in A
 * (NULL: those with gadj) are adjacent to G. That sub-graph, plus G, must
 * be a tree. out = f(G). Errors: out of memory only. */
us_Status us_count_tree(const us_CGraph *g, const us_Bitset *R, const us_Bitset *A, us_Big *out,
                        us_Error *err);
/* The frontier dynamic programme over all of g (count_frontier.c). */
us_Status us_count_frontier(const us_CGraph *g, us_CountRun *run, us_Big *out, us_Error *err);
/* Deletion-contraction with memo over all of g (count_contract.c). */
us_Status us_count_contract(const us_CGraph *g, us_CountRun *run, us_Big *out, us_Error *err);

#endif
