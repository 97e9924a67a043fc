/* The PNG writer's entry points as module png.so gives them to its proxy
 * (png_lazy.c; core/module.h). */
#ifndef US_RENDER_PNG_MODULE_H
#define US_RENDER_PNG_MODULE_H

#include "render/render.h"

typedef struct us_PngModule {
  us_Status (*write_png)(FILE *fp, const us_Scene *sc, const char *path, us_Error *err);
} us_PngModule;

#endif
