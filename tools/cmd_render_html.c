/* unstack render --html: the interactive plan viewer (docs/viewer.md).
 *
 * The page shows what the plan file holds (its order, blocked bodies and,
 * when it was made with --certificates, the forces of every step) and what
 * verification finds: a plan with status found is re-checked here with the
 * library's us_verify_steps (the same test as `unstack verify`), so a step
 * after which the rest falls is shown in red whatever the file claims.
 * Without a plan, --forces gives the forces of the full structure. Exit 0
 * written; 1 written, and verification proves the order invalid; 2 usage or
 * input error (nothing written). */
#include "options.h"

#include <stdio.h>
#include <string.h>

int cli_html_name(const char *out) {
  size_t n = strlen(out);
  return (n >= 5 && !strcmp(out + n - 5, ".html")) || (n >= 4 && !strcmp(out + n - 4, ".htm"));
}

/* Title: the structure file's name without its directories. */
static const char *base_name(const char *path) {
  const char *slash = strrchr(path, '/');
  return slash && slash[1] ? slash + 1 : path;
}

/* Verification of a found plan; 1 when it proves the order invalid. */
static int verify_plan(const us_Structure *s, const us_PlanFile *pf, CliCommon *c,
                       us_HtmlSettings *h, us_Error *err) {
  if (pf->status != US_PLAN_FOUND) return 0;
  int r = cli_verify_plan(s, pf, c, &h->verify, err);
  h->verified = r >= 0;
  return r;
}

int cli_render_html(const us_Structure *s, const char *plan, const us_PlanFile *pf, CliCommon *c,
                    const us_RenderSettings *r, const char *file, const char *out, us_Error *err) {
  us_HtmlSettings h = us_html_default_settings();
  h.title = base_name(file);
  us_Forces *certs = NULL;
  int invalid = 0;
  if (plan) {
    h.status = pf->status;
    if (us_plan_read_certs(s, plan, pf, &certs, err)) return CLI_EXIT_ERR;
    h.certs = certs;
    invalid = verify_plan(s, pf, c, &h, err);
  } else {
    h.certs = r->forces; /* --forces: the full structure's, or NULL */
  }
  us_Status st = invalid < 0 ? err->code : us_render_html(s, r, &h, out, err);
  us_certs_free(certs, plan ? pf->ngroups + 1 : 0);
  if (st) return CLI_EXIT_ERR;
  if (invalid)
    fprintf(stderr, "unstack render: verify: the order is invalid (shown in red in the page)\n");
  else if (h.verified && h.verify.undecided)
    fprintf(stderr, "unstack render: verify: undecided (%s); shown in the page\n", h.verify.note);
  return invalid ? CLI_EXIT_NO : CLI_EXIT_OK;
}
