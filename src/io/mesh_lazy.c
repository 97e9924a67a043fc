/* The mesh import's proxy: Assimp lives in module mesh.so (core/module.h),
 * loaded the first time a mesh is read, so no other command maps it. */
#include "io/mesh_module.h"

#include "core/module.h"

#include <string.h>

static us_Module mesh_module = {"mesh", "the mesh import, Assimp", NULL};

us_Structure *us_structure_read_mesh(const char *path, const us_MeshSettings *set,
                                     us_MeshInfo *info, us_Error *err) {
  const us_MeshModule *m = us_module_api(&mesh_module, err);
  if (!m && info) memset(info, 0, sizeof *info);
  return m ? m->read(path, set, info, err) : NULL;
}
