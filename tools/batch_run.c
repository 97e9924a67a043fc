/* What one input of `unstack batch` gives: the task's core (task.h, the
 * same calls as the single command) on the loaded structure, turned into
 * one JSON line: the file as given, the status or verdict with its exit
 * code, tests, time, and the task's key results; or an error line with the
 * single command's message. The line is written in place (batch_json.c). */
#define _POSIX_C_SOURCE 200809L
#include "batch.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *batch_task_name(BatchTask t) {
  return t == BATCH_PLAN ? "plan" : t == BATCH_CHECK ? "check" : "classify";
}

static void jbody(JLine *l, const us_Structure *s, int b) {
  if (b >= 0) jl_str(l, s->bodies[b].id);
  else jl_raw(l, "null");
}

/* A list of ids: v[from..to-1]. */
static void jids(JLine *l, const us_Structure *s, const int *v, int from, int to) {
  jl_raw(l, "[");
  for (int q = from; q < to; q++) {
    if (q > from) jl_raw(l, ",");
    jl_str(l, s->bodies[v[q]].id);
  }
  jl_raw(l, "]");
}

static void jkey_int(JLine *l, const char *key, long long v) { jl_key(l, key), jl_int(l, v); }
static void jkey_str(JLine *l, const char *key, const char *v) { jl_key(l, key), jl_str(l, v); }

/* plan: status, steps and the order (a list of steps, each a list of
 * ids), or the bodies that block. */
static void plan_fields(JLine *l, const us_Structure *s, const us_Plan *p) {
  jkey_str(l, "status", us_plan_status_name(p->status));
  jkey_int(l, "exit", cli_plan_exit(p));
  jkey_int(l, "tests", p->stats.tests);
  jkey_int(l, "bodies", us_structure_movable_count(s));
  if (p->status == US_PLAN_FOUND) {
    jkey_int(l, "steps", p->ngroups);
    jl_key(l, "order");
    jl_raw(l, "[");
    for (int k = 0; k < p->ngroups; k++) {
      if (k) jl_raw(l, ",");
      if (p->group_start) jids(l, s, p->order, p->group_start[k], p->group_start[k + 1]);
      else jids(l, s, p->order, k, k + 1);
    }
    jl_raw(l, "]");
  } else if (p->blocked) {
    jl_key(l, "blocked");
    jids(l, s, p->blocked, 0, p->nblocked);
  }
  if (p->status == US_PLAN_UNDECIDED && p->note[0]) jkey_str(l, "note", p->note);
}

static void check_fields(JLine *l, const us_Structure *s, const CliCheckOutcome *c) {
  jkey_str(l, "verdict", us_verdict_name(c->res.verdict));
  jkey_int(l, "exit", cli_check_exit(c->res.verdict));
  jkey_int(l, "tests", c->info.tests);
  jkey_int(l, "bodies", us_structure_movable_count(s));
  jkey_int(l, "contacts", s->ncontact);
  if (c->res.verdict != US_STABLE) jl_key(l, "unstable_body"), jbody(l, s, c->res.unstable_body);
  if (c->res.note[0] && c->res.verdict != US_STABLE) jkey_str(l, "note", c->res.note);
}

/* classify: the classes of `unstack classify --json` that answer yes or
 * no, with the same words. */
static void classify_fields(JLine *l, const us_Structure *s, const us_Classification *c) {
  jkey_str(l, "status", c->undecided ? "undecided" : "classified");
  jkey_int(l, "exit", cli_classify_exit(c));
  jkey_int(l, "tests", c->dfs_tests + c->sequence_tests + c->group_tests);
  jkey_int(l, "bodies", c->nbody);
  jl_key(l, "stands"), jl_raw(l, c->stands ? "true" : "false");
  jl_key(l, "unstable_body"), jbody(l, s, c->unstable_body);
  jl_key(l, "mu_critical"), jl_real(l, c->mu_critical);
  jl_key(l, "topdown"), jl_raw(l, c->topdown < 0 ? "null" : c->topdown ? "true" : "false");
  jkey_str(l, "sequence_status", us_plan_status_name(c->sequence_status));
  jl_key(l, "min_group");
  if (c->group_status == US_PLAN_FOUND) jl_int(l, c->min_group);
  else jl_raw(l, "null");
}

/* The task on a loaded structure: its fields into o; US_OK or err set. */
static us_Status run_task(const Batch *b, const us_Structure *s, double deadline, JLine *o,
                          us_Error *err) {
  double left = deadline > 0 ? fmax(deadline - us_now(), 1e-3) : 0.0;
  us_Status st;
  if (b->task == BATCH_PLAN) {
    us_Plan p;
    if ((st = cli_plan_run(s, &b->common, left, &p, err)) == US_OK) plan_fields(o, s, &p), us_plan_free(&p);
  } else if (b->task == BATCH_CHECK) {
    CliCheckOutcome c;
    if ((st = cli_check_run(s, &b->common, left, &c, err)) == US_OK)
      check_fields(o, s, &c), us_stability_result_free(&c.res);
  } else {
    us_Classification c;
    if ((st = cli_classify_run(s, &b->classify, &c, err)) == US_OK) classify_fields(o, s, &c);
    if (st == US_OK) us_classification_free(&c);
  }
  return st;
}

/* Loading cut by --time-limit: an outcome, undecided, as the single command says. */
static void cut_fields(JLine *o, const Batch *b, const us_Error *err) {
  jkey_str(o, b->task == BATCH_CHECK ? "verdict" : "status", "undecided");
  jkey_int(o, "exit", CLI_EXIT_UNDECIDED);
  char note[sizeof err->msg + 64];
  snprintf(note, sizeof note, "loading was cut by the time limit: %s", err->msg);
  jkey_str(o, "note", note);
}

static void error_fields(JLine *o, const Batch *b, const us_Error *err) {
  char line[sizeof err->msg + 128];
  cli_error_text(line, sizeof line, batch_task_name(b->task), err);
  jkey_str(o, "error", line);
  jkey_int(o, "exit", CLI_EXIT_ERR);
}

char *batch_run_one(const Batch *b, const char *path, int *failed) {
  double t0 = us_now(), deadline = b->time_limit > 0 ? t0 + b->time_limit : 0.0;
  const CliCommon *c = b->task == BATCH_CLASSIFY ? &b->classify.common : &b->common;
  us_Error err;
  us_error_clear(&err);
  JLine o;
  jl_open(&o);
  jkey_str(&o, "file", path);
  us_Structure *s = cli_load_quiet(path, c, deadline, &err);
  us_Status st = s ? run_task(b, s, deadline, &o, &err) : err.code;
  *failed = st != US_OK && !(!s && st == US_ERR_TIME_LIMIT);
  if (!s && st == US_ERR_TIME_LIMIT) cut_fields(&o, b, &err);
  else if (st) error_fields(&o, b, &err);
  jl_key(&o, "time");
  jl_real(&o, round((us_now() - t0) * 1e6) / 1e6);
  us_structure_free(s);
  return jl_close(&o);
}
