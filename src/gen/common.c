/* Generator settings (defaults and checks) and the small building steps
 * every generator shares: start a structure, add numbered blocks, seal it.
 *
 * Every generator returns a finalized structure (validated, mass
 * properties, detected contacts) whose bodies are all movable and named
 * "b1", "b2", ... in the generator's documented order; the structure's
 * default friction is g->friction and every block has density g->density.
 * Bad settings are US_ERR_USAGE with a message naming the generator and the
 * setting; nothing is allocated when they are rejected. The random
 * generators draw from one splitmix64 stream seeded with g->seed. */
#include "gen.h"
#include "stability/stability.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

us_GenSettings us_gen_default_settings(void) {
  us_GenSettings g;
  memset(&g, 0, sizeof g); /* every field not named below is 0 */
  g.n = 10;
  g.rows = 10;
  g.cols = 10;
  g.width = 1.0;
  g.height = 0.5;
  g.radius = 3.0;
  g.thickness = 0.5;
  g.friction = 0.5;
  g.density = 1.0;
  g.seed = 1;
  g.max_tries = 10000;
  g.depth = 1.0;
  g.jitter = 0.0;
  g.segments = 12;
  g.oculus = 15.0;
  g.chamfer = 0.02;
  return g;
}

us_Status us_gen_check_positive(double v, const char *what, const char *name, us_Error *err) {
  if (!(v > 0) || !isfinite(v))
    return us_error_set(err, US_ERR_USAGE, "%s: %s must be a positive number, got %g", what, name,
                        v);
  return US_OK;
}

us_Status us_gen_check_common(const us_GenSettings *g, const char *what, us_Error *err) {
  if (!g) return us_error_set(err, US_ERR_USAGE, "%s: no settings given", what);
  if (!(g->friction >= 0)) /* INFINITY allowed: no sliding */
    return us_error_set(err, US_ERR_USAGE, "%s: friction must be >= 0 or infinite, got %g", what,
                        g->friction);
  return us_gen_check_positive(g->density, what, "density", err);
}

us_Structure *us_gen_begin(const us_GenSettings *g, us_Error *err) {
  return us_gen_begin_dim(g, 2, err);
}

us_Structure *us_gen_begin_dim(const us_GenSettings *g, int dim, us_Error *err) {
  us_Structure *s = us_structure_new(dim);
  if (!s) {
    us_error_set(err, US_ERR_NOMEM, "out of memory creating a structure");
    return NULL;
  }
  s->friction = g->friction;
  s->ground = 1;
  return s;
}

us_Status us_gen_add(us_Structure *s, const us_GenSettings *g, int k, int nvert,
                     const double *xy, us_Error *err) {
  char id[24];
  us_Error local;
  snprintf(id, sizeof id, "b%d", k + 1);
  if (!err) err = &local; /* callers may pass NULL; we still need the code */
  us_BodyDef d = us_default_body_def();
  d.id = id;
  d.nvert = nvert;
  d.xy = xy;
  d.density = g->density;
  if (us_structure_add_body(s, &d, err) < 0)
    return err->code;
  return US_OK;
}

us_Status us_gen_add_box(us_Structure *s, const us_GenSettings *g, int k, double x0, double y0,
                         double x1, double y1, us_Error *err) {
  double xy[8] = {x0, y0, x1, y0, x1, y1, x0, y1};
  return us_gen_add(s, g, k, 4, xy, err);
}

us_Status us_gen_add_solid(us_Structure *s, const us_GenSettings *g, int k, int n,
                           const double *xyz, us_Error *err) {
  char id[24];
  us_Error local;
  snprintf(id, sizeof id, "b%d", k + 1);
  if (!err) err = &local;
  us_BodyDef d = us_default_body_def();
  d.id = id;
  d.nvert = n;
  d.xyz = xyz;
  d.density = g->density;
  return us_structure_add_body(s, &d, err) < 0 ? err->code : US_OK;
}

us_Status us_gen_add_prism(us_Structure *s, const us_GenSettings *g, int k, const double *xy,
                           double z0, double z1, us_Error *err) {
  double p[24];
  for (int c = 0; c < 8; c++) {
    p[3 * c] = xy[2 * (c % 4)];
    p[3 * c + 1] = xy[2 * (c % 4) + 1];
    p[3 * c + 2] = c < 4 ? z0 : z1;
  }
  return us_gen_add_solid(s, g, k, 8, p, err);
}

us_Status us_gen_add_box3(us_Structure *s, const us_GenSettings *g, int k, double x0, double y0,
                          double z0, double x1, double y1, double z1, us_Error *err) {
  double xy[8] = {x0, y0, x1, y0, x1, y1, x0, y1};
  return us_gen_add_prism(s, g, k, xy, z0, z1, err);
}

us_Structure *us_gen_finish(us_Structure *s, const us_GenSettings *g, us_Error *err) {
  if (us_structure_finalize_until(s, g->deadline, err) != US_OK) {
    us_structure_free(s);
    return NULL;
  }
  return s;
}


us_Status us_gen_stands(const us_Structure *s, int *stable, us_Error *err) {
  us_StabilitySettings set = us_stability_default_settings();
  us_Stability *w = us_stability_new(s, &set, err);
  if (!w) return err->code;
  us_StabilityResult res;
  us_stability_result_init(&res);
  us_Status st = us_stability_test_full(w, &res, err);
  *stable = !st && res.verdict == US_STABLE;
  us_stability_result_free(&res);
  us_stability_free(w);
  return st;
}

/* Checks shared by the block generators: common settings, block size, a
 * positive count `n` named `nname`, and a total below the body limit. */
us_Status us_gen_check_blocks(const us_GenSettings *g, const char *what, int n, const char *nname,
                              long total, us_Error *err) {
  us_Status st = us_gen_check_common(g, what, err);
  if (!st) st = us_gen_check_positive(g->width, what, "block width", err);
  if (!st) st = us_gen_check_positive(g->height, what, "block height", err);
  if (!st && n < 1) st = us_error_set(err, US_ERR_USAGE, "%s: %s must be >= 1, got %d", what, nname, n);
  if (!st && total > US_GEN_MAX_BODIES)
    st = us_error_set(err, US_ERR_USAGE, "%s: %ld blocks is more than the limit of %ld", what,
                      total, US_GEN_MAX_BODIES);
  return st;
}

/* ------------------------------------------------------ carried forces */

/* The order of carried contacts: bodies, point, normal, tangents. */
static int contact_cmp(const us_Contact *x, const us_Contact *y) {
  if (x->a != y->a) return x->a < y->a ? -1 : 1;
  if (x->b != y->b) return x->b < y->b ? -1 : 1;
  const double *u[4] = {x->p, x->n, x->t[0], x->t[1]}, *v[4] = {y->p, y->n, y->t[0], y->t[1]};
  for (int a = 0; a < 4; a++)
    for (int k = 0; k < 3; k++)
      if (u[a][k] != v[a][k]) return u[a][k] < v[a][k] ? -1 : 1;
  return 0;
}

typedef struct Slot {
  us_Contact c;
  int idx;
} Slot;

static int slot_qcmp(const void *x, const void *y) {
  const Slot *a = x, *b = y;
  int r = contact_cmp(&a->c, &b->c);
  return r ? r : (a->idx > b->idx) - (a->idx < b->idx);
}

void us_gen_carry_free(us_GenCarry *k) {
  us_free(k->c);
  us_free(k->f);
  us_free(k->body);
  memset(k, 0, sizeof *k);
}

us_Status us_gen_carry_keep(us_GenCarry *k, const us_Structure *s, const us_Bitset *present,
                            const us_Forces *f, us_Error *err) {
  size_t dim = (size_t)s->dim, n = (size_t)(f->ncontact > 0 ? f->ncontact : 1);
  us_Contact *c = us_realloc(k->c, n * sizeof *c);
  if (c) k->c = c;
  double *fv = c ? us_realloc(k->f, n * dim * sizeof *fv) : NULL;
  if (fv) k->f = fv;
  int *body = fv ? us_realloc(k->body, (size_t)(s->nbody > 0 ? s->nbody : 1) * sizeof *body) : NULL;
  if (body) k->body = body;
  if (!body) return us_error_set(err, US_ERR_NOMEM, "generator: out of memory keeping forces");
  /* sorted with their forces: sort indices by contact, then gather */
  Slot *sl = us_malloc(n * sizeof *sl);
  if (!sl) return us_error_set(err, US_ERR_NOMEM, "generator: out of memory keeping forces");
  for (int j = 0; j < f->ncontact; j++) sl[j].c = s->contacts[f->contact[j]], sl[j].idx = j;
  qsort(sl, (size_t)f->ncontact, sizeof *sl, slot_qcmp);
  for (int j = 0; j < f->ncontact; j++) {
    k->c[j] = sl[j].c;
    memcpy(k->f + (size_t)j * dim, f->f + (size_t)sl[j].idx * dim, dim * sizeof(double));
  }
  us_free(sl);
  k->n = f->ncontact;
  k->dim = s->dim;
  k->nbody = 0;
  for (int i = 0; i < s->nbody; i++)
    if (us_bitset_get(present, i)) k->body[k->nbody++] = i;
  return US_OK;
}

us_Status us_gen_carry_seed(const us_GenCarry *k, const us_Structure *s, us_Stability *w,
                            us_Bitset *present, int *taken, us_Error *err) {
  *taken = 0;
  if (!k->body || k->dim != s->dim) return US_OK;
  for (int q = 0; q < k->nbody; q++)
    if (k->body[q] >= s->nbody) return US_OK; /* a stage that is gone */
  size_t nc = (size_t)(s->ncontact > 0 ? s->ncontact : 1), dim = (size_t)s->dim;
  Slot *sl = us_malloc(nc * sizeof *sl);
  us_Forces f = {0, s->ncontact, us_malloc(nc * sizeof(int)), us_malloc(nc * dim * sizeof(double))};
  us_Status st = sl && f.contact && f.f ? US_OK
                                        : us_error_set(err, US_ERR_NOMEM, "generator: out of memory carrying forces");
  int matched = 0;
  if (!st) { /* s's contacts sorted the same way, merged with the kept ones */
    for (int c = 0; c < s->ncontact; c++) sl[c].c = s->contacts[c], sl[c].idx = c;
    qsort(sl, (size_t)s->ncontact, sizeof *sl, slot_qcmp);
    int c = 0;
    for (int j = 0; j < k->n; j++) {
      while (c < s->ncontact && contact_cmp(&sl[c].c, &k->c[j]) < 0) c++;
      if (c == s->ncontact || contact_cmp(&sl[c].c, &k->c[j]) != 0) break;
      f.contact[f.ncontact] = sl[c].idx;
      memcpy(f.f + (size_t)f.ncontact++ * dim, k->f + (size_t)j * dim, dim * sizeof(double));
      c++;
      matched++;
    }
  }
  if (!st && matched == k->n) {
    memset(present->w, 0, (size_t)present->nwords * sizeof(uint64_t));
    for (int q = 0; q < k->nbody; q++) us_bitset_set(present, k->body[q]);
    st = us_stability_seed(w, present, &f, taken, err);
  }
  us_free(sl);
  us_forces_free(&f);
  return st;
}
