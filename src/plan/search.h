/* Private interface of the planner: the search context shared by the
 * driver (plan.c), the node test with the culling rules (rules.c), the
 * greedy assembly (assemble.c), the graph searches (dfs.c, bfs.c) and the
 * candidate ordering (order.c). */
#ifndef US_SEARCH_H
#define US_SEARCH_H

#include "core/core.h"
#include "contact/kinematics.h"
#include "graph.h"

/* A node of the disassembly graph is the set of movable bodies present
 * (bits over body indices; fixed bodies' bits stay clear). A move toggles
 * one body: direction down removes a present body, up adds an absent one.
 * The searches plan one part at a time (the whole structure, or one
 * component of it under the components rule): `part` is the set of bodies
 * being planned, the root is `part` (down) or the empty set (up) and the
 * goal the other one. The root is known stable when a search starts. */
typedef struct us_SearchCtx {
  const us_Structure *s;
  const us_PlanSettings *set;
  us_Stability *stab;
  us_StabilityResult res;
  us_Graph g;
  us_Kinematics *kin;   /* NULL: any removal */
  int *comp, *stack;    /* scratch [nbody] */
  unsigned char *mark;  /* scratch [nbody] */
  us_Bitset scratch;    /* scratch node */
  int nmov;             /* movable bodies */
  int ncand;            /* bodies of the part */
  int *cand;            /* [nmov] bodies of the part in the order moves are tried */
  us_Bitset full;       /* all movable bodies */
  us_Bitset part;       /* the part being planned */
  us_Bitset cur;        /* the node being expanded */
  us_BitsetSet dead;    /* nodes known not to lead to the goal */
  us_BitsetSet stable_parts, unstable_parts; /* union rule: components by verdict */
  int *path;            /* [nmov] moves from the root to cur */
  int npath;
  us_PlanStats *st;
  double t_start;
  long budget_end;      /* random search: restart when tests reach this (0: none) */
  long exact_end;       /* an exact decision stops when tests reach this (0: none) */
  struct us_Exact *exact; /* greedy rule: exact buildability memo (K = 1) */
  int root_live;        /* greedy rule: the part's root can be emptied */
  uint64_t rng;         /* random search */
} us_SearchCtx;

/* Greedy assembly (assemble.c). Builds from the empty set inside `within`
 * (movable bodies), adding any body or group of at most max_group (>= 1)
 * bodies that keeps the set standing, lowest first. Fills the placement
 * sequence and its steps. Returns 1 when all of `within` was built, 0 when
 * stuck (built = a maximal buildable sub-assembly reached greedily; being
 * stuck proves nothing by itself, see exact.c), -1 error (err set), -2
 * limit. */
typedef struct us_Assembly {
  us_Bitset built;
  int *seq, nseq;       /* bodies in placement order */
  int *gstart, ngroups; /* [ngroups + 1] step offsets into seq */
  int max_group;        /* largest step used, or the bound when stuck */
} us_Assembly;
int us_assemble(us_SearchCtx *ctx, const us_Bitset *within, int max_group, us_Assembly *out,
                us_Error *err);
/* The same from a standing set `start` ⊆ within already in place (its
 * bodies are not in the sequence). */
int us_assemble_from(us_SearchCtx *ctx, const us_Bitset *within, const us_Bitset *start,
                     int max_group, us_Assembly *out, us_Error *err);
void us_assembly_free(us_Assembly *a);

/* Exact buildability with a memo over connected sets (exact.c): steps of
 * at most K bodies. us_exact_solve: 1 when `set` can be emptied (its
 * removal order, with step ends marked, in order/step_end when not NULL:
 * capacity nbody), 0 when not, -1 error, -2 limit. */
typedef struct us_Exact us_Exact;
us_Exact *us_exact_new(int nbody, int K);
void us_exact_free(us_Exact *e);
size_t us_exact_bytes(const us_Exact *e);
int us_exact_solve(us_SearchCtx *ctx, us_Exact *e, const us_Bitset *set, int *order,
                   unsigned char *step_end, int *n, us_Error *err);

/* order.c: fill ctx->cand with the bodies of ctx->part according to
 * set->order and direction; 0, or -1 on OOM. */
int us_plan_order_candidates(us_SearchCtx *ctx);
/* order.c: sort bodies[0..n) highest first (top of the geometry, then the
 * centre, then the index); 0, or -1 on OOM. */
int us_plan_sort_highest(const us_Structure *s, int *bodies, int n);

/* plan.c: one stability test of `node`; 1 stable, 0 not, -1 error, -2 limit,
 * -3 restart budget reached (random search). */
int us_plan_test(us_SearchCtx *ctx, const us_Bitset *node, us_Error *err);
/* rules.c: the node test of the graph searches, with the ground and union
 * rules when enabled; same return values. */
int us_plan_node_test(us_SearchCtx *ctx, const us_Bitset *node, us_Error *err);
/* rules.c, greedy rule: 1 when `node` (down: the bodies left) can be
 * emptied one body at a time (exact, exact.c), 0 when not, < 0 as above.
 * When live and seq is not NULL, seq[0..*nseq) is a removal order of it. */
int us_plan_node_live(us_SearchCtx *ctx, const us_Bitset *node, int *seq, int *nseq,
                      us_Error *err);
/* rules.c: the one-sided check: 1 when greedy assembly finishes from
 * `node` (down: rebuilds it from the ground; up: completes the part from
 * it), and then seq, if not NULL, holds the moves that take `node` to the
 * goal; 0 when it is stuck (which proves nothing), < 0 as above. */
int us_plan_node_greedy(us_SearchCtx *ctx, const us_Bitset *node, int *seq, int *nseq,
                        us_Error *err);
/* 1 when `node` is the goal of the search direction. */
int us_plan_is_goal(const us_SearchCtx *ctx, const us_Bitset *node);
/* 1 when moving body b is a legal move from `node` (direction, part and
 * removal kinematics). */
int us_plan_can_move(const us_SearchCtx *ctx, const us_Bitset *node, int b);
static inline void us_plan_toggle(us_Bitset *node, int b) { node->w[b >> 6] ^= (uint64_t)1 << (b & 63); }

/* dfs.c / bfs.c: search from ctx->cur (the root). On success fill
 * ctx->path / npath with the moves and return US_PLAN_FOUND; otherwise
 * US_PLAN_NONE or US_PLAN_LIMIT. Errors: return -1 with err set. */
int us_plan_dfs(us_SearchCtx *ctx, us_Error *err);
int us_plan_random(us_SearchCtx *ctx, us_Error *err);
int us_plan_bfs(us_SearchCtx *ctx, us_Error *err);
/* dfs.c, greedy rule (downward): a deep node on the current path
 * (ctx->path[0..npath), ending at ctx->cur; the root is live) that greedy
 * assembly rebuilds, by binary search (top_dead: the last node is known
 * dead and is not checked), then its removal order to the goal (the root's
 * exact order when no node below it passes). US_PLAN_FOUND or < 0. */
int us_plan_rescue(us_SearchCtx *ctx, int top_dead, us_Error *err);

#endif
