/* Module png.so: the PNG writer (render/png.c, with cairo) behind the
 * proxy of render/png_lazy.c. */
#include "module.h"
#include "render/png_module.h"

US_MODULE_EXPORT const void *us_module_png(const us_ModuleHost *host);

static const us_PngModule api = {us_scene_write_png};

const void *us_module_png(const us_ModuleHost *host) {
  return us_module_accept(host) ? &api : NULL;
}
