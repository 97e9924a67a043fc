/* The mesh import's neutral document (io/mesh.h): objects with their
 * vertices and polygon faces, filled by the Assimp reader (module mesh.so)
 * or by tests, read by mesh_build.c. */
#include "mesh.h"

#include <string.h>

int us_mesh_object(us_MeshDoc *d, const char *name, int named, int merge) {
  /* OBJ objects are few; a linear search keeps the file's order */
  for (int k = 0; merge && k < d->nobj; k++)
    if (d->objs[k].named == named && !strcmp(d->objs[k].name, name)) return k;
  if (us_grow((void **)&d->objs, &d->ocap, d->nobj + 1, sizeof *d->objs)) return -1;
  us_MeshObject *o = &d->objs[d->nobj];
  memset(o, 0, sizeof *o);
  o->named = named;
  o->name = us_strdup(name);
  o->fstart = us_calloc(1, sizeof *o->fstart);
  o->fcap = 1;
  if (!o->name || !o->fstart) {
    us_free(o->name);
    us_free(o->fstart);
    return -1;
  }
  return d->nobj++;
}

int us_mesh_add_vertex(us_MeshObject *o, const double p[3]) {
  if (us_grow((void **)&o->xyz, &o->vcap, 3 * (o->nvert + 1), sizeof *o->xyz)) return -1;
  memcpy(o->xyz + 3 * o->nvert++, p, 3 * sizeof *p);
  return 0;
}

int us_mesh_add_face(us_MeshObject *o, int base, const unsigned *idx, int n) {
  if (us_grow((void **)&o->fidx, &o->icap, o->nidx + n, sizeof *o->fidx) ||
      us_grow((void **)&o->fstart, &o->fcap, o->nface + 2, sizeof *o->fstart))
    return -1;
  for (int k = 0; k < n; k++) o->fidx[o->nidx++] = base + (int)idx[k];
  o->fstart[++o->nface] = o->nidx;
  return 0;
}

void us_mesh_doc_free(us_MeshDoc *d) {
  for (int k = 0; k < d->nobj; k++) {
    us_free(d->objs[k].name);
    us_free(d->objs[k].xyz);
    us_free(d->objs[k].fstart);
    us_free(d->objs[k].fidx);
  }
  us_free(d->objs);
  d->objs = NULL;
  d->nobj = d->ocap = 0;
}
