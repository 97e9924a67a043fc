/* Structure.plan(**settings): the planner with the keywords of `unstack
 * plan` (the long option names, '-' as '_'), and the plan handle that keeps
 * the library's us_Plan for write() and verify(). The plan's data (status,
 * steps, actions, statistics) is copied into a dict once. */
#include "ext.h"

#include <string.h>

/* d[key] = v (stolen); -1 when v is NULL or the store fails */
static int put(PyObject *d, const char *key, PyObject *v) {
  if (!v) return -1;
  int r = PyDict_SetItemString(d, key, v);
  Py_DECREF(v);
  return r;
}

/* ------------------------------------------------------------ settings */

/* An enum keyword by its parser (0 ok); `words` lists the choices. */
static int take_enum(PyObject *kw, const char *key, int (*parse)(const char *, void *), void *out,
                     const char *words) {
  const char *w;
  PyObject *keep = NULL;
  int r = us_py_take_str(kw, key, &w, &keep);
  if (r <= 0) return r;
  r = parse(w, out) ? (us_py_fail("unknown %s '%s' (%s)", key, w, words), -1) : 0;
  Py_DECREF(keep);
  return r;
}

static int parse_search(const char *w, void *o) { return us_search_parse(w, o); }
static int parse_order(const char *w, void *o) { return us_order_parse(w, o); }
static int parse_direction(const char *w, void *o) { return us_direction_parse(w, o); }
static int parse_removal(const char *w, void *o) { return us_removal_parse(w, o); }
static int parse_rules(const char *w, void *o) { return us_rules_parse(w, o); }

/* hands= and max_group=: "auto" (0) or 1..64 */
static int take_count(PyObject *kw, const char *key, int *out) {
  PyObject *v = PyDict_GetItemString(kw, key);
  if (!v || v == Py_None) return v ? PyDict_DelItemString(kw, key) : 0;
  long n = -1;
  if (PyUnicode_Check(v) && !strcmp(PyUnicode_AsUTF8(v), "auto")) n = 0;
  else if (PyLong_Check(v) && !PyBool_Check(v)) n = PyLong_AsLong(v);
  if (PyErr_Occurred()) PyErr_Clear(), n = -1;
  if (n < 0 || n > 64) return us_py_fail("%s needs 'auto' or an integer from 1 to 64", key), -1;
  if (n == 0 && !PyUnicode_Check(v)) return us_py_fail("%s needs 'auto' or an integer from 1 to 64", key), -1;
  *out = (int)n;
  return PyDict_DelItemString(kw, key);
}

/* The plan keywords; the stability ones after (time_limit is the plan's). */
static int plan_settings(PyObject *kw, us_PlanSettings *p) {
  long seed = -1, tests = 0, exact = -1;
  int r;
  if (take_enum(kw, "search", parse_search, &p->search, "assemble, dfs, bfs, random") < 0 ||
      take_enum(kw, "order", parse_order, &p->order, "highest, lowest, input") < 0 ||
      take_enum(kw, "direction", parse_direction, &p->direction, "down, up") < 0 ||
      take_enum(kw, "removal", parse_removal, &p->removal, "any, up, free") < 0 ||
      take_enum(kw, "rules", parse_rules, &p->rules,
                "all, none, or a comma list of memo, ground, union, components, greedy") < 0 ||
      take_count(kw, "hands", &p->hands) < 0 || take_count(kw, "max_group", &p->max_group) < 0 ||
      us_py_take_double(kw, "time_limit", &p->time_limit) < 0 ||
      us_py_take_long(kw, "seed", &seed) < 0 || us_py_take_long(kw, "max_tests", &tests) < 0 ||
      (r = us_py_take_long(kw, "exact_tests", &exact)) < 0)
    return -1;
  if (r) p->max_exact_tests = exact;
  if (seed >= 0) p->seed = (unsigned long)seed;
  p->max_tests = tests;
  PyObject *c = PyDict_GetItemString(kw, "certificates");
  if (c && (p->certificates = PyObject_IsTrue(c)) < 0) return -1;
  if (c && PyDict_DelItemString(kw, "certificates") < 0) return -1;
  if (p->time_limit < 0 || exact < -1 || tests < 0)
    return us_py_fail("time_limit, max_tests and exact_tests need numbers >= 0"), -1;
  return us_py_stability_settings(kw, &p->stability);
}

/* ------------------------------------------------------------ results */

/* steps k of v as lists of ids; start NULL: one body a step */
static PyObject *steps(const us_Structure *s, const int *v, const int *start, int nsteps) {
  PyObject *l = PyList_New(nsteps);
  for (int k = 0; l && k < nsteps; k++) {
    int lo = start ? start[k] : k, hi = start ? start[k + 1] : k + 1;
    PyObject *step = PyList_New(hi - lo);
    for (int q = lo; step && q < hi; q++) PyList_SET_ITEM(step, q - lo, us_py_body_id(s, v[q]));
    if (!step) return Py_DECREF(l), NULL;
    PyList_SET_ITEM(l, k, step);
  }
  return l;
}

static PyObject *actions(const us_Structure *s, const us_Plan *p) {
  if (!p->actions) Py_RETURN_NONE;
  PyObject *l = PyList_New(p->nactions);
  for (int k = 0; l && k < p->nactions; k++)
    PyList_SET_ITEM(l, k, Py_BuildValue("(sN)", us_action_name(p->actions[k].verb),
                                        us_py_body_id(s, p->actions[k].body)));
  return l;
}

static PyObject *stats(const us_PlanStats *st) {
  PyObject *d = PyDict_New();
  if (!d || put(d, "tests", PyLong_FromLong(st->tests)) || put(d, "stable", PyLong_FromLong(st->stable)) ||
      put(d, "unstable", PyLong_FromLong(st->unstable)) ||
      put(d, "undecided", PyLong_FromLong(st->undecided)) ||
      put(d, "revisited", PyLong_FromLong(st->revisited)) ||
      put(d, "nodes_expanded", PyLong_FromLong(st->nodes_expanded)) ||
      put(d, "max_depth", PyLong_FromLong(st->max_depth)) ||
      put(d, "backtracks", PyLong_FromLong(st->backtracks)) ||
      put(d, "exact_checks", PyLong_FromLong(st->exact_checks)) ||
      put(d, "components", PyLong_FromLong(st->components)) ||
      put(d, "time_total", PyFloat_FromDouble(st->time_total)) ||
      put(d, "time_search", PyFloat_FromDouble(st->time_search)) ||
      put(d, "time_solve", PyFloat_FromDouble(st->time_solve)) ||
      put(d, "time_check", PyFloat_FromDouble(st->time_check)) ||
      put(d, "stability", us_py_stability_info(&st->stability)))
    return Py_XDECREF(d), NULL;
  return d;
}

/* Everything a Python user reads of a plan. */
static PyObject *plan_dict(const us_Structure *s, const us_Plan *p) {
  int found = p->status == US_PLAN_FOUND;
  PyObject *d = PyDict_New();
  if (!d || put(d, "status", PyUnicode_FromString(us_plan_status_name(p->status))) ||
      put(d, "order", found && !p->actions ? steps(s, p->order, p->group_start, p->group_start ? p->ngroups : p->nsteps)
                                           : PyList_New(0)) ||
      put(d, "actions", actions(s, p)) || put(d, "hands", PyLong_FromLong(p->hands)) ||
      put(d, "hands_lower", PyLong_FromLong(p->hands_lower)) ||
      put(d, "max_group", PyLong_FromLong(p->max_group)) ||
      put(d, "blocked", steps(s, p->blocked, NULL, p->blocked ? p->nblocked : 0)) ||
      put(d, "build", p->buildable && p->build_start ? steps(s, p->buildable, p->build_start, p->nbuild)
                                                     : PyList_New(0)) ||
      put(d, "note", PyUnicode_FromString(p->note)) || put(d, "stats", stats(&p->stats)))
    return Py_XDECREF(d), NULL;
  return d;
}

PyObject *us_py_plan(PyObject *self, PyObject *args, PyObject *kwargs) {
  PyStructure *h;
  (void)self;
  if (!PyArg_ParseTuple(args, "O!", &us_py_structure_type, &h)) return NULL;
  const us_Structure *s = us_py_structure(h);
  PyObject *kw = kwargs ? PyDict_Copy(kwargs) : PyDict_New();
  us_PlanSettings set = us_plan_default_settings();
  if (!s || !kw || plan_settings(kw, &set) < 0 || us_py_no_more(kw, "plan") < 0)
    return Py_XDECREF(kw), NULL;
  Py_DECREF(kw);
  PyPlan *pp = PyObject_New(PyPlan, &us_py_plan_type);
  if (!pp) return NULL;
  pp->owner = h, pp->set = set, pp->live = 0;
  Py_INCREF(h);
  us_Error err;
  us_error_clear(&err);
  us_Status st;
  h->busy++;
  Py_BEGIN_ALLOW_THREADS
  st = us_plan(s, &set, &pp->plan, &err);
  Py_END_ALLOW_THREADS
  h->busy--;
  if (st) return Py_DECREF(pp), us_py_raise(&err);
  pp->live = 1;
  PyObject *d = plan_dict(s, &pp->plan);
  if (!d) return Py_DECREF(pp), NULL;
  return Py_BuildValue("(NN)", pp, d);
}

/* ------------------------------------------------------------ methods */

/* the plan's structure, or NULL with unstack.Error set */
static const us_Structure *live(PyPlan *pp) {
  if (!pp->live) return us_py_fail("the plan is closed"), NULL;
  return us_py_structure(pp->owner);
}

static PyObject *pl_close(PyPlan *pp, PyObject *unused) {
  (void)unused;
  if (pp->live) us_plan_free(&pp->plan);
  pp->live = 0;
  Py_RETURN_NONE;
}

static PyObject *pl_write(PyPlan *pp, PyObject *args) {
  const char *path;
  const us_Structure *s = live(pp);
  if (!s || !PyArg_ParseTuple(args, "s", &path)) return NULL;
  us_Error err;
  us_error_clear(&err);
  if (us_plan_write(s, &pp->plan, &pp->set, path, &err)) return us_py_raise(&err);
  Py_RETURN_NONE;
}

static PyObject *report(const us_Structure *s, const us_VerifyReport *r) {
  PyObject *d = PyDict_New();
  if (!d || put(d, "ok", PyBool_FromLong(r->ok)) ||
      put(d, "full_unstable", PyBool_FromLong(r->full_unstable)) ||
      put(d, "failed_step", r->failed_step >= 0 ? PyLong_FromLong(r->failed_step) : (Py_INCREF(Py_None), Py_None)) ||
      put(d, "undecided", PyBool_FromLong(r->undecided)) ||
      put(d, "incomplete", PyBool_FromLong(r->incomplete)) ||
      put(d, "unstable_body", r->unstable_body >= 0 ? us_py_body_id(s, r->unstable_body) : (Py_INCREF(Py_None), Py_None)) ||
      put(d, "steps_checked", PyLong_FromLong(r->steps_checked)) ||
      put(d, "max_force_residual", PyFloat_FromDouble(r->max_force_residual)) ||
      put(d, "max_torque_residual", PyFloat_FromDouble(r->max_torque_residual)) ||
      put(d, "note", PyUnicode_FromString(r->note)))
    return Py_XDECREF(d), NULL;
  return d;
}

/* Re-check the order (or the actions) step by step with fresh tests. */
static PyObject *pl_verify(PyPlan *pp, PyObject *unused) {
  (void)unused;
  const us_Structure *s = live(pp);
  if (!s) return NULL;
  const us_Plan *p = &pp->plan;
  if (p->status != US_PLAN_FOUND)
    return us_py_fail("verify: the plan's status is %s: it has no order to check",
                      us_plan_status_name(p->status));
  us_VerifyReport rep;
  us_Error err;
  us_error_clear(&err);
  us_Status st;
  us_StabilitySettings set = pp->set.stability;
  set.skip_forces = 0;
  pp->owner->busy++;
  Py_BEGIN_ALLOW_THREADS
  st = p->actions ? us_verify_actions(s, &set, p->hands, p->actions, p->nactions, &rep, &err)
                  : us_verify_steps(s, &set, p->order, p->nsteps, p->group_start,
                                    p->group_start ? p->ngroups : p->nsteps, &rep, &err);
  Py_END_ALLOW_THREADS
  pp->owner->busy--;
  return st ? us_py_raise(&err) : report(s, &rep);
}

/* The certificate forces of every step (certificates=True), or None. */
static PyObject *pl_certificates(PyPlan *pp, PyObject *unused) {
  (void)unused;
  const us_Structure *s = live(pp);
  if (!s) return NULL;
  const us_Plan *p = &pp->plan;
  if (!p->certs) Py_RETURN_NONE;
  PyObject *l = PyList_New(p->ngroups + 1);
  for (int k = 0; l && k <= p->ngroups; k++) {
    PyObject *f = us_py_forces(s, &p->certs[k]);
    if (!f) return Py_DECREF(l), NULL;
    PyList_SET_ITEM(l, k, f);
  }
  return l;
}

static void pl_dealloc(PyPlan *pp) {
  if (pp->live) us_plan_free(&pp->plan);
  Py_XDECREF(pp->owner);
  Py_TYPE(pp)->tp_free((PyObject *)pp);
}

static PyMethodDef pl_methods[] = {
    {"close", (PyCFunction)pl_close, METH_NOARGS, "free the plan now"},
    {"write", (PyCFunction)pl_write, METH_VARARGS, "write(path): the plan file (docs/format.md)"},
    {"verify", (PyCFunction)pl_verify, METH_NOARGS, "re-check every step with fresh tests"},
    {"certificates", (PyCFunction)pl_certificates, METH_NOARGS, "forces before every step"},
    {NULL, NULL, 0, NULL}};

PyTypeObject us_py_plan_type = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "unstack._unstack.Plan",
    .tp_basicsize = sizeof(PyPlan),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "A plan owned by the library (use unstack.Plan).",
    .tp_dealloc = (destructor)pl_dealloc,
    .tp_methods = pl_methods,
};
