/* unstack render: draw a structure, optionally with a plan and forces, as
 * SVG or PNG (docs/render.md), or as the interactive HTML viewer
 * (--html, cmd_render_html.c, docs/viewer.md). 3D structures are drawn
 * axonometrically (--view AZ,EL) as SVG or PNG, or in the HTML viewer.
 *
 * The flow: parse, check the output can be written, pick the format
 * (--format or --html, else the output's extension), load the structure
 * and the plan (refused when its fingerprint names another structure),
 * test the full structure when a picture's title needs its verdict (no
 * plan) or --forces needs its forces, verify a found plan's order (as
 * `unstack verify`; an invalid one is drawn with its failing step, the
 * falling body and the remainder's mechanism, exit 1), compose the title,
 * write with the format's writer (write_output: one branch per format). */
#include "options.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static const char head[] =
    "usage: unstack render FILE [--plan PLAN.json] [--forces [contacts|resultants]]\n"
    "                           [--force-set solver|margin|min-sum|min-norm] -o OUT.svg|OUT.png\n"
    "       unstack render FILE [--plan PLAN.json] --html -o OUT.html\n"
    "\n"
    "Draw the structure in FILE as SVG or PNG (a 3D one in an axonometric view,\n"
    "--view): a title with the plan's status (or, without a plan, whether the\n"
    "structure stands), bodies coloured and numbered by their removal step when a\n"
    "plan is given (with a legend), bodies that cannot be removed (a plan with\n"
    "status none) hatched red and the buildable rest numbered as it is placed,\n"
    "contact points, and with --forces the certificate forces of the full\n"
    "structure as arrows scaled to the largest: at each contact the force the\n"
    "lower body exerts on the upper one (upper: the side the contact normal\n"
    "enters when it points up), normal part blue, friction part orange. Forces\n"
    "are not unique: the arrows are one admissible set (docs/render.md). A\n"
    "structure that does not stand has the body that falls outlined red and its\n"
    "mechanism drawn (arrows, and in 2D a dashed ghost of the moving bodies). A\n"
    "found plan is verified: an invalid order is drawn with its failing step\n"
    "marked. A plan of another structure (its fingerprint) is refused. A plan\n"
    "with hands is numbered as placed; --action K draws it after K actions, held\n"
    "bodies marked (docs/render.md, \"Hands\").\n";
static const char tail[] =
    "exit: 0 written, 1 --forces given but the structure does not stand, or verify\n"
    "finds the plan's order invalid (written, the failing step marked),\n"
    "3 --forces given but the test is undecided (1 and 3: written without forces),\n"
    "2 usage or input error (nothing written)\n";

typedef enum Format { FMT_NONE = 0, FMT_SVG, FMT_PNG, FMT_HTML } Format;

/* Formats by name and by the output's extension. */
static const struct {
  const char *name, *ext;
  Format f;
} kFormats[] = {{"svg", ".svg", FMT_SVG},
                {"png", ".png", FMT_PNG},
                {"html", ".html", FMT_HTML},
                {"html", ".htm", FMT_HTML}};
#define NFORMATS ((int)(sizeof kFormats / sizeof kFormats[0]))

typedef struct {
  const char *file, *out, *plan, *title;
  int forces, time_limit_given;
  int action, action_given; /* --action K: the state after K actions */
  us_ForceSet force_set;
  int format; /* a Format */
  us_RenderSettings r;
} RenderArgs;

/* What verification of a found plan says, and the failure to mark. */
typedef struct {
  int verified, invalid;
  us_VerifyReport rep;
  us_StabilityResult rest; /* the remainder after the failing step */
  us_RenderFailure fail;
  int hands_invalid; /* a plan with actions: verify_actions' failure (rep) */
} PlanCheck;

/* --labels ids|steps|none. */
static int set_labels(const char *v, void *dst, const char *cmd) {
  static const char *const words[] = {"auto", "ids", "steps", "none"};
  for (int i = 1; i < 4; i++)
    if (!strcmp(v, words[i])) return *(us_Labels *)dst = (us_Labels)i, 0;
  return cli_fail(cmd, "unknown --labels '%s' (ids, steps, none)", v);
}

/* --view AZ,EL: two numbers, the elevation in [-90, 90]. */
static int set_view(const char *v, void *dst, const char *cmd) {
  us_RenderSettings *r = dst;
  char buf[64];
  const char *comma = strchr(v, ',');
  size_t n = comma ? (size_t)(comma - v) : 0;
  if (comma && n < sizeof buf) memcpy(buf, v, n), buf[n] = 0;
  if (!comma || n >= sizeof buf || cli_parse_double(buf, &r->view_az) ||
      cli_parse_double(comma + 1, &r->view_el) || !(fabs(r->view_az) <= 3600.0) ||
      !(fabs(r->view_el) <= 90.0))
    return cli_fail(cmd, "--view needs AZ,EL in degrees (azimuth in [-3600, 3600], "
                    "elevation in [-90, 90]), got '%s'", v);
  return 0;
}

static int set_format(const char *v, void *dst, const char *cmd) {
  for (int i = 0; i < NFORMATS; i++)
    if (!strcmp(v, kFormats[i].name)) return *(int *)dst = (int)kFormats[i].f, 0;
  return cli_fail(cmd, "unknown --format '%s' (svg, png, html)", v);
}

/* --forces [contacts|resultants]: draw forces, per contact or per pair. */
static int set_forces(const char *v, void *dst, const char *cmd) {
  RenderArgs *a = dst;
  a->forces = 1;
  if (!v || !strcmp(v, "contacts")) return a->r.force_resultants = 0, 0;
  if (!strcmp(v, "resultants")) return a->r.force_resultants = 1, 0;
  return cli_fail(cmd, "unknown --forces '%s' (contacts, resultants)", v);
}

/* --force-set NAME. */
static int set_force_set(const char *v, void *dst, const char *cmd) {
  for (int k = US_FORCESET_SOLVER; k <= US_FORCESET_MIN_NORM; k++)
    if (!strcmp(v, us_force_set_name((us_ForceSet)k)))
      return *(us_ForceSet *)dst = (us_ForceSet)k, 0;
  return cli_fail(cmd, "unknown --force-set '%s' (solver, margin, min-sum, min-norm)", v);
}

/* The command line, by render's option table (optable.h). */
static int parse(int argc, char **argv, CliCommon *c, RenderArgs *a) {
  /* One entry per option, in --help's order; optable.h says how to add one. */
  const CliOpt opts[] = {
      CLI_TEXT("--output", "OUT", &a->out, "output file (required); .svg or .png picks the format",
               .alias = "-o"),
      CLI_CALL("--format", "svg|png|html", &a->format, set_format,
               "the format, whatever the output's name"),
      CLI_FLAG_VAL("--html", &a->format, FMT_HTML,
                   "the interactive viewer, one self-contained page, 2D or 3D (also chosen by an "
                   "output name ending in .html; docs/viewer.md)"),
      CLI_TEXT("--plan", "PLAN.json", &a->plan, "colour and number bodies by removal order"),
      CLI_INT("--action", "K", &a->action, "a plan with hands: the state after its first K "
              "actions (0 to their number): placed bodies drawn, held ones marked, the rest faint",
              CLI_ATLEAST(0), .given = &a->action_given, .need = "a whole number, 0 or more"),
      CLI_CALL("--forces", NULL, a, set_forces,
               "draw the contact forces that hold the structure: one arrow per contact "
               "(contacts, the default), or one per pair of touching bodies at the resultant's "
               "point (resultants)", .optional = 1, .next_words = "contacts|resultants"),
      CLI_CALL("--force-set", "S", &a->force_set, set_force_set,
               "which admissible set: solver (its own, default), margin (the largest smallest "
               "normal force), min-sum (the least total force), min-norm (the least sum of "
               "squares: the load spread evenly); each is certified before it is drawn"),
      CLI_OPT_METHOD(c),
      CLI_OPT_LOCAL(c),
      CLI_OPT_TIME_LIMIT(&c->stab.time_limit, "limit of the stability test (default 10 s)",
                         .given = &a->time_limit_given),
      CLI_TEXT("--title", "TEXT", &a->title, "the title line (default: file, bodies, status)"),
      CLI_FLAG_VAL("--no-contacts", &a->r.show_contacts, 0, "do not mark contact points"),
      CLI_CALL("--labels", "ids|steps|none", &a->r.labels, set_labels,
               "label bodies by id or step number, or not (default: steps with a plan, ids "
               "without)"),
      CLI_FLAG_VAL("--no-labels", &a->r.labels, US_LABELS_NONE, "the same as --labels none"),
      CLI_REAL("--width", "PX", &a->r.width_px,
               "picture width in pixels (default 800; PNG at most 16384)", CLI_RANGE(16, 100000),
               .need = "a number of pixels in [16, 100000]"),
      CLI_REAL("--height", "PX", &a->r.height_px,
               "picture height (default: as the drawing needs; a PNG stays within 16384 px a "
               "side and 64 million pixels)", CLI_RANGE(16, 100000),
               .need = "a number of pixels in [16, 100000]"),
      CLI_CALL("--view", "AZ,EL", &a->r, set_view,
               "3D: azimuth and elevation of the view in degrees (default 35,25; EL in [-90, "
               "90]; docs/render.md; with --html the page's first view)"),
      CLI_OPT_CONTACT_TOL(c),
      CLI_END};
  const CliSpec spec = {"render", head, tail, opts, &a->file, 1, "more than one FILE given"};
  int r = cli_parse(&spec, argc, argv);
  if (r) return r;
  if (!a->file) return cli_fail("render", "no FILE given (see 'unstack render --help')");
  if (!a->out) return cli_fail("render", "no output given: use -o OUT.svg or -o OUT.png");
  if (a->r.labels == US_LABELS_STEPS && !a->plan)
    return cli_fail("render", "--labels steps needs --plan (steps come from a plan)");
  return 0;
}

/* Equal but for ASCII case. */
static int same_ext(const char *a, const char *b) {
  for (; *a && *b; a++, b++)
    if (tolower((unsigned char)*a) != tolower((unsigned char)*b)) return 0;
  return !*a && !*b;
}

/* --format, else the output's extension; no extension (/dev/stdout): SVG. */
static int pick_format(RenderArgs *a) {
  if (a->format) return 0;
  const char *base = strrchr(a->out, '/'), *dot = strrchr(base ? base : a->out, '.');
  if (!dot) return a->format = FMT_SVG, 0;
  for (int i = 0; i < NFORMATS; i++)
    if (same_ext(dot, kFormats[i].ext)) return a->format = (int)kFormats[i].f, 0;
  return cli_fail("render", "cannot tell the picture format from '%s': name it .svg, .png or "
                  ".html, or give --format svg|png|html", a->out);
}

/* Test the full structure, within --time-limit or 10 s: 0 done
 * (res->verdict), -1 error. */
static int full_test(const us_Structure *s, const RenderArgs *a, const CliCommon *c,
                     us_StabilityResult *res, us_Error *err) {
  us_StabilitySettings set = c->stab;
  if (!a->time_limit_given) set.time_limit = 10.0;
  us_Stability *w = us_stability_new(s, &set, err);
  int r = w && us_stability_test_full(w, res, err) == US_OK ? 0 : -1;
  us_stability_free(w);
  return r;
}

/* --force-set margin|min-sum on a stable full structure: its
 * representative forces replace the solver's in res when certified; else
 * a note, and the solver's are drawn (the legend says which). */
static int representative(const us_Structure *s, RenderArgs *a, const CliCommon *c,
                          us_StabilityResult *res, us_Error *err) {
  if (!a->forces || a->force_set == US_FORCESET_SOLVER || res->verdict != US_STABLE) return 0;
  us_Bitset all;
  if (us_bitset_init(&all, s->nbody > 0 ? s->nbody : 1))
    return us_error_set(err, US_ERR_NOMEM, "out of memory"), -1;
  us_bitset_fill(&all);
  us_StabilityResult rep;
  us_stability_result_init(&rep);
  us_Status st = us_stability_forces_representative(s, &all, a->force_set, &c->stab, &rep, err);
  us_bitset_free(&all);
  if (!st && rep.verdict == US_STABLE) {
    us_Forces keep = res->forces;
    res->forces = rep.forces, rep.forces = keep; /* rep frees the solver's */
  } else if (!st) {
    fprintf(stderr, "unstack render: %s; drawing the solver's forces\n", rep.note);
    a->force_set = US_FORCESET_SOLVER;
  }
  us_stability_result_free(&rep);
  return st ? -1 : 0;
}

/* A plan with hands (docs/render.md, "Hands"): placements in order, and
 * each body's US_HAND_* state after the first --action actions. */
typedef struct HandsView {
  int *placed, nplaced;
  unsigned char *state; /* NULL without --action */
  int held;
} HandsView;

static int hands_view(const us_Structure *s, const us_PlanFile *pf, const RenderArgs *a,
                      HandsView *hv, us_Error *err) {
  hv->placed = us_malloc(((size_t)pf->nactions + 1) * sizeof *hv->placed);
  hv->state = a->action_given ? us_calloc((size_t)s->nbody + 1, 1) : NULL;
  if (!hv->placed || (a->action_given && !hv->state))
    return us_error_set(err, US_ERR_NOMEM, "render: out of memory"), -1;
  for (int k = 0; k < pf->nactions; k++) {
    const us_Action *x = &pf->actions[k];
    if (x->verb == US_ACTION_PLACE) hv->placed[hv->nplaced++] = x->body;
    if (hv->state && k < a->action)
      hv->state[x->body] = x->verb == US_ACTION_RELEASE ? US_HAND_PLACED : US_HAND_HELD;
  }
  for (int i = 0; hv->state && i < s->nbody; i++) hv->held += hv->state[i] == US_HAND_HELD;
  return 0;
}

/* "arch.json — 10 bodies, action 3 of 20: place b8; 1 of H=2 hands held",
 * or the whole plan with its number of hands and whether it is minimal. */
static void hands_title(char *what, size_t n, const us_Structure *s, const us_PlanFile *pf,
                        const RenderArgs *a, const PlanCheck *pc, const HandsView *hv) {
  char proof[64];
  if (pc->hands_invalid) {
    snprintf(what, n, "the actions fail at action %d of %d", pc->rep.failed_step, pf->nactions);
    return;
  }
  if (a->action_given) {
    const us_Action *x = a->action > 0 ? &pf->actions[a->action - 1] : NULL;
    snprintf(what, n, "action %d of %d: %s %s; %d of H=%d hands held", a->action, pf->nactions,
             x ? us_action_name(x->verb) : "nothing", x ? us_id_text(s->bodies[x->body].id).s
                                                        : "placed", hv->held, pf->hands);
    return;
  }
  if (pf->hands_lower >= pf->hands) snprintf(proof, sizeof proof, "proven minimal");
  else if (pf->hands_lower <= 0) snprintf(proof, sizeof proof, "not proven minimal");
  else if (pf->hands_lower == pf->hands - 1)
    snprintf(proof, sizeof proof, "%d unproven", pf->hands - 1);
  else snprintf(proof, sizeof proof, "%d to %d unproven", pf->hands_lower, pf->hands - 1);
  snprintf(what, n, "plan found, %d actions (numbered as placed); hands: %d (%s)", pf->nactions,
           pf->hands, proof);
}

/* "pyramid.json — 91 bodies, plan found, 91 steps" */
static void make_title(char *buf, size_t n, const RenderArgs *a, const us_Structure *s,
                       const us_PlanFile *pf, const us_StabilityResult *res, const PlanCheck *pc,
                       const HandsView *hv) {
  const char *base = strrchr(a->file, '/');
  char what[160];
  if (a->plan && pf->nactions > 0)
    hands_title(what, sizeof what, s, pf, a, pc, hv);
  else if (pc->invalid && pc->rep.failed_step >= 0)
    snprintf(what, sizeof what, "the plan fails at step %d of %d", pc->rep.failed_step + 1,
             pf->ngroups);
  else if (pc->invalid && pc->rep.full_unstable)
    snprintf(what, sizeof what, "plan invalid: the structure does not stand");
  else if (pc->invalid)
    snprintf(what, sizeof what, "plan incomplete: %d bodies are never removed", pc->rep.remaining);
  else if (a->plan && pf->status == US_PLAN_FOUND)
    snprintf(what, sizeof what, "plan found, %d steps%s", pf->ngroups,
             pc->rep.undecided ? " (verify: undecided)" : "");
  else if (a->plan && pf->status == US_PLAN_NONE && pf->nbuildable > 0)
    snprintf(what, sizeof what, "plan status none, %d bodies cannot be removed, %d buildable "
             "(numbered as placed)", pf->nblocked, pf->nbuildable);
  else if (a->plan && pf->status == US_PLAN_NONE)
    snprintf(what, sizeof what, "plan status none, %d bodies cannot be removed", pf->nblocked);
  else if (a->plan)
    snprintf(what, sizeof what, "plan status %s", us_plan_status_name(pf->status));
  else
    snprintf(what, sizeof what, "%s", res->verdict == US_STABLE     ? "stands"
                                      : res->verdict == US_UNSTABLE ? "does not stand"
                                                                    : "stability undecided");
  snprintf(buf, n, "%s \xE2\x80\x94 %d bodies, %s", base ? base + 1 : a->file, s->nbody, what);
}

/* The format's writer; an exit code. */
static int write_output(const RenderArgs *a, const us_Structure *s, const us_PlanFile *pf,
                        CliCommon *c, us_Error *err) {
  us_Status st;
  switch (a->format) {
  case FMT_HTML: return cli_render_html(s, a->plan, pf, c, &a->r, a->file, a->out, err);
  case FMT_PNG: st = us_render_png(s, &a->r, a->out, err); break;
  default: st = us_render_svg(s, &a->r, a->out, err); break;
  }
  return st ? CLI_EXIT_ERR : CLI_EXIT_OK;
}

/* What the picture marks: an invalid plan's failure, or the full
 * structure's when it does not stand (no plan, or --forces). */
static const us_RenderFailure *failure_of(const RenderArgs *a, const us_StabilityResult *res,
                                          PlanCheck *pc) {
  if (pc->invalid && (pc->rep.failed_step >= 0 || pc->rep.full_unstable)) return &pc->fail;
  if (pc->invalid || res->verdict != US_UNSTABLE || (a->plan && !a->forces)) return NULL;
  pc->fail = (us_RenderFailure){0, res->unstable_body, &res->mechanism};
  return &pc->fail;
}

/* The remainder after step k (0-based) of pf, tested for its mechanism. */
static int test_rest(const us_Structure *s, const us_PlanFile *pf, int k, const CliCommon *c,
                     us_StabilityResult *res, us_Error *err) {
  us_Bitset present;
  if (us_bitset_init(&present, s->nbody > 0 ? s->nbody : 1))
    return us_error_set(err, US_ERR_NOMEM, "render: out of memory"), -1;
  for (int i = 0; i < s->nbody; i++) us_bitset_set(&present, i);
  for (int q = 0; q < pf->group_start[k + 1]; q++) us_bitset_clear(&present, pf->order[q]);
  us_Stability *w = us_stability_new(s, &c->stab, err);
  int r = w && us_stability_test(w, &present, res, err) == US_OK ? 0 : -1;
  us_stability_free(w);
  us_bitset_free(&present);
  return r;
}

/* A found plan is verified as `unstack verify` does; an invalid one gets
 * its failing step, the body that falls and the remainder's mechanism. */
static int check_plan(const us_Structure *s, const us_PlanFile *pf, CliCommon *c, PlanCheck *pc,
                      us_Error *err) {
  if (pf->status != US_PLAN_FOUND) return 0;
  if (pf->nactions > 0) { /* the actions replayed, as `unstack verify` does */
    if (us_verify_actions(s, &c->stab, pf->hands, pf->actions, pf->nactions, &pc->rep, err))
      return -1;
    pc->verified = 1;
    pc->hands_invalid = !pc->rep.ok && !pc->rep.undecided;
    return 0;
  }
  int r = cli_verify_plan(s, pf, c, &pc->rep, err);
  if (r < 0) return -1;
  pc->verified = 1;
  pc->invalid = r;
  int k = pc->rep.failed_step;
  pc->fail = (us_RenderFailure){k + 1, pc->rep.unstable_body, NULL};
  if (!r || (k < 0 && !pc->rep.full_unstable)) return 0;
  if (test_rest(s, pf, k, c, &pc->rest, err)) return -1;
  if (pc->rest.verdict == US_UNSTABLE) pc->fail.mechanism = &pc->rest.mechanism;
  if (pc->fail.body < 0 && pc->rest.verdict == US_UNSTABLE) pc->fail.body = pc->rest.unstable_body;
  return 0;
}

/* The order to number: the plan's, a none plan's build order, or a hands
 * plan's placements. */
static void set_order(us_RenderSettings *r, const us_PlanFile *pf, int html, const HandsView *hv) {
  if (!html && hv->placed) {
    r->order = hv->placed;
    r->norder = r->ngroups = hv->nplaced;
    r->group_start = NULL;
    r->order_builds = 1;
    r->hand_state = hv->state;
    return;
  }
  int build = !html && pf->status == US_PLAN_NONE && pf->nbuildable > 0;
  r->order = build ? pf->buildable : pf->order;
  r->norder = build ? pf->nbuildable : pf->n;
  r->ngroups = build ? pf->nbuild : pf->ngroups;
  r->group_start = r->ngroups != r->norder ? (build ? pf->build_start : pf->group_start) : NULL;
  r->order_builds = build;
}

/* Settings from the plan, forces and title; then the output. */
static int draw(RenderArgs *a, const us_Structure *s, const us_PlanFile *pf,
                const us_StabilityResult *res, PlanCheck *pc, const HandsView *hv, CliCommon *c,
                us_Error *err) {
  char title[512];
  make_title(title, sizeof title, a, s, pf, res, pc, hv);
  set_order(&a->r, pf, a->format == FMT_HTML, hv);
  if (a->format != FMT_HTML) a->r.failure = failure_of(a, res, pc);
  a->r.blocked = pf->blocked;
  a->r.nblocked = pf->nblocked;
  a->r.forces = a->forces && res->verdict == US_STABLE ? &res->forces : NULL;
  a->r.force_set = a->force_set;
  a->r.title = a->title ? a->title : title;
  return write_output(a, s, pf, c, err);
}

/* Exit code once the picture is written: an invalid order, --forces that
 * could not be drawn. */
static int outcome(const RenderArgs *a, const us_StabilityResult *res, const PlanCheck *pc) {
  if (pc->hands_invalid) {
    fprintf(stderr, "unstack render: verify: the actions are invalid (action %d)\n",
            pc->rep.failed_step);
    return CLI_EXIT_NO;
  }
  if (pc->invalid) {
    fprintf(stderr, "unstack render: verify: the order is invalid (%s; marked in the picture)\n",
            pc->rep.failed_step >= 0 ? "a failing step" : pc->rep.full_unstable
                                                             ? "the structure does not stand"
                                                             : "incomplete");
    return CLI_EXIT_NO;
  }
  if (pc->verified && pc->rep.undecided)
    fprintf(stderr, "unstack render: verify: undecided (%s)\n", pc->rep.note);
  if (!a->forces || res->verdict == US_STABLE) return CLI_EXIT_OK;
  if (res->verdict == US_UNSTABLE) {
    fprintf(stderr, "unstack render: the structure does not stand: no forces drawn\n");
    return CLI_EXIT_NO;
  }
  fprintf(stderr, "unstack render: stability undecided (%s): no forces drawn\n", res->note);
  return CLI_EXIT_UNDECIDED;
}

/* --action K needs a plan with actions, K in 0..their number; exit 2 else. */
static int check_action(const RenderArgs *a, const us_PlanFile *pf, us_Error *err) {
  if (!a->plan) us_error_set(err, US_ERR_USAGE, "--action needs --plan with a plan of hands");
  else if (pf->nactions == 0)
    us_error_set(err, US_ERR_USAGE, "%s: --action needs a plan with actions (plan --hands H|auto)",
                 a->plan);
  else if (a->format == FMT_HTML)
    us_error_set(err, US_ERR_USAGE, "--action draws one picture (SVG or PNG); the viewer steps "
                 "through every action");
  else if (a->action > pf->nactions)
    us_error_set(err, US_ERR_USAGE, "--action %d: %s has %d actions (0 to %d)", a->action, a->plan,
                 pf->nactions, pf->nactions);
  else return 0;
  return CLI_EXIT_ERR;
}

int cmd_render(int argc, char **argv) {
  CliCommon c;
  cli_common_init(&c);
  RenderArgs a;
  memset(&a, 0, sizeof a);
  a.r = us_render_default_settings();
  int r = parse(argc, argv, &c, &a);
  if (r) return r < 0 ? CLI_EXIT_OK : r;
  const char *inputs[2] = {a.file, a.plan};
  if (cli_check_output("render", a.out, inputs, a.plan ? 2 : 1)) return CLI_EXIT_ERR;
  if (pick_format(&a)) return CLI_EXIT_ERR;
  int load;
  us_Structure *s = cli_load("render", a.file, &c, c.stab.time_limit, &load);
  if (!s) return load;
  us_Error err;
  us_error_clear(&err);
  us_PlanFile pf;
  memset(&pf, 0, sizeof pf);
  us_StabilityResult res;
  us_stability_result_init(&res);
  res.verdict = US_UNDECIDED;
  PlanCheck pc;
  memset(&pc, 0, sizeof pc);
  us_stability_result_init(&pc.rest);
  int code = CLI_EXIT_OK;
  HandsView hv = {0};
  if (a.plan && cli_read_plan("render", s, a.file, a.plan, &pf, &err)) code = CLI_EXIT_ERR;
  if (!code && a.action_given) code = check_action(&a, &pf, &err);
  if (!code && pf.nactions > 0 && hands_view(s, &pf, &a, &hv, &err)) code = CLI_EXIT_ERR;
  int verdict_needed = a.forces || (!a.plan && a.format != FMT_HTML);
  if (!code && verdict_needed && full_test(s, &a, &c, &res, &err)) code = CLI_EXIT_ERR;
  if (!code && a.plan && a.format != FMT_HTML && check_plan(s, &pf, &c, &pc, &err))
    code = CLI_EXIT_ERR;
  if (!code && representative(s, &a, &c, &res, &err)) code = CLI_EXIT_ERR;
  if (!code) code = draw(&a, s, &pf, &res, &pc, &hv, &c, &err);
  if (code == CLI_EXIT_ERR) cli_error("render", &err);
  else if (code == CLI_EXIT_OK) code = outcome(&a, &res, &pc);
  us_stability_result_free(&pc.rest);
  us_stability_result_free(&res);
  us_free(hv.placed);
  us_free(hv.state);
  us_plan_file_free(&pf);
  us_structure_free(s);
  return code;
}
