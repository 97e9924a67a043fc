/* Reading the geometry of a 3D body (docs/format.md, "3D structures"):
 * "vertices", "box" or "parts", each turned into point sets whose convex
 * hulls finalize takes. Only types and ranges are checked here (arrays of
 * finite numbers, at least 4 points, positive box sizes, a non-zero
 * quaternion); shape checks (points off one plane, volume, overlaps,
 * ground) are finalize's, which names the body. A box becomes its 8
 * corners (geometry/polyhedron.c, us_box_points); "rotation" is a
 * quaternion [w, x, y, z] (normalized), "euler" angles in degrees,
 * intrinsic z-y-x (R = Rz Ry Rx); giving both is an error. */
#include <math.h>
#include <string.h>

#include "geometry/geometry3.h"
#include "io.h"

#define MAX_POINTS 10000000 /* far beyond any real block; keeps int sizes safe */
#define MAX_PARTS 1000000

static const char *const box_keys[] = {"center", "size", "rotation", "euler", NULL};
static const char *const part_keys[] = {"vertices", "box", NULL};

static us_Status nomem(const us_IoCtx *c) {
  return us_error_set(c->err, US_ERR_NOMEM, "%s: out of memory", c->name);
}

/* "vertices": an array of at least 4 [x, y, z]. */
static us_Status read_vertices(const us_IoCtx *c, const char *where, const char *field, json_t *v,
                               us_PartDef *p) {
  if (!json_is_array(v))
    return us_io_bad(c, where, "%s: expected an array of [x, y, z] points", field);
  size_t n = json_array_size(v);
  if (n < 4) return us_io_bad(c, where, "%s: needs at least 4 points (got %zu)", field, n);
  if (n > MAX_POINTS) return us_io_bad(c, where, "%s: too many points (%zu)", field, n);
  double *xyz = us_malloc(3 * n * sizeof(double));
  if (!xyz) return nomem(c);
  p->xyz = xyz;
  p->nvert = (int)n;
  for (size_t k = 0; k < n; k++) {
    char f[64];
    snprintf(f, sizeof f, "%s[%zu]", field, k);
    us_Status st = us_io_vecn(c, where, f, json_array_get(v, k), 3, xyz + 3 * k);
    if (st) return st;
  }
  return US_OK;
}

/* The rotation of a box: identity, a quaternion or Euler angles. */
static us_Status read_rotation(const us_IoCtx *c, const char *where, json_t *box, double q[4]) {
  json_t *r = json_object_get(box, "rotation"), *e = json_object_get(box, "euler");
  q[0] = 1, q[1] = q[2] = q[3] = 0;
  if (r && e) return us_io_bad(c, where, "box: give either 'rotation' or 'euler', not both");
  if (e) {
    double deg[3];
    us_Status st = us_io_vecn(c, where, "box.euler", e, 3, deg);
    if (!st) us_quat_from_euler(deg, q);
    return st;
  }
  if (!r) return US_OK;
  us_Status st = us_io_vecn(c, where, "box.rotation", r, 4, q);
  /* normalized here, its norm taken after dividing by the largest
   * component, so that [1e308, 1e308, 0, 0] does not overflow */
  double m = 0.0, l = 0.0;
  for (int k = 0; !st && k < 4; k++) m = fmax(m, fabs(q[k]));
  for (int k = 0; !st && k < 4; k++) l += (q[k] / m) * (q[k] / m);
  if (!st && !(m > 0))
    st = us_io_bad(c, where, "box.rotation: the quaternion must not be zero");
  for (int k = 0; !st && k < 4; k++) q[k] = q[k] / m / sqrt(l);
  return st;
}

/* "box": {"center", "size", "rotation" | "euler"} -> its 8 corners. */
static us_Status read_box(const us_IoCtx *c, const char *where, json_t *box, us_PartDef *p) {
  if (!json_is_object(box)) return us_io_bad(c, where, "box: expected an object");
  double center[3], size[3], q[4];
  us_Status st = us_io_check_keys(c, where, box, box_keys);
  json_t *v;
  if (!st && !(v = json_object_get(box, "center"))) st = us_io_bad(c, where, "box: missing field 'center'");
  if (!st) st = us_io_vecn(c, where, "box.center", v, 3, center);
  if (!st && !(v = json_object_get(box, "size"))) st = us_io_bad(c, where, "box: missing field 'size'");
  if (!st) st = us_io_vecn(c, where, "box.size", v, 3, size);
  for (int k = 0; !st && k < 3; k++)
    if (!(size[k] > 0)) st = us_io_bad(c, where, "box.size: must be > 0 (got %g)", size[k]);
  if (!st) st = read_rotation(c, where, box, q);
  if (st) return st;
  double *xyz = us_malloc(24 * sizeof(double));
  if (!xyz) return nomem(c);
  us_box_points(center, size, q, xyz);
  p->xyz = xyz;
  p->nvert = 8;
  return US_OK;
}

/* One convex piece: an object with exactly one of "vertices" and "box". */
static us_Status read_piece(const us_IoCtx *c, const char *where, json_t *obj, us_PartDef *p) {
  json_t *v = json_object_get(obj, "vertices"), *b = json_object_get(obj, "box");
  if (v && b) return us_io_bad(c, where, "give one of 'vertices' and 'box', not both");
  if (v) return read_vertices(c, where, "vertices", v, p);
  return read_box(c, where, b, p);
}

static us_Status read_parts(const us_IoCtx *c, const char *where, json_t *arr, us_PartDef **parts,
                            int *npart) {
  if (!json_is_array(arr) || json_array_size(arr) < 1)
    return us_io_bad(c, where, "parts: expected a non-empty array of parts");
  size_t n = json_array_size(arr);
  if (n > MAX_PARTS) return us_io_bad(c, where, "parts: too many parts (%zu)", n);
  *parts = us_calloc(n, sizeof **parts);
  if (!*parts) return nomem(c);
  *npart = (int)n;
  for (size_t k = 0; k < n; k++) {
    char w[200];
    json_t *o = json_array_get(arr, k);
    snprintf(w, sizeof w, "%s: parts[%zu]", where, k);
    us_Status st = json_is_object(o) ? us_io_check_keys(c, w, o, part_keys)
                                     : us_io_bad(c, w, "expected an object");
    if (!st && !json_object_get(o, "vertices") && !json_object_get(o, "box"))
      st = us_io_bad(c, w, "missing field 'vertices' or 'box'");
    if (!st) st = read_piece(c, w, o, &(*parts)[k]);
    if (st) return st;
  }
  return US_OK;
}

us_Status us_io_read_solid(const us_IoCtx *c, const char *where, json_t *body, us_PartDef **parts,
                           int *npart) {
  json_t *v = json_object_get(body, "vertices"), *b = json_object_get(body, "box"),
         *p = json_object_get(body, "parts");
  *parts = NULL;
  *npart = 0;
  if ((v != NULL) + (b != NULL) + (p != NULL) > 1)
    return us_io_bad(c, where, "give one of 'vertices', 'box' and 'parts'");
  if (p) return read_parts(c, where, p, parts, npart);
  *parts = us_calloc(1, sizeof **parts);
  if (!*parts) return nomem(c);
  *npart = 1;
  return read_piece(c, where, body, *parts);
}

void us_io_solid_free(us_PartDef *parts, int npart) {
  for (int k = 0; parts && k < npart; k++) us_free((void *)parts[k].xyz);
  us_free(parts);
}
