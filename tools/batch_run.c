/* What one input of `unstack batch` gives: the task's core (task.h, the
 * same calls as the single command) on the loaded structure, turned into
 * one JSON line: the file as given, the status or verdict with its exit
 * code, tests, time, and the task's key results; or an error line with the
 * single command's message. */
#define _POSIX_C_SOURCE 200809L
#include "batch.h"

#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *batch_task_name(BatchTask t) {
  return t == BATCH_PLAN ? "plan" : t == BATCH_CHECK ? "check" : "classify";
}

/* A JSON string of text that may not be UTF-8 (file names): bytes that
 * break it become '?'. */
static json_t *jtext(const char *s) {
  json_t *j = json_string(s);
  if (j) return j;
  char *c = strdup(s);
  if (!c) return NULL;
  for (unsigned char *p = (unsigned char *)c; *p; p++)
    if (*p >= 0x80) *p = '?';
  j = json_string(c);
  free(c);
  return j;
}

static json_t *jnum(double x) { return isfinite(x) ? json_real(x) : json_null(); }
static json_t *jbody(const us_Structure *s, int b) {
  return b >= 0 ? jtext(s->bodies[b].id) : json_null();
}

/* A list of ids: v[from..to-1]. */
static json_t *jids(const us_Structure *s, const int *v, int from, int to) {
  json_t *a = json_array();
  for (int q = from; a && q < to; q++) json_array_append_new(a, jtext(s->bodies[v[q]].id));
  return a;
}

/* plan: status, steps and the order (a list of steps, each a list of
 * ids), or the bodies that block. */
static void plan_fields(json_t *o, const us_Structure *s, const us_Plan *p) {
  json_object_set_new(o, "status", json_string(us_plan_status_name(p->status)));
  json_object_set_new(o, "exit", json_integer(cli_plan_exit(p)));
  json_object_set_new(o, "tests", json_integer(p->stats.tests));
  json_object_set_new(o, "bodies", json_integer(us_structure_movable_count(s)));
  if (p->status == US_PLAN_FOUND) {
    json_t *order = json_array();
    for (int k = 0; order && k < p->ngroups; k++)
      json_array_append_new(order, p->group_start ? jids(s, p->order, p->group_start[k],
                                                         p->group_start[k + 1])
                                                  : jids(s, p->order, k, k + 1));
    json_object_set_new(o, "steps", json_integer(p->ngroups));
    json_object_set_new(o, "order", order);
  } else if (p->blocked) {
    json_object_set_new(o, "blocked", jids(s, p->blocked, 0, p->nblocked));
  }
  if (p->status == US_PLAN_UNDECIDED && p->note[0]) json_object_set_new(o, "note", jtext(p->note));
}

static void check_fields(json_t *o, const us_Structure *s, const CliCheckOutcome *c) {
  json_object_set_new(o, "verdict", json_string(us_verdict_name(c->res.verdict)));
  json_object_set_new(o, "exit", json_integer(cli_check_exit(c->res.verdict)));
  json_object_set_new(o, "tests", json_integer(c->info.tests));
  json_object_set_new(o, "bodies", json_integer(us_structure_movable_count(s)));
  json_object_set_new(o, "contacts", json_integer(s->ncontact));
  if (c->res.verdict != US_STABLE) json_object_set_new(o, "unstable_body", jbody(s, c->res.unstable_body));
  if (c->res.note[0] && c->res.verdict != US_STABLE) json_object_set_new(o, "note", jtext(c->res.note));
}

/* classify: the classes of `unstack classify --json` that answer yes or
 * no, with the same words. */
static void classify_fields(json_t *o, const us_Structure *s, const us_Classification *c) {
  json_object_set_new(o, "status", json_string(c->undecided ? "undecided" : "classified"));
  json_object_set_new(o, "exit", json_integer(cli_classify_exit(c)));
  json_object_set_new(o, "tests", json_integer(c->dfs_tests + c->sequence_tests + c->group_tests));
  json_object_set_new(o, "bodies", json_integer(c->nbody));
  json_object_set_new(o, "stands", json_boolean(c->stands));
  json_object_set_new(o, "unstable_body", jbody(s, c->unstable_body));
  json_object_set_new(o, "mu_critical", jnum(c->mu_critical));
  json_object_set_new(o, "topdown", c->topdown < 0 ? json_null() : json_boolean(c->topdown));
  json_object_set_new(o, "sequence_status", json_string(us_plan_status_name(c->sequence_status)));
  json_object_set_new(o, "min_group", c->group_status == US_PLAN_FOUND ? json_integer(c->min_group)
                                                                       : json_null());
}

/* The task on a loaded structure: its fields into o; US_OK or err set. */
static us_Status run_task(const Batch *b, const us_Structure *s, double deadline, json_t *o,
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
static void cut_fields(json_t *o, const Batch *b, const us_Error *err) {
  json_object_set_new(o, b->task == BATCH_CHECK ? "verdict" : "status", json_string("undecided"));
  json_object_set_new(o, "exit", json_integer(CLI_EXIT_UNDECIDED));
  char note[sizeof err->msg + 64];
  snprintf(note, sizeof note, "loading was cut by the time limit: %s", err->msg);
  json_object_set_new(o, "note", jtext(note));
}

static void error_fields(json_t *o, const Batch *b, const us_Error *err) {
  char line[sizeof err->msg + 128];
  cli_error_text(line, sizeof line, batch_task_name(b->task), err);
  json_object_set_new(o, "error", jtext(line));
  json_object_set_new(o, "exit", json_integer(CLI_EXIT_ERR));
}

char *batch_run_one(const Batch *b, const char *path, int *failed) {
  double t0 = us_now(), deadline = b->time_limit > 0 ? t0 + b->time_limit : 0.0;
  const CliCommon *c = b->task == BATCH_CLASSIFY ? &b->classify.common : &b->common;
  us_Error err;
  us_error_clear(&err);
  json_t *o = json_object();
  if (!o) return NULL;
  json_object_set_new(o, "file", jtext(path));
  us_Structure *s = cli_load_quiet(path, c, deadline, &err);
  us_Status st = s ? run_task(b, s, deadline, o, &err) : err.code;
  *failed = st != US_OK && !(!s && st == US_ERR_TIME_LIMIT);
  if (!s && st == US_ERR_TIME_LIMIT) cut_fields(o, b, &err);
  else if (st) error_fields(o, b, &err);
  json_object_set_new(o, "time", json_real(round((us_now() - t0) * 1e6) / 1e6));
  us_structure_free(s);
  char *text = json_dumps(o, JSON_COMPACT | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(9));
  json_decref(o);
  size_t len = text ? strlen(text) : 0;
  char *line = text ? realloc(text, len + 2) : NULL;
  if (!line) return free(text), NULL;
  line[len] = '\n', line[len + 1] = '\0';
  return line;
}
