/* Wavefront OBJ -> the mesh import's neutral document (io/mesh.h), read
 * here rather than by Assimp (docs/mesh.md, "Formats"): Assimp 5.2 cuts an
 * `o` name at its first space and then merges `o block 1` with `o block 2`
 * into one object, makes every `g` an object of its own, and keeps
 * coordinates in single precision. This reader keeps whole names and
 * doubles.
 *
 * Grammar read: `v x y z [w]`; `f` with corners `i`, `i/t`, `i//n`,
 * `i/t/n`, negative indices counting back from the last vertex; `o NAME`
 * and `g NAME ...` (the rest of the line, trimmed, is the name). Faces go
 * to the current `o`; before any `o`, to the current `g`; before either,
 * to one unnamed object (split into shells by mesh_build.c). An `o` name
 * given twice is one object. Texture, normal, smoothing, material, line
 * and point statements are skipped; free-form geometry (curv, surf, ...)
 * and unknown statements are errors naming the line. Every face corner
 * becomes a vertex of its object; mesh_build.c welds equal positions. */
#include "mesh.h"

#include "io.h"

#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>

/* Statements skipped: attributes, grouping and display, points, lines. */
static const char *const skipped[] = {"vt", "vn", "s", "usemtl", "mtllib", "l", "p", "mg",
                                      "lod", "bevel", "c_interp", "d_interp", "usemap",
                                      "maplib", "shadow_obj", "trace_obj", NULL};
/* Free-form geometry, which this reader does not read. */
static const char *const freeform[] = {"vp", "cstype", "deg", "bmat", "step", "curv", "curv2",
                                       "surf", "parm", "trim", "hole", "scrv", "sp", "end",
                                       "con", "ctech", "stech", NULL};

typedef struct Obj {
  us_MeshDoc *doc;
  us_Error *err;
  long line;
  double *v;        /* the file's vertices so far */
  int nv, vcap;
  char *object;     /* the current o's name, or NULL */
  char *group;      /* the current g's name, or NULL */
  int cur;          /* the object faces go to, -1: look it up */
  us_IdMap named;   /* object name -> index (keys: the objects' names) */
  int unnamed;      /* the object of faces before any o or g, or -1 */
} Obj;

static int in_list(const char *const *list, const char *w, size_t n) {
  for (int k = 0; list[k]; k++)
    if (strlen(list[k]) == n && !strncmp(list[k], w, n)) return 1;
  return 0;
}

static us_Status parse_error(const Obj *o, const char *what) {
  return us_error_set(o->err, US_ERR_PARSE, "%s:%ld: %s", o->doc->name, o->line, what);
}

static us_Status nomem(const Obj *o) {
  return us_error_set(o->err, US_ERR_NOMEM, "%s: out of memory", o->doc->name);
}

/* `v x y z [w]`: three numbers (nan and inf are read, and refused later
 * naming the object). */
static us_Status vertex(Obj *o, const char *s) {
  double p[3];
  for (int a = 0; a < 3; a++) {
    char *end;
    p[a] = strtod(s, &end);
    if (end == s) return parse_error(o, "a vertex needs three numbers");
    s = end;
  }
  if (us_grow((void **)&o->v, &o->vcap, 3 * (o->nv + 1), sizeof *o->v)) return nomem(o);
  memcpy(o->v + 3 * o->nv++, p, sizeof p);
  return US_OK;
}

/* The object the next face goes to: found by name, else made. */
static int current(Obj *o) {
  if (o->cur >= 0) return o->cur;
  const char *name = o->object ? o->object : o->group;
  int k = name ? us_idmap_get(&o->named, name) : o->unnamed;
  if (k < 0) k = us_mesh_object(o->doc, name ? name : "", name != NULL, 0);
  if (k >= 0 && name && us_idmap_put(&o->named, o->doc->objs[k].name, k) == -2) k = -1;
  if (k >= 0 && !name) o->unnamed = k;
  return o->cur = k;
}

/* One corner's vertex index (0-based), or -1 with the error set. */
static int corner(Obj *o, const char **s) {
  char *end;
  errno = 0;
  long i = strtol(*s, &end, 10);
  if (end == *s || errno) return parse_error(o, "a face corner needs a vertex number"), -1;
  while (*end && !isspace((unsigned char)*end)) end++; /* /t/n */
  *s = end;
  long k = i < 0 ? o->nv + i : i - 1;
  if (i == 0 || k < 0 || k >= o->nv) {
    char m[120];
    snprintf(m, sizeof m, "face corner %ld: no such vertex (%d so far)", i, o->nv);
    return parse_error(o, m), -1;
  }
  return (int)k;
}

/* `f a b c ...`: its corners' positions become new vertices of the object. */
static us_Status face(Obj *o, const char *s) {
  int k = current(o);
  if (k < 0) return nomem(o);
  us_MeshObject *m = &o->doc->objs[k];
  int base = m->nvert;
  unsigned n = 0;
  for (;;) {
    while (isspace((unsigned char)*s)) s++;
    if (!*s) break;
    int i = corner(o, &s);
    if (i < 0) return o->err->code;
    if (us_mesh_add_vertex(m, o->v + 3 * i)) return nomem(o);
    n++;
  }
  unsigned *idx = us_malloc((n + 1) * sizeof *idx);
  if (!idx) return nomem(o);
  for (unsigned c = 0; c < n; c++) idx[c] = c;
  int r = us_mesh_add_face(m, base, idx, (int)n);
  us_free(idx);
  return r ? nomem(o) : US_OK;
}

/* `o NAME` / `g NAME`: the rest of the line, trimmed. */
static us_Status name(Obj *o, const char *s, char **slot) {
  while (isspace((unsigned char)*s)) s++;
  size_t n = strlen(s);
  while (n > 0 && isspace((unsigned char)s[n - 1])) n--;
  char *copy = us_malloc(n + 1);
  if (!copy) return nomem(o);
  memcpy(copy, s, n);
  copy[n] = '\0';
  us_free(*slot);
  *slot = copy;
  o->cur = -1;
  return US_OK;
}

static us_Status statement(Obj *o, const char *s) {
  while (isspace((unsigned char)*s)) s++;
  size_t n = strcspn(s, " \t\r\n");
  if (n == 0 || *s == '#') return US_OK;
  const char *rest = s + n;
  if (n == 1 && *s == 'v') return vertex(o, rest);
  if (n == 1 && *s == 'f') return face(o, rest);
  if (n == 2 && !strncmp(s, "fo", 2)) return face(o, rest); /* old spelling of f */
  if (n == 1 && *s == 'o') return name(o, rest, &o->object);
  if (n == 1 && *s == 'g') return o->object ? US_OK : name(o, rest, &o->group);
  if (in_list(skipped, s, n)) return US_OK;
  char m[160];
  snprintf(m, sizeof m, "%s '%.*s'", in_list(freeform, s, n) ? "free-form geometry is not read:"
           : "not an OBJ statement:", (int)US_MIN(n, 40), s);
  return parse_error(o, m);
}

us_Status us_mesh_read_obj(us_MeshDoc *doc, const char *path, us_Error *err) {
  size_t len = 0;
  char *text = us_io_slurp(path, &len, err);
  if (!text) return err->code;
  if (memchr(text, '\0', len)) {
    us_free(text);
    return us_error_set(err, US_ERR_PARSE, "%s: not a text file (a NUL byte): not OBJ", path);
  }
  Obj o = {doc, err, 0, NULL, 0, 0, NULL, NULL, -1, {0}, -1};
  us_Status st = us_idmap_init(&o.named, 16) ? nomem(&o) : US_OK;
  for (char *line = text, *next; line && !st; line = next) {
    next = strchr(line, '\n');
    if (next) *next++ = '\0';
    o.line++;
    st = statement(&o, line);
  }
  us_free(o.v), us_free(o.object), us_free(o.group), us_free(text);
  us_idmap_free(&o.named);
  return st;
}
