/* Structure.render(path, plan=None, ...): a picture (SVG, PNG) or the
 * interactive page (HTML) of a structure and, when given, its plan: a
 * found plan's order (or a hands plan's actions in the page), a none plan's
 * build order and blocked bodies, and the plan's certificate forces when it
 * was made with certificates=True. */
#include "ext.h"

#include <string.h>

/* What the plan shows: its order (found) or the greedy's build (none). */
static void plan_order(const us_Plan *p, us_RenderSettings *r) {
  if (p->status == US_PLAN_FOUND && !p->actions) {
    r->order = p->order, r->norder = p->nsteps;
    r->group_start = p->group_start, r->ngroups = p->group_start ? p->ngroups : p->nsteps;
  } else if (p->buildable && p->build_start) {
    r->order = p->buildable, r->norder = p->nbuildable, r->order_builds = 1;
    r->group_start = p->build_start, r->ngroups = p->nbuild;
  }
  if (p->blocked) r->blocked = p->blocked, r->nblocked = p->nblocked;
}

/* The page's settings: status, per-step forces, hands actions, and a found
 * order's verification (as `unstack render --html`: a failing step in red). */
static us_Status page(const us_Structure *s, const us_Plan *p, const us_StabilitySettings *stab,
                      us_HtmlSettings *h, us_Error *err) {
  if (!p) return US_OK;
  h->status = p->status;
  if (p->certs && !p->actions) h->certs = p->certs; /* the page toggles them */
  if (p->actions) h->hands = p->hands, h->actions = p->actions, h->nactions = p->nactions;
  if (p->status != US_PLAN_FOUND || p->actions) return US_OK;
  h->verified = 1;
  return us_verify_steps(s, stab, p->order, p->nsteps, p->group_start,
                         p->group_start ? p->ngroups : p->nsteps, &h->verify, err);
}

/* Write path in the format its suffix names (.svg, .png, .html). */
static us_Status draw(const us_Structure *s, const PyPlan *pp, const char *path, const char *title,
                      int forces, us_Error *err) {
  const us_Plan *p = pp ? &pp->plan : NULL;
  us_RenderSettings r = us_render_default_settings();
  r.title = title;
  if (p) plan_order(p, &r);
  if (forces && p && p->certs) r.forces = &p->certs[0]; /* the full structure's */
  size_t n = strlen(path);
  if (n > 5 && !strcmp(path + n - 5, ".html")) {
    us_HtmlSettings h = us_html_default_settings();
    h.title = title;
    if (page(s, p, pp ? &pp->set.stability : NULL, &h, err)) return err->code;
    if (p && p->actions) r.order = NULL, r.norder = 0, r.group_start = NULL, r.ngroups = 0;
    return us_render_html(s, p ? &r : NULL, &h, path, err);
  }
  if (n > 4 && !strcmp(path + n - 4, ".png")) return us_render_png(s, &r, path, err);
  if (n > 4 && !strcmp(path + n - 4, ".svg")) return us_render_svg(s, &r, path, err);
  return us_error_set(err, US_ERR_USAGE, "%s: render writes .svg, .png or .html", path);
}

PyObject *us_py_render(PyObject *self, PyObject *args) {
  PyStructure *h;
  PyObject *plan;
  const char *path, *title = NULL;
  int forces = 0;
  (void)self;
  if (!PyArg_ParseTuple(args, "O!sO|pz", &us_py_structure_type, &h, &path, &plan, &forces, &title))
    return NULL;
  const us_Structure *s = us_py_structure(h);
  if (!s) return NULL;
  PyPlan *pp = NULL;
  if (plan != Py_None) {
    if (!PyObject_TypeCheck(plan, &us_py_plan_type)) return us_py_fail("render: plan must be a Plan");
    pp = (PyPlan *)plan;
    if (!pp->live) return us_py_fail("the plan is closed");
    if (pp->owner != h) return us_py_fail("render: the plan is of another structure");
  }
  us_Error err;
  us_error_clear(&err);
  if (draw(s, pp, path, title, forces, &err)) return us_py_raise(&err);
  Py_RETURN_NONE;
}
