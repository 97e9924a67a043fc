/* Contact detection: the vertex-on-edge contacts of a structure's polygons
 * with each other and with the ground, returned as a list. The structure is
 * only read (us_structure_detect_contacts in model/structure.c installs the
 * list), so detection does not depend on the structure builder.
 *
 * Tolerances follow the bodies involved, never the whole structure: a body's
 * own tolerance is US_GEOM_TOL_REL times its bounding-box diagonal, a pair's
 * is the smaller of the two bodies' own, and a body's contacts with the
 * ground use its own. A tolerance given in the settings (> 0) replaces all
 * of them. So adding a body far away changes no contact, and scaling every
 * coordinate scales every tolerance with it.
 *
 * Steps: ground contacts (every vertex of a movable body with |y| <= its
 * tolerance, normal (0, 1), a = US_GROUND), in body then vertex order; the
 * broad phase (broadphase.c) gives candidate pairs sorted by (i, j), never
 * two fixed bodies; for each pair the overlap check (overlap.c, US_ERR_INPUT
 * naming both bodies) and the vertex-on-edge contacts (pair.c). Polygons
 * must be counter-clockwise (finalize makes them so): a clockwise one is
 * US_ERR_INPUT. Bodies without geometry are ignored. On error the list is
 * left empty. The output order depends only on the input. 3D structures
 * take the same tolerances and broad phase, and their own narrow phase
 * (detect3.c). */
#include "contact.h"

#include "geometry/geometry3.h"

#include <math.h>
#include <string.h>

/* Each body's own tolerance (the settings' when given). */
static double *body_tols(const us_Structure *s, double given) {
  double *tol = us_malloc((size_t)(s->nbody > 0 ? s->nbody : 1) * sizeof *tol);
  if (!tol) return NULL;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    double size = s->dim == 3 ? us_body_diameter(b) : us_poly_diameter(b->verts, b->nvert);
    tol[i] = given > 0 ? given : us_geom_tol(size);
  }
  return tol;
}

static int ground_contacts(const us_Structure *s, const double *tol, us_CandList *out) {
  if (!s->ground) return 0;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    if (b->fixed || b->nvert < 3) continue;
    for (int k = 0; k < b->nvert; k++) {
      us_Vec2 v = us_poly_vertex(b->verts, b->nvert, k);
      if (fabs(v.y) <= tol[i] && us_cand_push(out, US_GROUND, i, v, us_v2(0, 1))) return -1;
    }
  }
  return 0;
}

static us_Status pair_phase(const us_Structure *s, int reference, const double *tol,
                            double deadline, us_CandList *out, us_Error *err) {
  us_BodyPair *pairs = NULL;
  int np = 0, nb = s->nbody > 0 ? s->nbody : 1;
  us_Detect d = {s, reference, tol, us_calloc((size_t)nb, sizeof(us_EdgeGrid)),
                 us_calloc((size_t)nb, 1), {{0}}, {-1, -1}, 0};
  us_Status st = US_OK;
  if (!d.grid || !d.built)
    st = us_error_set(err, US_ERR_NOMEM, "out of memory in contact detection");
  else if (reference)
    st = us_broadphase_all(s, &pairs, &np, err);
  else
    st = us_broadphase(s, tol, &pairs, &np, err);
  for (int k = 0; !st && k < np; k++) {
    int i = pairs[k].i, j = pairs[k].j;
    double t = US_MIN(tol[i], tol[j]);
    if ((k & 1023) == 1023 && us_past(deadline)) st = us_detect_timeout(k, np, err);
    if (!st) st = us_pair_overlap(&d, i, j, t, err);
    if (!st) st = us_pair_contacts(&d, i, j, t, out, err);
  }
  for (int i = 0; d.built && i < s->nbody; i++)
    if (d.built[i]) us_edge_grid_free(&d.grid[i]);
  us_free(d.grid);
  us_free(d.built);
  us_free(pairs);
  return st;
}

static us_Status check_input(const us_Structure *s, us_Error *err) {
  if (s->dim != 2 && s->dim != 3)
    return us_error_set(err, US_ERR_INPUT, "contact detection needs dimension 2 or 3");
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    if (b->nvert >= 3 && us_poly_signed_area(b->verts, b->nvert) < 0)
      return us_error_set(err, US_ERR_INPUT,
                          "body '%s': polygon is clockwise (contact detection needs the "
                          "counter-clockwise order that finalize gives)",
                          us_id_text(b->id).s);
  }
  return US_OK;
}

/* Move the candidates into the caller's list (a, b, p, n; mu = -1). */
static us_Status to_list(const us_CandList *l, us_ContactList *out, us_Error *err) {
  if (US_GROW(out->c, out->cap, l->n > 0 ? l->n : 1))
    return us_error_set(err, US_ERR_NOMEM, "out of memory in contact detection");
  for (int k = 0; k < l->n; k++) {
    us_Contact *c = &out->c[k];
    memset(c, 0, sizeof *c);
    c->a = l->c[k].a;
    c->b = l->c[k].b;
    c->p[0] = l->c[k].p.x;
    c->p[1] = l->c[k].p.y;
    c->n[0] = l->c[k].n.x;
    c->n[1] = l->c[k].n.y;
    c->mu = -1.0;
  }
  out->n = l->n;
  return US_OK;
}

us_Status us_detect_contacts(const us_Structure *s, const us_ContactSettings *set,
                             us_ContactList *out, us_Error *err) {
  return us_detect_contacts_until(s, set, 0.0, out, err);
}

us_Status us_detect_contacts_until(const us_Structure *s, const us_ContactSettings *set,
                                   double deadline, us_ContactList *out, us_Error *err) {
  out->n = 0;
  us_Status st = check_input(s, err);
  if (st) return st;
  double *tol = body_tols(s, set ? set->tol : 0.0);
  if (!tol) return us_error_set(err, US_ERR_NOMEM, "out of memory in contact detection");
  if (s->dim == 3) {
    st = us_detect_contacts3(s, tol, set && set->reference, deadline, out, err);
    us_free(tol);
    return st;
  }
  us_CandList l = {NULL, 0, 0};
  if (ground_contacts(s, tol, &l))
    st = us_error_set(err, US_ERR_NOMEM, "out of memory in contact detection");
  if (!st) st = pair_phase(s, set && set->reference, tol, deadline, &l, err);
  if (!st) st = to_list(&l, out, err);
  us_free(l.c);
  us_free(tol);
  return st;
}

void us_contact_list_free(us_ContactList *l) {
  if (!l) return;
  us_free(l->c);
  l->c = NULL;
  l->n = l->cap = 0;
}
