/* Plan files (docs/format.md): writing a plan with its settings, optional
 * per-step certificates and statistics; reading back its status and removal
 * order as body indices of a given structure.
 *
 * Certificates: certs[k] holds the contact forces of the structure before
 * removal k (all movable bodies minus order[0..k-1]). Each written step
 * carries those forces in the contacts' frames (f_n along the normal, f_t
 * along t = (-n_y, n_x)) and an independent re-check (us_certificate_check)
 * of that sub-assembly, so a reader can judge the certificate without a
 * solver. Reading ignores steps and statistics: only the status and the
 * order matter, and every id in the order must name a distinct movable
 * body of the structure. Completeness of the order is for verification to
 * judge, not the reader. */
#include <string.h>

#include "io.h"

static const char *const plan_keys[] = {
    "format",          "version",   "status", "order",      "method", "search",
    "order_heuristic", "direction", "steps",  "statistics", NULL};

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
  write_field_num(o, in, "solve_time", st->stability.solve_time, 0);
  write_field_num(o, in, "check_time", st->stability.check_time, 1);
  us_jo_raw(o, "    }\n  }\n");
}

static void write_cert_contact(us_JsonOut *o, const us_Structure *s, const us_Forces *f, int j) {
  const us_Contact *c = &s->contacts[f->contact[j]];
  us_jo_raw(o, "          {");
  us_jo_contact_fields(o, s, c);
  us_jo_raw(o, ", \"force\": ");
  us_jo_vec2(o, f->f + 2 * j);
  us_jo_raw(o, "}");
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

/* One step: the body removed and the certificate of the structure before. */
static void write_step(us_JsonOut *o, const us_Structure *s, const us_Plan *p, int k,
                       const us_Bitset *present, double tol) {
  const us_Forces *f = &p->certs[k];
  us_jo_raw(o, k ? ",\n    {\"remove\": " : "\n    {\"remove\": ");
  us_jo_string(o, s->bodies[p->order[k]].id);
  us_jo_raw(o, ",\n      \"certificate\": {\n        \"contacts\": [");
  for (int j = 0; j < f->ncontact; j++) {
    us_jo_raw(o, j ? ",\n" : "\n");
    write_cert_contact(o, s, f, j);
  }
  us_jo_raw(o, f->ncontact ? "\n        ],\n" : "],\n");
  us_CertCheck ck = us_certificate_check(s, present, f, tol);
  write_check(o, &ck);
  us_jo_raw(o, "      }}");
}

static us_Status write_steps(us_JsonOut *o, const us_Structure *s, const us_Plan *p, double tol) {
  us_Bitset present;
  if (us_bitset_init(&present, s->nbody > 0 ? s->nbody : 1)) return US_ERR_NOMEM;
  for (int i = 0; i < s->nbody; i++) us_bitset_set(&present, i);
  us_jo_raw(o, "  \"steps\": [");
  for (int k = 0; k < p->nsteps; k++) {
    write_step(o, s, p, k, &present, tol);
    us_bitset_clear(&present, p->order[k]);
  }
  us_jo_raw(o, p->nsteps ? "\n  ],\n" : "],\n");
  us_bitset_free(&present);
  return US_OK;
}

static void write_header(us_JsonOut *o, const us_Structure *s, const us_Plan *p,
                         const us_PlanSettings *set) {
  us_jo_raw(o, "{\n  \"format\": \"unstack-plan\",\n  \"version\": 1,\n  \"status\": ");
  us_jo_string(o, us_io_plan_status_word(p->status));
  if (set) {
    fprintf(o->fp, ",\n  \"method\": \"%s\",\n  \"search\": \"%s\",\n",
            us_io_method_word(set->stability.method), us_io_search_word(set->search));
    fprintf(o->fp, "  \"order_heuristic\": \"%s\",\n  \"direction\": \"%s\"",
            us_io_order_word(set->order), us_io_direction_word(set->direction));
  }
  us_jo_raw(o, ",\n  \"order\": [");
  for (int k = 0; k < p->nsteps; k++) {
    if (k) us_jo_raw(o, ", ");
    us_jo_string(o, s->bodies[p->order[k]].id);
  }
  us_jo_raw(o, "],\n");
}

/* Indices in the plan must be bodies of s (a caller bug otherwise). */
static int plan_consistent(const us_Structure *s, const us_Plan *p) {
  if (p->nsteps < 0 || (p->nsteps > 0 && !p->order)) return 0;
  for (int k = 0; k < p->nsteps; k++)
    if (p->order[k] < 0 || p->order[k] >= s->nbody) return 0;
  for (int k = 0; p->certs && k < p->nsteps; k++)
    for (int j = 0; j < p->certs[k].ncontact; j++)
      if (p->certs[k].contact[j] < 0 || p->certs[k].contact[j] >= s->ncontact) return 0;
  return 1;
}

us_Status us_plan_write(const us_Structure *s, const us_Plan *p, const us_PlanSettings *set,
                        const char *path, us_Error *err) {
  if (!s || !p || !path) return us_error_set(err, US_ERR_USAGE, "us_plan_write: missing argument");
  if (!plan_consistent(s, p))
    return us_error_set(err, US_ERR_USAGE, "%s: plan does not match the structure", path);
  us_AtomicFile *af = us_atomic_open(path, err);
  if (!af) return err ? err->code : US_ERR_IO;
  us_JsonOut o = {us_atomic_stream(af), 0};
  us_Status st = US_OK;
  write_header(&o, s, p, set);
  if (p->certs) st = write_steps(&o, s, p, set ? set->stability.cert_tol : 1e-6);
  if (!st) write_stats(&o, &p->stats);
  us_jo_raw(&o, "}\n");
  if (st || o.bad) {
    us_atomic_abort(af);
    if (st) return us_error_set(err, st, "%s: out of memory writing the plan", path);
    return us_error_set(err, US_ERR_INPUT, "%s: the plan holds a non-finite number", path);
  }
  return us_atomic_commit(af, err);
}

/* ------------------------------------------------------------------- read */

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
  if (!json_is_string(v) || us_io_plan_status_parse(json_string_value(v), status))
    return us_io_bad(c, "", "status: expected one of \"found\", \"none\", \"unstable\", \"limit\"");
  return US_OK;
}

/* Map order[k] to a body index: a known, movable body not seen before
 * (first[i] = position of body i in the order so far, or -1). */
static us_Status read_order_entry(const us_IoCtx *c, const us_Structure *s, json_t *v, int k,
                                  int *first, int *out) {
  char where[32];
  snprintf(where, sizeof where, "order[%d]", k);
  if (!json_is_string(v)) return us_io_bad(c, where, "expected a body id (string)");
  const char *id = json_string_value(v);
  int i = us_structure_find_body(s, id);
  if (i < 0) return us_io_bad(c, where, "unknown body id '%.80s'", id);
  if (s->bodies[i].fixed)
    return us_io_bad(c, where, "body '%.80s' is fixed and cannot be removed", id);
  if (first[i] >= 0)
    return us_io_bad(c, where, "body '%.80s' appears twice (also order[%d])", id, first[i]);
  first[i] = k;
  *out = i;
  return US_OK;
}

static us_Status read_order(const us_IoCtx *c, const us_Structure *s, json_t *arr,
                            us_PlanFile *out) {
  if (!arr) return us_io_bad(c, "", "missing field 'order'");
  if (!json_is_array(arr)) return us_io_bad(c, "", "order: expected an array of body ids");
  size_t n = json_array_size(arr);
  if (n > (size_t)s->nbody) return us_io_bad(c, "", "order: more entries (%zu) than bodies", n);
  int *first = us_malloc(((size_t)s->nbody + 1) * sizeof *first);
  out->order = us_malloc((n + 1) * sizeof *out->order);
  us_Status st = US_OK;
  if (!first || !out->order)
    st = us_error_set(c->err, US_ERR_NOMEM, "%s: out of memory", c->name);
  for (int i = 0; !st && i < s->nbody; i++) first[i] = -1;
  for (size_t k = 0; !st && k < n; k++)
    st = read_order_entry(c, s, json_array_get(arr, k), (int)k, first, &out->order[k]);
  us_free(first);
  out->n = (int)n;
  return st;
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
  if (!st) st = read_order(&c, s, json_object_get(root, "order"), out);
  json_decref(root);
  us_free(text);
  if (st) {
    us_plan_file_free(out);
    if (err) *err = local;
  }
  return st;
}

void us_plan_file_free(us_PlanFile *pf) {
  if (!pf) return;
  us_free(pf->order);
  pf->order = NULL;
  pf->n = 0;
}
