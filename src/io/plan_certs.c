/* The certificates of a plan file (its "steps", docs/format.md) read back
 * as us_Forces on a given structure, for the HTML viewer.
 *
 * A step k holds "remove" (the ids of order step k) and
 * "certificate.contacts": entries {a, b, point, normal, force}, the forces
 * of the structure before step k in the contact's frame. Each entry is
 * matched to the structure's contact with the same bodies a and b (a may
 * be "ground") and the same normal (within 1e-6), not matched before in
 * the step, nearest to `point` within 1e-6 of the structure's scale (a
 * plan written for this structure repeats its points exactly; a small
 * shift from another contact tolerance is accepted). Two contacts may
 * share a point (a corner on two faces): their normals tell them apart.
 * The forces are
 * copied as written: this reader does not judge them (verification does).
 * Points, normals and forces have the structure's dimension of components
 * (3D forces: normal, then along the contact's tangents t1 and t2).
 *
 * Invariants of the result: certs has ngroups + 1 entries; certs[k] names
 * only contacts of s, each at most once; certs[ngroups] (the empty
 * structure) is empty. Steps must follow the order entry for entry, so a
 * plan edited by hand cannot show one step's forces on another.
 *
 * Lookup: contacts are bucketed by body b (CSR offsets), so matching an
 * entry scans only the contacts of its body b. */
#include <math.h>
#include <string.h>

#include "io.h"

typedef struct CertCtx {
  us_IoCtx io;
  const us_Structure *s;
  const us_PlanFile *pf;
  int *start;   /* [nbody + 1]: contacts of body b are by_b[start[b] .. start[b+1]-1] */
  int *by_b;    /* [ncontact] contact indices grouped by b */
  int *seen;    /* [ncontact] step + 1 that last used the contact */
} CertCtx;

static us_Status nomem(const CertCtx *c) {
  return us_error_set(c->io.err, US_ERR_NOMEM, "%s: out of memory", c->io.name);
}

/* ------------------------------------------------------------ lookup */

static us_Status build_index(CertCtx *c) {
  const us_Structure *s = c->s;
  c->start = us_calloc((size_t)s->nbody + 1, sizeof *c->start);
  c->by_b = us_malloc(((size_t)s->ncontact + 1) * sizeof *c->by_b);
  c->seen = us_calloc((size_t)s->ncontact + 1, sizeof *c->seen);
  if (!c->start || !c->by_b || !c->seen) return nomem(c);
  for (int j = 0; j < s->ncontact; j++) c->start[s->contacts[j].b + 1]++;
  for (int b = 0; b < s->nbody; b++) c->start[b + 1] += c->start[b];
  int *fill = us_malloc(((size_t)s->nbody + 1) * sizeof *fill);
  if (!fill) return nomem(c);
  memcpy(fill, c->start, (size_t)s->nbody * sizeof *fill);
  for (int j = 0; j < s->ncontact; j++) c->by_b[fill[s->contacts[j].b]++] = j;
  us_free(fill);
  return US_OK;
}

/* Body index of an id, US_GROUND for "ground" (side a only), or -2. */
static int side_index(const us_Structure *s, json_t *v, int may_be_ground) {
  const char *id = json_string_value(v);
  if (!id) return -2;
  if (may_be_ground && !strcmp(id, "ground")) return US_GROUND;
  int i = us_structure_find_body(s, id);
  return i >= 0 ? i : -2;
}

/* The contact of s between a and b with normal n nearest to p, within
 * tol, not yet used by step k, or -1. (Two contacts may share a point:
 * a corner on two faces; their normals tell them apart.) */
static double dist(const double *x, const double *y, int dim) {
  double s = 0.0;
  for (int d = 0; d < dim; d++) s += (x[d] - y[d]) * (x[d] - y[d]);
  return sqrt(s);
}
static int find_contact(const CertCtx *c, int a, int b, const double p[3], const double n[3],
                        int k) {
  double best = 1e-6 * c->s->scale;
  int hit = -1, dim = c->s->dim;
  for (int q = c->start[b]; q < c->start[b + 1]; q++) {
    int j = c->by_b[q];
    const us_Contact *x = &c->s->contacts[j];
    double d = dist(x->p, p, dim);
    if (x->a != a || c->seen[j] == k + 1 || dist(x->n, n, dim) > 1e-6) continue;
    if (d <= best) best = d, hit = j;
  }
  return hit;
}

/* ------------------------------------------------------------ entries */

/* One certificate entry into slot j of f. */
static us_Status read_entry(CertCtx *c, json_t *e, const char *where, int k, us_Forces *f,
                            int j) {
  if (!json_is_object(e)) return us_io_bad(&c->io, where, "expected a contact object");
  int a = side_index(c->s, json_object_get(e, "a"), 1);
  int b = side_index(c->s, json_object_get(e, "b"), 0);
  if (a == -2 || b < 0) return us_io_bad(&c->io, where, "a, b: expected body ids of the structure");
  double p[3] = {0, 0, 0}, n[3] = {0, 0, 0}, force[3] = {0, 0, 0};
  int dim = c->s->dim;
  us_Status st = us_io_vecn(&c->io, where, "point", json_object_get(e, "point"), dim, p);
  if (!st) st = us_io_vecn(&c->io, where, "normal", json_object_get(e, "normal"), dim, n);
  if (!st) st = us_io_vecn(&c->io, where, "force", json_object_get(e, "force"), dim, force);
  if (st) return st;
  int hit = find_contact(c, a, b, p, n, k);
  if (hit < 0)
    return us_io_bad(&c->io, where, "no contact between '%s' and '%s' at (%g, %g) with normal "
                     "(%g, %g) in the structure, or one given twice (a plan for another "
                     "structure?)", a == US_GROUND ? "ground" : us_id_text(c->s->bodies[a].id).s,
                     us_id_text(c->s->bodies[b].id).s, p[0], p[1], n[0], n[1]);
  c->seen[hit] = k + 1;
  f->contact[j] = hit;
  for (int d = 0; d < dim; d++) f->f[(size_t)dim * (size_t)j + (size_t)d] = force[d];
  return US_OK;
}

/* steps[k].remove must name the bodies of order step k, in order. */
static us_Status check_remove(const CertCtx *c, json_t *v, int k, const char *where) {
  const us_PlanFile *pf = c->pf;
  int a = pf->group_start[k], n = pf->group_start[k + 1] - a;
  int arr = json_is_array(v);
  if (arr ? (int)json_array_size(v) != n || n < 2 : n != 1)
    return us_io_bad(&c->io, where, "remove: does not match order[%d]", k);
  for (int q = 0; q < n; q++) {
    const char *id = json_string_value(arr ? json_array_get(v, (size_t)q) : v);
    if (!id || strcmp(id, c->s->bodies[pf->order[a + q]].id))
      return us_io_bad(&c->io, where, "remove: does not match order[%d]", k);
  }
  return US_OK;
}

static us_Status read_step(CertCtx *c, json_t *step, int k, us_Forces *f) {
  char where[64];
  snprintf(where, sizeof where, "steps[%d]", k);
  if (!json_is_object(step)) return us_io_bad(&c->io, where, "expected an object");
  us_Status st = check_remove(c, json_object_get(step, "remove"), k, where);
  if (st) return st;
  json_t *list = json_object_get(json_object_get(step, "certificate"), "contacts");
  if (!json_is_array(list)) return us_io_bad(&c->io, where, "certificate.contacts: expected an array");
  size_t n = json_array_size(list);
  if (n > (size_t)c->s->ncontact)
    return us_io_bad(&c->io, where, "more certificate contacts than the structure has");
  f->contact = us_malloc((n + 1) * sizeof *f->contact);
  f->f = us_malloc(((size_t)c->s->dim * n + 1) * sizeof *f->f);
  if (!f->contact || !f->f) return nomem(c);
  f->cap = (int)n;
  for (size_t j = 0; !st && j < n; j++) {
    snprintf(where, sizeof where, "steps[%d].certificate.contacts[%zu]", k, j);
    st = read_entry(c, json_array_get(list, j), where, k, f, (int)j);
    if (!st) f->ncontact++;
  }
  return st;
}

static us_Status read_steps(CertCtx *c, json_t *steps, us_Forces *certs) {
  int n = c->pf->ngroups;
  if (!json_is_array(steps)) return us_io_bad(&c->io, "", "steps: expected an array");
  if (json_array_size(steps) != (size_t)n)
    return us_io_bad(&c->io, "", "steps: %zu entries for %d steps of the order",
                     json_array_size(steps), n);
  us_Status st = build_index(c);
  for (int k = 0; !st && k < n; k++) st = read_step(c, json_array_get(steps, (size_t)k), k, &certs[k]);
  return st;
}

/* ------------------------------------------------------------- driver */

void us_certs_free(us_Forces *certs, int n) {
  for (int k = 0; certs && k < n; k++) us_forces_free(&certs[k]);
  us_free(certs);
}

static us_Status read_root(CertCtx *c, json_t *root, us_Forces **certs) {
  json_t *steps = json_is_object(root) ? json_object_get(root, "steps") : NULL;
  if (!json_is_object(root)) return us_io_bad(&c->io, "", "expected a JSON object at the top level");
  if (!steps) return US_OK; /* a plan without certificates */
  *certs = us_calloc((size_t)c->pf->ngroups + 1, sizeof **certs);
  return *certs ? read_steps(c, steps, *certs) : nomem(c);
}

us_Status us_plan_read_certs(const us_Structure *s, const char *path, const us_PlanFile *pf,
                             us_Forces **certs, us_Error *err) {
  us_Error local;
  us_error_clear(&local);
  if (!s || !path || !pf || !certs || (pf->ngroups > 0 && !pf->group_start))
    return us_error_set(err, US_ERR_USAGE, "us_plan_read_certs: missing argument");
  *certs = NULL;
  if (s->dim != 2 && s->dim != 3)
    return us_error_set(err, US_ERR_INPUT, "%s: certificates are read for 2D and 3D structures "
                        "only (this one is %dD)", path, s->dim);
  CertCtx c = {{path, &local}, s, pf, NULL, NULL, NULL};
  size_t len = 0;
  char *text = us_io_slurp(path, &len, &local);
  json_t *root = text ? us_io_parse_json(&c.io, text, len) : NULL;
  us_Status st = root ? read_root(&c, root, certs) : local.code;
  json_decref(root);
  us_free(text);
  us_free(c.start);
  us_free(c.by_b);
  us_free(c.seen);
  if (st) {
    us_certs_free(*certs, pf->ngroups + 1);
    *certs = NULL;
    if (err) *err = local;
  }
  return st;
}
