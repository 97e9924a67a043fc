/* Lemke's method with a lexicographic ratio test on a dense tableau
 * (lemke.c): the pivoting core shared by the lp-lcp backend (lp_lcp.c,
 * the statics LP as a skew-symmetric LCP) and the cone LCP's exact
 * fallback (lcp_lemke.c, a symmetric PSD LCP).
 *
 * The caller fills the starting tableau of w = M z + q + e z0 (every w
 * basic: row i holds M's row i, qb = q) after us_lemke_clear, may pivot
 * pairs in itself (a warm start), then calls us_lemke_run. Variables are
 * numbered w_i = i, z_i = dim + i, z0 = 2 dim. */
#ifndef US_STABILITY_LEMKE_H
#define US_STABILITY_LEMKE_H

#include "core/core.h"

typedef enum us_LemkeEnd {
  US_LEMKE_GO = 0, /* still running (us_lemke_limits) */
  US_LEMKE_SOLVED, /* z0 left: the basic solution solves the LCP */
  US_LEMKE_RAY,    /* a secondary ray: nothing blocks the entering column */
  US_LEMKE_LIMIT,  /* pivot limit */
  US_LEMKE_TIME,   /* deadline */
  US_LEMKE_NONFINITE /* a basic value is not finite (data beyond doubles) */
} us_LemkeEnd;

/* Tableau (Tucker's condensed form): row i reads
 *   basic_i = qb_i + sum_j t[i][j] nonbasic_j,
 * dim rows of width dim + 1 (the dim nonbasic members of the pairs and
 * z0). pos[v] is the row of a basic v, or -(column + 1). */
typedef struct us_Lemke {
  int dim;
  double *t, *qb;
  int *rowvar, *colvar, *pos; /* [dim], [dim + 1], [2 dim + 1] */
  int *ref;                   /* [dim] basic variable of each row at the run's start */
  int *nz, *ties;             /* scratch: [dim + 1], [dim] */
  int cap_t, cap_q, cap_rv, cap_cv, cap_pos, cap_ref, cap_nz, cap_ties;
  long pivots;     /* total */
  long limit;      /* us_lemke_limits stops when pivots reaches this */
  double deadline; /* us_now() time, 0: none */
} us_Lemke;

/* Room for dim pairs; sets k->dim. 0, or -1 (out of memory, or a tableau
 * above 2^28 cells). */
int us_lemke_reserve(us_Lemke *k, int dim);
void us_lemke_free(us_Lemke *k);
/* The empty start: t = 0 but the covering column (1), qb = 0, every w
 * basic. */
void us_lemke_clear(us_Lemke *k);
/* Exchange the basic variable of row r with the nonbasic of column s. */
void us_lemke_pivot(us_Lemke *k, int r, int s);
/* US_LEMKE_LIMIT, US_LEMKE_TIME (looked at every 64 pivots) or GO. */
us_LemkeEnd us_lemke_limits(const us_Lemke *k);
/* Lemke's method from the current complementary basis with covering
 * vector e in its coordinates. US_LEMKE_RAY leaves the unblocked column
 * in *ray_col. */
us_LemkeEnd us_lemke_run(us_Lemke *k, int *ray_col);
/* The default pivot limit of a run on dim pairs: 20 dim + 200 (the
 * lexicographic path is finite but not polynomially bounded; in practice
 * it takes a few pivots per pair). */
long us_lemke_default_limit(int dim);
/* The value of variable v in the basic solution (0 if nonbasic). */
double us_lemke_value(const us_Lemke *k, int v);
/* The ray's direction of variable v when column s enters. */
double us_lemke_ray_dir(const us_Lemke *k, int v, int s);

static inline double *us_lemke_row(const us_Lemke *k, int r) {
  return k->t + (size_t)r * (size_t)(k->dim + 1);
}

#endif
