/* Module mesh.so: the mesh import's Assimp part (io/mesh_import.c) behind
 * the proxy of io/mesh_lazy.c. */
#include "module.h"
#include "io/mesh_module.h"

US_MODULE_EXPORT const void *us_module_mesh(const us_ModuleHost *host);

static const us_MeshModule api = {us_structure_read_mesh};

const void *us_module_mesh(const us_ModuleHost *host) {
  return us_module_accept(host) ? &api : NULL;
}
