/* The LCP stability backends (Baraff 1994 / Dantzig principal pivoting),
 * from scratch (us_backend_lcp) and with computation reuse
 * (us_backend_lcp_reuse).
 *
 * Placeholder: both backends are declared so that the library links; their
 * solve reports that the LCP backend is not finished yet.
 */
#include "stability.h"

static void *lcp_stub_create(const us_Structure *s, const us_StabilitySettings *set,
                             us_Error *err) {
  US_UNUSED(s), US_UNUSED(set);
  void *w = us_calloc(1, 1);
  if (!w) us_error_set(err, US_ERR_NOMEM, "out of memory creating the LCP workspace");
  return w;
}

static void lcp_stub_destroy(void *ws) { us_free(ws); }

static us_Status lcp_stub_solve(void *ws, const us_EqSystem *sys, const int *added, int nadded,
                                const int *removed, int nremoved, int restart,
                                us_Verdict *verdict, double *f, us_StabilityInfo *info,
                                char *note, size_t note_sz, us_Error *err) {
  US_UNUSED(ws), US_UNUSED(sys), US_UNUSED(added), US_UNUSED(nadded), US_UNUSED(removed);
  US_UNUSED(nremoved), US_UNUSED(restart), US_UNUSED(verdict), US_UNUSED(f), US_UNUSED(info);
  US_UNUSED(note), US_UNUSED(note_sz);
  return us_error_set(err, US_ERR_SOLVER, "LCP backend not finished");
}

const us_Backend us_backend_lcp = {"lcp", lcp_stub_create, lcp_stub_destroy, lcp_stub_solve,
                                   NULL};
const us_Backend us_backend_lcp_reuse = {"lcp-reuse", lcp_stub_create, lcp_stub_destroy,
                                         lcp_stub_solve, NULL};
