/* The fingerprint of a structure: a 64-bit FNV-1a hash of what determines
 * every stability verdict and plan, so that a plan file can name the
 * structure it was made for (docs/format.md, "Fingerprint").
 *
 * The bytes hashed (a canonical serialisation; nothing of the file's
 * spelling, order of keys, spacing or number format enters): integers as
 * 8-byte little-endian two's complement, doubles as their IEEE-754 binary64
 * bits in 8 little-endian bytes (-0 taken as +0), strings as their length
 * then their bytes. In order: "unstack-fp1", the dimension, gravity (dim
 * components), the default friction, the ground flag, the body count, then
 * per body in file order its id, fixed flag, mass given (1: the mass, 0:
 * the density; a fixed body neither), its own friction (-1 when not given),
 * its geometry, and last, with explicit contacts, each contact's sides
 * (-1 the ground), point, normal (dim components) and coefficient.
 *
 * Geometry: a 2D polygon as its vertex count and vertices, counter-clockwise
 * (as finalize leaves it) starting from the least vertex (x, then y), so the
 * starting vertex and orientation of the file do not matter; a 3D body as
 * its part count and each part's hull vertices sorted (x, then y, then z),
 * which the hull of the same points gives whatever order it builds them
 * in; a body without geometry as its centre. Contact tolerance and the
 * settings of a run are not in it: they are the run's, not the
 * structure's. */
#include "io.h"

#include <stdlib.h>
#include <string.h>

#define FNV_OFFSET 0xcbf29ce484222325ull
#define FNV_PRIME 0x100000001b3ull

static void put_bytes(uint64_t *h, const unsigned char *p, size_t n) {
  for (size_t k = 0; k < n; k++) *h = (*h ^ p[k]) * FNV_PRIME;
}

static void put_u64(uint64_t *h, uint64_t v) {
  unsigned char b[8];
  for (int k = 0; k < 8; k++) b[k] = (unsigned char)(v >> (8 * k));
  put_bytes(h, b, 8);
}

static void put_int(uint64_t *h, long long v) { put_u64(h, (uint64_t)v); }

static void put_double(uint64_t *h, double x) {
  uint64_t bits;
  if (x == 0.0) x = 0.0; /* -0 as +0 */
  memcpy(&bits, &x, sizeof bits);
  put_u64(h, bits);
}

static void put_str(uint64_t *h, const char *s) {
  size_t n = s ? strlen(s) : 0;
  put_u64(h, (uint64_t)n);
  put_bytes(h, (const unsigned char *)s, n);
}

/* qsort order of points: by x, then y, then z. */
static int cmp3(const void *pa, const void *pb) {
  const double *a = pa, *b = pb;
  for (int d = 0; d < 3; d++)
    if (a[d] != b[d]) return a[d] < b[d] ? -1 : 1;
  return 0;
}

/* A polygon from its least vertex, in its (counter-clockwise) order. */
static void put_polygon(uint64_t *h, const us_Body *b) {
  int first = 0;
  for (int k = 1; k < b->nvert; k++) {
    const double *p = b->verts + 2 * k, *q = b->verts + 2 * first;
    if (p[0] < q[0] || (p[0] == q[0] && p[1] < q[1])) first = k;
  }
  put_int(h, b->nvert);
  for (int k = 0; k < b->nvert; k++) {
    const double *p = b->verts + 2 * ((first + k) % b->nvert);
    put_double(h, p[0]);
    put_double(h, p[1]);
  }
}

/* One part's hull vertices, sorted; 0 on out of memory. */
static int put_part(uint64_t *h, const us_Polyhedron *p) {
  double *v = us_malloc(((size_t)p->nvert * 3 + 1) * sizeof *v);
  if (!v) return 0;
  memcpy(v, p->verts, (size_t)p->nvert * 3 * sizeof *v);
  qsort(v, (size_t)p->nvert, 3 * sizeof *v, cmp3);
  put_int(h, p->nvert);
  for (int k = 0; k < 3 * p->nvert; k++) put_double(h, v[k]);
  us_free(v);
  return 1;
}

/* A body's geometry (see the file head); 0 on out of memory. */
static int put_geometry(uint64_t *h, const us_Structure *s, const us_Body *b) {
  if (s->dim == 2 && b->nvert > 0) return put_polygon(h, b), 1;
  if (s->dim == 3 && b->npart > 0) {
    put_int(h, b->npart);
    for (int k = 0; k < b->npart; k++)
      if (!put_part(h, &b->parts[k])) return 0;
    return 1;
  }
  put_int(h, 0);
  for (int d = 0; d < s->dim; d++) put_double(h, b->com[d]);
  return 1;
}

static int put_body(uint64_t *h, const us_Structure *s, const us_Body *b) {
  put_str(h, b->id);
  put_int(h, b->fixed != 0);
  if (!b->fixed) {
    put_int(h, b->mass_given != 0);
    put_double(h, b->mass_given ? b->mass : b->density);
  }
  put_double(h, b->friction < 0 ? -1.0 : b->friction);
  return put_geometry(h, s, b);
}

static void put_contact(uint64_t *h, const us_Structure *s, const us_Contact *c) {
  put_int(h, c->a == US_GROUND ? -1 : c->a);
  put_int(h, c->b);
  for (int d = 0; d < s->dim; d++) put_double(h, c->p[d]);
  for (int d = 0; d < s->dim; d++) put_double(h, c->n[d]);
  put_double(h, c->mu);
}

us_Status us_structure_fingerprint(const us_Structure *s, uint64_t *out, us_Error *err) {
  if (!s || !out) return us_error_set(err, US_ERR_USAGE, "fingerprint: missing argument");
  uint64_t h = FNV_OFFSET;
  put_str(&h, "unstack-fp1");
  put_int(&h, s->dim);
  for (int d = 0; d < s->dim; d++) put_double(&h, s->gravity[d]);
  put_double(&h, s->friction);
  put_int(&h, s->ground != 0);
  put_int(&h, s->nbody);
  for (int i = 0; i < s->nbody; i++)
    if (!put_body(&h, s, &s->bodies[i]))
      return us_error_set(err, US_ERR_NOMEM, "fingerprint: out of memory");
  put_int(&h, s->explicit_contacts ? s->ncontact : -1);
  for (int c = 0; s->explicit_contacts && c < s->ncontact; c++)
    put_contact(&h, s, &s->contacts[c]);
  *out = h;
  return US_OK;
}

void us_fingerprint_text(uint64_t fp, char out[US_FINGERPRINT_CHARS]) {
  snprintf(out, US_FINGERPRINT_CHARS, "fnv1a64:%016llx", (unsigned long long)fp);
}
