/* Box piles from bytes: the second input form of the `pipeline` and `oom`
 * targets. Mutated JSON mostly fails to parse, so the planner and the
 * stability methods would see few structures; here every byte string is a
 * valid pile, built as the text of a structure file (so it still goes
 * through the reader).
 *
 * Bytes: the first gives the friction (b / 32: 0 to ~8, 0 included), then
 * three bytes per box: x (low 5 bits, in quarter units), width (low 4
 * bits: 1 to 16 quarters), height (low 3 bits: 1 to 8 eighths; bit 6:
 * fixed; bit 7: density 3). Each box is dropped onto the skyline of the
 * boxes before it (a quarter-unit grid 48 cells wide), so boxes never
 * overlap and every contact is exact in binary floating point: piles with
 * centres of mass exactly above an edge, the degenerate cases where
 * methods are most likely to disagree. At most FZ_MAX_BODIES boxes. */
#include "fuzz.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CELLS 48

static size_t put_box(char *t, size_t cap, size_t n, int k, const uint8_t *b, double *sky) {
  int x = b[0] & 31, w = 1 + (b[1] & 15), hq = 1 + (b[2] & 7);
  double top = 0;
  for (int c = x; c < x + w; c++)
    if (sky[c] > top) top = sky[c];
  double x0 = x * 0.25, x1 = (x + w) * 0.25, y0 = top, y1 = top + hq * 0.125;
  for (int c = x; c < x + w; c++) sky[c] = y1;
  n += (size_t)snprintf(t + n, cap - n,
                        "%s{\"id\": \"b%d\", \"polygon\": [[%g, %g], [%g, %g], [%g, %g], [%g, %g]]%s%s}",
                        k ? ",\n" : "", k, x0, y0, x1, y0, x1, y1, x0, y1,
                        b[2] & 64 ? ", \"fixed\": true" : "", b[2] & 128 ? ", \"density\": 3" : "");
  return n;
}

char *fz_boxes_text(const uint8_t *d, size_t size) {
  int nbox = size > 1 ? (int)((size - 1) / 3) : 0;
  if (nbox > FZ_MAX_BODIES) nbox = FZ_MAX_BODIES;
  size_t cap = 200 + (size_t)nbox * 200, n = 0;
  char *t = malloc(cap);
  if (!t) abort();
  double sky[CELLS] = {0};
  n += (size_t)snprintf(t, cap, "{\"friction\": %g, \"bodies\": [\n", size ? d[0] / 32.0 : 0.5);
  for (int k = 0; k < nbox; k++) n = put_box(t, cap, n, k, d + 1 + 3 * k, sky);
  snprintf(t + n, cap - n, "]}\n");
  return t;
}

char *fz_structure_text(const uint8_t *d, size_t size) {
  if (size > 0 && d[0] == 0) return fz_boxes_text(d + 1, size - 1);
  return fz_text(d, size);
}
