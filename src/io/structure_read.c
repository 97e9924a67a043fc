/* Reading structure files (docs/format.md): JSON text -> a finalized
 * us_Structure, with messages that name the file and the JSON path.
 *
 * Order of work: parse the JSON (syntax errors carry file:line:column), read
 * the top-level settings, then every body (the structure's id index means
 * duplicate ids and the ids used by explicit contacts are found in O(1)),
 * then the explicit contacts if there are any, and finally
 * us_structure_finalize, whose geometric messages (they name body ids) are
 * prefixed with the file name. Type and range checks happen here, before
 * the structure builder sees a value, because the builder gives some
 * values a meaning (mass <= 0: "use the density") that a file must not
 * reach by accident. Unknown keys are errors unless they start with '_'.
 * A friction coefficient is a number >= 0 or the string "infinite" (no
 * sliding: mu = INFINITY, which JSON numbers cannot hold).
 *
 * The dimension is read first, since it decides the structure and the
 * length of every vector: 2D bodies have a "polygon", 3D bodies
 * "vertices", "box" or "parts" (structure_read3.c); points, normals,
 * centres and gravity have dim components. */
#include <limits.h>
#include <math.h>
#include <string.h>

#include "io.h"
#include "model/model.h"

#define MAX_VERTS 10000000 /* far beyond any real polygon; keeps int sizes safe */

static const char *const top_keys[] = {"dimension", "gravity",  "friction", "ground",
                                       "bodies",    "contacts", NULL};
static const char *const body_keys[] = {"id",     "polygon",  "density",  "mass",
                                        "fixed",  "friction", "center",   "inertia",
                                        "vertices", "box",    "parts",    NULL};
static const char *const contact_keys[] = {"a", "b", "point", "normal", "friction", NULL};

/* Reader state: the structure under construction. Streamed (spans set),
 * the bodies are parsed one at a time from text; a failure before
 * finalize is then only a signal to read the text whole, so the messages
 * of bodies are not formatted. */
typedef struct Reader {
  us_IoCtx c;
  us_Structure *s;
  int explicit_contacts;
  double deadline; /* us_LoadSettings.deadline */
  const char *text;
  const us_BodySpans *spans;
  int finalizing; /* every value was read: errors from here on are final */
  const double *lane_xy; /* streamed: the body's plain polygon, read from */
  int lane_n;            /* the text (structure_split.c); NULL: none */
} Reader;

/* A friction field: a number >= 0, or "infinite" (INFINITY). */
static us_Status read_friction(Reader *r, const char *where, json_t *v, double *out) {
  if (json_is_string(v)) {
    if (strcmp(json_string_value(v), "infinite") != 0)
      return us_io_bad(&r->c, where, "friction: expected a number >= 0 or \"infinite\"");
    *out = INFINITY;
    return US_OK;
  }
  return us_io_sign_number(&r->c, where, "friction", v, 0, out);
}

/* "dimension": 2 (default) or 3. */
static us_Status read_dimension(Reader *r, json_t *root, int *dim) {
  json_t *v = json_object_get(root, "dimension");
  double d = 2;
  us_Status st = v ? us_io_number(&r->c, "", "dimension", v, &d) : US_OK;
  if (!st && d != 2 && d != 3) st = us_io_bad(&r->c, "", "dimension: must be 2 or 3 (got %g)", d);
  *dim = d == 3 ? 3 : 2;
  return st;
}

static us_Status read_globals(Reader *r, json_t *root) {
  us_Status st = us_io_check_keys(&r->c, "", root, top_keys);
  json_t *v;
  if (!st && (v = json_object_get(root, "gravity")))
    st = us_io_vecn(&r->c, "", "gravity", v, r->s->dim, r->s->gravity);
  if (!st && (v = json_object_get(root, "friction")))
    st = read_friction(r, "", v, &r->s->friction);
  if (!st && (v = json_object_get(root, "ground")))
    st = us_io_bool(&r->c, "", "ground", v, &r->s->ground);
  return st;
}

/* 1 if v is [x, y] with two finite numbers (into out), without a message:
 * the common case, which needs no field name formatted. */
static int plain_vec2(json_t *v, double out[2]) {
  if (!json_is_array(v) || json_array_size(v) != 2) return 0;
  json_t *x = json_array_get(v, 0), *y = json_array_get(v, 1);
  if (!json_is_number(x) || !json_is_number(y)) return 0;
  out[0] = json_number_value(x), out[1] = json_number_value(y);
  return isfinite(out[0]) && isfinite(out[1]);
}

/* The polygon of a body: an array of at least 3 [x, y] pairs. */
static us_Status read_polygon(Reader *r, const char *where, json_t *v, double **xy, int *n) {
  if (!json_is_array(v))
    return us_io_bad(&r->c, where, "polygon: expected an array of [x, y] vertices");
  size_t nv = json_array_size(v);
  if (nv < 3) return us_io_bad(&r->c, where, "polygon: needs at least 3 vertices (got %zu)", nv);
  if (nv > MAX_VERTS) return us_io_bad(&r->c, where, "polygon: too many vertices (%zu)", nv);
  *xy = us_malloc(2 * nv * sizeof(double));
  if (!*xy) return us_error_set(r->c.err, US_ERR_NOMEM, "%s: out of memory", r->c.name);
  for (size_t k = 0; k < nv; k++) {
    if (plain_vec2(json_array_get(v, k), *xy + 2 * k)) continue;
    char field[32]; /* a bad vertex: the checked read says why */
    snprintf(field, sizeof field, "polygon[%zu]", k);
    us_Status st = us_io_vec2(&r->c, where, field, json_array_get(v, k), *xy + 2 * k);
    if (st) return st;
  }
  *n = (int)nv;
  return US_OK;
}

/* Material fields shared by both kinds of body. */
typedef struct BodyFields {
  double density, mass, friction, inertia, center[3];
  int fixed;
} BodyFields;

static us_Status read_material(Reader *r, const char *where, json_t *b, BodyFields *f) {
  json_t *v;
  us_Status st = US_OK;
  f->density = 0, f->mass = 0, f->friction = -1, f->inertia = 0, f->fixed = 0;
  if (json_object_get(b, "density") && json_object_get(b, "mass"))
    return us_io_bad(&r->c, where, "give either 'density' or 'mass', not both");
  if ((v = json_object_get(b, "density")))
    st = us_io_sign_number(&r->c, where, "density", v, 1, &f->density);
  if (!st && (v = json_object_get(b, "mass")))
    st = us_io_sign_number(&r->c, where, "mass", v, 1, &f->mass);
  if (!st && (v = json_object_get(b, "friction")))
    st = read_friction(r, where, v, &f->friction);
  if (!st && (v = json_object_get(b, "fixed")))
    st = us_io_bool(&r->c, where, "fixed", v, &f->fixed);
  if (!st && (v = json_object_get(b, "inertia")))
    st = us_io_sign_number(&r->c, where, "inertia", v, 1, &f->inertia);
  return st;
}

/* A body without geometry: only with explicit contacts; needs a centre and
 * (unless fixed) a mass. */
static us_Status add_point_body(Reader *r, const char *where, const char *id, json_t *b,
                                const BodyFields *f) {
  BodyFields g = *f;
  json_t *v = json_object_get(b, "center");
  if (!r->explicit_contacts)
    return us_io_bad(&r->c, where,
                     r->s->dim == 3 ? "missing field 'vertices', 'box' or 'parts' (bodies without "
                                      "geometry need explicit contacts)"
                                    : "missing field 'polygon' (bodies without a polygon need "
                                      "explicit contacts)");
  if (!v) return us_io_bad(&r->c, where, "missing field 'center' (a body without a polygon)");
  us_Status st = us_io_vecn(&r->c, where, "center", v, r->s->dim, g.center);
  if (st) return st;
  if (json_object_get(b, "density"))
    return us_io_bad(&r->c, where, "'density' needs a polygon (give 'mass')");
  if (!g.fixed && !json_object_get(b, "mass"))
    return us_io_bad(&r->c, where, "missing field 'mass' (a body without a polygon)");
  int i = us_structure_add_point_body(r->s, id, g.mass, g.center, g.fixed, r->c.err);
  if (i < 0) return r->c.err->code;
  r->s->bodies[i].friction = g.friction;
  r->s->bodies[i].inertia = g.inertia;
  return US_OK;
}

/* A body definition with id and the material fields; geometry to add. */
static us_BodyDef material_def(const char *id, const BodyFields *f) {
  us_BodyDef d = us_default_body_def();
  d.id = id, d.density = f->density, d.mass = f->mass, d.fixed = f->fixed, d.friction = f->friction;
  return d;
}

static us_Status add_polygon_body(Reader *r, const char *where, const char *id, json_t *b,
                                  const BodyFields *f) {
  if (json_object_get(b, "center") || json_object_get(b, "inertia"))
    return us_io_bad(&r->c, where, "'center' and 'inertia' are only for bodies without a polygon");
  us_BodyDef d = material_def(id, f);
  double *xy = NULL;
  us_Status st = US_OK;
  if (r->lane_xy)
    d.xy = r->lane_xy, d.nvert = r->lane_n;
  else
    st = read_polygon(r, where, json_object_get(b, "polygon"), &xy, &d.nvert), d.xy = xy;
  if (!st && us_structure_add_body(r->s, &d, r->c.err) < 0) st = r->c.err->code;
  us_free(xy);
  return st;
}

/* A 3D body: a polyhedron, a box or a compound (structure_read3.c). */
static us_Status add_solid_body(Reader *r, const char *where, const char *id, json_t *b,
                                const BodyFields *f) {
  if (json_object_get(b, "center") || json_object_get(b, "inertia"))
    return us_io_bad(&r->c, where, "'center' and 'inertia' are only for bodies without geometry");
  us_PartDef *parts = NULL;
  int np = 0;
  us_Status st = us_io_read_solid(&r->c, where, b, &parts, &np);
  us_BodyDef d = material_def(id, f);
  if (np == 1)
    d.nvert = parts[0].nvert, d.xyz = parts[0].xyz;
  else
    d.npart = np, d.parts = parts;
  if (!st && us_structure_add_body(r->s, &d, r->c.err) < 0) st = r->c.err->code;
  us_io_solid_free(parts, np);
  return st;
}

/* Geometry fields of the other dimension are errors that say so. */
static us_Status check_dimension_fields(Reader *r, const char *where, json_t *b) {
  static const char *const solid[] = {"vertices", "box", "parts"};
  if (r->s->dim == 3 && json_object_get(b, "polygon"))
    return us_io_bad(&r->c, where, "'polygon' is for dimension 2 (3D bodies have 'vertices', "
                                   "'box' or 'parts')");
  for (int k = 0; r->s->dim == 2 && k < 3; k++)
    if (json_object_get(b, solid[k]))
      return us_io_bad(&r->c, where, "'%s' is for dimension 3 (set \"dimension\": 3)", solid[k]);
  return US_OK;
}

/* The id of body k: a unique non-empty string other than "ground". */
static us_Status read_id(Reader *r, const char *where, json_t *b, const char **id) {
  json_t *v = json_object_get(b, "id");
  if (!v) return us_io_bad(&r->c, where, "missing field 'id'");
  if (!json_is_string(v)) return us_io_bad(&r->c, where, "id: expected a string");
  *id = json_string_value(v);
  if (!**id) return us_io_bad(&r->c, where, "id: must not be empty");
  if (!strcmp(*id, "ground"))
    return us_io_bad(&r->c, where, "id 'ground' is reserved for the ground");
  /* streamed, the builder's own check finds a duplicate (and the text is
   * then read whole for this message) */
  int other = r->spans ? -1 : us_structure_find_body(r->s, *id);
  if (other >= 0)
    return us_io_bad(&r->c, where, "duplicate id '%s' (also bodies[%d])", us_id_text(*id).s, other);
  return US_OK;
}

static us_Status read_body(Reader *r, int k, json_t *b) {
  char where[160] = "bodies";
  if (!r->spans) snprintf(where, sizeof where, "bodies[%d]", k);
  if (!json_is_object(b)) return us_io_bad(&r->c, where, "expected an object");
  const char *id = NULL;
  us_Status st = read_id(r, where, b, &id);
  if (st) return st;
  if (!r->spans) snprintf(where, sizeof where, "bodies[%d] (id '%s')", k, us_id_text(id).s);
  BodyFields f;
  st = us_io_check_keys(&r->c, where, b, body_keys);
  if (!st) st = read_material(r, where, b, &f);
  if (!st) st = check_dimension_fields(r, where, b);
  if (st) return st;
  if (json_object_get(b, "polygon"))
    st = add_polygon_body(r, where, id, b, &f);
  else if (json_object_get(b, "vertices") || json_object_get(b, "box") || json_object_get(b, "parts"))
    st = add_solid_body(r, where, id, b, &f);
  else
    st = add_point_body(r, where, id, b, &f);
  return st;
}

#define LANE_MAX 64       /* vertices of a polygon taken from the text */
#define LANE_TEXT 2048    /* the rest of a body's text, on the stack */

/* Streamed: a body of only a plain id, polygon and fixed flag, added as
 * read_body adds it (the defaults of every other field), with no tree.
 * Whatever read_body would refuse is an error without a message: the
 * text is then read whole. */
static us_Status add_lane_body(Reader *r, const us_LaneBody *lb, const double *xy) {
  if (r->s->dim != 2 || !lb->id[0] || !strcmp(lb->id, "ground")) return US_ERR_INPUT;
  BodyFields f = {0, 0, -1, 0, {0, 0, 0}, lb->fixed};
  us_BodyDef d = material_def(lb->id, &f);
  d.xy = xy, d.nvert = lb->nv;
  return us_structure_add_body(r->s, &d, r->c.err) < 0 ? r->c.err->code : US_OK;
}

/* Streamed: body k parsed from its span, read, and its tree freed. A
 * plain body needs no tree; a plain polygon is read from the text, and
 * jansson gets the rest of the body with "polygon": []. */
static us_Status read_span(Reader *r, int k) {
  const us_JsonSpan *sp = &r->spans->el[k];
  const char *t = r->text + sp->off;
  double xy[2 * LANE_MAX];
  us_LaneBody lb;
  if (us_io_lane_body(t, sp->len, xy, LANE_MAX, &lb)) return add_lane_body(r, &lb, xy);
  char rest[LANE_TEXT];
  us_JsonSpan pv;
  size_t n = sp->len;
  int nv = sp->len < LANE_TEXT ? us_io_split_polygon(t, sp->len, &pv, xy, LANE_MAX) : 0;
  if (nv) {
    memcpy(rest, t, pv.off);
    memcpy(rest + pv.off, "[]", 2);
    memcpy(rest + pv.off + 2, t + pv.off + pv.len, sp->len - pv.off - pv.len);
    n = sp->len - pv.len + 2, t = rest;
  }
  json_error_t je;
  json_t *b = json_loadb(t, n, US_IO_JSON_FLAGS, &je);
  if (!b) return us_error_set(r->c.err, US_ERR_PARSE, "%s: bodies[%d] does not parse", r->c.name, k);
  r->lane_xy = nv ? xy : NULL, r->lane_n = nv;
  us_Status st = read_body(r, k, b);
  r->lane_xy = NULL;
  json_decref(b);
  return st;
}

static us_Status read_bodies(Reader *r, json_t *root) {
  json_t *arr = json_object_get(root, "bodies");
  if (!arr) return us_io_bad(&r->c, "", "missing field 'bodies'");
  if (!json_is_array(arr)) return us_io_bad(&r->c, "", "bodies: expected an array");
  size_t n = r->spans ? (size_t)r->spans->n : json_array_size(arr);
  if (n > (size_t)INT_MAX / 4) return us_io_bad(&r->c, "", "bodies: too many bodies");
  if (r->spans && us_structure_reserve(r->s, (int)n))
    return us_error_set(r->c.err, US_ERR_NOMEM, "%s: out of memory", r->c.name);
  for (size_t k = 0; k < n; k++) {
    if ((k & 1023) == 1023 && us_past(r->deadline))
      return us_error_set(r->c.err, US_ERR_TIME_LIMIT, "%s: time limit reached reading the bodies "
                          "(%zu of %zu read)", r->c.name, k, n);
    us_Status st = r->spans ? read_span(r, (int)k) : read_body(r, (int)k, json_array_get(arr, k));
    if (st) return st;
  }
  return US_OK;
}

/* One side of an explicit contact: a body id, or "ground" for side a. */
static us_Status read_side(Reader *r, const char *where, json_t *c, const char *field, int *out) {
  json_t *v = json_object_get(c, field);
  if (!v) return us_io_bad(&r->c, where, "missing field '%s'", field);
  if (!json_is_string(v)) return us_io_bad(&r->c, where, "%s: expected a body id (string)", field);
  const char *id = json_string_value(v);
  if (!strcmp(id, "ground")) {
    if (field[0] == 'b')
      return us_io_bad(&r->c, where, "b: must be a body, not the ground (put the ground in 'a')");
    if (!r->s->ground)
      return us_io_bad(&r->c, where, "a: 'ground' used but the structure has \"ground\": false");
    *out = US_GROUND;
    return US_OK;
  }
  *out = us_structure_find_body(r->s, id);
  if (*out < 0) return us_io_bad(&r->c, where, "%s: unknown body id '%s'", field, us_id_text(id).s);
  return US_OK;
}

/* The contact normal: unit length (within 1e-3, then normalized). */
static us_Status read_normal(Reader *r, const char *where, json_t *c, double n[3]) {
  json_t *v = json_object_get(c, "normal");
  if (!v) return us_io_bad(&r->c, where, "missing field 'normal'");
  int dim = r->s->dim;
  us_Status st = us_io_vecn(&r->c, where, "normal", v, dim, n);
  if (st) return st;
  double len = hypot(n[0], n[1]);
  if (dim == 3) len = hypot(len, n[2]);
  if (!(len > 1e-12)) return us_io_bad(&r->c, where, "normal: must not be zero");
  if (fabs(len - 1.0) > 1e-3)
    return us_io_bad(&r->c, where, "normal: must be a unit vector (length %g)", len);
  n[0] /= len, n[1] /= len, n[2] = dim == 3 ? n[2] / len : 0.0;
  return US_OK;
}

static us_Status read_contact(Reader *r, int k, json_t *c) {
  char where[48];
  snprintf(where, sizeof where, "contacts[%d]", k);
  if (!json_is_object(c)) return us_io_bad(&r->c, where, "expected an object");
  int a = 0, b = 0;
  double p[3] = {0, 0, 0}, n[3] = {0, 0, 0}, mu = -1.0;
  json_t *v;
  us_Status st = us_io_check_keys(&r->c, where, c, contact_keys);
  if (!st) st = read_side(r, where, c, "a", &a);
  if (!st) st = read_side(r, where, c, "b", &b);
  if (!st && a == b) st = us_io_bad(&r->c, where, "a and b are the same body");
  if (!st && !(v = json_object_get(c, "point")))
    st = us_io_bad(&r->c, where, "missing field 'point'");
  if (!st) st = us_io_vecn(&r->c, where, "point", v, r->s->dim, p);
  if (!st) st = read_normal(r, where, c, n);
  if (!st && (v = json_object_get(c, "friction")))
    st = read_friction(r, where, v, &mu);
  if (!st && us_structure_add_contact(r->s, a, b, p, n, mu, r->c.err) < 0) st = r->c.err->code;
  return st;
}

static us_Status read_contacts(Reader *r, json_t *arr) {
  if (!json_is_array(arr)) return us_io_bad(&r->c, "", "contacts: expected an array");
  for (size_t k = 0; k < json_array_size(arr); k++) {
    us_Status st = read_contact(r, (int)k, json_array_get(arr, k));
    if (st) return st;
  }
  r->s->explicit_contacts = 1;
  return US_OK;
}

/* Messages from the builder and finalize name bodies but not the file. */
static us_Status prefix_file(const us_IoCtx *c, us_Status st) {
  char msg[sizeof c->err->msg];
  memcpy(msg, c->err->msg, sizeof msg);
  return us_error_set(c->err, st, "%s: %s", c->name, msg);
}

/* Build s from the parsed document; returns a status, err set. */
static us_Status read_document(Reader *r, json_t *root, double contact_tol) {
  if (!json_is_object(root)) return us_io_bad(&r->c, "", "expected a JSON object at the top level");
  json_t *contacts = json_object_get(root, "contacts");
  r->explicit_contacts = contacts != NULL;
  int dim = 2;
  us_Status st = read_dimension(r, root, &dim);
  if (!st && !(r->s = us_structure_new(dim)))
    st = us_error_set(r->c.err, US_ERR_NOMEM, "%s: out of memory", r->c.name);
  if (!st) st = read_globals(r, root);
  if (!st) st = read_bodies(r, root);
  if (!st && contacts) st = read_contacts(r, contacts);
  if (st) return st;
  r->s->explicit_contacts = r->explicit_contacts;
  if (contact_tol > 0) r->s->contact_tol = contact_tol;
  r->finalizing = 1;
  st = us_structure_finalize_until(r->s, r->deadline, r->c.err);
  return st ? prefix_file(&r->c, st) : US_OK;
}

us_LoadSettings us_load_default_settings(void) { return (us_LoadSettings){0.0, 0.0}; }

us_Structure *us_structure_parse(const char *text, const char *name, double contact_tol,
                                 us_Error *err) {
  us_LoadSettings set = {contact_tol, 0.0};
  return us_structure_parse_with(text, name, &set, err);
}

/* The document without its bodies: the text with the bodies array
 * emptied, parsed; NULL when it does not parse. */
static json_t *parse_rest(const char *text, size_t len, const us_BodySpans *b) {
  size_t tail = b->arr_off + b->arr_len, n = b->arr_off + 2 + (len - tail);
  char *rest = us_malloc(n);
  if (!rest) return NULL;
  memcpy(rest, text, b->arr_off);
  memcpy(rest + b->arr_off, "[]", 2);
  memcpy(rest + b->arr_off + 2, text + tail, len - tail);
  json_error_t je;
  json_t *root = json_loadb(rest, n, US_IO_JSON_FLAGS, &je);
  us_free(rest);
  return root;
}

/* Read the text one body at a time (structure_split.c): US_OK, or an error
 * whose message is final only when r->finalizing is set, or for a time
 * limit or out of memory; otherwise the caller reads the text whole. */
static us_Status read_streamed(Reader *r, const char *text, size_t len, double contact_tol) {
  us_BodySpans b;
  int split = us_io_split_bodies(text, len, &b);
  json_t *root = split == 1 ? parse_rest(text, len, &b) : NULL;
  us_Status st = root ? US_OK : split < 0 ? US_ERR_NOMEM : US_ERR_PARSE;
  if (st == US_ERR_NOMEM) us_error_set(r->c.err, st, "%s: out of memory", r->c.name);
  r->text = text, r->spans = &b;
  if (!st) st = read_document(r, root, contact_tol);
  r->text = NULL, r->spans = NULL;
  json_decref(root);
  us_io_spans_free(&b);
  return st;
}

/* Read the text as one JSON tree: the reference for every message. */
static us_Status read_whole(Reader *r, const char *text, size_t len, double contact_tol) {
  json_t *root = us_io_parse_json_until(&r->c, text, len, r->deadline);
  us_Status st = root ? US_OK : r->c.err->code;
  if (!st) st = read_document(r, root, contact_tol);
  json_decref(root);
  return st;
}

/* Streamed first; a failure that is not final is read again whole. */
static us_Status read_text(Reader *r, const char *text, double contact_tol) {
  size_t len = strlen(text), bom = len >= 3 && !memcmp(text, "\xEF\xBB\xBF", 3) ? 3 : 0;
  us_Status st = read_streamed(r, text + bom, len - bom, contact_tol);
  if (!st || r->finalizing || st == US_ERR_NOMEM || st == US_ERR_TIME_LIMIT) return st;
  us_structure_free(r->s);
  r->s = NULL;
  us_error_clear(r->c.err);
  return read_whole(r, text, len, contact_tol);
}

/* Streamed (whole = 0) or as one tree (the reference). */
static us_Structure *parse(const char *text, const char *name, const us_LoadSettings *set,
                           int whole, us_Error *err) {
  us_LoadSettings def = us_load_default_settings();
  if (!set) set = &def;
  us_Error local;
  us_error_clear(&local);
  Reader r = {{name ? name : "<input>", &local}, NULL, 0, set->deadline, NULL, NULL, 0, NULL, 0};
  us_Status st = whole ? read_whole(&r, text, strlen(text), set->contact_tol)
                       : read_text(&r, text, set->contact_tol);
  if (st) {
    us_structure_free(r.s);
    if (err) *err = local;
    return NULL;
  }
  return r.s;
}

us_Structure *us_structure_parse_with(const char *text, const char *name,
                                      const us_LoadSettings *set, us_Error *err) {
  return parse(text, name, set, 0, err);
}

us_Structure *us_io_parse_whole(const char *text, const char *name, double contact_tol,
                                us_Error *err) {
  us_LoadSettings set = {contact_tol, 0.0};
  return parse(text, name, &set, 1, err);
}

us_Structure *us_structure_read(const char *path, double contact_tol, us_Error *err) {
  us_LoadSettings set = {contact_tol, 0.0};
  return us_structure_read_with(path, &set, err);
}

us_Structure *us_structure_read_with(const char *path, const us_LoadSettings *set,
                                     us_Error *err) {
  size_t len = 0;
  char *text = us_io_slurp(path, &len, err);
  if (!text) return NULL;
  if (strlen(text) != len) {
    us_free(text);
    us_error_set(err, US_ERR_PARSE, "%s: contains a NUL byte (not a JSON text file)", path);
    return NULL;
  }
  us_Structure *s = us_structure_parse_with(text, path, set, err);
  us_free(text);
  return s;
}
