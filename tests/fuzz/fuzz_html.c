/* Fuzz target `html`: the HTML viewer writer (us_render_html, src/render/
 * html.c) fed with structures and plans derived from the input.
 *
 * Input: one control byte, then a structure as for `pipeline` (a NUL byte
 * and a box pile, or the text of a structure file). Control bits: 0-1 the
 * search, 2 certificates, 3 verify the order drawn, 4 draw the plan's
 * order reversed (most often invalid: a failing step), 5 a title made of
 * the first body's id (user text in the page). Properties checked for
 * every 2D structure within the caps of fuzz.h:
 *   - the page is written (a finite 2D structure with a consistent plan
 *     is never refused);
 *   - the data block (<script id="us-data" type="application/json">) holds
 *     no '<' (the writer's safety invariant, html.c) and parses as JSON
 *     with one body per body and one step per step drawn;
 *   - nothing leaks through the allocation funnel. */
#include "fuzz.h"

#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DATA_OPEN "<script id=\"us-data\" type=\"application/json\">"

/* The data block of the page at path, checked; its JSON (json_decref). */
static json_t *page_data(const char *path) {
  size_t n = 0;
  char *t = fz_slurp(path, &n);
  if (!t) fz_finding("the page cannot be read back");
  char *a = strstr(t, DATA_OPEN);
  if (!a) fz_finding("the page has no data block");
  a += strlen(DATA_OPEN);
  char *e = strstr(a, "</script");
  if (!e) fz_finding("the data block is not closed");
  if (memchr(a, '<', (size_t)(e - a))) fz_finding("a '<' inside the data block");
  json_error_t je;
  json_t *j = json_loadb(a, (size_t)(e - a), 0, &je);
  if (!j) fz_finding("the data block is not JSON: %s (column %d)", je.text, je.column);
  free(t);
  return j;
}

static void check_page(const char *path, int nbody, int nsteps) {
  json_t *j = page_data(path);
  if (json_array_size(json_object_get(j, "bodies")) != (size_t)nbody)
    fz_finding("the page holds %zu bodies, not %d", json_array_size(json_object_get(j, "bodies")), nbody);
  if (json_array_size(json_object_get(j, "steps")) != (size_t)nsteps)
    fz_finding("the page holds %zu steps, not %d", json_array_size(json_object_get(j, "steps")), nsteps);
  json_decref(j);
}

/* r and h from plan p, reversed or not. */
static void from_plan(const us_Plan *p, int reverse, int *rev, us_RenderSettings *r, us_HtmlSettings *h) {
  h->status = p->status;
  if (p->status == US_PLAN_NONE) r->blocked = p->blocked, r->nblocked = p->nblocked;
  if (p->status != US_PLAN_FOUND || p->nsteps == 0) return;
  r->norder = p->nsteps;
  r->order = p->order;
  r->group_start = p->group_start;
  r->ngroups = p->group_start ? p->ngroups : 0;
  h->certs = p->certs;
  if (!reverse) return;
  for (int k = 0; k < p->nsteps; k++) rev[k] = p->order[p->nsteps - 1 - k];
  r->order = rev, r->group_start = NULL, r->ngroups = 0, h->certs = NULL;
}

static void render(const us_Structure *s, uint8_t c) {
  us_PlanSettings set = us_plan_default_settings();
  set.search = (us_Search)(c & 3);
  set.certificates = (c >> 2) & 1;
  set.max_tests = 100;
  set.max_exact_tests = 100;
  us_Plan p;
  us_Error err;
  us_error_clear(&err);
  us_Status st = us_plan(s, &set, &p, &err);
  fz_check_error("plan", st, &err);
  if (st) return;
  int *rev = malloc(((size_t)p.nsteps + 1) * sizeof *rev);
  us_RenderSettings r = us_render_default_settings();
  us_HtmlSettings h = us_html_default_settings();
  if (!rev) abort();
  from_plan(&p, (c >> 4) & 1, rev, &r, &h);
  if ((c >> 5) & 1) h.title = s->bodies[0].id;
  if (((c >> 3) & 1) && r.order) {
    us_StabilitySettings ss = us_stability_default_settings();
    st = us_verify_steps(s, &ss, r.order, r.norder, r.group_start, r.ngroups, &h.verify, &err);
    fz_check_error("verify", st, &err);
    h.verified = st == US_OK;
  }
  const char *path = fz_path(0, "page.html");
  st = us_render_html(s, &r, &h, path, &err);
  fz_check_error("render_html", st, &err);
  if (st) fz_finding("the page was refused: %s", err.msg);
  check_page(path, s->nbody, r.order ? (r.group_start ? r.ngroups : r.norder) : 0);
  free(rev);
  us_plan_free(&p);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size < 1 || size > FZ_MAX_INPUT) return 0;
  long live = us_alloc_live();
  char *text = fz_structure_text(data + 1, size - 1);
  us_Error err;
  us_error_clear(&err);
  us_Structure *s = us_structure_parse(text, "input.json", 0, &err);
  if (!s) fz_check_error("parse", err.code, &err);
  if (s && s->dim == 2 && s->nbody > 0 && fz_small(s)) render(s, data[0]);
  us_structure_free(s);
  free(text);
  if (us_alloc_live() != live)
    fz_finding("%ld blocks leaked through the allocation funnel", us_alloc_live() - live);
  return 0;
}
