/* The clamped system of the LCP solver, factorized (lcp_factor.c): a
 * sparse LU (KLU) of a base K0 bordered by the changes since, with the
 * border's Schur complement as a dense inverse (lcp_dense.h).
 *
 * The factorization owns the member list (slots 0..k-1, mem / pos) and
 * each member's row: a clamped row (a_i = 0, row i of A) or a bound row
 * f_t + coef f_n = 0 (a friction t at its bound, coef = -s mu). It knows
 * nothing of the solver's index states: a rebuild that finds members
 * (nearly) dependent drops them and returns them to the caller, who
 * decides what they become. */
#ifndef US_LCP_FACTOR_H
#define US_LCP_FACTOR_H

#include "lcp_dense.h"
#include "lcp_ops.h"

/* Limits and thresholds of the factorization (fields of us_LcpSettings). */
typedef struct us_LcpFactorSettings {
  /* refactorize when the border holds more items than this (default 64;
   * 0: refactorize after every change; while the base is empty, systems
   * of up to this many members live in the dense inverse alone) */
  int border_limit;
  /* ... or when the changes since the last refactorization exceed
   * update_per_member * k + update_base (defaults 4 and 64) */
  int update_per_member;
  int update_base;
  /* a pivot |U_jj| of the fresh LU (rows scaled to max 1) at or below
   * this marks its member as dependent (default 1e-9; far below the
   * solver's refusal threshold on arrival, so that a member accepted once
   * is not deferred at the next refactorization and driven in again) */
  double tiny_lu_pivot;
  /* a Schur pivot at or below this when a base member leaves (or a
   * pivot of the dense inverse being deleted) means the rest is singular:
   * refactorize (default 1e-300) */
  double singular_pivot;
} us_LcpFactorSettings;

enum { US_LCP_ROW_NONE = 0, US_LCP_ROW_CLAMP, US_LCP_ROW_BOUND };

typedef struct us_LcpFactor {
  int n;                   /* indices of the problem */
  us_LcpOps ops;           /* A, for the columns of a refactorization */
  us_LcpFactorSettings set;
  /* members: slots 0..k-1 */
  int k, cap;
  int *mem;                /* [cap] member index of each slot */
  int *pos;                /* [n] slot of each index or -1 */
  signed char *row;        /* [n] US_LCP_ROW_* */
  double *bcoef;           /* [n] bound row t: coefficient of f_n */
  int *bnorm;              /* [n] bound row t: its normal n */
  int *bound_of;           /* [n] normal n: the bound row t referring to it, or -1 */
  /* the block LU */
  int n0;                  /* base size (0: no base, all members are border) */
  int *bidx;               /* [n0] member index of each base slot */
  unsigned char *gone;     /* [n0] base member that left (has a DEL item) */
  void *klu;               /* KLU common, symbolic and numeric objects */
  int m, mcap;             /* border items */
  int *item;               /* [mcap] >= 0: ADD item (member index); -1 - j: DEL of base slot j */
  double **y;              /* [mcap] K0^-1 u_b (n0 each, NULL when n0 == 0) */
  int **vi;                /* [mcap] sparse base part of an ADD item's row */
  double **vx;
  int *vn;
  us_DenseInv S;           /* inverse of the border's Schur complement */
  int *bpos, *ipos;        /* [n] member -> base slot / border item, or -1 */
  long updates;            /* border changes since the last refactorization */
  long refactors;
  /* scratch of this file */
  double *x0;              /* [n0] */
  double *w, *uc, *vr;     /* [mcap] */
  double *col;             /* [n] a column of A, kept zero between uses */
  int *out;                /* [n] */
} us_LcpFactor;

/* Defaults of the factorization's settings. */
us_LcpFactorSettings us_lcp_factor_default_settings(void);
/* n indices, no member. set NULL: defaults. 0 or -1 (OOM). */
int us_lcp_fac_init(us_LcpFactor *F, int n, const us_LcpOps *ops, const us_LcpFactorSettings *set);
void us_lcp_fac_free(us_LcpFactor *F);
/* Forget the members and the factorization. */
void us_lcp_fac_reset(us_LcpFactor *F);
/* Room for `need` members. 0 or -1. */
int us_lcp_fac_reserve(us_LcpFactor *F, int need);
/* Member idx joins with a clamped row (bound_normal < 0) or the bound row
 * f_idx + coef f_{bound_normal} = 0: u = K[members, idx], v = K[idx,
 * members] (by slot), alpha = K[idx, idx]. 0, 1 if the pivot is tiny
 * (|sigma| <= tol; nothing changes), -1 OOM. */
int us_lcp_fac_append(us_LcpFactor *F, int idx, int bound_normal, double coef, const double *u,
                      const double *v, double alpha, double tol);
/* Member idx joins the list without an update (the factorization is then
 * out of date: us_lcp_fac_rebuild before the next solve). Room must have
 * been reserved. */
void us_lcp_fac_enlist(us_LcpFactor *F, int idx, int bound_normal, double coef);
/* The member in slot s leaves (the last member moves into s). 0, -1 OOM,
 * or 1 if the rest looked singular: it was refactorized, and the members
 * found dependent then left too; they are listed in dep[0..*ndep) (dep
 * holds n). */
int us_lcp_fac_delete(us_LcpFactor *F, int s, int *dep, int *ndep);
/* x = K^-1 r (by slot; x and r distinct). */
void us_lcp_fac_solve(us_LcpFactor *F, const double *r, double *x);
/* Refactorize K from the members; members found (nearly) dependent leave
 * and are listed in dep (holds n). Returns their count, or -1 (OOM). */
int us_lcp_fac_rebuild(us_LcpFactor *F, int *dep);
/* The border has grown past its limits: time to rebuild. */
int us_lcp_fac_stale(const us_LcpFactor *F);
/* Bytes held by the factorization; *lu_nnz (if not NULL) the LU entries. */
double us_lcp_fac_bytes(const us_LcpFactor *F, long *lu_nnz);

#endif
