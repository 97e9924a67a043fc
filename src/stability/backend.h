/* The interface every stability backend implements (lp_clp.c,
 * lp_lpsolve.c, lcp_backend.c, lp_lcp.c), in the settings / workspace / solve shape.
 *
 * The front end (stability.c) owns the public workspace: it tracks the
 * last tested sub-assembly, builds the equilibrium system of the next one
 * (equilibrium.h), hands the backend the list of bodies added and removed
 * since its previous call (computation reuse), scales the forces back to
 * newtons and re-checks them without any solver (certificate.h).
 */
#ifndef US_STABILITY_BACKEND_H
#define US_STABILITY_BACKEND_H

#include "core/core.h"
#include "equilibrium.h"
#include "stability.h"

/* What a backend decides: the sub-assembly `sys`. added / removed: bodies
 * that changed since this backend's previous solve (restart = 1: no
 * previous state to reuse, e.g. first call). added = removed = NULL with
 * restart = 0: `sys` is a region system of the local tests (local.h), not
 * a sub-assembly; a backend may start from whatever it last knew of its
 * contacts. */
typedef struct us_BackendProblem {
  const us_EqSystem *sys;
  const int *added;
  int nadded;
  const int *removed;
  int nremoved;
  int restart;
  /* Optional (NULL: none): forces near the answer, normalized, per
   * structure contact (dim each); a backend may start from the columns
   * they use (the local tests pass the base forces). */
  const double *hint;
  /* 1: only a feasible answer matters (a region's fixed LP): an
   * infeasible one needs no checked Farkas ray (backends may ignore it) */
  int no_ray;
} us_BackendProblem;

/* What a backend answers: the verdict; on stable, dim * ncontact
 * normalized forces in the caller's f; its counters added to info; why,
 * in words, in note. */
typedef struct us_BackendOut {
  us_Verdict verdict;
  double *f;
  us_StabilityInfo *info;
  char *note;
  size_t note_sz;
} us_BackendOut;

/* A stability backend. The workspace is the backend's own state and may
 * keep the last sub-assembly's solution for reuse. */
typedef struct us_Backend {
  us_Method method; /* its name is us_method_name(method) */
  void *(*create)(const us_Structure *s, const us_StabilitySettings *set, us_Error *err);
  void (*destroy)(void *ws);
  /* Decide the problem (us_BackendProblem) into out (us_BackendOut);
   * errors in err, outcomes in out->verdict. */
  us_Status (*solve)(void *ws, const us_BackendProblem *pb, us_BackendOut *out, us_Error *err);
  /* Optional (NULL: unknown). After an unstable verdict: the body the
   * backend's evidence points at (e.g. largest virtual motion in a Farkas
   * ray), else -1. */
  int (*unstable_body)(void *ws);
  /* Optional (NULL: the backend's solves are short). Solves that run past
   * `deadline` (us_now() seconds; 0: none) stop and return US_OK with
   * verdict US_UNDECIDED and a note that says "time limit". */
  void (*set_deadline)(void *ws, double deadline);
  /* Optional (NULL: none). After an unstable verdict: a Farkas ray y of
   * the last system's rows (y . rhs != 0, every cone generator on one side
   * of it, checked by the backend), its length, or 0 when there is none. */
  int (*farkas_ray)(void *ws, const double **y);
  /* 1: the front end runs the local tests (local.h) in front of this
   * backend, which also solves their region systems (CLP only). */
  int local_tests;
} us_Backend;

extern const us_Backend us_backend_clp;     /* lp_clp.c */
extern const us_Backend us_backend_lpsolve; /* lp_lpsolve.c */
extern const us_Backend us_backend_lcp;     /* lcp_backend.c (from scratch) */
extern const us_Backend us_backend_lcp_reuse;
extern const us_Backend us_backend_lp_lcp;  /* lp_lcp.c (Lemke on the LP's LCP) */

/* A workspace on a given backend (tests, benchmarks); us_stability_new picks
 * the backend from set->method. */
us_Stability *us_stability_new_backend(const us_Structure *s, const us_StabilitySettings *set,
                                       const us_Backend *be, us_Error *err);

#endif
