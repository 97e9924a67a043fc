/* Exact local stability tests: a test costs what the change costs.
 *
 * State: the base B, the last sub-assembly proven stable, with forces
 * fbase (normalized, dim per structure contact) and the plumb memo's
 * pending loads (plumb.h, lazy routing). Invariant: fbase plus the pending
 * loads pushed down their memoised lines is zero on every contact that is
 * not active in B and holds every body of B in equilibrium inside the
 * cones (each body's residual passed the check when its forces last
 * changed, each line when it was memoised; a body's residual depends only
 * on the forces of its own contacts); every line a pending load reaches
 * rests on bodies of B. Whatever reads fbase (region LPs, removals, full
 * solves, forces handed out) first pushes the pending loads down.
 *
 * A test of S (movable bits): added = S \ B, removed = B \ S. The bodies
 * whose equilibrium changes are the seeds D: the added bodies and the
 * bodies of S that touched a removed body. Removed bodies that touch no
 * body of S change nothing (their contacts with S do not exist), so a
 * planner that tests one component after another stays local. Then, for
 * regions R ⊇ D of growing size:
 *   level 0:  R = D and the present bodies touching it (D alone past
 *             90 rows, and in 3D, where it runs only while it finds
 *             proofs), the support LP only (does some body of D fall,
 *             or push a neighbour over, even if everything further away
 *             is held still?);
 *   level 1:  R = D plus its supporters under the footprint of the change
 *             (bodies below a seed whose horizontal extent overlaps the
 *             changed bodies', followed down to the ground): the path the
 *             weight of the change takes;
 *   level 1b: the bodies resting on a seed (a counterweight on an added
 *             cantilever) and their supporters under their own footprint,
 *             followed down: the path of the load the counterweight moves
 *             (first, when a present body rests on a seed);
 *   level 1c: (2D) the supporters under R's own extent, followed down;
 *   level 2:  every supporter of R, followed down (the load's cone);
 *   level k:  rings of neighbours, until R at least doubled;
 * at each level the fixed LP (feasible: stable) and the support LP
 * (infeasible: unstable). When R passes the limit (a quarter of S; in 2D
 * 500 bodies) the test is handed back for the full system, which then
 * solves only the components of S that changed when bodies were only
 * added (us_local_changed_part), in 2D from the base's forces
 * (us_local_hint, the sparse simplex); when a ring adds
 * nothing, R is a union of components of S and the two LPs coincide, so
 * the loop always ends with a verdict or a hand-back.
 *
 * Stable: the merged forces (base values off R's free contacts, the LP's
 * on them) are re-checked on R's bodies by the independent check
 * (certificate.c): by the invariant, that proves all of S. A failed
 * re-check hands the test back. The base becomes S (or B ∪ S when no
 * removed body touches S: then B \ S and S share no contact).
 *
 * Cost per test: O(|added| + |removed touching S| * degree) to find D,
 * then LPs over R only; the full structure is never swept, except to
 * report forces (us_local_forces) when a caller wants them. The diff B xor
 * S is kept as lists that follow every change of S (us_local_toggle,
 * O(degree): each body's count of contacts with S) and every move of the
 * base, with the list of the bodies of B \ S that touch S, the count of S
 * and of the memo's bodies absent from S, so no test scans a bitset or
 * the bodies of B \ S that touch nothing (the other components an
 * assembly by components leaves in B).
 */
#include "local.h"

#include "certificate.h"
#include "lp_gen.h"
#include "lp_sparse.h"
#include "plumb.h"
#include "model/massprops.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LOCAL_MIN_BODIES 1    /* default: smaller sub-assemblies go to the full system */
#define LOCAL_GLOBAL_SHARE 0.25 /* 3D: a region past this share of S: the full system
                                  (0.5 and 0.75 measured slower on random stacks;
                                  1/16 and 1/32 2.4-3x slower on stacks of 876
                                  and 9,352 blocks: the full system then takes
                                  the tests a level-1 column settles) */
#define LOCAL_REGION_BODIES 500 /* 2D: regions up to this many bodies (1,500
                                  rows, the sparse simplex's) whatever their
                                  share of S: a component of 1,076 blocks sent
                                  117 tests to the full system at a quarter,
                                  none at 300; two 60 x 60 stacker stacks sent
                                  2 each at 300, none at 500 (docs/local.md) */
#define HINT_SEEDS 128       /* a hand-back of at most this many changed bodies
                                starts from B's forces whatever its size */
#define LEVEL0_ROWS 90        /* 2D level 0 takes the seeds' neighbours up to this;
                                 regions of up to this many rows are never
                                 handed to the full system */
#define SUPPORT_COS 1e-3      /* a contact supports if its push has this much "up" */

/* Whether an optional LP finds proofs often enough to run (pays()). */
typedef struct us_Pays {
  long tries, hits, chances;
} us_Pays;

struct us_Local {
  const us_Structure *s;
  us_StabilitySettings set;
  const us_Backend *be;
  void *bws[2];          /* the support LP's and the fixed LP's (each warm
                            starts from its own previous basis) */
  void *sparse[2];       /* the sparse simplex (lp_sparse.h): support, fixed */
  const void *ray_ws;    /* the workspace of the last support LP */
  const us_Backend *ray_be;
  us_EqSystem eq;
  int dim;
  int *inc_start, *inc;  /* body -> contacts */
  int nax;               /* horizontal axes: 1 in 2D, 2 in 3D */
  double *lo, *hi;       /* [nbody * 2] horizontal extents of each body */
  double up[3];          /* against gravity */
  us_Bitset base;
  us_Bitset part;        /* after a hand-back: the components of S with a seed */
  int npart;             /* their bodies; -1: none kept (us_local_changed_part) */
  int *stack;            /* [nbody] scratch of the components' search */
  int have_base;
  int hint_ok;           /* the last test changed few bodies of its base (or
                            few at all): B's forces start its hand-back
                            (us_local_hint) */
  /* B xor S as two lists, S \ B (alist) and B \ S (rlist): a body is in
     the one its base bit names while it differs, at slot dpos (else -1);
     tlist: the bodies of B \ S that touch S (tcur > 0), at slot tpos */
  int *alist, *rlist, *tlist, na, nr, nt;
  int *dpos, *tpos;
  int *tcur;             /* [nbody] contacts of each body with a body of S */
  int ncur;              /* |S| */
  int dep_absent;        /* bodies of the plumb memo's dep not in S */
  double *fbase;         /* [ncontact * dim] */
  unsigned char *in_r;   /* [nbody] */
  int *reg, nreg;        /* [nbody] the region */
  int *added, *removed, nadd, nrem;
  int touching;          /* some removed body touches S */
  int no_route;          /* the fixed LP starts from fbase as it is (a lever's) */
  int *carry_c, ncarry, cap_carry; /* a failed fixed LP's contacts and where */
  double *carry_f;       /* its phase 1 stopped: the next fixed LP's start */
  int cap_carry_f;
  double foot_lo[2], foot_hi[2]; /* the change's horizontal extent */
  double *f, *saved;     /* LP solution; base values it replaces */
  int cap_f, cap_saved;
  int *list, *slot;      /* mechanism check: contacts of R, body slots (and
                            the re-check's, check_list) */
  double *cacc;          /* the re-check's sums, US_CERT_ACC per body */
  int cap_cacc;
  us_Pays seed_pays;     /* 3D level-0 support LPs: run, and proofs found */
  us_Pays grow_pays;     /* the support LPs of grown levels before the last */
  double mass;           /* movable mass, summed once for the checks */
  us_Plumb plumb;        /* plumb-line load paths (plumb.h) */
  us_ConeSet *cones;     /* 3D: the friction polygons (shared), or NULL */
};

/* ------------------------------------------------------------- set-up */

static int build_incidence(us_Local *L) {
  const us_Structure *s = L->s;
  int n = s->nbody;
  L->inc_start = us_calloc((size_t)n + 1, sizeof(int));
  L->inc = us_malloc((size_t)(2 * s->ncontact + 1) * sizeof(int));
  if (!L->inc_start || !L->inc) return -1;
  for (int c = 0; c < s->ncontact; c++) {
    const us_Contact *k = &s->contacts[c];
    if (k->a >= 0) L->inc_start[k->a + 1]++;
    if (k->b >= 0) L->inc_start[k->b + 1]++;
  }
  for (int i = 0; i < n; i++) L->inc_start[i + 1] += L->inc_start[i];
  int *fill = us_malloc((size_t)(n > 0 ? n : 1) * sizeof(int));
  if (!fill) return -1;
  memcpy(fill, L->inc_start, (size_t)n * sizeof(int));
  for (int c = 0; c < s->ncontact; c++) {
    const us_Contact *k = &s->contacts[c];
    if (k->a >= 0) L->inc[fill[k->a]++] = c;
    if (k->b >= 0) L->inc[fill[k->b]++] = c;
  }
  us_free(fill);
  return 0;
}

/* Unit vector "up": against gravity; +y, or +z in 3D, without gravity. */
static void measure_up(us_Local *L) {
  const us_Structure *s = L->s;
  double g = us_gravity_norm(s->gravity);
  for (int j = 0; j < 3; j++) L->up[j] = g > 0 ? -s->gravity[j] / g : 0.0;
  if (!(g > 0)) L->up[s->dim == 3 ? 2 : 1] = 1.0;
  if (s->dim == 2) L->up[2] = 0.0;
}

static void widen(const us_Local *L, double *lo, double *hi, const double *p) {
  double x[2];
  us_plumb_horizontal(&L->plumb, p, x);
  for (int a = 0; a < L->nax; a++) lo[a] = US_MIN(lo[a], x[a]), hi[a] = US_MAX(hi[a], x[a]);
}

/* Extent of every body along the horizontal axes of the plumb lines'
 * frame (its vertices, all parts in 3D, and its centre for point bodies). */
static void measure_extents(us_Local *L) {
  const us_Structure *s = L->s;
  L->nax = L->plumb.nax;
  for (int i = 0; i < s->nbody; i++) {
    const us_Body *b = &s->bodies[i];
    double *lo = L->lo + 2 * (size_t)i, *hi = L->hi + 2 * (size_t)i;
    lo[0] = lo[1] = INFINITY, hi[0] = hi[1] = -INFINITY;
    widen(L, lo, hi, b->com);
    for (int k = 0; k < b->nvert && s->dim == 2; k++) {
      double p[3] = {b->verts[2 * k], b->verts[2 * k + 1], 0.0};
      widen(L, lo, hi, p);
    }
    for (int q = 0; q < b->npart && s->dim == 3; q++)
      for (int k = 0; k < b->parts[q].nvert; k++) widen(L, lo, hi, b->parts[q].verts + 3 * k);
  }
}

void us_local_free(us_Local *L) {
  if (!L) return;
  for (int k = 0; k < 2; k++)
    if (L->bws[k]) L->be->destroy(L->bws[k]);
  for (int k = 0; k < 2; k++)
    if (L->sparse[k]) us_backend_sparse.destroy(L->sparse[k]);
  us_eq_free(&L->eq);
  us_free(L->inc_start);
  us_free(L->inc);
  us_free(L->lo);
  us_free(L->hi);
  us_bitset_free(&L->base);
  us_bitset_free(&L->part);
  us_free(L->stack);
  us_free(L->alist);
  us_free(L->rlist);
  us_free(L->tlist);
  us_free(L->dpos);
  us_free(L->tpos);
  us_free(L->tcur);
  us_free(L->fbase);
  us_free(L->in_r);
  us_free(L->reg);
  us_free(L->added);
  us_free(L->removed);
  us_free(L->list);
  us_free(L->slot);
  us_free(L->f);
  us_free(L->saved);
  us_free(L->carry_c);
  us_free(L->cacc);
  us_free(L->carry_f);
  us_plumb_free(&L->plumb);
  us_free(L);
}

us_Local *us_local_new(const us_Structure *s, const us_StabilitySettings *set,
                       const us_Backend *be, us_ConeSet *cones, us_Error *err) {
  us_Local *L = us_calloc(1, sizeof *L);
  if (!L) return us_error_set(err, US_ERR_NOMEM, "out of memory (local tests)"), NULL;
  L->s = s;
  L->set = *set;
  L->be = be;
  L->dim = s->dim;
  size_t nb = (size_t)(s->nbody > 0 ? s->nbody : 1);
  size_t nc = (size_t)(s->ncontact > 0 ? s->ncontact : 1) * (size_t)s->dim;
  L->lo = us_malloc(2 * nb * sizeof(double));
  L->hi = us_malloc(2 * nb * sizeof(double));
  L->fbase = us_calloc(nc, sizeof(double));
  L->in_r = us_calloc(nb, 1);
  L->reg = us_malloc(nb * sizeof(int));
  L->added = us_malloc(nb * sizeof(int));
  L->removed = us_malloc(nb * sizeof(int));
  L->list = us_malloc((size_t)(2 * s->ncontact + 1) * sizeof(int));
  L->slot = us_malloc(nb * sizeof(int));
  L->alist = us_malloc(nb * sizeof(int));
  L->rlist = us_malloc(nb * sizeof(int));
  L->tlist = us_malloc(nb * sizeof(int));
  L->dpos = us_malloc(nb * sizeof(int));
  L->tpos = us_malloc(nb * sizeof(int));
  L->tcur = us_calloc(nb, sizeof(int));
  for (size_t i = 0; L->slot && i < nb; i++) L->slot[i] = -1;
  for (size_t i = 0; L->dpos && i < nb; i++) L->dpos[i] = -1;
  for (size_t i = 0; L->tpos && i < nb; i++) L->tpos[i] = -1;
  int bad = !L->list || !L->slot || !L->lo || !L->hi || !L->fbase || !L->in_r || !L->reg ||
            !L->alist || !L->rlist || !L->tlist || !L->dpos || !L->tpos || !L->tcur ||
            !L->added || !L->removed || build_incidence(L) || us_eq_init(&L->eq, s) || us_bitset_init(&L->base, s->nbody);
  if (bad) {
    us_local_free(L);
    return us_error_set(err, US_ERR_NOMEM, "out of memory (local tests)"), NULL;
  }
  L->cones = cones;
  L->eq.cones = cones;
  measure_up(L);
  L->mass = us_movable_mass(s);
  if (us_plumb_init(&L->plumb, s, L->inc_start, L->inc, L->up, L->eq.mass_total)) {
    us_local_free(L);
    return us_error_set(err, US_ERR_NOMEM, "out of memory (local tests)"), NULL;
  }
  measure_extents(L);
  for (int k = 0; k < 2; k++) {
    L->bws[k] = be->create(s, set, err);
    if (!L->bws[k]) {
      us_local_free(L);
      return NULL;
    }
  }
  for (int k = 0; k < 2; k++) L->sparse[k] = us_backend_sparse.create(s, set, err);
  if (!L->sparse[0] || !L->sparse[1]) {
    us_local_free(L);
    return NULL;
  }
  return L;
}

void us_local_set_deadline(us_Local *L, double deadline) {
  if (L && L->be->set_deadline)
    for (int k = 0; k < 2; k++) L->be->set_deadline(L->bws[k], deadline);
}

static void memo_flush(us_Local *L);

void us_local_forget(us_Local *L) {
  L->have_base = 0;
  memo_flush(L);
}

/* ---------------------------------------------------------------- base */

/* The plumb memo emptied: no body of it is absent. */
static void memo_flush(us_Local *L) {
  us_plumb_flush(&L->plumb);
  L->dep_absent = 0;
}

/* Body i into list `list` (slots in pos), or out of it. */
static void list_flip(int *list, int *n, int *pos, int i) {
  int q = pos[i];
  if (q < 0) {
    pos[i] = *n;
    list[(*n)++] = i;
    return;
  }
  int last = list[--*n];
  list[q] = last;
  pos[last] = q;
  pos[i] = -1;
}

/* Body r into tlist, or out of it, as it now is or is not a body of
 * B \ S that touches S. */
static void t_update(us_Local *L, const us_Bitset *cur, int r) {
  int want = L->have_base && L->dpos[r] >= 0 && !us_bitset_get(cur, r) && L->tcur[r] > 0;
  if (want != (L->tpos[r] >= 0)) list_flip(L->tlist, &L->nt, L->tpos, r);
}

/* Body i into the diff (it differs from B now), or out of it: its list
 * is the one its base bit names. */
static void d_toggle(us_Local *L, int i) {
  if (us_bitset_get(&L->base, i)) list_flip(L->rlist, &L->nr, L->dpos, i);
  else list_flip(L->alist, &L->na, L->dpos, i);
}

static void d_clear(us_Local *L) {
  for (int q = 0; q < L->na; q++) L->dpos[L->alist[q]] = -1;
  for (int q = 0; q < L->nr; q++) L->dpos[L->rlist[q]] = -1;
  for (int q = 0; q < L->nt; q++) L->tpos[L->tlist[q]] = -1;
  L->na = L->nr = L->nt = 0;
}

/* The other side of contact c of body u (a body index, or < 0). */
static int other_side(const us_Local *L, int c, int u) {
  const us_Contact *k = &L->s->contacts[c];
  return k->a == u ? k->b : k->a;
}

void us_local_toggle(us_Local *L, const us_Bitset *cur, int i) {
  int in = us_bitset_get(cur, i);
  L->ncur += in ? 1 : -1;
  if (L->plumb.dep.w && us_bitset_get(&L->plumb.dep, i)) L->dep_absent += in ? -1 : 1;
  if (L->have_base) d_toggle(L, i); /* else rebuilt when a base is taken */
  for (int m = L->inc_start[i]; m < L->inc_start[i + 1]; m++) {
    int v = other_side(L, L->inc[m], i);
    if (v < 0) continue;
    L->tcur[v] += in ? 1 : -1;
    if (L->have_base) t_update(L, cur, v);
  }
  if (L->have_base) t_update(L, cur, i);
}

void us_local_sync(us_Local *L, const us_Bitset *cur) {
  L->ncur = us_bitset_count(cur);
  L->dep_absent = 0;
  for (int k = 0; L->plumb.dep.w && k < cur->nwords; k++)
    L->dep_absent += __builtin_popcountll(L->plumb.dep.w[k] & ~cur->w[k]);
  memset(L->tcur, 0, (size_t)L->s->nbody * sizeof(int));
  for (int c = 0; c < L->s->ncontact; c++) {
    const us_Contact *k = &L->s->contacts[c];
    if (k->a >= 0 && k->b >= 0 && us_bitset_get(cur, k->a)) L->tcur[k->b]++;
    if (k->a >= 0 && k->b >= 0 && us_bitset_get(cur, k->b)) L->tcur[k->a]++;
  }
  d_clear(L);
  L->have_base = 0;
}

int us_local_delta_consistent(const us_Local *L, const us_Bitset *cur) {
  int nd = 0, absent = 0, nt = 0;
  for (int k = 0; k < cur->nwords; k++) {
    if (L->plumb.dep.w) absent += __builtin_popcountll(L->plumb.dep.w[k] & ~cur->w[k]);
    if (L->have_base) nd += __builtin_popcountll(L->base.w[k] ^ cur->w[k]);
  }
  for (int q = 0; L->have_base && q < L->na; q++)
    if (L->dpos[L->alist[q]] != q || us_bitset_get(&L->base, L->alist[q]) ||
        !us_bitset_get(cur, L->alist[q]))
      return 0;
  for (int q = 0; L->have_base && q < L->nr; q++)
    if (L->dpos[L->rlist[q]] != q || !us_bitset_get(&L->base, L->rlist[q]) ||
        us_bitset_get(cur, L->rlist[q]))
      return 0;
  for (int i = 0; i < L->s->nbody; i++) {
    int t = 0;
    for (int m = L->inc_start[i]; m < L->inc_start[i + 1]; m++) {
      int v = other_side(L, L->inc[m], i);
      t += v >= 0 && us_bitset_get(cur, v);
    }
    int touch = L->have_base && L->dpos[i] >= 0 && !us_bitset_get(cur, i) && t > 0;
    if (t != L->tcur[i] || touch != (L->tpos[i] >= 0) ||
        (touch && L->tlist[L->tpos[i]] != i))
      return 0;
    nt += touch;
  }
  return L->ncur == us_bitset_count(cur) && L->dep_absent == absent && L->nt == nt &&
         (!L->have_base || L->na + L->nr == nd);
}

/* The base after S stood: B ∪ S when keep (B \ S shares no contact with
 * S), else S; the lists follow (S \ B joins B; B \ S stays, or leaves B),
 * in O(|S \ B|), and O(|B \ S|) when it leaves. */
static void base_take(us_Local *L, const us_Bitset *cur, int keep) {
  if (!L->have_base) { /* the lists are stale: a whole copy */
    memcpy(L->base.w, cur->w, (size_t)cur->nwords * sizeof(uint64_t));
    d_clear(L);
    L->have_base = 1;
    return;
  }
  for (int q = 0; q < L->na; q++) {
    us_bitset_set(&L->base, L->alist[q]);
    L->dpos[L->alist[q]] = -1;
  }
  L->na = 0;
  if (keep) return;
  for (int q = 0; q < L->nr; q++) {
    us_bitset_clear(&L->base, L->rlist[q]);
    L->dpos[L->rlist[q]] = -1;
  }
  for (int q = 0; q < L->nt; q++) L->tpos[L->tlist[q]] = -1;
  L->nr = L->nt = 0;
}

/* No base yet: B is empty, so every body of S differs. */
static void base_restart(us_Local *L, const us_Bitset *cur) {
  memset(L->base.w, 0, (size_t)L->base.nwords * sizeof(uint64_t));
  memset(L->fbase, 0, (size_t)L->s->ncontact * (size_t)L->dim * sizeof(double));
  memo_flush(L);
  d_clear(L);
  L->have_base = 1;
  for (int k = 0; k < cur->nwords; k++)
    for (uint64_t x = cur->w[k]; x; x &= x - 1) d_toggle(L, k * 64 + __builtin_ctzll(x));
}

void us_local_set_base(us_Local *L, const us_Bitset *cur, const us_EqSystem *e,
                       const double *f) {
  size_t dim = (size_t)L->dim;
  int keep = 0; /* keep B \ S with its forces when it shares no contact with S */
  if (us_plumb_materialize(&L->plumb, L->fbase)) { /* OOM: B \ S's forces are lost */
    us_plumb_drop(&L->plumb);
    L->have_base = 0;
  }
  if (L->have_base) keep = L->nt == 0; /* no body of B \ S touches S */
  if (!keep) memset(L->fbase, 0, (size_t)L->s->ncontact * dim * sizeof(double));
  for (int ci = 0; ci < e->ncontact; ci++)
    memcpy(L->fbase + (size_t)e->contact[ci] * dim, f + (size_t)ci * dim, dim * sizeof(double));
  base_take(L, cur, keep);
}

void us_local_seed_base(us_Local *L, const us_Bitset *cur, const us_Forces *f) {
  size_t dim = (size_t)L->dim;
  us_plumb_drop(&L->plumb); /* pending loads belong to the old base */
  memo_flush(L);
  memset(L->fbase, 0, (size_t)L->s->ncontact * dim * sizeof(double));
  for (int j = 0; j < f->ncontact; j++)
    for (size_t k = 0; k < dim; k++)
      L->fbase[(size_t)f->contact[j] * dim + k] = f->f[(size_t)j * dim + k] / L->eq.force_scale;
  memcpy(L->base.w, cur->w, (size_t)cur->nwords * sizeof(uint64_t));
  d_clear(L);
  L->have_base = 1;
}

int us_local_forces(us_Local *L, const us_Bitset *cur, us_Forces *out) {
  const us_Structure *s = L->s;
  if (us_plumb_materialize(&L->plumb, L->fbase)) return -1;
  int n = 0;
  for (int c = 0; c < s->ncontact; c++) n += us_contact_active(s, cur, c);
  if (n > out->cap) {
    int *ci = us_realloc(out->contact, (size_t)n * sizeof(int));
    if (!ci) return -1;
    out->contact = ci;
    double *v = us_realloc(out->f, (size_t)n * 3 * sizeof(double));
    if (!v) return -1;
    out->f = v;
    out->cap = n;
  }
  double w = L->eq.force_scale;
  size_t dim = (size_t)L->dim;
  out->ncontact = 0;
  for (int c = 0; c < s->ncontact; c++) {
    if (!us_contact_active(s, cur, c)) continue;
    int j = out->ncontact++;
    out->contact[j] = c;
    for (size_t k = 0; k < dim; k++) out->f[(size_t)j * dim + k] = L->fbase[(size_t)c * dim + k] * w;
  }
  return 0;
}

/* ------------------------------------------------------------- regions */

static void region_add(us_Local *L, int i) {
  L->in_r[i] = 1;
  L->reg[L->nreg++] = i;
}

static void region_clear(us_Local *L) {
  for (int q = 0; q < L->nreg; q++) L->in_r[L->reg[q]] = 0;
  L->nreg = 0;
}

static void widen_foot(us_Local *L, int i) {
  for (int a = 0; a < L->nax; a++) {
    L->foot_lo[a] = US_MIN(L->foot_lo[a], L->lo[2 * (size_t)i + (size_t)a]);
    L->foot_hi[a] = US_MAX(L->foot_hi[a], L->hi[2 * (size_t)i + (size_t)a]);
  }
}

static void foot_set(us_Local *L, double lo, double hi) {
  L->foot_lo[0] = L->foot_lo[1] = lo;
  L->foot_hi[0] = L->foot_hi[1] = hi;
}

/* Does body v's horizontal extent overlap the footprint's (strictly, by
 * more than a relative margin) on every axis? */
static int under_foot(const us_Local *L, int v) {
  for (int a = 0; a < L->nax; a++) {
    double flo = L->foot_lo[a], fhi = L->foot_hi[a];
    double margin = isfinite(fhi - flo) ? 1e-9 * (fhi - flo) : 0.0;
    if (L->hi[2 * (size_t)v + (size_t)a] - margin <= flo ||
        L->lo[2 * (size_t)v + (size_t)a] + margin >= fhi)
      return 0;
  }
  return 1;
}

static int int_cmp(const void *a, const void *b) {
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

/* added (S \ B) and removed (the bodies of B \ S that touch S), each in
 * increasing order (regions and routes do not depend on how the change was
 * stated): copies of the lists, sorted. The bodies of B \ S that touch
 * nothing of S (other components, as the assembly's tests by component
 * leave them in B) are not listed: O(|change|) per test, not O(|B \ S|). */
static void diff_base(us_Local *L) {
  L->nadd = L->na;
  L->nrem = L->nt;
  memcpy(L->added, L->alist, (size_t)L->na * sizeof(int));
  memcpy(L->removed, L->tlist, (size_t)L->nt * sizeof(int));
  if (L->nadd > 1) qsort(L->added, (size_t)L->nadd, sizeof(int), int_cmp);
  if (L->nrem > 1) qsort(L->removed, (size_t)L->nrem, sizeof(int), int_cmp);
}

/* The seeds D into the region: the added bodies, and the bodies of S that
 * touch a removed body; the footprint of the change. */
static void seed_region(us_Local *L, const us_Bitset *cur) {
  const us_Structure *s = L->s;
  L->touching = 0;
  foot_set(L, INFINITY, -INFINITY);
  for (int q = 0; q < L->nadd; q++) {
    region_add(L, L->added[q]);
    widen_foot(L, L->added[q]);
  }
  for (int q = 0; q < L->nrem; q++) {
    int r = L->removed[q];
    for (int m = L->inc_start[r]; m < L->inc_start[r + 1]; m++) {
      const us_Contact *k = &s->contacts[L->inc[m]];
      int v = k->a == r ? k->b : k->a;
      if (v < 0 || !us_bitset_get(cur, v)) continue;
      if (!L->touching) L->touching = 1;
      widen_foot(L, r);
      if (!L->in_r[v]) region_add(L, v);
    }
  }
}

/* Is some seed held by no active contact? Such a body falls however
 * light it is; the full system decides that exactly (before any solver
 * whose tolerance could absorb a tiny weight), so the test goes there. */
static int seed_unheld(const us_Local *L, const us_Bitset *cur) {
  const us_Structure *s = L->s;
  for (int q = 0; q < L->nreg; q++) {
    int u = L->reg[q], held = 0;
    for (int m = L->inc_start[u]; m < L->inc_start[u + 1] && !held; m++) {
      const us_Contact *k = &s->contacts[L->inc[m]];
      int v = k->a == u ? k->b : k->a;
      held = v < 0 || s->bodies[v].fixed || us_bitset_get(cur, v);
    }
    if (!held) return 1;
  }
  return 0;
}

/* Does contact c push body u up (u rests on the other side)? */
static int supports(const us_Local *L, const us_Contact *k, int u) {
  double d = k->n[0] * L->up[0] + k->n[1] * L->up[1] + k->n[2] * L->up[2];
  return (u == k->b ? d : -d) > SUPPORT_COS;
}

/* The supporters under the footprint of the region's bodies from index
 * q0 on, followed down (BFS: the bodies found join the scan). */
static void grow_supporters_from(us_Local *L, const us_Bitset *cur, int q0) {
  const us_Structure *s = L->s;
  for (int q = q0; q < L->nreg; q++) {
    int u = L->reg[q];
    for (int m = L->inc_start[u]; m < L->inc_start[u + 1]; m++) {
      const us_Contact *k = &s->contacts[L->inc[m]];
      int v = k->a == u ? k->b : k->a;
      if (v < 0 || L->in_r[v] || !us_bitset_get(cur, v) || !supports(L, k, u)) continue;
      if (!under_foot(L, v)) continue;
      region_add(L, v);
    }
  }
}

/* Level 1: the supporters under the footprint, followed down. */
static void grow_supporters(us_Local *L, const us_Bitset *cur) { grow_supporters_from(L, cur, 0); }

/* Level 1b, the counterweights' load path: the present bodies resting on
 * a seed (a counterweight pressing on an added cantilever can only hold it
 * by taking load off its own supports), and their supporters under their
 * own footprint, followed down: where the load the counterweight moves
 * leaves and where it arrives. The number of bodies added. */
static int grow_pressers(us_Local *L, const us_Bitset *cur, int nseed) {
  const us_Structure *s = L->s;
  int before = L->nreg;
  foot_set(L, INFINITY, -INFINITY);
  for (int q = 0; q < nseed; q++) {
    int u = L->reg[q];
    for (int m = L->inc_start[u]; m < L->inc_start[u + 1]; m++) {
      const us_Contact *k = &s->contacts[L->inc[m]];
      int v = k->a == u ? k->b : k->a;
      if (v < 0 || !us_bitset_get(cur, v) || !supports(L, k, v)) continue;
      widen_foot(L, v);
      if (!L->in_r[v]) region_add(L, v);
    }
  }
  if (L->nreg == before) return 0;
  grow_supporters_from(L, cur, before);
  return L->nreg - before;
}

/* Level 1c: the supporters under the extent of every body of R (not only
 * of the changed ones), followed down: a wider column than level 1's,
 * narrower than level 2's cone. The number of bodies added. */
static int grow_widened(us_Local *L, const us_Bitset *cur) {
  int before = L->nreg;
  foot_set(L, INFINITY, -INFINITY);
  for (int q = 0; q < L->nreg; q++) widen_foot(L, L->reg[q]);
  grow_supporters(L, cur);
  return L->nreg - before;
}

/* One ring of present neighbours; the number of bodies added. */
static int grow_ring(us_Local *L, const us_Bitset *cur) {
  const us_Structure *s = L->s;
  int end = L->nreg, before = L->nreg;
  for (int q = 0; q < end; q++) {
    int u = L->reg[q];
    for (int m = L->inc_start[u]; m < L->inc_start[u + 1]; m++) {
      const us_Contact *k = &s->contacts[L->inc[m]];
      int v = k->a == u ? k->b : k->a;
      if (v >= 0 && !L->in_r[v] && us_bitset_get(cur, v)) region_add(L, v);
    }
  }
  return L->nreg - before;
}

/* Rings until the region doubled; 0 when a ring added nothing (closed). */
static int grow_rings(us_Local *L, const us_Bitset *cur) {
  int target = 2 * L->nreg;
  while (L->nreg < target)
    if (grow_ring(L, cur) == 0) return 0;
  return 1;
}

/* ---------------------------------------------------------------- LPs */

/* Solve the fixed (fixed = 1) or support LP of the region. */
static us_Status solve_region(us_Local *L, const us_Bitset *cur, int fixed, us_Verdict *v,
                              us_StabilityResult *res, us_StabilityInfo *info, us_Error *err) {
  us_EqRegion g = {L->reg, L->nreg, L->in_r, L->inc_start, L->inc, fixed};
  if (L->cones) /* fixed: inner polygons (stable proofs); support: outer (unstable) */
    L->cones->mode = fixed ? US_CONE_INNER : US_CONE_OUTER;
  if (us_eq_build_region(&L->eq, cur, &g, L->fbase))
    return us_error_set(err, US_ERR_NOMEM, "out of memory building a local system");
  if (US_GROW(L->f, L->cap_f, L->eq.ncontact * L->dim + 1))
    return us_error_set(err, US_ERR_NOMEM, "out of memory building a local system");
  info->local_lps++;
  L->ray_be = L->be;
  L->ray_ws = L->bws[0];
  us_Status st = US_OK;
  *v = US_UNDECIDED;
  /* the start: B's forces, and for a fixed LP the added weights down their
     plumb lines as far as they go (taken back below; the build above
     folded B's own forces) */
  int carried = fixed && L->ncarry > 0;
  if (carried) { /* the last fixed LP's stop on its contacts, all inside R */
    size_t dim = (size_t)L->dim;
    for (int q = 0; q < L->ncarry; q++) {
      double *fb = L->fbase + (size_t)L->carry_c[q] * dim, t[3];
      memcpy(t, fb, dim * sizeof(double));
      memcpy(fb, L->carry_f + q * dim, dim * sizeof(double));
      memcpy(L->carry_f + q * dim, t, dim * sizeof(double));
    }
  }
  int routed = fixed && L->dim == 2 && !L->touching && L->nadd > 0 && !carried && !L->no_route;
  if (routed && us_plumb_route_hint(&L->plumb, cur, L->added, L->nadd, L->fbase)) {
    us_plumb_undo(&L->plumb, L->fbase);
    return us_error_set(err, US_ERR_NOMEM, "out of memory (local tests)");
  }
  /* a region system: no lists, no restart (backend.h) */
  const us_BackendProblem pb = {.sys = &L->eq, .hint = L->fbase, .no_ray = fixed};
  us_BackendOut out = {US_UNDECIDED, L->f, info, res->note, sizeof res->note};
  /* 2D up to US_SPARSE_ROWS rows the sparse simplex, then CLP. The dense
     tableau of lp_small.c took regions of up to 90 rows until 2026-12-06:
     with the sparse simplex's superbasic starts (a few pivots) it cost
     more on every stack measured (docs/local.md) */
  if (us_sparse_fits_region(&L->eq)) {
    st = us_backend_sparse.solve(L->sparse[fixed], &pb, &out, err);
    *v = out.verdict;
    if (!st && *v != US_UNDECIDED) {
      L->ray_be = &us_backend_sparse;
      L->ray_ws = L->sparse[fixed];
    }
  }
  if (!st && *v == US_UNDECIDED) {
    st = L->be->solve(L->bws[fixed], &pb, &out, err);
    *v = out.verdict;
  }
  if (L->cones) L->cones->mode = US_CONE_INNER; /* the full system's default */
  if (routed) us_plumb_undo(&L->plumb, L->fbase);
  if (carried) {
    size_t dim = (size_t)L->dim;
    for (int q = 0; q < L->ncarry; q++)
      memcpy(L->fbase + (size_t)L->carry_c[q] * dim, L->carry_f + q * dim, dim * sizeof(double));
    L->ncarry = 0;
  }
  return st;
}

/* The independent re-check of the listed bodies under fbase
 * (us_certificate_check_list) into out: 0, or -1 on OOM (out not set). */
static int check_list(us_Local *L, const us_Bitset *cur, const int *bodies, int nb,
                      us_CertCheck *out) {
  if (US_GROW(L->cacc, L->cap_cacc, US_CERT_ACC * nb + 1)) return -1;
  us_certificate_check_list(L->s, cur, bodies, nb, L->inc_start, L->inc, L->fbase, L->mass,
                            L->set.cert_tol, L->slot, L->cacc, out);
  return 0;
}

/* Merge the fixed LP's forces into fbase and re-check R's bodies; undo
 * and return 0 if the check fails. */
static int merge_and_check(us_Local *L, const us_Bitset *cur, us_StabilityResult *res) {
  const us_EqSystem *e = &L->eq;
  size_t dim = (size_t)L->dim, n = (size_t)e->ncontact * dim;
  if (US_GROW(L->saved, L->cap_saved, (int)n + 1)) return 0;
  for (int ci = 0; ci < e->ncontact; ci++) {
    double *fb = L->fbase + (size_t)e->contact[ci] * dim;
    memcpy(L->saved + (size_t)ci * dim, fb, dim * sizeof(double));
    memcpy(fb, L->f + (size_t)ci * dim, dim * sizeof(double));
  }
  if (check_list(L, cur, L->reg, L->nreg, &res->check) == 0 && res->check.ok) return 1;
  for (int ci = 0; ci < e->ncontact; ci++)
    memcpy(L->fbase + (size_t)e->contact[ci] * dim, L->saved + (size_t)ci * dim,
           dim * sizeof(double));
  return 0;
}

/* The base after a local stable verdict of cur. */
static void advance_base(us_Local *L, const us_Bitset *cur) {
  if (!L->touching) { /* B \ S shares no contact with S: B ∪ S stands */
    base_take(L, cur, 1);
    return;
  }
  size_t dim = (size_t)L->dim;
  for (int q = 0; q < L->nr; q++) { /* every body of B \ S leaves B */
    int r = L->rlist[q];
    for (int m = L->inc_start[r]; m < L->inc_start[r + 1]; m++)
      memset(L->fbase + (size_t)L->inc[m] * dim, 0, dim * sizeof(double));
  }
  base_take(L, cur, 0);
}

static int bucket_of(int n) {
  int b = 0;
  while (n > 1 && b < US_LOCAL_BUCKETS - 1) n >>= 1, b++;
  return b;
}

static int settle_n(int verdict, int n, us_StabilityInfo *info) {
  info->local_settled[bucket_of(n)]++;
  info->local_region_bodies += n;
  if (verdict == US_LOCAL_STABLE) info->local_stable++;
  else info->local_unstable++;
  return verdict;
}

static int settle(us_Local *L, int verdict, us_StabilityInfo *info) {
  return settle_n(verdict, L->nreg, info);
}

int us_mechanism_from_ray(us_Mechanism *m, const us_EqSystem *e, const double *y, int ny) {
  m->nbody = 0;
  m->ok = 0;
  m->worst_power = INFINITY;
  size_t nw = (size_t)e->nw; /* a row block's duals are the body's velocities */
  if (ny != e->nbody * e->nw) return 0;
  if (e->nbody > m->cap) {
    int *b = us_realloc(m->body, (size_t)e->nbody * sizeof(int));
    if (!b) return -1;
    m->body = b;
    double *v = us_realloc(m->v, (size_t)e->nbody * 6 * sizeof(double));
    if (!v) return -1;
    m->v = v;
    m->cap = e->nbody;
  }
  double by = 0.0;
  for (int r = 0; r < ny; r++) by += e->rhs[r] * y[r];
  double sg = by < 0 ? 1.0 : -1.0; /* rhs . v < 0: gravity drives v */
  m->nbody = e->nbody;
  for (int q = 0; q < e->nbody; q++) {
    m->body[q] = e->body[q];
    for (size_t k = 0; k < nw; k++) m->v[nw * (size_t)q + k] = sg * y[nw * (size_t)q + k];
  }
  return 0;
}

/* The support LP's Farkas ray as a mechanism of R, checked against the
 * contacts of R's bodies. 1 accepted, 0 not, -1 OOM. */
static int region_mechanism(us_Local *L, const us_Bitset *cur, us_Mechanism *m) {
  const double *y = NULL;
  int ny = L->ray_be->farkas_ray ? L->ray_be->farkas_ray((void *)L->ray_ws, &y) : 0;
  if (!ny || !y) return 0;
  if (us_mechanism_from_ray(m, &L->eq, y, ny)) return -1;
  int nlist = 0;
  for (int q = 0; q < L->nreg; q++) {
    int u = L->reg[q];
    for (int j = L->inc_start[u]; j < L->inc_start[u + 1]; j++) L->list[nlist++] = L->inc[j];
  }
  return us_mechanism_check_list(L->s, cur, m, L->set.cert_tol, L->slot, L->list, nlist);
}

/* The support LP at the current region: 1 unstable (res set, mechanism
 * checked), 0 not proven, -1 error. */
static int try_support(us_Local *L, const us_Bitset *cur, us_StabilityResult *res,
                       us_StabilityInfo *info, us_Error *err) {
  us_Verdict v;
  if (solve_region(L, cur, 0, &v, res, info, err)) return -1;
  if (v != US_UNSTABLE) return 0;
  int ok = region_mechanism(L, cur, &res->mechanism);
  if (ok < 0) return us_error_set(err, US_ERR_NOMEM, "out of memory (local tests)"), -1;
  if (!ok) return 0; /* no checked mechanism: no proof, grow */
  res->verdict = US_UNSTABLE;
  res->unstable_body = L->ray_be->unstable_body ? L->ray_be->unstable_body((void *)L->ray_ws) : -1;
  snprintf(res->note, sizeof res->note,
           "local: %d bodies cannot stand even with the rest held still", L->nreg);
  return 1;
}

int us_local_held(us_Local *L, const us_Bitset *present, const int *reg, int nreg,
                  us_StabilityResult *res, us_StabilityInfo *info, us_Error *err) {
  region_clear(L);
  for (int q = 0; q < nreg; q++)
    if (!L->in_r[reg[q]]) region_add(L, reg[q]);
  int r = try_support(L, present, res, info, err);
  region_clear(L);
  return r;
}

/* The fixed LP at the current region: 1 stable (certificate merged and
 * checked), 0 not proven, -1 error. */
static int try_fixed(us_Local *L, const us_Bitset *cur, us_StabilityResult *res,
                     us_StabilityInfo *info, us_Error *err) {
  us_Verdict v;
  if (solve_region(L, cur, 1, &v, res, info, err)) return -1;
  if (v == US_UNSTABLE && L->ray_be == &us_backend_sparse && L->dim == 2) {
    /* keep where phase 1 stopped for the grown region's LP */
    int n = L->eq.ncontact;
    size_t dim = (size_t)L->dim;
    if (US_GROW(L->carry_c, L->cap_carry, n + 1) || US_GROW(L->carry_f, L->cap_carry_f, (int)dim * n + 1))
      return us_error_set(err, US_ERR_NOMEM, "out of memory (local tests)"), -1;
    memcpy(L->carry_c, L->eq.contact, (size_t)n * sizeof(int));
    memcpy(L->carry_f, L->f, (size_t)n * dim * sizeof(double));
    L->ncarry = n;
  }
  if (v != US_STABLE || !merge_and_check(L, cur, res)) return 0;
  res->verdict = US_STABLE;
  snprintf(res->note, sizeof res->note, "local: %d bodies, the rest unchanged", L->nreg);
  return 1;
}

/* The plumb lines of the added bodies, memoised (plumb.h, lazy routing),
 * when no removed body touches S (so B's forces, with the pending loads,
 * still hold every body of S that was in B) and the memo's bodies are all
 * in S: 1 stable (the added weights wait as pending load on checked
 * lines), 0 not proven (nothing changed), -1 OOM. The re-check is the
 * check of every line routed now (plumb.c, check_line); the lines met
 * again were checked when first routed and rest on bodies still present. */
static int try_plumb(us_Local *L, const us_Bitset *cur, us_StabilityResult *res,
                     us_StabilityInfo *info, us_Error *err) {
  if (L->touching || !L->nadd || L->dep_absent) return 0;
  int r = us_plumb_route_lazy(&L->plumb, cur, L->added, L->nadd, L->set.cert_tol);
  if (r < 0) return us_error_set(err, US_ERR_NOMEM, "out of memory (local tests)"), -1;
  if (r == 0) return 0;
  const us_Plumb *p = &L->plumb;
  memset(&res->check, 0, sizeof res->check);
  res->check.ok = 1;
  res->check.worst_body = res->check.worst_contact = -1;
  res->check.max_force_residual = res->check.max_torque_residual = p->worst_line;
  res->verdict = US_STABLE;
  snprintf(res->note, sizeof res->note, "local: plumb lines (%d routed now), the rest unchanged",
           p->nnew);
  info->local_plumb++;
  return 1;
}

/* Is contact c's force in fbase outside its cone (us_cone_distance)? */
static int outside_cone(const us_Local *L, int c) {
  const double *f = L->fbase + (size_t)L->dim * (size_t)c;
  double t = L->dim == 2 ? fabs(f[1]) : hypot(f[1], f[2]);
  return us_cone_distance(f[0], t, L->s->contacts[c].mu) > 0.0;
}

/* The fixed LP of the current region from fbase as it is (no route);
 * what try_fixed returns. */
static int try_fixed_as_is(us_Local *L, const us_Bitset *cur, us_StabilityResult *res,
                           us_StabilityInfo *info, us_Error *err) {
  L->no_route = 1;
  int r = try_fixed(L, cur, res, info, err);
  L->no_route = 0;
  L->ncarry = 0; /* the next region need not hold this one */
  return r;
}

/* A lever whose route left some contact outside its cone (a release
 * took off more than the base had there), or whose check failed: the
 * fixed LP from its forces, which are B's but where the lever moved
 * them, on
 *   1. the bodies of the contacts outside their cones and their
 *      neighbours on the lever's path (the release goes elsewhere near
 *      where it failed: seed 19 287 -> 219 M instructions, 632 blocks
 *      100 -> 83 M; the contacts' bodies alone: no gain; two rings of
 *      neighbours: less gain);
 *   2. the whole path (every contact the lever changed has both sides
 *      there, or the ground, so the region's boundary is B's): on the
 *      stacker's stacks it settles nearly every test (118 of 125 on seed
 *      15) that the levels took through levels 1 to 1c.
 * 1 stable (merged and checked), 0 not proven (the region back to the
 * seeds), -1 error. */
static int lever_region(us_Local *L, const us_Bitset *cur, us_StabilityResult *res,
                        us_StabilityInfo *info, us_Error *err) {
  const us_Plumb *p = &L->plumb;
  region_clear(L);
  for (int q = 0; q < p->nlog; q++) {
    int c = p->log_c[q];
    if (!outside_cone(L, c)) continue;
    const us_Contact *k = &L->s->contacts[c];
    int e[2] = {k->a, k->b};
    for (int j = 0; j < 2; j++)
      if (e[j] >= 0 && !L->s->bodies[e[j]].fixed && !L->in_r[e[j]]) region_add(L, e[j]);
  }
  for (int q = 0, end = L->nreg; q < end; q++) {
    int u = L->reg[q];
    for (int m = L->inc_start[u]; m < L->inc_start[u + 1]; m++) {
      int v = other_side(L, L->inc[m], u);
      if (v >= 0 && p->mark[v] && !L->in_r[v] && !L->s->bodies[v].fixed && us_bitset_get(cur, v))
        region_add(L, v);
    }
  }
  int r = L->nreg > 0 && L->nreg < p->npath ? try_fixed_as_is(L, cur, res, info, err) : 0;
  if (r == 0) {
    region_clear(L);
    for (int q = 0; q < p->npath; q++) {
      int v = p->path[q];
      if (!L->s->bodies[v].fixed && us_bitset_get(cur, v) && !L->in_r[v]) region_add(L, v);
    }
    r = try_fixed_as_is(L, cur, res, info, err);
  }
  region_clear(L);
  seed_region(L, cur);
  return r;
}

/* The lever of one added cantilever held by a body resting on it (plumb.h,
 * us_plumb_lever), after the pending loads went down (its release reads
 * fbase): the changed bodies re-checked by the independent check, as a
 * region's, and where the check fails the fixed LP on them
 * (lever_region). 1 stable, 0 not proven (fbase unchanged), -1 error. */
static int try_lever(us_Local *L, const us_Bitset *cur, us_StabilityResult *res,
                     us_StabilityInfo *info, us_Error *err) {
  if (L->touching || L->nadd != 1) return 0;
  us_Plumb *p = &L->plumb;
  int r = us_plumb_lever(p, cur, L->added[0], L->fbase);
  if (r < 0) return us_error_set(err, US_ERR_NOMEM, "out of memory (local tests)"), -1;
  if (r == 0) return 0;
  if (check_list(L, cur, p->path, p->npath, &res->check)) res->check.ok = 0;
  if (!res->check.ok) {
    r = lever_region(L, cur, res, info, err);
    if (r < 0) return -1;
    if (r == 0) {
      us_plumb_undo(p, L->fbase);
      return 0;
    }
    return 1;
  }
  res->verdict = US_STABLE;
  snprintf(res->note, sizeof res->note, "local: a lever (%d bodies), the rest unchanged",
           p->npath);
  info->local_lever++;
  return 1;
}

/* The pending plumb loads into fbase (B's certificate made explicit). */
static int materialize(us_Local *L, us_Error *err) {
  if (us_plumb_materialize(&L->plumb, L->fbase))
    return us_error_set(err, US_ERR_NOMEM, "out of memory (local tests)"), -1;
  return 0;
}

/* An optional support LP pays when it finds proofs: it is skipped while
 * fewer than one in k of its recent runs did (every 16th chance runs it
 * anyway, to notice when the workload changes). */
static int pays(us_Pays *p, int k) {
  return p->tries < 32 || p->chances++ % 16 == 0 || k * p->hits >= p->tries;
}

/* A run of it, and whether it proved "unstable" (1) or failed (-1). */
static int paid(us_Pays *p, int r) {
  p->tries++;
  if (r > 0) p->hits++;
  if (p->tries >= 256) p->tries /= 2, p->hits /= 2; /* recent history */
  return r;
}

/* Back to the first n bodies of the region. */
static void region_truncate(us_Local *L, int n) {
  for (int q = n; q < L->nreg; q++) L->in_r[L->reg[q]] = 0;
  L->nreg = n;
}

/* The support LP at the last region (run_levels), unless R is the seeds
 * (level 0 ran it) or it ran at this region already (regions only grow,
 * so the same size is the same region): unstable, or the full system. */
static int last_support(us_Local *L, const us_Bitset *cur, int nseed, int supported,
                        us_StabilityResult *res, us_StabilityInfo *info, us_Error *err) {
  int r = L->nreg > nseed && L->nreg != supported ? try_support(L, cur, res, info, err) : 0;
  if (r) return r < 0 ? -1 : settle(L, US_LOCAL_UNSTABLE, info);
  return US_LOCAL_GLOBAL;
}

/* The levels; a US_LOCAL_* verdict or -1.
 *
 * The fixed LP runs at every level; the support LP at level 0, at the
 * last region (the largest before the region would pass the limit, or
 * the closed one), and at the levels between while it pays (pays(): an
 * early proof spares the growth of an unstable test's region). The
 * last one is enough for exactness: the support LP only grows stronger
 * with R (its forces restricted to a smaller R' hold R'), so an
 * "unstable" it would prove at a smaller region it proves at the last
 * one (docs/local.md, "Regions"). */
static int run_levels(us_Local *L, const us_Bitset *cur, int size, us_StabilityResult *res,
                      us_StabilityInfo *info, us_Error *err) {
  /* level 0, the support LP only. 2D: the seeds and the bodies they
     touch, the rest held still (a block that tips pushes its neighbour
     over: 8 of 24 full-system tests of a 931-block stack; the seeds alone
     past LEVEL0_ROWS), at every test. 3D: the seeds alone, while it pays
     (a 3D region LP is CLP's; on a 200-box random3d pile the 2D rule
     cost 23 % more instructions) */
  int nseed = -1, r;
  if (L->dim == 2 || pays(&L->seed_pays, 8)) {
    int n0 = L->nreg;
    if (L->dim == 2) {
      grow_ring(L, cur);
      if (L->nreg * L->eq.nw > LEVEL0_ROWS) region_truncate(L, n0);
      r = try_support(L, cur, res, info, err);
    } else {
      r = paid(&L->seed_pays, try_support(L, cur, res, info, err));
    }
    if (r) return r < 0 ? -1 : settle(L, US_LOCAL_UNSTABLE, info);
    region_truncate(L, n0);
    nseed = n0;
  }
  int nfirst = L->nreg, pressed = 0, last = L->nreg;
  int supported = -1; /* the region size of the latest support LP */
  /* level 1c in 2D only: on a 200-box random3d pile it added 36 region
     LPs and 3-5 % to the plan for 2 fewer full-system tests */
  int closed = 0, coned = 0, widened = L->dim != 2;
  int limit = US_MAX((int)(LOCAL_GLOBAL_SHARE * size), LEVEL0_ROWS / L->eq.nw);
  if (L->dim == 2) /* the sparse simplex's regions (3D regions go to CLP) */
    limit = US_MIN(size, LOCAL_REGION_BODIES);
  if (L->plumb.tipped) {
    /* the added body lies beyond its supports and nothing presses it
       (us_plumb_lever): only its side neighbours can hold it (friction on
       the joints of its row), so level 1 starts from them, under their
       own extent (before, such tests went through levels 1 to 2 to the
       rings: 19 tests on seed 15 cost a quarter of its plan; with this,
       632 blocks 134 -> 104 M instructions, seed 11 550 -> 372 M) */
    grow_ring(L, cur);
    foot_set(L, INFINITY, -INFINITY);
    for (int q = 0; q < L->nreg; q++) widen_foot(L, L->reg[q]);
  }
  grow_supporters(L, cur);
  /* a seed that a present body rests on: level 1 alone never held one
     (0 of 894 such tests on stacks of 632 to 9,352 blocks), so the first
     fixed LP is at level 1b, unless that passes the limit */
  int n1 = L->nreg;
  if (grow_pressers(L, cur, nfirst)) {
    pressed = 1;
    if (L->nreg > limit) region_truncate(L, n1);
  }
  for (;;) {
    if (L->nreg > limit && !closed) { /* the last region was the one before */
      region_truncate(L, last);
      return last_support(L, cur, nseed, supported, res, info, err);
    }
    r = try_fixed(L, cur, res, info, err);
    if (r) return r < 0 ? -1 : settle(L, US_LOCAL_STABLE, info);
    /* closed: both LPs are the exact test of R's components; neither
     * decided if a re-check failed, or the solver gave up */
    if (closed) return last_support(L, cur, nseed, supported, res, info, err);
    /* an early proof spares an unstable test the growth: at 1 in 32 it
       pays on a 9,352-block stack (regions up to 2,300 bodies); at 1 in
       8 it was skipped there, 7 % more instructions */
    if (L->nreg > nseed && pays(&L->grow_pays, 32)) {
      r = paid(&L->grow_pays, try_support(L, cur, res, info, err));
      supported = L->nreg;
      if (r) return r < 0 ? -1 : settle(L, US_LOCAL_UNSTABLE, info);
    }
    last = L->nreg;
    if (!pressed) { /* level 1b: the counterweights' load path */
      pressed = 1;
      if (grow_pressers(L, cur, nfirst)) continue;
    }
    if (!widened) { /* level 1c: a wider column */
      widened = 1;
      if (grow_widened(L, cur)) continue;
    }
    if (!coned) { /* level 2: every supporter of R, followed down */
      coned = 1;
      int before = L->nreg;
      foot_set(L, -INFINITY, INFINITY);
      grow_supporters(L, cur);
      if (L->nreg > before) continue;
    }
    closed = !grow_rings(L, cur);
  }
}

/* The components of cur that hold one of the seeds L->reg[0 .. nseed),
 * into L->part (L->npart bodies): a depth-first search over contacts
 * between present bodies. -1 on OOM (L->npart stays -1). */
static int changed_part(us_Local *L, const us_Bitset *cur, int nseed) {
  int n = L->s->nbody, top = 0, count = 0;
  if (!L->part.w && us_bitset_init(&L->part, n)) return -1;
  if (!L->stack && !(L->stack = us_malloc((size_t)(n > 0 ? n : 1) * sizeof(int)))) return -1;
  memset(L->part.w, 0, (size_t)L->part.nwords * sizeof(uint64_t));
  for (int q = 0; q < nseed; q++)
    if (!us_bitset_get(&L->part, L->reg[q])) us_bitset_set(&L->part, L->reg[q]), L->stack[top++] = L->reg[q];
  while (top > 0) {
    int u = L->stack[--top];
    count++;
    for (int m = L->inc_start[u]; m < L->inc_start[u + 1]; m++) {
      int v = other_side(L, L->inc[m], u);
      if (v >= 0 && us_bitset_get(cur, v) && !us_bitset_get(&L->part, v))
        us_bitset_set(&L->part, v), L->stack[top++] = v;
    }
  }
  L->npart = count;
  return 0;
}

const double *us_local_hint(us_Local *L) {
  if (!L->have_base || !L->hint_ok || us_plumb_materialize(&L->plumb, L->fbase)) return NULL;
  return L->fbase;
}

int us_local_changed_part(const us_Local *L, const us_Bitset **part) {
  *part = &L->part;
  return L->npart;
}

/* Few enough changed bodies (seeds) for B's forces to be most of S's:
 * more go to the full system. */
static int few_seeds(int nseed, int size) { return nseed <= 16 + size / 8; }

int us_local_test(us_Local *L, const us_Bitset *cur, us_StabilityResult *res,
                  us_StabilityInfo *info, us_Error *err) {
  L->npart = -1;
  L->hint_ok = 0;
  L->plumb.tipped = 0;
  int min = L->set.local_min_bodies > 0 ? L->set.local_min_bodies : LOCAL_MIN_BODIES;
  int size = L->ncur;
  if (size < min) return US_LOCAL_GLOBAL;
  if (!L->have_base) /* from the empty set: every body is added (plumb lines can
                        prove a whole structure, as `check` asks, one visit
                        per distinct line) */
    base_restart(L, cur);
  diff_base(L);
  /* removals change B's certificate on their contacts, and a memo line
     resting on a body not in S is void: make B's forces explicit first */
  int valid = L->dep_absent == 0;
  if ((L->nrem > 0 || !valid) && materialize(L, err)) return -1;
  if (!valid) memo_flush(L);
  seed_region(L, cur);
  int r, nseed = L->nreg;
  /* B's forces start the full system's sparse simplex (stability.c) when
     few bodies changed, or few at all: from nothing (`check`, whose base
     is empty) its pivots grow with the bodies, and on stacker stacks CLP
     (its module's loading included) was faster from about 185 bodies on:
     281 bodies 84 ms against 38 ms, 632 bodies 0.30 s against 0.09 s */
  L->hint_ok = few_seeds(nseed, size) || nseed <= HINT_SEEDS;
  if (L->nreg == 0) { /* S inside B, apart from what left: B's forces hold */
    memset(&res->check, 0, sizeof res->check);
    res->check.ok = 1;
    res->check.worst_body = res->check.worst_contact = -1;
    res->verdict = US_STABLE;
    snprintf(res->note, sizeof res->note, "local: no body's contacts changed");
    r = settle(L, US_LOCAL_STABLE, info);
  } else if (seed_unheld(L, cur)) {
    r = US_LOCAL_GLOBAL;
  } else if ((r = try_plumb(L, cur, res, info, err)) != 0) {
    if (r > 0) r = settle_n(US_LOCAL_STABLE, L->nadd, info);
  } else if (materialize(L, err)) {
    r = -1;
  } else if ((r = try_lever(L, cur, res, info, err)) != 0) {
    if (r > 0) r = settle_n(US_LOCAL_STABLE, L->plumb.npath, info);
  } else if (!few_seeds(nseed, size)) {
    r = US_LOCAL_GLOBAL;
  } else {
    r = run_levels(L, cur, size, res, info, err);
  }
  if (r == US_LOCAL_STABLE) advance_base(L, cur);
  /* handed back with only bodies added (none removed touches S): S's
     components without a seed are components of B, unchanged, held by
     B's forces, so the full system need only solve the others */
  if (r == US_LOCAL_GLOBAL && L->nt == 0 && nseed > 0) {
    region_truncate(L, nseed);
    if (changed_part(L, cur, nseed)) L->npart = -1; /* OOM: the whole system */
  }
  region_clear(L);
  L->ncarry = 0;
  if (r == US_LOCAL_GLOBAL) info->local_global++;
  return r;
}
