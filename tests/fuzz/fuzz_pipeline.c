/* Fuzz target `pipeline`: parse, check with every method, plan, plan file,
 * verify (pipeline.c states the properties).
 *
 * Input: two control bytes, then the text of a structure file, or a NUL
 * byte and the bytes of a box pile (boxes.c). Control byte 0:
 * search (bits 0-1: assemble, dfs, bfs, random), step size of the assemble search
 * (bits 2-3: 1, 1, 2, auto), removal kinematics of the graph searches (bits 4-5: any, up,
 * free, any), direction (bit 6), certificates (bit 7). Byte 1: the plan's
 * method (bits 0-1), body order (bits 2-3), culling rules switched off
 * (bits 3-7, XOR-ed out of all rules) and the random seed. */
#include "fuzz.h"

#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size < 2 || size > FZ_MAX_INPUT) return 0;
  long live = us_alloc_live();
  char *text = fz_structure_text(data + 2, size - 2);
  fz_pipeline(text, data[0], data[1], -1, 0);
  free(text);
  if (us_alloc_live() != live)
    fz_finding("%ld blocks leaked through the allocation funnel", us_alloc_live() - live);
  return 0;
}
