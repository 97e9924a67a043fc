/* unstack classify: the classes of a structure (stands, friction, top-down,
 * one-at-a-time, smallest group, strong = weak), each with its evidence,
 * as text (one line per class) or as one JSON object. */
#include "task.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const char head[] =
    "usage: unstack classify FILE [options]\n"
    "\n"
    "Classify the structure in FILE, one line per class with its evidence\n"
    "(docs/classify.md):\n"
    "  stands       does the full structure stand with its own friction?\n"
    "  friction     frictionless, or only with friction: the critical coefficient mu*\n"
    "  strong-weak  frictionless, strong and weak stability coincide\n"
    "  strong       with friction: does every solution of the dynamics stay at rest?\n"
    "               yes (a proof), no (a witness motion, checked) or undecided\n"
    "  top-down     does 'remove the highest body' work? (the source's plain DFS)\n"
    "  sequence     does a one-at-a-time removal order exist? (if not: the blocked bodies)\n"
    "  group        the smallest K such that steps of at most K bodies suffice\n"
    "  buttressing  without a sequence: the smallest number of hands holding bodies\n"
    "               still that builds it (plan --hands auto), proven or bounded\n"
    "  count        connected sub-assemblies containing the ground (bound on tests)\n";
static const char tail[] =
    "exit: 0 classified, 2 usage or input error, 3 some class is undecided (a\n"
    "stability test it rests on could not be decided)\n";

#define TEXT_IDS 20 /* blocked bodies named in the text output */

/* --strong HOW: the method of class 6, or off. */
static int set_strong(const char *v, void *dst, const char *cmd) {
  us_ClassifySettings *set = dst;
  static const char *words[] = {"auto", "enum", "mip"}; /* us_StrongMethod order */
  set->strong = strcmp(v, "off") != 0;
  for (int k = 0; k < 3; k++)
    if (!strcmp(v, words[k])) set->strong_settings.method = (us_StrongMethod)k;
  if (set->strong && strcmp(v, "auto") && strcmp(v, "enum") && strcmp(v, "mip"))
    return cli_fail(cmd, "--strong takes auto, mip, enum or off (got '%s')", v);
  return 0;
}

/* classify's option table (optable.h), shared with batch (task.h). */
void cli_classify_table(ClassifyArgs *a, CliOpt *out) {
  CliCommon *c = &a->common;
  /* One entry per option, in --help's order; optable.h says how to add one. */
  const CliOpt opts[] = {
      CLI_FLAG("--json", &a->json, "print one JSON object instead"),
      CLI_OPT_METHOD(c),
      CLI_OPT_LOCAL(c),
      CLI_LONG("--max-tests", "N", &a->set.max_tests,
               "test limit of the top-down DFS (default 20000; 0: none)", CLI_ATLEAST(0),
               .need = "an integer >= 0"),
      CLI_REAL("--time-limit", "S", &a->set.time_limit,
               "seconds for the friction bisection and for each search of top-down, sequence "
               "and group (default 60; 0: none); a class cut there is unknown",
               CLI_ATLEAST(0), .need = "a number >= 0"),
      CLI_CALL("--strong", "HOW", &a->set, set_strong,
               "strong stability with friction: auto (default: the MIP with CBC, else the "
               "exhaustive mode search), mip, enum, or off"),
      CLI_OPT_CONTACT_TOL(c),
      CLI_END};
  _Static_assert(sizeof opts / sizeof opts[0] <= CLI_TABLE_MAX, "CLI_TABLE_MAX too small");
  memcpy(out, opts, sizeof opts);
}

/* -1: help printed (exit 0); else 0 or CLI_EXIT_ERR. By classify's option
 * table. */
static int parse_args(int argc, char **argv, ClassifyArgs *a) {
  CliOpt opts[CLI_TABLE_MAX];
  cli_classify_table(a, opts);
  const CliSpec spec = {"classify", head, tail, opts, &a->file, 1, "more than one FILE given"};
  int r = cli_parse(&spec, argc, argv);
  if (r) return r;
  if (!a->file) return cli_fail("classify", "no FILE given (see 'unstack classify --help')");
  a->set.stability = a->common.stab;
  return 0;
}

/* ------------------------------------------------------------- strings */

/* A JSON string: quotes, backslashes and control characters escaped (ids
 * are user data and may hold any of them). Used by the text output too. */
static void put_string(const char *s) {
  putchar('"');
  for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
    if (*p == '"' || *p == '\\') printf("\\%c", *p);
    else if (*p < 0x20 || *p == 0x7f) printf("\\u%04x", *p);
    else putchar(*p);
  }
  putchar('"');
}

static void put_body(const us_Structure *s, int b) { put_string(s->bodies[b].id); }

/* ---------------------------------------------------------------- text */

static void text_stands(const us_Structure *s, const us_Classification *c, const char *method) {
  if (c->stands) {
    printf("stands: yes (%s, certificate re-checked)\n", method);
    return;
  }
  if (c->stands_undecided) {
    printf("stands: undecided (%s: the test could not be decided)\n", method);
    return;
  }
  printf("stands: no (%s", method);
  if (c->unstable_body >= 0) printf(": body "), put_body(s, c->unstable_body), printf(" cannot be held");
  printf(")\n");
}

static void text_friction(const us_Classification *c, double time_limit) {
  if (c->friction_timed_out) {
    printf("friction: unknown (time limit of %g s, %d probes", time_limit, c->friction_probes);
    if (c->stands_some_mu)
      printf("; stands with mu = %.6f, mu* in (%.6f, %.6f]", c->mu_critical, c->mu_low,
             c->mu_critical);
    printf(")\n");
    return;
  }
  if (c->friction_undecided > 0 && !c->stands_frictionless) {
    printf("friction: undecided (%d of %d probes could not be decided", c->friction_undecided,
           c->friction_probes);
    if (c->stands_some_mu) printf("; stands with mu = %.6f, mu* may be lower", c->mu_critical);
    printf(")\n");
    return;
  }
  if (c->stands_frictionless)
    printf("friction: stands frictionless (mu* = 0, %d probe%s)\n", c->friction_probes,
           c->friction_probes == 1 ? "" : "s");
  else if (c->stands_some_mu)
    printf("friction: stands only with friction, mu* = %.6f (every contact alike; bisection to "
           "1e-7, %d probes)\n", c->mu_critical, c->friction_probes);
  else
    printf("friction: stands for no mu up to 1000 (%d probes)\n", c->friction_probes);
}

static void text_strong_weak(const us_Classification *c) {
  if (c->strong_equals_weak)
    printf("strong-weak: frictionless: strong = weak (Gauss's principle)\n");
  else if (c->friction_timed_out && !c->stands_some_mu)
    printf("strong-weak: unknown (the friction class was cut by the time limit)\n");
  else
    printf("strong-weak: not frictionless: they may differ (the strong line decides)\n");
}

static const char *plural(long n) { return n == 1 ? "" : "s"; }

/* "R rejected moves, B backtracks" */
static void moves(const us_Classification *c) {
  printf("%ld rejected move%s, %ld backtrack%s", c->rejected, plural(c->rejected), c->backtracks,
         plural(c->backtracks));
}

static void text_topdown(const us_Classification *c) {
  printf("top-down: ");
  if (c->topdown == 1) {
    printf("yes (the source's DFS, highest first: %ld tests, no rejected move, no "
           "backtracking)\n", c->dfs_tests);
  } else if (c->dfs_status == US_PLAN_UNSTABLE) {
    printf("no (the full structure does not stand)\n");
  } else if (c->dfs_undecided > 0) {
    printf("undecided (%ld of the source's DFS's %ld tests could not be decided)\n",
           c->dfs_undecided, c->dfs_tests);
  } else if (c->topdown == -1) {
    printf("unknown (limit: the source's DFS stopped at %ld tests before any move failed)\n",
           c->dfs_tests);
  } else if (c->dfs_status == US_PLAN_FOUND) {
    printf("no, needs backtracking in the source's DFS (found after "), moves(c);
    printf("; %ld tests)\n", c->dfs_tests);
  } else if (c->dfs_status == US_PLAN_NONE) {
    printf("no (the source's DFS finds no order: %ld tests, ", c->dfs_tests), moves(c);
    printf(")\n");
  } else {
    printf("no, highest first fails ("), moves(c);
    printf("; the source's DFS stopped at its limit after %ld tests)\n", c->dfs_tests);
  }
}

static void text_blocked(const us_Structure *s, const us_Classification *c) {
  for (int k = 0; k < c->nblocked && k < TEXT_IDS; k++) {
    if (k) printf(", ");
    put_body(s, c->blocked[k]);
  }
  if (c->nblocked > TEXT_IDS) printf(" and %d more", c->nblocked - TEXT_IDS);
}

static void text_sequence(const us_Structure *s, const us_Classification *c,
                          const ClassifyArgs *a) {
  switch (c->sequence_status) {
  case US_PLAN_FOUND:
    printf("sequence: yes, one body at a time (assemble search, %ld tests)\n", c->sequence_tests);
    return;
  case US_PLAN_UNSTABLE: printf("sequence: none (the full structure does not stand)\n"); return;
  case US_PLAN_LIMIT:
    printf("sequence: unknown (time limit of %g s, %ld tests)\n", a->set.time_limit,
           c->sequence_tests);
    return;
  case US_PLAN_UNDECIDED:
    printf("sequence: undecided (none found; some of its %ld tests could not be decided)\n",
           c->sequence_tests);
    return;
  default: break;
  }
  printf("sequence: none; blocked: ");
  text_blocked(s, c);
  printf(" (a maximal buildable sub-assembly has %d of %d bodies; %ld tests)\n", c->nbuildable,
         c->nbody, c->sequence_tests);
}

static void text_group(const us_Classification *c, const ClassifyArgs *a) {
  switch (c->group_status) {
  case US_PLAN_FOUND:
    if (c->sequence) printf("group: smallest K = 1\n");
    else printf("group: smallest K = %d (assemble with automatic K, %ld tests)\n", c->min_group,
                c->group_tests);
    return;
  case US_PLAN_UNSTABLE:
    printf("group: no sequence for any K: the full structure does not stand (removing "
           "everything at once is one step)\n");
    return;
  case US_PLAN_NONE:
    printf("group: K > %d (the planner's bound; K <= %d, all bodies at once)\n", c->group_bound,
           c->nbody);
    return;
  case US_PLAN_UNDECIDED:
    printf("group: undecided (");
    if (c->group_bound > 0) printf("K > %d; ", c->group_bound);
    if (c->min_group > 0) printf("K <= %d; ", c->min_group);
    printf("some tests could not be decided)\n");
    return;
  default: break;
  }
  printf("group: unknown (time limit of %g s", a->set.time_limit);
  if (c->group_bound > 0) printf("; K > %d", c->group_bound);
  printf(")\n");
}

static void text_count(const us_Classification *c) {
  if (c->count)
    printf("count: %s connected sub-assemblies containing the ground (bound on a search's "
           "tests)\n", c->count);
  else
    printf("count: refused (%s)\n", c->count_note);
}

/* 7. needs buttressing: only when no one-at-a-time sequence exists. */
static void text_hands(const us_Classification *c) {
  if (c->sequence_status != US_PLAN_NONE) return;
  if (c->hands_status == US_PLAN_FOUND && c->hands_lower >= c->hands)
    printf("buttressing: needed: the smallest number of hands holding bodies still is %d "
           "(proven: %d cannot build it; plan --hands auto, %ld tests)\n", c->hands,
           c->hands - 1, c->hands_tests);
  else if (c->hands_status == US_PLAN_FOUND)
    printf("buttressing: needed: %d hands suffice; %d to %d not proven impossible (plan "
           "--hands auto, %ld tests)\n", c->hands, c->hands_lower, c->hands - 1, c->hands_tests);
  else
    printf("buttressing: needed; the number of hands is unknown (%s)\n",
           us_plan_status_name(c->hands_status));
}

/* 8. stands only with equality constraints (bilateral joints). */
static void text_equality(const us_Structure *s, const us_Classification *c) {
  printf("equality constraints: ");
  if (c->stands) {
    printf("no, it stands already with unilateral contacts\n");
  } else if (c->equality > 0) {
    printf("yes, stands only with equality constraints (bilateral joints: contact forces free "
           "in sign, as with mortar)\n");
  } else if (c->equality < 0) {
    printf("unknown (%s)\n", c->stands_undecided ? "the unilateral test is undecided"
                                                   : "the bilateral test is undecided");
  } else {
    printf("no, it does not stand even with bilateral joints: ");
    if (c->bilateral_loose) printf("body "), put_body(s, c->bilateral_body), printf(" touches nothing");
    else if (c->bilateral_mechanism) printf("a mechanism moves without opening or sliding a joint");
    else printf("no forces balance gravity");
    if (!c->bilateral_loose && c->bilateral_body >= 0)
      printf(" (moving most: "), put_body(s, c->bilateral_body), printf(")");
    printf("\n");
  }
}

static const char *mode_word(us_ContactMode m) {
  static const char *w[] = {"separates", "sticks", "slides+", "slides-"};
  return (unsigned)m < 4 ? w[m] : "?";
}

static const char *strong_method_word(us_StrongMethod m) {
  return m == US_STRONG_MIP ? "mip" : m == US_STRONG_ENUM ? "enumeration" : "auto";
}

/* Class 6 with friction on one line: the answer, how, and for "no" the
 * witness's moving bodies and its contact modes (JSON has it all). */
static void text_strong(const us_Structure *s, const us_Classification *c) {
  const us_StrongResult *r = &c->strong_result;
  if (c->strong == -2) return;
  printf("strong: %s (%s", c->strong == 1 ? "yes" : c->strong == 0 ? "no" : "undecided", r->note);
  if (r->nodes) printf("; %s, %ld %s", strong_method_word(r->method), r->nodes,
                       r->method == US_STRONG_MIP ? "nodes" : "LPs");
  printf(")");
  if (r->has_witness) {
    printf("; witness:");
    for (int k = 0; k < r->nbody && k < TEXT_IDS; k++) {
      printf(" "), put_body(s, r->body[k]);
      const double *a = r->accel + (r->dim == 3 ? 6 : 3) * k;
      if (r->dim == 3)
        printf(" a = (%.4g, %.4g, %.4g) alpha = (%.4g, %.4g, %.4g)", a[0], a[1], a[2], a[3], a[4],
               a[5]);
      else
        printf(" a = (%.4g, %.4g) alpha = %.4g", a[0], a[1], a[2]);
    }
    int n[4] = {0, 0, 0, 0};
    for (int k = 0; k < r->ncontact; k++) n[r->mode[k] & 3]++;
    printf("; contacts: %d separate, %d stick, %d slide", n[0], n[1], n[2] + n[3]);
  }
  printf("\n");
}

static void print_text(const us_Structure *s, const us_Classification *c, const ClassifyArgs *a) {
  const char *method = us_method_name(us_method_resolve(a->set.stability.method, s));
  text_stands(s, c, method);
  text_friction(c, a->set.time_limit);
  text_strong_weak(c);
  text_strong(s, c);
  text_topdown(c);
  text_sequence(s, c, a);
  text_group(c, a);
  text_hands(c);
  text_equality(s, c);
  text_count(c);
  printf("time: %.3f s (%d bodies, %d contacts)\n", c->seconds, c->nbody, s->ncontact);
}

/* ---------------------------------------------------------------- JSON */

static const char *json_bool(int b) { return b ? "true" : "false"; }

static void json_body_or_null(const us_Structure *s, int b) {
  if (b >= 0) put_body(s, b);
  else printf("null");
}

static void json_friction(const us_Classification *c) {
  printf(", \"stands_frictionless\": %s, \"stands_with_friction\": %s, \"mu_critical\": ",
         json_bool(c->stands_frictionless), json_bool(c->stands_some_mu));
  if (isfinite(c->mu_critical)) printf("%.6f", c->mu_critical);
  else printf("null");
  printf(", \"friction_probes\": %d, \"friction_undecided\": %d, \"friction_timed_out\": %s, "
         "\"mu_low\": %.6f, \"strong_equals_weak\": %s",
         c->friction_probes, c->friction_undecided, json_bool(c->friction_timed_out), c->mu_low,
         json_bool(c->strong_equals_weak));
}

static void json_topdown(const us_Classification *c, long max_tests) {
  printf(", \"topdown\": %s", c->topdown < 0 ? "null" : json_bool(c->topdown));
  printf(", \"dfs\": {\"status\": \"%s\", \"tests\": %ld, \"undecided\": %ld, \"rejected\": %ld, "
         "\"backtracks\": %ld, \"max_tests\": %ld}", us_plan_status_name(c->dfs_status),
         c->dfs_tests, c->dfs_undecided, c->rejected, c->backtracks, max_tests);
}

static void json_sequence(const us_Structure *s, const us_Classification *c) {
  printf(", \"sequence\": %s, \"sequence_status\": \"%s\", \"sequence_tests\": %ld, "
         "\"buildable\": %d, \"blocked\": [",
         c->sequence_status == US_PLAN_LIMIT || c->sequence_status == US_PLAN_UNDECIDED ? "null"
         : json_bool(c->sequence), us_plan_status_name(c->sequence_status), c->sequence_tests,
         c->nbuildable);
  for (int k = 0; k < c->nblocked; k++) {
    if (k) printf(", ");
    put_body(s, c->blocked[k]);
  }
  printf("]");
}

static const char *group_word(us_PlanStatus st) {
  switch (st) {
  case US_PLAN_NONE: return "beyond-bound"; /* no step of up to the bound */
  default: return us_plan_status_name(st);
  }
}

static void json_group(const us_Classification *c) {
  printf(", \"min_group\": ");
  if (c->group_status == US_PLAN_FOUND) printf("%d", c->min_group);
  else printf("null");
  printf(", \"group_status\": \"%s\", \"group_bound\": %d, \"group_tests\": %ld",
         group_word(c->group_status), c->group_bound, c->group_tests);
}

static void json_equality(const us_Structure *s, const us_Classification *c) {
  const char *why = c->equality != 0 || c->stands ? "null"
                    : c->bilateral_loose          ? "\"loose body\""
                    : c->bilateral_mechanism      ? "\"mechanism\""
                                                  : "\"infeasible\"";
  printf(", \"equality\": %s, \"stands_bilateral\": %s, \"equality_reason\": ",
         c->equality < 0 ? "null" : json_bool(c->equality),
         c->stands_bilateral < 0 ? "null" : json_bool(c->stands_bilateral));
  if (c->stands) printf("\"stands\"");
  else printf("%s", why);
  printf(", \"bilateral_body\": ");
  json_body_or_null(s, c->bilateral_body);
}

static void json_count(const us_Classification *c) {
  printf(", \"count\": ");
  if (c->count) put_string(c->count);
  else printf("null");
  printf(", \"count_status\": \"%s\", \"count_note\": ", us_count_status_name(c->count_status));
  put_string(c->count_note);
}

/* Class 6 with friction: strong, its method, note, and the witness. */
static void json_strong(const us_Structure *s, const us_Classification *c) {
  const us_StrongResult *r = &c->strong_result;
  printf(", \"strong\": %s, \"strong_method\": ",
         c->strong == 1 ? "true" : c->strong == 0 ? "false" : "null");
  if (r->nodes) printf("\"%s\"", strong_method_word(r->method));
  else printf("null");
  printf(", \"strong_note\": ");
  put_string(c->strong == -2 ? "not asked" : r->note);
  printf(", \"strong_nodes\": %ld, \"strong_witness\": ", r->nodes);
  if (!r->has_witness) {
    printf("null");
    return;
  }
  printf("{\"bodies\": [");
  for (int k = 0; k < r->nbody; k++) {
    printf("%s{\"id\": ", k ? ", " : "");
    put_body(s, r->body[k]);
    const double *a = r->accel + (r->dim == 3 ? 6 : 3) * k;
    if (r->dim == 3)
      printf(", \"a\": [%.9g, %.9g, %.9g], \"alpha\": [%.9g, %.9g, %.9g]}", a[0], a[1], a[2],
             a[3], a[4], a[5]);
    else
      printf(", \"a\": [%.9g, %.9g], \"alpha\": %.9g}", a[0], a[1], a[2]);
  }
  printf("], \"contacts\": [");
  for (int k = 0; k < r->ncontact; k++) {
    const us_Contact *ct = &s->contacts[r->contact[k]];
    printf("%s{\"a\": ", k ? ", " : "");
    json_body_or_null(s, ct->a);
    printf(", \"b\": ");
    put_body(s, ct->b);
    if (r->dim == 3)
      printf(", \"p\": [%.9g, %.9g, %.9g], \"mode\": \"%s\", \"f\": [%.9g, %.9g, %.9g]}",
             ct->p[0], ct->p[1], ct->p[2], mode_word(r->mode[k]), r->force[3 * k],
             r->force[3 * k + 1], r->force[3 * k + 2]);
    else
      printf(", \"p\": [%.9g, %.9g], \"mode\": \"%s\", \"f\": [%.9g, %.9g]}", ct->p[0],
             ct->p[1], mode_word(r->mode[k]), r->force[2 * k], r->force[2 * k + 1]);
  }
  printf("]}");
}

static void print_json(const us_Structure *s, const us_Classification *c, const ClassifyArgs *a) {
  printf("{\"file\": ");
  put_string(a->file);
  printf(", \"method\": \"%s\", \"bodies\": %d, \"contacts\": %d, \"stands\": %s, "
         "\"stands_undecided\": %s, \"unstable_body\": ", us_method_name(us_method_resolve(a->set.stability.method, s)),
         c->nbody, s->ncontact, json_bool(c->stands), json_bool(c->stands_undecided));
  json_body_or_null(s, c->unstable_body);
  json_friction(c);
  json_topdown(c, a->set.max_tests);
  printf(", \"time_limit\": %g", a->set.time_limit);
  json_sequence(s, c);
  json_group(c);
  if (c->sequence_status == US_PLAN_NONE)
    printf(", \"hands\": %d, \"hands_lower\": %d, \"hands_status\": \"%s\"", c->hands,
           c->hands_lower, us_plan_status_name(c->hands_status));
  json_equality(s, c);
  json_count(c);
  json_strong(s, c);
  printf(", \"undecided\": %s", json_bool(c->undecided));
  printf(", \"seconds\": %.6f, \"times\": {\"stands\": %.6f, \"friction\": %.6f, \"topdown\": %.6f, "
         "\"sequence\": %.6f, \"group\": %.6f, \"equality\": %.6f, \"count\": %.6f, "
         "\"strong\": %.6f}}\n",
         c->seconds, c->t_stands, c->t_friction, c->t_topdown, c->t_sequence, c->t_group,
         c->t_equality, c->t_count, c->t_strong);
}

us_Status cli_classify_run(const us_Structure *s, const ClassifyArgs *a, us_Classification *c,
                           us_Error *err) {
  us_ClassifySettings set = a->set;
  set.stability = a->common.stab;
  return us_classify(s, &set, c, err);
}

int cli_classify_exit(const us_Classification *c) {
  return c->undecided ? CLI_EXIT_UNDECIDED : CLI_EXIT_OK;
}

int cmd_classify(int argc, char **argv) {
  ClassifyArgs a;
  memset(&a, 0, sizeof a);
  cli_common_init(&a.common);
  a.set = us_classify_default_settings();
  a.set.strong = 1; /* --strong auto */
  int r = parse_args(argc, argv, &a);
  if (r) return r < 0 ? CLI_EXIT_OK : r;
  int load;
  us_Structure *s = cli_load("classify", a.file, &a.common, a.set.time_limit, &load);
  if (!s) return load;
  us_Error err;
  us_error_clear(&err);
  us_Classification c;
  int code = CLI_EXIT_ERR;
  if (cli_classify_run(s, &a, &c, &err) == US_OK) {
    if (a.json) print_json(s, &c, &a);
    else print_text(s, &c, &a);
    code = cli_classify_exit(&c);
  } else {
    cli_error("classify", &err);
  }
  us_classification_free(&c);
  us_structure_free(s);
  return code;
}
