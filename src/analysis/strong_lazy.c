/* The proxy of module cbc.so (core/module.h): the strong-stability MIP
 * with CBC and its libraries, loaded the first time a search asks for it
 * (strong.c), so that start-up never maps CBC. */
#include "strong.h"

#include "core/module.h"

static us_Module cbc_module = {"cbc", "the CBC mixed-integer solver", NULL};

const us_CbcModule *us_cbc_module_api(us_Error *err) { return us_module_api(&cbc_module, err); }
