/* unstack verify: re-check every step of a plan, naming the first that fails. */
#include "options.h"

#include <stdio.h>
#include <string.h>

static const char head[] =
    "usage: unstack verify FILE PLAN.json [options]\n"
    "\n"
    "Re-test the structure in FILE and the remainder after every removal of the\n"
    "plan, each with a fresh stability test whose forces are re-checked without\n"
    "the solver. Names the first step after which the remainder does not stand.\n";
static const char tail[] =
    "exit: 0 every step stands and all bodies are removed, 1 not, 2 usage or input\n"
    "error, 3 undecided (a step's test could not be decided and no later step\n"
    "falls)\n";

int cli_read_plan(const char *cmd, const us_Structure *s, const char *file, const char *plan,
                  us_PlanFile *pf, us_Error *err) {
  if (us_plan_read(s, plan, pf, err) == US_OK) {
    if (!pf->has_fingerprint)
      fprintf(stderr, "unstack %s: note: %s has no fingerprint (an older plan file): it is not "
              "checked to be a plan of %s\n", cmd, plan, file);
    return 0;
  }
  if (pf->other_structure) {
    uint64_t h = 0;
    char mine[US_FINGERPRINT_CHARS];
    us_structure_fingerprint(s, &h, NULL);
    us_fingerprint_text(h, mine);
    us_error_set(err, US_ERR_INPUT, "%s is a plan of another structure, not of %s (fingerprints "
                 "differ: the plan's %s, %s's %s)", plan, file, pf->fingerprint, file, mine);
  }
  return -1;
}

/* A found plan verified as `unstack verify` does (render and render --html):
 * 1 invalid, 0 valid or undecided, -1 error. */
int cli_verify_plan(const us_Structure *s, const us_PlanFile *pf, CliCommon *c,
                    us_VerifyReport *rep, us_Error *err) {
  cli_progress_on("render", c, CLI_PROGRESS_STEPS, pf->ngroups);
  us_Status st = us_verify_steps(s, &c->stab, pf->order, pf->n, pf->group_start, pf->ngroups,
                                 rep, err);
  cli_progress_off(c);
  if (st) return -1;
  return !rep->ok && !rep->undecided;
}

/* The command line, by verify's option table (optable.h): files[0] the
 * structure, files[1] the plan. */
static int parse(int argc, char **argv, CliCommon *c, const char **files) {
  /* One entry per option, in --help's order; optable.h says how to add one. */
  const CliOpt opts[] = {
      CLI_OPT_METHOD(c),
      CLI_OPT_LOCAL(c),
      CLI_OPT_TIME_LIMIT(&c->stab.time_limit, "stop after S seconds, inside the solver too "
                         "(undecided)"),
      CLI_OPT_CONTACT_TOL(c),
      CLI_END};
  const CliSpec spec = {"verify", head, tail, opts, files, 2, "too many arguments"};
  int r = cli_parse(&spec, argc, argv);
  if (!r && !files[1]) return cli_fail("verify", "need FILE and PLAN.json (see 'unstack verify --help')");
  return r;
}

/* A test that could not be decided: "step k: undecided (reason)". */
static int report_undecided(const us_Structure *s, const us_PlanFile *pf,
                            const us_VerifyReport *rep) {
  int k = rep->undecided_step;
  if (!strncmp(rep->note, "time limit", 10)) {
    printf("undecided: %s; none of them falls\n", rep->note);
    return CLI_EXIT_UNDECIDED;
  }
  if (k < 0) {
    printf("undecided: the full structure: its test could not be decided (%s)\n", rep->note);
  } else {
    printf("undecided: step %d (removing '%s'%s): undecided (%s)\n", k + 1,
           s->bodies[pf->order[pf->group_start[k]]].id,
           pf->group_start[k + 1] - pf->group_start[k] > 1 ? " and others" : "", rep->note);
  }
  printf("  (no later step falls; %d tests)\n", rep->steps_checked);
  return CLI_EXIT_UNDECIDED;
}

static int report(const us_Structure *s, const us_PlanFile *pf, const us_VerifyReport *rep) {
  if (rep->ok) {
    printf("valid: %d removals", pf->n);
    if (pf->ngroups != pf->n) printf(" in %d steps", pf->ngroups);
    printf(" re-checked; worst certificate residuals: force %.2e, torque %.2e (relative)\n",
           rep->max_force_residual, rep->max_torque_residual);
    return CLI_EXIT_OK;
  }
  if (rep->undecided) return report_undecided(s, pf, rep);
  if (rep->full_unstable) {
    printf("invalid: the full structure does not stand\n");
  } else if (rep->failed_step >= 0) {
    int k = rep->failed_step;
    printf("invalid: step %d (removing '%s'%s): the remaining %d bodies do not stand", k + 1,
           us_id_text(s->bodies[pf->order[pf->group_start[k]]].id).s,
           pf->group_start[k + 1] - pf->group_start[k] > 1 ? " and others" : "", rep->remaining);
    if (rep->unstable_body >= 0) printf(" ('%s' cannot be held)",
                                        us_id_text(s->bodies[rep->unstable_body].id).s);
    printf("\n");
  } else {
    printf("invalid: incomplete order: %d bodies are never removed\n", rep->remaining);
  }
  return CLI_EXIT_NO;
}

/* The plan says how bodies may leave (removal up or free): check it. */
static int check_removals(const us_Structure *s, const us_PlanFile *pf, us_Error *err) {
  if (pf->ngroups != pf->n)
    return us_error_set(err, US_ERR_INPUT, "removal kinematics with steps of several bodies "
                        "cannot be checked"), CLI_EXIT_ERR;
  int k, by;
  if (us_verify_removals(s, pf->removal, pf->order, pf->n, &k, &by, err)) return CLI_EXIT_ERR;
  if (k < 0) {
    printf("valid: every removal can %s\n", pf->removal == US_REMOVAL_UP
                                                ? "be lifted straight up"
                                                : "leave along a free direction");
    return CLI_EXIT_OK;
  }
  printf("invalid: step %d: '%s' cannot %s", k + 1, us_id_text(s->bodies[pf->order[k]].id).s,
         pf->removal == US_REMOVAL_UP ? "be lifted straight up" : "leave in any direction");
  if (by >= 0) printf(" ('%s' is in the way)", us_id_text(s->bodies[by].id).s);
  if (by == US_GROUND) printf(" (the ground is in the way)");
  printf("\n");
  return CLI_EXIT_NO;
}

/* An action plan's order must be its placements reversed. */
static int order_matches(const us_PlanFile *pf, us_Error *err) {
  int q = pf->n;
  for (int k = 0; k < pf->nactions; k++)
    if (pf->actions[k].verb == US_ACTION_PLACE && (--q < 0 || pf->order[q] != pf->actions[k].body))
      return us_error_set(err, US_ERR_INPUT, "\"order\" is not the reverse of the placements "
                          "(action %d)", k), 0;
  if (q != 0) return us_error_set(err, US_ERR_INPUT, "\"order\" is not the reverse of the "
                                  "placements"), 0;
  return 1;
}

/* A plan with hands: the actions replayed (verify_actions.c). */
static int verify_hands(const us_Structure *s, CliCommon *c, const us_PlanFile *pf,
                        us_Error *err) {
  us_VerifyReport rep;
  if (!order_matches(pf, err)) return CLI_EXIT_ERR;
  c->stab.time_limit = cli_time_left(c->stab.time_limit);
  if (us_verify_actions(s, &c->stab, pf->hands, pf->actions, pf->nactions, &rep, err))
    return CLI_EXIT_ERR;
  if (rep.ok) {
    printf("valid: %d actions with at most %d hands, %d releases re-checked; worst certificate "
           "residuals: force %.2e, torque %.2e (relative)\n", pf->nactions, pf->hands,
           rep.steps_checked, rep.max_force_residual, rep.max_torque_residual);
    return CLI_EXIT_OK;
  }
  if (rep.failed_step >= 0) {
    const us_Action *a = &pf->actions[rep.failed_step];
    printf("invalid: action %d (release '%s'): the %d placed bodies do not stand with the held "
           "ones fixed", rep.failed_step, us_id_text(s->bodies[a->body].id).s, rep.remaining);
    if (rep.unstable_body >= 0) printf(" ('%s' cannot be held)",
                                       us_id_text(s->bodies[rep.unstable_body].id).s);
    printf("\n");
    return CLI_EXIT_NO;
  }
  printf("undecided: action %d (release '%s'): undecided (%s)\n", rep.undecided_step,
         us_id_text(s->bodies[pf->actions[rep.undecided_step].body].id).s, rep.note);
  return CLI_EXIT_UNDECIDED;
}

/* us_verify_steps with the progress line (on a terminal). */
static us_Status verify_with_progress(const us_Structure *s, CliCommon *c, const us_PlanFile *pf,
                                      us_VerifyReport *rep, us_Error *err) {
  cli_progress_on("verify", c, CLI_PROGRESS_STEPS, pf->ngroups);
  c->stab.time_limit = cli_time_left(c->stab.time_limit);
  us_Status st = us_verify_steps(s, &c->stab, pf->order, pf->n, pf->group_start, pf->ngroups,
                                 rep, err);
  cli_progress_off(c);
  return st;
}

int cmd_verify(int argc, char **argv) {
  CliCommon c;
  cli_common_init(&c);
  const char *files[2] = {NULL, NULL};
  int r = parse(argc, argv, &c, files);
  if (r) return r < 0 ? CLI_EXIT_OK : r;
  int load;
  us_Structure *s = cli_load("verify", files[0], &c, c.stab.time_limit, &load);
  if (!s) return load;
  us_Error err;
  us_error_clear(&err);
  us_PlanFile pf;
  memset(&pf, 0, sizeof pf);
  us_VerifyReport rep;
  int code = CLI_EXIT_ERR;
  if (cli_read_plan("verify", s, files[0], files[1], &pf, &err) == 0) {
    if (pf.status == US_PLAN_UNDECIDED) {
      printf("undecided: the plan's status is \"%s\": it holds no order to verify\n",
             us_plan_status_name(pf.status));
      code = CLI_EXIT_UNDECIDED;
    } else if (pf.status != US_PLAN_FOUND) {
      printf("invalid: the plan's status is \"%s\": it holds no complete order\n",
             us_plan_status_name(pf.status));
      code = CLI_EXIT_NO;
    } else if (pf.hands > 0) {
      code = verify_hands(s, &c, &pf, &err);
    } else if (verify_with_progress(s, &c, &pf, &rep, &err) == US_OK) {
      code = report(s, &pf, &rep);
      if (code == CLI_EXIT_OK && pf.removal != US_REMOVAL_ANY)
        code = check_removals(s, &pf, &err);
    }
  }
  if (code == CLI_EXIT_ERR) cli_error("verify", &err);
  us_plan_file_free(&pf);
  us_structure_free(s);
  return code;
}
