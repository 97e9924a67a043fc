/* Inside a module (core/module.h): the entry point's helper and its
 * export mark. Only us_module_<name> leaves a module (module.map). */
#ifndef US_MODULE_MODULE_H
#define US_MODULE_MODULE_H

#include "core/module.h"

#define US_MODULE_EXPORT __attribute__((visibility("default")))

/* Keep the host's table when it matches this build (1), else 0. */
int us_module_accept(const us_ModuleHost *h);

#endif
