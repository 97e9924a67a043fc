/* The LP backends' settings (us_LpSettings): their defaults and the
 * resolution of fields left <= 0, shared by the front end (stability.c)
 * and every LP backend (lp_clp.c, lp_lpsolve.c, lp_lcp.c, lp_small.c), so
 * it sits below all of them. */
#include "lp_gen.h"

/* Default tolerances of the LP backends (us_LpSettings documents them). */
#define LP_PRIMAL_TOL 1e-9
#define LP_WARM_ACCEPT 1e-9
#define LP_FARKAS_SLACK 1e-9
#define LP_N_COLUMN_MU 1.0

us_LpSettings us_lp_default_settings(void) {
  us_LpSettings l;
  l.primal_tol = LP_PRIMAL_TOL;
  l.warm_accept = LP_WARM_ACCEPT;
  l.farkas_slack = LP_FARKAS_SLACK;
  l.n_column_mu = LP_N_COLUMN_MU;
  return l;
}

us_LpSettings us_lp_settings_resolve(const us_LpSettings *in) {
  us_LpSettings d = us_lp_default_settings(), r = *in;
  if (!(r.primal_tol > 0)) r.primal_tol = d.primal_tol;
  if (!(r.warm_accept > 0)) r.warm_accept = d.warm_accept;
  if (!(r.farkas_slack > 0)) r.farkas_slack = d.farkas_slack;
  if (!(r.n_column_mu > 0)) r.n_column_mu = d.n_column_mu;
  return r;
}
