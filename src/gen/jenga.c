/* A Jenga tower: g->n levels of 3 pieces, alternating direction, with
 * chosen pieces knocked out.
 *
 * Layout: a piece is 3 w long, w wide and h high (w = g->width, h =
 * g->height; the game's pieces are 7.5 x 2.5 x 1.5 cm, h = 0.6 w, the
 * CLI's default). Level L (1-based from the ground) spans z in [(L - 1) h,
 * L h]; odd levels run along x (piece P covers y in [(P - 1) w, P w]),
 * even levels along y (piece P covers x in [(P - 1) w, P w]), so the tower
 * stands on the square [0, 3w]^2 and every piece crosses the three of the
 * level below on w x w squares. Coordinates are integer multiples of w
 * and h, so contacts are exact faces.
 *
 * Removal: g->remove holds g->nremove (level, position) pairs, position 1
 * and 3 the sides, 2 the middle; a listed piece is simply not built (a
 * piece listed twice is an error). Bodies are numbered level by level from
 * the ground, by position within a level, skipping removed pieces; a
 * piece's id stays "b<3 (L - 1) + P>" so ids name the piece whatever was
 * removed.
 *
 * Statics (a rigid model): with the middle piece gone a level stands on its
 * two sides, whose hull holds the centre line; with both sides gone the
 * tower above balances on the middle piece, whose strip holds the centre:
 * it stands as well. A level reduced to one side piece puts the centre of
 * the tower above outside its support: everything above it falls (unless
 * it is the top level). */
#include "gen.h"


static us_Status check_jenga(const us_GenSettings *g, us_Error *err) {
  us_Status st = us_gen_check_common(g, "jenga", err);
  if (!st) st = us_gen_check_positive(g->width, "jenga", "block width", err);
  if (!st) st = us_gen_check_positive(g->height, "jenga", "block height", err);
  if (!st && g->n < 1) st = us_error_set(err, US_ERR_USAGE, "jenga: levels must be >= 1, got %d", g->n);
  if (!st && 3L * g->n > US_GEN_MAX_BODIES)
    st = us_error_set(err, US_ERR_USAGE, "jenga: %d levels is more than the limit", g->n);
  if (!st && g->nremove > 0 && !g->remove)
    st = us_error_set(err, US_ERR_USAGE, "jenga: %d pieces to remove but no list", g->nremove);
  for (int k = 0; !st && k < g->nremove; k++) {
    int lv = g->remove[2 * k], p = g->remove[2 * k + 1];
    if (lv < 1 || lv > g->n || p < 1 || p > 3)
      st = us_error_set(err, US_ERR_USAGE,
                        "jenga: cannot remove %d:%d: levels are 1..%d, positions 1..3", lv, p, g->n);
    for (int i = 0; !st && i < k; i++)
      if (g->remove[2 * i] == lv && g->remove[2 * i + 1] == p)
        st = us_error_set(err, US_ERR_USAGE, "jenga: piece %d:%d is removed twice", lv, p);
  }
  return st;
}

static int removed(const us_GenSettings *g, int level, int pos) {
  for (int k = 0; k < g->nremove; k++)
    if (g->remove[2 * k] == level && g->remove[2 * k + 1] == pos) return 1;
  return 0;
}

/* Piece `pos` of `level` (both 1-based), id b<3 (level - 1) + pos>. */
static us_Status add_piece(us_Structure *s, const us_GenSettings *g, int level, int pos,
                           us_Error *err) {
  double w = g->width, a = (double)(pos - 1) * w, b = (double)pos * w, len = 3.0 * w;
  double z0 = (double)(level - 1) * g->height, z1 = (double)level * g->height;
  int k = 3 * (level - 1) + pos - 1;
  return level % 2 ? us_gen_add_box3(s, g, k, 0.0, a, z0, len, b, z1, err)
                   : us_gen_add_box3(s, g, k, a, 0.0, z0, b, len, z1, err);
}

us_Structure *us_gen_jenga(const us_GenSettings *g, us_Error *err) {
  if (check_jenga(g, err)) return NULL;
  us_Structure *s = us_gen_begin_dim(g, 3, err);
  us_Status st = s ? US_OK : US_ERR_NOMEM;
  for (int lv = 1; !st && lv <= g->n; lv++)
    for (int p = 1; !st && p <= 3; p++)
      if (!removed(g, lv, p)) st = add_piece(s, g, lv, p, err);
  if (st) {
    us_structure_free(s);
    return NULL;
  }
  return us_gen_finish(s, g, err);
}
