/* The SVG import's proxy: libxml2 lives in module svg.so (core/module.h),
 * loaded the first time an SVG is read. */
#include "io/svg_module.h"

#include "core/module.h"

#include <string.h>

static us_Module svg_module = {"svg", "the SVG import, libxml2", NULL};

/* Without the module the settings are all zero: the import that would
 * use them reports the missing module. */
us_SvgSettings us_svg_default_settings(void) {
  const us_SvgModule *m = us_module_api(&svg_module, NULL);
  us_SvgSettings none;
  memset(&none, 0, sizeof none);
  return m ? m->default_settings() : none;
}

us_Structure *us_structure_parse_svg(const char *text, size_t len, const char *name,
                                     const us_SvgSettings *set, us_SvgInfo *info, us_Error *err) {
  const us_SvgModule *m = us_module_api(&svg_module, err);
  if (!m && info) memset(info, 0, sizeof *info);
  return m ? m->parse(text, len, name, set, info, err) : NULL;
}

us_Structure *us_structure_read_svg(const char *path, const us_SvgSettings *set, us_SvgInfo *info,
                                    us_Error *err) {
  const us_SvgModule *m = us_module_api(&svg_module, err);
  if (!m && info) memset(info, 0, sizeof *info);
  return m ? m->read(path, set, info, err) : NULL;
}
