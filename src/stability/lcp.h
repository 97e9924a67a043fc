/* Private interface of the LCP solver (Baraff 1994, Dantzig's principal
 * pivoting) used by the LCP stability backends, exposed so that the solver
 * can be tested on raw (A, b) problems.
 *
 * The problem: indices i = 0..n-1 of two kinds.
 *   normal   i: f_i >= 0, a_i >= 0, f_i a_i = 0;
 *   friction t (partner normal n, coefficient mu > 0): |f_t| <= mu f_n,
 *              a_t (mu f_n - |f_t|) = 0, a_t f_t <= 0 (2D static friction,
 *              the bound moves with f_n);
 * with a = A f + b, A symmetric (J M^-1 J^T). A is reached only through callbacks (an entry on
 * demand, a sparse product, a full recomputation of a), so a caller can
 * keep A implicit (A = J M^-1 J^T through the bodies, lcp_sys.c).
 *
 * Only `live` indices take part; the others keep f = 0 and are ignored.
 * The solver keeps its state (forces, index sets, the factorized clamped
 * system) between runs, which is what computation reuse builds on:
 * us_lcp_add (new indices, driven from zero) and us_lcp_fade (indices whose
 * forces are driven to zero and which then leave).
 */
#ifndef US_LCP_H
#define US_LCP_H

#include "core/core.h"

typedef struct us_LcpOps {
  void *ctx;
  /* A_ij */
  double (*entry)(void *ctx, int i, int j);
  /* y = A x for x non-zero only at idx[0..k) (values x[0..k)): writes y[i]
   * for every index i it lists in out[] (returns the count; out holds n).
   * Unlisted indices have y_i = 0. May list non-live indices. */
  int (*apply)(void *ctx, const int *idx, const double *x, int k, double *y, int *out);
  /* a = A f + b for every index with live[i] != 0 (others untouched). */
  void (*full)(void *ctx, const double *f, const unsigned char *live, double *a);
} us_LcpOps;

enum { US_LCP_NORMAL = 0, US_LCP_FRICTION = 1 };

/* Index states. OFF: friction whose normal is not clamped (f_t = 0, no
 * condition) or a non-live index. PEND: queued for a drive. NC: normal with
 * f = 0, a >= 0. C: clamped (a = 0), a row of the factorized system. BND:
 * friction at its bound f_t = s mu f_n (row f_t - s mu f_n = 0 of the
 * system). FREE: an index that could not join the system (redundant,
 * a ~ 0; keeps its force, unwatched by the ratio test), re-checked at the
 * end of every run. DRV: being driven. */
enum { US_LCP_OFF = 0, US_LCP_PEND, US_LCP_NC, US_LCP_C, US_LCP_BND, US_LCP_FREE, US_LCP_DRV };

/* Outcome of a run. */
typedef enum us_LcpResult {
  US_LCP_SOLVED = 0, /* every live index satisfies its conditions */
  US_LCP_LIMIT,      /* pivot limit reached */
  US_LCP_DEGENERATE, /* tiny pivot where one is needed, unbounded drive,
                        cycling, or conditions not restored */
  US_LCP_NOMEM
} us_LcpResult;

/* One pivot, reported to an optional trace callback. */
typedef struct us_LcpStep {
  int driven;      /* driven index, -1 for a fade */
  double lambda;   /* step length (in units of the driven force) */
  int event;       /* US_LCP_EV_* */
  int index;       /* index that changed set */
  const double *f; /* forces after the step (n) */
  const double *a; /* accelerations after the step (n, live only) */
} us_LcpStep;

enum {
  US_LCP_EV_DONE = 0, /* the driven a reached 0: it is clamped */
  US_LCP_EV_ZERO,     /* the driven normal force reached 0: NC */
  US_LCP_EV_BOUND,    /* the driven friction reached its bound */
  US_LCP_EV_C_NC,     /* a clamped normal force reached 0 */
  US_LCP_EV_NC_C,     /* a non-clamped normal a reached 0 */
  US_LCP_EV_C_BND,    /* a sticking friction reached its bound */
  US_LCP_EV_BND_C,    /* a friction at its bound stopped sliding */
  US_LCP_EV_FADED     /* a fade finished */
};

/* lcp_dense.c: a dense inverse H = K^-1 (k x k, leading dimension cap),
 * updated by bordering (append) and Schur complement (delete), O(k^2)
 * each. */
typedef struct us_DenseInv {
  int k, cap;
  double *H;
  double *y, *z; /* [cap] scratch */
  int *nz;       /* [cap] scratch */
} us_DenseInv;

/* Room for `need` rows. 0 or -1. */
int us_dinv_reserve(us_DenseInv *d, int need);
void us_dinv_free(us_DenseInv *d);
/* Border K with column u, row v, corner alpha. 0, 1 if the pivot is tiny
 * (|sigma| <= tol: nothing changes), -1 OOM. */
int us_dinv_append(us_DenseInv *d, const double *u, const double *v, double alpha, double tol);
/* Delete row and column s (the last one moves into s). 1 if the rest
 * looks singular, else 0. */
int us_dinv_delete(us_DenseInv *d, int s);
/* x = H r (x and r distinct). */
void us_dinv_mult(const us_DenseInv *d, const double *r, double *x);

/* lcp_factor.c: the clamped system as a block LU, a sparse LU (KLU) of a
 * base K0 bordered by the changes since (see the file). */
typedef struct us_LcpFactor {
  int n0;             /* base size (0: no base, all members are border) */
  int *bidx;          /* [n0] member index of each base slot */
  unsigned char *gone; /* [n0] base member that left (has a DEL item) */
  double *x0;         /* [n0] scratch */
  void *klu;          /* KLU common, symbolic and numeric objects */
  int m, mcap;        /* border items */
  int *item;          /* [mcap] >= 0: ADD item (member index); -1 - j: DEL of base slot j */
  double **y;         /* [mcap] K0^-1 u_b (n0 each, NULL when n0 == 0) */
  int **vi;           /* [mcap] sparse base part of an ADD item's row */
  double **vx;
  int *vn;
  us_DenseInv S;      /* inverse of the border's Schur complement */
  int *bpos, *ipos;   /* [n] member -> base slot / border item, or -1 */
  double *w, *uc, *vr; /* [mcap] scratch */
  int limit;          /* refactorize when the border has more items */
  long updates;       /* border changes since the last refactorization */
  long refactors;
} us_LcpFactor;

typedef struct us_Lcp {
  int n;
  us_LcpOps ops;
  signed char *kind; /* US_LCP_NORMAL / FRICTION */
  int *partner;      /* normal: its friction or -1; friction: its normal */
  double *mu;        /* friction coefficient of a friction index */
  unsigned char *live;
  signed char *state;
  signed char *bsign; /* BND: the sign s of f_t = s mu f_n */
  double *f, *a;
  /* clamped system: members mem[0..k), pos[i] = member slot or -1, the
   * system matrix K factorized in fac */
  int k, cap;
  int *mem, *pos;
  us_LcpFactor fac;
  /* drive queue (FIFO ring of n), inq[i] = queued */
  int *queue, qhead, qlen;
  unsigned char *inq;
  /* scratch */
  double *dfm;   /* member force increments [cap] */
  double *r, *e; /* [cap] */
  double *da;            /* [n] */
  int *out, *didx;       /* [n] */
  double *dval;          /* [n] driven direction values */
  unsigned char *zmark;  /* [n] changed set during the current zero-step streak */
  int *zlist;            /* [n] the marked indices */
  /* settings and counters */
  long max_pivots; /* per run; <= 0: 4 n + 1000 */
  long pivots;     /* total */
  long deferred;   /* redundant indices left out of the system */
  long rebuilds;   /* refactorizations of the clamped system (total) */
  double tol_a, tol_f, tol_piv;
  const char *why; /* reason of the last DEGENERATE end (static string) */
  void (*trace)(void *ud, const us_LcpStep *st);
  void *trace_ud;
} us_Lcp;

/* n indices, all normals, none live. 0 or -1 on OOM. */
int us_lcp_init(us_Lcp *p, int n, const us_LcpOps *ops);
void us_lcp_free(us_Lcp *p);
/* Make friction index t the friction of normal n with coefficient mu > 0. */
void us_lcp_set_friction(us_Lcp *p, int t, int n, double mu);
/* Forget everything: f = 0, nothing live, empty system. */
void us_lcp_reset(us_Lcp *p);
/* Make indices live with f = 0; normals are queued for a drive (their
 * frictions are queued once the normal is clamped). */
void us_lcp_add(us_Lcp *p, const int *idx, int k);
/* Drive the forces of live indices idx[0..k) to zero along a straight line
 * while every other live index keeps its conditions (pivoting as needed),
 * then make them non-live. The caller must have changed A so that these
 * indices no longer couple with the rest only after this call. */
us_LcpResult us_lcp_fade(us_Lcp *p, const int *idx, int k);
/* Drive every queued index, then re-check all live indices (fresh a) and
 * drive the violated ones until none is left. */
us_LcpResult us_lcp_run(us_Lcp *p);
/* Start from the forces in f (live indices; e.g. the LP's static
 * solution): index sets from the forces, a fresh factorization, then a run
 * that repairs any violated condition. */
us_LcpResult us_lcp_seed(us_Lcp *p);
/* Recompute a from f for the live indices. */
void us_lcp_refresh(us_Lcp *p);

/* lcp_factor.c: the clamped system K over the members (slot order). */
int us_lcp_fac_init(us_Lcp *p);
void us_lcp_fac_free(us_Lcp *p);
/* Forget the members and the factorization. */
void us_lcp_fac_reset(us_Lcp *p);
/* Room for `need` members (mem and the slot scratch dfm, r, e). 0 or -1. */
int us_lcp_fac_reserve(us_Lcp *p, int need);
/* Member idx joins: u = K[members, idx], v = K[idx, members] (by slot),
 * alpha = K[idx, idx]. 0, 1 if the pivot is tiny (|sigma| <= tol; nothing
 * changes), -1 OOM. */
int us_lcp_fac_append(us_Lcp *p, int idx, const double *u, const double *v, double alpha,
                      double tol);
/* The member in slot s leaves (the last member moves into s). 0, 1 if the
 * rest looked singular (it was refactorized, deferring dependent members),
 * -1 OOM. */
int us_lcp_fac_delete(us_Lcp *p, int s);
/* x = K^-1 r (by slot; x and r distinct). */
void us_lcp_fac_solve(us_Lcp *p, const double *r, double *x);
/* Refactorize K from the members; a member found dependent is deferred
 * (state FREE). 0 or -1 (OOM). Uses the scratch da / out. */
int us_lcp_fac_rebuild(us_Lcp *p);
/* The border has grown past its limit: time to rebuild. */
int us_lcp_fac_stale(const us_Lcp *p);
/* Bytes held by the factorization; *lu_nnz (if not NULL) the LU entries. */
double us_lcp_fac_bytes(const us_Lcp *p, long *lu_nnz);

/* ------------------------------------------------- lcp_sys.c: A = J M^-1 J^T
 *
 * The operator of a 2D structure: LCP index 2c is the normal of structure
 * contact c, 2c + 1 its friction. Per body, generalized coordinates
 * (x, y, angle * L) with masses (m, m, I / L^2) / m_total, forces in units
 * of the weight W, torques / (W L): the normalization of us_EqSystem. */
typedef struct us_LcpSys {
  const us_Structure *s;
  int nbody, ncontact;
  double *minv;           /* [3 nbody] inverse masses (normalized) */
  double *fext;           /* [3 nbody] external force (normalized), present only */
  unsigned char *present; /* [nbody] movable and in the sub-assembly */
  int *cb;                /* [2 ncontact] the bodies of a contact (-1: fixed/ground) */
  double *w;              /* [12 ncontact]: (index 2c+k, side) -> 3 wrench rows */
  int *adj_start, *adj;   /* contacts of each body */
  double *u;              /* [3 nbody] scratch, kept zero */
  int *touched;           /* [nbody] */
  unsigned char *bmark;   /* [nbody] */
  unsigned char *cmark;   /* [ncontact] */
} us_LcpSys;

int us_lcp_sys_init(us_LcpSys *y, const us_Structure *s);
void us_lcp_sys_free(us_LcpSys *y);
us_LcpOps us_lcp_sys_ops(us_LcpSys *y);
/* Per-index wrench on body side `side` of LCP index i (3 values). */
static inline const double *us_lcp_sys_w(const us_LcpSys *y, int i, int side) {
  return y->w + ((size_t)i * 2 + (size_t)side) * 3;
}
/* Net normalized wrench r = E f + F_ext on every present body; returns the
 * largest component magnitude and the body (index) where it occurs, and
 * (energy not NULL) v^T M v = sum r^T M^-1 r with v the accelerations. */
double us_lcp_sys_residual(us_LcpSys *y, const double *f, int *worst_body, double *energy);

#endif
