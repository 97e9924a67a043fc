/* Module cbc.so: the strong-stability MIP (analysis/strong_mip.c, with CBC,
 * Cgl, Osi, CLP and CoinUtils), reached through us_cbc_module_api
 * (analysis/strong.c), loaded the first time classify decides strong
 * stability with friction. */
#include "module.h"
#include "analysis/strong.h"

US_MODULE_EXPORT const void *us_module_cbc(const us_ModuleHost *host);

static const us_CbcModule api = {us_strong_mip};

const void *us_module_cbc(const us_ModuleHost *host) {
  return us_module_accept(host) ? &api : NULL;
}
