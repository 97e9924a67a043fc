/* The Python binding's shared declarations: the handle types (a structure,
 * a plan) and the helpers that turn library errors and settings into
 * Python exceptions and back. Only the public API (US_API) of
 * libunstack.so is used. */
#ifndef US_PY_EXT_H
#define US_PY_EXT_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "unstack/unstack.h"

/* A structure handle: owns one finalized us_Structure until close() or
 * deallocation. `busy` counts calls running with the GIL released, so that
 * close() from another thread cannot free the structure under them. */
typedef struct PyStructure {
  PyObject_HEAD
  us_Structure *s;
  int busy;
} PyStructure;

/* A plan handle: owns one us_Plan and the settings that made it, and holds
 * a reference to its structure's handle (plans name its bodies). */
typedef struct PyPlan {
  PyObject_HEAD
  PyStructure *owner;
  us_Plan plan;
  us_PlanSettings set;
  int live; /* plan holds library memory */
} PyPlan;

extern PyTypeObject us_py_structure_type;
extern PyTypeObject us_py_plan_type;

/* the exception unstack.Error (module.c) */
PyObject *us_py_error_type(void);
/* raise unstack.Error from a library error (code name and message); NULL */
PyObject *us_py_raise(const us_Error *err);
/* raise unstack.Error with a printf-style message; NULL */
PyObject *us_py_fail(const char *fmt, ...);

/* the structure of a live handle, or NULL with unstack.Error set */
const us_Structure *us_py_structure(PyStructure *h);
PyObject *us_py_structure_wrap(us_Structure *s);
/* a body's id ("ground" for US_GROUND) as a str */
PyObject *us_py_body_id(const us_Structure *s, int body);
/* a list of dim floats */
PyObject *us_py_vector(const double *v, int dim);

/* keyword settings (check.c): stability settings from method=, local=,
 * time_limit=, cert_tol=, max_pivots=; consumed keys are deleted from kw
 * (a copy); 0 or -1 with an exception set */
int us_py_stability_settings(PyObject *kw, us_StabilitySettings *set);
/* kw must be empty now: else unstack.Error naming the first unknown key */
int us_py_no_more(PyObject *kw, const char *what);
/* kw[key] as a double / long / str, when present: 1 taken, 0 absent, -1 error */
int us_py_take_double(PyObject *kw, const char *key, double *out);
int us_py_take_long(PyObject *kw, const char *key, long *out);
int us_py_take_str(PyObject *kw, const char *key, const char **out, PyObject **keep);

/* check.c: a workspace's statistics and a set of forces as Python objects */
PyObject *us_py_stability_info(const us_StabilityInfo *in);
PyObject *us_py_forces(const us_Structure *s, const us_Forces *f);

/* the module's functions */
PyObject *us_py_read(PyObject *self, PyObject *args);
PyObject *us_py_parse(PyObject *self, PyObject *args);
PyObject *us_py_read_svg(PyObject *self, PyObject *args);
PyObject *us_py_generate(PyObject *self, PyObject *args, PyObject *kw);
PyObject *us_py_check(PyObject *self, PyObject *args, PyObject *kw);
PyObject *us_py_plan(PyObject *self, PyObject *args, PyObject *kw);
PyObject *us_py_render(PyObject *self, PyObject *args);

#endif
