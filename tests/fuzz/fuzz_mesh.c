/* Fuzz target `mesh`: the mesh import's checks and bodies (mesh_build.c)
 * on documents decoded from a byte buffer; Assimp itself is not fuzzed
 * here (its parsers are not ours).
 *
 * Input: byte 0 picks the settings (bit 0: --up y, bit 1: no ground, bit
 * 2: --fixed '*-1', bit 3: --scale 1000); then records, each an opcode
 * byte and its operands:
 *   op % 4 == 0  a new object, named "oN" (N the next byte) when the
 *                opcode's bit 2 is set, else unnamed;
 *   op % 4 == 1  a box of the current object at the grid point of the
 *                next three bytes (halves), 1 or 2 wide (bit 2), its faces
 *                turned by bits 3-4 and reversed by bit 5: touching boxes
 *                share corners, edges and faces, as blocks in one STL do;
 *   op % 4 == 2  a vertex ((b - 128) / 8 for three bytes);
 *   op % 4 == 3  a face of 3 + (next byte % 3) corners, each a byte
 *                modulo the object's vertex count + 1 (one out of range).
 * Properties checked for every input: no crash; a rejection is an error
 * whose message names the file ("input.mesh"), or out of memory; an
 * accepted structure is finalized and (within fuzz.h's caps) written as a
 * structure file reads back identical; nothing leaks. */
#include "fuzz.h"

#include "io/mesh.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct Bytes {
  const uint8_t *d;
  size_t n, at;
} Bytes;

static int next(Bytes *b) { return b->at < b->n ? b->d[b->at++] : 0; }

static const unsigned faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};

static int box(us_MeshObject *o, Bytes *b, int op) {
  double lo[3], w = op & 4 ? 2 : 1;
  for (int a = 0; a < 3; a++) lo[a] = next(b) / 2.0;
  int base = o->nvert, rot = (op >> 3) & 3;
  for (int k = 0; k < 8; k++) {
    double p[3];
    for (int a = 0; a < 3; a++) p[a] = lo[a] + ((k >> a) & 1) * w;
    if (us_mesh_add_vertex(o, p)) return -1;
  }
  for (int f = 0; f < 6; f++) {
    unsigned q[4];
    for (int i = 0; i < 4; i++) q[i] = faces[f][(i + rot) % 4];
    if (op & 32) {
      unsigned t = q[1];
      q[1] = q[3], q[3] = t;
    }
    if (us_mesh_add_face(o, base, q, 4)) return -1;
  }
  return 0;
}

static int record(us_MeshDoc *d, Bytes *b) {
  int op = next(b);
  if (op % 4 == 0) {
    char name[16];
    snprintf(name, sizeof name, "o%d", next(b));
    return us_mesh_object(d, op & 4 ? name : "", (op & 4) != 0, 0) < 0 ? -1 : 0;
  }
  if (d->nobj == 0 && us_mesh_object(d, "", 0, 0) < 0) return -1; /* records before any object */
  us_MeshObject *o = &d->objs[d->nobj - 1];
  if (op % 4 == 1) return box(o, b, op);
  if (op % 4 == 2) {
    double p[3];
    for (int a = 0; a < 3; a++) p[a] = (next(b) - 128) / 8.0;
    return us_mesh_add_vertex(o, p);
  }
  unsigned idx[5];
  int n = 3 + next(b) % 3;
  for (int i = 0; i < n; i++) idx[i] = (unsigned)(next(b) % (o->nvert + 1));
  return us_mesh_add_face(o, 0, idx, n);
}

static void round_trip(const us_Structure *s) {
  us_Error err;
  us_error_clear(&err);
  const char *p = fz_path(0, "mesh.json");
  if (us_structure_write(s, p, &err) != US_OK)
    fz_finding("an imported structure cannot be written: %s", err.msg);
  us_Structure *back = us_structure_read(p, 0, &err);
  if (!back) fz_finding("the imported structure does not read back: %s", err.msg);
  const char *diff = fz_structure_diff(s, back);
  if (diff) fz_finding("imported structure read back differs: %s", diff);
  us_structure_free(back);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size > FZ_MAX_INPUT || size == 0) return 0;
  long live = us_alloc_live();
  Bytes b = {data, size, 1};
  us_MeshDoc d;
  memset(&d, 0, sizeof d);
  d.name = "input.mesh";
  d.stem = "input";
  int oom = 0;
  while (b.at < b.n && d.nobj < 40 && !oom) oom = record(&d, &b) != 0;
  us_MeshSettings set = us_mesh_default_settings();
  set.up = data[0] & 1 ? 'y' : 'z';
  set.ground = !(data[0] & 2);
  set.fixed = data[0] & 4 ? "*-1" : NULL;
  set.scale = data[0] & 8 ? 1000 : 1;
  us_Error err;
  us_error_clear(&err);
  us_Structure *s = oom ? NULL : us_mesh_build(&d, &set, NULL, &err);
  if (!oom && !s) {
    fz_check_error("mesh import", err.code, &err);
    if (err.code != US_ERR_NOMEM && !strstr(err.msg, "input.mesh"))
      fz_finding("a mesh import error does not name the file: %s", err.msg);
  }
  if (getenv("FZ_REPLAY_VERBOSE")) /* what each seed does */
    fprintf(stderr, "  %s: %d bodies\n", s ? "accepted" : oom ? "out of memory" : err.msg, s ? s->nbody : 0);
  if (s && fz_small(s)) round_trip(s);
  us_structure_free(s);
  us_mesh_doc_free(&d);
  if (us_alloc_live() != live)
    fz_finding("%ld blocks leaked through the allocation funnel", us_alloc_live() - live);
  return 0;
}
