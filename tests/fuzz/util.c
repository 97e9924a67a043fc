/* Helpers shared by the fuzz targets: findings, a private temporary
 * directory, the size caps, and the field-by-field comparison of two
 * structures used by the write/read-back round trip.
 *
 * Comparison is exact (==, so 0 and -0 are equal): the writer prints every
 * number in a form that reads back to the same double, so a structure
 * read back from its own file must have the same bodies, vertices,
 * masses, centres, inertias, materials and contacts bit for bit. Density
 * is compared only when it is what defines the mass (a given mass makes it
 * irrelevant and the writer drops it). */
#define _POSIX_C_SOURCE 200809L
#include "fuzz.h"

#include <dirent.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

void fz_finding(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fputs("finding: ", stderr);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  fflush(stderr);
  abort();
}

char *fz_text(const uint8_t *data, size_t size) {
  char *t = malloc(size + 1);
  if (!t) abort();
  if (size) memcpy(t, data, size);
  t[size] = 0;
  return t;
}

/* ------------------------------------------------------------- temp files */

static char tmpdir[256];

static void remove_tmpdir(void) {
  DIR *d = opendir(tmpdir);
  if (!d) return;
  struct dirent *e;
  char p[600];
  while ((e = readdir(d)) != NULL) {
    if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
    snprintf(p, sizeof p, "%s/%s", tmpdir, e->d_name);
    unlink(p);
  }
  closedir(d);
  rmdir(tmpdir);
}

static void make_tmpdir(void) {
  const char *base = getenv("TMPDIR");
  snprintf(tmpdir, sizeof tmpdir, "%s/us-fuzz-XXXXXX", base && *base ? base : "/tmp");
  if (!mkdtemp(tmpdir)) {
    perror("mkdtemp");
    abort();
  }
  atexit(remove_tmpdir);
}

const char *fz_path(int slot, const char *name) {
  static char paths[4][300];
  if (!tmpdir[0]) make_tmpdir();
  snprintf(paths[slot & 3], sizeof paths[0], "%s/%s", tmpdir, name);
  return paths[slot & 3];
}

char *fz_slurp(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  size_t cap = 4096, n = 0;
  char *b = malloc(cap + 1);
  size_t got;
  while (b && (got = fread(b + n, 1, cap - n, f)) > 0) {
    n += got;
    if (n == cap) {
      char *nb = realloc(b, 2 * cap + 1);
      if (!nb) free(b);
      b = nb;
      cap *= 2;
    }
  }
  fclose(f);
  if (!b) return NULL;
  b[n] = 0;
  *len = n;
  return b;
}

/* ------------------------------------------------------------------ caps */

int fz_small(const us_Structure *s) {
  if (s->nbody > FZ_MAX_BODIES) return 0;
  long nv = 0;
  for (int i = 0; i < s->nbody; i++) {
    nv += s->bodies[i].nvert;
    for (int k = 0; k < s->bodies[i].npart; k++) nv += s->bodies[i].parts[k].nvert;
  }
  return nv <= FZ_MAX_VERTS;
}

/* ------------------------------------------------------------- comparison */

static char diff_msg[512];

static int differ(const double *a, const double *b, int n) {
  for (int k = 0; k < n; k++)
    if (!(a[k] == b[k]) && !(a[k] != a[k] && b[k] != b[k])) return 1;
  return 0;
}

/* 3D parts: the same hulls (vertices bit for bit, face count). */
static const char *parts_diff(const us_Body *a, const us_Body *b) {
  if (a->npart != b->npart) return "part count";
  for (int k = 0; k < a->npart; k++) {
    const us_Polyhedron *p = &a->parts[k], *q = &b->parts[k];
    if (p->nvert != q->nvert || p->nface != q->nface) return "part hull size";
    if (differ(p->verts, q->verts, 3 * p->nvert)) return "part vertices";
  }
  for (int r = 0; r < 3; r++)
    if (differ(a->inertia3[r], b->inertia3[r], 3)) return "inertia tensor";
  return NULL;
}

static const char *body_diff(const us_Body *a, const us_Body *b) {
  if (strcmp(a->id, b->id)) return "id";
  if (a->nvert != b->nvert) return "vertex count";
  if (differ(a->verts, b->verts, 2 * a->nvert)) return "vertices";
  const char *d = parts_diff(a, b);
  if (d) return d;
  if (a->fixed != b->fixed) return "fixed";
  if (a->mass_given != b->mass_given) return "mass given";
  if (differ(&a->mass, &b->mass, 1)) return "mass";
  if (!a->mass_given && (a->nvert > 0 || a->npart > 0) && differ(&a->density, &b->density, 1))
    return "density";
  if (differ(a->com, b->com, 3)) return "centre of mass";
  if (differ(&a->inertia, &b->inertia, 1)) return "inertia";
  if (differ(&a->friction, &b->friction, 1)) return "friction";
  return NULL;
}

static const char *contact_diff(const us_Contact *a, const us_Contact *b) {
  if (a->a != b->a || a->b != b->b) return "bodies";
  if (differ(a->p, b->p, 3)) return "point";
  if (differ(a->n, b->n, 3)) return "normal";
  if (differ(a->t[0], b->t[0], 3) || differ(a->t[1], b->t[1], 3)) return "tangents";
  if (differ(&a->mu, &b->mu, 1)) return "friction";
  return NULL;
}

static const char *globals_diff(const us_Structure *a, const us_Structure *b) {
  if (a->dim != b->dim) return "dimension";
  if (differ(a->gravity, b->gravity, 3)) return "gravity";
  if (differ(&a->friction, &b->friction, 1)) return "friction";
  if (a->ground != b->ground) return "ground";
  if (a->nbody != b->nbody) return "body count";
  if (a->explicit_contacts != b->explicit_contacts) return "explicit contacts";
  if (differ(&a->contact_tol, &b->contact_tol, 1)) return "contact tolerance";
  if (a->ncontact != b->ncontact) return "contact count";
  return NULL;
}

const char *fz_structure_diff(const us_Structure *a, const us_Structure *b) {
  const char *d = globals_diff(a, b);
  if (d) {
    snprintf(diff_msg, sizeof diff_msg, "%s (contacts %d vs %d)", d, a->ncontact, b->ncontact);
    return diff_msg;
  }
  for (int i = 0; i < a->nbody; i++)
    if ((d = body_diff(&a->bodies[i], &b->bodies[i])) != NULL) {
      snprintf(diff_msg, sizeof diff_msg, "body %d (%.40s): %s", i, a->bodies[i].id, d);
      return diff_msg;
    }
  for (int c = 0; c < a->ncontact; c++)
    if ((d = contact_diff(&a->contacts[c], &b->contacts[c])) != NULL) {
      snprintf(diff_msg, sizeof diff_msg, "contact %d: %s", c, d);
      return diff_msg;
    }
  return NULL;
}

void fz_check_error(const char *what, us_Status st, const us_Error *err) {
  if (st == US_OK) return;
  if (st < 0 || st >= US_ERR_COUNT) fz_finding("%s: status %d out of range", what, (int)st);
  if (err->code != st)
    fz_finding("%s: returned %s but the error says %s", what, us_status_name(st),
               us_status_name(err->code));
  if (!err->msg[0]) fz_finding("%s: %s without a message", what, us_status_name(st));
}
