/* unstack.generate(kind, **params): the generators of `unstack generate`
 * with the same parameters (the long option names, '-' as '_') and the
 * same kind-specific defaults and checks as tools/cmd_generate.c. */
#include "ext.h"

#include <stddef.h>
#include <string.h>

typedef us_GenFn GenFn;

/* What a parameter holds: an int >= 1, an int >= 0, a real, a seed, a flag. */
typedef enum { P_POS, P_NONNEG, P_REAL, P_SEED, P_FLAG } ParamKind;

static const struct {
  const char *name;
  ParamKind kind;
  size_t off; /* into us_GenSettings */
} params[] = {
    {"blocks", P_POS, offsetof(us_GenSettings, n)},
    {"rows", P_POS, offsetof(us_GenSettings, rows)},
    {"cols", P_POS, offsetof(us_GenSettings, cols)},
    {"voussoirs", P_POS, offsetof(us_GenSettings, n)},
    {"courses", P_POS, offsetof(us_GenSettings, n)},
    {"segments", P_POS, offsetof(us_GenSettings, segments)},
    {"levels", P_POS, offsetof(us_GenSettings, n)},
    {"loose", P_POS, offsetof(us_GenSettings, loose)},
    {"radius", P_REAL, offsetof(us_GenSettings, radius)},
    {"thickness", P_REAL, offsetof(us_GenSettings, thickness)},
    {"oculus", P_REAL, offsetof(us_GenSettings, oculus)},
    {"cap", P_FLAG, offsetof(us_GenSettings, cap)},
    {"chamfer", P_REAL, offsetof(us_GenSettings, chamfer)},
    {"returns", P_NONNEG, offsetof(us_GenSettings, returns)},
    {"jitter", P_REAL, offsetof(us_GenSettings, jitter)},
    {"seed", P_SEED, offsetof(us_GenSettings, seed)},
    {"block_width", P_REAL, offsetof(us_GenSettings, width)},
    {"block_height", P_REAL, offsetof(us_GenSettings, height)},
    {"block_depth", P_REAL, offsetof(us_GenSettings, depth)},
    {"friction", P_REAL, offsetof(us_GenSettings, friction)},
    {"density", P_REAL, offsetof(us_GenSettings, density)},
    {"max_tries", P_POS, offsetof(us_GenSettings, max_tries)},
};
#define NPARAMS ((int)(sizeof params / sizeof params[0]))

/* What the table does not hold: which defaults were overridden. */
typedef struct Extra {
  double width;      /* width=, 0 when not given */
  double time_limit; /* seconds, 0: none */
  int rows_given, height_given, tries_given, returns_given;
  int *remove;       /* jenga pairs (level, position), PyMem */
  int nremove;
} Extra;

static int set_int(us_GenSettings *g, int k, long v) {
  long least = params[k].kind == P_POS ? 1 : 0;
  if (v < least || v > 1000000000L)
    return us_py_fail("generate: %s needs an integer >= %ld, got %ld", params[k].name, least, v),
           -1;
  *(int *)((char *)g + params[k].off) = (int)v;
  return 0;
}

/* A flag parameter (cap=): any truth value. */
static int take_flag(PyObject *kw, const char *key, int *out) {
  PyObject *o = PyDict_GetItemString(kw, key);
  if (!o) return 0;
  int r = PyObject_IsTrue(o);
  if (r < 0) return -1;
  *out = r;
  return PyDict_DelItemString(kw, key) < 0 ? -1 : 1;
}

/* An integer parameter: a count (checked) or the seed. */
static int store_long(us_GenSettings *g, int k, long v) {
  if (params[k].kind != P_SEED) return set_int(g, k, v);
  if (v < 0) return us_py_fail("generate: seed needs an integer >= 0"), -1;
  *(unsigned long *)((char *)g + params[k].off) = (unsigned long)v;
  return 0;
}

/* One table parameter from kw, when given; remembers which defaults the
 * kind-specific rules must not apply. */
static int take_param(PyObject *kw, int k, us_GenSettings *g, Extra *x) {
  const char *name = params[k].name;
  void *field = (char *)g + params[k].off;
  long v = 0;
  int r = params[k].kind == P_FLAG   ? take_flag(kw, name, field)
          : params[k].kind == P_REAL ? us_py_take_double(kw, name, field)
                                     : us_py_take_long(kw, name, &v);
  if (r <= 0) return r;
  x->rows_given |= !strcmp(name, "rows");
  x->height_given |= !strcmp(name, "block_height");
  x->tries_given |= !strcmp(name, "max_tries");
  x->returns_given |= !strcmp(name, "returns");
  return params[k].kind == P_FLAG || params[k].kind == P_REAL ? 0 : store_long(g, k, v);
}

/* remove=[(level, position), ...]: jenga pieces left out. */
static int take_remove(PyObject *kw, Extra *x) {
  PyObject *o = PyDict_GetItemString(kw, "remove");
  if (!o) return 0;
  PyObject *seq = PySequence_Fast(o, "generate: remove needs a list of (level, position) pairs");
  if (!seq) return PyErr_Clear(), us_py_fail("generate: remove needs a list of (level, position) pairs"), -1;
  Py_ssize_t n = PySequence_Fast_GET_SIZE(seq);
  x->remove = PyMem_Calloc((size_t)n + 1, 2 * sizeof(int));
  for (Py_ssize_t k = 0; x->remove && k < n; k++) {
    long lv = -1, pos = -1;
    PyObject *pair = PySequence_Fast_GET_ITEM(seq, k);
    if (!PyArg_ParseTuple(pair, "ll", &lv, &pos)) PyErr_Clear();
    if (lv < 1 || lv > 1000000000L || pos < 1 || pos > 3) {
      Py_DECREF(seq);
      return us_py_fail("generate: remove needs (level, position) pairs, levels from 1, positions "
                        "1..3"), -1;
    }
    x->remove[2 * k] = (int)lv, x->remove[2 * k + 1] = (int)pos;
  }
  Py_DECREF(seq);
  if (!x->remove) return PyErr_NoMemory(), -1;
  x->nremove = (int)n;
  return PyDict_DelItemString(kw, "remove");
}

static int take_all(PyObject *kw, us_GenSettings *g, Extra *x) {
  for (int k = 0; k < NPARAMS; k++)
    if (take_param(kw, k, g, x) < 0) return -1;
  int w = us_py_take_double(kw, "width", &x->width);
  if (w < 0 || us_py_take_double(kw, "time_limit", &x->time_limit) < 0 || take_remove(kw, x) < 0)
    return -1;
  if (w && !(x->width > 0)) return us_py_fail("generate: width needs a positive number"), -1;
  return us_py_no_more(kw, "generate");
}

/* Kind-specific defaults and checks (us_gen_settle, as the CLI's); 0 or
 * -1 with the exception set. */
static int settle(GenFn fn, us_GenSettings *g, const Extra *x) {
  us_GenGiven given = {x->width, x->height_given, x->tries_given, x->returns_given,
                       x->remove != NULL};
  switch (us_gen_settle(fn, g, &given)) {
  case US_GEN_FITS: return 0;
  case US_GEN_REMOVE_NOT_JENGA: return us_py_fail("generate: remove is for jenga"), -1;
  case US_GEN_RETURNS_NOT_WALL3D: return us_py_fail("generate: returns is for wall3d"), -1;
  case US_GEN_BLOCK_WIDTH_FIXED:
    return us_py_fail("generate: block widths are fixed for random, stacker and random3d; set "
                      "the structure width with width="), -1;
  case US_GEN_WIDTH_NOT_RANDOM: break;
  }
  return us_py_fail("generate: width is for random, stacker and random3d (structure width in "
                    "blocks); use block_width"), -1;
}

static GenFn find_kind(const char *kind) {
  char list[256] = "";
  size_t len = 0;
  GenFn fn = us_gen_find(kind);
  if (fn) return fn;
  for (int k = 0; us_gen_kind(k); k++)
    len += (size_t)snprintf(list + len, sizeof list - len, "%s%s", k ? ", " : "", us_gen_kind(k));
  us_py_fail("generate: unknown kind '%s' (%s)", kind, list);
  return NULL;
}

/* Run the generator with the GIL released. */
static PyObject *run(GenFn fn, us_GenSettings *g, double time_limit) {
  us_Error err;
  us_error_clear(&err);
  us_Structure *s;
  Py_BEGIN_ALLOW_THREADS
  g->deadline = time_limit > 0 ? us_now() + time_limit : 0;
  s = fn(g, &err);
  Py_END_ALLOW_THREADS
  return s ? us_py_structure_wrap(s) : us_py_raise(&err);
}

PyObject *us_py_generate(PyObject *self, PyObject *args, PyObject *kwargs) {
  const char *kind;
  (void)self;
  if (!PyArg_ParseTuple(args, "s", &kind)) return NULL;
  GenFn fn = find_kind(kind);
  if (!fn) return NULL;
  us_GenSettings g = us_gen_default_settings();
  int default_rows = g.rows;
  Extra x;
  memset(&x, 0, sizeof x);
  PyObject *kw = kwargs ? PyDict_Copy(kwargs) : PyDict_New();
  PyObject *out = NULL;
  if (kw && take_all(kw, &g, &x) == 0) {
    if ((fn == us_gen_pyramid || fn == us_gen_pyramid3d) && x.rows_given) g.n = g.rows;
    if (!x.rows_given) g.rows = default_rows;
    g.remove = x.remove, g.nremove = x.nremove;
    if (settle(fn, &g, &x) == 0) out = run(fn, &g, x.time_limit);
  }
  Py_XDECREF(kw);
  PyMem_Free(x.remove);
  return out;
}
