/* unstack render --html: the interactive plan viewer (docs/viewer.md).
 *
 * The page shows what the plan file holds (its order, blocked bodies and,
 * when it was made with --certificates, the forces of every step) and what
 * verification finds: a plan with status found is re-checked here with the
 * library's us_verify_steps (the same test as `unstack verify`), so a step
 * after which the rest falls is shown in red whatever the file claims.
 * Without a plan, --forces gives the forces of the full structure. The
 * page re-checks every step's forces itself (us_render_html), so forces
 * edited in the file are flagged at their step. --force-set margin|min-sum
 * replaces each step's forces by that representative set where it is
 * certified. A plan with status none has no order: the page takes apart
 * the buildable part (the movable bodies not blocked), in the reverse of
 * a greedy build from the ground (lowest first), with the blocked bodies
 * shown at every step. Exit 0 written; 1 written, and verification proves
 * the order invalid; 2 usage or input error (nothing written). */
#include "options.h"

#include <stdio.h>
#include <stdlib.h>
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

/* Bodies by height of their centre of mass (y in 2D, z in 3D), then
 * index (qsort context free: the keys are copied in). */
typedef struct Low {
  double y;
  int i;
} Low;
static int low_cmp(const void *a, const void *b) {
  const Low *x = a, *y = b;
  if (x->y != y->y) return x->y < y->y ? -1 : 1;
  return (x->i > y->i) - (x->i < y->i);
}

/* The first candidate (lowest first) that stands with `present`; it is
 * added. 1 added, 0 none, -1 error. *budget counts tests down. */
static int build_one(us_Stability *w, us_Bitset *present, Low *cand, int n, char *in,
                     long *budget, int *added, us_Error *err) {
  us_StabilityResult res;
  us_stability_result_init(&res);
  int r = 0;
  for (int k = 0; k < n && !r && *budget > 0; k++) {
    if (in[k]) continue;
    us_bitset_set(present, cand[k].i);
    (*budget)--;
    if (us_stability_test(w, present, &res, err)) r = -1;
    else if (res.verdict == US_STABLE) r = 1, in[k] = 1, *added = cand[k].i;
    else us_bitset_clear(present, cand[k].i);
  }
  us_stability_result_free(&res);
  return r;
}

/* A none plan's buildable part as steps: the reverse of a greedy build
 * from the ground, lowest first, within 50 n + 1000 tests. order gets
 * the removal order (may be shorter than the part); its length, or -1. */
static int buildable_order(const us_Structure *s, const us_PlanFile *pf, CliCommon *c, int *order,
                           us_Error *err) {
  Low *cand = us_malloc(((size_t)s->nbody + 1) * sizeof *cand);
  char *in = us_calloc((size_t)s->nbody + 1, 1), *blocked = us_calloc((size_t)s->nbody + 1, 1);
  us_StabilitySettings set = c->stab;
  set.skip_forces = 1;
  us_Stability *w = cand && in && blocked ? us_stability_new(s, &set, err) : NULL;
  us_Bitset present;
  int n = 0, got = 0, r = 1, added = -1;
  if (!w || us_bitset_init(&present, s->nbody > 0 ? s->nbody : 1)) {
    us_stability_free(w), us_free(cand), us_free(in), us_free(blocked);
    return err->code ? -1 : (us_error_set(err, US_ERR_NOMEM, "render: out of memory"), -1);
  }
  for (int k = 0; k < pf->nblocked; k++) blocked[pf->blocked[k]] = 1;
  for (int i = 0; i < s->nbody; i++)
    if (!s->bodies[i].fixed && !blocked[i]) cand[n++] = (Low){s->bodies[i].com[s->dim == 3 ? 2 : 1], i};
  qsort(cand, (size_t)n, sizeof *cand, low_cmp);
  long budget = 50L * n + 1000;
  while (got < n && (r = build_one(w, &present, cand, n, in, &budget, &added, err)) == 1)
    order[n - 1 - got++] = added; /* removal is the build reversed */
  memmove(order, order + n - got, (size_t)got * sizeof *order);
  us_bitset_free(&present);
  us_stability_free(w), us_free(cand), us_free(in), us_free(blocked);
  return r < 0 ? -1 : got;
}

/* Each position's forces replaced by the representative set of rule
 * h->force_set where it is certified (the others keep the file's). */
static int representative_steps(const us_Structure *s, const us_PlanFile *pf, CliCommon *c,
                                us_Forces **certs, us_HtmlSettings *h, us_Error *err) {
  if (h->force_set == US_FORCESET_SOLVER || pf->status != US_PLAN_FOUND) return 0;
  if (!*certs && !(*certs = us_calloc((size_t)pf->ngroups + 1, sizeof **certs)))
    return us_error_set(err, US_ERR_NOMEM, "render: out of memory"), -1;
  us_Bitset present;
  if (us_bitset_init(&present, s->nbody > 0 ? s->nbody : 1))
    return us_error_set(err, US_ERR_NOMEM, "render: out of memory"), -1;
  us_bitset_fill(&present);
  us_StabilityResult rep;
  us_stability_result_init(&rep);
  int r = 0, kept = 0;
  for (int k = 0; k <= pf->ngroups && !r; k++) {
    if (us_stability_forces_representative(s, &present, h->force_set, &c->stab, &rep, err)) r = -1;
    else if (rep.verdict == US_STABLE) {
      us_Forces t = (*certs)[k];
      (*certs)[k] = rep.forces, rep.forces = t;
    } else kept++;
    for (int q = pf->group_start[k]; k < pf->ngroups && q < pf->group_start[k + 1]; q++)
      us_bitset_clear(&present, pf->order[q]); /* the structure before step k + 1 */
  }
  if (kept)
    fprintf(stderr, "unstack render: %d of %d steps have no certified %s forces: the plan "
            "file's are shown there\n", kept, pf->ngroups + 1, us_force_set_name(h->force_set));
  us_stability_result_free(&rep);
  us_bitset_free(&present);
  return r;
}

int cli_render_html(const us_Structure *s, const char *plan, const us_PlanFile *pf, CliCommon *c,
                    const us_RenderSettings *r, const char *file, const char *out, us_Error *err) {
  us_HtmlSettings h = us_html_default_settings();
  h.title = base_name(file);
  h.force_set = r->force_set;
  us_RenderSettings rr = *r;
  us_Forces *certs = NULL;
  int invalid = 0, *order = NULL;
  if (plan && pf->nactions > 0) { /* hands: the actions replayed, no step forces */
    h.status = pf->status;
    h.hands = pf->hands, h.actions = pf->actions, h.nactions = pf->nactions;
    us_VerifyReport rep;
    if (us_verify_actions(s, &c->stab, pf->hands, pf->actions, pf->nactions, &rep, err))
      return CLI_EXIT_ERR;
    invalid = !rep.ok && !rep.undecided;
  } else if (plan) {
    h.status = pf->status;
    if (us_plan_read_certs(s, plan, pf, &certs, err)) return CLI_EXIT_ERR;
    h.certs = certs;
    invalid = verify_plan(s, pf, c, &h, err);
    if (!invalid && representative_steps(s, pf, c, &certs, &h, err)) invalid = -1;
    h.certs = certs;
  } else {
    h.certs = r->forces; /* --forces: the full structure's, or NULL */
  }
  if (!invalid && plan && pf->status == US_PLAN_NONE && pf->n == 0) {
    order = us_malloc(((size_t)s->nbody + 1) * sizeof *order);
    rr.norder = order ? buildable_order(s, pf, c, order, err) : -1;
    rr.order = order, rr.group_start = NULL, rr.ngroups = 0;
    if (rr.norder < 0) invalid = -1, err->code = err->code ? err->code : US_ERR_NOMEM;
  }
  us_Status st = invalid < 0 ? err->code : us_render_html(s, &rr, &h, out, err);
  us_free(order);
  us_certs_free(certs, plan ? pf->ngroups + 1 : 0);
  if (st) return CLI_EXIT_ERR;
  if (invalid && h.nactions)
    fprintf(stderr, "unstack render: verify: the actions are invalid (unstack verify says "
            "where)\n");
  else if (invalid)
    fprintf(stderr, "unstack render: verify: the order is invalid (shown in red in the page)\n");
  else if (h.verified && h.verify.undecided)
    fprintf(stderr, "unstack render: verify: undecided (%s); shown in the page\n", h.verify.note);
  return invalid ? CLI_EXIT_NO : CLI_EXIT_OK;
}
