/* The host's side inside a module: the table handed over at load, and the
 * allocation funnel forwarded to the host's (core/module.h), so that the
 * module's copy of core never counts or fails allocations on its own. */
#include "module.h"

#include <stdatomic.h>
#include <string.h>

/* written once per load, with the same value whichever thread loads */
static const us_ModuleHost *_Atomic host;

static const us_ModuleHost *H(void) { return atomic_load_explicit(&host, memory_order_acquire); }

int us_module_accept(const us_ModuleHost *h) {
  if (!h || h->abi != US_MODULE_ABI || h->size != sizeof *h || strcmp(h->version, US_VERSION))
    return 0;
  atomic_store_explicit(&host, h, memory_order_release);
  return 1;
}

void *us_malloc(size_t n) { return H()->malloc_fn(n); }
void *us_calloc(size_t count, size_t size) { return H()->calloc_fn(count, size); }
void *us_realloc(void *p, size_t n) { return H()->realloc_fn(p, n); }
void us_free(void *p) { H()->free_fn(p); }
char *us_strdup(const char *s) { return H()->strdup_fn(s); }
int us_grow(void **arr, int *cap, int need, size_t elem) { return H()->grow_fn(arr, cap, need, elem); }
