/* The interactive plan viewer: one self-contained HTML page (docs/viewer.md)
 * made of the page template src/render/viewer.html (embedded at build time,
 * viewer.h) with the structure and plan as JSON in place of its marker.
 *
 * The data (read by the page's script; every index is 0-based; D is the
 * structure's dimension, 2 or 3, and every point or vector has D numbers):
 *   title     string
 *   dim       D; a 3D page carries the 3D view (src/render/viewer3.js) in
 *             place of the script's second marker, a 2D page nothing there
 *   view      [azimuth, elevation] of a 3D page's first view (degrees, the
 *             axes of src/render/scene3.c)
 *   ground    whether the half-plane y <= 0 (3D: z <= 0) supports it
 *   status    the plan's status word, or null without an order
 *   bodies    [{id, m (null when fixed), fixed, xy: [x0, y0, x1, ...], c: [x, y]}];
 *             3D: [{id, m, fixed, parts: [{v: [x0, y0, z0, x1, ...], f:
 *             [[v, ...], ...]}], c: [x, y, z]}]: each convex part's
 *             vertices and faces (vertex indices counter-clockwise seen
 *             from outside)
 *   contacts  [[a, b, p (D numbers), n (D numbers)]]: a = -1 for the
 *             ground, the unit normal from a into b
 *   steps     [[body, ...]]: step k removes these bodies
 *   blocked   [body, ...]: bodies that cannot be removed (status none)
 *   forces    null, or one entry per position 0..nsteps (the structure
 *             before step k; the last, empty structure too): a flat list
 *             [contact, normal (D), friction (D), ...]: at each contact the
 *             force the lower body exerts on the upper one (the picture's
 *             one convention, src/render/forces.c), its normal part and
 *             friction part in world axes
 *   certs     null, or per position the independent re-check of those
 *             forces (us_certificate_check, no solver): {ok, force,
 *             torque, cone, sign} (the residuals relative to the weight;
 *             null when not finite): a plan file edited by hand shows its
 *             failing steps as failing, whatever verify says of the order
 *   force_set the admissible set the forces are ("solver", "margin", ...)
 *   verify    null, or us_VerifyReport's fields (failed_step, unstable_body,
 *             undecided_step: -1 when none)
 *   hands     a plan with hands: its H (0 without actions)
 *   actions   null, or [[verb, body]] in assembly order (place, grab,
 *             release): the slider then steps through them
 *
 * Safety invariant: the JSON sits in a <script type="application/json">
 * element, whose content ends at the first "</script" (any case) and
 * changes parsing state at "<!--". The writer never emits '<' inside the
 * data: strings escape '<', '>' and '&' as \u003c, \u003e, \u0026 (and
 * U+2028, U+2029, control characters, quote and backslash as JSON
 * requires; invalid UTF-8 from the C API becomes U+FFFD), and numbers and
 * punctuation contain none. The script reads user text with JSON.parse and
 * places it with textContent only, so ids are never markup.
 *
 * Numbers: 9 significant digits (a thousandth of a pixel on any screen);
 * a non-finite one refuses the page (US_ERR_INPUT) before the file is
 * opened, as do settings that do not match the structure (US_ERR_USAGE). */
#include "core/core.h"
#include "render/render.h"
#include "render/viewer.h"
#include "stability/certificate.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define DATA_MARKER "@US_DATA@"
#define VIEW3_MARKER "/*@US_VIEW3@*/"

/* ------------------------------------------------------------ checks */

static int nsteps_of(const us_RenderSettings *r) {
  if (!r || r->norder <= 0) return 0;
  return r->group_start ? r->ngroups : r->norder;
}
static int step_first(const us_RenderSettings *r, int k) {
  return r->group_start ? r->group_start[k] : k;
}

/* The order: bodies of s, each once, steps covering it in increasing
 * offsets; blocked bodies of s outside the order. seen[i] is set for each
 * body of either list. */
static us_Status check_order(const us_Structure *s, const us_RenderSettings *r, char *seen,
                             us_Error *err) {
  if (r->norder < 0 || (r->norder > 0 && !r->order) || r->nblocked < 0 ||
      (r->nblocked > 0 && !r->blocked))
    return us_error_set(err, US_ERR_USAGE, "render --html: bad order or blocked list");
  if (r->group_start && r->norder > 0 &&
      (r->ngroups < 1 || r->group_start[0] != 0 || r->group_start[r->ngroups] != r->norder))
    return us_error_set(err, US_ERR_USAGE, "render --html: steps do not cover the order");
  for (int k = 0; r->group_start && k < nsteps_of(r); k++)
    if (r->group_start[k + 1] <= r->group_start[k])
      return us_error_set(err, US_ERR_USAGE, "render --html: step %d is empty", k);
  for (int k = 0; k < r->norder + r->nblocked; k++) {
    int i = k < r->norder ? r->order[k] : r->blocked[k - r->norder];
    if (i < 0 || i >= s->nbody || seen[i] || s->bodies[i].fixed)
      return us_error_set(err, US_ERR_USAGE, "render --html: order or blocked entry %d is not a "
                          "movable body named once", k);
    seen[i] = 1;
  }
  return US_OK;
}

static us_Status check_certs(const us_Structure *s, const us_Forces *certs, int n, us_Error *err) {
  for (int k = 0; certs && k <= n; k++) {
    const us_Forces *f = &certs[k];
    if (f->ncontact < 0 || (f->ncontact > 0 && (!f->contact || !f->f)))
      return us_error_set(err, US_ERR_USAGE, "render --html: bad forces at step %d", k);
    for (int j = 0; j < f->ncontact; j++)
      if (f->contact[j] < 0 || f->contact[j] >= s->ncontact)
        return us_error_set(err, US_ERR_USAGE, "render --html: forces at step %d name contact "
                            "%d, not in 0..%d", k, f->contact[j], s->ncontact - 1);
  }
  return US_OK;
}

static us_Status check_verify(const us_Structure *s, const us_HtmlSettings *h, int n,
                              us_Error *err) {
  const us_VerifyReport *v = &h->verify;
  if (!h->verified) return US_OK;
  if (v->failed_step < -1 || v->failed_step >= n || v->undecided_step < -1 ||
      v->undecided_step >= n || v->unstable_body < -1 || v->unstable_body >= s->nbody)
    return us_error_set(err, US_ERR_USAGE, "render --html: the verify report does not match "
                        "the order");
  return US_OK;
}

static int finite_xy(const double *v, int n) {
  for (int k = 0; k < n; k++)
    if (!isfinite(v[k])) return 0;
  return 1;
}

/* A body's geometry: its polygon (2D) or its parts' vertices (3D). */
static int finite_body(const us_Body *b, int dim) {
  int ok = finite_xy(b->com, dim) && (b->fixed || isfinite(b->mass));
  if (dim == 2) return ok && finite_xy(b->verts, 2 * b->nvert);
  for (int p = 0; ok && p < b->npart; p++) ok = finite_xy(b->parts[p].verts, 3 * b->parts[p].nvert);
  return ok;
}

/* Every number the page will hold is finite. */
static us_Status check_numbers(const us_Structure *s, const us_Forces *certs, int n,
                               us_Error *err) {
  int ok = 1, dim = s->dim;
  for (int i = 0; ok && i < s->nbody; i++) ok = finite_body(&s->bodies[i], dim);
  for (int c = 0; ok && c < s->ncontact; c++)
    ok = finite_xy(s->contacts[c].p, dim) && finite_xy(s->contacts[c].n, dim);
  for (int k = 0; ok && certs && k <= n; k++) ok = finite_xy(certs[k].f, dim * certs[k].ncontact);
  if (!ok) return us_error_set(err, US_ERR_INPUT, "render --html: a coordinate, mass or force "
                               "is not a finite number");
  return US_OK;
}

static us_Status check_all(const us_Structure *s, const us_RenderSettings *r,
                           const us_HtmlSettings *h, us_Error *err) {
  if (s->dim != 2 && s->dim != 3)
    return us_error_set(err, US_ERR_INPUT, "render --html: only 2D and 3D structures can be "
                        "shown (this one is %dD)", s->dim);
  if (s->dim == 3 && r && !(isfinite(r->view_az) && r->view_el >= -90.0 && r->view_el <= 90.0))
    return us_error_set(err, US_ERR_USAGE, "render --html: the view (%g, %g) is not an azimuth "
                        "and an elevation in [-90, 90] degrees", r->view_az, r->view_el);
  if (!us_structure_is_finalized(s))
    return us_error_set(err, US_ERR_USAGE, "render --html: the structure is not finalized");
  char *seen = us_calloc((size_t)s->nbody + 1, 1);
  if (!seen) return us_error_set(err, US_ERR_NOMEM, "render --html: out of memory");
  us_Status st = r ? check_order(s, r, seen, err) : US_OK;
  us_free(seen);
  int n = nsteps_of(r);
  if (!st) st = check_certs(s, h->certs, n, err);
  if (!st) st = check_verify(s, h, n, err);
  if (!st) st = check_numbers(s, h->certs, n, err);
  for (int k = 0; !st && k < h->nactions; k++)
    if (!h->actions || h->actions[k].body < 0 || h->actions[k].body >= s->nbody ||
        (unsigned)h->actions[k].verb > US_ACTION_RELEASE)
      st = us_error_set(err, US_ERR_USAGE, "render --html: action %d is not a verb on a body", k);
  return st;
}

/* ------------------------------------------------------------ JSON */

static void put_num(FILE *fp, double x) { fprintf(fp, "%.9g", x); }

static void put_int(FILE *fp, int i) { fprintf(fp, "%d", i); }

/* A JSON string safe inside <script> (see the file head). */
static void put_str(FILE *fp, const char *s) {
  fputc('"', fp);
  while (s && *s) {
    uint32_t c;
    int n = us_utf8_next(s, &c);
    if (c == '"' || c == '\\') fprintf(fp, "\\%c", (char)c);
    else if (c < 0x20 || c == '<' || c == '>' || c == '&' || c == 0x2028 || c == 0x2029)
      fprintf(fp, "\\u%04x", (unsigned)c);
    else if (c == US_UTF8_INVALID) fputs("\\ufffd", fp);
    else fwrite(s, 1, (size_t)n, fp);
    s += n;
  }
  fputc('"', fp);
}

/* n numbers separated by commas. */
static void put_nums(FILE *fp, const double *v, int n) {
  for (int k = 0; k < n; k++) {
    if (k) fputc(',', fp);
    put_num(fp, v[k]);
  }
}

/* A convex part: {v: vertices, f: faces as vertex index lists}. */
static void put_part(FILE *fp, const us_Polyhedron *p) {
  fputs("{\"v\":[", fp);
  put_nums(fp, p->verts, 3 * p->nvert);
  fputs("],\"f\":[", fp);
  for (int f = 0; f < p->nface; f++) {
    fputs(f ? ",[" : "[", fp);
    for (int q = p->face_start[f]; q < p->face_start[f + 1]; q++)
      fprintf(fp, q > p->face_start[f] ? ",%d" : "%d", p->face_vert[q]);
    fputc(']', fp);
  }
  fputs("]}", fp);
}

static void put_body(FILE *fp, const us_Body *b, int dim) {
  fputs("{\"id\":", fp);
  put_str(fp, b->id);
  fputs(",\"m\":", fp);
  if (b->fixed) fputs("null", fp);
  else put_num(fp, b->mass);
  fputs(b->fixed ? ",\"fixed\":true" : ",\"fixed\":false", fp);
  if (dim == 2) {
    fputs(",\"xy\":[", fp);
    put_nums(fp, b->verts, 2 * b->nvert);
  } else {
    fputs(",\"parts\":[", fp);
    for (int p = 0; p < b->npart; p++) {
      if (p) fputc(',', fp);
      put_part(fp, &b->parts[p]);
    }
  }
  fputs("],\"c\":[", fp);
  put_nums(fp, b->com, dim);
  fputs("]}", fp);
}

static void put_bodies(FILE *fp, const us_Structure *s) {
  fputs(",\n\"bodies\":[", fp);
  for (int i = 0; i < s->nbody; i++) {
    fputs(i ? ",\n" : "\n", fp);
    put_body(fp, &s->bodies[i], s->dim);
  }
  fputs("]", fp);
}

static void put_contacts(FILE *fp, const us_Structure *s) {
  fputs(",\n\"contacts\":[", fp);
  for (int c = 0; c < s->ncontact; c++) {
    const us_Contact *k = &s->contacts[c];
    fprintf(fp, "%s[%d,%d,", c ? ",\n" : "\n", k->a == US_GROUND ? -1 : k->a, k->b);
    put_nums(fp, k->p, s->dim);
    fputc(',', fp);
    put_nums(fp, k->n, s->dim);
    fputc(']', fp);
  }
  fputs("]", fp);
}

static void put_index_list(FILE *fp, const int *v, int n) {
  fputc('[', fp);
  for (int k = 0; k < n; k++) {
    if (k) fputc(',', fp);
    put_int(fp, v[k]);
  }
  fputc(']', fp);
}

static void put_steps(FILE *fp, const us_RenderSettings *r) {
  int n = nsteps_of(r);
  fputs(",\n\"steps\":[", fp);
  for (int k = 0; k < n; k++) {
    fputs(k ? ",\n" : "\n", fp);
    put_index_list(fp, r->order + step_first(r, k), step_first(r, k + 1) - step_first(r, k));
  }
  fputs("],\n\"blocked\":", fp);
  put_index_list(fp, r ? r->blocked : NULL, r ? r->nblocked : 0);
}

/* Forces of one position: each contact's drawn force (lower body on the
 * upper one), normal and friction parts in world axes. */
static void put_forces_at(FILE *fp, const us_Structure *s, const us_Forces *f) {
  fputc('[', fp);
  for (int j = 0; j < f->ncontact; j++) {
    us_DrawnForce d;
    us_drawn_force(s, f, j, &d);
    fprintf(fp, "%s%d", j ? "," : "", f->contact[j]);
    for (int q = 0; q < 2 * s->dim; q++) {
      double v = q < s->dim ? d.normal[q] : d.friction[q - s->dim];
      fputc(',', fp);
      put_num(fp, isfinite(v) ? v : 0.0);
    }
  }
  fputc(']', fp);
}

/* A residual of the re-check, null when it is not finite. */
static void put_residual(FILE *fp, const char *key, double x) {
  fprintf(fp, ",\"%s\":", key);
  if (isfinite(x)) put_num(fp, x);
  else fputs("null", fp);
}

/* The re-check of every position's forces (ck: nsteps + 1 entries). */
static void put_certs(FILE *fp, const us_CertCheck *ck, int n) {
  fputs(",\n\"certs\":", fp);
  if (!ck) {
    fputs("null", fp);
    return;
  }
  fputc('[', fp);
  for (int k = 0; k <= n; k++) {
    fprintf(fp, "%s{\"ok\":%s", k ? ",\n" : "\n", ck[k].ok ? "true" : "false");
    put_residual(fp, "force", ck[k].max_force_residual);
    put_residual(fp, "torque", ck[k].max_torque_residual);
    put_residual(fp, "cone", ck[k].max_cone_violation);
    put_residual(fp, "sign", ck[k].max_sign_violation);
    fputc('}', fp);
  }
  fputc(']', fp);
}

static void put_forces(FILE *fp, const us_Structure *s, const us_Forces *certs, int n) {
  fputs(",\n\"forces\":", fp);
  if (!certs) {
    fputs("null", fp);
    return;
  }
  fputc('[', fp);
  for (int k = 0; k <= n; k++) {
    fputs(k ? ",\n" : "\n", fp);
    put_forces_at(fp, s, &certs[k]);
  }
  fputc(']', fp);
}

static void put_verify(FILE *fp, const us_HtmlSettings *h) {
  const us_VerifyReport *v = &h->verify;
  fputs(",\n\"verify\":", fp);
  if (!h->verified) {
    fputs("null", fp);
    return;
  }
  fprintf(fp, "{\"ok\":%s,\"full_unstable\":%s,\"failed_step\":%d,\"incomplete\":%s,"
          "\"undecided\":%s,\"undecided_step\":%d,\"remaining\":%d,\"unstable_body\":%d,"
          "\"note\":", v->ok ? "true" : "false", v->full_unstable ? "true" : "false",
          v->failed_step, v->incomplete ? "true" : "false", v->undecided ? "true" : "false",
          v->undecided_step, v->remaining, v->unstable_body);
  char note[sizeof v->note + 1];
  memcpy(note, v->note, sizeof v->note);
  note[sizeof v->note] = 0; /* a report filled by hand may lack the NUL */
  put_str(fp, note);
  fputc('}', fp);
}

/* A plan with hands: H and its actions as [verb, body]. */
static void put_actions(FILE *fp, const us_HtmlSettings *h) {
  fprintf(fp, ",\n\"hands\":%d,\n\"actions\":", h->nactions > 0 ? h->hands : 0);
  if (h->nactions <= 0) {
    fputs("null", fp);
    return;
  }
  for (int k = 0; k < h->nactions; k++)
    fprintf(fp, "%s[\"%s\",%d]", k ? "," : "[", us_action_name(h->actions[k].verb),
            h->actions[k].body);
  fputc(']', fp);
}

static void put_data(FILE *fp, const us_Structure *s, const us_RenderSettings *r,
                     const us_HtmlSettings *h, const us_CertCheck *ck) {
  int with_plan = r && (r->norder > 0 || r->nblocked > 0);
  fputs("{\"title\":", fp);
  put_str(fp, h->title ? h->title : "unstack");
  fprintf(fp, ",\n\"dim\":%d", s->dim);
  if (s->dim == 3) {
    us_RenderSettings def = us_render_default_settings();
    const us_RenderSettings *v = r ? r : &def;
    fputs(",\n\"view\":[", fp);
    put_num(fp, v->view_az);
    fputc(',', fp);
    put_num(fp, v->view_el);
    fputc(']', fp);
  }
  fputs(s->ground ? ",\n\"ground\":true" : ",\n\"ground\":false", fp);
  fputs(",\n\"status\":", fp);
  if (with_plan) put_str(fp, us_plan_status_name(h->status));
  else fputs("null", fp);
  put_bodies(fp, s);
  put_contacts(fp, s);
  put_steps(fp, r);
  put_forces(fp, s, h->certs, nsteps_of(r));
  put_certs(fp, ck, nsteps_of(r));
  fputs(",\n\"force_set\":", fp);
  put_str(fp, us_force_set_name(h->force_set));
  fputs(r && r->force_resultants ? ",\n\"resultants\":true" : ",\n\"resultants\":false", fp);
  put_verify(fp, h);
  put_actions(fp, h);
  fputs("}", fp);
}

/* ------------------------------------------------------------ re-check */

/* Every position's forces through the library's certificate check (no
 * solver): position k is the structure before step k. *out gets nsteps + 1
 * entries. The check's scratch is allocated here once, so that a memory
 * failure is an error, never a step flagged as failing. */
static us_Status recheck_certs(const us_Structure *s, const us_RenderSettings *r,
                               const us_Forces *certs, us_CertCheck **out, us_Error *err) {
  int n = nsteps_of(r);
  double tol = us_stability_default_settings().cert_tol;
  us_Bitset present = {0};
  double *acc = us_malloc(((size_t)US_CERT_ACC * (size_t)s->nbody + 1) * sizeof *acc);
  unsigned char *seen = us_malloc((size_t)s->ncontact + 1);
  *out = us_calloc((size_t)n + 1, sizeof **out);
  int ok = acc && seen && *out && !us_bitset_init(&present, s->nbody > 0 ? s->nbody : 1);
  if (ok) us_bitset_fill(&present);
  for (int k = 0; ok && k <= n; k++) {
    us_certificate_check_buf(s, &present, &certs[k], tol, acc, seen, &(*out)[k]);
    for (int q = k < n ? step_first(r, k) : 0; k < n && q < step_first(r, k + 1); q++)
      us_bitset_clear(&present, r->order[q]);
  }
  us_bitset_free(&present);
  us_free(acc);
  us_free(seen);
  if (ok) return US_OK;
  us_free(*out);
  *out = NULL;
  return us_error_set(err, US_ERR_NOMEM, "render --html: out of memory");
}

/* ------------------------------------------------------------ driver */

us_HtmlSettings us_html_default_settings(void) {
  us_HtmlSettings h;
  memset(&h, 0, sizeof h);
  h.status = US_PLAN_FOUND;
  h.verify.failed_step = h.verify.undecided_step = h.verify.unstable_body = -1;
  return h;
}

/* The template around its two markers: the data in place of the first,
 * the 3D view's script (3D only) in place of the second. */
static void put_page(FILE *fp, const us_Structure *s, const us_RenderSettings *r,
                     const us_HtmlSettings *h, const us_CertCheck *ck, const char *mark,
                     const char *mark3) {
  const char *page = (const char *)us_viewer_html, *rest = mark + strlen(DATA_MARKER);
  fwrite(page, 1, (size_t)(mark - page), fp);
  put_data(fp, s, r, h, ck);
  fwrite(rest, 1, (size_t)(mark3 - rest), fp);
  if (s->dim == 3) fwrite(us_viewer3_js, 1, us_viewer3_js_size, fp);
  fputs(mark3 + strlen(VIEW3_MARKER), fp);
}

us_Status us_render_html(const us_Structure *s, const us_RenderSettings *r,
                         const us_HtmlSettings *h, const char *path, us_Error *err) {
  us_Error local;
  if (!err) err = &local; /* the steps below read err->code */
  if (!s || !path) return us_error_set(err, US_ERR_USAGE, "render --html: no structure or no path");
  us_HtmlSettings def = us_html_default_settings();
  if (!h) h = &def;
  const char *mark = strstr((const char *)us_viewer_html, DATA_MARKER);
  const char *mark3 = mark ? strstr(mark, VIEW3_MARKER) : NULL;
  if (!mark3) return us_error_set(err, US_ERR_USAGE, "render --html: the page template lacks "
                                  "its data or 3D view marker (a build error)");
  us_Status st = check_all(s, r, h, err);
  if (st) return st;
  us_CertCheck *ck = NULL;
  if (h->certs && recheck_certs(s, r, h->certs, &ck, err)) return err->code;
  us_AtomicFile *af = us_atomic_open(path, err);
  if (af) put_page((FILE *)us_atomic_stream(af), s, r, h, ck, mark, mark3);
  us_free(ck);
  return af ? us_atomic_commit(af, err) : err->code;
}
