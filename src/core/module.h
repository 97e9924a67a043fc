/* Modules: the back ends that pull heavy shared libraries (CLP, cairo,
 * libxml2) are built as small shared objects of their own and loaded with
 * dlopen on first use, so that a command that never solves an LP, draws a
 * PNG or reads an SVG never maps those libraries (docs/modules.md).
 *
 * The host (the executable, libunstack.so or a test program) keeps a
 * proxy at the entry points of each back end (a us_Backend vtable, a
 * public function); the first call loads the module and every call is
 * forwarded to it. A module carries its own copy of the stateless layers
 * it uses; the one stateful piece, the allocation funnel, stays the
 * host's: the module's us_malloc and friends forward to the host's through
 * the table handed over at load (src/module/host.c), so leak counts and
 * the failing-allocation hook of the tests see every allocation. */
#ifndef US_CORE_MODULE_H
#define US_CORE_MODULE_H

#include "core.h"

/* Host and module must come from the same build: the table's layout, the
 * library version and this number must all agree. */
#define US_MODULE_ABI 2

typedef struct us_ModuleHost {
  int abi;              /* US_MODULE_ABI */
  const char *version;  /* US_VERSION */
  size_t size;          /* sizeof(us_ModuleHost) */
  void *(*malloc_fn)(size_t n);
  void *(*calloc_fn)(size_t count, size_t size);
  void *(*realloc_fn)(void *p, size_t n);
  void (*free_fn)(void *p);
  char *(*strdup_fn)(const char *s);
  int (*grow_fn)(void **arr, int *cap, int need, size_t elem);
} us_ModuleHost;

/* Every module exports one function, us_module_<name>: it takes the host's
 * table and returns the module's entry points (a us_Backend, or the
 * struct its proxy expects), or NULL when the table does not match. */
typedef const void *(*us_ModuleEntry)(const us_ModuleHost *host);

/* One module as its proxy knows it: file "<name>.so", entry
 * "us_module_<name>", and what it holds (for messages). `api` caches the
 * entry points once loaded. */
typedef struct us_Module {
  const char *name;
  const char *what;
  const void *_Atomic api;
} us_Module;

/* The module's entry points, loading it on first use: NULL with
 * US_ERR_IO naming the module, where it was looked for and why it failed.
 * Thread-safe. */
const void *us_module_api(us_Module *m, us_Error *err);

/* The directories searched, in order, for a module, from `self_dir` (the
 * directory of the executable or library that holds the host): <dir>/modules
 * (the build tree), <dir>/unstack (an installed libunstack.so in
 * PREFIX/LIBDIR), and PREFIX/LIBDIR/unstack and PREFIX/lib/<multiarch>/unstack
 * seen from an installed executable in PREFIX/BINDIR (CMake's
 * GNUInstallDirs). Writes the k-th candidate into buf: 1, or 0 when there
 * is no k-th. */
int us_module_dir(const char *self_dir, int k, char *buf, size_t cap);

#endif
