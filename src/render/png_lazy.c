/* The PNG writer's proxy: cairo lives in module png.so (core/module.h),
 * loaded the first time a PNG is written. */
#include "render/png_module.h"

#include "core/module.h"

static us_Module png_module = {"png", "the PNG writer, cairo", NULL};

us_Status us_scene_write_png(FILE *fp, const us_Scene *sc, const char *path, us_Error *err) {
  us_Error local;
  const us_PngModule *m = us_module_api(&png_module, err ? err : &local);
  if (!m) return err ? err->code : local.code;
  return m->write_png(fp, sc, path, err);
}
