/* The source's Figure 4: the time of one stability test against the number
 * of bodies in the tested sub-assembly, per method.
 *
 * For a structure file and a method, plan it once with the default method
 * (to get a removal order), then build it back up along that order, one
 * body per test, timing each us_stability_test on its own (the walk the
 * assembly search and verify make, so each method's reuse works as it does
 * there). With `down`, the source's own walk instead: the order of its
 * depth-first search from the top (highest first, no culling rules), and
 * the structure taken apart along it, from the whole structure down to one
 * body (the source's Figure 4 was measured so). A method that would run
 * past its budget stops early: the slow methods cover the sizes tested
 * first only. Prints CSV rows
 *   structure,method,bodies,seconds
 * (one per test) on stdout.
 *
 * Usage: bench_fig4 FILE NAME METHOD [BUDGET_SECONDS [up|down]]
 *        (default 20 s, up)
 * Uses the public API only. */
#include "unstack/unstack.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int order_of(const us_Structure *s, int down, us_Plan *p) {
  us_PlanSettings set = us_plan_default_settings();
  if (down) set.search = US_SEARCH_DFS, set.order = US_ORDER_HIGHEST, set.rules = 0;
  us_Error err;
  if (us_plan(s, &set, p, &err) != US_OK) {
    fprintf(stderr, "bench_fig4: plan: %s\n", err.msg);
    return -1;
  }
  if (p->status != US_PLAN_FOUND) {
    fprintf(stderr, "bench_fig4: no removal order (%s)\n", us_plan_status_name(p->status));
    return -1;
  }
  return 0;
}

/* The sub-assembly of test k: up, the last k + 1 bodies of the removal
 * order; down, all but the first k. */
static void node_of(us_Bitset *node, const us_Plan *p, int down, int k) {
  if (!down) us_bitset_set(node, p->order[p->nsteps - 1 - k]);
  else if (k == 0)
    for (int j = 0; j < p->nsteps; j++) us_bitset_set(node, p->order[j]);
  else us_bitset_clear(node, p->order[k - 1]);
}

static int walk(const us_Structure *s, const us_Plan *p, const char *name, us_Method m,
                double budget, int down) {
  us_StabilitySettings set = us_stability_default_settings();
  set.method = m;
  set.skip_forces = 1;
  us_Error err;
  us_Stability *w = us_stability_new(s, &set, &err);
  if (!w) return fprintf(stderr, "bench_fig4: %s\n", err.msg), -1;
  us_Bitset node = {0};
  us_StabilityResult res;
  us_stability_result_init(&res);
  int bad = us_bitset_init(&node, s->nbody);
  double t_start = us_now();
  for (int k = 0; k < p->nsteps && !bad; k++) {
    node_of(&node, p, down, k);
    int size = down ? p->nsteps - k : k + 1;
    double t0 = us_now();
    bad = us_stability_test(w, &node, &res, &err) != US_OK;
    double t = us_now() - t0;
    if (!bad) printf("%s,%s,%d,%.9f\n", name, us_method_name(m), size, t);
    if (!bad && res.verdict != US_STABLE)
      fprintf(stderr, "bench_fig4: %s with %s: %d bodies %s\n", name, us_method_name(m), size,
              us_verdict_name(res.verdict));
    if (us_now() - t_start > budget) break;
  }
  us_stability_result_free(&res);
  us_bitset_free(&node);
  us_stability_free(w);
  return bad ? -1 : 0;
}

int main(int argc, char **argv) {
  if (argc < 4) {
    fprintf(stderr, "usage: bench_fig4 FILE NAME METHOD [BUDGET_SECONDS [up|down]]\n");
    return 2;
  }
  us_Method m;
  if (us_method_parse(argv[3], &m)) return fprintf(stderr, "unknown method %s\n", argv[3]), 2;
  double budget = argc > 4 ? atof(argv[4]) : 20.0;
  int down = argc > 5 && !strcmp(argv[5], "down");
  us_Error err;
  us_Structure *s = us_structure_read(argv[1], 0.0, &err);
  if (!s) return fprintf(stderr, "bench_fig4: %s\n", err.msg), 2;
  us_Plan p;
  int r = order_of(s, down, &p);
  if (!r) {
    r = walk(s, &p, argv[2], m, budget, down);
    us_plan_free(&p);
  }
  us_structure_free(s);
  return r ? 1 : 0;
}
