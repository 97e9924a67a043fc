/* Fuzz target `svg`: the SVG importer (us_structure_parse_svg) from a
 * byte buffer.
 *
 * Input: the bytes of a drawing. Each input is imported twice, with the
 * default settings and with root user units, no snapping and no ground.
 * Properties checked for every input:
 *   - the import never crashes; a rejection is an error with a message
 *     that names the file ("input.svg");
 *   - the work of entity references stays within the budget of
 *     docs/svg.md (info.entity_bytes <= 1 MiB + 4 x the input size);
 *   - an accepted structure is finalized, and (within the caps of fuzz.h)
 *     written as a structure file it reads back identical;
 *   - nothing leaks through the allocation funnel. */
#include "fuzz.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void quiet(const char *msg, void *user) {
  (void)msg;
  (void)user;
}

static void round_trip(const us_Structure *s) {
  us_Error err;
  us_error_clear(&err);
  const char *p = fz_path(0, "svg.json");
  us_Status st = us_structure_write(s, p, &err);
  if (st != US_OK) fz_finding("an imported structure cannot be written: %s", err.msg);
  us_Structure *back = us_structure_read(p, 0, &err);
  if (!back) fz_finding("the imported structure does not read back: %s", err.msg);
  const char *d = fz_structure_diff(s, back);
  if (d) fz_finding("imported structure read back differs: %s", d);
  us_structure_free(back);
}

static void import(const char *text, size_t size, int raw) {
  us_SvgSettings set = us_svg_default_settings();
  set.warn = quiet;
  if (raw) set.unit = "user", set.snap = 0, set.ground = 0;
  us_SvgInfo info;
  us_Error err;
  us_error_clear(&err);
  us_Structure *s = us_structure_parse_svg(text, size, "input.svg", &set, &info, &err);
  if (!s) {
    fz_check_error("import", err.code, &err);
    if (err.code != US_ERR_NOMEM && !strstr(err.msg, "input.svg"))
      fz_finding("an import error does not name the file: %s", err.msg);
  }
  if (info.entity_bytes > ((size_t)1 << 20) + 4 * size)
    fz_finding("entity references expanded to %zu bytes, over the budget", info.entity_bytes);
  if (s && fz_small(s)) round_trip(s);
  us_structure_free(s);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size > FZ_MAX_INPUT) return 0;
  long live = us_alloc_live();
  char *text = fz_text(data, size);
  import(text, size, 0);
  import(text, size, 1);
  free(text);
  if (us_alloc_live() != live)
    fz_finding("%ld blocks leaked through the allocation funnel", us_alloc_live() - live);
  return 0;
}
