/* Module clp.so's entry points (core/module.h): the CLP backend and the
 * representative-forces LPs, both needing CLP; the host reaches them
 * through us_clp_module_api (lp_clp_lazy.c), loading the module once. */
#ifndef US_STABILITY_CLP_MODULE_H
#define US_STABILITY_CLP_MODULE_H

#include "backend.h"
#include "equilibrium.h"

/* represent_lp.c: the LP of rule `kind` (named `name` in notes) on system e,
 * its forces certified at tol into res (STABLE, or UNDECIDED with a note);
 * errors are memory only. */
us_Status us_represent_run(const us_EqSystem *e, const us_Bitset *present, us_ForceSet kind,
                           const char *name, double tol, us_StabilityResult *res,
                           us_Error *err);

typedef struct us_ClpModule {
  const us_Backend *lp; /* lp_clp.c's us_backend_clp */
  us_Status (*represent)(const us_EqSystem *e, const us_Bitset *present, us_ForceSet kind,
                         const char *name, double tol, us_StabilityResult *res, us_Error *err);
} us_ClpModule;

/* The module's entry points, loading it on first use; NULL with the
 * loader's error (US_ERR_IO naming the module). Thread-safe. */
const us_ClpModule *us_clp_module_api(us_Error *err);

#endif
