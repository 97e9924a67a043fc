/* The viewer's page template (src/render/viewer.html), embedded in the
 * library at build time by cmake/embed.cmake: its bytes, NUL-terminated,
 * and its length without the NUL. src/render/html.c writes it with the
 * plan's data in place of its one "@US_DATA@" marker. */
#ifndef US_RENDER_VIEWER_H
#define US_RENDER_VIEWER_H

#include <stddef.h>

extern const unsigned char us_viewer_html[];
extern const size_t us_viewer_html_size;

#endif
