/* Pictures of a structure (src/render): the colour ramp, the scene (one
 * drawing description, computed once from structure + settings) and its two
 * writers, SVG text and PNG through cairo.
 *
 * A scene is in pixels, y down, origin at the picture's top-left corner:
 * every position, size and colour a writer needs is in it, so the writers
 * only translate shapes into their format and never decide what to draw. */
#ifndef US_RENDER_H
#define US_RENDER_H

#include "core/core.h"

#include <stdio.h>

/* 8-bit sRGB: both writers use these bytes as they are. */
typedef struct us_Rgb {
  unsigned char r, g, b;
} us_Rgb;

/* The removal-order ramp at t in [0, 1] (clamped): dark purple (removed
 * first) through blue, teal and green to yellow, lightness increasing
 * linearly (src/render/ramp.c). */
us_Rgb us_ramp(double t);
/* OKLab lightness in [0, 1] of an sRGB colour. */
double us_rgb_lightness(us_Rgb c);

/* A fill: a solid colour, or that colour crossed by hatch lines. */
typedef struct us_Paint {
  us_Rgb fill;
  int hatch;        /* index into us_hatches, or -1 for a solid fill */
} us_Paint;

/* The hatches: on a ground of colour `base`, lines of colour `line`,
 * `width` px wide, `gap` px apart, at `angle` degrees (counter-clockwise on
 * the page from the x axis); `name` is the SVG pattern id. A hatched
 * paint's fill is its hatch's base. */
typedef struct us_Hatch {
  const char *name;
  us_Rgb base, line;
  double angle, gap, width;
} us_Hatch;
enum { US_HATCH_GROUND, US_HATCH_FIXED, US_HATCH_BLOCKED, US_NHATCH };
extern const us_Hatch us_hatches[US_NHATCH];

/* One line of text: anchored at (x, y) on its baseline, or on its middle
 * when `centred`; `anchor` -1 start, 0 middle, 1 end. */
typedef struct us_SceneText {
  const char *text;   /* NULL: nothing to draw */
  double x, y, size;
  int anchor, centred, bold;
  us_Rgb color;
} us_SceneText;

/* A body: a polygon (pts[2 first .. 2 (first + npt) - 1]) or, without
 * geometry, a dot of radius US_POINT_BODY_PX at (cx, cy). */
#define US_POINT_BODY_PX 6.0
typedef struct us_SceneBody {
  int body;           /* index into the structure */
  int first, npt;
  double cx, cy;
  us_Paint paint;
  us_SceneText label; /* step number (text in num) or id */
  char num[12];
  double depth;       /* 3D: centroid along the view direction (larger is
                         nearer the viewer); 0 in 2D */
  int mark;           /* US_MARK_*: the failure marks (SVG classes) */
  int hidden;         /* 3D proto: 1 leaves the body out (not placed yet) */
} us_SceneBody;
/* A body that falls (class "falls": a thick red outline); one removed at
 * the failing step (class "failing-step": a dashed red outline); one held
 * by a hand (class "held-body": a thick outline in the hand colour). */
enum { US_MARK_NONE = 0, US_MARK_FALLS, US_MARK_STEP, US_MARK_HELD };

/* An axis-aligned box, for the legend's swatches. */
typedef struct us_SceneBox {
  double x, y, w, h;
  us_Paint paint;
} us_SceneBox;

#define US_SCENE_TEXTS 16
#define US_SCENE_BOXES 4
#define US_RAMP_STOPS 21

typedef struct us_Scene {
  double w, h;            /* the picture, whole pixels */
  double stroke;          /* body outline width */
  double ground_y;        /* top of the ground band (>= draw_bottom: none) */
  double draw_top, draw_bottom; /* the drawing's band; the ground fills
                                   [ground_y, draw_bottom] */
  int nbody;
  us_SceneBody *bodies;   /* 2D: one per body; 3D: one per face turned to
                             the viewer, in the painter's order */
  int labels_in_order;    /* 1 (3D): each label drawn right after its entry,
                             so nearer faces cover it; 0 (2D): the SVG puts it
                             in its body's group, the PNG after every body */
  int nline;
  double *lines;          /* 3D ground grid (x1, y1, x2, y2), under the bodies */
  double line_width;
  us_Rgb line_color;
  double *pts;            /* body vertices, pixels */
  int ndot;
  double *dots;           /* contact points (x, y) */
  double dot_r;
  us_Rgb dot_color;
  int narrow;
  double *arrows;         /* force arrows (x1, y1, x2, y2), head at (x2, y2) */
  unsigned char *arrow_kind; /* [narrow] 0 normal part, 1 friction part */
  double arrow_width, arrow_head;
  us_Rgb arrow_color, friction_color; /* of the two kinds */
  int nmech;              /* mechanism: velocity arrows (x1, y1, x2, y2) at
                             the moving bodies' centres, class "mechanism" */
  double *mech;
  int nghost;             /* 2D: the moving bodies displaced along the
                             mechanism, outlines ghost_start[g] ..
                             ghost_start[g + 1] - 1 of ghost_pts (x, y) */
  int *ghost_start;
  double *ghost_pts;
  us_Rgb mark_color;      /* failure marks, mechanism and ghosts */
  int nhand;              /* hand marks (x, y): discs of radius hand_r at the
                             held bodies' centres, class "held" */
  double *hands, hand_r;
  us_Rgb hand_color;      /* hand marks and held bodies' outlines */
  struct us_Depth *depth; /* 3D, while the scene is built: the painter's
                             order's nodes, for what covers a mark
                             (src/render/depth3.c); NULL otherwise */
  int has_ramp;           /* the legend's ramp strip */
  us_SceneBox ramp_box;
  us_Rgb ramp[US_RAMP_STOPS]; /* us_ramp at evenly spaced t */
  int nbox;
  us_SceneBox boxes[US_SCENE_BOXES];
  int ntext;              /* title and legend lines */
  us_SceneText texts[US_SCENE_TEXTS];
  char text_buf[US_SCENE_TEXTS][192];
} us_Scene;

/* The view: world to pixels. A world point p is first projected to
 * (x, y) = (p . r, p . u) (2D: r = x, u = y), then X = ox + (x - x0) k,
 * Y = oy + (y1 - y) k. e points from the scene toward the viewer. */
typedef struct us_SceneView {
  double x0, y1;   /* left and top edges of the view, projected */
  double ww, wh;   /* width and height of the view, projected */
  double k;        /* pixels per world unit */
  double ox, oy;   /* pixel position of (x0, y1) */
  double span;     /* larger side of the view */
  double r[3], u[3], e[3]; /* right, up, toward the viewer (unit, orthogonal) */
} us_SceneView;

/* The axonometric axes of azimuth az and elevation el (degrees, see
 * src/render/scene3.c) into v->r, v->u, v->e. */
void us_scene3_axes(us_SceneView *v, double az, double el);
/* p in pixels under v. */
void us_scene_px(const us_SceneView *v, const double p[3], double *X, double *Y);
/* Entries (faces and point bodies) and face vertices a 3D scene needs. */
void us_scene3_count(const us_Structure *s, size_t *nentry, size_t *npt);
/* Grow bb (xmin, ymin, xmax, ymax, projected) by the bodies and the grid. */
void us_scene3_bounds(const us_Structure *s, const us_SceneView *v, double bb[4]);
/* The visible faces in the painter's order (src/render/depth3.c), painted
 * from proto[body] (paint; label text and colour) and shaded; labels at
 * the bodies' projected centres, left out where a nearer body covers
 * them; the ground grid. sc->bodies and sc->pts hold us_scene3_count's
 * sizes, sc->lines 4 US_GRID_LINES doubles. proto's depths are used as
 * marks. Sets sc->depth; 1 on out of memory. */
#define US_GRID_LINES 64
int us_scene3_bodies(us_Scene *sc, const us_SceneView *v, const us_Structure *s,
                     us_SceneBody *proto);

/* The painter's order (src/render/depth3.c): sc->bodies[0 .. nbody) as
 * collected, the faces of each convex part in a run of equal node_of[],
 * plane[e] the face plane of entry e (NULL: a point body), reordered so
 * that a nearer part comes after every part it overlaps; the order kept
 * in sc->depth (even on failure: us_depth3_free). 1 on out of memory. */
typedef struct us_Depth us_Depth;
int us_depth3_order(us_Scene *sc, const us_SceneView *v, int nbody, const double *const *plane,
                    const int *node_of);
/* 1 when a part painted after every part of bodies a and b (US_GROUND:
 * none) covers the box of half sides hw, hh at (x, y), or the segment
 * seg (x1, y1, x2, y2), px; 0 without sc->depth (2D). */
int us_depth3_covers_box(const us_Scene *sc, int a, int b, double x, double y, double hw,
                         double hh);
int us_depth3_covers_segment(const us_Scene *sc, int a, int b, const double seg[4]);
/* 1 when parts painted after body's cover more than a quarter of the
 * label box (half sides hw, hh at x, y); 0 without sc->depth. */
int us_depth3_hides_label(const us_Scene *sc, int body, double x, double y, double hw,
                          double hh);
void us_depth3_free(us_Scene *sc);

/* Failure marks (src/render/failure.c): r->failure checked against s
 * (US_ERR_USAGE); the body that falls (named, else the mechanism's
 * fastest, else -1); the mark of body i (step[i]: its 1-based step); the
 * legend's line; the mechanism's arrays (1 on out of memory); its arrows
 * and 2D ghosts. */
us_Status us_scene_check_failure(const us_Structure *s, const us_RenderSettings *r,
                                 us_Error *err);
int us_scene_falling(const us_Structure *s, const us_RenderFailure *f);
int us_scene_mark(const us_RenderSettings *r, const int *step, int i, int falls);
int us_scene_removed(const us_RenderSettings *r, const int *step, int i); /* by the failure */
void us_scene_failure_line(char *buf, size_t n, const us_Structure *s,
                           const us_RenderSettings *r);
int us_scene_alloc_failure(us_Scene *sc, const us_Structure *s, const us_RenderSettings *r);
void us_scene_mechanism(us_Scene *sc, const us_SceneView *v, const us_Structure *s,
                        const us_RenderFailure *f);

/* Largest PNG: sides and area, so that a huge structure gives a bounded
 * picture (about 256 MB of pixels at most). */
#define US_PNG_MAX_SIDE 16384.0
#define US_PNG_MAX_PIXELS 64e6

/* Build the scene of s under r, at most max_side pixels a side and
 * max_pixels in area (the height shrinks the drawing to fit; a width or
 * height asked for beyond them is US_ERR_USAGE). Checks r against s
 * (US_ERR_USAGE). The scene points into s and r->title: keep them alive. */
us_Status us_scene_build(us_Scene *sc, const us_Structure *s, const us_RenderSettings *r,
                         double max_side, double max_pixels, us_Error *err);
void us_scene_free(us_Scene *sc);

/* The force a picture draws at contact k of f (src/render/forces.c): the
 * force the lower body exerts on the upper one (upper: the side the
 * normal enters when it points up, against gravity), split into its
 * normal part (into the upper body) and its friction part, world axes. */
typedef struct us_DrawnForce {
  int upper, lower;     /* body indices (lower may be US_GROUND) */
  double p[3];          /* point of application */
  double normal[3], friction[3];
  double fn;            /* the normal component (>= 0 when admissible) */
} us_DrawnForce;
void us_drawn_force(const us_Structure *s, const us_Forces *f, int k, us_DrawnForce *out);
/* One resultant per pair of touching bodies, at the centre of pressure;
 * out holds f->ncontact entries. The count, or -1 on OOM. */
int us_drawn_resultants(const us_Structure *s, const us_Forces *f, us_DrawnForce *out);

/* The writers: the scene to an open stream. */
void us_scene_write_svg(FILE *fp, const us_Scene *sc, const us_Structure *s);
us_Status us_scene_write_png(FILE *fp, const us_Scene *sc, const char *path, us_Error *err);

#endif
