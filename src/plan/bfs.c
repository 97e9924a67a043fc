/* Breadth-first search of the disassembly graph. Every plan moves every
 * body once, so all plans have the same length; BFS explores the graph level by level (all nodes with k bodies
 * moved before any with k + 1), which makes it the exhaustive reference
 * search: it tests every reachable stable node of a level before going
 * deeper, and its memory grows with the width of the graph.
 *
 * Every node seen is kept in a pool of words with its parent and the move
 * that reached it; `seen` (a visited set of this part's search)
 * guarantees each node is tested once (BFS's own visited set, kept
 * whatever the culling rules say). Children are tested with the ground
 * and union rules (rules.c). */
#include "rescue.h"
#include "rules.h"
#include "searches.h"

#include <string.h>

typedef struct {
  int parent;
  int move;
} Rec;

typedef struct {
  uint64_t *words; /* node k at words + k * nwords */
  Rec *rec;
  int n, cap;
  int nwords;
  us_BitsetSet seen;
} Queue;

static int queue_push(Queue *q, const us_Bitset *node, int parent, int move) {
  if (q->n == q->cap) {
    int ncap = q->cap ? 2 * q->cap : 256;
    uint64_t *w = us_realloc(q->words, (size_t)ncap * (size_t)q->nwords * sizeof(uint64_t));
    if (!w) return -1;
    q->words = w;
    Rec *r = us_realloc(q->rec, (size_t)ncap * sizeof(Rec));
    if (!r) return -1;
    q->rec = r;
    q->cap = ncap;
  }
  memcpy(q->words + (size_t)q->n * (size_t)q->nwords, node->w,
         (size_t)q->nwords * sizeof(uint64_t));
  q->rec[q->n].parent = parent;
  q->rec[q->n].move = move;
  q->n++;
  return 0;
}

/* Moves from the root to node k, into ctx->path. */
static void reconstruct(us_SearchCtx *ctx, const Queue *q, int k) {
  int len = 0;
  for (int i = k; q->rec[i].parent >= 0; i = q->rec[i].parent) len++;
  ctx->npath = len;
  for (int i = k; q->rec[i].parent >= 0; i = q->rec[i].parent) ctx->path[--len] = q->rec[i].move;
}

/* Expand node k: push every stable child not seen before. Returns 1 when
 * the goal was pushed, 0 to go on, or a us_Step to stop. */
static int expand(us_SearchCtx *ctx, Queue *q, int k, us_Error *err) {
  memcpy(ctx->cur.w, q->words + (size_t)k * (size_t)q->nwords,
         (size_t)q->nwords * sizeof(uint64_t));
  ctx->st->nodes_expanded++;
  for (int i = 0; i < ctx->ncand; i++) {
    int b = ctx->cand[i];
    if (!us_plan_can_move(ctx, &ctx->cur, b)) continue;
    us_plan_toggle(&ctx->cur, b);
    int added = us_bitset_set_add(&q->seen, &ctx->cur);
    int goal = us_plan_is_goal(ctx, &ctx->cur);
    int r = added < 0 ? US_STEP_ERROR : added == 0 ? 0 : goal ? 1 : us_plan_node_test(ctx, &ctx->cur, err);
    if (added < 0) us_error_set(err, US_ERR_NOMEM, "out of memory in the search");
    if (added == 0) ctx->st->revisited++;
    if (r == 1 && queue_push(q, &ctx->cur, k, b))
      r = US_STEP_ERROR, us_error_set(err, US_ERR_NOMEM, "out of memory in the search");
    us_plan_toggle(&ctx->cur, b);
    if (r < 0) return r;
    if (r == 1 && goal) return 1;
  }
  return 0;
}

/* Greedy rule, when the queue outgrows 64 + 4 n nodes: finish
 * from the deepest node queued (us_plan_rescue). */
static int bfs_rescue(us_SearchCtx *ctx, const Queue *q, us_Error *err) {
  int j = q->n - 1;
  memcpy(ctx->cur.w, q->words + (size_t)j * (size_t)q->nwords, (size_t)q->nwords * sizeof(uint64_t));
  reconstruct(ctx, q, j);
  return us_plan_rescue(ctx, 0, err);
}

static int rescue_due(const us_SearchCtx *ctx, const Queue *q) {
  return (ctx->set->rules & US_RULE_GREEDY) && !ctx->kin && ctx->root_live &&
         q->n > 64 + 4 * ctx->ncand;
}

int us_plan_bfs(us_SearchCtx *ctx, us_Error *err) {
  Queue q = {NULL, NULL, 0, 0, ctx->cur.nwords, {0}};
  int status = US_PLAN_NONE;
  if (us_bitset_set_init(&q.seen, ctx->s->nbody) || queue_push(&q, &ctx->cur, -1, -1) ||
      us_bitset_set_add(&q.seen, &ctx->cur) < 0) {
    status = US_STEP_ERROR;
    us_error_set(err, US_ERR_NOMEM, "out of memory in the search");
  }
  if (status == US_PLAN_NONE && us_plan_is_goal(ctx, &ctx->cur)) status = US_PLAN_FOUND;
  for (int k = 0; status == US_PLAN_NONE && k < q.n; k++) {
    if (rescue_due(ctx, &q)) {
      int r = bfs_rescue(ctx, &q, err);
      status = r == US_PLAN_FOUND ? US_PLAN_FOUND : r == US_STEP_LIMIT ? US_PLAN_LIMIT : US_STEP_ERROR;
      break;
    }
    int r = expand(ctx, &q, k, err);
    if (r == 1) {
      reconstruct(ctx, &q, q.n - 1);
      status = US_PLAN_FOUND;
    } else if (r < 0) {
      status = r == US_STEP_LIMIT ? US_PLAN_LIMIT : US_STEP_ERROR; /* no restart budget here */
    }
  }
  if (status == US_PLAN_FOUND && q.n == 1) ctx->npath = 0;
  ctx->st->memo_bytes += (size_t)q.cap * ((size_t)q.nwords * sizeof(uint64_t) + sizeof(Rec));
  ctx->st->memo_bytes += us_bitset_set_bytes(&q.seen);
  us_bitset_set_free(&q.seen);
  us_free(q.words);
  us_free(q.rec);
  return status;
}
