/* The planner's driver: check the settings, set up a search context, test
 * the full structure, run the chosen search, turn its result into a removal
 * order in steps, and collect per-step certificates when asked.
 *
 * The assemble search (the default) builds from the ground greedily and the
 * removal order is the reverse of its build order; when the greedy is stuck
 * the exact decision (exact.c) settles it, and a `none` names the greedy's
 * maximal buildable sub-assembly and the bodies outside it. With
 * max_group 0 the step bound K rises from 1 until an order exists (at most
 * the largest component: a component taken away whole always works when
 * the structure stands). The graph searches (DFS, BFS, random) plan each
 * component of the structure apart when the components rule is on (the
 * parts are independent: a removal in one never changes the verdict of
 * another, so the orders concatenate), decide the root exactly when the
 * greedy rule is on, and search each part's disassembly graph. Going up, a
 * part's path adds bodies and its reverse is the removal order.
 *
 * With certificates, each structure along the order is tested once more
 * (the search keeps no forces, so memory stays independent of the path
 * length); those tests are counted in the statistics like the others. */
#include "assemble.h"
#include "exact.h"
#include "hands.h"
#include "hook.h"
#include "stability/stability.h"
#include "order.h"
#include "rules.h"
#include "searches.h"

#include <math.h>
#include <string.h>

us_PlanSettings us_plan_default_settings(void) {
  us_PlanSettings p;
  memset(&p, 0, sizeof p);
  p.search = US_SEARCH_ASSEMBLE;
  p.order = US_ORDER_HIGHEST;
  p.direction = US_DIR_DOWN;
  p.removal = US_REMOVAL_ANY;
  p.max_group = 1;
  p.rules = US_RULE_ALL;
  p.seed = 1;
  p.max_exact_tests = 100000;
  p.hands = 1;
  p.stability = us_stability_default_settings();
  return p;
}

void us_plan_free(us_Plan *p) {
  if (!p) return;
  if (p->certs)
    for (int k = 0; k <= p->ngroups; k++) us_forces_free(&p->certs[k]);
  us_free(p->certs);
  us_free(p->order);
  us_free(p->group_start);
  us_free(p->buildable);
  us_free(p->blocked);
  us_free(p->build_start);
  for (int k = 0; p->release_certs && k < p->nactions; k++) us_forces_free(&p->release_certs[k]);
  us_free(p->release_certs);
  us_free(p->actions);
  p->release_certs = NULL;
  p->actions = NULL;
  p->nactions = 0;
  p->certs = NULL;
  p->order = p->group_start = p->buildable = p->blocked = p->build_start = NULL;
  p->nsteps = p->ngroups = p->nbuildable = p->nblocked = p->nbuild = 0;
}

/* ------------------------------------------------------------ set-up */

static void ctx_free(us_SearchCtx *ctx) {
  us_stability_free(ctx->stab);
  us_stability_result_free(&ctx->res);
  us_kinematics_free(ctx->kin);
  us_graph_free(&ctx->g);
  us_free(ctx->comp);
  us_free(ctx->stack);
  us_free(ctx->mark);
  us_exact_free(ctx->exact);
  us_free(ctx->cand);
  us_free(ctx->path);
  us_bitset_free(&ctx->scratch);
  us_bitset_free(&ctx->full);
  us_bitset_free(&ctx->part);
  us_bitset_free(&ctx->cur);
  us_bitset_set_free(&ctx->dead);
  us_bitset_set_free(&ctx->stable_parts);
  us_bitset_set_free(&ctx->unstable_parts);
}

static int ctx_alloc(us_SearchCtx *ctx, const us_Structure *s) {
  size_t n = (size_t)s->nbody + 1;
  ctx->cand = us_malloc(n * sizeof(int));
  ctx->path = us_malloc(n * sizeof(int));
  ctx->comp = us_malloc(n * sizeof(int));
  ctx->stack = us_malloc(n * sizeof(int));
  ctx->mark = us_malloc(n);
  return !ctx->cand || !ctx->path || !ctx->comp || !ctx->stack || !ctx->mark ||
         us_graph_init(&ctx->g, s) || us_structure_movable_set(s, &ctx->full) ||
         us_bitset_init(&ctx->part, s->nbody) || us_bitset_init(&ctx->scratch, s->nbody) ||
         us_bitset_init(&ctx->cur, s->nbody) || us_bitset_set_init(&ctx->dead, s->nbody) ||
         us_bitset_set_init(&ctx->stable_parts, s->nbody) ||
         us_bitset_set_init(&ctx->unstable_parts, s->nbody);
}

static us_Status ctx_init(us_SearchCtx *ctx, const us_Structure *s, const us_PlanSettings *set,
                          us_PlanStats *st, us_Error *err) {
  memset(ctx, 0, sizeof *ctx);
  ctx->s = s;
  ctx->set = set;
  ctx->st = st;
  ctx->t_start = us_now();
  ctx->nmov = us_structure_movable_count(s);
  ctx->rng = (uint64_t)set->seed * 0x9e3779b97f4a7c15ULL + 1;
  if (ctx_alloc(ctx, s)) return us_error_set(err, US_ERR_NOMEM, "out of memory setting up the search");
  if (set->removal != US_REMOVAL_ANY && !(ctx->kin = us_kinematics_new(s, set->removal, err)))
    return err && err->code ? err->code : US_ERR_NOMEM;
  ctx->stab = us_stability_new(s, &set->stability, err);
  if (ctx->stab) us_stability_set_skip_forces(ctx->stab, 1); /* verdicts only */
  /* the plan's time limit holds inside the solvers too */
  if (ctx->stab && set->time_limit > 0 && isfinite(set->time_limit) &&
      !(set->stability.time_limit > 0 && set->stability.time_limit < set->time_limit))
    us_stability_set_deadline(ctx->stab, ctx->t_start + set->time_limit);
  return ctx->stab ? US_OK : (err && err->code ? err->code : US_ERR_NOMEM);
}

static us_Status check_settings(const us_PlanSettings *set, us_Error *err) {
  if ((unsigned)set->search > US_SEARCH_RANDOM || (unsigned)set->order > US_ORDER_INPUT ||
      (unsigned)set->direction > US_DIR_UP || (unsigned)set->removal > US_REMOVAL_FREE)
    return us_error_set(err, US_ERR_USAGE, "plan settings: unknown search, order, direction or removal");
  if (set->max_group < 0 || set->max_group > 64)
    return us_error_set(err, US_ERR_USAGE, "plan settings: max_group must be 0 (auto) to 64, got %d",
                        set->max_group);
  if (set->removal != US_REMOVAL_ANY && set->search == US_SEARCH_ASSEMBLE)
    return us_error_set(err, US_ERR_USAGE, "removal kinematics (up, free) break the union theorem "
                        "the assemble search rests on: use a graph search (dfs, bfs, random)");
  if (set->max_group != 1 && set->search != US_SEARCH_ASSEMBLE)
    return us_error_set(err, US_ERR_USAGE, "steps of several bodies (max_group != 1) need the "
                        "assemble search");
  return US_OK;
}

/* ------------------------------------------------------------ results */

static us_Status alloc_order(us_Plan *out, int n, us_Error *err) {
  out->order = us_malloc(((size_t)n + 1) * sizeof(int));
  out->group_start = us_malloc(((size_t)n + 2) * sizeof(int));
  if (!out->order || !out->group_start) return us_error_set(err, US_ERR_NOMEM, "out of memory");
  out->group_start[0] = 0;
  return US_OK;
}

/* Removal order = the build sequence reversed, step by step. */
static us_Status order_from_assembly(const us_Assembly *a, us_Plan *out, us_Error *err) {
  if (alloc_order(out, a->nseq, err)) return US_ERR_NOMEM;
  for (int k = a->ngroups - 1; k >= 0; k--) {
    for (int q = a->gstart[k]; q < a->gstart[k + 1]; q++) out->order[out->nsteps++] = a->seq[q];
    out->group_start[++out->ngroups] = out->nsteps;
  }
  out->max_group = a->max_group;
  return US_OK;
}

/* A removal order with step ends marked (exact.c) into the plan. */
static us_Status order_from_exact(const int *order, const unsigned char *end, int n, us_Plan *out,
                                  us_Error *err) {
  if (alloc_order(out, n, err)) return US_ERR_NOMEM;
  out->max_group = 0;
  for (int q = 0; q < n; q++) {
    out->order[out->nsteps++] = order[q];
    if (!end[q]) continue;
    out->group_start[++out->ngroups] = out->nsteps;
    int size = out->group_start[out->ngroups] - out->group_start[out->ngroups - 1];
    if (size > out->max_group) out->max_group = size;
  }
  return US_OK;
}

/* The greedy's placements as the plan's build order, in its steps. */
static void report_build(const us_Assembly *a, us_Plan *out) {
  for (int q = 0; q < a->nseq; q++) out->buildable[out->nbuildable++] = a->seq[q];
  for (int g = 0; g <= a->ngroups; g++) out->build_start[g] = a->gstart[g];
  out->nbuild = a->ngroups;
}

/* A maximal buildable sub-assembly (the greedy's, in placement order) and
 * the bodies outside it. */
static us_Status report_stuck(const us_SearchCtx *ctx, const us_Assembly *a, us_Plan *out,
                              us_Error *err) {
  us_free(out->buildable);
  us_free(out->blocked);
  us_free(out->build_start);
  out->nbuildable = out->nblocked = out->nbuild = 0;
  out->buildable = us_malloc(((size_t)ctx->nmov + 1) * sizeof(int));
  out->blocked = us_malloc(((size_t)ctx->nmov + 1) * sizeof(int));
  out->build_start = us_malloc(((size_t)a->ngroups + 2) * sizeof(int));
  if (!out->buildable || !out->blocked || !out->build_start)
    return us_error_set(err, US_ERR_NOMEM, "out of memory");
  report_build(a, out);
  for (int i = 0; i < ctx->s->nbody; i++)
    if (!ctx->s->bodies[i].fixed && !us_bitset_get(&a->built, i))
      out->blocked[out->nblocked++] = i;
  return US_OK;
}

/* The exact decision for steps of at most K, after the greedy was stuck. */
static int exact_for(us_SearchCtx *ctx, int K, us_Plan *out, us_Error *err) {
  size_t n = (size_t)ctx->s->nbody + 1;
  int *order = us_malloc(n * sizeof(int)), len = 0;
  unsigned char *end = us_malloc(n);
  us_Exact *e = us_exact_new(ctx->s->nbody, K);
  int r = order && end && e ? us_exact_solve(ctx, e, &ctx->full, order, end, &len, err) : US_STEP_ERROR;
  if (r == 1 && order_from_exact(order, end, len, out, err)) r = US_STEP_ERROR;
  if (e) ctx->st->memo_bytes += us_exact_bytes(e);
  us_exact_free(e);
  us_free(order);
  us_free(end);
  if (r == US_STEP_ERROR && err && !err->code)
    us_error_set(err, US_ERR_NOMEM, "out of memory in the search");
  return r;
}

/* The full structure's test, once: the assembly search only needs it when
 * the greedy is stuck (a completed assembly proves it stands). 1 stands,
 * US_STEP_FALLS, or another us_Step (error, limit). */
static int full_stands(us_SearchCtx *ctx, us_Error *err) {
  if (ctx->full_stable) return 1;
  int r = us_plan_test(ctx, &ctx->full, err);
  if (r < 0) return r;
  ctx->full_stable = r;
  return r ? 1 : US_STEP_FALLS;
}

/* Steps of at most K: the greedy, then (stuck) the exact decision. */
static int assemble_with(us_SearchCtx *ctx, int K, us_Plan *out, us_Error *err) {
  us_Assembly a;
  int r = us_assemble(ctx, &ctx->full, K, &a, err);
  us_Status st = US_OK;
  if (r == 1) st = order_from_assembly(&a, out, err);
  if (r == 0) st = report_stuck(ctx, &a, out, err);
  us_assembly_free(&a);
  if (st) return US_STEP_ERROR;
  if (r == 0) {
    r = full_stands(ctx, err);
    if (r == 1) r = 0;
  }
  if (r == 0) r = exact_for(ctx, K, out, err);
  if (r == 0) out->max_group = K;
  return r;
}

/* The size of the largest component: no step needs to be larger. */
static int largest_component(us_SearchCtx *ctx) {
  int k = us_graph_components(&ctx->g, &ctx->full, ctx->comp, ctx->stack), best = 1;
  int *size = ctx->stack; /* free again: one count per component */
  for (int c = 0; c < k; c++) size[c] = 0;
  for (int i = 0; i < ctx->s->nbody; i++)
    if (ctx->comp[i] >= 0 && ++size[ctx->comp[i]] > best) best = size[ctx->comp[i]];
  return best;
}

/* The assemble search; max_group 0: K = 1, 2, ... until an order exists. */
static int run_assemble(us_SearchCtx *ctx, us_Plan *out, us_Error *err) {
  int K = ctx->set->max_group > 0 ? ctx->set->max_group : 1;
  int top = ctx->set->max_group > 0 ? K : US_MIN(largest_component(ctx), 64);
  int r = 0;
  for (; K <= top && r == 0; K++) r = assemble_with(ctx, K, out, err);
  if ((r == 1 || r == US_STEP_FALLS) && out->buildable) {
    us_free(out->buildable);
    us_free(out->blocked);
    us_free(out->build_start);
    out->buildable = out->blocked = out->build_start = NULL;
    out->nbuildable = out->nblocked = out->nbuild = 0;
  }
  return r == 1 ? US_PLAN_FOUND : r == 0 ? US_PLAN_NONE : r == US_STEP_FALLS ? US_PLAN_UNSTABLE : r;
}

/* ------------------------------------------------------ graph searches */

/* Append the part's path as removals, one body per step. */
static void append_path(const us_SearchCtx *ctx, us_Plan *out) {
  for (int k = 0; k < ctx->npath; k++) {
    int j = ctx->set->direction == US_DIR_DOWN ? k : ctx->npath - 1 - k;
    out->order[out->nsteps++] = ctx->path[j];
    out->group_start[++out->ngroups] = out->nsteps;
  }
}

static int search_part(us_SearchCtx *ctx, us_Error *err) {
  if (us_plan_order_candidates(ctx))
    return us_error_set(err, US_ERR_NOMEM, "out of memory in the search"), US_STEP_ERROR;
  ctx->npath = 0;
  int greedy = (ctx->set->rules & US_RULE_GREEDY) && !ctx->kin;
  int live = greedy ? us_plan_node_live(ctx, &ctx->part, NULL, NULL, err) : 1;
  if (live < 0) return live;
  if (!live) return US_PLAN_NONE;
  ctx->root_live = greedy;
  if (ctx->set->direction == US_DIR_DOWN) us_bitset_copy(&ctx->cur, &ctx->part);
  else memset(ctx->cur.w, 0, (size_t)ctx->cur.nwords * sizeof(uint64_t));
  switch (ctx->set->search) {
  case US_SEARCH_BFS: return us_plan_bfs(ctx, err);
  case US_SEARCH_RANDOM: return us_plan_random(ctx, err);
  default: return us_plan_dfs(ctx, err);
  }
}

/* The parts: components of the structure (components rule) or the whole. */
static int run_graph_search(us_SearchCtx *ctx, us_Plan *out, us_Error *err) {
  if (alloc_order(out, ctx->nmov, err)) return US_STEP_ERROR;
  /* with kinematics a part's bodies can block another's: no split */
  int split = (ctx->set->rules & US_RULE_COMPONENTS) && !ctx->kin;
  int k = split ? us_graph_components(&ctx->g, &ctx->full, ctx->comp, ctx->stack) : 1;
  int *label = us_malloc(((size_t)ctx->s->nbody + 1) * sizeof(int));
  if (!label) return us_error_set(err, US_ERR_NOMEM, "out of memory"), US_STEP_ERROR;
  if (split) memcpy(label, ctx->comp, (size_t)ctx->s->nbody * sizeof(int));
  ctx->st->components = k;
  int r = US_PLAN_FOUND;
  for (int c = 0; c < k && r == US_PLAN_FOUND; c++) {
    for (int i = 0; i < ctx->s->nbody; i++) {
      int in = split ? label[i] == c : us_bitset_get(&ctx->full, i);
      if (in) us_bitset_set(&ctx->part, i);
      else us_bitset_clear(&ctx->part, i);
    }
    r = search_part(ctx, err);
    if (r == US_PLAN_FOUND) append_path(ctx, out);
  }
  us_free(label);
  return r;
}

/* For a graph search that ends in none: name a maximal buildable
 * sub-assembly too (removal any only). */
static us_Status name_stuck(us_SearchCtx *ctx, us_Plan *out, us_Error *err) {
  if (ctx->kin) return US_OK;
  us_Assembly a;
  int r = us_assemble(ctx, &ctx->full, 1, &a, err);
  us_Status st = r == 0 ? report_stuck(ctx, &a, out, err) : US_OK;
  us_assembly_free(&a);
  return r == US_STEP_ERROR ? (err && err->code ? err->code : US_ERR_NOMEM) : st;
}

static int run_search(us_SearchCtx *ctx, us_Plan *out, us_Error *err) {
  if (ctx->set->search == US_SEARCH_ASSEMBLE) return run_assemble(ctx, out, err);
  int r = run_graph_search(ctx, out, err);
  if (r == US_PLAN_NONE && name_stuck(ctx, out, err)) return US_STEP_ERROR;
  if (r == US_PLAN_FOUND) out->max_group = 1;
  return r;
}

/* Only a found plan has an order (a part's order may be there from a
 * search that stopped later). */
static void drop_order(us_Plan *out) {
  us_free(out->order);
  us_free(out->group_start);
  out->order = out->group_start = NULL;
  out->nsteps = out->ngroups = 0;
}

/* ------------------------------------------------------- certificates */

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

/* certs[k]: forces of the structure before step k. Walked from the empty
 * structure up (each test adds one step, so local tests apply; the full
 * structure comes last). */
static us_Status collect_certificates(us_SearchCtx *ctx, us_Plan *out, us_Error *err) {
  out->certs = us_calloc((size_t)out->ngroups + 1, sizeof(us_Forces));
  if (!out->certs) return us_error_set(err, US_ERR_NOMEM, "out of memory");
  us_Bitset node = {0};
  if (us_bitset_init(&node, ctx->s->nbody)) return us_error_set(err, US_ERR_NOMEM, "out of memory");
  us_stability_set_skip_forces(ctx->stab, 0);
  us_stability_set_deadline(ctx->stab, 0); /* the order is found: finish its certificates */
  us_Status st = US_OK;
  for (int k = out->ngroups; k >= 0 && !st; k--) {
    for (int q = k < out->ngroups ? out->group_start[k] : 0; k < out->ngroups && q < out->group_start[k + 1]; q++)
      us_bitset_set(&node, out->order[q]);
    st = us_plan_stability_test(ctx->stab, &node, &ctx->res, err);
    ctx->st->tests++;
    if (!st && ctx->res.verdict != US_STABLE)
      st = us_error_set(err, US_ERR_SOLVER, "step %d no longer tests stable", k);
    if (!st) st = copy_forces(&out->certs[k], &ctx->res.forces, ctx->s->dim, err);
  }
  us_bitset_free(&node);
  return st;
}

static void finish_stats(us_SearchCtx *ctx, us_PlanStats *st, double t_search) {
  const us_StabilityInfo *info = us_stability_info(ctx->stab);
  st->stability = *info;
  st->time_solve = info->solve_time;
  st->time_check = info->check_time;
  st->time_search = us_now() - t_search;
  st->time_total = us_now() - ctx->t_start;
  st->memo_bytes += us_bitset_set_bytes(&ctx->dead) + us_bitset_set_bytes(&ctx->stable_parts) +
                    us_bitset_set_bytes(&ctx->unstable_parts) +
                    (ctx->exact ? us_exact_bytes(ctx->exact) : 0);
}

/* A none or unstable that an undecided test may have decided is no proof
 * (search.c): the answer is undecided. */
static int downgrade(const us_SearchCtx *ctx, int r) {
  int proof = r == US_PLAN_NONE || r == US_PLAN_UNSTABLE;
  return proof && ctx->st->undecided > 0 ? US_PLAN_UNDECIDED : r;
}

/* The search after set-up: the full structure's test, then the search;
 * a status, or US_STEP_ERROR (err set). */
static int run(us_SearchCtx *ctx, us_Plan *out, double *t_search, us_Error *err) {
  /* the assembly search starts from the empty set and tests the full
   * structure only if it gets stuck */
  int full = ctx->set->search == US_SEARCH_ASSEMBLE ? 1 : us_plan_test(ctx, &ctx->full, err);
  out->stats.time_setup = us_now() - ctx->t_start;
  *t_search = us_now();
  int r = full < 0 ? full : full == 0 ? US_PLAN_UNSTABLE : run_search(ctx, out, err);
  return r == US_STEP_LIMIT ? US_PLAN_LIMIT : r < 0 ? US_STEP_ERROR : downgrade(ctx, r);
}

/* hands != 1 (hands.c): auto first asks today's planner for H = 1, the
 * time it took coming off the hands search's limit. */
static us_Status plan_with_hands(const us_Structure *s, const us_PlanSettings *set, us_Plan *out,
                                 us_Error *err) {
  us_Plan one;
  memset(&one, 0, sizeof one);
  us_PlanSettings sh = *set, s1 = *set;
  s1.hands = 1;
  s1.certificates = 0;
  us_Status st = set->hands == 0 ? us_plan(s, &s1, &one, err) : US_OK;
  if (!st && sh.time_limit > 0) /* what is left, never 0 (that is no limit) */
    sh.time_limit = US_MAX(set->time_limit - one.stats.time_total, 1e-9);
  if (!st) st = us_plan_hands(s, &sh, set->hands == 0 ? &one : NULL, out, err);
  if (!st) out->stats.time_total += one.stats.time_total;
  us_plan_free(&one);
  return st;
}

us_Status us_plan(const us_Structure *s, const us_PlanSettings *set, us_Plan *out,
                  us_Error *err) {
  us_Error local;
  if (!err) err = &local;
  us_error_clear(err);
  if (!out) return us_error_set(err, US_ERR_USAGE, "us_plan: NULL argument");
  memset(out, 0, sizeof *out);
  if (!s || !set) return us_error_set(err, US_ERR_USAGE, "us_plan: NULL argument");
  us_Status st = check_settings(set, err);
  if (st) return st;
  if (set->hands != 1) return plan_with_hands(s, set, out, err);
  us_SearchCtx ctx;
  st = ctx_init(&ctx, s, set, &out->stats, err);
  ctx.note = out->note;
  ctx.note_sz = sizeof out->note;
  double t_search = us_now();
  int r = st ? US_STEP_ERROR : run(&ctx, out, &t_search, err);
  if (!st && r < 0) st = err->code ? err->code : US_ERR_SOLVER;
  if (!st) out->status = (us_PlanStatus)r;
  if (!st && r != US_PLAN_FOUND) drop_order(out);
  if (!st && r == US_PLAN_FOUND && set->certificates) st = collect_certificates(&ctx, out, err);
  if (ctx.stab) finish_stats(&ctx, &out->stats, t_search);
  ctx_free(&ctx);
  if (st) us_plan_free(out);
  return st;
}
