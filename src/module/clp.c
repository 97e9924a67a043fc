/* Module clp.so: the CLP backend (stability/lp_clp.c, with CLP, CoinUtils
 * and their LAPACK) behind the proxy vtable of stability/lp_clp_lazy.c, and
 * the representative-forces LPs (stability/represent_lp.c). */
#include "module.h"
#include "stability/clp_module.h"

US_MODULE_EXPORT const void *us_module_clp(const us_ModuleHost *host);

static const us_ClpModule api = {&us_backend_clp, us_represent_run};

const void *us_module_clp(const us_ModuleHost *host) {
  return us_module_accept(host) ? &api : NULL;
}
