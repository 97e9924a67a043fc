/* The culling rules of the graph searches (DFS, BFS, random): what may be
 * decided about a node without a stability test, or without exploring it.
 *
 *   ground  A node in which some body is not connected to a support (the
 *           ground or a fixed body) through bodies of the node is unstable:
 *           the part it belongs to touches no support, so the sum of the
 *           external forces on that part is its weight, which no internal
 *           contact force can cancel. Costs O(n), no LP.
 *   union   A node stands iff each of its components stands (the
 *           decoupling lemma, graph.h). Components are tested one by one
 *           and their verdicts memoised; a node whose components are all
 *           known is decided without a test. The source's union theorem is
 *           the "stable" half: disjoint parts that stood apart stand
 *           together.
 *   greedy  Whether a node can be emptied at all is decided exactly by
 *           exact.c (greedy assembly first, an exhaustive search over
 *           connected sets where the greedy is stuck, memoised). The
 *           driver asks it for the root (so `none` needs no search of the
 *           graph). A downward search that has to backtrack then looks for
 *           the deepest node of its path that greedy assembly can rebuild
 *           (a one-sided check: success proves the node live, failure
 *           proves nothing) and finishes from there with the greedy's
 *           order, or from the root with the exact order; searches that
 *           never backtrack pay nothing for it.
 * The memo rule (nodes known dead are not tested again) lives in the
 * searches themselves; the components rule in the driver (plan.c). */
#include "exact.h"
#include "assemble.h"
#include "rules.h"

#include <string.h>

/* Bodies of `node` grouped by component: order[] lists them component by
 * component, first[c] .. first[c + 1] - 1 the slice of component c. */
static int group_by_component(us_SearchCtx *ctx, const us_Bitset *node, int *order, int *first) {
  int k = us_graph_components(&ctx->g, node, ctx->comp, ctx->stack);
  for (int c = 0; c <= k; c++) first[c] = 0;
  for (int i = 0; i < ctx->s->nbody; i++)
    if (ctx->comp[i] >= 0) first[ctx->comp[i] + 1]++;
  for (int c = 0; c < k; c++) first[c + 1] += first[c];
  for (int i = 0; i < ctx->s->nbody; i++)
    if (ctx->comp[i] >= 0) order[first[ctx->comp[i]]++] = i;
  for (int c = k; c > 0; c--) first[c] = first[c - 1];
  first[0] = 0;
  return k;
}

static void mark_slice(us_Bitset *b, const int *order, int from, int to, int on) {
  for (int q = from; q < to; q++) {
    if (on) us_bitset_set(b, order[q]);
    else us_bitset_clear(b, order[q]);
  }
}

/* Verdict of one component (in ctx->scratch): memo first, else a test. */
static int component_verdict(us_SearchCtx *ctx, int *tested, us_Error *err) {
  if (us_bitset_set_contains(&ctx->stable_parts, &ctx->scratch)) return 1;
  if (us_bitset_set_contains(&ctx->unstable_parts, &ctx->scratch)) return 0;
  int r = us_plan_test(ctx, &ctx->scratch, err);
  if (r < 0) return r;
  *tested = 1;
  us_BitsetSet *memo = r ? &ctx->stable_parts : &ctx->unstable_parts;
  if (us_bitset_set_add(memo, &ctx->scratch) < 0)
    return us_error_set(err, US_ERR_NOMEM, "out of memory in the search"), US_STEP_ERROR;
  return r;
}

/* The union rule: components one by one, stopping at the first that falls. */
static int test_by_components(us_SearchCtx *ctx, const us_Bitset *node, us_Error *err) {
  int n = ctx->s->nbody;
  int *order = us_malloc(((size_t)n + 1) * sizeof(int));
  int *first = us_malloc(((size_t)n + 2) * sizeof(int));
  if (!order || !first) {
    us_free(order);
    us_free(first);
    return us_error_set(err, US_ERR_NOMEM, "out of memory in the search"), US_STEP_ERROR;
  }
  int k = group_by_component(ctx, node, order, first), r = 1, tested = 0;
  for (int c = 0; c < k && r == 1; c++) {
    mark_slice(&ctx->scratch, order, first[c], first[c + 1], 1);
    r = component_verdict(ctx, &tested, err);
    mark_slice(&ctx->scratch, order, first[c], first[c + 1], 0);
  }
  if (r >= 0 && !tested) ctx->st->saved_union++;
  us_free(order);
  us_free(first);
  return r;
}

int us_plan_node_test(us_SearchCtx *ctx, const us_Bitset *node, us_Error *err) {
  unsigned rules = ctx->set->rules;
  if ((rules & US_RULE_GROUND) &&
      !us_graph_all_grounded(&ctx->g, node, ctx->mark, ctx->stack)) {
    ctx->st->saved_ground++;
    return 0;
  }
  if (rules & US_RULE_UNION) return test_by_components(ctx, node, err);
  return us_plan_test(ctx, node, err);
}

int us_plan_node_live(us_SearchCtx *ctx, const us_Bitset *node, int *seq, int *nseq,
                      us_Error *err) {
  if (!ctx->exact && !(ctx->exact = us_exact_new(ctx->s->nbody, 1)))
    return us_error_set(err, US_ERR_NOMEM, "out of memory in the search"), US_STEP_ERROR;
  ctx->st->exact_checks++;
  return us_exact_solve(ctx, ctx->exact, node, seq, NULL, nseq, err);
}

int us_plan_node_greedy(us_SearchCtx *ctx, const us_Bitset *node, int *seq, int *nseq,
                        us_Error *err) {
  us_Assembly a;
  ctx->st->greedy_checks++;
  int up = ctx->set->direction == US_DIR_UP;
  int r = up ? us_assemble_from(ctx, &ctx->part, node, 1, &a, err)
             : us_assemble(ctx, node, 1, &a, err);
  if (r == 1 && seq) {
    for (int k = 0; k < a.nseq; k++) seq[k] = up ? a.seq[k] : a.seq[a.nseq - 1 - k];
    *nseq = a.nseq;
  }
  us_assembly_free(&a);
  return r;
}
