/* The structure model: building a structure body by body, and sealing it
 * with finalize, a pipeline of steps that each only read what the previous
 * ones wrote: validate -> mass properties -> measure -> detect -> install.
 * Detection (contact/) returns a contact list and never calls back here;
 * this file installs the list, so the dependency runs one way only.
 *
 * Invariants after finalize: polygons are counter-clockwise and simple;
 * 3D parts are convex hulls with outward faces; movable bodies have mass
 * > 0 and finite inertia; every contact has a unit
 * normal pointing from a into b, a tangent basis, and mu >= 0; scale > 0.
 * contact_tol keeps the caller's value (<= 0: tolerances per pair). Fixed
 * bodies keep their geometry and take no mass. */
#include "model.h"
#include "massprops.h"

#include "contact/contact.h"
#include "geometry/geometry3.h"

#include <math.h>
#include <string.h>

/* What users never see of a structure (us_Structure.internal), allocated
 * with it in one block. A struct copy of a us_Structure shares it: such a
 * copy may be read (ids, finalized) but not grown or freed. */
struct us_StructureInternal {
  int finalized;
  int cap_body, cap_contact; /* capacities of bodies, contacts */
  us_IdMap *id_index;        /* id -> body index, NULL until the first body */
};

typedef struct Block {
  us_Structure s;
  struct us_StructureInternal in;
} Block;

us_Structure *us_structure_new(int dim) {
  Block *blk = us_calloc(1, sizeof *blk);
  if (!blk) return NULL;
  us_Structure *s = &blk->s;
  s->internal = &blk->in;
  s->dim = dim;
  s->gravity[0] = 0.0;
  s->gravity[1] = dim == 3 ? 0.0 : -9.81;
  s->gravity[2] = dim == 3 ? -9.81 : 0.0;
  s->friction = 0.5;
  s->ground = 1;
  s->contact_tol = 0.0;
  return s;
}

void us_structure_free(us_Structure *s) {
  if (!s) return;
  for (int i = 0; i < s->nbody; i++) {
    us_free(s->bodies[i].id);
    us_free(s->bodies[i].verts);
    us_body_free_parts(&s->bodies[i]);
  }
  us_free(s->bodies);
  us_free(s->contacts);
  if (s->internal->id_index) us_idmap_free(s->internal->id_index);
  us_free(s->internal->id_index);
  us_free(s); /* the block (its first member) */
}

int us_structure_find_body(const us_Structure *s, const char *id) {
  us_IdMap *m = s->internal->id_index;
  return m ? us_idmap_get(m, id) : -1;
}

/* Register body i's id; -1 duplicate, -2 out of memory. */
static int index_id(us_Structure *s, int i) {
  struct us_StructureInternal *in = s->internal;
  if (!in->id_index && !(in->id_index = us_calloc(1, sizeof(us_IdMap)))) return -2;
  return us_idmap_put(in->id_index, s->bodies[i].id, i);
}

int us_structure_reserve(us_Structure *s, int n) {
  struct us_StructureInternal *in = s->internal;
  if (US_GROW(s->bodies, in->cap_body, n)) return -1;
  if (in->id_index || n < 1) return 0;
  if (!(in->id_index = us_calloc(1, sizeof(us_IdMap)))) return -1;
  return us_idmap_init(in->id_index, n);
}

/* Append a body with the given id; returns its index or -1. */
static int add_body(us_Structure *s, const char *id, us_Error *err) {
  if (!id || !*id) {
    us_error_set(err, US_ERR_INPUT, "body %d: empty id", s->nbody);
    return -1;
  }
  if (!strcmp(id, "ground")) {
    us_error_set(err, US_ERR_INPUT, "body id 'ground' is reserved for the ground");
    return -1;
  }
  if (US_GROW(s->bodies, s->internal->cap_body, s->nbody + 1)) {
    us_error_set(err, US_ERR_NOMEM, "out of memory adding body '%s'", us_id_text(id).s);
    return -1;
  }
  us_Body *b = &s->bodies[s->nbody];
  memset(b, 0, sizeof *b);
  b->id = us_strdup(id);
  int r = b->id ? index_id(s, s->nbody) : -2;
  if (r < 0) {
    us_free(b->id);
    if (r == -1) us_error_set(err, US_ERR_INPUT, "duplicate body id '%s'", us_id_text(id).s);
    else us_error_set(err, US_ERR_NOMEM, "out of memory adding body '%s'", us_id_text(id).s);
    return -1;
  }
  b->friction = -1.0;
  s->internal->finalized = 0;
  return s->nbody++;
}

us_BodyDef us_default_body_def(void) {
  us_BodyDef d;
  memset(&d, 0, sizeof d);
  d.density = 1.0;
  d.friction = -1.0;
  return d;
}

/* The material fields every body takes from its definition. */
static void set_material(us_Body *b, const us_BodyDef *def) {
  b->density = def->density > 0 ? def->density : 1.0;
  b->mass = def->mass;
  b->mass_given = def->mass > 0;
  b->fixed = def->fixed != 0;
  b->friction = def->friction;
}

/* A 3D body: its parts' points copied (the hulls are built by finalize). */
static int add_solid(us_Structure *s, const us_BodyDef *def, us_Error *err) {
  us_Polyhedron *parts = NULL;
  int np = 0;
  if (us_solid_parts_from_def(def, &parts, &np, err)) return -1;
  int i = add_body(s, def->id, err);
  if (i < 0) {
    for (int k = 0; k < np; k++) us_polyhedron_free(&parts[k]);
    us_free(parts);
    return -1;
  }
  us_Body *b = &s->bodies[i];
  b->parts = parts;
  b->npart = np;
  set_material(b, def);
  return i;
}

int us_structure_add_body(us_Structure *s, const us_BodyDef *def, us_Error *err) {
  if (s->dim == 3 || def->xyz || def->npart) {
    if (s->dim != 3 || def->xy) {
      us_error_set(err, US_ERR_INPUT, "body '%s': %s", us_id_text(def->id ? def->id : "?").s,
                   s->dim == 3 ? "a polygon (xy) in a 3D structure: give xyz or parts"
                               : "points in 3D (xyz or parts) in a 2D structure");
      return -1;
    }
    return add_solid(s, def, err);
  }
  const char *id = def->id;
  int nvert = def->nvert;
  if (nvert < 0 || (nvert > 0 && !def->xy)) {
    us_error_set(err, US_ERR_INPUT, "body '%s': bad polygon", us_id_text(id ? id : "?").s);
    return -1;
  }
  double *v = us_malloc((size_t)(nvert > 0 ? nvert : 1) * 2 * sizeof(double));
  if (!v) {
    us_error_set(err, US_ERR_NOMEM, "out of memory adding body '%s'", us_id_text(id ? id : "?").s);
    return -1;
  }
  int i = add_body(s, id, err);
  if (i < 0) {
    us_free(v);
    return -1;
  }
  us_Body *b = &s->bodies[i];
  if (nvert > 0) memcpy(v, def->xy, (size_t)nvert * 2 * sizeof(double));
  b->verts = v;
  b->nvert = nvert;
  set_material(b, def);
  return i;
}

int us_structure_add_polygon(us_Structure *s, const char *id, int nvert, const double *xy,
                             double density, double mass, int fixed, double friction,
                             us_Error *err) {
  us_BodyDef d = us_default_body_def();
  d.id = id, d.nvert = nvert, d.xy = xy, d.density = density, d.mass = mass;
  d.fixed = fixed, d.friction = friction;
  return us_structure_add_body(s, &d, err);
}

int us_structure_add_point_body(us_Structure *s, const char *id, double mass,
                                const double *center, int fixed, us_Error *err) {
  int i = add_body(s, id, err);
  if (i < 0) return -1;
  us_Body *b = &s->bodies[i];
  b->mass = mass;
  b->mass_given = 1;
  b->fixed = fixed != 0;
  b->density = 1.0;
  b->com[0] = center[0];
  b->com[1] = center[1];
  b->com[2] = s->dim == 3 ? center[2] : 0.0;
  b->inertia = 0.0; /* derived in finalize when not given */
  return i;
}

double us_structure_pair_friction(const us_Structure *s, int a, int b) {
  double fa = (a >= 0 && s->bodies[a].friction >= 0) ? s->bodies[a].friction : s->friction;
  double fb = (b >= 0 && s->bodies[b].friction >= 0) ? s->bodies[b].friction : s->friction;
  return fa < fb ? fa : fb;
}

void us_contact_frame(int dim, us_Contact *c) {
  if (dim == 2) {
    c->t[0][0] = -c->n[1];
    c->t[0][1] = c->n[0];
    c->t[0][2] = 0.0;
    memset(c->t[1], 0, sizeof c->t[1]);
    return;
  }
  /* 3D: t1 orthogonal to n from its smallest component, t2 = n x t1 */
  us_Vec3 t1, t2;
  us_v3_frame(us_v3(c->n[0], c->n[1], c->n[2]), &t1, &t2);
  c->t[0][0] = t1.x, c->t[0][1] = t1.y, c->t[0][2] = t1.z;
  c->t[1][0] = t2.x, c->t[1][1] = t2.y, c->t[1][2] = t2.z;
}

/* Contact c from its sides, point, normal (of length len > 0) and mu;
 * p and n may point into c itself. */
static void set_contact(const us_Structure *s, us_Contact *c, int a, int b, const double *p,
                        const double *n, double len, double mu) {
  double pp[3] = {0, 0, 0}, nn[3] = {0, 0, 0};
  for (int j = 0; j < s->dim; j++) pp[j] = p[j], nn[j] = n[j] / len;
  memset(c, 0, sizeof *c);
  c->a = a;
  c->b = b;
  memcpy(c->p, pp, sizeof pp);
  memcpy(c->n, nn, sizeof nn);
  us_contact_frame(s->dim, c);
  c->mu = mu >= 0 ? mu : us_structure_pair_friction(s, a, b);
}

int us_structure_add_contact(us_Structure *s, int a, int b, const double *p, const double *n,
                             double mu, us_Error *err) {
  if (a < US_GROUND || a >= s->nbody || b < 0 || b >= s->nbody || a == b) {
    us_error_set(err, US_ERR_INPUT, "contact %d: bad body pair (%d, %d)", s->ncontact, a, b);
    return -1;
  }
  int dim = s->dim;
  double len = 0.0;
  for (int j = 0; j < dim; j++) len += n[j] * n[j];
  len = sqrt(len);
  if (!(len > 1e-12) || !isfinite(len)) {
    us_error_set(err, US_ERR_INPUT, "contact %d (%s, %s): zero or non-finite normal",
                 s->ncontact, a < 0 ? "ground" : us_id_text(s->bodies[a].id).s,
                 us_id_text(s->bodies[b].id).s);
    return -1;
  }
  if (US_GROW(s->contacts, s->internal->cap_contact, s->ncontact + 1)) {
    us_error_set(err, US_ERR_NOMEM, "out of memory adding a contact");
    return -1;
  }
  set_contact(s, &s->contacts[s->ncontact], a, b, p, n, len, mu);
  return s->ncontact++;
}

int us_structure_movable_set(const us_Structure *s, us_Bitset *out) {
  if (us_bitset_init(out, s->nbody)) return -1;
  for (int i = 0; i < s->nbody; i++)
    if (!s->bodies[i].fixed) us_bitset_set(out, i);
  return 0;
}

static void bbox_add(double *bb, double x, double y) {
  if (x < bb[0]) bb[0] = x;
  if (y < bb[1]) bb[1] = y;
  if (x > bb[2]) bb[2] = x;
  if (y > bb[3]) bb[3] = y;
}

static void bbox3_add(double *bb, const double *p) {
  for (int d = 0; d < 3; d++) {
    if (p[d] < bb[d]) bb[d] = p[d];
    if (p[d] > bb[d + 3]) bb[d + 3] = p[d];
  }
}

/* The 3D box of every part, point body centre and contact point. */
static void measure3(const us_Structure *s, double bb[6]) {
  for (int d = 0; d < 3; d++) bb[d] = INFINITY, bb[d + 3] = -INFINITY;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    for (int p = 0; p < b->npart; p++)
      for (int k = 0; k < b->parts[p].nvert; k++) bbox3_add(bb, b->parts[p].verts + 3 * k);
    if (b->npart == 0) bbox3_add(bb, b->com);
  }
  for (int k = 0; k < s->ncontact; k++) bbox3_add(bb, s->contacts[k].p);
  if (!(bb[0] <= bb[3])) memset(bb, 0, 6 * sizeof *bb);
}

void us_model_measure(us_Structure *s) {
  double bb[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
  double mass = 0.0;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    for (int k = 0; k < b->nvert; k++) bbox_add(bb, b->verts[2 * k], b->verts[2 * k + 1]);
    if (b->nvert == 0) bbox_add(bb, b->com[0], b->com[1]);
    if (!b->fixed) mass += b->mass;
  }
  for (int k = 0; k < s->ncontact; k++) bbox_add(bb, s->contacts[k].p[0], s->contacts[k].p[1]);
  if (!(bb[0] <= bb[2])) bb[0] = bb[1] = bb[2] = bb[3] = 0.0;
  double b3[6] = {bb[0], bb[1], 0, bb[2], bb[3], 0};
  if (s->dim == 3) measure3(s, b3);
  if (s->dim == 3) bb[0] = b3[0], bb[1] = b3[1], bb[2] = b3[3], bb[3] = b3[4];
  memcpy(s->bbox, bb, sizeof bb);
  memcpy(s->bbox3, b3, sizeof b3);
  double d = s->dim == 3 ? us_bbox3_diameter(b3) : hypot(bb[2] - bb[0], bb[3] - bb[1]);
  s->scale = d > 0 ? d : 1.0;
  double g = us_gravity_norm(s->gravity); /* no overflow: massprops.h */
  s->weight = g * mass > 0 ? g * mass : 1.0;
}

/* Replace the structure's contacts by a detected list, taking over its
 * array (friction rule and tangent basis as us_structure_add_contact
 * gives them; the list is valid, so nothing can fail). */
static void install(us_Structure *s, us_ContactList *l) {
  us_free(s->contacts);
  s->contacts = l->c;
  s->internal->cap_contact = l->cap;
  s->ncontact = l->n;
  s->explicit_contacts = 0;
  for (int k = 0; k < l->n; k++) {
    us_Contact *c = &l->c[k];
    double len = 0.0;
    for (int j = 0; j < s->dim; j++) len += c->n[j] * c->n[j];
    set_contact(s, c, c->a, c->b, c->p, c->n, sqrt(len), -1.0);
  }
  l->c = NULL;
  l->n = l->cap = 0;
  s->contacts_detected = 1;
}

static us_Status detect_until(us_Structure *s, const us_ContactSettings *set, double deadline,
                              us_Error *err) {
  for (int i = 0; i < s->nbody; i++)
    if (s->bodies[i].nvert >= 3) us_poly_make_ccw(s->bodies[i].verts, s->bodies[i].nvert);
  us_ContactSettings own = {s->contact_tol, 0};
  us_ContactList l = {NULL, 0, 0};
  us_Status st = us_detect_contacts_until(s, set ? set : &own, deadline, &l, err);
  if (!st) install(s, &l);
  us_contact_list_free(&l);
  return st;
}

us_Status us_structure_detect_contacts(us_Structure *s, const us_ContactSettings *set,
                                       us_Error *err) {
  return detect_until(s, set, 0.0, err);
}

us_Status us_structure_finalize(us_Structure *s, us_Error *err) {
  return us_structure_finalize_until(s, 0.0, err);
}

us_Status us_structure_finalize_until(us_Structure *s, double deadline, us_Error *err) {
  us_Status st = us_model_validate(s, deadline, err);
  if (st) return st;
  us_model_measure(s); /* scale: the fallback radius of point bodies */
  st = us_model_mass_properties(s, err);
  if (st) return st;
  /* contacts added by the caller are explicit; detected ones are redone,
   * so finalizing again after adding bodies sees the new bodies */
  if (s->ncontact > 0 && !s->contacts_detected) s->explicit_contacts = 1;
  if (!s->explicit_contacts) {
    st = detect_until(s, NULL, deadline, err);
    if (st) return st;
  }
  us_model_measure(s); /* weight, and the bbox with contact points */
  s->internal->finalized = 1;
  return US_OK;
}

int us_structure_is_finalized(const us_Structure *s) { return s && s->internal->finalized; }
