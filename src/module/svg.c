/* Module svg.so: the SVG import's XML part (io/svg_import.c and
 * io/svg_walk.c, with libxml2) behind the proxy of io/svg_lazy.c. */
#include "module.h"
#include "io/svg_module.h"

US_MODULE_EXPORT const void *us_module_svg(const us_ModuleHost *host);

static const us_SvgModule api = {us_svg_default_settings, us_structure_parse_svg,
                                 us_structure_read_svg};

const void *us_module_svg(const us_ModuleHost *host) {
  return us_module_accept(host) ? &api : NULL;
}
