/* Meshes -> a 3D structure (docs/mesh.md): the checks and the bodies of
 * the mesh import, on the neutral document of io/mesh.h.
 *
 * Per object, in this order: every coordinate finite; vertices welded
 * (equal coordinates, exactly: files repeat a vertex by value, STL
 * always); a face's repeated corners dropped, and a face with fewer than
 * 3 corners left, or an area <= 1e-12 x its longest edge squared, is
 * degenerate; then shells. Faces that share an edge belong to one shell
 * when the edge has exactly two faces; an odd number is an open mesh.
 * Where closed shells touch (stacked blocks in one STL share corners,
 * edges and whole faces) an edge has 4, 6, ... faces; they are paired
 * about the edge (pair_radially): with faces wound outward, going round
 * the edge, every face that runs against the edge's direction opens a
 * solid's wedge and the next face closes it. Coincident faces (two
 * blocks' shared face, seen from both) are ordered so that the empty
 * wedge lies between them. So touching shells need outward winding, as
 * every exporter writes it; a shell that touches nothing may be wound
 * any way.
 *
 * Then per shell, with the shell's own tolerance (tol = 1e-6 x its
 * bounding-box diagonal plus 4 float ulps of its largest coordinate:
 * Assimp keeps coordinates as floats), convexity: with each face's plane
 * turned so that the shell's vertex centroid is behind it, the face's
 * own corners within tol of it (a bent polygon has no plane), no vertex
 * of the shell more than tol in front, and the centroid more than tol
 * behind (O(vertices x faces) per shell; the centroid of a convex solid's
 * vertices is inside it, so a convex shell passes whatever its winding).
 *
 * Bodies: a named object is one body, its shells the parts of a compound
 * when there are several; an unnamed object (STL, PLY, OFF) gives one body
 * per shell. Coordinates are turned (--up y: (x, y, z) -> (x, -z, y), a
 * quarter turn about x that takes y to z), scaled, and with a ground
 * shifted so the lowest point is at z = 0. Ids: bytes that are not
 * printable UTF-8 (controls, space, malformed sequences) become '_', an
 * empty name the file's stem, an unnamed object's shells NAME-1, NAME-2,
 * ..., and a repeat of a taken id (or "ground") NAME-2, NAME-3, ... */
#include "mesh.h"

#include "geometry/geometry.h"
#include "io.h"

#include <float.h>
#include <fnmatch.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DEGENERATE_REL 1e-12
#define FLOAT_ULPS 4.0
#define PI 3.14159265358979323846
#define RADIAL_TIE 1e-9 /* radians: faces this close about an edge lie on each other */
#define CLOCK_EVERY 1024 /* faces between two reads of the clock */

us_MeshSettings us_mesh_default_settings(void) {
  us_MeshSettings s;
  memset(&s, 0, sizeof s);
  s.up = 'z';
  s.scale = 1;
  s.friction = -1;
  s.density = 1;
  s.ground = 1;
  return s;
}

/* One object's welded vertices, cleaned faces and shells. */
typedef struct Work {
  const us_MeshDoc *doc;
  const us_MeshObject *obj;
  const us_MeshSettings *set;
  us_Error *err;
  int nv;          /* welded vertices */
  double *p;       /* 3 * nv, file coordinates */
  int *fstart;     /* cleaned faces: obj->nface + 1 */
  int *fidx;
  int nshell;
  int *fshell;     /* shell of each face */
  int *sstart;     /* shell k's vertices: sv[sstart[k] .. sstart[k + 1]) */
  int *sv;
} Work;

static void work_free(Work *w) {
  us_free(w->p), us_free(w->fstart), us_free(w->fidx);
  us_free(w->fshell), us_free(w->sstart), us_free(w->sv);
}

static us_Status nomem(Work *w) {
  return us_error_set(w->err, US_ERR_NOMEM, "%s: out of memory", w->doc->name);
}

/* "FILE: object 'NAME'" (or "a mesh without a name") into buf. */
static void where(const Work *w, char *buf, size_t cap) {
  if (w->obj->name[0]) snprintf(buf, cap, "%s: object '%s'", w->doc->name, us_id_text(w->obj->name).s);
  else snprintf(buf, cap, "%s: a mesh without a name", w->doc->name);
}

static us_Status bad(const Work *w, const char *what) {
  char at[300];
  where(w, at, sizeof at);
  return us_error_set(w->err, US_ERR_INPUT, "%s: %s", at, what);
}

/* ---------------------------------------------------------------- weld */

typedef struct Key {
  double x, y, z;
  int i;
} Key;

static int pos_cmp(const Key *p, const Key *q) {
  if (p->x != q->x) return p->x < q->x ? -1 : 1;
  if (p->y != q->y) return p->y < q->y ? -1 : 1;
  if (p->z != q->z) return p->z < q->z ? -1 : 1;
  return 0;
}

static int key_cmp(const void *a, const void *b) {
  const Key *p = a, *q = b;
  int c = pos_cmp(p, q);
  return c ? c : (p->i > q->i) - (p->i < q->i);
}

static us_Status check_finite(Work *w) {
  const us_MeshObject *o = w->obj;
  for (int k = 0; k < 3 * o->nvert; k++)
    if (!isfinite(o->xyz[k])) {
      char m[160];
      snprintf(m, sizeof m, "vertex %d has a non-finite coordinate (%g)", k / 3 + 1, o->xyz[k]);
      return bad(w, m);
    }
  return US_OK;
}

/* Equal positions become one vertex, numbered in order of first use:
 * sorted, each run's first index is its representative. */
static us_Status weld(Work *w, int *map) {
  const us_MeshObject *o = w->obj;
  int n = o->nvert;
  Key *keys = us_malloc((size_t)(n + 1) * sizeof *keys);
  int *rep = us_malloc((size_t)(n + 1) * sizeof *rep);
  w->p = us_malloc((size_t)(3 * n + 3) * sizeof *w->p);
  if (!keys || !rep || !w->p) return us_free(keys), us_free(rep), nomem(w);
  for (int i = 0; i < n; i++)
    keys[i] = (Key){o->xyz[3 * i], o->xyz[3 * i + 1], o->xyz[3 * i + 2], i};
  qsort(keys, (size_t)n, sizeof *keys, key_cmp);
  for (int k = 0, first = 0; k < n; k++) { /* a run's first has the smallest index */
    if (k == 0 || pos_cmp(&keys[k], &keys[k - 1])) first = keys[k].i;
    rep[keys[k].i] = first;
  }
  w->nv = 0;
  for (int i = 0; i < n; i++) {
    if (rep[i] == i) {
      memcpy(w->p + 3 * w->nv, o->xyz + 3 * i, 3 * sizeof(double));
      map[i] = w->nv++;
    } else map[i] = map[rep[i]];
  }
  us_free(keys);
  us_free(rep);
  return US_OK;
}

/* ---------------------------------------------------------------- faces */

static us_Status degenerate_face(const Work *w, int f, const char *why) {
  char m[200];
  snprintf(m, sizeof m, "face %d is degenerate (%s)", f + 1, why);
  return bad(w, m);
}

/* Twice the area times the unit normal of face f (fan from corner 0). */
static void face_normal(const Work *w, int f, double n[3]) {
  const double *o = w->p + 3 * w->fidx[w->fstart[f]];
  n[0] = n[1] = n[2] = 0;
  for (int i = w->fstart[f] + 1; i + 1 < w->fstart[f + 1]; i++) {
    const double *a = w->p + 3 * w->fidx[i], *b = w->p + 3 * w->fidx[i + 1];
    double u[3] = {a[0] - o[0], a[1] - o[1], a[2] - o[2]}, v[3] = {b[0] - o[0], b[1] - o[1], b[2] - o[2]};
    n[0] += u[1] * v[2] - u[2] * v[1];
    n[1] += u[2] * v[0] - u[0] * v[2];
    n[2] += u[0] * v[1] - u[1] * v[0];
  }
}

/* A face has area when it exceeds DEGENERATE_REL x its longest edge
 * squared: the face's own scale, whatever the rest of the file. */
static int face_has_area(const Work *w, int f) {
  double n[3], e2 = 0;
  face_normal(w, f, n);
  for (int i = w->fstart[f]; i < w->fstart[f + 1]; i++) {
    int j = i + 1 < w->fstart[f + 1] ? i + 1 : w->fstart[f];
    const double *a = w->p + 3 * w->fidx[i], *b = w->p + 3 * w->fidx[j];
    e2 = fmax(e2, (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
  }
  return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) > DEGENERATE_REL * e2;
}

/* Each face's welded corners, a corner equal to the one before dropped. */
static us_Status clean_faces(Work *w, const int *map) {
  const us_MeshObject *o = w->obj;
  w->fstart = us_malloc((size_t)(o->nface + 1) * sizeof *w->fstart);
  w->fidx = us_malloc((size_t)(o->nidx + 1) * sizeof *w->fidx);
  if (!w->fstart || !w->fidx) return nomem(w);
  int m = 0;
  w->fstart[0] = 0;
  for (int f = 0; f < o->nface; f++) {
    int s = o->fstart[f], e = o->fstart[f + 1], first = m;
    for (int k = s; k < e; k++) {
      int v = o->fidx[k];
      if (v < 0 || v >= o->nvert) return degenerate_face(w, f, "a corner out of range");
      v = map[v];
      if (m == first || w->fidx[m - 1] != v) w->fidx[m++] = v;
    }
    while (m - first > 1 && w->fidx[m - 1] == w->fidx[first]) m--;
    if (m - first < 3) return degenerate_face(w, f, "fewer than 3 distinct corners");
    w->fstart[f + 1] = m;
    if (!face_has_area(w, f)) return degenerate_face(w, f, "no area");
  }
  return US_OK;
}

/* One side of an edge: the face, and +1 when it runs from the edge's
 * lower vertex to its higher one, -1 the other way. */
typedef struct Side {
  uint64_t key; /* lower << 32 | higher */
  int face, sigma;
  double angle; /* about the edge (radial pairing) */
} Side;

static int side_cmp(const void *a, const void *b) {
  const Side *p = a, *q = b;
  if (p->key != q->key) return p->key < q->key ? -1 : 1;
  return (p->face > q->face) - (p->face < q->face);
}

static int angle_cmp(const void *a, const void *b) {
  const Side *p = a, *q = b;
  return (p->angle > q->angle) - (p->angle < q->angle);
}

static us_Status edge_error(const Work *w, uint64_t key, const char *fmt, int count) {
  const double *a = w->p + 3 * (key >> 32), *b = w->p + 3 * (key & 0xffffffffu);
  char what[200], m[500];
  snprintf(what, sizeof what, fmt, count, count == 1 ? "" : "s");
  snprintf(m, sizeof m, "%s: the edge from (%g, %g, %g) to (%g, %g, %g)", what, a[0], a[1], a[2],
           b[0], b[1], b[2]);
  return bad(w, m);
}

static int find(int *up, int v) {
  while (up[v] != v) v = up[v] = up[up[v]];
  return v;
}

/* Face f's centroid. */
static void face_centre(const Work *w, int f, double c[3]) {
  int n = w->fstart[f + 1] - w->fstart[f];
  c[0] = c[1] = c[2] = 0;
  for (int i = w->fstart[f]; i < w->fstart[f + 1]; i++)
    for (int a = 0; a < 3; a++) c[a] += w->p[3 * w->fidx[i] + a] / n;
}

/* Each face's angle about the edge, from the first face's direction:
 * the direction from the edge to the face's centre, across the edge. */
static void radial_angles(const Work *w, Side *e, int m) {
  const double *a = w->p + 3 * (e[0].key >> 32), *b = w->p + 3 * (e[0].key & 0xffffffffu);
  double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v1[3] = {0, 0, 0}, v2[3] = {0, 0, 0};
  double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (int k = 0; k < 3; k++) d[k] /= dl;
  for (int i = 0; i < m; i++) {
    double c[3], u[3];
    face_centre(w, e[i].face, c);
    for (int k = 0; k < 3; k++) u[k] = c[k] - a[k];
    double t = u[0] * d[0] + u[1] * d[1] + u[2] * d[2];
    for (int k = 0; k < 3; k++) u[k] -= t * d[k];
    if (i == 0) { /* the frame: v1 along the first face, v2 = d x v1 */
      double l = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      for (int k = 0; k < 3; k++) v1[k] = u[k] / l;
      v2[0] = d[1] * v1[2] - d[2] * v1[1];
      v2[1] = d[2] * v1[0] - d[0] * v1[2];
      v2[2] = d[0] * v1[1] - d[1] * v1[0];
    }
    double th = atan2(u[0] * v2[0] + u[1] * v2[1] + u[2] * v2[2], u[0] * v1[0] + u[1] * v1[1] + u[2] * v1[2]);
    e[i].angle = th < -PI + RADIAL_TIE ? th + 2 * PI : th;
  }
}

/* Faces of touching shells share an edge (stacked blocks: 4 faces). With
 * outward faces, a face running high -> low (sigma -1) has its solid on
 * the side of larger angles about the edge, one running low -> high on
 * the smaller: around the edge, each -1 face and the next face (a +1
 * face) bound one solid's wedge. Faces at one angle (two blocks' shared
 * face, seen from both) are ordered +1 first, so the empty wedge between
 * them is outside. Pairs are joined; 0, or -1 when the pattern breaks. */
static int pair_radially(const Work *w, Side *e, int m, int *up) {
  radial_angles(w, e, m);
  qsort(e, (size_t)m, sizeof *e, angle_cmp);
  for (int i = 0; i + 1 < m; i++) /* ties: +1 before -1 (bubble within a run) */
    for (int j = i + 1; j > 0 && e[j].angle - e[j - 1].angle <= RADIAL_TIE && e[j].sigma > e[j - 1].sigma; j--) {
      Side t = e[j];
      e[j] = e[j - 1], e[j - 1] = t;
    }
  for (int i = 0; i < m; i++) {
    const Side *f = &e[i], *g = &e[(i + 1) % m];
    if (f->sigma < 0 && g->sigma < 0) return -1;
    if (f->sigma < 0) up[find(up, f->face)] = find(up, g->face);
  }
  return 0;
}

/* Every edge on an even number of faces, joined into shells: two faces
 * at an edge are one shell's; more are paired about the edge. */
static us_Status join_faces(Work *w, int *up) {
  int nf = w->obj->nface, ne = w->fstart[nf];
  Side *e = us_malloc((size_t)(ne + 1) * sizeof *e);
  if (!e) return nomem(w);
  for (int f = 0, k = 0; f < nf; f++) {
    up[f] = f;
    for (int i = w->fstart[f]; i < w->fstart[f + 1]; i++) {
      int j = i + 1 < w->fstart[f + 1] ? i + 1 : w->fstart[f], a = w->fidx[i], b = w->fidx[j];
      e[k++] = (Side){(uint64_t)US_MIN(a, b) << 32 | (uint64_t)US_MAX(a, b), f, a < b ? 1 : -1, 0};
    }
  }
  qsort(e, (size_t)ne, sizeof *e, side_cmp);
  us_Status st = US_OK;
  for (int k = 0, run = 1; k < ne && !st; k += run) {
    for (run = 1; k + run < ne && e[k + run].key == e[k].key;) run++;
    if (run % 2) st = edge_error(w, e[k].key, "open mesh: %d face%s at an edge (a closed surface has 2, or an even number where closed shells touch)", run);
    else if (run == 2) up[find(up, e[k].face)] = find(up, e[k + 1].face);
    else if (pair_radially(w, e + k, run, up))
      st = edge_error(w, e[k].key, "%d face%s meet at an edge and are not all wound the same way (outward, counter-clockwise seen from outside), so its shells cannot be told apart", run);
  }
  us_free(e);
  return st;
}

/* Each shell's distinct vertices (a vertex may be in several shells):
 * the faces sorted by shell (counting sort into order), then per shell
 * its corners, each once (stamp). */
static void list_shell_vertices(Work *w, int *order, int *end, int *stamp) {
  int nf = w->obj->nface;
  for (int k = 0; k <= w->nshell; k++) end[k] = 0;
  for (int f = 0; f < nf; f++) end[w->fshell[f] + 1]++;
  for (int k = 0; k < w->nshell; k++) end[k + 1] += end[k];
  for (int f = 0; f < nf; f++) order[end[w->fshell[f]]++] = f;
  for (int k = 0, n = 0, o = 0; k < w->nshell; k++) { /* end[k]: shell k's last + 1 */
    for (; o < end[k]; o++)
      for (int i = w->fstart[order[o]]; i < w->fstart[order[o] + 1]; i++)
        if (stamp[w->fidx[i]] != k + 1) stamp[w->fidx[i]] = k + 1, w->sv[n++] = w->fidx[i];
    w->sstart[k + 1] = n;
  }
}

/* Shells: the faces joined, numbered in order of first face. */
static us_Status find_shells(Work *w) {
  int nf = w->obj->nface;
  int *up = us_malloc((size_t)(nf + 1) * sizeof *up);
  int *num = us_malloc((size_t)(nf + 1) * sizeof *num);
  int *stamp = us_calloc((size_t)w->nv + 1, sizeof *stamp);
  w->fshell = us_malloc((size_t)(nf + 1) * sizeof *w->fshell);
  w->sv = us_malloc((size_t)(w->fstart[nf] + 1) * sizeof *w->sv);
  us_Status st = up && num && stamp && w->fshell && w->sv ? join_faces(w, up) : nomem(w);
  w->nshell = 0;
  for (int f = 0; f < nf && !st; f++) num[f] = -1;
  for (int f = 0; f < nf && !st; f++) {
    int r = find(up, f);
    if (num[r] < 0) num[r] = w->nshell++;
    w->fshell[f] = num[r];
  }
  w->sstart = st ? NULL : us_calloc((size_t)w->nshell + 1, sizeof *w->sstart);
  if (!st && !w->sstart) st = nomem(w);
  if (!st) list_shell_vertices(w, up, num, stamp); /* up and num reused */
  us_free(up), us_free(num), us_free(stamp);
  return st;
}

/* ------------------------------------------------------------ convexity */

/* The shell's tolerance and vertex centroid. */
static double shell_tol(const Work *w, int k, double c[3]) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, big = 0;
  int n = w->sstart[k + 1] - w->sstart[k];
  c[0] = c[1] = c[2] = 0;
  for (int i = w->sstart[k]; i < w->sstart[k + 1]; i++)
    for (int a = 0; a < 3; a++) {
      double x = w->p[3 * w->sv[i] + a];
      lo[a] = fmin(lo[a], x), hi[a] = fmax(hi[a], x), big = fmax(big, fabs(x));
      c[a] += x / n;
    }
  double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                     (hi[2] - lo[2]) * (hi[2] - lo[2]));
  return US_GEOM_TOL_REL * diag + FLOAT_ULPS * FLT_EPSILON * big;
}

static us_Status not_convex(const Work *w, int f, const double *v, double d, double tol) {
  char m[500];
  snprintf(m, sizeof m, "not convex: vertex (%g, %g, %g) is %g in front of the plane of face %d "
           "(tolerance %g); give it as convex parts, each a closed mesh of its own "
           "(docs/mesh.md, \"Compounds\")", v[0], v[1], v[2], d, f + 1, tol);
  return bad(w, m);
}

static us_Status not_planar(const Work *w, int f, const double *v, double d, double tol) {
  char m[400];
  snprintf(m, sizeof m, "face %d is not planar: its corner (%g, %g, %g) is %g off its plane "
           "(tolerance %g); split it into triangles", f + 1, v[0], v[1], v[2], d, tol);
  return bad(w, m);
}

/* Face f of shell k: its corners on its plane, no shell vertex in front. */
static us_Status check_face(const Work *w, int k, int f, const double c[3], double tol) {
  double n[3];
  face_normal(w, f, n);
  double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const double *o = w->p + 3 * w->fidx[w->fstart[f]];
  double side = (n[0] * (c[0] - o[0]) + n[1] * (c[1] - o[1]) + n[2] * (c[2] - o[2])) / len;
  double s = side > 0 ? -1 / len : 1 / len;
  if (fabs(side) <= tol) { /* a convex solid's centroid is inside: flat, or folded */
    char m[300];
    snprintf(m, sizeof m, "flat or not convex: the centre of its vertices is on the plane of "
             "face %d (tolerance %g); give it as convex parts, each a closed mesh of its own "
             "(docs/mesh.md, \"Compounds\")", f + 1, tol);
    return bad(w, m);
  }
  for (int i = w->fstart[f]; i < w->fstart[f + 1]; i++) { /* its own corners on its plane */
    const double *v = w->p + 3 * w->fidx[i];
    double d = s * (n[0] * (v[0] - o[0]) + n[1] * (v[1] - o[1]) + n[2] * (v[2] - o[2]));
    if (fabs(d) > tol) return not_planar(w, f, v, fabs(d), tol);
  }
  for (int i = w->sstart[k]; i < w->sstart[k + 1]; i++) {
    const double *v = w->p + 3 * w->sv[i];
    double d = s * (n[0] * (v[0] - o[0]) + n[1] * (v[1] - o[1]) + n[2] * (v[2] - o[2]));
    if (d > tol) return not_convex(w, f, v, d, tol);
  }
  return US_OK;
}

static us_Status check_shells(Work *w) {
  double (*c)[3] = us_malloc((size_t)(w->nshell + 1) * sizeof *c);
  double *tol = us_malloc((size_t)(w->nshell + 1) * sizeof *tol);
  if (!c || !tol) return us_free(c), us_free(tol), nomem(w);
  for (int k = 0; k < w->nshell; k++) tol[k] = shell_tol(w, k, c[k]);
  us_Status st = US_OK;
  for (int f = 0; f < w->obj->nface && !st; f++) {
    int k = w->fshell[f];
    st = check_face(w, k, f, c[k], tol[k]);
    if (!st && f % CLOCK_EVERY == CLOCK_EVERY - 1 && us_past(w->set->deadline))
      st = us_error_set(w->err, US_ERR_TIME_LIMIT, "%s: the time limit passed while checking "
                        "the meshes", w->doc->name);
  }
  us_free(c);
  us_free(tol);
  return st;
}

/* The object's checks, in the order of the file head. */
static us_Status analyse(Work *w) {
  const us_MeshObject *o = w->obj;
  if (o->nface == 0) return bad(w, "has no faces (points or lines only)");
  us_Status st = check_finite(w);
  int *map = st ? NULL : us_malloc((size_t)(o->nvert + 1) * sizeof *map);
  if (!st && !map) st = nomem(w);
  if (!st) st = weld(w, map);
  if (!st) st = clean_faces(w, map);
  us_free(map);
  if (!st) st = find_shells(w);
  return st ? st : check_shells(w);
}

/* ------------------------------------------------------------------ ids */

typedef struct Names {
  us_IdMap taken;
  char **owned;
  int n, cap;
  int renamed;
} Names;

/* name with every byte that is not printable UTF-8 turned into '_'. */
static char *sanitize(const char *name) {
  char *s = us_strdup(name);
  for (size_t k = 0; s && s[k];) {
    uint32_t cp;
    int len = us_utf8_next(s + k, &cp);
    if (cp == US_UTF8_INVALID || cp <= 0x20 || cp == 0x7f || (cp >= 0x80 && cp < 0xa0))
      for (int j = 0; j < len; j++) s[k + (size_t)j] = '_';
    k += (size_t)len;
  }
  return s;
}

/* A free id from `base` (and shell number `part` > 0): base, then base-2,
 * base-3, ...; owned by names. NULL out of memory. */
static const char *unique_id(Names *nm, const char *base, int part) {
  char *clean = sanitize(base);
  size_t cap = (clean ? strlen(clean) : 0) + 32;
  char *id = clean ? us_malloc(cap) : NULL;
  if (!id || US_GROW(nm->owned, nm->cap, nm->n + 1)) return us_free(clean), us_free(id), NULL;
  if (part > 0) snprintf(id, cap, "%s-%d", clean, part);
  else snprintf(id, cap, "%s", clean);
  int changed = strcmp(clean, base) != 0;
  for (int k = 2; !strcmp(id, "ground") || us_idmap_get(&nm->taken, id) >= 0; k++, changed = 1)
    if (part > 0) snprintf(id, cap, "%s-%d-%d", clean, part, k);
    else snprintf(id, cap, "%s-%d", clean, k);
  us_free(clean);
  nm->owned[nm->n++] = id;
  nm->renamed += changed;
  return us_idmap_put(&nm->taken, id, nm->n) == -2 ? NULL : id;
}

/* ---------------------------------------------------------------- bodies */

/* Shell k's vertices, turned, scaled and shifted, into xyz. */
static void place(const Work *w, int k, double shift, double *xyz) {
  const us_MeshSettings *set = w->set;
  for (int i = w->sstart[k], j = 0; i < w->sstart[k + 1]; i++, j++) {
    const double *v = w->p + 3 * w->sv[i];
    double y = set->up == 'y' ? -v[2] : v[1], z = set->up == 'y' ? v[1] : v[2];
    xyz[3 * j] = v[0] * set->scale;
    xyz[3 * j + 1] = y * set->scale;
    xyz[3 * j + 2] = z * set->scale - shift;
  }
}

/* One body of shells [k0, k1) named id. */
static us_Status add_body(Work *w, us_Structure *s, int k0, int k1, const char *id, double shift,
                          us_MeshInfo *info) {
  us_PartDef *parts = us_calloc((size_t)(k1 - k0), sizeof *parts);
  double *xyz = us_malloc((size_t)(w->sstart[k1] - w->sstart[k0]) * 3 * sizeof *xyz);
  if (!parts || !xyz) return us_free(parts), us_free(xyz), nomem(w);
  for (int k = k0; k < k1; k++) {
    parts[k - k0].nvert = w->sstart[k + 1] - w->sstart[k];
    parts[k - k0].xyz = xyz + 3 * (w->sstart[k] - w->sstart[k0]);
    place(w, k, shift, xyz + 3 * (w->sstart[k] - w->sstart[k0]));
  }
  us_BodyDef def = us_default_body_def();
  def.id = id;
  def.density = w->set->density;
  def.fixed = w->set->fixed && fnmatch(w->set->fixed, id, 0) == 0;
  if (k1 - k0 > 1) def.npart = k1 - k0, def.parts = parts;
  else def.nvert = parts[0].nvert, def.xyz = parts[0].xyz;
  int r = us_structure_add_body(s, &def, w->err);
  us_free(parts);
  us_free(xyz);
  info->fixed += def.fixed;
  info->compounds += k1 - k0 > 1;
  return r < 0 ? w->err->code : US_OK;
}

/* The object's bodies: one, or one per shell when the file names none. */
static us_Status add_object(Work *w, us_Structure *s, Names *nm, double shift, us_MeshInfo *info) {
  const char *base = w->obj->name[0] ? w->obj->name : w->doc->stem;
  us_Status st = US_OK;
  info->shells += w->nshell;
  if (w->obj->named) {
    const char *id = unique_id(nm, base, 0);
    return id ? add_body(w, s, 0, w->nshell, id, shift, info) : nomem(w);
  }
  for (int k = 0; k < w->nshell && !st; k++) {
    const char *id = unique_id(nm, base, w->nshell > 1 ? k + 1 : 0);
    st = id ? add_body(w, s, k, k + 1, id, shift, info) : nomem(w);
  }
  return st;
}

/* ---------------------------------------------------------------- driver */

static us_Status check_settings(const us_MeshDoc *d, const us_MeshSettings *set, us_Error *err) {
  if (set->up != 'z' && set->up != 'y')
    return us_error_set(err, US_ERR_USAGE, "%s: the up axis must be 'z' or 'y'", d->name);
  if (!(set->scale > 0) || !isfinite(set->scale))
    return us_error_set(err, US_ERR_USAGE, "%s: the scale must be a finite number > 0", d->name);
  if (!(set->density > 0) || !isfinite(set->density))
    return us_error_set(err, US_ERR_USAGE, "%s: the density must be a finite number > 0", d->name);
  if (isnan(set->friction) || isnan(set->contact_tol) || set->contact_tol < 0)
    return us_error_set(err, US_ERR_USAGE, "%s: bad friction or contact tolerance", d->name);
  if (d->nobj == 0)
    return us_error_set(err, US_ERR_INPUT, "%s: no meshes to import", d->name);
  return US_OK;
}

/* The lowest z of the output over every object, before the shift. */
static double lowest(const us_MeshDoc *d, const us_MeshSettings *set) {
  double z = INFINITY;
  for (int k = 0; k < d->nobj; k++)
    for (int i = 0; i < d->objs[k].nvert; i++)
      z = fmin(z, (set->up == 'y' ? d->objs[k].xyz[3 * i + 1] : d->objs[k].xyz[3 * i + 2]));
  return z * set->scale;
}

static us_Status finalize(const us_MeshDoc *d, us_Structure *s, double deadline, us_Error *err) {
  us_Status st = us_structure_finalize_until(s, deadline, err);
  if (!st) return US_OK;
  char msg[sizeof err->msg];
  memcpy(msg, err->msg, sizeof msg);
  return us_error_set(err, st, "%s: %s", d->name, msg);
}

static us_Status add_objects(const us_MeshDoc *d, const us_MeshSettings *set, us_Structure *s,
                             us_MeshInfo *info, us_Error *err) {
  Names nm;
  memset(&nm, 0, sizeof nm);
  us_Status st = us_idmap_init(&nm.taken, 2 * d->nobj + 8)
                     ? us_error_set(err, US_ERR_NOMEM, "%s: out of memory", d->name) : US_OK;
  double shift = set->ground ? lowest(d, set) : 0;
  for (int k = 0; k < d->nobj && !st; k++) {
    Work w = {d, &d->objs[k], set, err, 0, NULL, NULL, NULL, 0, NULL, NULL, NULL};
    info->faces += d->objs[k].nface;
    st = analyse(&w);
    if (!st) st = add_object(&w, s, &nm, shift, info);
    work_free(&w);
  }
  for (int k = 0; k < nm.n; k++) us_free(nm.owned[k]);
  us_free(nm.owned);
  us_idmap_free(&nm.taken);
  info->ids_renamed = nm.renamed;
  return st;
}

us_Structure *us_mesh_build(const us_MeshDoc *d, const us_MeshSettings *set, us_MeshInfo *info,
                            us_Error *err) {
  us_MeshInfo local;
  memset(&local, 0, sizeof local);
  if (info) *info = local;
  if (check_settings(d, set, err)) return NULL;
  us_Structure *s = us_structure_new(3);
  if (!s) {
    us_error_set(err, US_ERR_NOMEM, "%s: out of memory", d->name);
    return NULL;
  }
  s->friction = set->friction >= 0 ? set->friction : s->friction;
  s->ground = set->ground ? 1 : 0;
  if (set->contact_tol > 0) s->contact_tol = set->contact_tol;
  if (add_objects(d, set, s, &local, err) || finalize(d, s, set->deadline, err)) {
    us_structure_free(s);
    s = NULL;
  }
  local.bodies = s ? s->nbody : 0;
  if (info) *info = local;
  return s;
}
