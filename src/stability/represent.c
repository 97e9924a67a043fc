/* Representative contact forces (us_stability_forces_representative): the
 * host's entry. The rules and their LPs are described in represent_lp.c,
 * which lives in module clp.so with CLP (core/module.h): the system is
 * built here and handed to the module, loaded on first use. */
#include "clp_module.h"
#include "equilibrium.h"

#include <string.h>

const char *us_force_set_name(us_ForceSet kind) {
  switch (kind) {
  case US_FORCESET_MARGIN: return "margin";
  case US_FORCESET_MIN_SUM: return "min-sum";
  case US_FORCESET_MIN_NORM: return "min-norm";
  default: return "solver";
  }
}

/* The module's LP on system e. */
static us_Status represent(const us_EqSystem *e, const us_Bitset *present, us_ForceSet kind,
                           double tol, us_StabilityResult *res, us_Error *err) {
  const us_ClpModule *api = us_clp_module_api(err);
  if (!api) return err ? err->code : US_ERR_IO;
  return api->represent(e, present, kind, us_force_set_name(kind), tol, res, err);
}

us_Status us_stability_forces_representative(const us_Structure *s, const us_Bitset *present,
                                             us_ForceSet kind, const us_StabilitySettings *set,
                                             us_StabilityResult *res, us_Error *err) {
  if (!s || !present || !res || kind <= US_FORCESET_SOLVER || kind > US_FORCESET_MIN_NORM)
    return us_error_set(err, US_ERR_USAGE, "representative forces: no structure, sub-assembly "
                        "or result, or a rule other than margin, min-sum and min-norm");
  us_StabilitySettings def = us_stability_default_settings();
  double tol = set && set->cert_tol > 0 ? set->cert_tol : def.cert_tol;
  res->verdict = US_UNDECIDED;
  res->forces.ncontact = 0;
  res->note[0] = 0;
  memset(&res->check, 0, sizeof res->check);
  us_EqSystem e;
  if (us_eq_init(&e, s)) return us_error_set(err, US_ERR_NOMEM, "out of memory (force LP)");
  us_Status st = us_eq_build(&e, present)
                     ? us_error_set(err, US_ERR_NOMEM, "out of memory (force LP)")
                     : represent(&e, present, kind, tol, res, err);
  us_eq_free(&e);
  return st;
}
