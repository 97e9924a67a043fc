/* The viewer's page template (src/render/viewer.html) and its 3D view
 * (src/render/viewer3.js), embedded in the library at build time by
 * cmake/embed.cmake: their bytes, NUL-terminated, and their lengths
 * without the NUL. src/render/html.c writes the template with the plan's
 * data in place of its "@US_DATA@" marker and, for a 3D structure, the 3D
 * view in place of its "/" "*@US_VIEW3@*" "/" marker. */
#ifndef US_RENDER_VIEWER_H
#define US_RENDER_VIEWER_H

#include <stddef.h>

extern const unsigned char us_viewer_html[];
extern const size_t us_viewer_html_size;
extern const unsigned char us_viewer3_js[];
extern const size_t us_viewer3_js_size;

#endif
