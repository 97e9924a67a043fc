/* SVG drawings -> structures (docs/svg.md): the driver and the public
 * entry points.
 *
 * Order of work: check the settings; parse the XML with libxml2 (no
 * network, no external entities; a syntax error names file:line); walk
 * the tree into rings in root user units (svg_walk.c); give every ring a
 * unique id; find the ground line (the drawing's lowest point, or the
 * given one); map root units to output units with y flipped, so the
 * ground is y = 0 and up is up; reject degenerate rings naming their
 * element and line; add the bodies, snap them into contact (svg_snap.c)
 * and finalize, whose messages (overlaps naming both bodies, bodies below
 * the ground) get the file name and the elements' lines appended.
 *
 * Ids: every explicit id is kept in document order; a repeat of an
 * earlier id (or "ground", which is reserved) becomes ID-2, ID-3, ...,
 * and a shape without an id gets ELEMENT-1, ELEMENT-2, ... (rect-1,
 * path-3), skipping names already taken. A path with several closed
 * subpaths makes one body each, named as repeats of the path's id. One
 * hash map of taken names and one of the next suffix per base keep this
 * linear in the number of shapes. */
#include "svg.h"

#include "geometry/geometry.h"
#include "io.h"

#include <libxml/parser.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define SNAP_REL 1e-3
#define DEGENERATE_REL 1e-12
/* What entity references may add to attribute values in all: 1 MiB plus
 * 4 bytes per byte of the file (svg_walk.c, docs/svg.md) */
#define ENTITY_BASE ((size_t)1 << 20)
#define ENTITY_PER_BYTE 4
/* The largest drawing read: its tree, rings and structure take up to
 * about 40 times its size (a 20 MB wall of rects: 750 MB) */
#define SVG_MAX_BYTES (64 << 20)
/* Vertices the rings may have in all: 1 Mi plus 4 per byte of the file
 * (a default circle is about 70 from 25 bytes) */
#define POINTS_BASE (1 << 20)
#define POINTS_PER_BYTE 4

us_SvgSettings us_svg_default_settings(void) {
  us_SvgSettings s;
  memset(&s, 0, sizeof s);
  s.unit = "m";
  s.scale = 1;
  s.ground = 1;
  s.snap = -1;
  s.flatten = 1e-3;
  s.friction = -1;
  return s;
}

typedef struct Import {
  const us_SvgSettings *set;
  us_SvgDoc doc;
  us_SvgInfo info;
  char **ids;        /* final id of ring k (borrowed or in gen) */
  char **gen;        /* generated names (owned) */
  int ngen;
  double k[2];       /* output units per root user unit, x and y */
  double ground_y;   /* the ground line in root units (y down) */
  us_Error *err;
} Import;

static us_Status check_settings(const us_SvgSettings *s, const char *name, double *out_unit,
                                us_Error *err) {
  const char *u = s->unit ? s->unit : "m";
  *out_unit = strcmp(u, "user") ? us_svg_unit_metres(u, strlen(u)) : -1;
  if (*out_unit == 0) return us_error_set(err, US_ERR_USAGE, "unknown unit '%s' (m, cm, mm, in, pt, pc, px, user)", u);
  if (!(s->scale > 0) || !isfinite(s->scale))
    return us_error_set(err, US_ERR_USAGE, "%s: the scale must be a finite number > 0", name);
  if (!(s->flatten > 0 && s->flatten <= 0.5))
    return us_error_set(err, US_ERR_USAGE, "%s: the curve tolerance must be in (0, 0.5]", name);
  if (!isfinite(s->snap) || (s->ground_at_set && !isfinite(s->ground_at)))
    return us_error_set(err, US_ERR_USAGE, "%s: snap and ground-at must be finite", name);
  return US_OK;
}

/* ------------------------------------------------------------------ XML */

static void too_large(const char *name, double bytes, us_Error *err) {
  us_error_set(err, US_ERR_INPUT, "%s: too large (%.0f bytes): the import reads at most %d MiB "
               "of SVG, about a million blocks (docs/svg.md)", name, bytes, SVG_MAX_BYTES >> 20);
}

static xmlDoc *parse_xml(const char *text, size_t len, const char *name, us_Error *err) {
  if (len > SVG_MAX_BYTES) {
    too_large(name, (double)len, err);
    return NULL;
  }
  xmlParserCtxt *ctx = xmlNewParserCtxt();
  if (!ctx) {
    us_error_set(err, US_ERR_NOMEM, "out of memory");
    return NULL;
  }
  /* no network, no DTD loading, entities left as references (svg_walk.c),
   XML_PARSE_HUGE off (libxml2's size limits hold), short strings in nodes */
  int opts = XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING | XML_PARSE_BIG_LINES |
             XML_PARSE_COMPACT;
  xmlDoc *doc = xmlCtxtReadMemory(ctx, text, (int)len, name, NULL, opts);
  if (!doc) {
    const xmlError *e = xmlCtxtGetLastError(ctx);
    char msg[256] = "unknown error";
    if (e && e->message) snprintf(msg, sizeof msg, "%s", e->message);
    msg[strcspn(msg, "\n")] = '\0';
    /* libxml2's amplification guard says "loop" for a bomb too */
    const char *bomb = e && e->code == XML_ERR_ENTITY_LOOP ? " (or entities that expand too much)" : "";
    us_error_set(err, US_ERR_PARSE, "%s:%d: malformed XML: %s%s", name, e ? e->line : 0, msg, bomb);
  }
  xmlFreeParserCtxt(ctx);
  return doc;
}

/* ------------------------------------------------------------------ ids */

static us_Status name_rings(Import *im) {
  int n = im->doc.rings.nring;
  us_IdMap taken = {0}, next = {0};
  int *counter = us_calloc((size_t)n + 1, sizeof *counter);
  im->ids = us_calloc((size_t)n + 1, sizeof *im->ids);
  im->gen = us_calloc((size_t)n + 1, sizeof *im->gen);
  us_Status st = US_OK;
  if (!counter || !im->ids || !im->gen || us_idmap_init(&taken, 2 * n) || us_idmap_init(&next, n))
    st = US_ERR_NOMEM;
  for (int k = 0; k < n && !st; k++) { /* explicit ids, first come */
    char *id = im->doc.shapes[k].id;
    if (!id || !*id || !strcmp(id, "ground")) continue;
    int r = us_idmap_put(&taken, id, k);
    if (r == -2) st = US_ERR_NOMEM;
    else if (r == 0) im->ids[k] = id;
  }
  for (int k = 0; k < n && !st; k++) { /* repeats and missing ids */
    if (im->ids[k]) continue;
    const us_SvgShape *sh = &im->doc.shapes[k];
    int given = sh->id && *sh->id;
    const char *base = given ? sh->id : sh->kind;
    int b = us_idmap_get(&next, base);
    if (b < 0 && us_idmap_put(&next, base, k)) { st = US_ERR_NOMEM; break; }
    if (b < 0) b = k, counter[b] = given ? 2 : 1;
    size_t cap = strlen(base) + 16;
    char *buf = us_malloc(cap);
    if (!buf) { st = US_ERR_NOMEM; break; }
    im->gen[im->ngen++] = buf;
    do snprintf(buf, cap, "%s-%d", base, counter[b]++);
    while (us_idmap_get(&taken, buf) >= 0);
    if (us_idmap_put(&taken, buf, k)) { st = US_ERR_NOMEM; break; }
    im->ids[k] = buf;
    if (given) im->info.ids_renamed++;
    else im->info.ids_generated++;
  }
  us_idmap_free(&taken);
  us_idmap_free(&next);
  us_free(counter);
  return st ? us_error_set(im->err, st, "out of memory naming the shapes") : US_OK;
}

/* ------------------------------------------------------------ geometry */

/* "NAME:LINE: <kind id='x'>: " for ring k. */
static void where(const Import *im, int k, char *buf, size_t cap) {
  const us_SvgShape *sh = &im->doc.shapes[k];
  if (sh->id) snprintf(buf, cap, "%s:%ld: <%s id='%s'>", im->doc.name, sh->line, sh->kind, us_id_text(sh->id).s);
  else snprintf(buf, cap, "%s:%ld: <%s>", im->doc.name, sh->line, sh->kind);
}

/* Output units per root user unit. */
static void unit_factors(Import *im, double out_unit) {
  for (int a = 0; a < 2; a++)
    im->k[a] = out_unit < 0 ? im->set->scale : im->doc.unit_metres[a] / out_unit * im->set->scale;
  im->info.unit = im->k[0];
}

static void find_ground(Import *im) {
  const us_SvgRings *r = &im->doc.rings;
  double y = -INFINITY;
  for (int p = 0; p < r->start[r->nring]; p++) y = US_MAX(y, r->xy[2 * p + 1]);
  im->ground_y = im->set->ground_at_set ? im->set->ground_at : y;
}

/* Ring k in output coordinates into xy; checks it is finite and not
 * degenerate. */
static us_Status map_ring(Import *im, int k, double *xy) {
  const us_SvgRings *r = &im->doc.rings;
  int s = r->start[k], n = r->start[k + 1] - s;
  for (int p = 0; p < n; p++) {
    xy[2 * p] = r->xy[2 * (s + p)] * im->k[0];
    xy[2 * p + 1] = (im->ground_y - r->xy[2 * (s + p) + 1]) * im->k[1];
  }
  char at[200];
  int finite = 1;
  for (int p = 0; p < 2 * n; p++) finite &= isfinite(xy[p]) != 0;
  double d = finite ? us_poly_diameter(xy, n) : INFINITY, a = finite ? us_poly_signed_area(xy, n) : 0;
  where(im, k, at, sizeof at);
  if (!finite)
    return us_error_set(im->err, US_ERR_INPUT, "%s: a coordinate overflows in the output units (not finite)", at);
  /* area, size squared and the moment of inertia must stay doubles */
  if (!isfinite(d * d) || !isfinite(a) || !isfinite(us_poly_polar_moment(xy, n)))
    return us_error_set(im->err, US_ERR_INPUT, "%s: coordinates too large: the shape's area or "
                        "inertia overflows (its size is %g output units)", at, d);
  if (n >= 3 && fabs(a) > DEGENERATE_REL * d * d) return US_OK;
  return us_error_set(im->err, US_ERR_INPUT, "%s: degenerate shape (%s)", at,
                      n < 3 ? "fewer than 3 distinct points" : "no area");
}

static us_Status add_ring(Import *im, us_Structure *s, int k, double *xy) {
  const us_SvgShape *sh = &im->doc.shapes[k];
  us_BodyDef def = us_default_body_def();
  def.id = im->ids[k];
  def.nvert = im->doc.rings.start[k + 1] - im->doc.rings.start[k];
  def.xy = xy;
  if (sh->density > 0) def.density = sh->density;
  def.mass = sh->mass > 0 ? sh->mass : 0;
  def.fixed = sh->fixed;
  def.friction = sh->friction;
  if (us_structure_add_body(s, &def, im->err) < 0) return im->err->code;
  im->info.fixed += sh->fixed;
  return US_OK;
}

static us_Status add_bodies(Import *im, us_Structure *s) {
  const us_SvgRings *r = &im->doc.rings;
  int most = 0;
  for (int k = 0; k < r->nring; k++) most = US_MAX(most, r->start[k + 1] - r->start[k]);
  double *xy = us_malloc((size_t)(2 * most + 2) * sizeof *xy);
  if (!xy) return us_error_set(im->err, US_ERR_NOMEM, "out of memory");
  us_Status st = US_OK;
  for (int k = 0; k < r->nring && !st; k++) {
    st = map_ring(im, k, xy);
    if (!st) st = add_ring(im, s, k, xy);
  }
  us_free(xy);
  im->info.bodies = s->nbody;
  return st;
}

/* ------------------------------------------------------------- finalize */

/* Append the lines of the bodies a finalize message names ('id'). */
static void name_lines(const Import *im, const us_Structure *s, char *msg, size_t cap) {
  int found = 0;
  for (int i = 0; i < s->nbody && found < 2; i++) {
    char q[96];
    snprintf(q, sizeof q, "'%s'", us_id_text(s->bodies[i].id).s);
    if (!strstr(msg, q)) continue;
    size_t len = strlen(msg);
    snprintf(msg + len, cap - len, "%s%s is <%s> at line %ld", found ? ", " : " (",
             q, im->doc.shapes[i].kind, im->doc.shapes[i].line);
    found++;
  }
  if (found) strncat(msg, ")", cap - strlen(msg) - 1);
}

static us_Status finalize(Import *im, us_Structure *s) {
  us_Status st = us_structure_finalize(s, im->err);
  if (!st) return US_OK;
  char msg[sizeof im->err->msg];
  memcpy(msg, im->err->msg, sizeof msg);
  name_lines(im, s, msg, sizeof msg);
  if (im->info.snapped) /* what snapping did, and how to do without it */
    return us_error_set(im->err, st, "%s: %s; snapping moved %d vertices before this check "
                        "(--snap 0: none, --snap TOL: another tolerance)", im->doc.name, msg,
                        im->info.snapped);
  return us_error_set(im->err, st, "%s: %s", im->doc.name, msg);
}

static us_Status snap(Import *im, us_Structure *s) {
  double t = im->set->snap;
  if (t == 0) return US_OK;
  int m = us_svg_snap(s, t > 0 ? t * US_MIN(im->k[0], im->k[1]) : 0, SNAP_REL, im->err);
  if (m < 0) return im->err->code;
  im->info.snapped = m;
  return US_OK;
}

/* ---------------------------------------------------------------- driver */

static us_Structure *build(Import *im) {
  us_Structure *s = us_structure_new(2);
  if (!s) {
    us_error_set(im->err, US_ERR_NOMEM, "out of memory");
    return NULL;
  }
  const us_SvgSettings *set = im->set;
  s->friction = set->friction >= 0 ? set->friction : im->doc.friction >= 0 ? im->doc.friction : s->friction;
  s->ground = set->ground ? 1 : 0;
  if (set->contact_tol > 0) s->contact_tol = set->contact_tol;
  if (add_bodies(im, s) || snap(im, s) || finalize(im, s)) {
    us_structure_free(s);
    return NULL;
  }
  return s;
}

/* The XML document is freed as soon as it is walked: the structure is
 * built from the rings alone, so the two never take memory together. */
static us_Structure *import(Import *im, xmlDoc *xml, double out_unit) {
  us_Status walked = us_svg_walk(&im->doc, xml, im->err);
  xmlFreeDoc(xml);
  if (walked) return NULL;
  im->info.skipped = im->doc.skipped;
  im->info.curves = im->doc.rings.curves;
  if (im->doc.rings.nring == 0) {
    us_error_set(im->err, US_ERR_INPUT, "%s: no shapes to import (%d elements skipped)",
                 im->doc.name, im->doc.skipped);
    return NULL;
  }
  if (name_rings(im)) return NULL;
  unit_factors(im, out_unit);
  find_ground(im);
  return build(im);
}

us_Structure *us_structure_parse_svg(const char *text, size_t len, const char *name,
                                     const us_SvgSettings *set, us_SvgInfo *info, us_Error *err) {
  us_Error local;
  us_error_clear(&local);
  us_SvgSettings dflt = us_svg_default_settings();
  Import im;
  memset(&im, 0, sizeof im);
  im.set = set ? set : &dflt;
  im.err = err ? err : &local;
  im.doc.name = name ? name : "<input>";
  im.doc.flatten = im.set->flatten;
  im.doc.size = len;
  im.doc.entity_budget = ENTITY_BASE + ENTITY_PER_BYTE * len;
  im.doc.rings.max_pt = (int)US_MIN((size_t)POINTS_BASE + POINTS_PER_BYTE * len, (size_t)INT_MAX / 4);
  im.doc.warn = im.set->warn;
  im.doc.warn_user = im.set->warn_user;
  double out_unit;
  if (!text) {
    us_error_set(im.err, US_ERR_USAGE, "us_structure_parse_svg: no text");
    return NULL;
  }
  if (check_settings(im.set, im.doc.name, &out_unit, im.err)) return NULL;
  xmlDoc *xml = parse_xml(text, len, im.doc.name, im.err);
  us_Structure *s = xml ? import(&im, xml, out_unit) : NULL;
  for (int k = 0; k < im.ngen; k++) us_free(im.gen[k]);
  us_free(im.gen);
  us_free(im.ids);
  us_svg_doc_free(&im.doc);
  im.info.entity_bytes = im.doc.entity_bytes;
  if (info) *info = im.info;
  return s;
}

us_Structure *us_structure_read_svg(const char *path, const us_SvgSettings *set, us_SvgInfo *info,
                                    us_Error *err) {
  if (!path) {
    us_error_set(err, US_ERR_USAGE, "us_structure_read_svg: no path");
    return NULL;
  }
  FILE *fp = fopen(path, "rb"); /* too large: refused before it is read */
  long size = fp && !fseek(fp, 0, SEEK_END) ? ftell(fp) : -1;
  if (fp) fclose(fp);
  if (size > SVG_MAX_BYTES) {
    too_large(path, (double)size, err);
    return NULL;
  }
  size_t len = 0;
  char *text = us_io_slurp(path, &len, err);
  if (!text) return NULL;
  us_Structure *s = us_structure_parse_svg(text, len, path, set, info, err);
  us_free(text);
  return s;
}
