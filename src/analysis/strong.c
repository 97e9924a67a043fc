/* Strong stability with friction: the driver that builds the model
 * (strong_model.c), asks the MIP (module cbc, strong_mip.c) or the
 * exhaustive mode search (strong_enum.c), and turns a normalized solution
 * into a witness motion that must pass the independent check
 * (strong_check.c) before "no" is reported.
 *
 * Definitions (docs/classify.md): weakly stable, some solution of the
 * contact dynamics at rest has zero accelerations (the statics LP);
 * strongly stable, every one has. A structure that is not weakly stable is
 * not strongly stable. Friction is static Coulomb: a closed contact that
 * slips carries mu f_n against the slip, one that sticks carries any force
 * in the cone. Answers: yes only from a finished search (every contact-mode
 * pattern covered, or the MIP's proven bound at most tol); no only with a
 * checked witness (or the weak test's checked "unstable"); otherwise
 * undecided. */
#include "strong.h"

#include "model/massprops.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

us_StrongSettings us_strong_default_settings(void) {
  us_StrongSettings s = {US_STRONG_AUTO, 100000, 10.0, 1e-6};
  return s;
}

void us_strong_result_free(us_StrongResult *r) {
  if (!r) return;
  us_free(r->body);
  us_free(r->accel);
  us_free(r->contact);
  us_free(r->force);
  us_free(r->mode);
  memset(r, 0, sizeof *r);
}

int us_strong_witness(const us_StrongModel *m, const double *x, us_StrongResult *out) {
  const us_EqSystem *e = &m->e;
  double sc = x[m->nv - 1], g = us_gravity_norm(e->s->gravity);
  if (!(sc > 0)) return 1;
  size_t nb = (size_t)(e->nbody ? e->nbody : 1), nc = (size_t)(m->nc ? m->nc : 1);
  size_t nw = (size_t)e->nw, dim = (size_t)m->dim;
  out->body = us_malloc(nb * sizeof(int));
  out->accel = us_malloc(nw * nb * sizeof(double));
  out->contact = us_malloc(nc * sizeof(int));
  out->force = us_malloc(dim * nc * sizeof(double));
  out->mode = us_malloc(nc * sizeof(us_ContactMode));
  if (!out->body || !out->accel || !out->contact || !out->force || !out->mode) return -1;
  out->nbody = e->nbody, out->ncontact = m->nc, out->has_witness = 1, out->dim = m->dim;
  for (int i = 0; i < e->nbody; i++) {
    out->body[i] = e->body[i];
    for (int k = 0; k < e->nw; k++) /* the first dim are linear, the rest angular */
      out->accel[e->nw * i + k] = x[e->nw * i + k] / sc * g / (k < m->dim ? 1 : e->length_scale);
  }
  static const int f2[2] = {SV_FN, SV_FT}, f3[3] = {SV3_FN, SV3_FT1, SV3_FT2};
  for (int c = 0; c < m->nc; c++) {
    int mode = us_strong_mode_of(m, x, c, 1e-9);
    out->contact[c] = e->contact[c];
    for (int k = 0; k < m->dim; k++)
      out->force[m->dim * c + k] = x[us_sv(m, c, m->dim == 2 ? f2[k] : f3[k])] / sc * e->force_scale;
    /* 3D: every slide is reported as "slides" (its direction is the slip's) */
    if (m->dim == 3 && mode > US_MODE_SLIDES_POS) mode = US_MODE_SLIDES_POS;
    out->mode[c] = (us_ContactMode)(mode < 0 ? US_MODE_STICKS : mode);
  }
  return 0;
}

/* The weak verdict of `present` with the default backend: US_STABLE,
 * US_UNSTABLE (checked) or US_UNDECIDED; errors through *st. */
static us_Verdict weak_verdict(const us_Structure *s, const us_Bitset *present, double deadline,
                               us_Status *st, us_Error *err) {
  us_StabilitySettings set = us_stability_default_settings();
  us_Stability *w = us_stability_new(s, &set, err);
  us_StabilityResult res;
  us_stability_result_init(&res);
  us_Verdict v = US_UNDECIDED;
  *st = w ? US_OK : (err ? err->code : US_ERR_NOMEM);
  if (w) us_stability_set_deadline(w, deadline);
  if (w) *st = present ? us_stability_test(w, present, &res, err) : us_stability_test_full(w, &res, err);
  if (w && *st == US_OK) v = res.verdict;
  us_stability_result_free(&res);
  us_stability_free(w);
  return v;
}

/* Run the chosen solver on the model; x receives a witness for "no". */
static us_Status search(const us_StrongModel *m, const us_StrongSettings *set, double deadline,
                        double *x, us_StrongResult *out, us_Error *err) {
  if (set->method != US_STRONG_ENUM && m->dim == 2) { /* 3D: the mode search only */
    us_Error lerr = {0};
    const us_CbcModule *api = us_cbc_module_api(&lerr);
    if (api) {
      out->method = US_STRONG_MIP;
      return api->solve(m, set, deadline, x, out, err);
    }
    if (set->method == US_STRONG_MIP) {
      if (err) *err = lerr;
      return lerr.code ? lerr.code : US_ERR_IO;
    }
  }
  out->method = US_STRONG_ENUM;
  return us_strong_enumerate(m, set, deadline, x, out, err);
}

/* Method auto: a first dive of the mode search on the untightened model, a
 * few LPs deep:
 * the easy motions (things falling free, sliding) are found before the
 * bounds are tightened, which costs two LPs per contact. */
static us_Status dive(const us_StrongModel *m, const us_StrongSettings *set, double deadline,
                      double *x, us_StrongResult *out, us_Error *err) {
  us_StrongSettings d = *set;
  d.max_nodes = 2L * m->nc + 8;
  us_Status st = us_strong_enumerate(m, &d, deadline, x, out, err);
  out->method = US_STRONG_ENUM;
  return st;
}

/* Turn a "no" of the search into a checked witness, or undecided. */
static us_Status witness(const us_StrongModel *m, const us_Bitset *present, double *x,
                         const us_StrongSettings *set, us_StrongResult *out, us_Error *err) {
  int rc = us_strong_polish(m, x, out->power);
  if (rc >= 0) rc = us_strong_witness(m, x, out);
  if (rc < 0) {
    us_error_set(err, US_ERR_NOMEM, "out of memory writing a strong-stability witness");
    return US_ERR_NOMEM;
  }
  char why[128] = "the gravity scale of the solution is zero";
  if (rc == 0 && us_strong_check(m->e.s, present, out, 10 * set->tol, why, sizeof why)) return US_OK;
  out->strong = -1;
  out->has_witness = 0;
  snprintf(out->note, sizeof out->note, "witness rejected by the check: %s", why);
  return US_OK;
}

/* One model (3D: the inner or the outer cones) searched: its answer in out
 * ("no" only with a checked witness). */
static us_Status decide_model(const us_Structure *s, const us_Bitset *present, int outer,
                              const us_StrongSettings *set, double deadline, us_StrongResult *out,
                              us_Error *err) {
  us_StrongModel m;
  char why[128] = "";
  int rc = us_strong_model_build3(&m, s, present, outer, why, sizeof why);
  us_Status st = US_OK;
  double *x = rc ? NULL : us_calloc((size_t)m.nv, sizeof(double));
  if (rc < 0 || (rc == 0 && !x)) {
    st = US_ERR_NOMEM;
    us_error_set(err, st, "out of memory building the strong-stability model");
  } else if (rc > 0) {
    out->strong = -1;
    snprintf(out->note, sizeof out->note, "refused: %s", why);
  } else {
    out->strong = -1;
    if (set->method == US_STRONG_AUTO) st = dive(&m, set, deadline, x, out, err);
    if (st == US_OK && out->strong != 0) {
      memset(out, 0, sizeof *out);
      st = us_strong_model_tighten(&m, deadline) ? US_ERR_NOMEM : US_OK;
      if (st) us_error_set(err, st, "out of memory tightening the strong-stability model");
      if (!st) st = search(&m, set, deadline, x, out, err);
    }
    if (st == US_OK && out->strong == 0) st = witness(&m, present, x, set, out, err);
  }
  us_free(x);
  us_strong_model_free(&m);
  return st;
}

/* 3D: a motion of the inner cones is one of the circular cone (its
 * witness is re-checked against the circular cone); "yes" of the outer
 * cones is "yes" of the circular one; a "yes" of the inner cones alone or
 * an outer motion the circular cone rejects proves nothing: undecided. */
static us_Status decide3(const us_Structure *s, const us_Bitset *present,
                         const us_StrongSettings *set, double deadline, us_StrongResult *out,
                         us_Error *err) {
  us_Status st = decide_model(s, present, 0, set, deadline, out, err);
  if (st != US_OK || out->strong == 0) return st;
  int inner = out->strong;
  long nodes = out->nodes;
  us_strong_result_free(out);
  st = decide_model(s, present, 1, set, deadline, out, err);
  out->nodes += nodes;
  if (st != US_OK || out->strong == 0) return st;
  if (out->strong == 1)
    snprintf(out->note, sizeof out->note,
             "every contact-mode pattern of the outer polygonal cones (so of the circular cone)");
  else if (inner == 1) {
    char outer_note[sizeof out->note];
    memcpy(outer_note, out->note, sizeof outer_note);
    snprintf(out->note, sizeof out->note,
             "no motion with the inner polygonal cones; the outer ones: %.100s", outer_note);
  }
  else if (out->note[0] == 0)
    snprintf(out->note, sizeof out->note, "undecided with the polygonal cones");
  return st;
}

static us_Status decide(const us_Structure *s, const us_Bitset *present,
                        const us_StrongSettings *set, double deadline, us_StrongResult *out,
                        us_Error *err) {
  if (s->dim == 3) return decide3(s, present, set, deadline, out, err);
  return decide_model(s, present, 0, set, deadline, out, err);
}

us_Status us_strong_stability(const us_Structure *s, const us_Bitset *present,
                              const us_StrongSettings *set, us_StrongResult *out, us_Error *err) {
  us_StrongSettings d = set ? *set : us_strong_default_settings();
  if (!s || !out || (s->dim != 2 && s->dim != 3) || !(d.tol > 0) || d.max_nodes <= 0) {
    us_error_set(err, US_ERR_USAGE, "bad arguments to us_strong_stability");
    return US_ERR_USAGE;
  }
  memset(out, 0, sizeof *out);
  double t0 = us_now(), deadline = d.time_limit > 0 ? t0 + d.time_limit : 0;
  us_Status st;
  us_Verdict weak = weak_verdict(s, present, deadline, &st, err);
  if (st == US_OK) st = decide(s, present, &d, deadline, out, err);
  if (st == US_OK && weak != US_STABLE) {
    /* not weakly stable: not strongly either; keep a checked witness */
    out->strong = weak == US_UNSTABLE || out->has_witness ? 0 : -1;
    snprintf(out->note, sizeof out->note, "%s",
             weak == US_UNSTABLE  ? "does not stand (weak stability fails)"
             : out->has_witness ? "a motion the dynamics allow (checked; the weak test was undecided)"
                                : "the weak stability test was undecided");
  }
  if (st == US_OK && weak == US_STABLE && out->strong == 1 && !out->note[0])
    snprintf(out->note, sizeof out->note, "%s",
             out->method == US_STRONG_MIP ? "the MIP's proven bound" : "every contact-mode pattern");
  if (st == US_OK && s->dim == 3) out->method = US_STRONG_ENUM; /* 3D: the mode search only */
  if (st == US_OK && out->strong == 0 && out->has_witness && !out->note[0])
    snprintf(out->note, sizeof out->note, "a motion the dynamics allow (checked)");
  out->seconds = us_now() - t0;
  if (st != US_OK) us_strong_result_free(out);
  return st;
}
