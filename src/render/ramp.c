/* The removal-order colour ramp, our own: five anchor colours in OKLab,
 * joined by straight segments in OKLab and converted to 8-bit sRGB.
 *
 * OKLab (B. Ottosson, 2020) is a perceptual space: equal steps in it look
 * about equally different, and its L is perceived lightness. The anchors,
 * given as lightness L, chroma C and hue h (a = C cos h, b = C sin h), are
 * evenly spaced in t and their L grows by 0.16 from one to the next, so L
 * is a linear function of t along the whole ramp: the ramp is monotone in
 * lightness (it reads in grey-scale print and for colour-blind readers),
 * and equal steps in t are equal steps in lightness. Hue turns from purple
 * (t = 0, removed first) through blue, teal and green to yellow (t = 1),
 * like the viridis family. Every point of every segment is inside the sRGB
 * gamut (checked when the anchors were chosen: the smallest channel along
 * the ramp is 0.003 before gamma), so no clipping bends the lightness;
 * the conversion clamps anyway, to stay safe for rounding.
 *
 * Conversion OKLab -> linear sRGB: the published OKLab matrices (M2
 * inverse, cube, M1 inverse); linear -> sRGB: the sRGB transfer function.
 * us_rgb_lightness is the forward direction, for the label colours and the
 * tests. */
#include "render/render.h"

#include <math.h>

typedef struct Lab {
  double L, a, b;
} Lab;

/* Anchors: L, C, hue in degrees. */
static const double kAnchor[5][3] = {
    {0.28, 0.13, 305.0}, /* deep purple */
    {0.44, 0.13, 268.0}, /* blue */
    {0.60, 0.10, 205.0}, /* teal */
    {0.76, 0.16, 145.0}, /* green */
    {0.92, 0.18, 105.0}, /* yellow */
};

static Lab anchor(int i) {
  double h = kAnchor[i][2] * (3.14159265358979323846 / 180.0);
  return (Lab){kAnchor[i][0], kAnchor[i][1] * cos(h), kAnchor[i][1] * sin(h)};
}

static double encode(double x) {
  x = x < 0 ? 0 : (x > 1 ? 1 : x);
  return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

static double decode(double x) { return x <= 0.04045 ? x / 12.92 : pow((x + 0.055) / 1.055, 2.4); }

static unsigned char byte(double x) { return (unsigned char)lround(255.0 * encode(x)); }

static us_Rgb lab_to_rgb(Lab c) {
  double l = c.L + 0.3963377774 * c.a + 0.2158037573 * c.b;
  double m = c.L - 0.1055613458 * c.a - 0.0638541728 * c.b;
  double s = c.L - 0.0894841775 * c.a - 1.2914855480 * c.b;
  l = l * l * l, m = m * m * m, s = s * s * s;
  return (us_Rgb){byte(4.0767416621 * l - 3.3077115913 * m + 0.2309699292 * s),
                  byte(-1.2684380046 * l + 2.6097574011 * m - 0.3413193965 * s),
                  byte(-0.0041960863 * l - 0.7034186147 * m + 1.7076147010 * s)};
}

us_Rgb us_ramp(double t) {
  t = t > 0 ? (t < 1 ? t : 1) : 0; /* NaN -> 0 */
  double u = 4.0 * t;
  int k = (int)u;
  if (k > 3) k = 3;
  double f = u - (double)k;
  Lab p = anchor(k), q = anchor(k + 1);
  return lab_to_rgb((Lab){p.L + f * (q.L - p.L), p.a + f * (q.a - p.a), p.b + f * (q.b - p.b)});
}

double us_rgb_lightness(us_Rgb c) {
  double r = decode(c.r / 255.0), g = decode(c.g / 255.0), b = decode(c.b / 255.0);
  double l = cbrt(0.4122214708 * r + 0.5363325363 * g + 0.0514459929 * b);
  double m = cbrt(0.2119034982 * r + 0.6806995451 * g + 0.1073969566 * b);
  double s = cbrt(0.0883024619 * r + 0.2817188376 * g + 0.6299787005 * b);
  return 0.2104542553 * l + 0.7936177850 * m - 0.0040720468 * s;
}
