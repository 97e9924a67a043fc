/* Structure.check(**settings): one stability test of the whole structure,
 * returned as a dict (verdict, the certificate forces per contact when
 * stable, the mechanism when unstable), and the stability keywords shared
 * with plan (method=, local=, time_limit=, cert_tol=, max_pivots=). */
#include "ext.h"

#include <string.h>

/* local=: None (default), True/"on", False/"off" */
static int take_local(PyObject *kw, int *local) {
  PyObject *v = PyDict_GetItemString(kw, "local");
  if (!v) return 0;
  if (PyBool_Check(v)) *local = v == Py_True ? 1 : -1;
  else if (PyUnicode_Check(v) && !strcmp(PyUnicode_AsUTF8(v), "on")) *local = 1;
  else if (PyUnicode_Check(v) && !strcmp(PyUnicode_AsUTF8(v), "off")) *local = -1;
  else if (v != Py_None) return us_py_fail("local takes on or off (or True, False)"), -1;
  return PyDict_DelItemString(kw, "local");
}

int us_py_stability_settings(PyObject *kw, us_StabilitySettings *set) {
  const char *name = NULL;
  PyObject *keep = NULL;
  long pivots = 0;
  int r = us_py_take_str(kw, "method", &name, &keep);
  if (r < 0) return -1;
  if (r && us_method_parse(name, &set->method)) {
    us_py_fail("unknown method '%s' (auto, lp, lpsolve, lcp, lcp-reuse, lp-lcp)", name);
    return Py_DECREF(keep), -1;
  }
  Py_XDECREF(keep);
  if (take_local(kw, &set->local) < 0 || us_py_take_double(kw, "cert_tol", &set->cert_tol) < 0 ||
      us_py_take_double(kw, "time_limit", &set->time_limit) < 0)
    return -1;
  if ((r = us_py_take_long(kw, "max_pivots", &pivots)) < 0) return -1;
  if (r) set->max_pivots = pivots > 1000000000L ? 1000000000 : (int)pivots;
  if (!(set->cert_tol > 0)) return us_py_fail("cert_tol needs a positive number"), -1;
  if (set->time_limit < 0) return us_py_fail("time_limit needs a number >= 0"), -1;
  return 0;
}

/* d[key] = v (stolen); -1 when v is NULL or the store fails */
static int put(PyObject *d, const char *key, PyObject *v) {
  if (!v) return -1;
  int r = PyDict_SetItemString(d, key, v);
  Py_DECREF(v);
  return r;
}

PyObject *us_py_stability_info(const us_StabilityInfo *in) {
  PyObject *d = PyDict_New();
  if (!d || put(d, "tests", PyLong_FromLong(in->tests)) || put(d, "pivots", PyLong_FromLong(in->pivots)) ||
      put(d, "lp_fallbacks", PyLong_FromLong(in->lp_fallbacks)) ||
      put(d, "reused", PyLong_FromLong(in->reused)) ||
      put(d, "solve_time", PyFloat_FromDouble(in->solve_time)) ||
      put(d, "check_time", PyFloat_FromDouble(in->check_time)) ||
      put(d, "local_stable", PyLong_FromLong(in->local_stable)) ||
      put(d, "local_unstable", PyLong_FromLong(in->local_unstable)) ||
      put(d, "local_global", PyLong_FromLong(in->local_global)) ||
      put(d, "local_global_part", PyLong_FromLong(in->local_global_part)) ||
      put(d, "local_global_sparse", PyLong_FromLong(in->local_global_sparse)) ||
      put(d, "local_plumb", PyLong_FromLong(in->local_plumb)) ||
      put(d, "timed_out", PyLong_FromLong(in->timed_out)))
    return Py_XDECREF(d), NULL;
  return d;
}

/* One certificate force: the contact, its bodies and frame, and the force. */
static PyObject *one_force(const us_Structure *s, const us_Forces *f, int k) {
  const us_Contact *c = &s->contacts[f->contact[k]];
  int dim = s->dim;
  const double *v = f->f + dim * k;
  double fric[3] = {0, 0, 0};
  for (int t = 0; t + 1 < dim; t++)
    for (int i = 0; i < 3; i++) fric[i] += v[1 + t] * c->t[t][i];
  PyObject *d = PyDict_New();
  if (!d || put(d, "contact", PyLong_FromLong(f->contact[k])) ||
      put(d, "a", us_py_body_id(s, c->a)) || put(d, "b", us_py_body_id(s, c->b)) ||
      put(d, "point", us_py_vector(c->p, dim)) || put(d, "normal", us_py_vector(c->n, dim)) ||
      put(d, "normal_force", PyFloat_FromDouble(v[0])) ||
      put(d, "tangential", us_py_vector(v + 1, dim - 1)) || put(d, "friction", us_py_vector(fric, dim)))
    return Py_XDECREF(d), NULL;
  return d;
}

PyObject *us_py_forces(const us_Structure *s, const us_Forces *f) {
  PyObject *l = PyList_New(f->ncontact);
  for (int k = 0; l && k < f->ncontact; k++) {
    PyObject *one = one_force(s, f, k);
    if (!one) return Py_DECREF(l), NULL;
    PyList_SET_ITEM(l, k, one);
  }
  return l;
}

/* The moving bodies and their velocities, or None. */
static PyObject *mechanism(const us_Structure *s, const us_Mechanism *m) {
  if (m->nbody == 0) Py_RETURN_NONE;
  int w = s->dim == 3 ? 6 : 3;
  PyObject *ids = PyList_New(m->nbody), *vel = PyList_New(m->nbody), *d = PyDict_New();
  for (int k = 0; ids && vel && k < m->nbody; k++) {
    PyList_SET_ITEM(ids, k, us_py_body_id(s, m->body[k]));
    PyList_SET_ITEM(vel, k, us_py_vector(m->v + w * k, w));
  }
  if (!d || !ids || !vel || put(d, "bodies", ids) || put(d, "velocities", vel) ||
      put(d, "ok", PyBool_FromLong(m->ok)) || put(d, "worst_power", PyFloat_FromDouble(m->worst_power)))
    return Py_XDECREF(d), NULL; /* ids and vel were stolen or are NULL */
  return d;
}

static PyObject *certificate(const us_CertCheck *c) {
  PyObject *d = PyDict_New();
  if (!d || put(d, "ok", PyBool_FromLong(c->ok)) ||
      put(d, "max_force_residual", PyFloat_FromDouble(c->max_force_residual)) ||
      put(d, "max_torque_residual", PyFloat_FromDouble(c->max_torque_residual)) ||
      put(d, "max_cone_violation", PyFloat_FromDouble(c->max_cone_violation)) ||
      put(d, "max_sign_violation", PyFloat_FromDouble(c->max_sign_violation)))
    return Py_XDECREF(d), NULL;
  return d;
}

/* The result of one test as a dict. */
static PyObject *result(const us_Structure *s, const us_StabilityResult *res, const us_Stability *w,
                        us_Method method) {
  int stable = res->verdict == US_STABLE;
  PyObject *d = PyDict_New();
  PyObject *forces = stable ? us_py_forces(s, &res->forces) : (Py_INCREF(Py_None), Py_None);
  PyObject *body = res->unstable_body >= 0 ? us_py_body_id(s, res->unstable_body)
                                           : (Py_INCREF(Py_None), Py_None);
  if (!d || put(d, "verdict", PyUnicode_FromString(us_verdict_name(res->verdict))) ||
      put(d, "forces", forces) || put(d, "unstable_body", body) ||
      put(d, "certificate", stable ? certificate(&res->check) : (Py_INCREF(Py_None), Py_None)) ||
      put(d, "mechanism", stable ? (Py_INCREF(Py_None), Py_None) : mechanism(s, &res->mechanism)) ||
      put(d, "note", PyUnicode_FromString(res->note)) ||
      put(d, "method", PyUnicode_FromString(us_method_name(us_method_resolve(method, s)))) ||
      put(d, "stats", us_py_stability_info(us_stability_info(w))))
    return Py_XDECREF(d), NULL;
  return d;
}

PyObject *us_py_check(PyObject *self, PyObject *args, PyObject *kwargs) {
  PyStructure *h;
  (void)self;
  if (!PyArg_ParseTuple(args, "O!", &us_py_structure_type, &h)) return NULL;
  const us_Structure *s = us_py_structure(h);
  PyObject *kw = kwargs ? PyDict_Copy(kwargs) : PyDict_New();
  us_StabilitySettings set = us_stability_default_settings();
  if (!s || !kw || us_py_stability_settings(kw, &set) < 0 || us_py_no_more(kw, "check") < 0)
    return Py_XDECREF(kw), NULL;
  Py_DECREF(kw);
  us_Error err;
  us_error_clear(&err);
  us_StabilityResult res;
  us_stability_result_init(&res);
  us_Status st = US_OK;
  h->busy++;
  us_Stability *w;
  Py_BEGIN_ALLOW_THREADS
  w = us_stability_new(s, &set, &err);
  st = w ? us_stability_test_full(w, &res, &err) : err.code;
  Py_END_ALLOW_THREADS
  h->busy--;
  PyObject *out = st ? us_py_raise(&err) : result(s, &res, w, set.method);
  us_stability_result_free(&res);
  us_stability_free(w);
  return out;
}
