/* Exact local stability tests in 3D (src/stability/local.c, plumb.c;
 * docs/local.md): the same verdicts as the full system with its circular
 * cone refinement (stability.c run_cones), every time.
 *
 * Each structure is walked through sequences of sub-assemblies by two
 * workspaces, local tests on (down to one body) and off; the verdicts must
 * agree. The sequences are those the planner and verify make, and some it
 * does not: the assembly order bottom up (every prefix), the plan's removal
 * order top down, random removal walks from the full structure down to
 * nothing (most remainders fall), random sets grown body by body from the
 * empty set, and a walk that stays near the border between standing and
 * falling (a move that made the sub-assembly fall is mostly undone). The
 * structures: towers (straight, and with turned boxes), 3D pyramids,
 * running-bond walls (straight and with returns), Jenga towers with pieces
 * knocked out, random 3D stacks and domes, at mu = 0.5, 0.2 and 0, some of
 * them under gravity tilted off the vertical (the structure on a slope:
 * every contact inclined, the local tests' horizontal axes no longer x, y).
 *
 * Every stable verdict of the local workspace must carry forces that pass
 * the library's check (r.check, then us_certificate_check on the forces)
 * and this file's own equilibrium check (below: net force and torque of
 * every present body, normal >= 0, inside the circular cone); every local
 * unstable verdict a mechanism (6 velocities per body) accepted by
 * us_mechanism_check and by this file's own power check against the
 * circular cones. The counts must show that both verdicts were common and
 * that the local tests decided most tests (by plumb lines and region LPs),
 * so the test fails if the local tests silently stop running in 3D.
 *
 * The mechanisms must also not rest on round-off: gravity's power must
 * stand clear of what errors of 1e-16 in the contact frames could do at
 * the mechanism's speeds, else a stable certificate and an unstable
 * mechanism can both pass on one sub-assembly.
 *
 * The 2D differential test's random piles, extruded into prisms and turned
 * about the vertical, add cantilevers, counterweights, leaning slabs and
 * arches, and a third opinion: the 2D structure's own verdict.
 *
 * A lever whose instability is global closes the file: a plank on a pier,
 * a column of blocks on its near end and a load on its far end; taking the
 * load off tips the plank towards the column, a change far from the pier
 * whose region must grow over the whole column.
 *
 * Every sequence is seeded from its structure's name; L3D_SEED=n changes
 * the seeds, L3D_TRACE=1 prints every test, -DSCALE=n makes more walks. */
#include "piles.h"
#include "extrude.h"
#include "test.h"
#include "walks.h"

#ifndef SCALE /* random walks per structure (-DSCALE=n for a longer run) */
#ifdef US_TEST_SANITIZED
#define SCALE 1 /* sanitizer builds: the same structures, fewer random walks */
#else
#define SCALE 2
#endif
#endif

#define NPILES (40 * SCALE) /* random piles (piles_agree) */

static const double PI = 3.14159265358979323846;

typedef struct Tally {
  long tests, stable, unstable;
  long local, local_stable, local_unstable, plumb, mech;
  long global_mech; /* full-system unstable verdicts with a checked mechanism */
  long refined;     /* directions added to friction polygons (both workspaces) */
} Tally;

/* -------------------------------------------------- independent checks */

static double dot3(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double *a, const double *b, double *o) {
  o[0] = a[1] * b[2] - a[2] * b[1];
  o[1] = a[2] * b[0] - a[0] * b[2];
  o[2] = a[0] * b[1] - a[1] * b[0];
}

static int side_present(const us_Structure *s, const us_Bitset *node, int i) {
  return i < 0 || s->bodies[i].fixed || us_bitset_get(node, i);
}

static int side_movable(const us_Structure *s, int i) { return i >= 0 && !s->bodies[i].fixed; }

static double movable_mass(const us_Structure *s) {
  double m = 0.0;
  for (int i = 0; i < s->nbody; i++)
    if (!s->bodies[i].fixed) m += s->bodies[i].mass;
  return m;
}

/* The forces (newtons, per contact: f_n, f_t1, f_t2 in the contact frame)
 * hold every present movable body of `node`: each contact is active, its
 * force has f_n >= 0 and |f_t| <= mu f_n, and every body's net force and
 * torque (about its centre of mass) vanish, all to tol relative to the
 * movable weight W (torques to W times the structure's scale). Written
 * here from the definitions, apart from the library's check. */
static int forces_hold(const us_Structure *s, const us_Bitset *node, const us_Forces *f,
                       double tol, char *why, size_t nwhy) {
  double g = sqrt(dot3(s->gravity, s->gravity)), W = movable_mass(s) * g, L = s->scale;
  double *acc = calloc((size_t)s->nbody * 6 + 1, sizeof(double));
  if (!acc) return snprintf(why, nwhy, "out of memory"), 0;
  int ok = 1;
  for (int j = 0; j < f->ncontact && ok; j++) {
    int c = f->contact[j];
    if (c < 0 || c >= s->ncontact) {
      snprintf(why, nwhy, "force on contact %d out of range", c);
      ok = 0;
      break;
    }
    const us_Contact *k = &s->contacts[c];
    if (!side_present(s, node, k->a) || !side_present(s, node, k->b) ||
        !(side_movable(s, k->a) || side_movable(s, k->b))) {
      if (f->f[3 * j] != 0.0 || f->f[3 * j + 1] != 0.0 || f->f[3 * j + 2] != 0.0) {
        snprintf(why, nwhy, "force on inactive contact %d", c);
        ok = 0;
      }
      continue;
    }
    double fn = f->f[3 * j], t1 = f->f[3 * j + 1], t2 = f->f[3 * j + 2], ft = hypot(t1, t2);
    if (fn < -tol * W) {
      snprintf(why, nwhy, "contact %d pulls: f_n = %g", c, fn);
      ok = 0;
    }
    double cap = isinf(k->mu) ? INFINITY : k->mu * fn;
    if (ft > cap + tol * W) {
      snprintf(why, nwhy, "contact %d outside its cone: |f_t| %g > mu f_n %g (mu %g)", c, ft, cap,
               k->mu);
      ok = 0;
    }
    double F[3], r[3], T[3];
    for (int d = 0; d < 3; d++) F[d] = fn * k->n[d] + t1 * k->t[0][d] + t2 * k->t[1][d];
    for (int side = 0; side < 2; side++) { /* b gets F, a gets -F */
      int i = side ? k->b : k->a;
      if (!side_movable(s, i)) continue;
      double sg = side ? 1.0 : -1.0, *a = acc + 6 * (size_t)i;
      for (int d = 0; d < 3; d++) r[d] = k->p[d] - s->bodies[i].com[d];
      cross3(r, F, T);
      for (int d = 0; d < 3; d++) a[d] += sg * F[d], a[3 + d] += sg * T[d];
    }
  }
  for (int i = 0; i < s->nbody && ok; i++) {
    if (!side_movable(s, i) || !us_bitset_get(node, i)) continue;
    double *a = acc + 6 * (size_t)i;
    for (int d = 0; d < 3; d++) a[d] += s->bodies[i].mass * s->gravity[d];
    double rf = sqrt(dot3(a, a)) / W, rt = sqrt(dot3(a + 3, a + 3)) / (W * L);
    if (!(rf <= tol && rt <= tol)) {
      snprintf(why, nwhy, "body %d out of equilibrium: force %.3g, torque %.3g (relative)", i, rf,
               rt);
      ok = 0;
    }
  }
  free(acc);
  return ok;
}

static void print_node(const us_Structure *s, const us_Bitset *node) {
  fprintf(stderr, "  present:");
  for (int i = 0; i < s->nbody; i++)
    if (us_bitset_get(node, i)) fprintf(stderr, " %d", i);
  fprintf(stderr, "\n");
}

static double worst_speed; /* largest sum of speeds per gravity's power met */

/* The mechanism m (per body vx, vy, vz at the centre of mass, then the
 * angular velocity in radians per structure scale) makes gravity do
 * positive work while every force any active contact could carry (normal
 * >= 0, inside its circular cone) does work >= -tol (relative to gravity's
 * power): at each contact touching a moving body, with relative velocity
 * v of b against a, v.n >= mu |v_t|. Written here from the definitions. */
static int mechanism_holds(const us_Structure *s, const us_Bitset *node, const us_Mechanism *m,
                           double tol, char *why, size_t nwhy) {
  if (m->nbody <= 0) return snprintf(why, nwhy, "no moving body"), 0;
  int *slot = malloc((size_t)s->nbody * sizeof(int));
  if (!slot) return snprintf(why, nwhy, "out of memory"), 0;
  for (int i = 0; i < s->nbody; i++) slot[i] = -1;
  double pg = 0.0, L = s->scale, mm = movable_mass(s), g = sqrt(dot3(s->gravity, s->gravity));
  int ok = 1;
  for (int q = 0; q < m->nbody && ok; q++) {
    int i = m->body[q];
    if (i < 0 || i >= s->nbody || !side_movable(s, i) || !us_bitset_get(node, i) || slot[i] >= 0) {
      snprintf(why, nwhy, "mechanism body %d is not a present movable body (or twice)", i);
      ok = 0;
      break;
    }
    slot[i] = q;
    for (int d = 0; d < 6 && ok; d++)
      if (!isfinite(m->v[6 * q + d]))
        snprintf(why, nwhy, "body %d: velocity %d is not finite", i, d), ok = 0;
    pg += s->bodies[i].mass / mm * dot3(s->gravity, m->v + 6 * q) / g;
  }
  if (ok && !(pg > 0)) {
    snprintf(why, nwhy, "gravity does no positive work (%g)", pg);
    ok = 0;
  }
  /* A proof must not rest on round-off: a motion whose speeds (velocity
     plus angular velocity, per body, in the units above) are more than
     1e12 times gravity's power draws its power from errors of the order
     of 1e-16 in the contact frames (a body sliding 1e18 sideways to sink
     1 along a 1e-18 slope that the round-off of a turned face's normal
     made). Legitimate rays of near-critical sub-assemblies were seen up
     to 7e6, past 1 / cert_tol, so the bar is at round-off. */
  double speed = 0.0;
  for (int q = 0; q < m->nbody && ok; q++) {
    const double *v = m->v + 6 * q, *w = v + 3;
    speed += sqrt(dot3(v, v)) + sqrt(dot3(w, w));
  }
  if (ok && pg > 0) worst_speed = fmax(worst_speed, speed / pg);
  if (ok && !(pg > 1e-12 * speed)) {
    snprintf(why, nwhy, "ill-conditioned: speeds %.3g for gravity's power %.3g", speed, pg);
    ok = 0;
  }
  for (int c = 0; c < s->ncontact && ok; c++) {
    const us_Contact *k = &s->contacts[c];
    int qa = k->a >= 0 ? slot[k->a] : -1, qb = k->b >= 0 ? slot[k->b] : -1;
    if (qa < 0 && qb < 0) continue;
    if (!side_present(s, node, k->a) || !side_present(s, node, k->b)) continue;
    double v[2][3] = {{0, 0, 0}, {0, 0, 0}};
    for (int side = 0; side < 2; side++) {
      int q = side ? qb : qa;
      if (q < 0) continue;
      const double *u = m->v + 6 * q, *w = u + 3, *com = s->bodies[m->body[q]].com;
      double r[3], wr[3];
      for (int d = 0; d < 3; d++) r[d] = (k->p[d] - com[d]) / L;
      cross3(w, r, wr);
      for (int d = 0; d < 3; d++) v[side][d] = u[d] + wr[d];
    }
    double vr[3] = {v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]};
    double pn = dot3(vr, k->n), vt[3];
    for (int d = 0; d < 3; d++) vt[d] = vr[d] - pn * k->n[d];
    double pt = sqrt(dot3(vt, vt));
    double p = pn; /* the least power of a unit generator of the cone */
    if (isinf(k->mu)) p = fmin(pn, -pt);
    else if (k->mu > 0.0) p = (pn - k->mu * pt) / hypot(1.0, k->mu);
    if (!(p >= -tol * pg)) {
      snprintf(why, nwhy, "contact %d resists the motion: power %.3g (gravity %.3g)", c, p, pg);
      ok = 0;
    }
  }
  free(slot);
  return ok;
}

/* ---------------------------------------------------- the differential */

typedef struct Pair {
  const us_Structure *s;
  const char *name;
  us_Stability *loc, *glob;
  us_StabilityResult rl, rg;
  Tally *t;
  double tl, tg; /* seconds in each workspace */
  const us_Structure *s2; /* a 2D twin (s is its extrusion) or NULL */
  us_Stability *w2;
  us_StabilityResult r2;
} Pair;

static int pair_open(Pair *p, const us_Structure *s, const us_Structure *s2, const char *name,
                     Tally *t) {
  us_StabilitySettings sl = local_settings(1), sg = local_settings(0);
  us_Error err;
  p->s = s, p->s2 = s2, p->name = name, p->t = t, p->tl = p->tg = 0.0;
  p->loc = us_stability_new(s, &sl, &err);
  p->glob = us_stability_new(s, &sg, &err);
  p->w2 = p->s2 ? us_stability_new(p->s2, &sg, &err) : NULL;
  us_stability_result_init(&p->rl);
  us_stability_result_init(&p->rg);
  us_stability_result_init(&p->r2);
  return p->loc && p->glob && (!p->s2 || p->w2) ? 0 : -1;
}

static void pair_close(Pair *p) {
  us_stability_result_free(&p->rl);
  us_stability_result_free(&p->rg);
  us_stability_result_free(&p->r2);
  us_stability_free(p->loc);
  us_stability_free(p->glob);
  us_stability_free(p->w2);
}

static long local_count(const us_Stability *w) {
  const us_StabilityInfo *in = us_stability_info(w);
  return in->local_stable + in->local_unstable;
}

/* Test `node` in both workspaces: 0 if the verdicts agree and every
 * certificate holds, else -1 (reported with the sub-assembly). */
static int compare(Pair *p, const us_Bitset *node) {
  const us_Structure *s = p->s;
  us_StabilityResult *rl = &p->rl, *rg = &p->rg;
  Tally *t = p->t;
  us_Error err;
  const us_StabilityInfo *li = us_stability_info(p->loc);
  long ls = li->local_stable, lu = li->local_unstable, plumbed = li->local_plumb;
  double c0 = us_now();
  us_Status e1 = us_stability_test(p->loc, node, rl, &err);
  double c1 = us_now();
  us_Status e2 = e1 ? e1 : us_stability_test(p->glob, node, rg, &err);
  p->tl += c1 - c0, p->tg += us_now() - c1;
  if (getenv("L3D_TRACE")) {
    fprintf(stderr, "    %d bodies: local %s %.1f ms (%s) | full %s %.1f ms (%s)\n",
            us_bitset_count(node), us_verdict_name(rl->verdict), 1e3 * (c1 - c0), rl->note,
            us_verdict_name(rg->verdict), 1e3 * (us_now() - c1), rg->note);
    if (s->nbody <= 40) print_node(s, node);
  }
  if (e1 || e2) {
    fprintf(stderr, "%s: test error: %s\n", p->name, err.msg);
    return -1;
  }
  int loc_stable = li->local_stable > ls, loc_unstable = li->local_unstable > lu;
  t->tests++;
  t->local += loc_stable || loc_unstable;
  t->local_stable += loc_stable;
  t->local_unstable += loc_unstable;
  t->plumb += li->local_plumb - plumbed;
  char why[200] = "";
  const char *bad = NULL;
  if (p->w2 && us_stability_test(p->w2, node, &p->r2, &err)) {
    fprintf(stderr, "%s: 2D test error: %s\n", p->name, err.msg);
    return -1;
  }
  if (rl->verdict != rg->verdict || rl->verdict == US_UNDECIDED)
    bad = "verdicts differ (or undecided)";
  else if (p->w2 && p->r2.verdict != rg->verdict)
    bad = "the 2D structure's verdict differs from its extrusion's";
  else if (local_count(p->glob) != 0)
    bad = "the workspace without local tests decided locally";
  else if ((loc_stable && rl->verdict != US_STABLE) || (loc_unstable && rl->verdict != US_UNSTABLE))
    bad = "the local counters disagree with the verdict";
  else if (rl->verdict == US_STABLE) {
    t->stable++;
    if (!rl->check.ok || !rg->check.ok) bad = "stable without a passing check";
    else if (rl->forces.ncontact > 0 && !us_certificate_check(s, node, &rl->forces, 1e-6).ok)
      bad = "the local forces fail us_certificate_check";
    else if (!forces_hold(s, node, &rl->forces, 1e-6, why, sizeof why))
      bad = "the local forces fail the test's own equilibrium check";
    else if (!forces_hold(s, node, &rg->forces, 1e-6, why, sizeof why))
      bad = "the full system's forces fail the test's own equilibrium check";
  } else {
    t->unstable++;
    if (loc_unstable) {
      us_Mechanism m = rl->mechanism; /* shares the arrays: checks renormalize in place */
      if (!rl->mechanism.ok || rl->mechanism.nbody == 0)
        bad = "local unstable without a mechanism";
      else if (!us_mechanism_check(s, node, &m, 1e-6))
        bad = "us_mechanism_check rejects the local mechanism";
      else if (!mechanism_holds(s, node, &m, 1e-6, why, sizeof why))
        bad = "the local mechanism fails the test's own power check";
      else t->mech++;
    }
    /* a mechanism the library accepted, from either workspace's full
       system, must pass this file's check too */
    if (!bad && !loc_unstable && rl->mechanism.nbody > 0 && rl->mechanism.ok) {
      us_Mechanism m = rl->mechanism;
      if (!mechanism_holds(s, node, &m, 1e-6, why, sizeof why))
        bad = "a checked mechanism (local workspace, full system) fails the test's own power check";
    }
    if (!bad && rg->mechanism.nbody > 0 && rg->mechanism.ok) {
      us_Mechanism m = rg->mechanism;
      if (!mechanism_holds(s, node, &m, 1e-6, why, sizeof why))
        bad = "the full system's checked mechanism fails the test's own power check";
      else t->global_mech++;
    }
  }
  if (bad) {
    fprintf(stderr, "%s, %d bodies: %s%s%s\n  local %s (%s)\n  full  %s (%s)\n", p->name,
            us_bitset_count(node), bad, why[0] ? ": " : "", why, us_verdict_name(rl->verdict),
            rl->note, us_verdict_name(rg->verdict), rg->note);
    if (p->w2)
      fprintf(stderr, "  2D    %s (%s)\n", us_verdict_name(p->r2.verdict), p->r2.note);
    print_node(s, node);
    return -1;
  }
  return 0;
}

/* ----------------------------------------------------------- sequences */

static unsigned long long rng_state = 0x3d10ca1u; /* seeded per structure (run_twin) */
static double rnd(void) { return test_rnd(&rng_state); }
static int below(int n) { return (int)(rnd() * n); }

/* Movable bodies in the order of their height (the centre of mass along
 * -gravity), lowest first; ties by index. */
static const us_Structure *sort_s;
static int by_height(const void *x, const void *y) {
  int a = *(const int *)x, b = *(const int *)y;
  double ha = -dot3(sort_s->bodies[a].com, sort_s->gravity);
  double hb = -dot3(sort_s->bodies[b].com, sort_s->gravity);
  return ha < hb ? -1 : ha > hb ? 1 : a - b;
}

static int movables(const us_Structure *s, int *out) {
  int n = 0;
  for (int i = 0; i < s->nbody; i++)
    if (!s->bodies[i].fixed) out[n++] = i;
  return n;
}

/* Bottom up: every prefix of the bodies by height. */
static int seq_build(Pair *p, us_Bitset *node, int *ord) {
  int n = movables(p->s, ord);
  sort_s = p->s;
  qsort(ord, (size_t)n, sizeof *ord, by_height);
  memset(node->w, 0, (size_t)node->nwords * sizeof(uint64_t));
  for (int k = 0; k < n; k++) {
    us_bitset_set(node, ord[k]);
    if (compare(p, node)) return -1;
  }
  return 0;
}

/* The plan's removal order: the remainder after every step (each stands
 * when a plan was found). *found: the plan's status was found. */
static int seq_plan(Pair *p, us_Bitset *node, int *found) {
  us_PlanSettings ps = us_plan_default_settings();
  us_Plan plan;
  us_Error err;
  *found = 0;
  if (us_plan(p->s, &ps, &plan, &err)) {
    fprintf(stderr, "%s: plan: %s\n", p->name, err.msg);
    return -1;
  }
  int r = 0;
  if (plan.status == US_PLAN_FOUND) {
    *found = 1;
    us_bitset_free(node);
    r = us_structure_movable_set(p->s, node);
    for (int k = 0; k < plan.nsteps && !r; k++) {
      us_bitset_clear(node, plan.order[k]);
      r = compare(p, node);
      if (!r && p->rl.verdict != US_STABLE) {
        fprintf(stderr, "%s: the plan's step %d falls\n", p->name, k);
        r = -1;
      }
    }
  }
  us_plan_free(&plan);
  return r;
}

/* From the full structure, remove random bodies one at a time until none
 * is left; every remainder is tested. */
static int seq_remove(Pair *p, us_Bitset *node, int *ord) {
  int n = movables(p->s, ord);
  for (int k = n - 1; k > 0; k--) { /* a random order */
    int j = below(k + 1), x = ord[k];
    ord[k] = ord[j], ord[j] = x;
  }
  us_bitset_free(node);
  if (us_structure_movable_set(p->s, node) || compare(p, node)) return -1;
  for (int k = 0; k < n; k++) {
    us_bitset_clear(node, ord[k]);
    if (compare(p, node)) return -1;
  }
  return 0;
}

/* An absent movable body that touches a present one or the ground, or
 * -1. */
static int touching_absent(const us_Structure *s, const us_Bitset *node) {
  for (int tries = 0; tries < 32 && s->ncontact > 0; tries++) {
    const us_Contact *k = &s->contacts[below(s->ncontact)];
    int a_in = side_present(s, node, k->a), b_in = side_present(s, node, k->b);
    if (a_in && !b_in) return k->b;
    if (b_in && !a_in) return k->a;
  }
  return -1;
}

/* An absent movable body at random, or -1. */
static int any_absent(const us_Structure *s, const us_Bitset *node) {
  int i = below(s->nbody);
  for (int k = 0; k < s->nbody; k++, i = (i + 1) % s->nbody)
    if (side_movable(s, i) && !us_bitset_get(node, i)) return i;
  return -1;
}

/* A present movable body at random, or -1. */
static int any_present(const us_Structure *s, const us_Bitset *node) {
  int i = below(s->nbody);
  for (int k = 0; k < s->nbody; k++, i = (i + 1) % s->nbody)
    if (side_movable(s, i) && us_bitset_get(node, i)) return i;
  return -1;
}

/* From the empty set, add random bodies (mostly ones touching what is
 * there, sometimes any) until all are present; every set is tested. */
static int seq_grow(Pair *p, us_Bitset *node) {
  memset(node->w, 0, (size_t)node->nwords * sizeof(uint64_t));
  for (;;) {
    int b = rnd() < 0.75 ? touching_absent(p->s, node) : -1;
    if (b < 0) b = any_absent(p->s, node);
    if (b < 0) return 0;
    us_bitset_set(node, b);
    if (compare(p, node)) return -1;
  }
}

static void flip(us_Bitset *b, int i) { b->w[i >> 6] ^= (uint64_t)1 << (i & 63); }

/* Near the border: from the full structure, add a touching body or remove
 * one per step (now and then two); a move after which the set fell is
 * mostly undone, so the walk keeps meeting both verdicts. */
static int seq_border(Pair *p, us_Bitset *node, int steps) {
  us_bitset_free(node);
  if (us_structure_movable_set(p->s, node)) return -1;
  int last[2] = {-1, -1};
  for (int k = 0; k < steps; k++) {
    if (compare(p, node)) return -1;
    if (p->rl.verdict != US_STABLE && rnd() < 0.6)
      for (int m = 0; m < 2; m++)
        if (last[m] >= 0) flip(node, last[m]);
    for (int m = 0; m < 2; m++) {
      last[m] = -1;
      if (m == 1 && rnd() >= 0.15) break;
      int b = rnd() < 0.5 ? touching_absent(p->s, node) : -1;
      if (b < 0) b = any_present(p->s, node);
      if (b >= 0) flip(node, b), last[m] = b;
    }
  }
  return 0;
}

/* Every sequence on one structure, through one pair of workspaces (the
 * local base carries over from sequence to sequence, as in a planner that
 * jumps); `walks` random removal walks, grown sets and border steps. */
static int run_twin(us_Structure *s, const us_Structure *s2, const char *name, int walks,
                    int border, Tally *t, int *plans) {
  if (!s) return fprintf(stderr, "%s: not generated\n", name), -1;
  if (s->dim != 3) return us_structure_free(s), fprintf(stderr, "%s: not 3D\n", name), -1;
  Pair p;
  memset(&p, 0, sizeof p);
  us_Bitset node = {0};
  int *ord = malloc((size_t)s->nbody * sizeof(int) + 1), found = 0;
  int r = !ord || pair_open(&p, s, s2, name, t) || us_bitset_init(&node, s->nbody);
  long tests0 = t->tests;
  rng_state = 0x3d10ca1u;
  for (const char *c = name; *c; c++) /* FNV-1a of the name */
    rng_state = (rng_state ^ (unsigned char)*c) * 0x100000001b3ull;
  rng_state ^= (unsigned long long)(s->friction * 1000.0) << 20;
  if (getenv("L3D_SEED"))
    rng_state ^= strtoull(getenv("L3D_SEED"), NULL, 0) * 0x9E3779B97F4A7C15ull;
  if (!rng_state) rng_state = 1;
  double t0 = us_now();
  if (!r) r = seq_build(&p, &node, ord);
  if (!r) r = seq_plan(&p, &node, &found);
  *plans += found;
  for (int w = 0; w < walks && !r; w++) r = seq_remove(&p, &node, ord);
  for (int w = 0; w < walks && !r; w++) r = seq_grow(&p, &node);
  if (!r) r = seq_border(&p, &node, border);
  fprintf(stderr,
          "  %s: %d bodies, %d contacts, plan %s, %ld sub-assemblies, %.2f s (local tests %.2f, "
          "full system %.2f)\n",
          name, s->nbody, s->ncontact, found ? "found" : "not found", t->tests - tests0,
          us_now() - t0, p.tl, p.tg);
  if (p.loc && p.glob)
    t->refined +=
        us_stability_info(p.loc)->cone3_refined + us_stability_info(p.glob)->cone3_refined;
  us_bitset_free(&node);
  pair_close(&p);
  free(ord);
  us_structure_free(s);
  return r ? -1 : 0;
}

static int run_structure(us_Structure *s, const char *name, int walks, Tally *t, int *plans) {
  return run_twin(s, NULL, name, walks, 40 * walks, t, plans);
}

/* Tilt gravity by `deg` degrees off the vertical towards azimuth `az`
 * (same magnitude): the structure on a slope. The mass properties and
 * contacts do not depend on gravity's direction; s->weight keeps. */
static us_Structure *tilted(us_Structure *s, double deg, double az) {
  if (!s) return NULL;
  double g = sqrt(dot3(s->gravity, s->gravity)), a = deg * PI / 180.0, b = az * PI / 180.0;
  s->gravity[0] = g * sin(a) * cos(b);
  s->gravity[1] = g * sin(a) * sin(b);
  s->gravity[2] = -g * cos(a);
  return s;
}

static void report(const char *what, const Tally *t) {
  fprintf(stderr,
          "%s: %ld sub-assemblies (%ld stable, %ld unstable); settled locally %ld (%ld stable, "
          "%ld of them by plumb lines; %ld unstable, %ld mechanisms checked); %ld full-system "
          "mechanisms checked\n",
          what, t->tests, t->stable, t->unstable, t->local, t->local_stable, t->plumb,
          t->local_unstable, t->mech, t->global_mech);
  fprintf(stderr,
          "%s: %ld directions added to friction polygons; largest sum of speeds per unit of "
          "gravity's power in a mechanism %.3g\n",
          what, t->refined, worst_speed);
  worst_speed = 0.0;
}

/* ------------------------------------------------------------------ cases */

static us_GenSettings gen(double mu, unsigned long seed) {
  us_GenSettings g = us_gen_default_settings();
  g.friction = mu;
  g.seed = seed;
  return g;
}

/* Towers, pyramids, walls: regular masonry, flat and turned joints. */
static void regular_agree(void) {
  Tally t = {0};
  int plans = 0;
  us_Error err;
  us_GenSettings g;
  static const double mus[] = {0.5, 0.2, 0.0};
  for (int m = 0; m < 3; m++) { /* at mu = 0.2 smaller ones (time) */
    g = gen(mus[m], 3u + (unsigned)m), g.n = 10;
    CHECK_INT(run_structure(us_gen_tower(&g, &err), "tower", 2 * SCALE, &t, &plans), ==, 0);
    g = gen(mus[m], 5u + (unsigned)m), g.n = m == 1 ? 3 : 4;
    CHECK_INT(run_structure(us_gen_pyramid3d(&g, &err), "pyramid3d", SCALE, &t, &plans), ==, 0);
    g = gen(mus[m], 7u), g.rows = m == 1 ? 4 : 5, g.cols = 5;
    CHECK_INT(run_structure(us_gen_wall3d(&g, &err), "wall3d", SCALE, &t, &plans), ==, 0);
  }
  g = gen(0.5, 11u), g.n = 12, g.jitter = 20;
  CHECK_INT(run_structure(us_gen_tower(&g, &err), "tower jitter 20", 2 * SCALE, &t, &plans), ==, 0);
  g = gen(0.2, 12u), g.n = 12, g.jitter = 45, g.width = 1.5;
  CHECK_INT(run_structure(us_gen_tower(&g, &err), "tower jitter 45", 2 * SCALE, &t, &plans), ==, 0);
  g = gen(0.5, 13u), g.rows = 4, g.cols = 4, g.returns = 2;
  CHECK_INT(run_structure(us_gen_wall3d(&g, &err), "wall3d returns", SCALE, &t, &plans), ==, 0);
  report("regular", &t);
  CHECK(plans >= 8);
  CHECK(t.stable > 200 && t.unstable > 200);
  CHECK(t.local > t.tests / 2);
  CHECK(t.plumb > t.local_stable / 4);
  CHECK(t.mech > 20);
}

/* Jenga towers with pieces out, random 3D stacks, domes. */
static void irregular_agree(void) {
  Tally t = {0};
  int plans = 0;
  us_Error err;
  us_GenSettings g;
  static const int rm[] = {2, 2, 3, 1, 4, 3, 5, 2, 6, 1}; /* (level, position) */
  g = gen(0.5, 1u), g.n = 8, g.height = 0.6, g.nremove = 5, g.remove = rm;
  CHECK_INT(run_structure(us_gen_jenga(&g, &err), "jenga mu 0.5", SCALE, &t, &plans), ==, 0);
  g = gen(0.0, 1u), g.n = 7, g.height = 0.6, g.nremove = 3, g.remove = rm;
  CHECK_INT(run_structure(us_gen_jenga(&g, &err), "jenga mu 0", SCALE, &t, &plans), ==, 0);
  for (int k = 0; k < 2; k++) {
    g = gen(k ? 0.2 : 0.5, 21u + (unsigned)k), g.n = 30, g.width = 3, g.max_tries = 300;
    CHECK_INT(run_structure(us_gen_random3d(&g, &err), "random3d", SCALE, &t, &plans), ==, 0);
  }
  /* the circular cones matter in the domes (hundreds of directions added
     to the friction polygons): up to tens of milliseconds a test, so one
     walk of each kind and shorter walks near the border */
  g = gen(0.5, 1u), g.n = 3, g.segments = 8, g.oculus = 30;
  CHECK_INT(run_twin(us_gen_dome(&g, &err), NULL, "dome mu 0.5", 1, 20 * SCALE, &t, &plans), ==, 0);
  g = gen(0.2, 1u), g.n = 3, g.segments = 8, g.oculus = 30, g.cap = 1;
  CHECK_INT(run_twin(us_gen_dome(&g, &err), NULL, "dome cap mu 0.2", 1, 10, &t, &plans), ==, 0);
  g = gen(0.0, 1u), g.n = 2, g.segments = 8, g.oculus = 45;
  CHECK_INT(run_structure(us_gen_dome(&g, &err), "dome mu 0", SCALE, &t, &plans), ==, 0);
  report("irregular", &t);
  CHECK(plans >= 4);
  CHECK(t.stable > 200 && t.unstable > 200);
  CHECK(t.local > t.tests * 2 / 5);
  CHECK(t.plumb > 50);
  CHECK(t.mech > 20);
  CHECK(t.refined > 100); /* the circular cones decided some (the domes) */
}

/* Gravity off the vertical: every joint inclined, friction decides. */
static void tilted_agree(void) {
  Tally t = {0};
  int plans = 0;
  us_Error err;
  us_GenSettings g;
  us_Structure *s;
  g = gen(0.5, 31u), g.n = 8;
  s = tilted(us_gen_tower(&g, &err), 10, 30);
  CHECK_INT(run_structure(s, "tilted tower", SCALE, &t, &plans), ==, 0);
  g = gen(0.2, 32u), g.n = 3;
  s = tilted(us_gen_pyramid3d(&g, &err), 8, 200);
  CHECK_INT(run_structure(s, "tilted pyramid3d", SCALE, &t, &plans), ==, 0);
  g = gen(0.5, 33u), g.rows = 4, g.cols = 4;
  s = tilted(us_gen_wall3d(&g, &err), 15, 100);
  CHECK_INT(run_structure(s, "tilted wall3d", SCALE, &t, &plans), ==, 0);
  g = gen(0.5, 34u), g.n = 20, g.width = 2.5, g.max_tries = 300;
  s = tilted(us_gen_random3d(&g, &err), 6, 250);
  CHECK_INT(run_structure(s, "tilted random3d", SCALE, &t, &plans), ==, 0);
  g = gen(0.5, 35u), g.n = 5, g.jitter = 30;
  s = tilted(us_gen_tower(&g, &err), 12, 300);
  CHECK_INT(run_structure(s, "tilted tower jitter", SCALE, &t, &plans), ==, 0);
  report("tilted", &t);
  CHECK(t.stable > 50 && t.unstable > 50);
  CHECK(t.local > t.tests / 2);
  CHECK(t.plumb > 30 && t.mech > 20);
}

/* The 2D structure s extruded along the horizontal into prisms `depth`
 * deep (2D y is 3D z), turned by `turn` about the vertical and shifted:
 * the same bodies in the same order, contacts found by the 3D detector.
 * Its verdict on every sub-assembly is the 2D one (a 3D solution mirrored
 * through the mid-plane and averaged projects to a 2D one; a 2D one split
 * over the two faces is a 3D one). */
static us_Structure *extrude(const us_Structure *s, double depth, double turn) {
  return test_extrude(s, depth, turn, 1.75, -0.5);
}

/* The 2D differential test's random piles (tests/piles.h: counterweights
 * on piers, leaning pairs, slabs leaning on blocks, arches, dropped boxes;
 * friction 0 or 0.3 to 0.8), extruded and turned: cantilevers and
 * inclined joints that the generators do not make, with the 2D verdict as
 * a third opinion on every sub-assembly. */
static void piles_agree(void) {
  Tally t = {0};
  int plans = 0, piles = 0;
  unsigned long long rng = 0x9113d5u;
  for (int k = 0; k < NPILES; k++) {
    us_Structure *s2 = pile_random(&rng, 4 + k % 9);
    if (!s2) continue;
    double turn = 2.0 * PI * pile_rnd(&rng), tilt = (pile_rnd(&rng) - 0.5) * 24.0 * PI / 180.0;
    us_Structure *s = extrude(s2, 0.5 + pile_rnd(&rng), turn);
    CHECK(s);
    if (k % 3 == 2) { /* on a slope along the 2D plane: the twins stay twins */
      double g = 9.81;
      s2->gravity[0] = g * sin(tilt), s2->gravity[1] = -g * cos(tilt);
      s->gravity[0] = cos(turn) * g * sin(tilt), s->gravity[1] = sin(turn) * g * sin(tilt);
      s->gravity[2] = -g * cos(tilt);
    }
    char name[32];
    snprintf(name, sizeof name, "pile %d", k);
    int r = run_twin(s, s2, name, 1, 40, &t, &plans);
    us_structure_free(s2);
    CHECK_INT(r, ==, 0);
    piles++;
  }
  report("piles", &t);
  CHECK(piles > NPILES * 3 / 4);
  CHECK(t.stable > 100 && t.unstable > 100);
  CHECK(t.local > t.tests / 3);
  CHECK(t.mech > 20);
}

/* ------------------------------------------------------------ the lever */

/* Box [x0, x1] x [y0, y1] x [z0, z1] turned by `turn` radians about the
 * vertical through the origin. */
static int box3(us_Structure *s, const char *id, double x0, double x1, double y0, double y1,
                double z0, double z1, double density, double turn) {
  double v[24], c = cos(turn), sn = sin(turn);
  for (int k = 0; k < 8; k++) {
    double x = k & 1 ? x1 : x0, y = k & 2 ? y1 : y0;
    v[3 * k] = c * x - sn * y;
    v[3 * k + 1] = sn * x + c * y;
    v[3 * k + 2] = k & 4 ? z1 : z0;
  }
  us_BodyDef d = us_default_body_def();
  d.id = id, d.nvert = 8, d.xyz = v, d.density = density;
  us_Error err;
  return us_structure_add_body(s, &d, &err);
}

/* A pier under a plank 8 long near its left end, a column of k blocks on
 * the plank's far left end, a load on its far right end; the whole turned
 * about the vertical. The column's weight tips the plank to the left about
 * the pier's left edge unless the load balances it. */
static us_Structure *lever(int k, double load_density, double turn) {
  /* masses: plank 1.6 (centre 1.5 right of the pier's left edge), column
     blocks 0.125 each (2.25 left of it), load 0.125 * density (5.25 right) */
  us_Structure *s = us_structure_new(3);
  s->friction = 0.6;
  box3(s, "pier", 2.5, 3.5, 0, 1, 0, 1, 1, turn);
  box3(s, "plank", 0, 8, 0, 1, 1, 1.2, 1, turn);
  char id[16];
  for (int i = 0; i < k; i++) {
    snprintf(id, sizeof id, "w%d", i);
    box3(s, id, 0, 0.5, 0.25, 0.75, 1.2 + 0.25 * i, 1.45 + 0.25 * i, 2, turn);
  }
  box3(s, "load", 7.5, 8, 0.25, 0.75, 1.2, 1.7, load_density, turn);
  return test_finalized(s, "lever");
}

static void lever_agrees(void) {
  Tally t = {0};
  int stood = 0, fell = 0, tipped = 0, grown = 0;
  for (int k = 8; k <= 24; k += 4)
    for (int d = 1; d <= 13; d += 2) {
      us_Structure *s = lever(k, d, 0.3 * (k + d));
      CHECK(s);
      Pair p;
      us_Bitset node = {0};
      int r = pair_open(&p, s, NULL, "lever", &t) || us_structure_movable_set(s, &node);
      int load = s->nbody - 1, with = -1;
      if (!r) r = compare(&p, &node); /* with the load: the base, if it stands */
      if (!r) with = p.rl.verdict;
      us_bitset_clear(&node, load);
      us_StabilityInfo before = *us_stability_info(p.loc);
      if (!r) r = compare(&p, &node); /* the load taken off */
      const us_StabilityInfo *after = us_stability_info(p.loc);
      if (!r && p.rl.verdict == US_STABLE) stood++;
      if (!r && p.rl.verdict == US_UNSTABLE) {
        fell++;
        if (with == US_STABLE) {
          /* the far load's removal tipped the plank: decided over more
             than the plank and the pier (grown regions or the full
             system), never at the first level */
          tipped++;
          grown += after->local_global > before.local_global ||
                   after->local_region_bodies - before.local_region_bodies > 2;
        }
      }
      us_bitset_free(&node);
      pair_close(&p);
      us_structure_free(s);
      CHECK_INT(r, ==, 0);
    }
  report("lever", &t);
  fprintf(stderr, "lever: %d stood without the load, %d fell (%d of them stood with it)\n", stood,
          fell, tipped);
  CHECK(stood > 0 && tipped > 0);
  CHECK_INT(grown, ==, tipped);
}

US_TEST_MAIN({"regular_agree", regular_agree}, {"irregular_agree", irregular_agree},
             {"tilted_agree", tilted_agree}, {"piles_agree", piles_agree},
             {"lever_agrees", lever_agrees})
