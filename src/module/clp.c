/* Module clp.so: the CLP backend (stability/lp_clp.c, with CLP, CoinUtils
 * and their LAPACK) behind the proxy vtable of stability/lp_clp_lazy.c. */
#include "module.h"
#include "stability/backend.h"

US_MODULE_EXPORT const void *us_module_clp(const us_ModuleHost *host);

const void *us_module_clp(const us_ModuleHost *host) {
  return us_module_accept(host) ? &us_backend_clp : NULL;
}
