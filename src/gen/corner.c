/* The 3D wall with corner returns (wall3d, g->returns = L > 0): the
 * running-bond wall of regular.c with, at both ends, a return wall of L
 * bricks' length running along +y, bonded to it at the corner as masons
 * bond a stretcher-bond corner.
 *
 * Layout (w the block width, a brick's length; T the thickness, its depth;
 * h the block height; C the columns, R the courses): in plan the main wall
 * covers x in [0, C w], y in [0, T], the left return x in [0, T] and the
 * right return x in [C w - T, C w], both y in [0, L w]. The outer faces
 * are x = 0, y = 0 and x = C w; every course covers this U exactly, course
 * r (0-based from the ground) spanning z in [r h, (r + 1) h].
 *
 * Bond: in even courses the main wall's corner bricks run through to the
 * returns' outer faces (the main wall is C full bricks, as in the straight
 * wall) and the returns start behind them at y = T; in odd courses the
 * returns' corner bricks run through to the main wall's outer face y = 0
 * and the main wall lies between x = T and C w - T. So at each corner the
 * bricks of the two walls cross over one another in alternate courses, and
 * in every course the through brick touches the end of the other wall's
 * first piece on a T x h face.
 *
 * Joints lie on the half-brick grid measured from the outer corners: a run
 * that starts at an outer face (the through run) has its joints at whole
 * bricks, k w; the run that stops at the other wall's inner face, at half
 * bricks, k w + w / 2. Joints are therefore staggered by half a brick from
 * course to course along both walls, as in the straight wall. A run's first
 * and last pieces are cut to where the run must end: with T = w / 2 (the
 * default; a brick twice as long as deep) the returns take the place of
 * the straight wall's half bricks and the only short pieces are the half
 * bricks at the returns' free ends; with T < w / 2 a closer of w / 2 - T
 * fills in beside each corner; with w / 2 < T < w the first brick past a
 * corner is cut to 3 w / 2 - T. No piece is longer than a brick.
 *
 * Body count: with T >= w / 2, R (C + 2 L) - floor(R / 2); with T < w / 2
 * the closers add 2 per course: R (C + 2 L + 2) - floor(R / 2).
 *
 * Exactness: every coordinate is a half-brick index times w / 2 (the same
 * expression as the straight wall's), T, C w - T or a course boundary,
 * each computed by one expression, so faces shared by two bricks have
 * bit-identical coordinates and contacts are exact faces. A joint within
 * SLIVER w of a run's end is not cut, so rounding never leaves a sliver
 * when T is w / 2 by intent (C w - T and C w - w / 2 may differ in the
 * last bit).
 *
 * Numbering: course by course from the ground; within a course along the
 * U, from the left return's free end to the corner, along the main wall
 * from left to right, and out along the right return to its free end. */
#include "gen.h"

/* Joints closer than this many block widths to a run's end are not cut
 * (they can only come from rounding; see above). */
#define SLIVER 1e-9

/* One straight run of a course: pieces along `axis` (0 x, 1 y) from lo to
 * hi, spanning [a0, a1] across, cut at the half-brick joints of parity
 * `parity` (half-block indices q = parity mod 2) strictly inside. */
typedef struct Run {
  int axis;
  int backward; /* number the pieces from hi down to lo */
  long parity;
  double lo, hi, a0, a1;
} Run;

/* Where the bodies of one course go. */
typedef struct Course {
  us_Structure *s;
  const us_GenSettings *g;
  int *k; /* the next body number */
  int r;  /* the course, 0 on the ground */
} Course;

/* The run's joints: half-block indices q0, q0 + 2, ..., q0 + 2 (m - 1). */
static void joints(const us_GenSettings *g, const Run *u, long *q0, long *m) {
  double eps = SLIVER * g->width;
  long q = u->parity;
  while (us_gen_half(g, q) <= u->lo + eps) q += 2;
  long n = 0;
  while (us_gen_half(g, q + 2 * n) < u->hi - eps) n++;
  *q0 = q, *m = n;
}

/* Cut point i of m + 2 (the run's ends and its joints). */
static double cut(const us_GenSettings *g, const Run *u, long q0, long m, long i) {
  return i == 0 ? u->lo : i == m + 1 ? u->hi : us_gen_half(g, q0 + 2 * (i - 1));
}

/* Add the piece [u0, u1] of run u. */
static us_Status add_piece(Course *c, const Run *u, double u0, double u1, us_Error *err) {
  double z0 = us_gen_course(c->g, c->r), z1 = us_gen_course(c->g, c->r + 1);
  us_Status st = u->axis == 0 ? us_gen_add_box3(c->s, c->g, *c->k, u0, u->a0, z0, u1, u->a1, z1, err)
                              : us_gen_add_box3(c->s, c->g, *c->k, u->a0, u0, z0, u->a1, u1, z1, err);
  if (!st) ++*c->k;
  return st;
}

static us_Status add_run(Course *c, const Run *u, us_Error *err) {
  long q0, m;
  joints(c->g, u, &q0, &m);
  us_Status st = US_OK;
  for (long j = 0; !st && j <= m; j++) {
    long i = u->backward ? m - j : j;
    st = add_piece(c, u, cut(c->g, u, q0, m, i), cut(c->g, u, q0, m, i + 1), err);
  }
  return st;
}

/* Course c->r: the left return, the main wall, the right return. In even
 * courses the main wall runs through the corners, in odd ones the returns. */
static us_Status add_course(Course *c, us_Error *err) {
  const us_GenSettings *g = c->g;
  double t = g->thickness, cw = us_gen_half(g, 2L * g->cols), lw = us_gen_half(g, 2L * g->returns);
  double xr = cw - t; /* the right return's inner face */
  int main_through = c->r % 2 == 0;
  double rlo = main_through ? t : 0.0;
  long rpar = main_through ? 1 : 0;
  Run left = {.axis = 1, .backward = 1, .parity = rpar, .lo = rlo, .hi = lw, .a0 = 0.0, .a1 = t};
  Run mid = {.axis = 0, .parity = main_through ? 0 : 1, .lo = main_through ? 0.0 : t,
             .hi = main_through ? cw : xr, .a0 = 0.0, .a1 = t};
  Run right = {.axis = 1, .parity = rpar, .lo = rlo, .hi = lw, .a0 = xr, .a1 = cw};
  us_Status st = add_run(c, &left, err);
  if (!st) st = add_run(c, &mid, err);
  if (!st) st = add_run(c, &right, err);
  return st;
}

/* The number of bricks (see the count above), as a double: no overflow. */
static double brick_count(const us_GenSettings *g) {
  int closers = us_gen_half(g, 1) > g->thickness + SLIVER * g->width;
  return (double)g->rows * ((double)g->cols + 2.0 * g->returns + 2.0 * closers) - (double)(g->rows / 2);
}

/* The wall's settings, the returns' own conditions and the body limit. */
static us_Status check_returns(const us_GenSettings *g, us_Error *err) {
  if (!g) return us_gen_check_common(g, "wall3d", err);
  double n = brick_count(g);
  long total = n > 1e18 ? (long)1e18 : n < 0 ? 0 : (long)n; /* bad counts are named below */
  us_Status st = us_gen_check_blocks(g, "wall3d", g->rows, "rows", total, err);
  if (!st && g->cols < 1) st = us_error_set(err, US_ERR_USAGE, "wall3d: cols must be >= 1, got %d", g->cols);
  if (!st) st = us_gen_check_positive(g->thickness, "wall3d", "thickness", err);
  if (!st && g->returns < 0)
    st = us_error_set(err, US_ERR_USAGE, "wall3d: returns must be >= 0 (bricks), got %d", g->returns);
  if (!st && !(g->thickness < g->width))
    st = us_error_set(err, US_ERR_USAGE,
                      "wall3d: returns need the thickness (%g) below the block width (%g): the "
                      "corner bond takes bricks longer than they are deep",
                      g->thickness, g->width);
  if (!st && !(us_gen_half(g, 2L * g->cols) - 2.0 * g->thickness > SLIVER * g->width))
    st = us_error_set(err, US_ERR_USAGE,
                      "wall3d: returns need the wall longer than twice its thickness (cols x block "
                      "width = %g, thickness %g): the two returns would meet",
                      us_gen_half(g, 2L * g->cols), g->thickness);
  return st;
}

us_Structure *us_gen_wall3d_returns(const us_GenSettings *g, us_Error *err) {
  if (check_returns(g, err)) return NULL;
  us_Structure *s = us_gen_begin_dim(g, 3, err);
  us_Status st = s ? US_OK : US_ERR_NOMEM;
  int k = 0;
  for (int r = 0; !st && r < g->rows; r++) {
    Course c = {s, g, &k, r};
    st = add_course(&c, err);
  }
  if (st) {
    us_structure_free(s);
    return NULL;
  }
  return us_gen_finish(s, g, err);
}
