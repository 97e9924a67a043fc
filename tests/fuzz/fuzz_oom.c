/* Fuzz target `oom`: the pipeline of fuzz_pipeline with one allocation
 * failing (and every one after it, as us_alloc_fail_after does).
 *
 * Input: byte 0 picks the phase where failures are armed (bits 0-1: parse,
 * stability, plan, plan file and verification); bytes 1-2 are N, the
 * allocations of that phase that still succeed (little-endian); then the
 * two control bytes and the structure (text or box pile) of the `pipeline`
 * target. Every
 * failure must come back as US_ERR_NOMEM with a message from a call that
 * succeeds with memory, never as another error or a different answer, and
 * nothing may leak (us_alloc_live back to where it started). */
#include "fuzz.h"

#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size < 5 || size > FZ_MAX_INPUT) return 0;
  long live = us_alloc_live();
  int phase = data[0] & 3;
  long n = (long)data[1] | (long)data[2] << 8;
  char *text = fz_structure_text(data + 5, size - 5);
  fz_pipeline(text, data[3], data[4], phase, n);
  free(text);
  if (us_alloc_live() != live)
    fz_finding("%ld blocks leaked through the allocation funnel (phase %d, n %ld)",
               us_alloc_live() - live, phase, n);
  return 0;
}
