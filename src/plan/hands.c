/* Plans with hands: assembly with up to H bodies held still at once
 * (docs/planning.md, "Hands", has the model and the proofs).
 *
 * Model. A state is (P, F): the placed bodies P and the held ones F ⊆ P,
 * |F| <= H. Actions: place b (b enters P and F), grab c ∈ P \ F (c enters
 * F), release r ∈ F. A state stands when the bodies of P stand with those
 * of F fixed: the ordinary stability test on a copy of the structure whose
 * bodies in F are marked `fixed` (one workspace per held set, a small
 * cache of them), certificate re-checked as every test's is. Only a
 * release needs a test: placing and grabbing add fixed supports, and a
 * set that stands with F fixed stands with any F' ⊇ F fixed (the same
 * forces balance; fixed bodies need no balance).
 *
 * Exact search (exact_search). Grabs can always wait until just before
 * the next release, so the moves from a standing state (P, F) are
 *   place b ∉ P when |F| < H            -> (P + b, F + b), no test;
 *   grab G ⊆ P \ F, |F ∪ G| <= H, release r ∈ F
 *                                        -> (P, F - r + G), one test.
 * Invariants: every state on the stack stands (tested or reached by
 * place); `seen` holds every state expanded. A state (P, F) is skipped
 * when some seen (P, F') has F' ⊆ F: every move of (P, F) is matched by
 * a move of (P, F') to the same or a smaller held set, so the states
 * reachable from (P, F) are dominated by states reachable from (P, F');
 * the goal (all placed, none held) is dominated only by itself. So a
 * search that ends without the goal and within its budget, with no
 * undecided test, proves that H hands are not enough (docs: Theorem H1).
 *
 * Decoupling. Components of the structure (contact graph of the movable
 * bodies; ground and fixed bodies join nothing) are planned apart: the
 * whole needs the maximum of the components' H (docs: Theorem H2).
 *
 * Constructive search (construct). Place the bodies of a component in a
 * given order; after every placement release held bodies, oldest first,
 * as long as one can go (the rest stands with the others held). The peak
 * number held is an H with a valid plan (every release was tested); it is
 * an upper bound, nothing more. Two orders are tried: along contacts
 * (next the lowest body touching the last placed one: an arch is then
 * built from one springing to the other, leap-frogging with two hands)
 * and lowest first.
 *
 * Auto (hands 0): H = 1 by today's planner (exact, with its cut); then the
 * constructive bound U; then the exact search for H = 2 .. U - 1, stopping
 * at the first H that works (the minimum) or the first budget hit (the H
 * from there up to U - 1 are reported unproven, hands_lower). */
#include "hands.h"
#include "hook.h"
#include "stability/backend.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define HANDS_CACHE 16  /* workspaces kept, one per held set */
#define DOMINANCE_MAX 10 /* held sets up to this size: every subset looked up */
#define RELEASE_TRIES 3  /* constructive: the oldest held bodies tried for release */
#define EXACT_SECONDS 10.0 /* auto without a time limit: the exact phase's time */

typedef struct {
  us_Structure s;   /* shallow copy whose held bodies are fixed */
  us_Body *bodies;
  us_Stability *w;
  us_Bitset held;
  long used;        /* 0: empty slot */
} Fixed;

typedef struct {
  us_Action *a;
  int n, cap;
} Actions;

typedef struct {
  const us_Structure *s;
  const us_PlanSettings *set;
  us_PlanStats *st;
  char *note;
  size_t note_sz;
  double t_start;
  long test_end;             /* the exact search's budget end (0: none) */
  double time_end;           /* the exact phase's deadline (us_now; 0: none) */
  int n;                     /* bodies */
  Fixed cache[HANDS_CACHE];
  long clock;
  us_StabilityResult res;
  us_BitsetSet stable, fallen; /* test memo, key P | F (fallen: not known stable) */
  us_BitsetSet seen;         /* exact search: expanded states */
  us_Bitset key, none;       /* key: 2 * 64 * nwords bits; none: empty held set */
  int *comp, ncomp;          /* comp[i]: component of movable body i, else -1 */
  const us_Plan *one;        /* auto: today's plan for H = 1 (us_plan's, or a
                                proven none from the caller) */
  int exact_only;            /* tests: fixed H by the exact search alone */
  Actions path;              /* actions of the search under way */
} Hands;

/* --------------------------------------------------------- held tests */

static int oom(us_Error *err) {
  us_error_set(err, US_ERR_NOMEM, "out of memory (hands)");
  return -1;
}

static void fixed_clear(Fixed *f) {
  us_stability_free(f->w);
  us_free(f->bodies);
  us_bitset_free(&f->held);
  memset(f, 0, sizeof *f);
}

int us_hands_fixed_copy(const us_Structure *s, const us_Bitset *F, us_Structure *copy,
                        us_Body **bodies) {
  *copy = *s;
  *bodies = us_malloc((size_t)s->nbody * sizeof(us_Body) + 1);
  if (!*bodies) return -1;
  memcpy(*bodies, s->bodies, (size_t)s->nbody * sizeof(us_Body));
  for (int i = 0; i < s->nbody; i++)
    if (us_bitset_get(F, i)) (*bodies)[i].fixed = 1;
  copy->bodies = *bodies;
  return 0;
}

/* A workspace on a copy of the structure with the bodies of F fixed. */
static int fixed_make(Hands *h, Fixed *f, const us_Bitset *F, us_Error *err) {
  if (us_hands_fixed_copy(h->s, F, &f->s, &f->bodies) || us_bitset_copy(&f->held, F))
    return oom(err);
  f->w = us_stability_new(&f->s, &h->set->stability, err);
  if (!f->w) return -1;
  /* no deadline inside the solver: the time limit is checked between
     tests (CLP's CPU-time limit, scaled by a share measured since the
     workspace was made, can stop a cached workspace's solve before the
     wall-clock deadline: an error, not a verdict) */
  us_stability_set_skip_forces(f->w, 1);
  return 0;
}

/* The cached workspace of held set F, made when missing (the least
 * recently used one is dropped). */
static Fixed *fixed_for(Hands *h, const us_Bitset *F, us_Error *err) {
  Fixed *victim = &h->cache[0];
  for (int k = 0; k < HANDS_CACHE; k++) {
    Fixed *f = &h->cache[k];
    if (f->used && us_bitset_equal(&f->held, F)) return f->used = ++h->clock, f;
    if (f->used < victim->used) victim = f;
  }
  fixed_clear(victim);
  if (fixed_make(h, victim, F, err)) {
    fixed_clear(victim);
    return NULL;
  }
  victim->used = ++h->clock;
  return victim;
}

/* key = P in the low half, F in the high half. */
static void make_key(us_Bitset *key, const us_Bitset *P, const us_Bitset *F) {
  int nw = P->nwords;
  memcpy(key->w, P->w, (size_t)nw * sizeof(uint64_t));
  memcpy(key->w + nw, F->w, (size_t)nw * sizeof(uint64_t));
}

static int limit_reached(const Hands *h) {
  const us_PlanSettings *set = h->set;
  if (set->max_tests > 0 && h->st->tests >= set->max_tests) return 1;
  if (h->test_end > 0 && h->st->tests >= h->test_end) return 1;
  if (h->time_end > 0 && us_now() >= h->time_end) return 1;
  return set->time_limit > 0 && us_now() - h->t_start >= set->time_limit;
}

static void count_verdict(Hands *h) {
  us_PlanStats *st = h->st;
  st->tests++;
  if (h->res.verdict == US_STABLE) st->stable++;
  else if (h->res.verdict == US_UNSTABLE) st->unstable++;
  else if (st->undecided++ == 0 && h->note)
    snprintf(h->note, h->note_sz, "%s", h->res.note[0] ? h->res.note : "no reason given");
}

/* Do the bodies of P stand with those of F fixed? 1 certified stable, 0
 * not known stable (undecided ones counted), -1 error, -2 limit. */
static int stands(Hands *h, const us_Bitset *P, const us_Bitset *F, us_Error *err) {
  make_key(&h->key, P, F);
  if (us_bitset_set_contains(&h->stable, &h->key)) return 1;
  if (us_bitset_set_contains(&h->fallen, &h->key)) return 0;
  if (limit_reached(h)) return -2;
  Fixed *f = fixed_for(h, F, err);
  if (!f) return -1;
  long timed_out = us_stability_info(f->w)->timed_out;
  if (us_plan_stability_test(f->w, P, &h->res, err)) return -1;
  if (us_stability_info(f->w)->timed_out > timed_out) return -2;
  count_verdict(h);
  int ok = h->res.verdict == US_STABLE;
  if (us_bitset_set_add(ok ? &h->stable : &h->fallen, &h->key) < 0)
    return oom(err);
  return ok;
}

/* ------------------------------------------------------------ actions */

static int push(Actions *p, us_ActionVerb v, int b) {
  if (p->n == p->cap) {
    int ncap = p->cap ? 2 * p->cap : 64;
    us_Action *a = us_realloc(p->a, (size_t)ncap * sizeof *a);
    if (!a) return -1;
    p->a = a;
    p->cap = ncap;
  }
  p->a[p->n++] = (us_Action){v, b};
  return 0;
}

static int append(Actions *dst, const Actions *src) {
  for (int k = 0; k < src->n; k++)
    if (push(dst, src->a[k].verb, src->a[k].body)) return -1;
  return 0;
}

/* Most bodies held at once along an action list. */
static int peak_held(const Actions *p) {
  int held = 0, peak = 0;
  for (int k = 0; k < p->n; k++) {
    held += p->a[k].verb == US_ACTION_RELEASE ? -1 : 1;
    if (held > peak) peak = held;
  }
  return peak;
}

/* ---------------------------------------------------------- components */

/* Components of the movable bodies by their contacts (union-find). */
static int find_root(int *up, int i) {
  while (up[i] != i) i = up[i] = up[up[i]];
  return i;
}

static int components(Hands *h) {
  const us_Structure *s = h->s;
  int *up = us_malloc((size_t)h->n * sizeof(int) + 1);
  h->comp = us_malloc((size_t)h->n * sizeof(int) + 1);
  if (!up || !h->comp) return us_free(up), -1;
  for (int i = 0; i < h->n; i++) up[i] = i;
  for (int c = 0; c < s->ncontact; c++) {
    int a = s->contacts[c].a, b = s->contacts[c].b;
    if (a < 0 || b < 0 || s->bodies[a].fixed || s->bodies[b].fixed) continue;
    up[find_root(up, a)] = find_root(up, b);
  }
  for (int i = 0; i < h->n; i++) h->comp[i] = -1;
  h->ncomp = 0;
  for (int i = 0; i < h->n; i++) {
    if (s->bodies[i].fixed) continue;
    int r = find_root(up, i);
    if (h->comp[r] < 0) h->comp[r] = h->ncomp++;
    h->comp[i] = h->comp[r];
  }
  us_free(up);
  return 0;
}

/* ------------------------------------------------------- constructive */

/* Height of body i along gravity (higher: larger). */
static double height(const us_Structure *s, int i) {
  const double *g = s->gravity, *c = s->bodies[i].com;
  return -(g[0] * c[0] + g[1] * c[1] + g[2] * c[2]);
}

static int touches(const us_Structure *s, int c, int i, const unsigned char *in) {
  int a = s->contacts[c].a, b = s->contacts[c].b;
  int other = a == i ? b : b == i ? a : -2;
  if (other == -2) return 0;
  return other < 0 || s->bodies[other].fixed || in[other];
}

/* The next body of the contact order: the lowest unplaced body of
 * component k touching `last` (or, failing that, touching anything
 * placed, the ground or a fixed body; or the lowest). */
static int next_along(const Hands *h, int k, int last, const unsigned char *placed) {
  const us_Structure *s = h->s;
  int best = -1, rank = -1;
  for (int c = 0; c < s->ncontact; c++)
    for (int side = 0; side < 2; side++) {
      int i = side ? s->contacts[c].b : s->contacts[c].a;
      if (i < 0 || h->comp[i] != k || placed[i] || !touches(s, c, i, placed)) continue;
      int other = side ? s->contacts[c].a : s->contacts[c].b;
      int r = other == last && last >= 0 ? 1 : 0;
      if (best < 0 || r > rank || (r == rank && height(s, i) < height(s, best)))
        best = i, rank = r;
    }
  for (int i = 0; best < 0 && i < h->n; i++)
    if (h->comp[i] == k && !placed[i]) best = i;
  return best;
}

/* Bodies of component k in contact order (along = 1) or lowest first. */
static int make_order(const Hands *h, int k, int along, int *ord) {
  unsigned char *placed = us_calloc((size_t)h->n + 1, 1);
  if (!placed) return -1;
  int m = 0, last = -1;
  for (int i = 0; i < h->n; i++) m += h->comp[i] == k;
  for (int q = 0; q < m; q++) {
    int b = along ? next_along(h, k, last, placed) : -1;
    for (int i = 0; b < 0 && i < h->n; i++)
      if (h->comp[i] == k && !placed[i]) b = i;
    for (int i = 0; !along && i < h->n; i++)
      if (h->comp[i] == k && !placed[i] && height(h->s, i) < height(h->s, b)) b = i;
    placed[b] = 1;
    ord[q] = last = b;
  }
  us_free(placed);
  return m;
}

/* Release held bodies, oldest first, while one of the RELEASE_TRIES
 * oldest can go (trying them all costs a test per held body after every
 * placement: on the dome, 3D tests of 100 bodies). held[0..*nh) by age;
 * F their set. 0 done, < 0 error or limit. */
static int release_eagerly(Hands *h, us_Bitset *P, us_Bitset *F, int *held, int *nh,
                           Actions *out, us_Error *err) {
  for (int q = 0; q < *nh && q < RELEASE_TRIES;) {
    us_bitset_clear(F, held[q]);
    int r = stands(h, P, F, err);
    if (r < 0) return r;
    if (!r) {
      us_bitset_set(F, held[q++]);
      continue;
    }
    if (push(out, US_ACTION_RELEASE, held[q]))
      return oom(err);
    memmove(held + q, held + q + 1, (size_t)(*nh - q - 1) * sizeof(int));
    (*nh)--;
    q = 0; /* a release may free an older body: from the oldest again */
  }
  return 0;
}

/* Build ord[0..m) with eager releases. 1 a plan (in out), 0 more than cap
 * bodies held at some point or stuck at the end, < 0 error or limit. */
static int construct(Hands *h, const int *ord, int m, int cap, Actions *out, us_Error *err) {
  us_Bitset P = {0}, F = {0};
  int *held = us_malloc((size_t)m * sizeof(int) + 1);
  int r = !held || us_bitset_init(&P, h->n) || us_bitset_init(&F, h->n) ? -1 : 0;
  if (r) oom(err);
  int nh = 0;
  out->n = 0;
  for (int q = 0; !r && q < m; q++) {
    if (nh >= cap) break;
    us_bitset_set(&P, ord[q]);
    us_bitset_set(&F, ord[q]);
    held[nh++] = ord[q];
    if (push(out, US_ACTION_PLACE, ord[q]))
      r = oom(err);
    if (!r) r = release_eagerly(h, &P, &F, held, &nh, out, err);
    if (!r && q == m - 1) r = nh == 0;
  }
  us_free(held);
  us_bitset_free(&P);
  us_bitset_free(&F);
  return r;
}

/* The best of the two orders for component k with at most cap hands: its
 * H (0: none within cap), plan in out; < 0 error or limit. */
static int construct_best(Hands *h, int k, int cap, Actions *out, us_Error *err) {
  int *ord = us_malloc((size_t)h->n * sizeof(int) + 1);
  Actions tmp = {0};
  if (!ord) return oom(err);
  int best = 0, r = 0;
  for (int along = 1; along >= 0 && r >= 0; along--) {
    int m = make_order(h, k, along, ord);
    if (m < 0) r = oom(err);
    if (r >= 0) r = construct(h, ord, m, best ? best - 1 : cap, &tmp, err);
    if (r == 1) {
      best = peak_held(&tmp);
      out->n = 0;
      if (append(out, &tmp)) r = oom(err);
    }
  }
  us_free(ord);
  us_free(tmp.a);
  return r < 0 ? r : best;
}

/* --------------------------------------------------------------- exact */

typedef struct {
  const us_Bitset *C; /* the component */
  int H;
  us_Bitset *P, *F;
  int nF;
  int *cand, ncand;   /* bodies of C, lowest first */
  int *grab;          /* [H] the grab set under construction */
} Exact;

/* Has some subset of F (with P) been expanded? (Only F itself when F is
 * large: fewer skips, still sound.) */
static int dominated(Hands *h, const us_Bitset *P, us_Bitset *F, int nF, const int *fl) {
  if (nF > DOMINANCE_MAX) {
    make_key(&h->key, P, F);
    return us_bitset_set_contains(&h->seen, &h->key);
  }
  int found = 0;
  for (unsigned mask = 0; !found && mask < (1u << nF); mask++) {
    for (int j = 0; j < nF; j++)
      if (mask >> j & 1) us_bitset_clear(F, fl[j]);
    make_key(&h->key, P, F);
    found = us_bitset_set_contains(&h->seen, &h->key);
    for (int j = 0; j < nF; j++) us_bitset_set(F, fl[j]);
  }
  return found;
}

/* The bodies of F, listed. */
static int list_of(const us_Bitset *F, int n, int *fl) {
  int m = 0;
  for (int i = 0; i < n; i++)
    if (us_bitset_get(F, i)) fl[m++] = i;
  return m;
}

static int dfs(Hands *h, Exact *x, us_Error *err);

/* Is the state (P, F) dominated by an expanded one? */
static int skip_state(Hands *h, Exact *x) {
  int fl[64];
  int nF = list_of(x->F, h->n, fl);
  return dominated(h, x->P, x->F, nF, fl);
}

/* Release r after grabbing grab[0..ng): F - r + G. */
static int try_release(Hands *h, Exact *x, int r, int ng, us_Error *err) {
  for (int j = 0; j < ng; j++) us_bitset_set(x->F, x->grab[j]);
  us_bitset_clear(x->F, r);
  int nf0 = x->nF, n0 = h->path.n, res = 0;
  x->nF += ng - 1;
  if (!skip_state(h, x)) res = stands(h, x->P, x->F, err);
  for (int j = 0; res == 1 && j < ng; j++)
    if (push(&h->path, US_ACTION_GRAB, x->grab[j])) res = -1;
  if (res == 1 && push(&h->path, US_ACTION_RELEASE, r)) res = -1;
  if (res == -1 && !err->code) us_error_set(err, US_ERR_NOMEM, "out of memory (hands)");
  if (res == 1) res = dfs(h, x, err);
  if (res != 1) h->path.n = n0;
  x->nF = nf0;
  us_bitset_set(x->F, r);
  for (int j = 0; j < ng; j++) us_bitset_clear(x->F, x->grab[j]);
  return res;
}

/* Every grab set G ⊆ P \ F of size `left` more (bodies after index
 * `from` of cand), each followed by every release. */
static int grabs(Hands *h, Exact *x, int from, int ng, int left, const int *fl, int nF,
                 us_Error *err) {
  if (left == 0) {
    for (int q = 0; q < nF; q++) {
      int r = try_release(h, x, fl[q], ng, err);
      if (r) return r;
    }
    return 0;
  }
  for (int q = from; q < x->ncand; q++) {
    int g = x->cand[q];
    if (!us_bitset_get(x->P, g) || us_bitset_get(x->F, g)) continue;
    x->grab[ng] = g;
    int r = grabs(h, x, q + 1, ng + 1, left - 1, fl, nF, err);
    if (r) return r;
  }
  return 0;
}

static int place(Hands *h, Exact *x, int b, us_Error *err) {
  us_bitset_set(x->P, b);
  us_bitset_set(x->F, b);
  x->nF++;
  int n0 = h->path.n;
  int r = skip_state(h, x) ? 0 : push(&h->path, US_ACTION_PLACE, b) ? -1 : dfs(h, x, err);
  if (r == -1 && !err->code) us_error_set(err, US_ERR_NOMEM, "out of memory (hands)");
  if (r != 1) h->path.n = n0;
  x->nF--;
  us_bitset_clear(x->P, b);
  us_bitset_clear(x->F, b);
  return r;
}

/* Expand the standing state (P, F): 1 goal reached (path holds the
 * actions), 0 not from here, < 0 error or limit. */
static int dfs(Hands *h, Exact *x, us_Error *err) {
  if (x->nF == 0 && us_bitset_equal(x->P, x->C)) return 1;
  make_key(&h->key, x->P, x->F);
  if (us_bitset_set_add(&h->seen, &h->key) < 0)
    return oom(err);
  h->st->nodes_expanded++;
  if (limit_reached(h)) return -2;
  int fl[64];
  int nF = list_of(x->F, h->n, fl);
  for (int extra = 0; nF > 0 && extra <= x->H - nF; extra++) {
    int r = grabs(h, x, 0, 0, extra, fl, nF, err);
    if (r) return r;
  }
  for (int q = 0; x->nF < x->H && q < x->ncand; q++) {
    if (us_bitset_get(x->P, x->cand[q])) continue;
    int r = place(h, x, x->cand[q], err);
    if (r) return r;
  }
  return 0;
}

/* Bodies of component k, lowest first; count returned. */
static int comp_bodies(const Hands *h, int k, int *cand, us_Bitset *C) {
  int m = 0;
  for (int i = 0; i < h->n; i++)
    if (h->comp[i] == k) cand[m++] = i, us_bitset_set(C, i);
  for (int a = 1; a < m; a++) /* insertion sort by height */
    for (int b = a; b > 0 && height(h->s, cand[b]) < height(h->s, cand[b - 1]); b--) {
      int t = cand[b];
      cand[b] = cand[b - 1], cand[b - 1] = t;
    }
  return m;
}

/* Exhaustive search for component k with H hands: 1 plan (in out), 0
 * none (a proof when no test was undecided meanwhile: see *proof), < 0
 * error or limit (the budget is max_exact_tests tests). */
static int exact_search(Hands *h, int k, int H, Actions *out, int *proof, us_Error *err) {
  us_Bitset C = {0}, P = {0}, F = {0};
  int *cand = us_malloc((size_t)h->n * sizeof(int) + 1), grab[64];
  int r = !cand || us_bitset_init(&C, h->n) || us_bitset_init(&P, h->n) ||
                  us_bitset_init(&F, h->n) || us_bitset_set_init(&h->seen, h->key.nbits)
              ? -1 : 0;
  long undecided = h->st->undecided;
  if (r) us_error_set(err, US_ERR_NOMEM, "out of memory (hands)");
  if (!r) {
    Exact x = {&C, H, &P, &F, 0, cand, comp_bodies(h, k, cand, &C), grab};
    long budget = h->set->max_exact_tests;
    h->test_end = budget > 0 ? h->st->tests + budget : 0;
    h->path.n = 0;
    h->st->exhaustive++;
    r = H > 64 ? 0 : dfs(h, &x, err);
    h->test_end = 0;
    h->st->memo_bytes += us_bitset_set_bytes(&h->seen);
  }
  if (r == 1) {
    out->n = 0;
    if (append(out, &h->path)) r = oom(err);
  }
  *proof = r == 0 && h->st->undecided == undecided;
  us_bitset_set_free(&h->seen);
  us_bitset_free(&C);
  us_bitset_free(&P);
  us_bitset_free(&F);
  us_free(cand);
  return r;
}

/* ------------------------------------------------------------- driver */

static void hands_free(Hands *h) {
  for (int k = 0; k < HANDS_CACHE; k++) fixed_clear(&h->cache[k]);
  us_stability_result_free(&h->res);
  us_bitset_set_free(&h->stable);
  us_bitset_set_free(&h->fallen);
  us_bitset_free(&h->key);
  us_bitset_free(&h->none);
  us_free(h->comp);
  us_free(h->path.a);
}

static us_Status hands_init(Hands *h, const us_Structure *s, const us_PlanSettings *set,
                            us_Plan *out, us_Error *err) {
  memset(h, 0, sizeof *h);
  h->s = s;
  h->set = set;
  h->st = &out->stats;
  h->note = out->note;
  h->note_sz = sizeof out->note;
  h->t_start = us_now();
  h->n = s->nbody;
  int nw = (s->nbody + 63) / 64;
  if (us_bitset_init(&h->key, 2 * 64 * (nw ? nw : 1)) || us_bitset_init(&h->none, s->nbody) ||
      us_bitset_set_init(&h->stable, h->key.nbits) ||
      us_bitset_set_init(&h->fallen, h->key.nbits) || components(h))
    return us_error_set(err, US_ERR_NOMEM, "out of memory (hands)");
  return US_OK;
}

/* Per component: its best plan so far and its H (0: none yet). */
typedef struct {
  Actions plan;
  int H;
} Part;

/* The removal order (the placements reversed) and the actions into out. */
static us_Status fill_plan(Hands *h, Part *parts, us_Plan *out, us_Error *err) {
  Actions all = {0};
  int ok = 1;
  for (int k = 0; k < h->ncomp && ok; k++) ok = !append(&all, &parts[k].plan);
  out->order = us_malloc((size_t)h->n * sizeof(int) + 1);
  if (!ok || !out->order) {
    us_free(all.a);
    return us_error_set(err, US_ERR_NOMEM, "out of memory (hands)");
  }
  for (int k = all.n - 1; k >= 0; k--)
    if (all.a[k].verb == US_ACTION_PLACE) out->order[out->nsteps++] = all.a[k].body;
  out->ngroups = out->nsteps;
  out->max_group = 1;
  out->actions = all.a;
  out->nactions = all.n;
  out->hands = peak_held(&all);
  return US_OK;
}

/* H = 1 by today's planner: its status; a found order into parts. */
static int one_hand(Hands *h, Part *parts, us_Error *err) {
  const us_Plan *p1 = h->one;
  if (!p1) return US_PLAN_LIMIT; /* not planned: nothing known */
  us_PlanStats *st = h->st;
  st->tests += p1->stats.tests, st->stable += p1->stats.stable;
  st->unstable += p1->stats.unstable, st->undecided += p1->stats.undecided;
  st->cuts += p1->stats.cuts, st->held_tests += p1->stats.held_tests;
  if (p1->stats.undecided && !h->note[0]) snprintf(h->note, h->note_sz, "%s", p1->note);
  int r = (int)p1->status;
  for (int q = p1->nsteps - 1; r == US_PLAN_FOUND && q >= 0; q--) {
    Actions *a = &parts[h->comp[p1->order[q]]].plan;
    if (push(a, US_ACTION_PLACE, p1->order[q]) || push(a, US_ACTION_RELEASE, p1->order[q]))
      r = oom(err);
  }
  for (int k = 0; r == US_PLAN_FOUND && k < h->ncomp; k++) parts[k].H = 1;
  return r;
}

/* The exact searches for H = 2, 3, ... below the constructive bound of
 * every component; *lower: the smallest H not proven impossible. A
 * status (found with parts' H, limit when cut), or < 0. */
static int auto_exact(Hands *h, Part *parts, int *lower, us_Error *err) {
  for (int H = *lower > 2 ? *lower : 2;; H++) {
    int all = 1, none = 0;
    for (int k = 0; k < h->ncomp && !none; k++) {
      if (parts[k].H && parts[k].H <= H) continue;
      int proof, r = exact_search(h, k, H, &parts[k].plan, &proof, err);
      if (r == -2 || (r == 0 && !proof)) return US_PLAN_LIMIT;
      if (r < 0) return r;
      if (r == 1) parts[k].H = H;
      else none = 1, all = 0;
    }
    if (none) *lower = H + 1;
    if (all) return US_PLAN_FOUND;
  }
}

/* hands 0: the smallest H (proven or bounded). A status or < 0. */
static int run_auto(Hands *h, Part *parts, int *lower, us_Error *err) {
  int r = one_hand(h, parts, err);
  *lower = r == US_PLAN_NONE ? 2 : 1;
  if (r < 0 || r == US_PLAN_FOUND || r == US_PLAN_UNSTABLE) return r;
  int ub = 0;
  for (int k = 0; k < h->ncomp; k++) {
    int H = construct_best(h, k, h->n + 1, &parts[k].plan, err);
    if (H < 0) return H == -2 ? US_PLAN_LIMIT : H;
    if (H == 0) return US_PLAN_UNDECIDED; /* stuck at the end: an undecided test */
    parts[k].H = H;
    if (H > ub) ub = H;
  }
  if (ub <= *lower) return US_PLAN_FOUND;
  if (h->set->time_limit <= 0) h->time_end = us_now() + EXACT_SECONDS;
  int e = auto_exact(h, parts, lower, err);
  h->time_end = 0;
  return e == US_PLAN_LIMIT ? US_PLAN_FOUND : e; /* the constructive plans stand */
}

/* hands H >= 2: a plan for every component, or a proof that one has none.
 * *failed: the component without a plan. A status or < 0. */
static int run_fixed(Hands *h, Part *parts, int H, int *failed, us_Error *err) {
  for (int k = 0; k < h->ncomp; k++) {
    int c = h->exact_only ? 0 : construct_best(h, k, H, &parts[k].plan, err);
    if (c < 0) return c == -2 ? US_PLAN_LIMIT : c;
    if (c > 0) continue;
    int proof, r = exact_search(h, k, H, &parts[k].plan, &proof, err);
    if (r == -2) return US_PLAN_LIMIT;
    if (r < 0) return r;
    if (r == 0) {
      *failed = k;
      return proof ? US_PLAN_NONE : US_PLAN_UNDECIDED;
    }
  }
  return US_PLAN_FOUND;
}

/* The bodies of component k as the plan's blocked list. */
static us_Status name_blocked(Hands *h, int k, us_Plan *out, us_Error *err) {
  out->blocked = us_malloc((size_t)h->n * sizeof(int) + 1);
  if (!out->blocked) return us_error_set(err, US_ERR_NOMEM, "out of memory (hands)");
  for (int i = 0; i < h->n; i++)
    if (h->comp[i] == k) out->blocked[out->nblocked++] = i;
  return US_OK;
}

/* The full structure's test (every plan ends with it standing alone). */
static int full_stands(Hands *h, us_Error *err) {
  us_Bitset all = {0};
  if (us_structure_movable_set(h->s, &all))
    return oom(err);
  int r = stands(h, &all, &h->none, err);
  us_bitset_free(&all);
  return r;
}

/* dst = src (dim forces per contact). */
static int forces_copy(us_Forces *dst, const us_Forces *src, int dim) {
  int n = src->ncontact;
  dst->contact = us_malloc((size_t)(n > 0 ? n : 1) * sizeof(int));
  dst->f = us_malloc((size_t)(n > 0 ? n : 1) * (size_t)dim * sizeof(double));
  if (!dst->contact || !dst->f) return -1;
  if (n > 0) memcpy(dst->contact, src->contact, (size_t)n * sizeof(int));
  if (n > 0) memcpy(dst->f, src->f, (size_t)n * (size_t)dim * sizeof(double));
  dst->ncontact = dst->cap = n;
  return 0;
}

/* Release k's certificate: the placed bodies P with the held ones F
 * fixed, tested again with forces kept (a fresh workspace). */
static int release_cert(Hands *h, const us_Bitset *P, const us_Bitset *F, us_Forces *out,
                        us_Error *err) {
  us_Structure copy;
  us_Body *bodies;
  if (us_hands_fixed_copy(h->s, F, &copy, &bodies)) return oom(err);
  us_Stability *w = us_stability_new(&copy, &h->set->stability, err);
  int r = w ? 0 : -1;
  if (w) us_stability_set_skip_forces(w, 0);
  if (!r && us_plan_stability_test(w, P, &h->res, err)) r = -1;
  if (!r) count_verdict(h);
  if (!r && h->res.verdict != US_STABLE) {
    us_error_set(err, US_ERR_SOLVER, "hands: a release of the plan did not test stable again "
                 "with forces (%s)", h->res.note);
    r = -1;
  }
  if (!r && forces_copy(out, &h->res.forces, h->s->dim)) r = oom(err);
  us_stability_free(w);
  us_free(bodies);
  return r;
}

/* Certificates of every release of out's actions. */
static int collect_certs(Hands *h, us_Plan *out, us_Error *err) {
  us_Bitset P = {0}, F = {0};
  out->release_certs = us_calloc((size_t)out->nactions + 1, sizeof(us_Forces));
  int r = !out->release_certs || us_bitset_init(&P, h->n) || us_bitset_init(&F, h->n) ? oom(err) : 0;
  for (int k = 0; !r && k < out->nactions; k++) {
    const us_Action *a = &out->actions[k];
    if (a->verb == US_ACTION_PLACE) us_bitset_set(&P, a->body);
    if (a->verb != US_ACTION_RELEASE) us_bitset_set(&F, a->body);
    if (a->verb != US_ACTION_RELEASE) continue;
    us_bitset_clear(&F, a->body);
    r = release_cert(h, &P, &F, &out->release_certs[k], err);
  }
  us_bitset_free(&P);
  us_bitset_free(&F);
  return r;
}

static int run(Hands *h, Part *parts, us_Plan *out, us_Error *err) {
  int full = full_stands(h, err), failed = -1, lower = h->set->hands;
  if (full <= 0) return full == -2 ? US_PLAN_LIMIT : full < 0 ? full : US_PLAN_UNSTABLE;
  int r = h->set->hands == 0 ? run_auto(h, parts, &lower, err)
                             : run_fixed(h, parts, h->set->hands, &failed, err);
  if (r == US_PLAN_FOUND && fill_plan(h, parts, out, err)) return -1;
  if (r == US_PLAN_FOUND && h->set->certificates && collect_certs(h, out, err)) return -1;
  out->hands_lower = h->set->hands ? 1 : lower; /* a fixed H proves nothing below it */
  if (r == US_PLAN_NONE) out->hands = h->set->hands, out->hands_lower = h->set->hands + 1;
  if (r == US_PLAN_NONE && name_blocked(h, failed, out, err)) return -1;
  return r;
}

/* What this file put into out, freed (on an error; us_plan_free is
 * plan.c's, which calls this file). */
static void drop_plan(us_Plan *out) {
  for (int k = 0; out->release_certs && k < out->nactions; k++)
    us_forces_free(&out->release_certs[k]);
  us_free(out->release_certs);
  us_free(out->actions);
  us_free(out->order);
  us_free(out->blocked);
  out->release_certs = NULL, out->actions = NULL;
  out->order = out->blocked = NULL;
  out->nactions = out->nsteps = out->ngroups = out->nblocked = 0;
}

static us_Status plan_hands(const us_Structure *s, const us_PlanSettings *set,
                            const us_Plan *one, int exact_only, us_Plan *out, us_Error *err) {
  if (set->hands < 0 || set->hands > 64 || (exact_only && set->hands < 1))
    return us_error_set(err, US_ERR_USAGE, "plan settings: hands must be 0 (auto) to 64, got %d",
                        set->hands);
  if (set->search != US_SEARCH_ASSEMBLE || set->removal != US_REMOVAL_ANY || set->max_group != 1)
    return us_error_set(err, US_ERR_USAGE, "plans with hands use the assemble search, removal "
                        "any and steps of one body");
  Hands h;
  Part *parts = NULL;
  us_Status st = hands_init(&h, s, set, out, err);
  h.one = one;
  h.exact_only = exact_only;
  if (!st && !(parts = us_calloc((size_t)h.ncomp + 1, sizeof *parts)))
    st = us_error_set(err, US_ERR_NOMEM, "out of memory (hands)");
  int r = st ? -1 : run(&h, parts, out, err);
  if (!st && r < 0) st = err->code ? err->code : US_ERR_SOLVER;
  if (!st) out->status = (us_PlanStatus)r;
  if (!st && r == US_PLAN_UNSTABLE && out->stats.undecided) out->status = US_PLAN_UNDECIDED;
  for (int k = 0; parts && k < h.ncomp; k++) us_free(parts[k].plan.a);
  us_free(parts);
  hands_free(&h);
  out->stats.time_total = us_now() - h.t_start;
  if (st) drop_plan(out);
  return st;
}

us_Status us_plan_hands(const us_Structure *s, const us_PlanSettings *set, const us_Plan *one,
                        us_Plan *out, us_Error *err) {
  return plan_hands(s, set, one, 0, out, err);
}

us_Status us_plan_hands_after_none(const us_Structure *s, const us_PlanSettings *set,
                                   us_Plan *out, us_Error *err) {
  us_Plan none;
  memset(&none, 0, sizeof none);
  none.status = US_PLAN_NONE;
  memset(out, 0, sizeof *out);
  return plan_hands(s, set, &none, 0, out, err);
}

us_Status us_plan_hands_exact(const us_Structure *s, const us_PlanSettings *set, us_Plan *out,
                              us_Error *err) {
  memset(out, 0, sizeof *out);
  return plan_hands(s, set, NULL, 1, out, err);
}
