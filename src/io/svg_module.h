/* The SVG import's public entry points as module svg.so gives them to
 * its proxy (svg_lazy.c; core/module.h). */
#ifndef US_IO_SVG_MODULE_H
#define US_IO_SVG_MODULE_H

#include "core/core.h"

typedef struct us_SvgModule {
  us_SvgSettings (*default_settings)(void);
  us_Structure *(*parse)(const char *text, size_t len, const char *name, const us_SvgSettings *set,
                         us_SvgInfo *info, us_Error *err);
  us_Structure *(*read)(const char *path, const us_SvgSettings *set, us_SvgInfo *info,
                        us_Error *err);
} us_SvgModule;

#endif
