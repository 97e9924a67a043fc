/* The public entry points of the renderer: default settings, and one
 * function per format that builds the scene (src/render/scene.c), opens
 * the output atomically (src/core/file.c) and hands the stream to the
 * format's writer (svg.c, png.c). Every check on the settings runs while
 * the scene is built, before the output is opened, and a writer's failure
 * aborts the temporary file: on any error nothing is written.
 *
 * The formats differ in their size limits only: an SVG may be up to 1e6
 * px a side, a PNG US_PNG_MAX_SIDE a side and US_PNG_MAX_PIXELS in area
 * (a raster costs 4 bytes a pixel; above the limits the drawing shrinks
 * to fit when the height is automatic, and is refused when asked for). */
#include "render/render.h"

#include <string.h>

typedef enum Format { FORMAT_SVG, FORMAT_PNG } Format;

us_RenderSettings us_render_default_settings(void) {
  us_RenderSettings r;
  memset(&r, 0, sizeof r);
  r.show_contacts = 1;
  r.show_labels = 1;
  r.width_px = 800.0;
  r.view_az = 35.0;
  r.view_el = 25.0;
  return r;
}

static us_Status write_scene(Format f, const us_Scene *sc, const us_Structure *s, const char *path,
                             us_Error *err) {
  us_AtomicFile *af = us_atomic_open(path, err);
  if (!af) return err->code;
  FILE *fp = us_atomic_stream(af);
  us_Status st = US_OK;
  if (f == FORMAT_PNG) st = us_scene_write_png(fp, sc, path, err);
  else us_scene_write_svg(fp, sc, s);
  if (st) {
    us_atomic_abort(af);
    return st;
  }
  return us_atomic_commit(af, err);
}

static us_Status render(Format f, const us_Structure *s, const us_RenderSettings *r,
                        const char *path, us_Error *err) {
  us_Error local;
  if (!err) err = &local; /* the steps below read err->code */
  if (!s || !path) return us_error_set(err, US_ERR_USAGE, "render: no structure or no path");
  us_RenderSettings def = us_render_default_settings();
  if (!r) r = &def;
  us_Scene sc;
  us_Status st = f == FORMAT_PNG
                     ? us_scene_build(&sc, s, r, US_PNG_MAX_SIDE, US_PNG_MAX_PIXELS, err)
                     : us_scene_build(&sc, s, r, 1e6, 1e12, err);
  if (st) return st;
  st = write_scene(f, &sc, s, path, err);
  us_scene_free(&sc);
  return st;
}

us_Status us_render_svg(const us_Structure *s, const us_RenderSettings *r, const char *path,
                        us_Error *err) {
  return render(FORMAT_SVG, s, r, path, err);
}

us_Status us_render_png(const us_Structure *s, const us_RenderSettings *r, const char *path,
                        us_Error *err) {
  return render(FORMAT_PNG, s, r, path, err);
}
