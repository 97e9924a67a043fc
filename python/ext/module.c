/* The module unstack._unstack: the exception type, the keyword helpers
 * shared by check, plan and generate, and the function table. The Python
 * package (python/unstack/__init__.py) wraps it in classes. */
#include "ext.h"

#include <stdarg.h>
#include <string.h>

/* The exception type lives in the module object; this pointer is set once at
 * import (the interpreter owns it, as every extension's types). */
static PyObject *error_type;

PyObject *us_py_error_type(void) { return error_type; }

/* .code of an error: a short word per us_Status */
static const char *code_word(us_Status st) {
  static const char *const words[US_ERR_COUNT] = {"ok",    "usage",  "io",    "parse",
                                                  "input", "nomem", "solver", "time_limit"};
  return st >= 0 && st < US_ERR_COUNT && words[st] ? words[st] : "error";
}

PyObject *us_py_raise(const us_Error *err) {
  /* the library's message as it is; the status name as .code */
  PyObject *exc = PyObject_CallFunction(error_type, "s", err->msg[0] ? err->msg : "error");
  if (!exc) return NULL;
  PyObject *code = PyUnicode_FromString(code_word(err->code));
  if (code) PyObject_SetAttrString(exc, "code", code);
  Py_XDECREF(code);
  PyErr_SetObject(error_type, exc);
  Py_DECREF(exc);
  return NULL;
}

PyObject *us_py_fail(const char *fmt, ...) {
  us_Error err;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err.msg, sizeof err.msg, fmt, ap);
  va_end(ap);
  err.code = US_ERR_USAGE;
  return us_py_raise(&err);
}

int us_py_no_more(PyObject *kw, const char *what) {
  PyObject *key;
  PyObject *val;
  Py_ssize_t pos = 0;
  if (!kw || !PyDict_Next(kw, &pos, &key, &val)) return 0;
  us_py_fail("%s: unknown parameter '%s'", what, PyUnicode_Check(key) ? PyUnicode_AsUTF8(key) : "?");
  return -1;
}

/* kw[key] (new reference) removed from kw, or NULL when absent */
static PyObject *take(PyObject *kw, const char *key) {
  PyObject *v = kw ? PyDict_GetItemString(kw, key) : NULL;
  if (!v || v == Py_None) {
    if (v) PyDict_DelItemString(kw, key);
    return NULL;
  }
  Py_INCREF(v);
  PyDict_DelItemString(kw, key);
  return v;
}

int us_py_take_double(PyObject *kw, const char *key, double *out) {
  PyObject *v = take(kw, key);
  if (!v) return 0;
  double d = PyFloat_AsDouble(v);
  int bad = PyErr_Occurred() != NULL || PyBool_Check(v);
  Py_DECREF(v);
  if (bad) return PyErr_Clear(), us_py_fail("%s needs a number", key), -1;
  return *out = d, 1;
}

int us_py_take_long(PyObject *kw, const char *key, long *out) {
  PyObject *v = take(kw, key);
  if (!v) return 0;
  long n = PyLong_Check(v) ? PyLong_AsLong(v) : -1;
  int bad = !PyLong_Check(v) || PyBool_Check(v) || PyErr_Occurred() != NULL;
  Py_DECREF(v);
  if (bad) return PyErr_Clear(), us_py_fail("%s needs an integer", key), -1;
  return *out = n, 1;
}

int us_py_take_str(PyObject *kw, const char *key, const char **out, PyObject **keep) {
  PyObject *v = take(kw, key);
  if (!v) return 0;
  if (!PyUnicode_Check(v)) return Py_DECREF(v), us_py_fail("%s needs a string", key), -1;
  *out = PyUnicode_AsUTF8(v);
  if (!*out) return Py_DECREF(v), -1;
  return *keep = v, 1;
}

static PyObject *alloc_live(PyObject *self, PyObject *unused) {
  (void)self, (void)unused;
  return PyLong_FromLong(us_alloc_live());
}

/* the library's out-of-memory hook, for the tests' sweeps: after n more
 * allocations of this thread every one fails; n < 0 turns it off */
static PyObject *alloc_fail_after(PyObject *self, PyObject *arg) {
  (void)self;
  long n = PyLong_AsLong(arg);
  if (n == -1 && PyErr_Occurred()) return NULL;
  return PyLong_FromLong(us_alloc_fail_after(n));
}

static PyMethodDef functions[] = {
    {"read", us_py_read, METH_VARARGS, "read(path, contact_tol) -> structure handle"},
    {"parse", us_py_parse, METH_VARARGS, "parse(text, name, contact_tol) -> structure handle"},
    {"read_svg", us_py_read_svg, METH_VARARGS,
     "read_svg(path, friction, scale, ground) -> structure handle"},
    {"generate", (PyCFunction)(void (*)(void))us_py_generate, METH_VARARGS | METH_KEYWORDS,
     "generate(kind, **params) -> structure handle"},
    {"check", (PyCFunction)(void (*)(void))us_py_check, METH_VARARGS | METH_KEYWORDS,
     "check(structure, **settings) -> dict"},
    {"plan", (PyCFunction)(void (*)(void))us_py_plan, METH_VARARGS | METH_KEYWORDS,
     "plan(structure, **settings) -> plan handle"},
    {"render", us_py_render, METH_VARARGS,
     "render(structure, path, plan, forces, title): .svg, .png or .html"},
    {"alloc_live", alloc_live, METH_NOARGS, "the library's live allocations (leak checks)"},
    {"alloc_fail_after", alloc_fail_after, METH_O, "fail the library's allocations after n more"},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "unstack._unstack",
                                    "The C binding of libunstack.", -1, functions,
                                    NULL, NULL, NULL, NULL};

PyMODINIT_FUNC PyInit__unstack(void);
PyMODINIT_FUNC PyInit__unstack(void) {
  if (PyType_Ready(&us_py_structure_type) < 0 || PyType_Ready(&us_py_plan_type) < 0) return NULL;
  PyObject *m = PyModule_Create(&module);
  if (!m) return NULL;
  error_type = PyErr_NewExceptionWithDoc("unstack.Error",
                                         "An error of the unstack library: its message, and .code "
                                         "(usage, io, parse, input, nomem, solver, time_limit).",
                                         NULL, NULL);
  if (!error_type || PyModule_AddObjectRef(m, "Error", error_type) < 0 ||
      PyModule_AddObjectRef(m, "Structure", (PyObject *)&us_py_structure_type) < 0 ||
      PyModule_AddObjectRef(m, "Plan", (PyObject *)&us_py_plan_type) < 0 ||
      PyModule_AddStringConstant(m, "version", US_VERSION) < 0) {
    Py_DECREF(m);
    return NULL;
  }
  return m;
}
