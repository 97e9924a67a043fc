/* The hands fields of plan files: "hands" (the most bodies held at once),
 * "hands_lower" (every smaller H is proven impossible from this one down:
 * the minimum is proven when it equals "hands") and "actions" (the
 * assembly, each entry [verb, id]). Reading checks the words and the ids;
 * whether the sequence is possible is verify's question (verify.c). */
#include "plan_actions.h"

#include <math.h>
#include <string.h>

/* "release_certificates": per release, its index, the bodies held after
 * it and the forces of the placed bodies with those fixed. */
static void write_certs(us_JsonOut *o, const us_Structure *s, const us_Plan *p) {
  unsigned char *held = us_calloc((size_t)s->nbody + 1, 1);
  if (!held) return (void)(o->bad = 1);
  us_jo_raw(o, "  \"release_certificates\": [");
  int first = 1;
  for (int k = 0; k < p->nactions; k++) {
    const us_Action *a = &p->actions[k];
    held[a->body] = a->verb != US_ACTION_RELEASE;
    if (a->verb != US_ACTION_RELEASE) continue;
    fprintf(o->fp, "%s\n    {\"action\": %d, \"held\": [", first ? "" : ",", k);
    first = 0;
    for (int i = 0, m = 0; i < s->nbody; i++)
      if (held[i]) us_jo_raw(o, m++ ? ", " : ""), us_jo_string(o, s->bodies[i].id);
    us_jo_raw(o, "], \"contacts\": [");
    for (int j = 0; j < p->release_certs[k].ncontact; j++) {
      us_jo_raw(o, j ? ",\n      " : "\n      ");
      us_jo_cert_contact(o, s, &p->release_certs[k], j);
    }
    us_jo_raw(o, "]}");
  }
  us_jo_raw(o, "],\n");
  us_free(held);
}

void us_plan_write_actions(us_JsonOut *o, const us_Structure *s, const us_Plan *p) {
  if (!p->actions) return;
  fprintf(o->fp, "  \"hands\": %d,\n  \"hands_lower\": %d,\n  \"actions\": [", p->hands,
          p->hands_lower);
  for (int k = 0; k < p->nactions; k++) {
    us_jo_raw(o, k ? ",\n    [" : "\n    [");
    us_jo_string(o, us_action_name(p->actions[k].verb));
    us_jo_raw(o, ", ");
    us_jo_string(o, s->bodies[p->actions[k].body].id);
    us_jo_raw(o, "]");
  }
  us_jo_raw(o, "],\n");
  if (p->release_certs) write_certs(o, s, p);
}

/* A whole number in [lo, hi]. */
static us_Status read_count(const us_IoCtx *c, json_t *v, const char *field, int lo, int hi,
                            int *out) {
  double x = json_is_number(v) ? json_number_value(v) : NAN;
  if (!(x >= lo && x <= hi) || x != floor(x))
    return us_io_bad(c, "", "%s: expected an integer from %d to %d", field, lo, hi);
  *out = (int)x;
  return US_OK;
}

/* actions[k]: [verb, id] with a known verb and a movable body. */
static us_Status read_action(const us_IoCtx *c, const us_Structure *s, json_t *v, size_t k,
                             us_Action *out) {
  char where[48];
  snprintf(where, sizeof where, "actions[%zu]", k);
  if (!json_is_array(v) || json_array_size(v) != 2 || !json_is_string(json_array_get(v, 0)) ||
      !json_is_string(json_array_get(v, 1)))
    return us_io_bad(c, where, "expected [verb, body id]");
  const char *verb = json_string_value(json_array_get(v, 0));
  const char *id = json_string_value(json_array_get(v, 1));
  if (us_action_parse(verb, &out->verb))
    return us_io_bad(c, where, "unknown verb '%s' (place, grab or release)", us_id_text(verb).s);
  out->body = us_structure_find_body(s, id);
  if (out->body < 0) return us_io_bad(c, where, "unknown body id '%s'", us_id_text(id).s);
  if (s->bodies[out->body].fixed)
    return us_io_bad(c, where, "body '%s' is fixed and cannot be placed", us_id_text(id).s);
  return US_OK;
}

us_Status us_plan_read_actions(const us_IoCtx *c, const us_Structure *s, json_t *root,
                               us_PlanFile *out) {
  json_t *h = json_object_get(root, "hands"), *arr = json_object_get(root, "actions");
  if (!h && !arr) return US_OK;
  if (!h || !arr) return us_io_bad(c, "", "\"hands\" and \"actions\" go together");
  us_Status st = read_count(c, h, "hands", 1, 64, &out->hands);
  json_t *lo = json_object_get(root, "hands_lower");
  if (!st && lo) st = read_count(c, lo, "hands_lower", 1, 65, &out->hands_lower);
  if (!st && !json_is_array(arr)) st = us_io_bad(c, "", "actions: expected an array");
  if (st) return st;
  size_t n = json_array_size(arr);
  out->actions = us_malloc((n + 1) * sizeof *out->actions);
  if (!out->actions) return us_error_set(c->err, US_ERR_NOMEM, "%s: out of memory", c->name);
  for (size_t k = 0; k < n; k++) {
    st = read_action(c, s, json_array_get(arr, k), k, &out->actions[k]);
    if (st) return st;
    out->nactions++;
  }
  return US_OK;
}
