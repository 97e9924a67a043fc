/* Benchmark of the planner's searches (src/plan): for each scene, every
 * search mode and direction with the default rules, the status, the number
 * of stability tests (and tests per movable body), the wall-clock time, and
 * whether the order re-verifies. Scenes: the random stacker's stacks (the
 * sizes of the issue: 18 rows x 9 wide, seeds 1..8, frictionless and
 * mu = 0.5), the source-style stacker at about 80 to 900 blocks (graph
 * searches on the two smaller ones), an arch next to
 * k loose blocks, the 91-block pyramid, a 1,012-brick wall. Timings live
 * here, never in the tests. Usage: bench_plan [quick]. */
#include "unstack/unstack.h"

#include <stdio.h>
#include <string.h>

static double time_limit = 120.0;

static int verified(const us_Structure *s, const us_Plan *p) {
  us_StabilitySettings st = us_stability_default_settings();
  us_VerifyReport rep;
  if (us_verify_steps(s, &st, p->order, p->nsteps, p->group_start, p->ngroups, &rep, NULL))
    return 0;
  return rep.ok;
}

/* One row: scene, search, direction, status, tests, tests/n, seconds, ok. */
static void row(const char *name, const us_Structure *s, us_Search search, us_Direction dir,
                int max_group) {
  us_PlanSettings set = us_plan_default_settings();
  set.search = search;
  set.direction = dir;
  set.max_group = max_group;
  set.time_limit = time_limit;
  us_Plan p;
  us_Error err;
  double t0 = us_now();
  if (us_plan(s, &set, &p, &err)) {
    printf("| %s | %s | error: %s |\n", name, us_search_name(search), err.msg);
    return;
  }
  double t = us_now() - t0;
  int n = us_structure_movable_count(s);
  const char *check = p.status == US_PLAN_FOUND ? (verified(s, &p) ? "yes" : "NO") : "-";
  char k[16] = "";
  if (p.status == US_PLAN_FOUND && p.max_group > 1) snprintf(k, sizeof k, " K=%d", p.max_group);
  printf("| %s | %d | %s%s%s | %s%s | %ld | %.2f | %.3f | %s |\n", name, n, us_search_name(search),
         search == US_SEARCH_ASSEMBLE ? "" : " ",
         search == US_SEARCH_ASSEMBLE ? "" : us_direction_name(dir), us_plan_status_name(p.status),
         k, p.stats.tests, n > 0 ? (double)p.stats.tests / n : 0.0, t, check);
  fflush(stdout);
  us_plan_free(&p);
}

static void all_modes(const char *name, const us_Structure *s, int graph) {
  row(name, s, US_SEARCH_ASSEMBLE, US_DIR_DOWN, 1);
  for (int m = US_SEARCH_DFS; graph && m <= US_SEARCH_RANDOM; m++)
    for (int d = 0; d < 2; d++) row(name, s, (us_Search)m, (us_Direction)d, 1);
}

/* A copy of s with every body's friction set to mu (via the default). */
static us_Structure *with_friction(us_Structure *s, double mu) {
  us_Structure *c = us_structure_new(2);
  c->friction = mu;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    us_structure_add_body(c,
                          &(us_BodyDef){.id = b->id,
                                        .nvert = b->nvert,
                                        .xy = b->verts,
                                        .density = b->density,
                                        .fixed = b->fixed,
                                        .friction = -1},
                          NULL);
  }
  if (us_structure_finalize(c, NULL)) {
    us_structure_free(c);
    return NULL;
  }
  return c;
}

static void random_stacks(int quick) {
  for (int seed = 1; seed <= (quick ? 2 : 8); seed++) {
    us_GenSettings g = us_gen_default_settings();
    g.rows = 18;
    g.width = 9;
    g.seed = (unsigned long)seed;
    us_Structure *s = us_gen_random(&g, NULL);
    if (!s) continue;
    for (int f = 0; f < 2; f++) {
      us_Structure *c = with_friction(s, f ? 0.5 : 0.0);
      char name[64];
      snprintf(name, sizeof name, "random 18x9 seed %d mu %.1f", seed, f ? 0.5 : 0.0);
      if (c) all_modes(name, c, 1);
      us_structure_free(c);
    }
    us_structure_free(s);
  }
}

static void stacker(int quick) {
  static const int sizes[][2] = {{14, 12}, {30, 30}, {45, 45}, {60, 60}};
  for (int k = 0; k < (quick ? 2 : 4); k++) {
    us_GenSettings g = us_gen_default_settings();
    g.rows = sizes[k][0];
    g.width = sizes[k][1];
    g.seed = 1;
    us_Structure *s = us_gen_stacker(&g, NULL);
    if (!s) continue;
    char name[64];
    snprintf(name, sizeof name, "stacker %dx%d", sizes[k][0], sizes[k][1]);
    all_modes(name, s, k < 2);
    us_structure_free(s);
  }
}

/* The 7-voussoir arch and k unit blocks on the ground beside it. */
static us_Structure *arch_with_loose(int k) {
  us_GenSettings g = us_gen_default_settings();
  g.n = 7;
  g.loose = k;
  return us_gen_arch(&g, NULL);
}

static void arches(void) {
  static const int ks[] = {8, 16, 30, 100};
  for (int i = 0; i < 4; i++) {
    us_Structure *s = arch_with_loose(ks[i]);
    char name[64];
    snprintf(name, sizeof name, "arch + %d loose", ks[i]);
    if (s) all_modes(name, s, 1);
    if (s && ks[i] == 30) row("arch + 30 loose, auto K", s, US_SEARCH_ASSEMBLE, US_DIR_DOWN, 0);
    us_structure_free(s);
  }
}

static void classics(void) {
  us_GenSettings g = us_gen_default_settings();
  g.n = 13;
  us_Structure *s = us_gen_pyramid(&g, NULL);
  if (s) all_modes("pyramid 91", s, 1);
  us_structure_free(s);
  g = us_gen_default_settings();
  g.rows = 25;
  g.cols = 40;
  s = us_gen_wall(&g, NULL);
  if (s) row("wall 25x40", s, US_SEARCH_ASSEMBLE, US_DIR_DOWN, 1);
  if (s) row("wall 25x40", s, US_SEARCH_DFS, US_DIR_DOWN, 1);
  us_structure_free(s);
}

int main(int argc, char **argv) {
  int quick = argc > 1 && !strcmp(argv[1], "quick");
  if (quick) time_limit = 20.0;
  printf("planner searches, default rules, time limit %.0f s per run\n\n", time_limit);
  printf("| scene | n | search | status | tests | tests/n | s | verified |\n");
  printf("|---|---|---|---|---|---|---|---|\n");
  arches();
  random_stacks(quick);
  stacker(quick);
  classics();
  return 0;
}
