/* unstack analysis: counting sub-assemblies and classifying structures.
 * Part of the public API; included by unstack/unstack.h. */
#ifndef UNSTACK_ANALYSIS_H
#define UNSTACK_ANALYSIS_H

#include "unstack/unstack.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ count */
/* (src/plan/count.c) */

/* ------------------------------------------------------------- classify */
/* (src/plan/classify.c, src/plan/friction.c) */

/* Critical friction (src/analysis/friction.c, docs/classify.md): the
 * smallest Coulomb coefficient mu which, put on every contact of the
 * structure alike (the contacts' own coefficients are ignored), lets the
 * sub-assembly stand. Standing is monotone in mu, so the value is found by
 * bisection on stability tests of a private copy of the structure whose
 * contacts carry the probe's mu. */
typedef struct us_FrictionResult {
  int stands_frictionless; /* stands at mu = 0 (then mu_critical = 0) */
  int stands;              /* stands at mu_max; 0: no coefficient up to mu_max works */
  double mu_critical;      /* stands: the smallest stable probe, within tol above
                              the true value; INFINITY when !stands */
  double mu_low, mu_high;  /* bracket: not standing at mu_low (or mu_low = 0 and it
                              stands there), standing at mu_high (INFINITY when !stands) */
  int probes;              /* stability tests run */
  int undecided;           /* probes whose verdict was undecided (taken as not standing) */
  us_Forces forces;        /* stands: contact forces at mu_high = mu_critical */
  us_CertCheck check;      /* stands: us_certificate_check of forces with every
                              contact's mu = mu_critical */
} us_FrictionResult;
void us_friction_result_free(us_FrictionResult *r);

/* Critical friction of sub-assembly `present` (NULL: every movable body)
 * under the stability settings `set` (NULL: defaults, method lp). tol: the
 * absolute tolerance on mu (<= 0: 1e-7); mu_max: the largest coefficient
 * tried (<= 0: 1e3). Standing, not standing and "not for any mu up to
 * mu_max" are outcomes in `out`; errors are bad arguments (US_ERR_USAGE),
 * memory (US_ERR_NOMEM) and backend failures. err may be NULL. */
us_Status us_critical_friction(const us_Structure *s, const us_Bitset *present,
                               const us_StabilitySettings *set, double tol, double mu_max,
                               us_FrictionResult *out, us_Error *err);

#ifdef __cplusplus
}
#endif
#endif
