/* Module clp.so: the CLP backend (stability/lp_clp.c, with CLP, CoinUtils
 * and their LAPACK) behind the proxy vtable of stability/lp_clp_lazy.c, and
 * the representative-forces LPs (stability/represent_lp.c). */
#define _GNU_SOURCE /* RTLD_NOLOAD */
#include "module.h"
#include "stability/clp_module.h"

#include <dlfcn.h>
#include <stdlib.h>

US_MODULE_EXPORT const void *us_module_clp(const us_ModuleHost *host);

static const us_ClpModule api = {&us_backend_clp, us_represent_run};

/* CLP's LAPACK is OpenBLAS here (Debian's libopenblas0-pthread), which by
 * default hands every BLAS call above its own size threshold to a thread
 * per core; each thread then spins on sched_yield for a while before it
 * sleeps. Our LPs are many and small, solved one per thread of the caller
 * (batch's jobs, the Python binding's threads): extra BLAS threads only
 * add that spinning (batch --jobs 1 on an idle machine: 0.08-0.10 s of
 * system time on 400 small inputs, none with one thread). So once the
 * module is loaded, OpenBLAS is asked for one thread, unless the user
 * chose a number (OPENBLAS_NUM_THREADS, GOTO_NUM_THREADS, OMP_NUM_THREADS).
 * Why not setenv before the dlopen: the environment is process state that
 * other threads may be reading (getenv is not safe against setenv), and a
 * library must not write it; openblas_set_num_threads is OpenBLAS's own
 * call for this, found without linking OpenBLAS (another LAPACK has no
 * such symbol and is left alone). It changes which thread computes a
 * block, not what is computed, and every verdict is re-checked anyway.
 * (The threads OpenBLAS made when it was loaded stay, asleep; the
 * `unstack` program sets OPENBLAS_NUM_THREADS=1 in main(), before any
 * module is loaded, so that even those are never made.) */
static void one_blas_thread(void) {
  if (getenv("OPENBLAS_NUM_THREADS") || getenv("GOTO_NUM_THREADS") || getenv("OMP_NUM_THREADS"))
    return;
  void *h = dlopen("libopenblas.so.0", RTLD_LAZY | RTLD_NOLOAD);
  if (!h) return;
  void (*set)(int);
  *(void **)&set = dlsym(h, "openblas_set_num_threads"); /* POSIX's way to a function */
  if (set) set(1);
  dlclose(h);
}

const void *us_module_clp(const us_ModuleHost *host) {
  if (!us_module_accept(host)) return NULL;
  one_blas_thread();
  return &api;
}
