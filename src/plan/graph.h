/* The contact graph of a structure, as the planner sees it: one node per
 * body, an edge where at least one contact joins two movable bodies, and a
 * "grounded" mark on every movable body that touches the ground or a fixed
 * body. Fixed bodies and the ground are supports: they are always present
 * and they never connect two parts (parts that touch only through supports
 * are independent, because a support takes any force).
 *
 * Components of a sub-assembly X are the classes of X under the edges
 * between bodies of X. The decoupling lemma the planner rests on: X stands
 * iff every component of X stands (the equilibrium rows of one component
 * share no contact force with another's). */
#ifndef US_PLAN_GRAPH_H
#define US_PLAN_GRAPH_H

#include "core/core.h"

typedef struct us_Graph {
  int n;                 /* bodies */
  int *start;            /* [n + 1] CSR offsets into adj */
  int *adj;              /* movable neighbours, each once, ascending */
  unsigned char *grounded; /* [n] touches the ground or a fixed body */
} us_Graph;

int us_graph_init(us_Graph *g, const us_Structure *s); /* 0, or -1 on OOM */
void us_graph_free(us_Graph *g);

/* Union-find over body indices with sizes (path halving, union by size). */
typedef struct us_Dsu {
  int *parent;
  int *size;
} us_Dsu;
int us_dsu_init(us_Dsu *d, int n);
void us_dsu_free(us_Dsu *d);
int us_dsu_find(us_Dsu *d, int x);
int us_dsu_union(us_Dsu *d, int a, int b); /* returns the new root */

/* Components of `node` (bits over bodies): comp[b] = component label
 * 0..k-1 for present movable bodies, -1 otherwise; returns k. `stack` is
 * scratch of g->n ints. */
int us_graph_components(const us_Graph *g, const us_Bitset *node, int *comp, int *stack);

/* 1 when every body of `node` is connected to a grounded body through
 * bodies of `node` (the ground rule: otherwise the node cannot stand under
 * gravity, since a part touching no support has a net external force).
 * `mark` and `stack` are scratch of g->n entries. */
int us_graph_all_grounded(const us_Graph *g, const us_Bitset *node, unsigned char *mark,
                          int *stack);

#endif
