/* Finding and loading the modules of module.h: the directory of the object
 * that holds this code, the candidate directories below it, dlopen and the
 * module's entry point, with one message that names the module when any
 * of it fails. */
#define _GNU_SOURCE /* dladdr1, RTLD_DL_LINKMAP */
#include "module.h"

#include <dlfcn.h>
#include <limits.h>
#include <link.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* where an installed module lives, relative to the executable's directory
 * and to the library directory (CMake computes them from GNUInstallDirs) */
#ifndef US_MODULE_FROM_BINDIR
#define US_MODULE_FROM_BINDIR "../lib/unstack"
#endif
#ifndef US_MODULE_FROM_BINDIR_ARCH
#define US_MODULE_FROM_BINDIR_ARCH US_MODULE_FROM_BINDIR
#endif
#ifndef US_MODULE_FROM_LIBDIR
#define US_MODULE_FROM_LIBDIR "unstack"
#endif

static const us_ModuleHost host_table = {
    US_MODULE_ABI, US_VERSION, sizeof(us_ModuleHost), us_malloc, us_calloc, us_realloc,
    us_free, us_strdup, us_grow,
};

int us_module_dir(const char *self_dir, int k, char *buf, size_t cap) {
  static const char *const below[] = {"modules", US_MODULE_FROM_LIBDIR, US_MODULE_FROM_BINDIR,
                                       US_MODULE_FROM_BINDIR_ARCH};
  int n_below = (int)(sizeof below / sizeof below[0]);
  if (strcmp(below[n_below - 1], below[n_below - 2]) == 0) n_below--; /* the same directory */
  if (k < 0 || k >= n_below) return 0;
  int n = snprintf(buf, cap, "%s/%s", self_dir, below[k]);
  return n > 0 && (size_t)n < cap;
}

/* The directory of the object holding this function: the library's own
 * file for libunstack.so, /proc/self/exe for an executable (its link map
 * has no name), symbolic links resolved. 0 or -1. */
static int self_dir(char *dir, size_t cap) {
  Dl_info info;
  struct link_map *map = NULL;
  char path[PATH_MAX];
  const char *file = NULL;
  if (dladdr1((void *)self_dir, &info, (void **)&map, RTLD_DL_LINKMAP) && map && map->l_name &&
      map->l_name[0])
    file = info.dli_fname;
  if (!file) {
    ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
    if (n <= 0) return -1;
    path[n] = '\0';
    file = path;
  }
  char real[PATH_MAX];
  if (!realpath(file, real)) return -1;
  char *slash = strrchr(real, '/');
  if (!slash || (size_t)(slash - real) >= cap) return -1;
  *slash = '\0';
  memcpy(dir, real, (size_t)(slash - real) + 1);
  return 0;
}

/* dlopen <dir>/<name>.so and call its entry: the API, or NULL with why[]. */
static const void *open_in(const us_Module *m, const char *dir, char *why, size_t cap) {
  char file[PATH_MAX + 64], entry[64];
  snprintf(file, sizeof file, "%s/%s.so", dir, m->name);
  if (access(file, F_OK) != 0) return NULL; /* not here: try the next directory */
  void *h = dlopen(file, RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    snprintf(why, cap, "%s", dlerror());
    return NULL;
  }
  snprintf(entry, sizeof entry, "us_module_%s", m->name);
  us_ModuleEntry fn;
  *(void **)&fn = dlsym(h, entry); /* POSIX's way from object to function pointer */
  const void *api = fn ? fn(&host_table) : NULL;
  if (!api) {
    snprintf(why, cap, "%s: %s", file,
             fn ? "built for another version of unstack" : "no entry point");
    dlclose(h);
  }
  return api;
}

const void *us_module_api(us_Module *m, us_Error *err) {
  const void *api = atomic_load_explicit(&m->api, memory_order_acquire);
  if (api) return api;
  /* two threads may both get here: dlopen counts, the module's table and
   * m->api are written with the same values, atomically */
  char dir[PATH_MAX], cand[PATH_MAX], why[PATH_MAX + 256] = "", tried[3 * PATH_MAX] = "";
  if (self_dir(dir, sizeof dir) == 0)
    for (int k = 0; !api && !why[0] && us_module_dir(dir, k, cand, sizeof cand); k++) {
      api = open_in(m, cand, why, sizeof why);
      size_t len = strlen(tried);
      snprintf(tried + len, sizeof tried - len, "%s%s", k ? ", " : "", cand);
    }
  if (!api)
    us_error_set(err, US_ERR_IO, "cannot load module '%s.so' (%s): %s%s", m->name, m->what,
                 why[0] ? why : "not found in ", why[0] ? "" : tried[0] ? tried : "(no directory)");
  else
    atomic_store_explicit(&m->api, api, memory_order_release);
  return api;
}
