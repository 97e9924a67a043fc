/* The CLP backend's proxy: us_backend_clp as the rest of the library sees
 * it. CLP, CoinUtils and their LAPACK live in module clp.so
 * (core/module.h). Workspaces are made eagerly (us_stability_new, the
 * local tests' region backends) but many are never asked anything: a
 * planner whose tests the local tests and plumb lines decide
 * (docs/local.md) never solves an LP. So create keeps what the module's
 * create needs, and the first solve loads the module and makes the real
 * workspace. A deadline makes it at once: CLP turns the wall-clock time
 * left into CPU seconds by the CPU share measured since its workspace was
 * made, which must span the work before the first LP as it always did. */
#include "clp_module.h"

#include "core/module.h"

static us_Module clp_module = {"clp", "the CLP LP solver", NULL};

const us_ClpModule *us_clp_module_api(us_Error *err) {
  return us_module_api(&clp_module, err);
}

typedef struct LazyWs {
  const us_Structure *s;
  us_StabilitySettings set;
  double deadline;       /* 0: none */
  const us_Backend *be;  /* the module's vtable, once loaded */
  void *ws;              /* its workspace, once made */
} LazyWs;

static void *lazy_create(const us_Structure *s, const us_StabilitySettings *set, us_Error *err) {
  LazyWs *w = us_calloc(1, sizeof *w);
  if (!w) {
    us_error_set(err, US_ERR_NOMEM, "out of memory creating the CLP workspace");
    return NULL;
  }
  w->s = s;
  w->set = *set;
  return w;
}

static void lazy_destroy(void *ws) {
  LazyWs *w = ws;
  if (w && w->ws) w->be->destroy(w->ws);
  us_free(w);
}

/* The real workspace, loading the module first: US_OK or the error. */
static us_Status ensure(LazyWs *w, us_Error *err) {
  if (w->ws) return US_OK;
  const us_ClpModule *api = us_clp_module_api(err);
  if (!api) return err ? err->code : US_ERR_IO;
  w->be = api->lp;
  w->ws = w->be->create(w->s, &w->set, err);
  if (!w->ws) return err ? err->code : US_ERR_NOMEM;
  if (w->deadline > 0) w->be->set_deadline(w->ws, w->deadline);
  return US_OK;
}

static us_Status lazy_solve(void *ws, const us_BackendProblem *pb, us_BackendOut *out,
                            us_Error *err) {
  LazyWs *w = ws;
  us_Status st = ensure(w, err);
  if (st) return st;
  return w->be->solve(w->ws, pb, out, err);
}

static int lazy_unstable_body(void *ws) {
  LazyWs *w = ws;
  return w->ws ? w->be->unstable_body(w->ws) : -1;
}

static void lazy_set_deadline(void *ws, double deadline) {
  LazyWs *w = ws;
  w->deadline = deadline;
  if (deadline > 0) ensure(w, NULL); /* a failure is reported by the next solve */
  if (w->ws) w->be->set_deadline(w->ws, deadline);
}

static int lazy_farkas_ray(void *ws, const double **y) {
  LazyWs *w = ws;
  if (w->ws) return w->be->farkas_ray(w->ws, y);
  *y = NULL;
  return 0;
}

const us_Backend us_backend_clp = {
    .method = US_METHOD_LP,
    .create = lazy_create,
    .destroy = lazy_destroy,
    .solve = lazy_solve,
    .unstable_body = lazy_unstable_body,
    .farkas_ray = lazy_farkas_ray,
    .set_deadline = lazy_set_deadline,
    .local_tests = 1,
};
