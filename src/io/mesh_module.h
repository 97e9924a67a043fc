/* The mesh import's public entry point as module mesh.so gives it to its
 * proxy (mesh_lazy.c; core/module.h). */
#ifndef US_IO_MESH_MODULE_H
#define US_IO_MESH_MODULE_H

#include "core/core.h"

typedef struct us_MeshModule {
  us_Structure *(*read)(const char *path, const us_MeshSettings *set, us_MeshInfo *info,
                        us_Error *err);
} us_MeshModule;

#endif
