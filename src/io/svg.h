/* Private pieces of the SVG import (docs/svg.md), one file each:
 *   svg_lex.c     numbers, lengths with units, transform lists, style
 *                 properties: text -> values, no XML;
 *   svg_path.c    rings (closed outlines) in root coordinates: path data
 *                 and basic shapes, curves flattened;
 *   svg_walk.c    the XML tree: groups, transforms, visibility, ids,
 *                 fixed marks and materials -> rings with their metadata;
 *   svg_snap.c    vertices that nearly touch another body or the ground
 *                 moved onto it;
 *   svg_import.c  the driver and the public entry points.
 * Coordinates here are the drawing's root user units (the viewBox's), y
 * pointing down as in the file, until svg_import.c maps them to the
 * structure's (y up, the ground at y = 0). */
#ifndef US_IO_SVG_H
#define US_IO_SVG_H

#include "core/core.h"

/* Affine map of SVG's matrix(a b c d e f): x' = a x + c y + e,
 * y' = b x + d y + f. */
typedef struct us_SvgMatrix {
  double a, b, c, d, e, f;
} us_SvgMatrix;

us_SvgMatrix us_svg_identity(void);
/* The map "n, then m" (m * n as matrices): a child's transform n inside a
 * parent whose map is m. */
us_SvgMatrix us_svg_mul(us_SvgMatrix m, us_SvgMatrix n);
void us_svg_apply(const us_SvgMatrix *m, double x, double y, double out[2]);

/* ---------------------------------------------------------------- lex */

/* Skip white space and at most one comma (SVG's comma-wsp). */
const char *us_svg_skip_sep(const char *p);
const char *us_svg_skip_ws(const char *p);
/* One number in SVG's grammar ([sign] digits [. digits] [e [sign] digits],
 * no "inf" or "nan") at *p after white space: 1 read (*p advanced), 0 no
 * number there, -1 a number whose value is not finite (1e999). */
int us_svg_number(const char **p, double *out);
/* A whole attribute holding one length: a number and an optional unit
 * (px, mm, cm, in, pt, pc, q), in user units (px). 0 ok; -1 not a length;
 * -2 a unit that needs a context (%, em, ex, ...); -3 not finite. */
int us_svg_length(const char *s, double *out);
/* The same, as the number and the size of its unit in metres (px when
 * none is given). */
int us_svg_length_unit(const char *s, double *num, double *unit_m);
/* Size of one unit ("m", "cm", "mm", "in", "pt", "pc", "px", "q") in metres;
 * 0 for an unknown word. */
double us_svg_unit_metres(const char *unit, size_t len);
/* A transform list into *out (identity for an empty list); US_ERR_PARSE
 * with a message naming the bad part. */
us_Status us_svg_transform(const char *s, us_SvgMatrix *out, us_Error *err);
/* The value of property `name` in a style attribute ("a: b; c: d"),
 * copied into buf (trimmed); 1 found, 0 not. */
int us_svg_style_get(const char *style, const char *name, char *buf, size_t cap);

/* ---------------------------------------------------------------- rings */

/* Closed outlines in root coordinates: ring k is xy[2*start[k] ..
 * 2*start[k+1]), start has nring + 1 entries. A ring is open while being
 * built (between begin and end). */
typedef struct us_SvgRings {
  double *xy;
  int npt, cap_pt;
  int *start;
  int nring, cap_start;
  int curves;       /* curve segments flattened so far */
  int max_pt;       /* points allowed in all (> 0) */
} us_SvgRings;

void us_svg_rings_free(us_SvgRings *r);
/* Start a ring; 0 or -1 on OOM. */
int us_svg_ring_begin(us_SvgRings *r);
/* Append m(x, y) to the open ring; consecutive repeats are dropped.
 * 0, -1 OOM, -2 the mapped point is not finite, -3 r->max_pt reached. */
int us_svg_ring_point(us_SvgRings *r, const us_SvgMatrix *m, double x, double y);
/* The error for a failed us_svg_ring_point's code rc. */
us_Status us_svg_ring_error(const us_SvgRings *r, int rc, us_Error *err);
/* Close the open ring (its last point dropped when it repeats the first):
 * 1 kept, 0 dropped (closed == 0: an open outline whose ends differ). */
int us_svg_ring_end(us_SvgRings *r, int closed);
/* Drop every ring from number k on (an element that failed). */
void us_svg_rings_truncate(us_SvgRings *r, int k);

/* Curve flattening (svg_path.c): a curve is replaced by a polyline within
 * `flatten` times the curve's own size of it (docs/svg.md). */
typedef struct us_SvgPathOpts {
  double flatten;   /* relative tolerance, > 0 */
  int open_rings;   /* out: subpaths left open (not closed, ends differ) */
} us_SvgPathOpts;

/* Path data `d` under map m into rings, one per subpath (open subpaths
 * are dropped and counted). US_ERR_PARSE naming the command and the
 * character offset on bad data; US_ERR_NOMEM. */
us_Status us_svg_path(us_SvgRings *r, const char *d, const us_SvgMatrix *m, us_SvgPathOpts *o,
                      us_Error *err);
/* The ellipse (cx, cy, rx, ry) as one ring. */
us_Status us_svg_ellipse(us_SvgRings *r, const us_SvgMatrix *m, double cx, double cy, double rx,
                         double ry, double flatten, us_Error *err);

/* ---------------------------------------------------------------- walk */

/* One ring's origin: the element it came from and what it says. */
typedef struct us_SvgShape {
  char *id;         /* the element's id (owned), or NULL */
  const char *kind; /* element name (static): generated ids and messages */
  long line;
  int fixed;
  double density;   /* > 0 given */
  double mass;      /* > 0 given */
  double friction;  /* >= 0 given (INFINITY: "infinite"), else -1 */
} us_SvgShape;

/* What the walk produced: ring k came from shapes[k]. */
typedef struct us_SvgDoc {
  const char *name; /* file name for messages */
  us_SvgRings rings;
  us_SvgShape *shapes;
  int cap_shape;
  double unit_metres[2]; /* size of a root user unit in metres, x and y
                            (0: the drawing gives no physical size) */
  double friction;  /* the root's data-friction, or -1 */
  double flatten;
  int skipped;      /* elements skipped with a warning */
  size_t size;      /* bytes of the file */
  size_t entity_budget; /* what entity references in attribute values may
                           add to the whole document (svg_walk.c) */
  size_t entity_bytes;  /* what they added, checked before the walk */
  void (*warn)(const char *msg, void *user);
  void *warn_user;
} us_SvgDoc;

void us_svg_doc_free(us_SvgDoc *d);
/* Walk the parsed document (an xmlDoc *, kept opaque here). */
us_Status us_svg_walk(us_SvgDoc *d, void *xml_doc, us_Error *err);

/* ---------------------------------------------------------------- snap */

/* Snap vertices of s's bodies (not finalized; coordinates y up, the ground
 * y = 0 when s->ground): tol_abs > 0 one tolerance, else each pair's
 * rel * its smaller bounding-box diagonal. Returns vertices moved, or -1
 * (err set: out of memory). */
int us_svg_snap(us_Structure *s, double tol_abs, double rel, us_Error *err);

#endif
