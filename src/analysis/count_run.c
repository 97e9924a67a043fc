/* The pieces of a count that the algorithms share with the driver
 * (count.h): freeing the contact graph, and the per-run limits (a refusal
 * is an outcome: status and note set, no value). Kept apart from count.c
 * so that the algorithms (count_frontier.c, count_contract.c) depend on
 * this file and count.c depends on them, one way. The clock is read every
 * 1024 units of work, so a time limit is checked at negligible cost. */
#include "analysis/count.h"

#include <stdio.h>
#include <string.h>

void us_cgraph_free(us_CGraph *g) {
  us_free(g->start);
  us_free(g->adj);
  us_free(g->gadj);
  us_free(g->body);
  memset(g, 0, sizeof *g);
}

/* ------------------------------------------------------------ run limits */

void us_count_refuse(us_CountRun *run, us_CountStatus st, const char *why) {
  run->out->status = st;
  snprintf(run->out->note, sizeof run->out->note, "%s", why);
}

int us_count_tick(us_CountRun *run) {
  if (run->out->status != US_COUNT_EXACT) return 1;
  long w = run->out->work++;
  double lim = run->set->time_limit;
  if ((w & 1023) != 0 || !(lim > 0) || us_now() - run->t0 <= lim) return 0;
  char msg[96];
  snprintf(msg, sizeof msg, "time limit of %g s reached", lim);
  us_count_refuse(run, US_COUNT_REFUSED_TIME, msg);
  return 1;
}

int us_count_over_memory(us_CountRun *run, double bytes) {
  if (run->out->status != US_COUNT_EXACT) return 1;
  double lim = run->set->max_memory_mb;
  if (!(lim > 0) || bytes <= lim * 1048576.0) return 0;
  char msg[96];
  snprintf(msg, sizeof msg, "the tables would pass the memory bound of %g MB", lim);
  us_count_refuse(run, US_COUNT_REFUSED_MEMORY, msg);
  return 1;
}
