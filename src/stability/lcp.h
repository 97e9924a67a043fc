/* Private interface of the LCP solver (Baraff 1994, Dantzig's principal
 * pivoting, lcp.c) used by the LCP stability backends, exposed so that the
 * solver can be tested on raw (A, b) problems. Its parts have their own
 * headers: the operator interface (lcp_ops.h), the factorized clamped
 * system (lcp_factor.h, lcp_dense.h), the operator of a structure
 * (lcp_sys.h), the backends' private constructor (lcp_backend.h).
 *
 * The problem: indices i = 0..n-1 of two kinds.
 *   normal   i: f_i >= 0, a_i >= 0, f_i a_i = 0;
 *   friction t (partner normal n, coefficient mu > 0): |f_t| <= mu f_n,
 *              a_t (mu f_n - |f_t|) = 0, a_t f_t <= 0 (2D static friction,
 *              the bound moves with f_n);
 *   friction t with mu = +inf (no sliding: the cone is the half-space
 *              f_n >= 0): f_t free, a_t = 0, whatever f_n;
 * with a = A f + b, A symmetric (J M^-1 J^T), reached through us_LcpOps.
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
#include "lcp_factor.h"
#include "lcp_ops.h"

/* Every limit and tolerance of the solver and of the LCP backends, with
 * its default from us_lcp_default_settings(). Forces are in the
 * operator's units (the backends: units of the structure's weight W). */
typedef struct us_LcpSettings {
  /* ---- the solver (lcp.c) */
  long max_pivots;       /* pivots per run; <= 0: pivots_per_index * n + pivots_base */
  double deadline;       /* us_now() time (0: none): a run past it stops as
                            US_LCP_LIMIT (checked every 64 pivots) */
  int pivots_per_index;  /* 4 */
  long pivots_base;      /* 1000 */
  double tol_a;          /* 1e-9: |a| below this counts as 0 (drives, checks) */
  double tol_f;          /* 1e-12: a normal force below this counts as 0 */
  double tol_piv;        /* 1e-6: a join whose Schur pivot is <= this times
                            |A_ii| (1 for a bound row) is refused: deferred */
  double tol_piv3;       /* 1e-13: the same for the 3D pivoting (lcp3_piv.c),
                            whose ratio test copes with small pivots */
  double pivot_floor;    /* 1e-300: floor of |A_ii| in that test */
  double ratio_tol;      /* 1e-11: the ratio test ignores increments below
                            this times the largest increment (forces / a) */
  double zero_step;      /* 1e-14: a step this short counts as zero length */
  double tie_window;     /* 1e-13: steps within this (relative) tie */
  int refine_rounds;     /* 2: iterative refinement rounds per direction */
  double refine_tol;     /* 1e-12: refine while the members' rows are off
                            by more than this times the largest increment */
  int zero_streak_per_index; /* 2: a run of more than this * n + */
  int zero_streak_base;      /* 20 zero-length steps is DEGENERATE */
  int zero_rebuild_streak;   /* 8: after this many zero-length steps in a */
  int zero_rebuild_border;   /* row with more than 16 border items: refactorize */
  int polish_rounds;     /* 3: Newton rounds of the final check's polish,
                            then a refactorization and as many again */
  double polish_tol;     /* 1e-3: polish while the rows drift by more than
                            this times tol_a */
  double check_tol_f;    /* 1e3: force tolerance of the final check, in
                            units of tol_f (times 1 + the largest force) */
  double force_limit;    /* 1e12: larger forces ran away along a nearly
                            unbounded ray: DEGENERATE, not a solution */
  int check_passes;      /* 50: final checks (drive, check again) per run */
  double seed_cone_margin; /* 1e-9: a seeded friction within this (relative)
                              of its bound starts at the bound */
  us_LcpFactorSettings factor; /* the factorization (lcp_factor.h) */
  /* ---- the backends (lcp_backend.c) */
  long reuse_pivots;     /* 1000: automatic pivot limit of a reused run, */
  int reuse_pivots_div;  /* 4: plus n / this */
  double eq_tol;         /* 1e-9: net wrench (units of W) below this: STABLE */
  double unstable_tol;   /* 1e-6: above this, exactly proven: UNSTABLE */
  double cone_slack;     /* 1e-12: round-off slack of the dual-cone test */
  double energy_slack;   /* 1e-10: v^T M v must exceed f^T a by this */
  int max_backoff;       /* 20: lcp-reuse skips at most 2^(this-1) - 1
                            tests after failures in a row */
  int lemke_max_dim;     /* 800: the cone LCP by Lemke (lcp_lemke.c) where
                            its Dantzig run fails, up to this many columns
                            (a dense tableau); larger ones go to the LP */
} us_LcpSettings;

us_LcpSettings us_lcp_default_settings(void);

enum { US_LCP_NORMAL = 0, US_LCP_FRICTION = 1 };

/* Index states. OFF: friction whose normal is not clamped (f_t = 0, no
 * condition) or a non-live index. PEND: queued for a drive. NC: normal with
 * f = 0, a >= 0. C: clamped (a = 0), a row of the factorized system. BND:
 * friction at its bound f_t = s mu f_n (row f_t - s mu f_n = 0 of the
 * system). FREE: an index that could not join the system (redundant,
 * a ~ 0; keeps its force, unwatched by the ratio test), re-checked at the
 * end of every run. DRV: being driven. A friction with mu = +inf is never
 * OFF while live and never BND. */
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

typedef struct us_Lcp {
  int n;
  us_LcpOps ops;
  us_LcpSettings set;
  signed char *kind; /* US_LCP_NORMAL / FRICTION */
  int *partner;      /* normal: its friction or -1; friction: its normal */
  double *mu;        /* friction coefficient of a friction index (> 0, may be +inf) */
  unsigned char *live;
  signed char *state;
  signed char *bsign; /* BND: the sign s of f_t = s mu f_n */
  double *f, *a;
  /* the clamped system: its members (fac.mem[0..fac.k), fac.pos) and
   * the factorized matrix K */
  us_LcpFactor fac;
  /* drive queue (FIFO ring of n), inq[i] = queued */
  int *queue, qhead, qlen;
  unsigned char *inq;
  /* scratch of lcp.c */
  int scap;              /* slots of the slot scratch */
  double *dfm;           /* [scap] member force increments */
  double *r, *e;         /* [scap] */
  double *da;            /* [n] kept zero between pivots */
  int *out, *didx;       /* [n], [2n] */
  double *dval;          /* [2n] driven direction values */
  int *dep;              /* [n] members a refactorization found dependent */
  unsigned char *zmark;  /* [n] changed set during the current zero-step streak */
  int *zlist;            /* [n] the marked indices */
  /* counters */
  long pivots;     /* total */
  long deferred;   /* redundant indices left out of the system */
  long rebuilds;   /* refactorizations of the clamped system (total) */
  const char *why; /* reason of the last DEGENERATE end (static string) */
  void (*trace)(void *ud, const us_LcpStep *st);
  void *trace_ud;
} us_Lcp;

/* n indices, all normals, none live, default settings. 0 or -1 on OOM. */
int us_lcp_init(us_Lcp *p, int n, const us_LcpOps *ops);
/* Replace the settings (also the factorization's); while the system is
 * empty (after init or reset). */
void us_lcp_configure(us_Lcp *p, const us_LcpSettings *set);
void us_lcp_free(us_Lcp *p);
/* Make friction index t the friction of normal n with coefficient mu > 0
 * (+inf: no sliding). */
void us_lcp_set_friction(us_Lcp *p, int t, int n, double mu);
/* Forget everything: f = 0, nothing live, empty system. */
void us_lcp_reset(us_Lcp *p);
/* Make indices live with f = 0; normals (and frictions with mu = +inf)
 * are queued for a drive (other frictions are queued once their normal is
 * clamped). */
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

#endif
