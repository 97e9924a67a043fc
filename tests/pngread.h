/* The render tests' PNG reader: a file decoded by cairo (ARGB32, opaque
 * pictures: the bytes are the colour) and its pixels. */
#ifndef US_TESTS_PNGREAD_H
#define US_TESTS_PNGREAD_H

#include "render/render.h"

#include <cairo.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

typedef struct Png {
  cairo_surface_t *img;
  int w, h, stride;
  const unsigned char *data;
} Png;

/* 1 decoded into p, 0 (p->img NULL) when cairo cannot read the file. */
static inline int png_open(Png *p, const char *path) {
  p->img = cairo_image_surface_create_from_png(path);
  if (cairo_surface_status(p->img) != CAIRO_STATUS_SUCCESS) {
    cairo_surface_destroy(p->img);
    p->img = NULL;
    return 0;
  }
  cairo_surface_flush(p->img);
  p->w = cairo_image_surface_get_width(p->img);
  p->h = cairo_image_surface_get_height(p->img);
  p->stride = cairo_image_surface_get_stride(p->img);
  p->data = cairo_image_surface_get_data(p->img);
  return 1;
}

static inline void png_close(Png *p) {
  if (p->img) cairo_surface_destroy(p->img);
  p->img = NULL;
}

/* The pixel at (x, y); outside the picture (or none) the marker (1, 2, 3). */
static inline us_Rgb pixel(const Png *p, double x, double y) {
  int i = (int)floor(x), j = (int)floor(y);
  if (!p->img || i < 0 || j < 0 || i >= p->w || j >= p->h) return (us_Rgb){1, 2, 3};
  uint32_t v;
  memcpy(&v, p->data + (size_t)j * (size_t)p->stride + 4 * (size_t)i, 4);
  return (us_Rgb){(unsigned char)(v >> 16), (unsigned char)(v >> 8), (unsigned char)v};
}

#endif
