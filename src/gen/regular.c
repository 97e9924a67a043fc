/* Regular masonry scenes: a column, a stack-bond pyramid and a running-bond
 * wall of rectangular blocks standing on the ground.
 *
 * Layout: x grows to the right from 0, y up from the ground (y = 0); row k
 * (0-based from the bottom) spans [k h, (k + 1) h]. Bodies are numbered
 * row by row from the bottom, left to right within a row ("b1" is the
 * leftmost block of the bottom row).
 *
 * Coordinates are computed from integer half-block indices, x = q * (w / 2),
 * so an edge shared by two blocks (side by side or one row above the other)
 * has bit-identical coordinates in both: contacts are exact, never a tiny
 * gap or overlap.
 *
 * The wall is one design for both dimensions: in 3D (wall3d) every brick
 * is a box from y = 0 to y = thickness, rows going up along z (the 3D
 * vertical), so the 3D wall is the 2D wall extruded. With corner returns
 * (g->returns > 0) the 3D wall is built by corner.c on the same grid. */
#include "gen.h"

/* The x coordinate of half-block index q. */
static double half_x(const us_GenSettings *g, long q) { return us_gen_half(g, q); }

/* The y coordinate of row boundary k. */
static double row_y(const us_GenSettings *g, int k) { return us_gen_course(g, k); }

/* Add block number *k spanning half-block indices [q0, q1] in row r. */
static us_Status add_row_block(us_Structure *s, const us_GenSettings *g, int *k, int r, long q0,
                               long q1, us_Error *err) {
  us_Status st = s->dim == 3 ? us_gen_add_box3(s, g, *k, half_x(g, q0), 0.0, row_y(g, r),
                                               half_x(g, q1), g->thickness, row_y(g, r + 1), err)
                             : us_gen_add_box(s, g, *k, half_x(g, q0), row_y(g, r), half_x(g, q1),
                                              row_y(g, r + 1), err);
  if (!st) (*k)++;
  return st;
}

/* Column: g->n blocks of g->width x g->height, aligned, b1 on the ground. */
us_Structure *us_gen_column(const us_GenSettings *g, us_Error *err) {
  if (us_gen_check_blocks(g, "column", g ? g->n : 0, "n", g ? (long)g->n : 0, err)) return NULL;
  us_Structure *s = us_gen_begin(g, err);
  us_Status st = s ? US_OK : US_ERR_NOMEM;
  for (int k = 0, r = 0; !st && r < g->n; r++) st = add_row_block(s, g, &k, r, 0, 2, err);
  if (st) {
    us_structure_free(s);
    return NULL;
  }
  return us_gen_finish(s, g, err);
}

/* Pyramid in stack bond: g->n rows; row r holds n - r blocks and starts
 * half a block further right than row r - 1, so each row is centred on the
 * one below. n rows hold n (n + 1) / 2 blocks (13 rows: 91). */
us_Structure *us_gen_pyramid(const us_GenSettings *g, us_Error *err) {
  long n = g ? (long)g->n : 0;
  if (us_gen_check_blocks(g, "pyramid", g ? g->n : 0, "n (rows)", n * (n + 1) / 2, err)) return NULL;
  us_Structure *s = us_gen_begin(g, err);
  us_Status st = s ? US_OK : US_ERR_NOMEM;
  int k = 0;
  for (int r = 0; !st && r < g->n; r++)
    for (long j = 0; !st && j < n - r; j++) st = add_row_block(s, g, &k, r, r + 2 * j, r + 2 * j + 2, err);
  if (st) {
    us_structure_free(s);
    return NULL;
  }
  return us_gen_finish(s, g, err);
}

/* One wall row: even rows hold C full bricks; odd rows a half brick, C - 1
 * full bricks and a half brick, so every row is C * width long. */
static us_Status wall_row(us_Structure *s, const us_GenSettings *g, int *k, int r, us_Error *err) {
  long c = g->cols;
  if (r % 2 == 0) {
    us_Status st = US_OK;
    for (long j = 0; !st && j < c; j++) st = add_row_block(s, g, k, r, 2 * j, 2 * j + 2, err);
    return st;
  }
  us_Status st = add_row_block(s, g, k, r, 0, 1, err);
  for (long j = 0; !st && j < c - 1; j++) st = add_row_block(s, g, k, r, 2 * j + 1, 2 * j + 3, err);
  if (!st) st = add_row_block(s, g, k, r, 2 * c - 1, 2 * c, err);
  return st;
}

/* Wall in running bond: g->rows rows of g->cols bricks (odd rows one more,
 * with the half bricks): ceil(R/2) C + floor(R/2) (C + 1) bricks in all
 * (25 x 40: 1,012), in dimension dim. */
static us_Structure *wall(const us_GenSettings *g, int dim, us_Error *err) {
  const char *what = dim == 3 ? "wall3d" : "wall";
  long r = g ? (long)g->rows : 0, c = g ? (long)g->cols : 0;
  long total = (r + 1) / 2 * c + r / 2 * (c + 1);
  if (us_gen_check_blocks(g, what, g ? g->rows : 0, "rows", total, err)) return NULL;
  if (c < 1) {
    us_error_set(err, US_ERR_USAGE, "%s: cols must be >= 1, got %ld", what, c);
    return NULL;
  }
  if (dim == 3 && us_gen_check_positive(g->thickness, what, "thickness", err)) return NULL;
  us_Structure *s = us_gen_begin_dim(g, dim, err);
  us_Status st = s ? US_OK : US_ERR_NOMEM;
  int k = 0;
  for (int row = 0; !st && row < g->rows; row++) st = wall_row(s, g, &k, row, err);
  if (st) {
    us_structure_free(s);
    return NULL;
  }
  return us_gen_finish(s, g, err);
}

us_Structure *us_gen_wall(const us_GenSettings *g, us_Error *err) { return wall(g, 2, err); }

/* The wall in 3D: bricks g->thickness deep (y), rows along z; with
 * g->returns, the returns at both ends (corner.c). */
us_Structure *us_gen_wall3d(const us_GenSettings *g, us_Error *err) {
  if (g && g->returns != 0) return us_gen_wall3d_returns(g, err);
  return wall(g, 3, err);
}
