/* The planner's driver: set up a search context, test the full structure,
 * run the chosen search, turn the path into a removal order, and collect
 * per-step certificates when asked.
 *
 * The removal order is the path itself going down; going up the path adds
 * bodies from the ground and its reverse is the removal order. With
 * certificates, each structure along the order is tested once more (the
 * search keeps no forces, so memory stays independent of the path length);
 * those tests are counted in the statistics like the others. */
#include "search.h"

#include <string.h>

static const char *const status_names[] = {"found", "none", "unstable", "limit"};

const char *us_plan_status_name(us_PlanStatus s) {
  if ((int)s < 0 || (int)s > US_PLAN_LIMIT) return "unknown";
  return status_names[s];
}

us_PlanSettings us_plan_default_settings(void) {
  us_PlanSettings p;
  memset(&p, 0, sizeof p);
  p.search = US_SEARCH_DFS;
  p.order = US_ORDER_HIGHEST;
  p.direction = US_DIR_DOWN;
  p.stability = us_stability_default_settings();
  return p;
}

void us_plan_free(us_Plan *p) {
  if (!p) return;
  if (p->certs)
    for (int k = 0; k <= p->nsteps; k++) us_forces_free(&p->certs[k]);
  us_free(p->certs);
  us_free(p->order);
  p->certs = NULL;
  p->order = NULL;
  p->nsteps = 0;
}

int us_plan_is_goal(const us_SearchCtx *ctx, const us_Bitset *node) {
  if (ctx->set->direction == US_DIR_UP) return us_bitset_equal(node, &ctx->full);
  for (int i = 0; i < node->nwords; i++)
    if (node->w[i]) return 0;
  return 1;
}

int us_plan_can_move(const us_SearchCtx *ctx, const us_Bitset *node, int b) {
  return us_bitset_get(node, b) == (ctx->set->direction == US_DIR_DOWN);
}

static int limit_reached(const us_SearchCtx *ctx) {
  const us_PlanSettings *set = ctx->set;
  if (set->max_tests > 0 && ctx->st->tests >= set->max_tests) return 1;
  return set->time_limit > 0 && us_now() - ctx->t_start >= set->time_limit;
}

int us_plan_test(us_SearchCtx *ctx, const us_Bitset *node, us_Error *err) {
  if (limit_reached(ctx)) {
    ctx->limit = 1;
    return -2;
  }
  if (us_stability_test(ctx->stab, node, &ctx->res, err)) return -1;
  ctx->st->tests++;
  int stable = ctx->res.verdict == US_STABLE;
  if (stable)
    ctx->st->stable++;
  else
    ctx->st->unstable++;
  return stable;
}

static void ctx_free(us_SearchCtx *ctx) {
  us_stability_free(ctx->stab);
  us_stability_result_free(&ctx->res);
  us_free(ctx->cand);
  us_free(ctx->path);
  us_bitset_free(&ctx->full);
  us_bitset_free(&ctx->cur);
  us_bitset_set_free(&ctx->dead);
}

static us_Status ctx_init(us_SearchCtx *ctx, const us_Structure *s, const us_PlanSettings *set,
                          us_PlanStats *st, us_Error *err) {
  memset(ctx, 0, sizeof *ctx);
  ctx->s = s;
  ctx->set = set;
  ctx->st = st;
  ctx->t_start = us_now();
  ctx->nmov = us_structure_movable_count(s);
  size_t n = (size_t)ctx->nmov + 1;
  ctx->cand = us_malloc(n * sizeof(int));
  ctx->path = us_malloc(n * sizeof(int));
  int bad = !ctx->cand || !ctx->path || us_structure_movable_set(s, &ctx->full) ||
            us_bitset_init(&ctx->cur, s->nbody) || us_bitset_set_init(&ctx->dead, s->nbody) ||
            us_plan_order_candidates(ctx);
  if (bad) return us_error_set(err, US_ERR_NOMEM, "out of memory setting up the search");
  ctx->stab = us_stability_new(s, &set->stability, err);
  return ctx->stab ? US_OK : err->code;
}

/* Removal order from the search path. */
static us_Status take_order(const us_SearchCtx *ctx, us_Plan *out, us_Error *err) {
  out->order = us_malloc((size_t)(ctx->npath > 0 ? ctx->npath : 1) * sizeof(int));
  if (!out->order) return us_error_set(err, US_ERR_NOMEM, "out of memory");
  out->nsteps = ctx->npath;
  for (int k = 0; k < ctx->npath; k++)
    out->order[k] = ctx->set->direction == US_DIR_DOWN ? ctx->path[k]
                                                       : ctx->path[ctx->npath - 1 - k];
  return US_OK;
}

static us_Status copy_forces(us_Forces *dst, const us_Forces *src, int dim, us_Error *err) {
  memset(dst, 0, sizeof *dst);
  int n = src->ncontact;
  dst->contact = us_malloc((size_t)(n > 0 ? n : 1) * sizeof(int));
  dst->f = us_malloc((size_t)(n > 0 ? n : 1) * (size_t)dim * sizeof(double));
  if (!dst->contact || !dst->f) return us_error_set(err, US_ERR_NOMEM, "out of memory");
  if (n > 0) {
    memcpy(dst->contact, src->contact, (size_t)n * sizeof(int));
    memcpy(dst->f, src->f, (size_t)n * (size_t)dim * sizeof(double));
  }
  dst->ncontact = dst->cap = n;
  return US_OK;
}

/* certs[k]: forces of the structure before removal k. */
static us_Status collect_certificates(us_SearchCtx *ctx, us_Plan *out, us_Error *err) {
  out->certs = us_calloc((size_t)out->nsteps + 1, sizeof(us_Forces));
  if (!out->certs) return us_error_set(err, US_ERR_NOMEM, "out of memory");
  us_Bitset node = {0};
  if (us_bitset_copy(&node, &ctx->full)) return us_error_set(err, US_ERR_NOMEM, "out of memory");
  us_Status st = US_OK;
  for (int k = 0; k <= out->nsteps && !st; k++) {
    if (k > 0) us_bitset_clear(&node, out->order[k - 1]);
    st = us_stability_test(ctx->stab, &node, &ctx->res, err);
    ctx->st->tests++;
    if (!st && ctx->res.verdict != US_STABLE)
      st = us_error_set(err, US_ERR_SOLVER, "step %d no longer tests stable", k);
    if (!st) st = copy_forces(&out->certs[k], &ctx->res.forces, ctx->s->dim, err);
  }
  us_bitset_free(&node);
  return st;
}

static int run_search(us_SearchCtx *ctx, us_Error *err) {
  if (ctx->set->direction == US_DIR_DOWN) us_bitset_copy(&ctx->cur, &ctx->full);
  return ctx->set->search == US_SEARCH_BFS ? us_plan_bfs(ctx, err) : us_plan_dfs(ctx, err);
}

static void finish_stats(us_SearchCtx *ctx, us_PlanStats *st, double t_search) {
  const us_StabilityInfo *info = us_stability_info(ctx->stab);
  st->stability = *info;
  st->time_solve = info->solve_time;
  st->time_check = info->check_time;
  st->time_search = us_now() - t_search;
  st->time_total = us_now() - ctx->t_start;
  st->memo_bytes += us_bitset_set_bytes(&ctx->dead);
}

us_Status us_plan(const us_Structure *s, const us_PlanSettings *set, us_Plan *out,
                  us_Error *err) {
  memset(out, 0, sizeof *out);
  us_SearchCtx ctx;
  us_Status st = ctx_init(&ctx, s, set, &out->stats, err);
  int full = st ? -1 : us_plan_test(&ctx, &ctx.full, err);
  out->stats.time_setup = us_now() - ctx.t_start;
  double t_search = us_now();
  int r = full < 0 ? full : full == 0 ? US_PLAN_UNSTABLE : run_search(&ctx, err);
  if (r == -2) r = US_PLAN_LIMIT;
  if (!st && r == -1) st = err->code ? err->code : US_ERR_SOLVER;
  if (!st) out->status = (us_PlanStatus)r;
  if (!st && r == US_PLAN_FOUND) st = take_order(&ctx, out, err);
  if (!st && r == US_PLAN_FOUND && set->certificates) st = collect_certificates(&ctx, out, err);
  if (ctx.stab) finish_stats(&ctx, &out->stats, t_search);
  ctx_free(&ctx);
  if (st) us_plan_free(out);
  return st;
}
