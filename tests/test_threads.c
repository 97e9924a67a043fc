/* The library called from several threads at once: each thread reads (or
 * generates), finalizes and plans its own structures, and every answer
 * must equal the one-thread answer (status, order, number of tests). The
 * planner is deterministic and the library keeps no mutable global state
 * (tests/globals.sh), so any difference is a race. The test hooks are per
 * thread: one thread's failing allocations or weakened verdicts never
 * reach another thread. */
#include "test.h"

#include "plan/hook.h"

#include <pthread.h>

#define NTHREAD 4
#define NROUND 2

/* One structure to plan: a file of tests/data, or a generator. */
typedef struct Job {
  const char *file;     /* or NULL */
  const char *kind;     /* generator when file is NULL */
  int n;
  us_Method method;
} Job;

static const Job jobs[] = {
    {"bridge.json", NULL, 0, US_METHOD_LP},
    {"cantilever.json", NULL, 0, US_METHOD_LPSOLVE},
    {"column3.json", NULL, 0, US_METHOD_LP},
    {"explicit.json", NULL, 0, US_METHOD_LCP},
    {"greedy_stuck.json", NULL, 0, US_METHOD_LP},
    {"lean_wall.json", NULL, 0, US_METHOD_LP_LCP},
    {"leaning.json", NULL, 0, US_METHOD_LCP_REUSE},
    {"lean_wall_mu0.json", NULL, 0, US_METHOD_LPSOLVE},
    {"wall3d_straight.json", NULL, 0, US_METHOD_LP},
    {NULL, "pyramid", 6, US_METHOD_LP},
    {NULL, "wall", 5, US_METHOD_LPSOLVE},
    {NULL, "arch", 7, US_METHOD_LP},
};
#define NJOB ((int)(sizeof jobs / sizeof jobs[0]))

/* What a plan answered; status -1: an error (code in err). */
typedef struct Answer {
  int status, nsteps, err;
  long tests;
  unsigned long order_hash;
} Answer;

static us_Structure *job_structure(const Job *j, us_Error *err) {
  if (j->file) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", US_TEST_DATA, j->file);
    return us_structure_read(path, 0, err);
  }
  us_GenSettings g = us_gen_default_settings();
  g.n = g.rows = g.cols = j->n;
  if (!strcmp(j->kind, "pyramid")) return us_gen_pyramid(&g, err);
  if (!strcmp(j->kind, "wall")) return us_gen_wall(&g, err);
  return us_gen_arch(&g, err);
}

static Answer run_job(const Job *j) {
  Answer a = {-1, 0, US_OK, 0, 0};
  us_Error err;
  us_Structure *s = job_structure(j, &err);
  if (!s) {
    a.err = err.code;
    return a;
  }
  us_PlanSettings set = us_plan_default_settings();
  set.stability.method = j->method;
  us_Plan p;
  us_Status st = us_plan(s, &set, &p, &err);
  if (st) {
    a.err = st;
  } else {
    a.status = (int)p.status;
    a.nsteps = p.nsteps;
    a.tests = p.stats.tests;
    a.order_hash = 5381;
    for (int k = 0; k < p.nsteps; k++) a.order_hash = a.order_hash * 33 + (unsigned long)p.order[k];
    us_plan_free(&p);
  }
  us_structure_free(s);
  return a;
}

static int same(Answer x, Answer y) {
  return x.status == y.status && x.nsteps == y.nsteps && x.err == y.err && x.tests == y.tests &&
         x.order_hash == y.order_hash;
}

typedef struct Worker {
  int first;                  /* this thread starts at job `first` */
  int mode;                   /* 0 plain, 1 failing allocations, 2 hooked verdicts */
  const Answer *ref;
  int mismatches, ran, failed_alloc, hooked;
} Worker;

static void undecide(void *user, const us_Bitset *node, us_StabilityResult *res) {
  US_UNUSED(node);
  (*(int *)user)++;
  res->verdict = US_UNDECIDED;
}

/* Every job, NROUND times, from job `first` on; checked against ref. */
static void *work(void *arg) {
  Worker *w = arg;
  int calls = 0;
  if (w->mode == 2) us_plan_set_test_hook(undecide, &calls);
  for (int r = 0; r < NROUND; r++)
    for (int k = 0; k < NJOB; k++) {
      int i = (w->first + k) % NJOB;
      if (w->mode == 1) us_alloc_fail_after(0); /* this thread's next allocation fails */
      Answer a = run_job(&jobs[i]);
      if (w->mode == 1) {
        us_alloc_fail_after(-1);
        w->failed_alloc += a.err == US_ERR_NOMEM;
      } else if (w->mode == 2) {
        w->hooked += a.status == US_PLAN_UNDECIDED && calls > 0;
      } else {
        w->mismatches += !same(a, w->ref[i]);
      }
      w->ran++;
    }
  if (w->mode == 2) us_plan_set_test_hook(NULL, NULL);
  return NULL;
}

/* Starts n workers with the given modes and joins them; 0 or -1. */
static int run_workers(Worker *w, int n) {
  pthread_t th[NTHREAD + 2];
  int started = 0;
  for (; started < n; started++)
    if (pthread_create(&th[started], NULL, work, &w[started])) break;
  for (int t = 0; t < started; t++) pthread_join(th[t], NULL);
  return started == n ? 0 : -1;
}

static void reference(Answer *ref) {
  for (int i = 0; i < NJOB; i++) ref[i] = run_job(&jobs[i]);
}

/* NTHREAD threads plan every job concurrently: the one-thread answers. */
static void threads_match_one_thread(void) {
  Answer ref[NJOB];
  reference(ref);
  int found = 0;
  for (int i = 0; i < NJOB; i++) {
    CHECK_INT(ref[i].err, ==, US_OK);
    found += ref[i].status == US_PLAN_FOUND;
  }
  CHECK_INT(found, >=, NJOB / 2); /* most jobs have a plan: the comparison sees orders */
  Worker w[NTHREAD];
  for (int t = 0; t < NTHREAD; t++) w[t] = (Worker){.first = t * NJOB / NTHREAD, .ref = ref};
  CHECK_INT(run_workers(w, NTHREAD), ==, 0);
  for (int t = 0; t < NTHREAD; t++) {
    CHECK_INT(w[t].ran, ==, NROUND * NJOB);
    CHECK_INT(w[t].mismatches, ==, 0);
  }
}

/* A thread whose allocations fail and a thread whose verdicts are all
 * undecided run beside plain threads: only their own work is touched. */
static void hooks_are_per_thread(void) {
  Answer ref[NJOB];
  reference(ref);
  Worker w[NTHREAD];
  for (int t = 0; t < NTHREAD; t++)
    w[t] = (Worker){.first = t * NJOB / NTHREAD, .mode = t < 2 ? t + 1 : 0, .ref = ref};
  CHECK_INT(run_workers(w, NTHREAD), ==, 0);
  CHECK_INT(w[0].failed_alloc, ==, NROUND * NJOB); /* every job of the failing thread */
  CHECK_INT(w[1].hooked, ==, NROUND * NJOB);       /* every answer undecided */
  for (int t = 2; t < NTHREAD; t++) CHECK_INT(w[t].mismatches, ==, 0);
  /* and the hooks are gone with their threads: this one plans as before */
  for (int i = 0; i < NJOB; i++) CHECK(same(run_job(&jobs[i]), ref[i]));
}

US_TEST_MAIN(T(threads_match_one_thread), T(hooks_are_per_thread))
