/* Shared helpers of the libFuzzer targets (tests/fuzz/, docs/fuzzing.md).
 *
 * Each target is one LLVMFuzzerTestOneInput; the same source is linked
 * either with libFuzzer (clang, `make fuzz`) or with replay.c (gcc, ctest
 * replays the corpus). A target reports a finding with fz_finding, which
 * prints the reason and aborts: libFuzzer saves the input, the replay
 * test fails. Everything a target writes goes to a private temporary
 * directory of the process, removed at exit. */
#ifndef US_FUZZ_H
#define US_FUZZ_H

#include "unstack/unstack.h"

#include <stddef.h>
#include <stdint.h>

/* Caps that keep every run fast (a finding is a crash or a wrong answer,
 * never a slow input). */
#define FZ_MAX_INPUT (64 * 1024)
#define FZ_MAX_BODIES 40
#define FZ_MAX_VERTS 2000 /* total polygon vertices */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Print "finding: <reason>" and abort. */
#if defined(__GNUC__)
__attribute__((noreturn, format(printf, 1, 2)))
#endif
void fz_finding(const char *fmt, ...);

/* A NUL-terminated copy of data (us_-free: plain malloc, the caller frees). */
char *fz_text(const uint8_t *data, size_t size);
/* "<private tmp dir>/<name>"; the buffer is static per name slot (0..3). */
const char *fz_path(int slot, const char *name);
/* The whole file as a malloc'ed buffer, its length in *len; NULL on error. */
char *fz_slurp(const char *path, size_t *len);

/* The structure text of an input of `pipeline` or `oom` (after their
 * control bytes): a NUL byte, then a box pile (boxes.c); else the text of
 * a structure file. malloc'ed; the caller frees. */
char *fz_boxes_text(const uint8_t *d, size_t size);
char *fz_structure_text(const uint8_t *d, size_t size);

/* Within the caps (bodies, vertices)? */
int fz_small(const us_Structure *s);
/* The first difference between two structures (ids, geometry, masses,
 * materials, contacts), or NULL when they are identical. */
const char *fz_structure_diff(const us_Structure *a, const us_Structure *b);
/* An error must carry its code and a message; anything else is a finding. */
void fz_check_error(const char *what, us_Status st, const us_Error *err);

/* The whole pipeline of fuzz_pipeline and fuzz_oom: parse, check with
 * every method, plan, write/read the plan and verify it. `ctl` chooses the
 * plan settings. With oom_phase >= 0 the pipeline runs twice: first as a
 * reference, then with the oom_n-th allocation of phase oom_phase failing
 * (us_alloc_fail_after); every call that succeeded in the reference must
 * then succeed with the same outcome or fail with US_ERR_NOMEM. */
void fz_pipeline(const char *text, uint8_t ctl0, uint8_t ctl1, int oom_phase, long oom_n);

#endif
