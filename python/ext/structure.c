/* The structure handle: reading a structure from a file or JSON text, and
 * what Python reads of it (dimension, ids, contacts, fingerprint); the
 * structure is freed by close() or when the handle is collected. */
#include "ext.h"

const us_Structure *us_py_structure(PyStructure *h) {
  if (!h->s) return us_py_fail("the structure is closed"), NULL;
  return h->s;
}

PyObject *us_py_structure_wrap(us_Structure *s) {
  PyStructure *h = PyObject_New(PyStructure, &us_py_structure_type);
  if (!h) return us_structure_free(s), NULL;
  h->s = s, h->busy = 0;
  return (PyObject *)h;
}

PyObject *us_py_body_id(const us_Structure *s, int body) {
  return PyUnicode_FromString(body < 0 ? "ground" : s->bodies[body].id);
}

PyObject *us_py_vector(const double *v, int dim) {
  PyObject *l = PyList_New(dim);
  for (int k = 0; l && k < dim; k++) {
    PyObject *x = PyFloat_FromDouble(v[k]);
    if (!x) return Py_DECREF(l), NULL;
    PyList_SET_ITEM(l, k, x);
  }
  return l;
}

/* a finished load: the handle, or unstack.Error with the library's message */
static PyObject *loaded(us_Structure *s, const us_Error *err) {
  return s ? us_py_structure_wrap(s) : us_py_raise(err);
}

PyObject *us_py_read(PyObject *self, PyObject *args) {
  const char *path;
  double tol = 0;
  (void)self;
  if (!PyArg_ParseTuple(args, "s|d", &path, &tol)) return NULL;
  us_LoadSettings set = us_load_default_settings();
  set.contact_tol = tol;
  us_Error err;
  us_error_clear(&err);
  us_Structure *s;
  Py_BEGIN_ALLOW_THREADS
  s = us_structure_read_with(path, &set, &err);
  Py_END_ALLOW_THREADS
  return loaded(s, &err);
}

PyObject *us_py_parse(PyObject *self, PyObject *args) {
  const char *text, *name;
  double tol = 0;
  (void)self;
  if (!PyArg_ParseTuple(args, "ss|d", &text, &name, &tol)) return NULL;
  us_LoadSettings set = us_load_default_settings();
  set.contact_tol = tol;
  us_Error err;
  us_error_clear(&err);
  us_Structure *s = us_structure_parse_with(text, name, &set, &err);
  return loaded(s, &err);
}

PyObject *us_py_read_svg(PyObject *self, PyObject *args) {
  const char *path;
  double friction = -1, scale = 1;
  int ground = 1;
  (void)self;
  if (!PyArg_ParseTuple(args, "s|ddp", &path, &friction, &scale, &ground)) return NULL;
  us_SvgSettings set = us_svg_default_settings();
  set.friction = friction, set.scale = scale, set.ground = ground;
  us_Error err;
  us_error_clear(&err);
  us_Structure *s;
  Py_BEGIN_ALLOW_THREADS
  s = us_structure_read_svg(path, &set, NULL, &err);
  Py_END_ALLOW_THREADS
  return loaded(s, &err);
}

/* ------------------------------------------------------------ methods */

static PyObject *st_close(PyStructure *h, PyObject *unused) {
  (void)unused;
  if (h->busy) return us_py_fail("the structure is in use by another thread");
  us_structure_free(h->s);
  h->s = NULL;
  Py_RETURN_NONE;
}

static PyObject *st_write(PyStructure *h, PyObject *args) {
  const char *path;
  const us_Structure *s = us_py_structure(h);
  if (!s || !PyArg_ParseTuple(args, "s", &path)) return NULL;
  us_Error err;
  us_error_clear(&err);
  if (us_structure_write(s, path, &err)) return us_py_raise(&err);
  Py_RETURN_NONE;
}

static PyObject *st_ids(PyStructure *h, void *unused) {
  (void)unused;
  const us_Structure *s = us_py_structure(h);
  PyObject *l = s ? PyList_New(s->nbody) : NULL;
  for (int k = 0; l && k < s->nbody; k++) {
    PyObject *id = us_py_body_id(s, k);
    if (!id) return Py_DECREF(l), NULL;
    PyList_SET_ITEM(l, k, id);
  }
  return l;
}

/* ids of the fixed bodies (never removed) */
static PyObject *st_fixed(PyStructure *h, void *unused) {
  (void)unused;
  const us_Structure *s = us_py_structure(h);
  PyObject *l = s ? PyList_New(0) : NULL;
  for (int k = 0; l && k < s->nbody; k++) {
    if (!s->bodies[k].fixed) continue;
    PyObject *id = us_py_body_id(s, k);
    if (!id || PyList_Append(l, id) < 0) return Py_XDECREF(id), Py_DECREF(l), NULL;
    Py_DECREF(id);
  }
  return l;
}

/* One body as a dict: id, fixed, mass (movable bodies), centre of mass. */
static PyObject *body_dict(const us_Structure *s, int k) {
  const us_Body *b = &s->bodies[k];
  PyObject *mass = b->fixed ? (Py_INCREF(Py_None), Py_None) : PyFloat_FromDouble(b->mass);
  return Py_BuildValue("{s:N,s:O,s:N,s:N}", "id", us_py_body_id(s, k), "fixed",
                       b->fixed ? Py_True : Py_False, "mass", mass, "com",
                       us_py_vector(b->com, s->dim));
}

/* One contact: its bodies, point, normal (from a into b) and coefficient. */
static PyObject *contact_dict(const us_Structure *s, int k) {
  const us_Contact *c = &s->contacts[k];
  return Py_BuildValue("{s:N,s:N,s:N,s:N,s:d}", "a", us_py_body_id(s, c->a), "b",
                       us_py_body_id(s, c->b), "point", us_py_vector(c->p, s->dim), "normal",
                       us_py_vector(c->n, s->dim), "mu", c->mu);
}

/* A list of n dicts made by one of the two above. */
static PyObject *dict_list(PyStructure *h, int contacts) {
  const us_Structure *s = us_py_structure(h);
  int n = s ? (contacts ? s->ncontact : s->nbody) : 0;
  PyObject *l = s ? PyList_New(n) : NULL;
  for (int k = 0; l && k < n; k++) {
    PyObject *d = contacts ? contact_dict(s, k) : body_dict(s, k);
    if (!d) return Py_DECREF(l), NULL;
    PyList_SET_ITEM(l, k, d);
  }
  return l;
}

static PyObject *st_bodies(PyStructure *h, void *unused) {
  (void)unused;
  return dict_list(h, 0);
}

static PyObject *st_contacts(PyStructure *h, void *unused) {
  (void)unused;
  return dict_list(h, 1);
}

static PyObject *st_dim(PyStructure *h, void *unused) {
  (void)unused;
  const us_Structure *s = us_py_structure(h);
  return s ? PyLong_FromLong(s->dim) : NULL;
}

static PyObject *st_ncontact(PyStructure *h, void *unused) {
  (void)unused;
  const us_Structure *s = us_py_structure(h);
  return s ? PyLong_FromLong(s->ncontact) : NULL;
}

static PyObject *st_closed(PyStructure *h, void *unused) {
  (void)unused;
  return PyBool_FromLong(h->s == NULL);
}

static PyObject *st_fingerprint(PyStructure *h, void *unused) {
  (void)unused;
  const us_Structure *s = us_py_structure(h);
  uint64_t fp;
  us_Error err;
  us_error_clear(&err);
  if (!s) return NULL;
  if (us_structure_fingerprint(s, &fp, &err)) return us_py_raise(&err);
  char text[US_FINGERPRINT_CHARS];
  us_fingerprint_text(fp, text);
  return PyUnicode_FromString(text);
}

static Py_ssize_t st_len(PyStructure *h) {
  const us_Structure *s = us_py_structure(h);
  return s ? s->nbody : -1;
}

static void st_dealloc(PyStructure *h) {
  us_structure_free(h->s); /* never busy here: a running call holds a reference */
  Py_TYPE(h)->tp_free((PyObject *)h);
}

static PyMethodDef st_methods[] = {
    {"close", (PyCFunction)st_close, METH_NOARGS, "free the structure now"},
    {"write", (PyCFunction)st_write, METH_VARARGS, "write(path): the structure file, atomically"},
    {NULL, NULL, 0, NULL}};

static PyGetSetDef st_getset[] = {
    {"ids", (getter)st_ids, NULL, "body ids in file order", NULL},
    {"fixed", (getter)st_fixed, NULL, "ids of the fixed bodies", NULL},
    {"dim", (getter)st_dim, NULL, "2 or 3", NULL},
    {"bodies", (getter)st_bodies, NULL, "bodies: id, fixed, mass, com", NULL},
    {"contacts", (getter)st_contacts, NULL, "contacts: a, b, point, normal, mu", NULL},
    {"ncontacts", (getter)st_ncontact, NULL, "number of contacts", NULL},
    {"closed", (getter)st_closed, NULL, "close() was called", NULL},
    {"fingerprint", (getter)st_fingerprint, NULL, "fnv1a64:... as in plan files", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PySequenceMethods st_sequence = {.sq_length = (lenfunc)st_len};

PyTypeObject us_py_structure_type = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "unstack._unstack.Structure",
    .tp_basicsize = sizeof(PyStructure),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "A finalized structure owned by the library (use unstack.Structure).",
    .tp_dealloc = (destructor)st_dealloc,
    .tp_methods = st_methods,
    .tp_getset = st_getset,
    .tp_as_sequence = &st_sequence,
};
