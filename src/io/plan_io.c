/* Plan files (docs/format.md): writing a plan with its settings, optional
 * per-step certificates and statistics; reading back its status and removal
 * order as body indices of a given structure. A written plan carries the
 * fingerprint of its structure (src/io/fingerprint.c); reading refuses a
 * plan whose fingerprint is not the structure's, and accepts one without
 * (older files).
 *
 * Steps: an "order" entry is a body id, or an array of ids removed in one
 * step (a group). Certificates: certs[k] holds the contact forces of the
 * structure before step k. Each written step
 * carries those forces in the contacts' frames (2D: f_n along the normal,
 * f_t along t = (-n_y, n_x); 3D: f_n, f_t1, f_t2 along n and the frame of
 * us_contact_frame) and an independent re-check (us_certificate_check)
 * of that sub-assembly, so a reader can judge the certificate without a
 * solver. Reading ignores steps and statistics: only the status and the
 * order matter, and every id in the order must name a distinct movable
 * body of the structure. Completeness of the order is for verification to
 * judge, not the reader. */
#include <string.h>

#include "io.h"
#include "plan_actions.h"
#include "stability/certificate.h"

static const char *const plan_keys[] = {
    "format",    "version",   "status",  "order",   "method",    "search",     "order_heuristic",
    "direction", "removal",   "max_group", "buildable", "blocked", "steps", "statistics",
    "fingerprint", "build", "hands",     "hands_lower", "actions", "release_certificates", NULL};

/* ------------------------------------------------------------------ write */

static void write_field_num(us_JsonOut *o, const char *indent, const char *key, double v,
                            int last) {
  fprintf(o->fp, "%s\"%s\": ", indent, key);
  us_jo_number(o, v);
  us_jo_raw(o, last ? "\n" : ",\n");
}

static void write_stats(us_JsonOut *o, const us_PlanStats *st) {
  us_jo_raw(o, "  \"statistics\": {\n");
  const char *in = "    ";
  write_field_num(o, in, "tests", (double)st->tests, 0);
  write_field_num(o, in, "stable", (double)st->stable, 0);
  write_field_num(o, in, "unstable", (double)st->unstable, 0);
  write_field_num(o, in, "revisited", (double)st->revisited, 0);
  write_field_num(o, in, "nodes_expanded", (double)st->nodes_expanded, 0);
  write_field_num(o, in, "max_depth", (double)st->max_depth, 0);
  write_field_num(o, in, "backtracks", (double)st->backtracks, 0);
  write_field_num(o, in, "saved_ground", (double)st->saved_ground, 0);
  write_field_num(o, in, "saved_union", (double)st->saved_union, 0);
  write_field_num(o, in, "exact_checks", (double)st->exact_checks, 0);
  write_field_num(o, in, "greedy_checks", (double)st->greedy_checks, 0);
  write_field_num(o, in, "exhaustive", (double)st->exhaustive, 0);
  write_field_num(o, in, "cuts", (double)st->cuts, 0);
  write_field_num(o, in, "held_tests", (double)st->held_tests, 0);
  write_field_num(o, in, "components", (double)st->components, 0);
  write_field_num(o, in, "retries_skipped", (double)st->retries_skipped, 0);
  write_field_num(o, in, "restarts", (double)st->restarts, 0);
  write_field_num(o, in, "time_total", st->time_total, 0);
  write_field_num(o, in, "time_setup", st->time_setup, 0);
  write_field_num(o, in, "time_search", st->time_search, 0);
  write_field_num(o, in, "time_solve", st->time_solve, 0);
  write_field_num(o, in, "time_check", st->time_check, 0);
  write_field_num(o, in, "memo_bytes", (double)st->memo_bytes, 0);
  us_jo_raw(o, "    \"stability\": {\n");
  in = "      ";
  write_field_num(o, in, "tests", (double)st->stability.tests, 0);
  write_field_num(o, in, "pivots", (double)st->stability.pivots, 0);
  write_field_num(o, in, "lp_fallbacks", (double)st->stability.lp_fallbacks, 0);
  write_field_num(o, in, "lcp_seeds", (double)st->stability.lcp_seeds, 0);
  write_field_num(o, in, "lcp_skips", (double)st->stability.lcp_skips, 0);
  write_field_num(o, in, "reused", (double)st->stability.reused, 0);
  write_field_num(o, in, "cone_lemke", (double)st->stability.cone_lemke, 0);
  write_field_num(o, in, "cone_lemke_failed", (double)st->stability.cone_lemke_failed, 0);
  write_field_num(o, in, "solve_time", st->stability.solve_time, 0);
  write_field_num(o, in, "check_time", st->stability.check_time, 1);
  us_jo_raw(o, "    }\n  }\n");
}

static void write_check(us_JsonOut *o, const us_CertCheck *ck) {
  us_jo_raw(o, ck->ok ? "        \"check\": {\"ok\": true" : "        \"check\": {\"ok\": false");
  us_jo_raw(o, ", \"force_residual\": ");
  us_jo_number(o, ck->max_force_residual);
  us_jo_raw(o, ", \"torque_residual\": ");
  us_jo_number(o, ck->max_torque_residual);
  us_jo_raw(o, ", \"cone_violation\": ");
  us_jo_number(o, ck->max_cone_violation);
  us_jo_raw(o, ", \"sign_violation\": ");
  us_jo_number(o, ck->max_sign_violation);
  us_jo_raw(o, "}\n");
}

/* Steps: group_start when given, else one body per step. */
static int nsteps_of(const us_Plan *p) { return p->group_start ? p->ngroups : p->nsteps; }
static int step_first(const us_Plan *p, int k) { return p->group_start ? p->group_start[k] : k; }

/* The ids of step k: a string for one body, an array for a group. */
static void write_step_ids(us_JsonOut *o, const us_Structure *s, const us_Plan *p, int k) {
  int a = step_first(p, k), b = step_first(p, k + 1);
  if (b - a > 1) us_jo_raw(o, "[");
  for (int q = a; q < b; q++) {
    if (q > a) us_jo_raw(o, ", ");
    us_jo_string(o, s->bodies[p->order[q]].id);
  }
  if (b - a > 1) us_jo_raw(o, "]");
}

/* One step: the bodies removed and the certificate of the structure before. */
static void write_step(us_JsonOut *o, const us_Structure *s, const us_Plan *p, int k,
                       const us_Bitset *present, double tol, double *acc, unsigned char *seen) {
  const us_Forces *f = &p->certs[k];
  us_jo_raw(o, k ? ",\n    {\"remove\": " : "\n    {\"remove\": ");
  write_step_ids(o, s, p, k);
  us_jo_raw(o, ",\n      \"certificate\": {\n        \"contacts\": [");
  for (int j = 0; j < f->ncontact; j++) {
    us_jo_raw(o, j ? ",\n" : "\n");
    us_jo_raw(o, "          ");
    us_jo_cert_contact(o, s, f, j);
  }
  us_jo_raw(o, f->ncontact ? "\n        ],\n" : "],\n");
  us_CertCheck ck;
  us_certificate_check_buf(s, present, f, tol, acc, seen, &ck);
  write_check(o, &ck);
  us_jo_raw(o, "      }}");
}

static us_Status write_steps(us_JsonOut *o, const us_Structure *s, const us_Plan *p, double tol) {
  us_Bitset present;
  /* the check's scratch, once for every step (no allocation failure can
     pass for a failed check) */
  double *acc = us_calloc((size_t)(s->nbody > 0 ? s->nbody : 1) * US_CERT_ACC, sizeof(double));
  unsigned char *seen = us_calloc((size_t)(s->ncontact > 0 ? s->ncontact : 1), 1);
  if (!acc || !seen || us_bitset_init(&present, s->nbody > 0 ? s->nbody : 1)) {
    us_free(acc);
    us_free(seen);
    return US_ERR_NOMEM;
  }
  for (int i = 0; i < s->nbody; i++) us_bitset_set(&present, i);
  us_jo_raw(o, "  \"steps\": [");
  for (int k = 0; k < nsteps_of(p); k++) {
    write_step(o, s, p, k, &present, tol, acc, seen);
    for (int q = step_first(p, k); q < step_first(p, k + 1); q++)
      us_bitset_clear(&present, p->order[q]);
  }
  us_jo_raw(o, nsteps_of(p) ? "\n  ],\n" : "],\n");
  us_bitset_free(&present);
  us_free(acc);
  us_free(seen);
  return US_OK;
}

static void write_id_list(us_JsonOut *o, const char *key, const us_Structure *s, const int *v,
                          int n) {
  fprintf(o->fp, "  \"%s\": [", key);
  for (int k = 0; k < n; k++) {
    if (k) us_jo_raw(o, ", ");
    us_jo_string(o, s->bodies[v[k]].id);
  }
  us_jo_raw(o, "],\n");
}

static void write_settings(us_JsonOut *o, const us_PlanSettings *set) {
  fprintf(o->fp, ",\n  \"method\": \"%s\",\n  \"search\": \"%s\",\n",
          us_method_name(set->stability.method), us_search_name(set->search));
  fprintf(o->fp, "  \"order_heuristic\": \"%s\",\n  \"direction\": \"%s\",\n",
          us_order_name(set->order), us_direction_name(set->direction));
  fprintf(o->fp, "  \"removal\": \"%s\"", us_removal_name(set->removal));
}

/* "build": the greedy's placements, steps as in "order". */
static void write_build(us_JsonOut *o, const us_Structure *s, const us_Plan *p) {
  us_jo_raw(o, "  \"build\": [");
  for (int k = 0; k < p->nbuild; k++) {
    int a = p->build_start[k], b = p->build_start[k + 1];
    us_jo_raw(o, k ? (b - a > 1 ? ", [" : ", ") : (b - a > 1 ? "[" : ""));
    for (int q = a; q < b; q++) {
      if (q > a) us_jo_raw(o, ", ");
      us_jo_string(o, s->bodies[p->buildable[q]].id);
    }
    if (b - a > 1) us_jo_raw(o, "]");
  }
  us_jo_raw(o, "],\n");
}

static void write_header(us_JsonOut *o, const us_Structure *s, const us_Plan *p,
                         const us_PlanSettings *set, const char *fp) {
  us_jo_raw(o, "{\n  \"format\": \"unstack-plan\",\n  \"version\": 1,\n  \"fingerprint\": ");
  us_jo_string(o, fp);
  us_jo_raw(o, ",\n  \"status\": ");
  us_jo_string(o, us_plan_status_name(p->status));
  if (set) write_settings(o, set);
  if (p->max_group > 0) fprintf(o->fp, ",\n  \"max_group\": %d", p->max_group);
  us_jo_raw(o, ",\n  \"order\": [");
  for (int k = 0; k < nsteps_of(p); k++) {
    if (k) us_jo_raw(o, ", ");
    write_step_ids(o, s, p, k);
  }
  us_jo_raw(o, "],\n");
  if (p->buildable) write_id_list(o, "buildable", s, p->buildable, p->nbuildable);
  if (p->blocked) write_id_list(o, "blocked", s, p->blocked, p->nblocked);
  if (p->buildable && p->build_start) write_build(o, s, p);
}

/* Indices in the plan must be bodies of s (a caller bug otherwise). */
static int plan_consistent(const us_Structure *s, const us_Plan *p) {
  if (p->nsteps < 0 || (p->nsteps > 0 && !p->order)) return 0;
  if (p->group_start && (p->ngroups < 0 || p->group_start[0] != 0 ||
                         p->group_start[p->ngroups] != p->nsteps))
    return 0;
  for (int k = 0; p->group_start && k < p->ngroups; k++)
    if (p->group_start[k + 1] <= p->group_start[k]) return 0;
  for (int k = 0; k < p->nbuildable; k++)
    if (p->buildable[k] < 0 || p->buildable[k] >= s->nbody) return 0;
  for (int k = 0; k < p->nblocked; k++)
    if (p->blocked[k] < 0 || p->blocked[k] >= s->nbody) return 0;
  if (p->build_start && (p->nbuild < 0 || p->build_start[0] != 0 ||
                         p->build_start[p->nbuild] != p->nbuildable))
    return 0;
  for (int k = 0; p->build_start && k < p->nbuild; k++)
    if (p->build_start[k + 1] <= p->build_start[k]) return 0;
  for (int k = 0; k < p->nsteps; k++)
    if (p->order[k] < 0 || p->order[k] >= s->nbody) return 0;
  for (int k = 0; p->certs && k <= nsteps_of(p); k++)
    for (int j = 0; j < p->certs[k].ncontact; j++)
      if (p->certs[k].contact[j] < 0 || p->certs[k].contact[j] >= s->ncontact) return 0;
  return 1;
}

static us_Status check_plan(const us_Structure *s, const us_Plan *p, const char *path,
                            us_Error *err) {
  if (!s || !p || !path) return us_error_set(err, US_ERR_USAGE, "us_plan_write: missing argument");
  if (!plan_consistent(s, p))
    return us_error_set(err, US_ERR_USAGE, "%s: plan does not match the structure", path);
  return US_OK;
}

/* The whole plan into fp; an error leaves fp with part of it. */
static us_Status write_plan(FILE *fp, const us_Structure *s, const us_Plan *p,
                            const us_PlanSettings *set, const char *path, us_Error *err) {
  uint64_t h;
  char fpt[US_FINGERPRINT_CHARS];
  us_Status st = us_structure_fingerprint(s, &h, err);
  if (st) return st;
  us_fingerprint_text(h, fpt);
  us_JsonOut o = {fp, 0, 0};
  write_header(&o, s, p, set, fpt);
  us_plan_write_actions(&o, s, p);
  if (p->certs) st = write_steps(&o, s, p, set ? set->stability.cert_tol : 1e-6);
  if (!st) write_stats(&o, &p->stats);
  us_jo_raw(&o, "}\n");
  if (st) return us_error_set(err, st, "%s: out of memory writing the plan", path);
  if (o.bad || o.bad_text)
    return us_error_set(err, US_ERR_INPUT, "%s: the plan holds %s", path,
                        o.bad ? "a non-finite number" : "an id that is not valid UTF-8");
  return US_OK;
}

us_Status us_plan_write(const us_Structure *s, const us_Plan *p, const us_PlanSettings *set,
                        const char *path, us_Error *err) {
  us_Status st = check_plan(s, p, path, err);
  if (st) return st;
  us_AtomicFile *af = us_atomic_open(path, err);
  if (!af) return err ? err->code : US_ERR_IO;
  st = write_plan(us_atomic_stream(af), s, p, set, path, err);
  if (!st) return us_atomic_commit(af, err);
  us_atomic_abort(af);
  return st;
}

us_Status us_plan_write_stream(const us_Structure *s, const us_Plan *p,
                               const us_PlanSettings *set, void *fp, const char *name,
                               us_Error *err) {
  us_Status st = check_plan(s, p, name, err);
  if (!st && !fp) st = us_error_set(err, US_ERR_USAGE, "us_plan_write_stream: no stream");
  if (!st) st = write_plan(fp, s, p, set, name, err);
  if (!st && (fflush(fp) || ferror(fp)))
    st = us_error_set(err, US_ERR_IO, "%s: write error", name);
  return st;
}

/* ------------------------------------------------------------------- read */

/* The words of an enum come from its table (src/plan/names.c), never
 * spelled here: "FIELD: expected one of "a", "b", ...". */
static const char *status_word(int i) { return us_plan_status_name((us_PlanStatus)i); }
static const char *removal_word(int i) { return us_removal_name((us_Removal)i); }

static us_Status expected_word(const us_IoCtx *c, const char *field, const char *(*word)(int)) {
  char list[160] = "";
  size_t len = 0;
  for (int i = 0; i < 16 && strcmp(word(i), "unknown") && len < sizeof list; i++)
    len += (size_t)snprintf(list + len, sizeof list - len, "%s\"%s\"", i ? ", " : "", word(i));
  return us_io_bad(c, "", "%s: expected one of %s", field, list);
}

static us_Status read_header(const us_IoCtx *c, json_t *root, us_PlanStatus *status) {
  us_Status st = us_io_check_keys(c, "", root, plan_keys);
  if (st) return st;
  json_t *v = json_object_get(root, "format");
  if (v && !(json_is_string(v) && !strcmp(json_string_value(v), "unstack-plan")))
    return us_io_bad(c, "", "format: expected \"unstack-plan\"");
  v = json_object_get(root, "version");
  if (v && !(json_is_number(v) && json_number_value(v) == 1.0))
    return us_io_bad(c, "", "version: only version 1 is supported");
  v = json_object_get(root, "status");
  if (!v) return us_io_bad(c, "", "missing field 'status'");
  if (!json_is_string(v) || us_plan_status_parse(json_string_value(v), status))
    return expected_word(c, "status", status_word);
  return US_OK;
}

/* Map one id to a body index: a known, movable body not seen before
 * (first[i] = position of body i in the order so far, or -1). */
static us_Status read_order_id(const us_IoCtx *c, const us_Structure *s, json_t *v,
                               const char *where, int pos, int *first, int *out) {
  if (!json_is_string(v)) return us_io_bad(c, where, "expected a body id (string)");
  const char *id = json_string_value(v);
  int i = us_structure_find_body(s, id);
  if (i < 0) return us_io_bad(c, where, "unknown body id '%s'", us_id_text(id).s);
  if (s->bodies[i].fixed)
    return us_io_bad(c, where, "body '%s' is fixed and cannot be removed", us_id_text(id).s);
  if (first[i] >= 0) return us_io_bad(c, where, "body '%s' appears twice", us_id_text(id).s);
  first[i] = pos;
  *out = i;
  return US_OK;
}

/* A list too long for the structure is most often a plan for another
 * structure: name its first unknown id (entries and groups' members). */
static us_Status first_unknown(const us_IoCtx *c, const us_Structure *s, json_t *arr,
                               const char *field) {
  char where[48];
  for (size_t k = 0; k < json_array_size(arr); k++) {
    json_t *v = json_array_get(arr, k);
    size_t m = json_is_array(v) ? json_array_size(v) : 1;
    for (size_t q = 0; q < m; q++) {
      json_t *e = json_is_array(v) ? json_array_get(v, q) : v;
      const char *id = json_string_value(e);
      if (!id || us_structure_find_body(s, id) >= 0) continue;
      if (json_is_array(v)) snprintf(where, sizeof where, "%s[%zu][%zu]", field, k, q);
      else snprintf(where, sizeof where, "%s[%zu]", field, k);
      return us_io_bad(c, where, "unknown body id '%s' (a plan for another structure?)",
                       us_id_text(id).s);
    }
  }
  return US_OK;
}

/* FIELD[k]: an id (one body) or a non-empty array of ids (a group). */
static us_Status read_order_entry(const us_IoCtx *c, const us_Structure *s, json_t *v,
                                  const char *field, int k, int *first, us_PlanFile *out) {
  char where[48];
  snprintf(where, sizeof where, "%s[%d]", field, k);
  if (!json_is_array(v)) {
    us_Status st = read_order_id(c, s, v, where, out->n, first, &out->order[out->n]);
    if (!st) out->n++;
    return st;
  }
  size_t m = json_array_size(v);
  if (m == 0) return us_io_bad(c, where, "an empty step");
  for (size_t q = 0; q < m; q++) {
    if (out->n >= s->nbody) return us_io_bad(c, where, "more bodies than the structure has");
    snprintf(where, sizeof where, "%s[%d][%zu]", field, k, q);
    us_Status st = read_order_id(c, s, json_array_get(v, q), where, out->n, first,
                                 &out->order[out->n]);
    if (st) return st;
    out->n++;
  }
  return US_OK;
}

/* "order" (or "build", the same syntax) into out->order, group_start. */
static us_Status read_order(const us_IoCtx *c, const us_Structure *s, json_t *arr,
                            const char *field, us_PlanFile *out) {
  if (!arr) return us_io_bad(c, "", "missing field '%s'", field);
  if (!json_is_array(arr)) return us_io_bad(c, "", "%s: expected an array of body ids", field);
  size_t n = json_array_size(arr);
  if (n > (size_t)s->nbody && first_unknown(c, s, arr, field)) return US_ERR_INPUT;
  if (n > (size_t)s->nbody)
    return us_io_bad(c, "", "%s: more entries (%zu) than bodies (%d)", field, n, s->nbody);
  int *first = us_malloc(((size_t)s->nbody + 1) * sizeof *first);
  out->order = us_malloc(((size_t)s->nbody + 1) * sizeof *out->order);
  out->group_start = us_malloc((n + 2) * sizeof *out->group_start);
  us_Status st = US_OK;
  if (!first || !out->order || !out->group_start)
    st = us_error_set(c->err, US_ERR_NOMEM, "%s: out of memory", c->name);
  for (int i = 0; !st && i < s->nbody; i++) first[i] = -1;
  if (!st) out->group_start[0] = 0;
  for (size_t k = 0; !st && k < n; k++) {
    st = read_order_entry(c, s, json_array_get(arr, k), field, (int)k, first, out);
    if (!st) out->group_start[++out->ngroups] = out->n;
  }
  us_free(first);
  return st;
}

/* "blocked" (optional): distinct movable bodies, none of them in the order. */
static us_Status read_blocked(const us_IoCtx *c, const us_Structure *s, json_t *arr,
                              us_PlanFile *out) {
  if (!arr) return US_OK;
  if (!json_is_array(arr)) return us_io_bad(c, "", "blocked: expected an array of body ids");
  size_t n = json_array_size(arr);
  if (n > (size_t)s->nbody && first_unknown(c, s, arr, "blocked")) return US_ERR_INPUT;
  if (n > (size_t)s->nbody)
    return us_io_bad(c, "", "blocked: more entries (%zu) than bodies (%d)", n, s->nbody);
  int *first = us_malloc(((size_t)s->nbody + 1) * sizeof *first);
  out->blocked = us_malloc((n + 1) * sizeof *out->blocked);
  us_Status st = first && out->blocked ? US_OK
                                       : us_error_set(c->err, US_ERR_NOMEM, "%s: out of memory", c->name);
  for (int i = 0; !st && i < s->nbody; i++) first[i] = -1;
  for (int k = 0; !st && k < out->n; k++) first[out->order[k]] = k;
  char where[32];
  for (size_t k = 0; !st && k < n; k++) {
    snprintf(where, sizeof where, "blocked[%zu]", k);
    st = read_order_id(c, s, json_array_get(arr, k), where, (int)k, first, &out->blocked[k]);
    if (!st) out->nblocked++;
  }
  us_free(first);
  return st;
}

/* "build" (optional): the buildable part in placement order, as "order". */
static us_Status read_build(const us_IoCtx *c, const us_Structure *s, json_t *arr,
                            us_PlanFile *out) {
  if (!arr) return US_OK;
  us_PlanFile b;
  memset(&b, 0, sizeof b);
  us_Status st = read_order(c, s, arr, "build", &b);
  out->buildable = b.order;
  out->build_start = b.group_start;
  out->nbuildable = b.n;
  out->nbuild = b.ngroups;
  return st;
}

/* "fingerprint" (optional: older files have none): the structure's, or
 * the file is refused as another structure's plan. */
static us_Status read_fingerprint(const us_IoCtx *c, const us_Structure *s, json_t *v,
                                  us_PlanFile *out) {
  if (!v) return US_OK;
  const char *text = json_string_value(v);
  if (!text || strlen(text) != US_FINGERPRINT_CHARS - 1 || strncmp(text, "fnv1a64:", 8))
    return us_io_bad(c, "", "fingerprint: expected \"fnv1a64:\" and 16 hex digits");
  uint64_t h;
  char mine[US_FINGERPRINT_CHARS];
  us_Status st = us_structure_fingerprint(s, &h, c->err);
  if (st) return st;
  us_fingerprint_text(h, mine);
  snprintf(out->fingerprint, sizeof out->fingerprint, "%s", text);
  out->has_fingerprint = 1;
  if (!strcmp(text, mine)) return US_OK;
  out->other_structure = 1;
  return us_io_bad(c, "", "fingerprint: a plan for another structure (the plan's %s, the "
                   "structure's %s)", text, mine);
}

static us_Status read_removal(const us_IoCtx *c, json_t *v, us_Removal *out) {
  *out = US_REMOVAL_ANY;
  if (v && (!json_is_string(v) || us_removal_parse(json_string_value(v), out)))
    return expected_word(c, "removal", removal_word);
  return US_OK;
}

us_Status us_plan_read(const us_Structure *s, const char *path, us_PlanFile *out, us_Error *err) {
  us_Error local;
  us_error_clear(&local);
  us_IoCtx c = {path, &local};
  memset(out, 0, sizeof *out);
  size_t len = 0;
  char *text = us_io_slurp(path, &len, &local);
  json_t *root = text ? us_io_parse_json(&c, text, len) : NULL;
  us_Status st = root ? US_OK : local.code;
  if (!st && !json_is_object(root))
    st = us_io_bad(&c, "", "expected a JSON object at the top level");
  if (!st) st = read_header(&c, root, &out->status);
  if (!st) st = read_fingerprint(&c, s, json_object_get(root, "fingerprint"), out);
  if (!st) st = read_order(&c, s, json_object_get(root, "order"), "order", out);
  if (!st) st = read_blocked(&c, s, json_object_get(root, "blocked"), out);
  if (!st) st = read_build(&c, s, json_object_get(root, "build"), out);
  if (!st) st = read_removal(&c, json_object_get(root, "removal"), &out->removal);
  if (!st) st = us_plan_read_actions(&c, s, root, out);
  json_decref(root);
  us_free(text);
  if (st) {
    us_plan_file_free(out); /* keeps the fingerprint fields for the caller */
    if (err) *err = local;
  }
  return st;
}

void us_plan_file_free(us_PlanFile *pf) {
  if (!pf) return;
  us_free(pf->order);
  us_free(pf->group_start);
  us_free(pf->blocked);
  us_free(pf->buildable);
  us_free(pf->build_start);
  us_free(pf->actions);
  pf->actions = NULL;
  pf->nactions = pf->hands = 0;
  pf->order = pf->group_start = pf->blocked = pf->buildable = pf->build_start = NULL;
  pf->n = pf->ngroups = pf->nblocked = pf->nbuildable = pf->nbuild = 0;
}
