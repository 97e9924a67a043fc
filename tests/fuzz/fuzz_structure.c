/* Fuzz target `structure`: the structure reader, writer and renderer.
 *
 * Input: the text of a structure file. Properties checked for every input:
 *   - us_structure_parse never crashes; a rejection is an error with a
 *     message;
 *   - an accepted structure written with us_structure_write and read back
 *     is identical (bodies, vertices, masses, materials, contacts), and
 *     writing the copy again gives the same bytes;
 *   - us_render_svg writes well-formed XML (checked with libxml2 when the
 *     build has it: US_FUZZ_XML); 2D only until render draws 3D;
 *   - nothing leaks through the allocation funnel.
 * Structures beyond the caps of fuzz.h are skipped after parsing. */
#include "fuzz.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef US_FUZZ_XML
#include <libxml/parser.h>
#endif

static void round_trip(const us_Structure *s) {
  us_Error err;
  us_error_clear(&err);
  const char *p1 = fz_path(0, "s1.json"), *p2 = fz_path(1, "s2.json");
  us_Status st = us_structure_write(s, p1, &err);
  fz_check_error("write", st, &err);
  if (st != US_OK) fz_finding("a parsed structure cannot be written: %s", err.msg);
  us_Structure *back = us_structure_read(p1, 0, &err);
  if (!back) fz_finding("the written structure does not read back: %s", err.msg);
  const char *d = fz_structure_diff(s, back);
  if (d) fz_finding("read back differs: %s", d);
  st = us_structure_write(back, p2, &err);
  if (st != US_OK) fz_finding("the read-back structure cannot be written: %s", err.msg);
  size_t n1 = 0, n2 = 0;
  char *t1 = fz_slurp(p1, &n1), *t2 = fz_slurp(p2, &n2);
  if (!t1 || !t2) fz_finding("written files cannot be read");
  if (n1 != n2 || memcmp(t1, t2, n1)) fz_finding("second write differs from the first");
  free(t1);
  free(t2);
  us_structure_free(back);
}

#ifdef US_FUZZ_XML
static void xml_quiet(void *ctx, const char *msg, ...) {
  (void)ctx;
  (void)msg;
}
#endif

static void check_xml(const char *path) {
#ifdef US_FUZZ_XML
  xmlSetGenericErrorFunc(NULL, xml_quiet);
  size_t n = 0;
  char *t = fz_slurp(path, &n);
  if (!t) fz_finding("the SVG cannot be read back");
  xmlDocPtr doc = xmlReadMemory(t, (int)n, "render.svg", NULL, XML_PARSE_NONET);
  if (!doc) {
    const xmlError *e = xmlGetLastError();
    fz_finding("render wrote malformed XML: line %d: %s", e ? e->line : 0,
               e && e->message ? e->message : "?");
  }
  xmlNodePtr root = xmlDocGetRootElement(doc);
  if (!root || strcmp((const char *)root->name, "svg"))
    fz_finding("render wrote XML whose root is not <svg>");
  xmlFreeDoc(doc);
  free(t);
#else
  (void)path;
#endif
}

static void render(const us_Structure *s) {
  us_Error err;
  us_error_clear(&err);
  us_RenderSettings r = us_render_default_settings();
  const char *p = fz_path(2, "render.svg");
  us_Status st = us_render_svg(s, &r, p, &err);
  fz_check_error("render", st, &err);
  if (st != US_OK) fz_finding("a parsed structure cannot be rendered: %s", err.msg);
  check_xml(p);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size > FZ_MAX_INPUT) return 0;
  long live = us_alloc_live();
  char *text = fz_text(data, size);
  us_Error err;
  us_error_clear(&err);
  us_Structure *s = us_structure_parse(text, "input.json", 0, &err);
  if (!s && err.code == US_OK) fz_finding("parse failed without an error code");
  if (!s) fz_check_error("parse", err.code, &err);
  if (s && fz_small(s)) {
    round_trip(s);
    if (s->dim == 2) render(s);
  }
  us_structure_free(s);
  free(text);
  if (us_alloc_live() != live)
    fz_finding("%ld blocks leaked through the allocation funnel", us_alloc_live() - live);
  return 0;
}
