/* Contact detection: replaces a structure's contacts by the vertex-on-edge
 * contacts of its polygons with each other and with the ground.
 *
 * Steps: polygons are made counter-clockwise in place (as validation
 * does); the tolerance (settings, else 1e-6 * scale, at least 1e-9); ground
 * contacts (every vertex of a movable body with |y| <= tol, normal (0, 1),
 * a = US_GROUND), in body then vertex order; the broad phase (broadphase.c)
 * gives candidate pairs sorted by (i, j), never two fixed bodies; for each
 * pair the overlap check (overlap.c, US_ERR_INPUT naming both bodies) and
 * the vertex-on-edge contacts (pair.c). Contacts are added only when all
 * pairs passed, through us_structure_add_contact so the friction rule
 * applies; on error the structure's contacts are left as they were (except
 * after an out-of-memory while adding, when they are cleared). Bodies
 * without geometry are ignored. The output order depends only on the input. */
#include "contact.h"

#include <math.h>

/* Bounding-box diagonal of all polygons (1 if none). */
static double polygon_scale(const us_Structure *s) {
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    for (int k = 0; k < b->nvert; k++)
      for (int d = 0; d < 2; d++) {
        lo[d] = US_MIN(lo[d], b->verts[2 * k + d]);
        hi[d] = US_MAX(hi[d], b->verts[2 * k + d]);
      }
  }
  double diag = hypot(hi[0] - lo[0], hi[1] - lo[1]);
  return diag > 0 && isfinite(diag) ? diag : 1.0;
}

static int ground_contacts(const us_Structure *s, double tol, us_CandList *out) {
  if (!s->ground) return 0;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    if (b->fixed || b->nvert < 3) continue;
    for (int k = 0; k < b->nvert; k++) {
      us_Vec2 v = us_poly_vertex(b->verts, b->nvert, k);
      if (fabs(v.y) <= tol && us_cand_push(out, US_GROUND, i, v, us_v2(0, 1))) return -1;
    }
  }
  return 0;
}

static us_Status pair_phase(const us_Structure *s, double tol, us_CandList *out, us_Error *err) {
  us_BodyPair *pairs = NULL;
  int np = 0;
  us_Status st = us_broadphase(s, tol, &pairs, &np, err);
  for (int k = 0; !st && k < np; k++) {
    st = us_pair_overlap(s, pairs[k].i, pairs[k].j, tol, err);
    if (!st) st = us_pair_contacts(s, pairs[k].i, pairs[k].j, tol, out, err);
  }
  us_free(pairs);
  return st;
}

static us_Status install(us_Structure *s, const us_CandList *l, us_Error *err) {
  s->ncontact = 0;
  s->explicit_contacts = 0;
  for (int k = 0; k < l->n; k++) {
    const us_Cand *c = &l->c[k];
    double p[3] = {c->p.x, c->p.y, 0.0}, n[3] = {c->n.x, c->n.y, 0.0};
    if (us_structure_add_contact(s, c->a, c->b, p, n, -1.0, err) < 0) {
      s->ncontact = 0;
      return err ? err->code : US_ERR_NOMEM;
    }
  }
  return US_OK;
}

us_Status us_detect_contacts(us_Structure *s, const us_ContactSettings *set, us_Error *err) {
  if (s->dim != 2) return us_error_set(err, US_ERR_INPUT, "contact detection needs dim 2");
  /* outward normals assume counter-clockwise polygons (finalize already
   * made them so; a direct call on a fresh structure may not have) */
  for (int i = 0; i < s->nbody; i++)
    if (s->bodies[i].nvert >= 3) us_poly_make_ccw(s->bodies[i].verts, s->bodies[i].nvert);
  double tol =
      set && set->tol > 0 ? set->tol : us_geom_tol(s->scale > 0 ? s->scale : polygon_scale(s));
  us_CandList l = {NULL, 0, 0};
  us_Status st = US_OK;
  if (ground_contacts(s, tol, &l))
    st = us_error_set(err, US_ERR_NOMEM, "out of memory in contact detection");
  if (!st) st = pair_phase(s, tol, &l, err);
  if (!st) st = install(s, &l, err);
  us_free(l.c);
  return st;
}
