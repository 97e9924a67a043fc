/* Tolerances follow the bodies involved, and detection is near-linear
 * without changing its answers:
 *  - a body added far away changes no contact and no verdict;
 *  - a structure and its copy scaled by 1e-6 and 1e6 (coordinates times k,
 *    gravity times k, density over k^2 so that masses stay the same: every
 *    force scales by k, so every answer must be the same) give the same
 *    contacts (count and pairs, in order), the same stability verdict and
 *    the same plan status, for generated columns, pyramids, walls, arches
 *    and random stacks;
 *  - tiny structures (1e-8 across) see an 8 % gap as a gap;
 *  - the fast detection (body and edge indexes, duplicate search by sorted
 *    keys) gives exactly the contacts of the reference mode
 *    (us_ContactSettings.reference: every pair, every edge, every earlier
 *    contact) on random piles, generated structures and polygons of many
 *    vertices (combs under plates, random stars among blocks). */
#include "piles.h"
#include "scenes.h"
#include "test.h"

/* A copy of s through the public API, scaled by k (see the file comment). */
static us_Structure *scaled_copy(const us_Structure *s, double k) {
  us_Structure *c = us_structure_new(2);
  us_Error err;
  c->friction = s->friction;
  c->ground = s->ground;
  for (int d = 0; d < 3; d++) c->gravity[d] = s->gravity[d] * k;
  for (int i = 0; c && i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    double *xy = us_malloc((size_t)b->nvert * 2 * sizeof *xy);
    for (int v = 0; xy && v < 2 * b->nvert; v++) xy[v] = b->verts[v] * k;
    us_BodyDef def = us_default_body_def();
    def.id = b->id;
    def.nvert = b->nvert;
    def.xy = xy;
    def.density = b->density / (k * k);
    def.mass = b->mass_given ? b->mass : 0.0;
    def.fixed = b->fixed;
    def.friction = b->friction;
    int r = xy ? us_structure_add_body(c, &def, &err) : -1;
    us_free(xy);
    if (r < 0) {
      us_structure_free(c);
      return NULL;
    }
  }
  return c ? scene_seal(c) : NULL;
}

static int same_pairs(const us_Structure *a, const us_Structure *b) {
  if (a->ncontact != b->ncontact) return 0;
  for (int k = 0; k < a->ncontact; k++)
    if (a->contacts[k].a != b->contacts[k].a || a->contacts[k].b != b->contacts[k].b) return 0;
  return 1;
}

static us_Verdict verdict(const us_Structure *s) {
  us_StabilitySettings set = us_stability_default_settings();
  us_Error err;
  us_Stability *w = us_stability_new(s, &set, &err);
  us_StabilityResult r;
  memset(&r, 0, sizeof r);
  us_Verdict v = US_UNDECIDED;
  if (w && us_stability_test_full(w, &r, &err) == US_OK) v = r.verdict;
  us_stability_result_free(&r);
  us_stability_free(w);
  return v;
}

static int plan_status(const us_Structure *s) {
  us_PlanSettings set = us_plan_default_settings();
  us_Plan p;
  us_Error err;
  memset(&p, 0, sizeof p);
  int st = us_plan(s, &set, &p, &err) == US_OK ? (int)p.status : -1;
  us_plan_free(&p);
  return st;
}

/* Block b floats 0.05 above block a: no contact, unstable; a block
 * 100,000 away changes neither. */
static void far_away_changes_nothing(void) {
  us_Structure *s[2];
  for (int far = 0; far < 2; far++) {
    s[far] = us_structure_new(2);
    scene_box(s[far], "a", 0, 0, 1, 1, 1);
    scene_box(s[far], "b", 0, 1.05, 1, 1, 1);
    if (far) scene_box(s[far], "far", 1e5, 0, 1, 1, 1);
    s[far] = scene_seal(s[far]);
    CHECK(s[far]);
  }
  int n0 = s[0]->ncontact, same = n0 == 2; /* a on the ground only */
  for (int k = 0; k < n0; k++)
    same = same && !memcmp(&s[0]->contacts[k], &s[1]->contacts[k], sizeof(us_Contact));
  same = same && s[1]->ncontact == n0 + 2; /* plus far on the ground */
  us_Verdict v0 = verdict(s[0]), v1 = verdict(s[1]);
  us_structure_free(s[0]);
  us_structure_free(s[1]);
  CHECK(same);
  CHECK_INT(v0, ==, US_UNSTABLE);
  CHECK_INT(v1, ==, US_UNSTABLE);
}

/* Two boxes 1e-8 across, 8e-10 apart (8 %): no contact between them (an
 * absolute floor of 1e-9 took it for one). */
static void tiny_gap_is_a_gap(void) {
  us_Structure *s = us_structure_new(2);
  scene_box(s, "a", 0, 0, 1e-8, 1e-8, 1);
  scene_box(s, "b", 0, 1.08e-8, 1e-8, 1e-8, 1);
  s = scene_seal(s);
  CHECK(s);
  int between = 0;
  for (int k = 0; k < s->ncontact; k++) between += s->contacts[k].a == 0;
  us_Verdict v = verdict(s);
  us_structure_free(s);
  CHECK_INT(between, ==, 0);
  CHECK_INT(v, ==, US_UNSTABLE);
}

static us_Structure *generated(int which) {
  us_GenSettings g = us_gen_default_settings();
  us_Error err;
  switch (which) {
    case 0: g.n = 5; return us_gen_column(&g, &err);
    case 1: g.n = 4; return us_gen_pyramid(&g, &err);
    case 2: g.rows = 3, g.cols = 4; return us_gen_wall(&g, &err);
    case 3: g.n = 7; return us_gen_arch(&g, &err);
    case 4: g.n = 12; g.thickness = 0.2; return us_gen_arch(&g, &err); /* too thin: falls */
    default: g.rows = 4, g.width = 5, g.seed = (unsigned long)which; return us_gen_random(&g, &err);
  }
}

/* Same contacts, verdict and plan status at scales 1e-6 and 1e6. */
static void scaled_copies_agree(void) {
  const double ks[2] = {1e-6, 1e6};
  for (int which = 0; which < 8; which++) {
    us_Structure *s = generated(which);
    CHECK(s);
    us_Verdict v = verdict(s);
    int ps = plan_status(s), ok = 1;
    for (int q = 0; q < 2 && ok; q++) {
      us_Structure *c = scaled_copy(s, ks[q]);
      ok = c && same_pairs(s, c) && verdict(c) == v && plan_status(c) == ps;
      if (!ok) fprintf(stderr, "  structure %d differs at scale %g\n", which, ks[q]);
      us_structure_free(c);
    }
    us_structure_free(s);
    CHECK(ok);
  }
}

/* Contacts of s by the fast path and by the reference agree exactly. */
static int same_as_reference(us_Structure *s) {
  us_Error err;
  us_ContactSettings fast = {s->contact_tol, 0}, ref = {s->contact_tol, 1};
  us_ContactList a = {0}, b = {0};
  us_Status sa = us_detect_contacts(s, &fast, &a, &err);
  us_Status sb = us_detect_contacts(s, &ref, &b, &err);
  int same = sa == sb && a.n == b.n && (a.n == 0 || !memcmp(a.c, b.c, (size_t)a.n * sizeof *a.c));
  if (!same) fprintf(stderr, "  fast %d (%d contacts), reference %d (%d)\n", sa, a.n, sb, b.n);
  us_contact_list_free(&a);
  us_contact_list_free(&b);
  return same;
}

static void reference_piles(void) {
  unsigned long long rng = 12345;
#ifdef US_TEST_SANITIZED
  int cases = 20;
#else
  int cases = 100;
#endif
  int drawn = 0;
  for (int t = 0; t < cases; t++) {
    us_Structure *s = pile_random(&rng, 4 + t % 9);
    if (!s) continue; /* a rare overlapping draw (piles.h) */
    drawn++;
    int ok = same_as_reference(s);
    us_structure_free(s);
    CHECK(ok);
  }
  CHECK_INT(drawn, >=, cases * 3 / 4);
  for (int which = 0; which < 8; which++) {
    us_Structure *s = generated(which);
    CHECK(s);
    int ok = same_as_reference(s);
    us_structure_free(s);
    CHECK(ok);
  }
}

/* A comb of `teeth` teeth (1 wide, pitch 2) standing on the ground, a
 * plate on the teeth and, when `blocks`, a small block in every other gap
 * resting on the comb's valley floor. */
static us_Structure *comb_unsealed(int teeth, int blocks) {
  int nv = 2 + 4 * teeth;
  double w = 2.0 * teeth - 1.0, *xy = us_malloc((size_t)nv * 2 * sizeof *xy);
  if (!xy) return NULL;
  double *p = xy;
  *p++ = 0, *p++ = 0, *p++ = w, *p++ = 0;
  for (int t = teeth - 1; t >= 0; t--) {
    double x = 2.0 * t;
    double q[8] = {x + 1, 1, x + 1, 2, x, 2, x, 1};
    memcpy(p, q, sizeof q);
    p += 8;
  }
  us_Structure *s = us_structure_new(2);
  us_BodyDef d = us_default_body_def();
  d.id = "comb", d.nvert = nv, d.xy = xy;
  us_Error err;
  us_structure_add_body(s, &d, &err);
  us_free(xy);
  scene_box(s, "plate", 0, 2, w, 1, 1);
  for (int t = 0; blocks && t + 1 < teeth; t += 2) {
    char id[16];
    snprintf(id, sizeof id, "g%d", t);
    scene_box(s, id, 2.0 * t + 1.25, 1, 0.5, 0.5, 1);
  }
  return s;
}

static us_Structure *comb(int teeth, int blocks) {
  us_Structure *s = comb_unsealed(teeth, blocks);
  return s ? scene_seal(s) : NULL;
}

/* A star of n vertices (radii alternating 1 and 0.6, rotated) with a unit
 * block on it and blocks against its tips. */
static us_Structure *star(int n, double turn) {
  double *xy = us_malloc((size_t)n * 2 * sizeof *xy), pi = 3.14159265358979323846;
  if (!xy) return NULL;
  for (int k = 0; k < n; k++) {
    double r = k % 2 ? 0.6 : 1.0, a = turn + 2 * pi * k / n;
    xy[2 * k] = 5 + r * cos(a);
    xy[2 * k + 1] = 2 + r * sin(a);
  }
  us_Structure *s = us_structure_new(2);
  us_BodyDef d = us_default_body_def();
  d.id = "star", d.nvert = n, d.xy = xy;
  us_Error err;
  us_structure_add_body(s, &d, &err);
  int t = 0, r = 0; /* the top and the rightmost vertex */
  for (int k = 1; k < n; k++) {
    if (xy[2 * k + 1] > xy[2 * t + 1]) t = k;
    if (xy[2 * k] > xy[2 * r]) r = k;
  }
  scene_box(s, "cap", xy[2 * t] - 0.5, xy[2 * t + 1], 1, 1, 1);
  scene_box(s, "side", xy[2 * r], xy[2 * r + 1] - 0.5, 1, 1, 1);
  us_free(xy);
  return scene_seal(s);
}

static void reference_many_vertices(void) {
  for (int teeth = 1; teeth <= 200; teeth = teeth * 3 + 1)
    for (int blocks = 0; blocks < 2; blocks++) {
      us_Structure *s = comb(teeth, blocks);
      CHECK(s);
      int ok = same_as_reference(s) && s->ncontact >= 2 * teeth;
      us_structure_free(s);
      CHECK(ok);
    }
  int stars = 0;
  for (int n = 8; n <= 400; n *= 3) {
    us_Structure *s = star(n, 0.1 * n);
    CHECK(s);
    stars++;
    int ok = same_as_reference(s) && s->ncontact >= 2;
    if (!ok) fprintf(stderr, "  star %d: %d contacts\n", n, s->ncontact);
    us_structure_free(s);
    CHECK(ok);
  }
  CHECK_INT(stars, ==, 4);
}

/* An interpenetrating comb is reported by both paths with the same
 * message. */
static void reference_overlap_message(void) {
  us_Structure *s = comb(50, 0);
  CHECK(s);
  s->bodies[1].verts[1] -= 0.3; /* the plate's lower left corner into the comb */
  s->bodies[1].verts[3] -= 0.3;
  us_Error e1, e2;
  us_ContactSettings fast = {0, 0}, ref = {0, 1};
  us_ContactList a = {0}, b = {0};
  us_Status s1 = us_detect_contacts(s, &fast, &a, &e1), s2 = us_detect_contacts(s, &ref, &b, &e2);
  us_contact_list_free(&a);
  us_contact_list_free(&b);
  us_structure_free(s);
  CHECK_INT(s1, ==, US_ERR_INPUT);
  CHECK_INT(s2, ==, US_ERR_INPUT);
  CHECK(strstr(e1.msg, "overlap") != NULL);
  CHECK(!strcmp(e1.msg, e2.msg));
}

/* Out of memory at every allocation of finalizing a comb (its edge grid,
 * the duplicate search): US_ERR_NOMEM or the full answer, nothing leaks. */
static void out_of_memory_comb(void) {
  us_Structure *ref = comb(13, 1);
  CHECK(ref);
  int nref = ref->ncontact, failures = 0, done = 0;
  us_structure_free(ref);
  for (long n = 0; n < 2000 && !done; n++) {
    us_Structure *s = comb_unsealed(13, 1);
    CHECK(s);
    us_Error err;
    us_alloc_fail_after(n);
    us_Status st = us_structure_finalize(s, &err);
    us_alloc_fail_after(-1);
    done = st == US_OK;
    int ok = done ? s->ncontact == nref : st == US_ERR_NOMEM;
    failures += !done;
    us_structure_free(s);
    CHECK(ok);
  }
  CHECK(done && failures > 0);
}

US_TEST_MAIN(T(far_away_changes_nothing), T(tiny_gap_is_a_gap), T(scaled_copies_agree),
             T(reference_piles), T(reference_many_vertices), T(reference_overlap_message),
             T(out_of_memory_comb))
