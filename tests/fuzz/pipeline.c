/* The whole pipeline, shared by the fuzz targets `pipeline` and `oom`:
 * parse -> the full structure with every stability method -> a short plan
 * -> plan file written and read back -> verification of the order read.
 *
 * Properties (the reference run checks them):
 *   - a STABLE verdict carries forces that pass the independent
 *     certificate check;
 *   - methods never disagree: STABLE from one method and UNSTABLE from
 *     another is a finding (UNDECIDED agrees with anything). Every method
 *     decides the same weak-stability question exactly: the LPs by
 *     feasibility, the LCP by a complementary solution or a dual-cone
 *     proof, falling back to the LP otherwise (docs/lcp.md);
 *   - the plan's status matches its method's verdict on the full
 *     structure (found => not unstable, unstable => not stable);
 *   - the plan file reads back with the same status, order and steps; a
 *     found order verifies (us_verify_steps) with the plan's method and
 *     with the default LP, and its removals with the plan's kinematics.
 *
 * Out of memory (oom_phase >= 0): every library call is numbered. The
 * reference run records each call's status and outcome (verdict, plan
 * status, verification result); the second run arms us_alloc_fail_after
 * at the start of phase oom_phase (0 parse, 1 stability, 2 plan, 3 plan
 * file and verification) and stops at its first error. A call that
 * succeeded in the reference must then either succeed with the same
 * outcome or fail with US_ERR_NOMEM: an allocation failure that turns into
 * another error or a different answer is a finding. Leaks are checked by
 * the caller (us_alloc_live). */
#include "fuzz.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_CALLS 64

typedef struct Run {
  int oom;           /* 0: reference run; 1: the run with failures armed */
  int phase;         /* phase at which failures are armed */
  long n;            /* allocations that succeed before the first failure */
  int ncall;
  int stopped;       /* oom run: the first error ended it */
  us_Status status[MAX_CALLS];
  int outcome[MAX_CALLS];
} Run;

static void enter_phase(Run *r, int phase) {
  if (r->oom && phase == r->phase) us_alloc_fail_after(r->n);
}

/* Record or compare one call; 1 when it succeeded and the run goes on. */
static int call(Run *r, const char *what, us_Status st, const us_Error *err, int outcome) {
  fz_check_error(what, st, err);
  if (st && getenv("FZ_DUMP")) fprintf(stderr, "%s: %s: %s\n", what, us_status_name(st), err->msg);
  int k = r->ncall++;
  if (k >= MAX_CALLS) fz_finding("more than %d calls", MAX_CALLS);
  if (!r->oom) {
    r->status[k] = st;
    r->outcome[k] = outcome;
    return st == US_OK;
  }
  if (st != US_OK) {
    if (r->status[k] == US_OK && st != US_ERR_NOMEM)
      fz_finding("%s: out of memory (phase %d, n %ld) reported as %s: %s", what, r->phase, r->n,
                 us_status_name(st), err->msg);
    r->stopped = 1;
    return 0;
  }
  if (r->status[k] != US_OK)
    fz_finding("%s: fails in the reference (%s) but succeeds out of memory", what,
               us_status_name(r->status[k]));
  if (r->outcome[k] != outcome)
    fz_finding("%s: outcome %d out of memory (phase %d, n %ld), %d in the reference", what,
               outcome, r->phase, r->n, r->outcome[k]);
  return 1;
}

/* ------------------------------------------------------------- stability */

static void check_certificate(const us_Structure *s, const us_StabilityResult *res,
                              const us_StabilitySettings *set) {
  us_Bitset full;
  if (us_structure_movable_set(s, &full)) fz_finding("movable set: out of memory");
  us_CertCheck c = us_certificate_check(s, &full, &res->forces, set->cert_tol);
  us_bitset_free(&full);
  if (!c.ok)
    fz_finding("%s: stable with a certificate that fails (force %g torque %g cone %g sign %g)",
               us_method_name(set->method), c.max_force_residual, c.max_torque_residual,
               c.max_cone_violation, c.max_sign_violation);
}

/* Verdict of one method on the full structure, or -1 (error). */
static int full_verdict(Run *r, const us_Structure *s, us_Method m) {
  us_Error err;
  us_error_clear(&err);
  us_StabilitySettings set = us_stability_default_settings();
  set.method = m;
  us_Stability *w = us_stability_new(s, &set, &err);
  if (!w && err.code == US_OK) fz_finding("stability_new failed without an error code");
  if (!call(r, "stability_new", w ? US_OK : err.code, &err, 0)) return -1;
  us_StabilityResult res;
  memset(&res, 0, sizeof res);
  us_Status st = us_stability_test_full(w, &res, &err);
  int v = call(r, us_method_name(m), st, &err, st ? -1 : (int)res.verdict) ? (int)res.verdict : -1;
  if (v == US_STABLE && !r->oom) check_certificate(s, &res, &set);
  us_stability_result_free(&res);
  us_stability_free(w);
  return v;
}

static void check_methods(Run *r, const us_Structure *s, int v[US_METHOD_COUNT]) {
  for (int m = 0; m < US_METHOD_COUNT; m++) {
    v[m] = r->stopped ? -1 : full_verdict(r, s, (us_Method)m);
  }
  if (r->oom) return;
  if (getenv("FZ_DUMP")) fprintf(stderr, "verdicts %d %d %d %d\n", v[0], v[1], v[2], v[3]);
  for (int a = 0; a < US_METHOD_COUNT; a++)
    for (int b = 0; b < US_METHOD_COUNT; b++)
      if (v[a] == US_STABLE && v[b] == US_UNSTABLE)
        fz_finding("%s says stable, %s says unstable", us_method_name((us_Method)a),
                   us_method_name((us_Method)b));
}

/* ------------------------------------------------------------------ plan */

static us_PlanSettings plan_settings(uint8_t c0, uint8_t c1) {
  static const int groups[4] = {1, 1, 2, 0};
  us_PlanSettings set = us_plan_default_settings();
  set.search = (us_Search)(c0 & 3);
  /* steps of several bodies need assemble; kinematics need a graph search */
  int assemble = set.search == US_SEARCH_ASSEMBLE;
  set.max_group = assemble ? groups[(c0 >> 2) & 3] : 1;
  set.removal = assemble ? US_REMOVAL_ANY : (us_Removal)(((c0 >> 4) & 3) % 3);
  set.direction = (us_Direction)((c0 >> 6) & 1);
  set.certificates = (c0 >> 7) & 1;
  set.stability.method = (us_Method)(c1 & 3);
  set.order = (us_Order)(((c1 >> 2) & 3) % 3);
  set.rules = US_RULE_ALL ^ ((unsigned)(c1 >> 3) & US_RULE_ALL);
  set.seed = c1;
  set.max_tests = 100;
  set.max_exact_tests = 100;
  return set;
}

static void check_read_back(const us_Plan *p, const us_PlanFile *pf) {
  if (pf->status != p->status) fz_finding("plan file: status %d read as %d", p->status, pf->status);
  if (p->status != US_PLAN_FOUND) return;
  if (pf->n != p->nsteps) fz_finding("plan file: %d removals read as %d", p->nsteps, pf->n);
  if (memcmp(pf->order, p->order, (size_t)p->nsteps * sizeof *p->order))
    fz_finding("plan file: the order reads back differently");
  int ng = p->group_start ? p->ngroups : p->nsteps;
  if (pf->ngroups != ng) fz_finding("plan file: %d steps read as %d", ng, pf->ngroups);
  for (int k = 0; k <= ng; k++)
    if (pf->group_start[k] != (p->group_start ? p->group_start[k] : k))
      fz_finding("plan file: step %d starts elsewhere", k);
}

static void verify_with(Run *r, const us_Structure *s, const us_PlanFile *pf, us_Method m) {
  us_Error err;
  us_error_clear(&err);
  us_StabilitySettings set = us_stability_default_settings();
  set.method = m;
  us_VerifyReport rep;
  memset(&rep, 0, sizeof rep);
  us_Status st = us_verify_steps(s, &set, pf->order, pf->n, pf->group_start, pf->ngroups, &rep, &err);
  if (!call(r, "verify", st, &err, st ? -1 : rep.ok) || r->oom) return;
  if (!rep.ok)
    fz_finding("a found plan does not verify with %s: failed step %d, full unstable %d, incomplete %d",
               us_method_name(m), rep.failed_step, rep.full_unstable, rep.incomplete);
}

static void verify_kinematics(Run *r, const us_Structure *s, const us_PlanFile *pf) {
  if (pf->removal == US_REMOVAL_ANY || pf->ngroups != pf->n) return;
  us_Error err;
  us_error_clear(&err);
  int failed = -1, blocker = -2;
  us_Status st = us_verify_removals(s, pf->removal, pf->order, pf->n, &failed, &blocker, &err);
  if (!call(r, "verify_removals", st, &err, st ? -1 : failed) || r->oom) return;
  if (failed != -1)
    fz_finding("a found plan's removal %d is blocked by %d (%s)", failed, blocker,
               us_removal_name(pf->removal));
}

static void plan_file(Run *r, const us_Structure *s, const us_Plan *p, const us_PlanSettings *set) {
  us_Error err;
  us_error_clear(&err);
  const char *path = fz_path(3, "plan.json");
  if (!call(r, "plan_write", us_plan_write(s, p, set, path, &err), &err, 0)) return;
  us_PlanFile pf;
  memset(&pf, 0, sizeof pf);
  us_Status st = us_plan_read(s, path, &pf, &err);
  if (call(r, "plan_read", st, &err, st ? -1 : (int)pf.status)) {
    if (!r->oom) check_read_back(p, &pf);
    if (pf.status == US_PLAN_FOUND) {
      verify_with(r, s, &pf, set->stability.method);
      if (set->stability.method != US_METHOD_LP && !r->stopped) verify_with(r, s, &pf, US_METHOD_LP);
      if (!r->stopped) verify_kinematics(r, s, &pf);
    }
  }
  us_plan_file_free(&pf);
}

static void check_plan_status(const us_Plan *p, const us_PlanSettings *set, const int *v) {
  int vm = v[set->stability.method];
  if (p->status == US_PLAN_FOUND && vm == US_UNSTABLE)
    fz_finding("plan found with %s, which says the full structure is unstable",
               us_method_name(set->stability.method));
  if (p->status == US_PLAN_UNSTABLE && vm == US_STABLE)
    fz_finding("plan says unstable, %s says stable", us_method_name(set->stability.method));
}

static void plan(Run *r, const us_Structure *s, uint8_t c0, uint8_t c1, const int *v) {
  us_PlanSettings set = plan_settings(c0, c1);
  us_Plan p;
  us_Error err;
  us_error_clear(&err);
  enter_phase(r, 2);
  us_Status st = us_plan(s, &set, &p, &err);
  if (!call(r, "plan", st, &err, st ? -1 : (int)p.status)) return;
  if (!r->oom && getenv("FZ_DUMP"))
    fprintf(stderr, "plan %s with %s: %s, %d removals in %d steps\n", us_search_name(set.search),
            us_method_name(set.stability.method), us_plan_status_name(p.status), p.nsteps,
            p.group_start ? p.ngroups : p.nsteps);
  if (!r->oom) check_plan_status(&p, &set, v);
  enter_phase(r, 3);
  plan_file(r, s, &p, &set);
  us_plan_free(&p);
}

/* ------------------------------------------------------------------ driver */

static void run(Run *r, const char *text, uint8_t c0, uint8_t c1) {
  us_Error err;
  us_error_clear(&err);
  enter_phase(r, 0);
  us_Structure *s = us_structure_parse(text, "input.json", 0, &err);
  if (!s && err.code == US_OK) fz_finding("parse failed without an error code");
  if (call(r, "parse", s ? US_OK : err.code, &err, 0) && fz_small(s)) {
    int v[US_METHOD_COUNT];
    enter_phase(r, 1);
    check_methods(r, s, v);
    if (!r->stopped) plan(r, s, c0, c1, v);
  }
  us_structure_free(s);
  us_alloc_fail_after(-1);
}

void fz_pipeline(const char *text, uint8_t c0, uint8_t c1, int oom_phase, long oom_n) {
  if (getenv("FZ_DUMP")) fprintf(stderr, "structure:\n%s\nctl %u %u\n", text, c0, c1);
  static Run r; /* large; one at a time */
  memset(&r, 0, sizeof r);
  r.phase = oom_phase;
  r.n = oom_n;
  run(&r, text, c0, c1);
  if (oom_phase < 0) return;
  r.oom = 1;
  r.ncall = 0;
  run(&r, text, c0, c1);
}
