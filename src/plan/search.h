/* The planner's search context and the helpers every search shares
 * (search.c): one stability test of a node with the limits and the
 * statistics, the goal test and the legal moves.
 *
 * Dependencies inside src/plan run one way (no cycles); each file
 * includes the headers of the files it calls:
 *   plan.c     -> hands.h (hands.c -> hook.h),
 *                 searches.h (dfs.c, bfs.c), rules.h, exact.h, assemble.h,
 *                 order.h, search.h, hook.h
 *   dfs.c, bfs.c -> rescue.h, rules.h, search.h
 *   rescue.c   -> rules.h, search.h
 *   rules.c    -> exact.h, assemble.h, search.h
 *   exact.c    -> assemble.h, order.h, search.h, hook.h
 *   assemble.c, order.c -> search.h
 *   classify.c -> hands.h, hook.h; verify_actions.c -> hands.h, hook.h
 *   search.c, verify.c -> hook.h
 *   search.h, graph.h and hook.h call nothing in src/plan. */
#ifndef US_SEARCH_H
#define US_SEARCH_H

#include "core/core.h"
#include "contact/kinematics.h"
#include "graph.h"

struct us_Exact;

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
  us_BitsetSet stable_parts, unstable_parts; /* union rule: components by verdict
                                                (unstable_parts: not known stable,
                                                undecided included) */
  int *path;            /* [nmov] moves from the root to cur */
  int npath;
  us_PlanStats *st;
  char *note;           /* [note_sz] the first undecided test's reason */
  size_t note_sz;
  double t_start;
  long budget_end;      /* random search: restart when tests reach this (0: none) */
  long exact_end;       /* an exact decision stops when tests reach this (0: none) */
  struct us_Exact *exact; /* greedy rule: exact buildability memo (K = 1) */
  int root_live;        /* greedy rule: the part's root can be emptied */
  int full_stable;      /* the full structure tested stable */
  uint64_t rng;         /* random search */
} us_SearchCtx;

/* The planner's steps answer in one int: a test 1 (certified stable) or 0
 * (not known stable), a search or decision its answer (a us_PlanStatus, or
 * 1 / 0), and any of them stops early with one of these, below 0 and so
 * apart from every answer. They never leave the planner: us_plan turns
 * them into a status (limit) or an error. */
typedef enum us_Step {
  US_STEP_ERROR = -1,   /* an error, err set */
  US_STEP_LIMIT = -2,   /* the time limit, the test budget or an exact decision's budget */
  US_STEP_RESTART = -3, /* random search: this restart's budget is spent */
  US_STEP_CUT_SPENT = -4, /* exact.c: the cut tried all the groups it may (proves nothing) */
  US_STEP_FALLS = -5     /* plan.c, assembly search: the full structure does not stand */
} us_Step;

/* One stability test of `node`: 1 certified stable, 0 not known stable
 * (unstable, or undecided: counted in st->undecided, so that a search
 * ending in none knows its answer is no proof), or a us_Step. */
int us_plan_test(us_SearchCtx *ctx, const us_Bitset *node, us_Error *err);
/* The same for the stability workspace's current set, which the caller
 * changes body by body (us_stability_add / remove): O(change) per test. */
int us_plan_test_current(us_SearchCtx *ctx, us_Error *err);
/* 1 when the planner's time limit or test budget is spent. */
int us_plan_limit_reached(const us_SearchCtx *ctx);
/* 1 when `node` is the goal of the search direction. */
int us_plan_is_goal(const us_SearchCtx *ctx, const us_Bitset *node);
/* 1 when moving body b is a legal move from `node` (direction, part and
 * removal kinematics). */
int us_plan_can_move(const us_SearchCtx *ctx, const us_Bitset *node, int b);
static inline void us_plan_toggle(us_Bitset *node, int b) { node->w[b >> 6] ^= (uint64_t)1 << (b & 63); }

#endif
