/* Classification of a structure along the lines of the research proposal:
 * each class is decided exactly by the library's own tests and searches,
 * never by a search of its own, and comes with its evidence.
 *
 *   1. stands: one stability test of the full structure with the
 *      contacts' own coefficients (the certificate is re-checked by the
 *      stability front end; an undecided verdict is not "stands").
 *   2. frictionless / only with friction: us_critical_friction on the full
 *      structure, every contact's mu overridden alike: mu* = 0 when it
 *      stands at mu = 0, else the bisection's smallest stable probe (within
 *      1e-7 above mu*), or none up to mu = 1e3.
 *   3. top-down: the source's plain DFS (order highest, direction down,
 *      culling rule memo only, so every child is tested). Its first path is
 *      the greedy "remove the highest body": the structure is top-down iff
 *      the DFS finds an order without one rejected move (a child tested
 *      unstable) and without one dead end (stats.backtracks counts only
 *      the latter: stepping back from a stable node whose moves all
 *      failed). A found order with either is "needs backtracking". The
 *      probe is cut at max_tests or time_limit: a cut after a rejection
 *      still proves "not top-down"; a cut before any leaves it unknown.
 *   4. a one-at-a-time sequence exists: the assemble search (max_group 1),
 *      greedy assembly from the ground and, where the greedy is stuck, the
 *      planner's exact decision (src/plan/exact.c), so "none" is a proof;
 *      its evidence is the bodies outside the greedy's maximal buildable
 *      sub-assembly.
 *   5. the smallest group size K: the assemble search with max_group 0,
 *      which decides K = 1, 2, ... in turn and stops at the first that
 *      gives an order, so that K is the smallest. A sequence of single
 *      bodies gives K = 1 without a second search (the automatic search
 *      starts with the same K = 1 search). Removing every body at once is
 *      one step, so some K exists iff the full structure stands; the
 *      planner stops at 64 bodies per step, beyond which K is reported as
 *      more than that bound.
 *   The searches of 3-5 stop at time_limit (the exact decision is
 *   exponential in K: 92 s for K = 10 on a 30-voussoir arch, in 422
 *   tests); a class cut there is unknown, with what was proven before the
 *   cut (K > group_bound).
 *   8. stands only with equality constraints (the source's "made stable
 *      only if their inequality constraints are made into equality
 *      constraints"): when class 1 says it does not stand, one test of
 *      the full structure with bilateral joints (us_stability_set_bilateral:
 *      every contact force component free in sign, no cone), on CLP
 *      whatever the method (its Farkas ray is the mechanism). Its
 *      certificate is re-checked in that mode; a "no" carries a checked
 *      mechanism that keeps every joint closed, or a body touching nothing.
 *   6. frictionless, strong stability (every solution of the contact LCP
 *      has zero accelerations) and weak stability (some has) coincide:
 *      docs/classify.md gives the proof (Gauss's principle of least
 *      constraint); reported when class 2 says frictionless. A structure
 *      that stands frictionless is strongly stable with any friction too
 *      (same docs), and one that does not stand is not; otherwise
 *      us_strong_stability decides (src/analysis/strong.c) within the
 *      time limit, a "no" carrying its checked witness motion.
 * Undecided tests (us_Verdict US_UNDECIDED) never decide a class: the
 * stands class says undecided; the friction bisection takes them as not
 * standing (its mu* stays a certified upper bound) and counts them; the
 * top-down probe with one is unknown (the move it skipped may have been
 * fine); the planner reports sequence and group searches that may rest on
 * one as undecided, and a K found past one as an upper bound only.
 * out->undecided says whether any class is undecided.
 * The count of connected sub-assemblies containing the ground
 * (us_count_subgraphs, with a short time limit) bounds the tests of a
 * search with the ground rule and a memo.
 *
 * Every step writes its own fields of the classification and its time;
 * the first error stops the driver and empties the result. */
#include "core/core.h"
#include "hands.h"
#include "stability/stability.h"
#include "hook.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define US_CLASSIFY_MAX_TESTS 20000 /* default limit of the top-down probe */
#define US_CLASSIFY_TIME 60.0       /* default seconds per search of classes 3-5 */
#define US_CLASSIFY_COUNT_TIME 2.0  /* default seconds for the count */

us_ClassifySettings us_classify_default_settings(void) {
  us_ClassifySettings c;
  memset(&c, 0, sizeof c);
  c.stability = us_stability_default_settings();
  c.max_tests = US_CLASSIFY_MAX_TESTS;
  c.time_limit = US_CLASSIFY_TIME;
  c.count_time_limit = US_CLASSIFY_COUNT_TIME;
  c.strong = 0; /* opt-in: its search can take its whole budget (arches) */
  c.strong_settings = us_strong_default_settings();
  return c;
}

static void reset(us_Classification *c) {
  memset(c, 0, sizeof *c);
  c->unstable_body = -1;
  c->mu_critical = INFINITY;
  c->topdown = -1;
  c->dfs_status = c->sequence_status = c->group_status = US_PLAN_LIMIT;
  c->count_status = US_COUNT_REFUSED_TIME;
  c->stands_bilateral = -1;
  c->bilateral_body = -1;
  c->strong = -2;
}

void us_classification_free(us_Classification *c) {
  if (!c) return;
  us_free(c->blocked);
  us_free(c->count);
  us_strong_result_free(&c->strong_result);
  reset(c);
}

/* The code of an error some callee reported (or out of memory). */
static us_Status failed(const us_Error *err) {
  return err->code != US_OK ? err->code : US_ERR_NOMEM;
}

/* ------------------------------------------------------------- 1. stands */

static us_Status classify_stands(const us_Structure *s, const us_ClassifySettings *set,
                                 us_Classification *out, us_Error *err) {
  us_Bitset full = {0};
  if (us_structure_movable_set(s, &full))
    return us_error_set(err, US_ERR_NOMEM, "out of memory classifying");
  us_Stability *w = us_stability_new(s, &set->stability, err);
  us_StabilityResult res;
  memset(&res, 0, sizeof res);
  us_Status st = w ? us_plan_stability_test(w, &full, &res, err) : failed(err);
  if (!st) {
    out->stands = res.verdict == US_STABLE;
    out->stands_undecided = res.verdict == US_UNDECIDED;
    out->unstable_body = res.verdict == US_UNSTABLE ? res.unstable_body : -1;
  }
  us_stability_result_free(&res);
  us_stability_free(w);
  us_bitset_free(&full);
  return st;
}

/* ----------------------------------------------------------- 2. friction */

static us_Status classify_friction(const us_Structure *s, const us_ClassifySettings *set,
                                   us_Classification *out, us_Error *err) {
  us_FrictionResult fr;
  us_StabilitySettings stab = set->stability;
  if (set->time_limit > 0 && !(stab.time_limit > 0 && stab.time_limit < set->time_limit))
    stab.time_limit = set->time_limit; /* the whole bisection's */
  us_Status st = us_critical_friction(s, NULL, &stab, 0.0, 0.0, &fr, err);
  if (!st) {
    out->stands_frictionless = fr.stands_frictionless;
    out->stands_some_mu = fr.stands;
    out->mu_critical = fr.mu_critical;
    out->friction_probes = fr.probes;
    out->friction_undecided = fr.undecided;
    out->friction_timed_out = fr.timed_out;
    out->mu_low = fr.mu_low;
    out->strong_equals_weak = fr.stands_frictionless;
  }
  us_friction_result_free(&fr);
  return st;
}

/* ------------------------------------------------- 6. strong stability */

/* Frictionless and standing: strong by the theorem; not standing: not
 * strong; undecided stands: undecided; else the search, within the time
 * limit. */
static us_Status classify_strong(const us_Structure *s, const us_ClassifySettings *set,
                                 us_Classification *out, us_Error *err) {
  if (!set->strong) return US_OK;
  us_StrongResult *r = &out->strong_result;
  const char *why = out->stands_undecided ? "the stands test was undecided" : NULL;
  out->strong = out->stands_frictionless ? 1 : !out->stands && !why ? 0 : -1;
  if (out->stands_frictionless) why = "frictionless: strong = weak (Gauss's principle)";
  else if (!out->stands && !why) why = "does not stand (weak stability fails)";
  if (why || !out->stands) {
    snprintf(r->note, sizeof r->note, "%s", why);
    return US_OK;
  }
  us_StrongSettings st = set->strong_settings;
  if (set->time_limit > 0 && !(st.time_limit > 0 && st.time_limit < set->time_limit))
    st.time_limit = set->time_limit;
  us_Status rc = us_strong_stability(s, NULL, &st, r, err);
  if (rc == US_OK) out->strong = r->strong;
  return rc;
}

/* ------------------------------------------------- 3. top-down (plain DFS) */

/* Plan settings of one probe: the classification's backend and time. */
static us_PlanSettings probe_settings(const us_ClassifySettings *set, us_Search search,
                                      int max_group) {
  us_PlanSettings p = us_plan_default_settings();
  p.search = search;
  p.max_group = max_group;
  p.stability = set->stability;
  p.time_limit = set->time_limit > 0 ? set->time_limit : 0.0;
  return p;
}

/* 1 top-down, 0 not, -1 unknown; see the file head. */
static int topdown_verdict(const us_Classification *c) {
  if (c->dfs_undecided > 0) return -1; /* a move it skipped may have been fine */
  int clean = c->rejected == 0 && c->backtracks == 0;
  if (c->dfs_status == US_PLAN_FOUND) return clean;
  if (c->dfs_status == US_PLAN_LIMIT) return clean ? -1 : 0;
  return 0; /* none, or the full structure does not stand */
}

static us_Status classify_topdown(const us_Structure *s, const us_ClassifySettings *set,
                                  us_Classification *out, us_Error *err) {
  us_PlanSettings p = probe_settings(set, US_SEARCH_DFS, 1);
  p.order = US_ORDER_HIGHEST;
  p.direction = US_DIR_DOWN;
  p.rules = US_RULE_MEMO;
  p.max_tests = set->max_tests > 0 ? set->max_tests : 0;
  us_Plan plan;
  us_Status st = us_plan(s, &p, &plan, err);
  if (st) return st;
  out->dfs_status = plan.status;
  out->dfs_tests = plan.stats.tests;
  out->dfs_undecided = plan.stats.undecided;
  /* the full structure's own test is the one unstable test of UNSTABLE */
  out->rejected = plan.stats.unstable - (plan.status == US_PLAN_UNSTABLE);
  out->backtracks = plan.stats.backtracks;
  out->topdown = topdown_verdict(out);
  us_plan_free(&plan);
  return US_OK;
}

/* --------------------------------------------------- 4. one at a time */

/* The bodies outside the greedy's maximal buildable sub-assembly. */
static us_Status keep_blocked(const us_Plan *plan, us_Classification *out, us_Error *err) {
  out->nbuildable = plan->nbuildable;
  out->blocked = us_malloc((size_t)(plan->nblocked > 0 ? plan->nblocked : 1) * sizeof(int));
  if (!out->blocked) return us_error_set(err, US_ERR_NOMEM, "out of memory classifying");
  if (plan->nblocked > 0) memcpy(out->blocked, plan->blocked, (size_t)plan->nblocked * sizeof(int));
  out->nblocked = plan->nblocked;
  return US_OK;
}

static us_Status classify_sequence(const us_Structure *s, const us_ClassifySettings *set,
                                   us_Classification *out, us_Error *err) {
  us_PlanSettings p = probe_settings(set, US_SEARCH_ASSEMBLE, 1);
  us_Plan plan;
  us_Status st = us_plan(s, &p, &plan, err);
  if (st) return st;
  out->sequence_tests = plan.stats.tests;
  out->sequence_status = plan.status;
  out->sequence = plan.status == US_PLAN_FOUND;
  if (plan.status == US_PLAN_NONE) st = keep_blocked(&plan, out, err);
  /* decided here: K = 1 with a sequence, no K when it does not stand, and
     unknown when K = 1 was cut (the group search would start there) */
  out->group_status = plan.status;
  out->min_group = out->group_bound = out->sequence;
  us_plan_free(&plan);
  return st;
}

/* ----------------------------------------------------- 5. smallest K */

static us_Status classify_group(const us_Structure *s, const us_ClassifySettings *set,
                                us_Classification *out, us_Error *err) {
  if (out->sequence_status != US_PLAN_NONE) return US_OK; /* decided by step 4 */
  us_PlanSettings p = probe_settings(set, US_SEARCH_ASSEMBLE, 0);
  us_Plan plan;
  us_Status st = us_plan(s, &p, &plan, err);
  if (st) return st;
  out->group_tests = plan.stats.tests;
  out->group_status = plan.status;
  /* found: the K of the order; none or limit: the largest K that failed
     (at least 1: step 4 proved K = 1 fails); an undecided test makes a
     failed K unproven, and a found K only an upper bound */
  int sure = plan.stats.undecided == 0;
  out->group_bound = sure ? US_MAX(plan.max_group, 1) : 1;
  out->min_group = plan.status == US_PLAN_FOUND ? plan.max_group : 0;
  if (!sure && plan.status == US_PLAN_FOUND) out->group_status = US_PLAN_UNDECIDED;
  if (plan.status == US_PLAN_UNSTABLE) /* step 4 saw it stand */
    st = us_error_set(err, US_ERR_SOLVER, "classify: the group search found the full structure "
                      "unstable after the sequence search found it standing");
  us_plan_free(&plan);
  return st;
}

/* ----------------------------------------------- 7. needs buttressing */

/* No one-at-a-time sequence (step 4 says none): the smallest number of
 * hands (src/plan/hands.c), proven (hands_lower == hands) or bounded. */
static us_Status classify_hands(const us_Structure *s, const us_ClassifySettings *set,
                                us_Classification *out, us_Error *err) {
  if (out->sequence_status != US_PLAN_NONE) return US_OK;
  us_PlanSettings p = probe_settings(set, US_SEARCH_ASSEMBLE, 1);
  p.hands = 0;
  us_Plan plan;
  memset(&plan, 0, sizeof plan);
  us_Status st = us_plan_hands_after_none(s, &p, &plan, err); /* step 4 proved H = 1 none */
  if (st) return st;
  out->hands_status = plan.status;
  out->hands = plan.status == US_PLAN_FOUND ? plan.hands : 0;
  out->hands_lower = plan.hands_lower;
  out->hands_tests = plan.stats.tests;
  us_plan_free(&plan);
  return US_OK;
}

/* ------------------------------------ 8. only with equality constraints */

/* Does any contact touch body b? */
static int touches(const us_Structure *s, int b) {
  for (int c = 0; c < s->ncontact; c++)
    if (s->contacts[c].a == b || s->contacts[c].b == b) return 1;
  return 0;
}

/* The full structure with bilateral joints, when it does not stand with
 * unilateral contacts (class 1); the verdict's evidence into out. */
static us_Status classify_equality(const us_Structure *s, const us_ClassifySettings *set,
                                   us_Classification *out, us_Error *err) {
  if (out->stands || out->stands_undecided) {
    out->equality = out->stands ? 0 : -1;
    return US_OK;
  }
  us_StabilitySettings stab = set->stability;
  stab.method = US_METHOD_LP; /* an LP with +-columns; CLP's Farkas ray is the mechanism */
  us_Bitset full = {0};
  if (us_structure_movable_set(s, &full))
    return us_error_set(err, US_ERR_NOMEM, "out of memory classifying");
  us_Stability *w = us_stability_new(s, &stab, err);
  us_StabilityResult res;
  memset(&res, 0, sizeof res);
  us_Status st = w ? US_OK : failed(err);
  if (!st && us_stability_set_bilateral(w, 1))
    st = us_error_set(err, US_ERR_USAGE, "classify: bilateral joints need an LP method");
  if (!st) st = us_stability_test(w, &full, &res, err);
  if (!st) {
    int fell = res.verdict == US_UNSTABLE;
    out->stands_bilateral = res.verdict == US_STABLE ? 1 : fell ? 0 : -1;
    out->equality = out->stands_bilateral;
    out->bilateral_body = fell ? res.unstable_body : -1;
    out->bilateral_mechanism = fell && res.mechanism.nbody > 0 && res.mechanism.ok;
    out->bilateral_loose = fell && res.unstable_body >= 0 && !touches(s, res.unstable_body);
  }
  us_stability_result_free(&res);
  us_stability_free(w);
  us_bitset_free(&full);
  return st;
}

/* -------------------------------------------------------------- count */

static us_Status classify_count(const us_Structure *s, const us_ClassifySettings *set,
                                us_Classification *out, us_Error *err) {
  us_CountSettings cs = us_count_default_settings();
  cs.time_limit = set->count_time_limit > 0 ? set->count_time_limit : 0.0;
  us_Count c;
  us_Status st = us_count_subgraphs(s, &cs, &c, err);
  if (!st) {
    out->count_status = c.status;
    out->count = c.value; /* taken over */
    c.value = NULL;
    memcpy(out->count_note, c.note, sizeof out->count_note);
    out->count_note[sizeof out->count_note - 1] = '\0';
  }
  us_count_free(&c);
  return st;
}

/* ------------------------------------------------------------- driver */

typedef us_Status (*Step)(const us_Structure *, const us_ClassifySettings *, us_Classification *,
                          us_Error *);

static us_Status check_args(const us_Structure *s, const us_Classification *out, us_Error *err) {
  if (!s || !out) return us_error_set(err, US_ERR_USAGE, "us_classify: NULL argument");
  if (!us_structure_is_finalized(s))
    return us_error_set(err, US_ERR_USAGE, "us_classify: the structure is not finalized");
  return US_OK;
}

us_Status us_classify(const us_Structure *s, const us_ClassifySettings *set,
                      us_Classification *out, us_Error *err) {
  us_Error local;
  if (!err) err = &local;
  us_error_clear(err);
  if (out) reset(out);
  us_Status st = check_args(s, out, err);
  if (st) return st;
  us_ClassifySettings def = us_classify_default_settings();
  if (!set) set = &def;
  const struct {
    Step fn;
    double *t;
  } steps[] = {{classify_stands, &out->t_stands},     {classify_friction, &out->t_friction},
               {classify_topdown, &out->t_topdown},   {classify_sequence, &out->t_sequence},
               {classify_group, &out->t_group},       {classify_hands, &out->t_hands},
               {classify_equality, &out->t_equality}, {classify_count, &out->t_count},
               {classify_strong, &out->t_strong}};
  double t0 = us_now();
  out->nbody = us_structure_movable_count(s);
  for (size_t k = 0; k < sizeof steps / sizeof steps[0] && !st; k++) {
    double t = us_now();
    st = steps[k].fn(s, set, out, err);
    *steps[k].t = us_now() - t;
  }
  out->seconds = us_now() - t0;
  out->undecided = out->stands_undecided || out->friction_undecided > 0 ||
                   out->dfs_undecided > 0 || out->sequence_status == US_PLAN_UNDECIDED ||
                   out->group_status == US_PLAN_UNDECIDED ||
                   (!out->stands && !out->stands_undecided && out->equality < 0);
  if (st) us_classification_free(out);
  return st;
}
