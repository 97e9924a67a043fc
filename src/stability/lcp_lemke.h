/* The cone LCP solved by Lemke's method (lcp_lemke.c): the exact
 * fallback of the LCP backends where the cone LCP's own Dantzig pivoting
 * (lcp.c) ends degenerate or at its pivot limit. */
#ifndef US_STABILITY_LCP_LEMKE_H
#define US_STABILITY_LCP_LEMKE_H

#include "lcp.h"
#include "lemke.h"

/* Workspace: the dense tableau and the map from its columns to LCP
 * indices. Zero-initialize; free with us_lcp_lemke_free. */
typedef struct us_LcpLemke {
  us_Lemke lk;
  int *col;          /* [dim] LCP index of each column */
  signed char *sgn;  /* [dim] +1, or -1: the negative part of a free index */
  int *colof;        /* [n] first column of an LCP index, -1 if none */
  double *d;         /* [n] scale of an index: 1 / sqrt(A'_ii) */
  double *b, *zero, *y; /* [n] scratch */
  int *out;          /* [n] scratch */
  int cap_col, cap_sgn, cap_colof, cap_d, cap_b, cap_zero, cap_y, cap_out;
} us_LcpLemke;

/* Outcome of us_lcp_lemke. */
typedef enum us_LcpLemkeEnd {
  US_LCP_LEMKE_SOLVED = 0, /* p->f holds a solution (live indices) */
  US_LCP_LEMKE_TOO_BIG,    /* more columns than max_dim: not tried */
  US_LCP_LEMKE_NOT_PSD,    /* a live friction with a finite mu: not a cone LCP */
  US_LCP_LEMKE_RAY,        /* a secondary ray (round-off: the LCP is feasible) */
  US_LCP_LEMKE_LIMIT,      /* pivot limit, deadline or non-finite data */
  US_LCP_LEMKE_NOMEM
} us_LcpLemkeEnd;

/* Solve the LCP of p's live indices, all normals (l >= 0, a >= 0,
 * l a = 0) or frictions with mu = +inf (free, a = 0), by Lemke's method
 * from the start, and write the solution into p->f. Only f changes: p's
 * index sets and factorization no longer describe it (reset or seed p
 * before its next run). *pivots grows by the pivots made. */
us_LcpLemkeEnd us_lcp_lemke(us_LcpLemke *k, us_Lcp *p, int max_dim, long *pivots);
void us_lcp_lemke_free(us_LcpLemke *k);

#endif
