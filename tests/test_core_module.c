/* Tests of the module loader (src/core/module.c, docs/modules.md): the
 * directories searched, in order; a missing module is US_ERR_IO naming it
 * and where it was looked for; a module of the build tree loads through
 * its entry point, once. */
#include "core/module.h"
#include "stability/clp_module.h"
#include "test.h"

#include <string.h>

static void module_dirs(void) {
  char buf[256];
  CHECK(us_module_dir("/p/bin", 0, buf, sizeof buf));
  CHECK(!strcmp(buf, "/p/bin/modules")); /* the build tree first */
  CHECK(us_module_dir("/p/bin", 1, buf, sizeof buf));
  CHECK(!strcmp(buf, "/p/bin/unstack")); /* an installed library's directory */
  int k = 2;
  while (us_module_dir("/p/bin", k, buf, sizeof buf)) {
    /* an installed executable's: PREFIX/bin/../LIBDIR/unstack */
    CHECK(!strncmp(buf, "/p/bin/../", 10));
    CHECK(strlen(buf) > 8 && !strcmp(buf + strlen(buf) - 8, "/unstack"));
    k++;
  }
  CHECK(k >= 3 && k <= 4);
  CHECK(!us_module_dir("/p/bin", -1, buf, sizeof buf));
  CHECK(!us_module_dir("/a/very/long/directory", 0, buf, 8)); /* does not fit */
}

static void missing_module_is_named(void) {
  us_Module m = {"no_such_module", "a module that is not built", NULL};
  us_Error err;
  us_error_clear(&err);
  CHECK(us_module_api(&m, &err) == NULL);
  CHECK_INT(err.code, ==, US_ERR_IO);
  CHECK(strstr(err.msg, "'no_such_module.so'") != NULL);
  CHECK(strstr(err.msg, "a module that is not built") != NULL);
  CHECK(strstr(err.msg, "/modules") != NULL); /* where it was looked for */
  CHECK(us_module_api(&m, NULL) == NULL);      /* no error record: still refused */
}

static void build_tree_module_loads_once(void) {
  us_Module m = {"clp", "the CLP LP solver", NULL};
  us_Error err;
  us_error_clear(&err);
  const us_ClpModule *api = us_module_api(&m, &err);
  CHECK(api != NULL);
  if (!api) return;
  CHECK_INT(api->lp->method, ==, US_METHOD_LP);
  CHECK(api->represent != NULL);
  CHECK(us_module_api(&m, &err) == api);
}

US_TEST_MAIN(T(module_dirs), T(missing_module_is_named), T(build_tree_module_loads_once))
