/* The SVG element tree -> rings with their origin (docs/svg.md).
 *
 * A depth-first walk in document order carries the inherited state of
 * each level: the map from the element's user space to the root's (the
 * parent's map times the element's `transform`), visibility, the fixed
 * mark and the materials given by an ancestor. Groups (g, a, switch,
 * nested svg) pass it on; shapes (rect, polygon, polyline, path, circle,
 * ellipse) turn into rings in root coordinates, each remembered with its
 * element (id, line, kind, fixed, materials) in doc->shapes, parallel to
 * doc->rings. What is never drawn (defs, clipPath, mask, symbol, marker,
 * pattern, gradients, filters, metadata, title, desc, style, script, and
 * elements of other namespaces such as sodipodi:namedview) is skipped
 * silently; what is drawn but is no block (text, image, line, use, open
 * outlines, hidden elements, unknown SVG elements) is skipped with a
 * warning through doc->warn. Every error names the file, the element's
 * line and the element.
 *
 * The root's viewBox sets the root user units that every coordinate is
 * given in; its width and height (with units) give their physical size,
 * doc->unit_metres (px when there is no physical size). The walk's cost is
 * linear in the document's size; its recursion depth is libxml2's element
 * depth limit (256). */
#include "svg.h"

#include <libxml/tree.h>
#include <math.h>
#include <stdarg.h>
#include <string.h>

#define SVG_NS "http://www.w3.org/2000/svg"
#define INKSCAPE_NS "http://www.inkscape.org/namespaces/inkscape"
#define PX_METRES (0.0254 / 96)
#define SVG_ENTITY_DEPTH 40 /* entity references within entities */

/* What an element inherits. */
typedef struct Ctx {
  us_SvgMatrix m;
  int hidden;       /* visibility: hidden from an ancestor */
  int fixed;
  double density;   /* > 0 given */
  double friction;  /* >= 0 given, else -1 */
} Ctx;

typedef struct Walk {
  us_SvgDoc *d;
  us_Error *err;
  const char *root_ns; /* the root element's namespace name */
} Walk;

/* ---------------------------------------------------------------- helpers */

static const char *name_of(const xmlNode *n) { return (const char *)n->name; }

static const char *ns_of(const xmlNode *n) {
  return n->ns && n->ns->href ? (const char *)n->ns->href : "";
}

/* SVG's namespace, none, or the root's own: old Illustrator files declare
 * xmlns="&ns_svg;" through an internal entity, which libxml2 leaves
 * unexpanded in the namespace name (entities are not substituted here). */
static int is_svg(const Walk *w, const xmlNode *n) {
  const char *ns = ns_of(n);
  return !*ns || !strcmp(ns, SVG_NS) || !strcmp(ns, w->root_ns);
}

/* ---------------------------------------------------------------- entities */

/* Attribute values are expanded here, not by xmlGetNoNsProp: libxml2
 * expands the entity references of a value only when it is read, outside
 * its parser's amplification guard, by repeated concatenation (quadratic
 * time). Ours is linear and bounded. Before the walk, check_entities()
 * measures every value that holds a reference against one budget for the
 * whole document, d->entity_budget; each reference costs its expansion
 * plus one (so that deep chains of empty entities count too). A drawing
 * over the budget is refused naming the element and the attribute. Past
 * that check a value costs its size each time it is read, and the walk
 * reads each attribute of an element a bounded number of times. */
typedef struct Expand {
  char *buf;        /* xmlMalloc'ed value; NULL: count only */
  size_t len, cap;
  size_t cost;      /* bytes plus references so far */
  size_t limit;     /* the cost allowed */
} Expand;

enum { EXP_OK, EXP_OVER, EXP_DEEP, EXP_NOMEM };

static int put(Expand *x, const char *s, size_t n) {
  if (n > x->limit - x->cost) return EXP_OVER;
  x->cost += n;
  if (!x->buf) return EXP_OK;
  if (x->len + n + 1 > x->cap) {
    size_t cap = US_MAX(2 * x->cap, x->len + n + 1);
    char *b = xmlRealloc(x->buf, cap);
    if (!b) return EXP_NOMEM;
    x->buf = b, x->cap = cap;
  }
  memcpy(x->buf + x->len, s, n);
  x->len += n;
  x->buf[x->len] = '\0';
  return EXP_OK;
}

static int expand_list(const xmlDoc *doc, const xmlNode *k, Expand *x, int depth) {
  int r = EXP_OK;
  for (; k && !r; k = k->next) {
    if (k->type == XML_TEXT_NODE || k->type == XML_CDATA_SECTION_NODE) {
      const char *t = k->content ? (const char *)k->content : "";
      r = put(x, t, strlen(t));
    } else if (k->type == XML_ENTITY_REF_NODE) {
      const xmlEntity *e = xmlGetDocEntity(doc, k->name);
      if (depth >= SVG_ENTITY_DEPTH) return EXP_DEEP;
      if (x->cost >= x->limit) return EXP_OVER;
      x->cost++;
      if (!e) r = k->content ? put(x, (const char *)k->content, strlen((const char *)k->content)) : EXP_OK;
      else r = expand_list(doc, e->children, x, depth + 1);
    }
  }
  return r;
}

static int has_reference(const xmlAttr *a) {
  for (const xmlNode *k = a->children; k; k = k->next)
    if (k->type == XML_ENTITY_REF_NODE) return 1;
  return 0;
}

/* A's value (xmlFree it), at most the whole budget long; NULL when it is
 * longer (never after check_entities) or out of memory (as libxml2's own
 * reader: its allocations are not the library's funnel). */
static char *attr_value(const Walk *w, const xmlAttr *a) {
  if (!a) return NULL;
  const xmlNode *k = a->children;
  if (!k || (!k->next && k->type == XML_TEXT_NODE)) /* the common case: one text */
    return (char *)xmlStrdup(k && k->content ? k->content : (const xmlChar *)"");
  Expand x = {xmlMalloc(1), 0, 1, 0, w->d->entity_budget};
  if (!x.buf) return NULL;
  x.buf[0] = '\0';
  if (expand_list(a->doc, k, &x, 0) == EXP_OK) return x.buf;
  xmlFree(x.buf);
  return NULL;
}

/* The attribute `name` of n in namespace ns (NULL: none) as written on
 * the element: defaults a DTD declares are not looked up (xmlHasNsProp
 * would, and their values would escape the entity budget). */
static const xmlAttr *find_attr(const xmlNode *n, const char *name, const char *ns) {
  for (const xmlAttr *a = n->properties; a; a = a->next)
    if (!strcmp((const char *)a->name, name) &&
        (ns ? a->ns && a->ns->href && !strcmp((const char *)a->ns->href, ns) : !a->ns))
      return a;
  return NULL;
}

/* An attribute without namespace (xmlFree it), or NULL. */
static char *attr(const Walk *w, const xmlNode *n, const char *name) {
  return attr_value(w, find_attr(n, name, NULL));
}

/* "<rect id='a'>" for messages. */
static void describe(const Walk *w, const xmlNode *n, char *buf, size_t cap) {
  char *id = attr(w, n, "id");
  if (id) snprintf(buf, cap, "<%s id='%s'>", name_of(n), us_id_text(id).s);
  else snprintf(buf, cap, "<%s>", name_of(n));
  xmlFree(id);
}

/* Set err to "NAME:LINE: <elem>: message". */
static us_Status fail(Walk *w, const xmlNode *n, us_Status code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static us_Status fail(Walk *w, const xmlNode *n, us_Status code, const char *fmt, ...) {
  char what[160], msg[sizeof w->err->msg];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  describe(w, n, what, sizeof what);
  return us_error_set(w->err, code, "%s:%ld: %s: %s", w->d->name, xmlGetLineNo(n), what, msg);
}

/* Prefix a message set by a lexer or path function. */
static us_Status reframe(Walk *w, const xmlNode *n, us_Status st) {
  char msg[sizeof w->err->msg];
  memcpy(msg, w->err->msg, sizeof msg);
  return fail(w, n, st, "%s", msg);
}

/* A warning "NAME:LINE: <elem>: text" through doc->warn. */
static void tell(Walk *w, const xmlNode *n, const char *text) {
  if (!w->d->warn) return;
  char what[160], msg[400];
  describe(w, n, what, sizeof what);
  snprintf(msg, sizeof msg, "%s:%ld: %s: %s", w->d->name, xmlGetLineNo(n), what, text);
  w->d->warn(msg, w->d->warn_user);
}

static void warn(Walk *w, const xmlNode *n, const char *why) {
  char text[200];
  w->d->skipped++;
  snprintf(text, sizeof text, "skipped (%s)", why);
  tell(w, n, text);
}

/* A length attribute in user units; absent: *out = dflt. */
static us_Status length_attr(Walk *w, const xmlNode *n, const char *name, double dflt,
                             double *out) {
  char *v = attr(w, n, name);
  *out = dflt;
  int r = v ? us_svg_length(v, out) : 0;
  xmlFree(v);
  if (r == -1) return fail(w, n, US_ERR_PARSE, "%s is not a length", name);
  if (r == -2) return fail(w, n, US_ERR_PARSE, "%s: relative units (%%, em, ex) are not supported", name);
  if (r == -3) return fail(w, n, US_ERR_PARSE, "%s is not finite", name);
  return US_OK;
}

/* A positive length that must be given (rect width, circle r). */
static us_Status size_attr(Walk *w, const xmlNode *n, const char *name, double *out) {
  if (length_attr(w, n, name, NAN, out)) return US_ERR_PARSE;
  if (isnan(*out)) return fail(w, n, US_ERR_INPUT, "%s is missing", name);
  if (!(*out > 0)) return fail(w, n, US_ERR_INPUT, "degenerate: %s is %g (must be > 0)", name, *out);
  return US_OK;
}

/* ---------------------------------------------------------------- marks */

/* s[0 .. len) is the word w, ASCII letters in any case. */
static int word_is(const char *s, size_t len, const char *w) {
  if (strlen(w) != len) return 0;
  for (size_t k = 0; k < len; k++) {
    char a = s[k] >= 'A' && s[k] <= 'Z' ? (char)(s[k] + 32) : s[k];
    if (a != w[k]) return 0;
  }
  return 1;
}

/* Does the white-space separated list s hold the word w (case-insensitive)?
 * first: only its first word counts. */
static int has_word(const char *s, const char *w, int first) {
  for (const char *p = us_svg_skip_ws(s); *p; p = us_svg_skip_ws(p)) {
    const char *e = p;
    while (*e && *e != ' ' && *e != '\t' && *e != '\n' && *e != '\r') e++;
    if (word_is(p, (size_t)(e - p), w)) return 1;
    if (first) return 0;
    p = e;
  }
  return 0;
}

/* An id "fixed", or "fixed" then '_', '-' or a digit: Illustrator writes
 * a layer named "fixed" as <g id="fixed">, a second one as "fixed_1_". */
static int id_fixed(const char *id) {
  if (!id || !word_is(id, US_MIN(strlen(id), 5), "fixed")) return 0;
  char c = id[5];
  return !c || c == '_' || c == '-' || (c >= '0' && c <= '9');
}

/* class="... fixed ...", data-fixed (anything but "false" / "0"), an
 * inkscape:label whose first word is "fixed", or an id as above. */
static int marked_fixed(const Walk *w, const xmlNode *n) {
  char *c = attr(w, n, "class"), *df = attr(w, n, "data-fixed"), *id = attr(w, n, "id");
  char *lab = attr_value(w, find_attr(n, "label", INKSCAPE_NS));
  int f = (c && has_word(c, "fixed", 0)) || (lab && has_word(lab, "fixed", 1)) ||
          (df && strcmp(df, "false") && strcmp(df, "0")) || id_fixed(id);
  xmlFree(c), xmlFree(df), xmlFree(lab), xmlFree(id);
  return f;
}

/* data-NAME as a number >= 0 (> 0 when positive), or "infinite" when
 * inf_ok; absent: *out unchanged. */
static us_Status material(Walk *w, const xmlNode *n, const char *name, int positive, int inf_ok,
                          double *out) {
  char *v = attr(w, n, name);
  if (!v) return US_OK;
  const char *p = v;
  double x;
  int r = us_svg_number(&p, &x);
  if (inf_ok && !strcmp(us_svg_skip_ws(v), "infinite")) r = 1, x = INFINITY, p = v + strlen(v);
  int ok = r == 1 && !*us_svg_skip_ws(p) && (positive ? x > 0 : x >= 0);
  xmlFree(v);
  if (!ok)
    return fail(w, n, US_ERR_INPUT, "%s must be a number %s%s", name, positive ? "> 0" : ">= 0",
                inf_ok ? " or \"infinite\"" : "");
  *out = x;
  return US_OK;
}

/* --------------------------------------------------------- state per level */

/* display="none" (attribute or style): 1; visibility: sets ctx->hidden. */
static int display_none(const Walk *w, const xmlNode *n, Ctx *c) {
  char *disp = attr(w, n, "display"), *vis = attr(w, n, "visibility"), *style = attr(w, n, "style");
  char sd[32] = "", sv[32] = ""; /* the style property wins over the attribute */
  if (style) {
    us_svg_style_get(style, "display", sd, sizeof sd);
    us_svg_style_get(style, "visibility", sv, sizeof sv);
  }
  const char *v = sv[0] ? sv : vis;
  if (v) c->hidden = !strcmp(v, "hidden") || !strcmp(v, "collapse");
  int none = !strcmp(sd, "none") || (!sd[0] && disp && !strcmp(disp, "none"));
  xmlFree(disp), xmlFree(vis), xmlFree(style);
  return none;
}

/* The element's own contribution to the inherited state. */
static us_Status enter(Walk *w, const xmlNode *n, Ctx *c) {
  char *t = attr(w, n, "transform");
  if (t) {
    us_SvgMatrix m;
    us_Status st = us_svg_transform(t, &m, w->err);
    xmlFree(t);
    if (st) return reframe(w, n, st);
    c->m = us_svg_mul(c->m, m);
  }
  c->fixed |= marked_fixed(w, n);
  if (material(w, n, "data-density", 1, 0, &c->density)) return US_ERR_INPUT;
  return material(w, n, "data-friction", 0, 1, &c->friction);
}

/* ---------------------------------------------------------------- shapes */

/* Shape elements by kind (their names outlive the XML document) */
static const char *const shapes[] = {"rect", "polygon", "polyline", "circle", "ellipse", "path", NULL};

static us_Status ring_status(Walk *w, const xmlNode *n, int rc) {
  if (!rc) return US_OK;
  us_Status st = us_svg_ring_error(&w->d->rings, rc, w->err);
  return st == US_ERR_NOMEM ? st : reframe(w, n, st);
}

static us_Status do_rect(Walk *w, const xmlNode *n, const Ctx *c) {
  double x, y, wd, ht, rx, ry;
  if (length_attr(w, n, "x", 0, &x) || length_attr(w, n, "y", 0, &y) ||
      size_attr(w, n, "width", &wd) || size_attr(w, n, "height", &ht) ||
      length_attr(w, n, "rx", 0, &rx) || length_attr(w, n, "ry", 0, &ry))
    return w->err->code;
  if (rx > 0 || ry > 0) tell(w, n, "rounded corners ignored: imported with square corners");
  us_SvgRings *r = &w->d->rings;
  int rc = us_svg_ring_begin(r);
  double px[4] = {x, x + wd, x + wd, x}, py[4] = {y, y, y + ht, y + ht};
  for (int k = 0; k < 4 && !rc; k++) rc = us_svg_ring_point(r, &c->m, px[k], py[k]);
  if (!rc) us_svg_ring_end(r, 1);
  return ring_status(w, n, rc);
}

static us_Status do_points(Walk *w, const xmlNode *n, const Ctx *c, int closed) {
  char *pts = attr(w, n, "points");
  if (!pts) return fail(w, n, US_ERR_INPUT, "no points");
  us_SvgRings *r = &w->d->rings;
  int rc = us_svg_ring_begin(r), cnt = 0, k = 0;
  const char *p = pts;
  double v[2];
  while (!rc && (k = us_svg_number(&p, &v[cnt % 2])) == 1) {
    if (++cnt % 2 == 0) rc = us_svg_ring_point(r, &c->m, v[0], v[1]);
    p = us_svg_skip_sep(p);
  }
  int trailing = *us_svg_skip_ws(p) != '\0';
  xmlFree(pts);
  if (rc) return ring_status(w, n, rc);
  if (k < 0) return fail(w, n, US_ERR_PARSE, "points: a number is not finite");
  if (trailing || cnt % 2) return fail(w, n, US_ERR_PARSE, "points: not a list of x,y pairs");
  if (!us_svg_ring_end(r, closed)) warn(w, n, "an open polyline: its ends differ");
  return US_OK;
}

static us_Status do_ellipse(Walk *w, const xmlNode *n, const Ctx *c, int circle) {
  double cx, cy, rx, ry;
  if (length_attr(w, n, "cx", 0, &cx) || length_attr(w, n, "cy", 0, &cy)) return w->err->code;
  if (circle ? size_attr(w, n, "r", &rx) : (size_attr(w, n, "rx", &rx) || size_attr(w, n, "ry", &ry)))
    return w->err->code;
  if (circle) ry = rx;
  us_Status st = us_svg_ellipse(&w->d->rings, &c->m, cx, cy, rx, ry, w->d->flatten, w->err);
  return st ? reframe(w, n, st) : US_OK;
}

static us_Status do_path(Walk *w, const xmlNode *n, const Ctx *c) {
  char *d = attr(w, n, "d");
  if (!d) return fail(w, n, US_ERR_INPUT, "no path data (d)");
  us_SvgPathOpts o = {w->d->flatten, 0};
  us_Status st = us_svg_path(&w->d->rings, d, &c->m, &o, w->err);
  xmlFree(d);
  if (st) return st == US_ERR_NOMEM ? st : reframe(w, n, st);
  if (o.open_rings) warn(w, n, o.open_rings > 1 ? "open subpaths: not closed by Z" : "an open subpath: not closed by Z");
  return US_OK;
}

/* Metadata for the rings from `first` on, made by element n. On failure
 * nothing of it is kept (the caller drops the rings). */
static us_Status record(Walk *w, const xmlNode *n, const Ctx *c, int kind, int first) {
  us_SvgDoc *d = w->d;
  if (US_GROW(d->shapes, d->cap_shape, d->rings.nring))
    return us_error_set(w->err, US_ERR_NOMEM, "out of memory");
  us_SvgShape sh = {NULL, shapes[kind], xmlGetLineNo(n), c->fixed, c->density, 0, c->friction};
  if (material(w, n, "data-mass", 1, 0, &sh.mass)) return US_ERR_INPUT;
  char *id = attr(w, n, "id");
  int k = first, oom = 0;
  for (; k < d->rings.nring && !oom; k++) {
    d->shapes[k] = sh;
    oom = id && !(d->shapes[k].id = us_strdup(id));
  }
  xmlFree(id);
  if (!oom) return US_OK;
  while (k-- > first) us_free(d->shapes[k].id);
  return us_error_set(w->err, US_ERR_NOMEM, "out of memory");
}

static us_Status do_shape(Walk *w, const xmlNode *n, const Ctx *c, int kind) {
  if (c->hidden) return warn(w, n, "hidden"), US_OK;
  int first = w->d->rings.nring;
  us_Status st = kind == 0 ? do_rect(w, n, c)
                 : kind <= 2 ? do_points(w, n, c, kind == 1)
                 : kind <= 4 ? do_ellipse(w, n, c, kind == 3)
                             : do_path(w, n, c);
  if (!st && w->d->rings.nring > first) st = record(w, n, c, kind, first);
  if (st) us_svg_rings_truncate(&w->d->rings, first);
  return st;
}

/* ---------------------------------------------------------------- tree */

static const char *const groups[] = {"g", "a", "switch", "svg", NULL};
static const char *const silent[] = {"defs", "clipPath", "mask", "symbol", "marker", "pattern",
                                     "linearGradient", "radialGradient", "filter", "metadata",
                                     "title", "desc", "style", "script", NULL};

static int find(const char *const *list, const char *name) {
  for (int k = 0; list[k]; k++)
    if (!strcmp(list[k], name)) return k;
  return -1;
}

static const char *skip_reason(const char *name) {
  if (!strcmp(name, "text")) return "text is not a block";
  if (!strcmp(name, "image")) return "an image is not a block";
  if (!strcmp(name, "line")) return "a line has no area";
  if (!strcmp(name, "use")) return "<use> copies are not imported";
  return "not a shape unstack imports";
}

static us_Status walk_children(Walk *w, const xmlNode *n, const Ctx *c);

/* A nested svg: x, y and its viewBox scaled into width x height. */
static us_Status nested_svg(Walk *w, const xmlNode *n, Ctx *c) {
  double x, y, wd, ht;
  if (length_attr(w, n, "x", 0, &x) || length_attr(w, n, "y", 0, &y) ||
      length_attr(w, n, "width", NAN, &wd) || length_attr(w, n, "height", NAN, &ht))
    return w->err->code;
  us_SvgMatrix t = {1, 0, 0, 1, x, y};
  char *vb = attr(w, n, "viewBox");
  const char *p = vb;
  double v[4];
  int k = 0;
  while (vb && k < 4 && us_svg_number(&p, &v[k]) == 1) k++, p = us_svg_skip_sep(p);
  xmlFree(vb);
  if (k == 4 && v[2] > 0 && v[3] > 0 && wd > 0 && ht > 0) {
    double s = US_MIN(wd / v[2], ht / v[3]);
    t = us_svg_mul(t, (us_SvgMatrix){s, 0, 0, s, -s * v[0], -s * v[1]});
  }
  c->m = us_svg_mul(c->m, t);
  return US_OK;
}

static us_Status walk_element(Walk *w, const xmlNode *n, Ctx c) {
  if (!is_svg(w, n)) return US_OK; /* editors' own elements */
  const char *name = name_of(n);
  if (find(silent, name) >= 0) return US_OK;
  int kind = find(shapes, name), group = find(groups, name);
  if (display_none(w, n, &c)) return warn(w, n, "display: none"), US_OK;
  if (kind < 0 && group < 0) return warn(w, n, skip_reason(name)), US_OK;
  if (group == 3 && nested_svg(w, n, &c)) return w->err->code;
  if (enter(w, n, &c)) return w->err->code;
  if (kind >= 0) return do_shape(w, n, &c, kind);
  return walk_children(w, n, &c);
}

static us_Status walk_children(Walk *w, const xmlNode *n, const Ctx *c) {
  for (const xmlNode *k = n->children; k; k = k->next)
    if (k->type == XML_ELEMENT_NODE) {
      us_Status st = walk_element(w, k, *c);
      if (st) return st;
    }
  return US_OK;
}

/* ---------------------------------------------------------------- entities */

/* Every attribute value that holds an entity reference, of n and the
 * elements below it, measured against what is left of the budget. */
static us_Status check_entities(Walk *w, const xmlNode *n) {
  us_SvgDoc *d = w->d;
  for (const xmlAttr *a = n->properties; a; a = a->next) {
    if (!has_reference(a)) continue;
    Expand x = {NULL, 0, 0, 0, d->entity_budget - d->entity_bytes};
    int r = expand_list(a->doc, a->children, &x, 0);
    d->entity_bytes += x.cost;
    if (r == EXP_DEEP)
      return fail(w, n, US_ERR_INPUT, "attribute '%s': entities nested deeper than %d levels",
                  (const char *)a->name, SVG_ENTITY_DEPTH);
    if (r)
      return fail(w, n, US_ERR_INPUT,
                  "attribute '%s': entity references expand past %zu bytes, the limit for "
                  "this %zu-byte file (an entity bomb?)",
                  (const char *)a->name, d->entity_budget, d->size);
  }
  for (const xmlNode *k = n->children; k; k = k->next)
    if (k->type == XML_ELEMENT_NODE && check_entities(w, k)) return w->err->code;
  return US_OK;
}

/* ---------------------------------------------------------------- root */

/* The root's width or height: the number and its unit's size in metres;
 * absent or 0: *num = 0. */
static us_Status root_size(Walk *w, const xmlNode *n, const char *name, double *num, double *um) {
  char *v = attr(w, n, name);
  *num = 0, *um = PX_METRES;
  int r = v ? us_svg_length_unit(v, num, um) : 0;
  int pct = v && strchr(v, '%');
  xmlFree(v);
  if (pct) return *num = 0, US_OK; /* a size relative to the viewer: none */
  if (r == -2) return fail(w, n, US_ERR_PARSE, "%s: relative units (em, ex) are not supported", name);
  if (r || *num < 0) return fail(w, n, US_ERR_PARSE, "%s is not a length >= 0", name);
  return US_OK;
}

/* The root's size of one user unit in metres, per axis: the viewport's
 * number per viewBox unit times the viewport unit, kept apart until the
 * end so that "160mm" over a viewBox 160 wide is exactly 1 mm. */
static us_Status root_units(Walk *w, const xmlNode *n) {
  double wd, ht, uw, uh, v[4];
  if (root_size(w, n, "width", &wd, &uw) || root_size(w, n, "height", &ht, &uh)) return w->err->code;
  char *vb = attr(w, n, "viewBox"), *par = attr(w, n, "preserveAspectRatio");
  const char *p = vb;
  int k = 0;
  while (vb && k < 4 && us_svg_number(&p, &v[k]) == 1) k++, p = us_svg_skip_sep(p);
  int bad = vb && (k < 4 || *us_svg_skip_ws(p) || !(v[2] > 0) || !(v[3] > 0));
  int none = par && has_word(par, "none", 1), slice = par && has_word(par, "slice", 0);
  xmlFree(vb), xmlFree(par);
  if (bad) return fail(w, n, US_ERR_PARSE, "viewBox must be four numbers: min-x min-y width > 0 height > 0");
  double sx = PX_METRES, sy = PX_METRES; /* metres per user unit */
  if (vb && (wd > 0 || ht > 0)) {
    sx = wd > 0 ? wd / v[2] * uw : ht / v[3] * uh;
    sy = ht > 0 ? ht / v[3] * uh : sx;
    if (!none) sx = sy = slice ? US_MAX(sx, sy) : US_MIN(sx, sy);
  }
  w->d->unit_metres[0] = sx;
  w->d->unit_metres[1] = sy;
  return US_OK;
}

us_Status us_svg_walk(us_SvgDoc *d, void *xml_doc, us_Error *err) {
  const xmlNode *root = xmlDocGetRootElement((xmlDoc *)xml_doc);
  if (!root) return us_error_set(err, US_ERR_PARSE, "%s: empty document", d->name);
  Walk w = {d, err, ns_of(root)};
  const char *ns = w.root_ns;
  if (check_entities(&w, root)) return err->code;
  if (strcmp(name_of(root), "svg") || (*ns && strcmp(ns, SVG_NS) && !strchr(ns, '&')))
    return fail(&w, root, US_ERR_PARSE, "not an SVG drawing (the root element must be <svg>%s%s)",
                *ns ? " in the SVG namespace, not " : "", ns);
  if (root_units(&w, root)) return err->code;
  Ctx c = {us_svg_identity(), 0, 0, -1, -1};
  double mu = -1;
  if (material(&w, root, "data-friction", 0, 1, &mu)) return err->code;
  d->friction = mu;
  Ctx top = c;
  if (display_none(&w, root, &top)) return US_OK;
  if (enter(&w, root, &top)) return err->code;
  top.friction = -1; /* the root's friction is the structure's default */
  return walk_children(&w, root, &top);
}

void us_svg_doc_free(us_SvgDoc *d) {
  for (int k = 0; k < d->rings.nring && d->shapes; k++) us_free(d->shapes[k].id);
  us_free(d->shapes);
  us_svg_rings_free(&d->rings);
  d->shapes = NULL;
  d->cap_shape = 0;
}
