/* Private pieces of the mesh import (docs/mesh.md), one file each:
 *   mesh_import.c  (module mesh.so) Assimp's scene -> a us_MeshDoc: every
 *                  object's faces in file coordinates, transforms applied;
 *   mesh_obj.c     (library) OBJ files -> a us_MeshDoc, without Assimp;
 *   mesh_build.c   (library) a us_MeshDoc -> a structure: vertices welded,
 *                  faces and shells checked, convexity, names, bodies;
 *   mesh_lazy.c    (library) the public entry points' proxy.
 * The document knows nothing of Assimp, so the checks are tested on
 * documents built by hand (tests/test_io_mesh.c). */
#ifndef US_IO_MESH_H
#define US_IO_MESH_H

#include "core/core.h"

/* One object of the file: the faces of every mesh under it, in the
 * file's coordinates (node transforms applied, before --up and --scale).
 * Face k is the polygon fidx[fstart[k] .. fstart[k + 1]). */
typedef struct us_MeshObject {
  char *name;   /* the file's name for it, as given (owned; may be "") */
  int named;    /* 1: one body (a compound when it has several shells);
                   0: the file names nothing: one body per shell */
  int nvert, vcap;
  double *xyz;  /* 3 * nvert */
  int nface, fcap;
  int *fstart;  /* nface + 1 */
  int nidx, icap;
  int *fidx;
} us_MeshObject;

typedef struct us_MeshDoc {
  const char *name; /* the file, for messages */
  const char *stem; /* the file's base name without extension (ids of unnamed shells) */
  int nobj, ocap;
  us_MeshObject *objs;
} us_MeshDoc;

/* A new object called `name`, or with `merge` the one of that name and
 * kind when there is one: its index, or -1 out of memory. */
int us_mesh_object(us_MeshDoc *d, const char *name, int named, int merge);
/* Append a vertex / a face of n vertex indices (relative to `base`, the
 * object's vertex count before the mesh was added): 0, or -1 OOM. */
int us_mesh_add_vertex(us_MeshObject *o, const double p[3]);
int us_mesh_add_face(us_MeshObject *o, int base, const unsigned *idx, int n);
void us_mesh_doc_free(us_MeshDoc *d);

/* Read an OBJ file into d (mesh_obj.c; d->name set by the caller):
 * US_ERR_IO, US_ERR_PARSE naming the line, or US_ERR_NOMEM. */
us_Status us_mesh_read_obj(us_MeshDoc *d, const char *path, us_Error *err);

/* The structure of a document (finalized), or NULL with err set naming
 * the file and the object. */
us_Structure *us_mesh_build(const us_MeshDoc *d, const us_MeshSettings *set, us_MeshInfo *info,
                            us_Error *err);

#endif
