/* unstack: plan how to take a structure of rigid blocks apart (or build it
 * up) so that every intermediate structure stands under gravity.
 *
 * This is the whole public API. Every public symbol starts with `us_` (types
 * `us_Xxx`, constants `US_XXX`). Everything under src/ is private.
 *
 * Shape of the library (after MuJoCo and OSQP):
 *   - us_Structure   immutable description: bodies, materials, contacts.
 *                    Built with us_structure_new / us_structure_add_* and
 *                    sealed by us_structure_finalize (validation, mass
 *                    properties, contact detection). Read by everything else.
 *   - us_Stability   a stability workspace (settings / result / info / opaque
 *                    backend state) that tests sub-assemblies of one
 *                    structure, incrementally: the backend keeps its last
 *                    sub-assembly and may reuse work when the next differs by
 *                    one body.
 *   - us_plan        search of the disassembly graph.
 *   - errors (us_Status, with a message in us_Error) are kept apart from
 *     outcomes (us_Verdict, us_PlanStatus).
 *
 * Conventions: dimension is a parameter (2 now, 3 later); points, normals
 * and tangents are always stored with 3 components (z = 0 in 2D). A body's
 * wrench has 3 components in 2D (fx, fy, torque_z) and 6 in 3D. A contact
 * normal points from body `a` into body `b`: the contact force on b is
 * f_n * n + f_t1 * t1 (+ f_t2 * t2) and a receives the opposite.
 */
#ifndef UNSTACK_UNSTACK_H
#define UNSTACK_UNSTACK_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define US_VERSION "0.1.0"

/* US_API marks the library's ABI: the shared library (libunstack.so) is
 * built with hidden visibility, so only these declarations are exported;
 * the ~100 internal us_ functions under src/ are not (tests/abi.sh checks
 * that the two sets are equal). */
#if defined(__GNUC__)
#define US_API __attribute__((visibility("default")))
#else
#define US_API
#endif

/* ------------------------------------------------------------------ errors */

/* Errors: something prevented an answer. Outcomes are separate enums. */
typedef enum us_Status {
  US_OK = 0,
  US_ERR_USAGE,   /* bad arguments or settings */
  US_ERR_IO,      /* cannot open, read or write a file */
  US_ERR_PARSE,   /* malformed JSON / SVG */
  US_ERR_INPUT,   /* well-formed but invalid structure or plan */
  US_ERR_NOMEM,   /* an allocation failed */
  US_ERR_SOLVER,  /* a backend failed in a way that gives no verdict */
  US_ERR_TIME_LIMIT, /* a deadline passed before the work was done (reading
                        and finalizing a structure, us_LoadSettings) */
  US_ERR_COUNT
} us_Status;

typedef struct us_Error {
  us_Status code;
  char msg[512];
} us_Error;

US_API const char *us_status_name(us_Status s);
/* Set err (if not NULL) and return code. printf-style. */
US_API us_Status us_error_set(us_Error *err, us_Status code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
US_API void us_error_clear(us_Error *err);

/* ------------------------------------------------------------- allocation */

/* One allocation funnel. Tests may install a hook that fails the N-th
 * allocation (us_alloc_fail_after) to exercise out-of-memory paths. */
US_API void *us_malloc(size_t n);
US_API void *us_calloc(size_t count, size_t size);
US_API void *us_realloc(void *p, size_t n);
US_API void us_free(void *p);
US_API char *us_strdup(const char *s);
/* After `n` more successful allocations, every allocation of the calling
 * thread fails; n < 0 turns the hook off. Returns the number of live
 * allocations of the process (for leak checks). Both are thread-safe: the
 * hook is per thread, the count atomic. */
US_API long us_alloc_fail_after(long n);
US_API long us_alloc_live(void);

/* ------------------------------------------------------------------ bitset */

/* Dynamic bitset: sub-assemblies of any size. */
typedef struct us_Bitset {
  int nbits;
  int nwords;
  uint64_t *w;
} us_Bitset;

US_API int us_bitset_init(us_Bitset *b, int nbits); /* all clear; 0 or -1 on OOM */
US_API void us_bitset_free(us_Bitset *b);
US_API int us_bitset_copy(us_Bitset *dst, const us_Bitset *src); /* dst inited or zeroed */
static inline int us_bitset_get(const us_Bitset *b, int i) {
  return (int)((b->w[i >> 6] >> (i & 63)) & 1u);
}
static inline void us_bitset_set(us_Bitset *b, int i) { b->w[i >> 6] |= (uint64_t)1 << (i & 63); }
static inline void us_bitset_clear(us_Bitset *b, int i) { b->w[i >> 6] &= ~((uint64_t)1 << (i & 63)); }
US_API int us_bitset_count(const us_Bitset *b);
US_API int us_bitset_equal(const us_Bitset *a, const us_Bitset *b);
US_API uint64_t us_bitset_hash(const us_Bitset *b);
US_API void us_bitset_fill(us_Bitset *b); /* set bits 0..nbits-1 */

/* --------------------------------------------------------------- structure */

#define US_GROUND (-1) /* body index of the ground in contacts */

/* A convex polyhedron (3D), one part of a body. Before finalize, verts
 * holds the points given (nface == 0); finalize replaces them by their
 * convex hull: the hull's vertices, its faces (coplanar facets merged into
 * one planar convex polygon each) and its edges. */
typedef struct us_Polyhedron {
  int nvert;
  double *verts;     /* 3*nvert coordinates */
  int nface;         /* 0 until the hull is built */
  int *face_start;   /* nface+1 offsets into face_vert */
  int *face_vert;    /* each face's vertex indices, counter-clockwise seen
                        from outside (right-hand rule: the outward normal) */
  double *planes;    /* 4*nface: outward unit normal (nx, ny, nz) and d;
                        n . x <= d for every vertex x */
  int nedge;
  int *edges;        /* 2*nedge vertex indices, each edge once */
  double volume;     /* > 0 once built */
} us_Polyhedron;

typedef struct us_Body {
  char *id;          /* unique, user-given */
  int nvert;         /* polygon vertices (2D), 0 for a body without geometry
                        and for every 3D body (3D geometry is in parts) */
  double *verts;     /* 2*nvert, counter-clockwise after finalize */
  double mass;       /* > 0 for movable bodies; fixed bodies: infinite */
  double density;    /* used when mass was not given */
  double com[3];     /* centre of mass */
  double inertia;    /* 2D: polar moment about com (kg m^2); 3D: the mean
                        principal moment, trace(inertia3) / 3 */
  double friction;   /* < 0: not given (use the structure default) */
  int fixed;         /* terrain, piers: never removed, never moves */
  int mass_given;
  /* 3D only (0 / NULL in 2D): the body is the union of npart convex
   * polyhedra (1 for a polyhedron or a box, more for a compound), in world
   * coordinates; 0 parts: a body without geometry. */
  int npart;
  us_Polyhedron *parts;
  double inertia3[3][3]; /* 3D: inertia tensor about com, world axes (kg m^2) */
} us_Body;

typedef struct us_Contact {
  int a, b;          /* body indices; a may be US_GROUND; normal from a into b */
  double p[3];       /* point */
  double n[3];       /* unit normal */
  double t[2][3];    /* tangent basis; 2D uses t[0] = (-n_y, n_x, 0) */
  double mu;         /* Coulomb coefficient, >= 0 */
} us_Contact;

typedef struct us_Structure {
  int dim;              /* 2 or 3 */
  double gravity[3];    /* default (0, -9.81, 0); 3D: (0, 0, -9.81) */
  double friction;      /* default contact coefficient (0.5) */
  int ground;           /* 1: the half-plane y <= 0 (3D: the half-space
                           z <= 0) is a fixed support */
  double contact_tol;   /* > 0: one length tolerance for every contact and
                           shape test; <= 0 (default): each follows the
                           bodies involved (see us_ContactSettings) */
  int nbody;
  us_Body *bodies;
  int ncontact;
  us_Contact *contacts;
  int explicit_contacts; /* contacts came from the user, not detection */
  int contacts_detected; /* the contacts are detection's own output */
  double bbox[4];       /* xmin, ymin, xmax, ymax of all geometry and centres */
  double scale;         /* characteristic length: bbox diagonal (>0) */
  double weight;        /* total weight of movable bodies, |g| * sum m */
  /* the library's own bookkeeping (finalize state, array capacities, the
   * id index): opaque, never read or written by users */
  struct us_StructureInternal *internal;
  double bbox3[6];      /* 3D: xmin, ymin, zmin, xmax, ymax, zmax (scale is its
                           diagonal); 2D: the x, y range of bbox, z = 0 */
} us_Structure;

US_API us_Structure *us_structure_new(int dim);
US_API void us_structure_free(us_Structure *s);

/* One convex part of a 3D body: the convex hull of nvert points. */
typedef struct us_PartDef {
  int nvert;          /* >= 4 points, not all (almost) in one plane */
  const double *xyz;  /* 3*nvert coordinates (copied) */
} us_PartDef;

/* Description of a body for us_structure_add_body. Start from
 * us_default_body_def() and set what differs. 2D: a polygon (nvert, xy).
 * 3D: a convex polyhedron, the hull of nvert points xyz, or a compound of
 * npart convex parts (then nvert is 0); one rigid body either way. */
typedef struct us_BodyDef {
  const char *id;    /* required: unique, not "ground" (copied) */
  int nvert;         /* 2D: number of vertices (>= 3 to finalize); 3D: of points */
  const double *xy;  /* 2D: 2*nvert coordinates, any orientation (copied) */
  double density;    /* default 1; used when mass is not given */
  double mass;       /* default 0: not given, density * area (3D: volume) */
  int fixed;         /* default 0; 1: terrain or pier, never moves */
  double friction;   /* default -1: not given, the structure's coefficient */
  const double *xyz; /* 3D: 3*nvert coordinates, the hull is taken (copied) */
  int npart;         /* 3D compound: number of convex parts (default 0) */
  const us_PartDef *parts; /* 3D compound: the parts (copied) */
} us_BodyDef;

/* The defaults above: id NULL, nvert 0, xy NULL, density 1, mass 0,
 * fixed 0, friction -1, xyz NULL, npart 0, parts NULL. */
US_API us_BodyDef us_default_body_def(void);

/* Add a body (a polygon in 2D, a convex polyhedron or compound in 3D).
 * Returns the body index or -1 (err set: empty, reserved or duplicate id,
 * bad vertex array, geometry of the other dimension, OOM). */
US_API int us_structure_add_body(us_Structure *s, const us_BodyDef *def, us_Error *err);

/* Thin wrapper of us_structure_add_body kept for old callers: the fields
 * of us_BodyDef in order (density <= 0 means 1, mass <= 0 means not
 * given). Prefer us_structure_add_body. */
US_API int us_structure_add_polygon(us_Structure *s, const char *id, int nvert, const double *xy,
                             double density, double mass, int fixed, double friction,
                             us_Error *err);
/* A body without geometry (only with explicit contacts); center has dim
 * components. */
US_API int us_structure_add_point_body(us_Structure *s, const char *id, double mass,
                                const double *center, int fixed, us_Error *err);
/* Explicit contact; a = US_GROUND or a body index. mu < 0: use the rule
 * (the smaller of the two bodies' coefficients, each defaulting to the
 * structure's). The tangent basis is derived from the normal. */
US_API int us_structure_add_contact(us_Structure *s, int a, int b, const double *p, const double *n,
                             double mu, us_Error *err);
US_API int us_structure_find_body(const us_Structure *s, const char *id); /* index or -1 */

/* Validate geometry (2D: >=3 vertices, finite, non-zero area, simple; 3D:
 * >= 4 points per part not in one plane, finite, the convex hull of each
 * part built, parts of one body not overlapping; both: not below the
 * ground, no interpenetration beyond the pair's tolerance), compute mass
 * properties (3D: mass, com and the inertia tensor, exactly), and detect
 * contacts unless explicit contacts were given. Messages name the body ids. */
US_API us_Status us_structure_finalize(us_Structure *s, us_Error *err);
/* 1 after a successful us_structure_finalize until the next body is added. */
US_API int us_structure_is_finalized(const us_Structure *s);
/* The same, stopped with US_ERR_TIME_LIMIT once us_now() passes deadline
 * (0: none); the hulls and contact detection read the clock as they go. */
US_API us_Status us_structure_finalize_until(us_Structure *s, double deadline, us_Error *err);

/* The friction coefficient of a contact between two bodies (a may be
 * US_GROUND): the smaller of the two sides' coefficients, each side
 * defaulting to the structure's coefficient. */
US_API double us_structure_pair_friction(const us_Structure *s, int a, int b);

/* Number of movable bodies. */
US_API int us_structure_movable_count(const us_Structure *s);
/* Initialize `out` as the set of all movable bodies (the full structure).
 * 0, or -1 when out of memory. */
US_API int us_structure_movable_set(const us_Structure *s, us_Bitset *out);

/* ---------------------------------------------------------------- contacts */

typedef struct us_ContactSettings {
  /* > 0: this length tolerance for every pair. <= 0: each pair's own,
   * 1e-6 times the smaller of the two bodies' bounding-box diagonals (a
   * body against the ground: its own diagonal), with no absolute floor. */
  double tol;
  /* 1: the slow reference for tests: every pair of bodies, every edge
   * against every vertex, duplicates against every earlier contact
   * (quadratic); the contacts must be the same as with 0 (default). */
  int reference;
} us_ContactSettings;

/* Detected contacts: a, b, p and n filled (normal from a into b); mu is -1
 * (the friction rule applies when installed) and t is left zero. */
typedef struct us_ContactList {
  us_Contact *c;
  int n, cap;
} us_ContactList;

/* Detect contacts (2D: vertex-on-edge; 3D: face-face patches, edge-face,
 * vertex-face and edge-edge points, docs/format.md) between all bodies and
 * with the ground into `out` (caller-owned, zero-initialised or reused; its old
 * entries are dropped); the structure is not changed. Polygons must be
 * counter-clockwise (as finalize leaves them). Broad phase over bodies,
 * then over the edges of each candidate pair, so the cost is near-linear
 * in the total number of vertices. Interpenetration beyond the pair's
 * tolerance is US_ERR_INPUT naming both bodies. */
US_API us_Status us_detect_contacts(const us_Structure *s, const us_ContactSettings *set,
                             us_ContactList *out, us_Error *err);
US_API void us_contact_list_free(us_ContactList *l);

/* Orient the polygons counter-clockwise, detect contacts with the given
 * settings (NULL: s->contact_tol) and replace s->contacts by them. On error
 * the structure's contacts are left as they were (after an out-of-memory
 * while installing them, they are cleared). */
US_API us_Status us_structure_detect_contacts(us_Structure *s, const us_ContactSettings *set,
                                       us_Error *err);

/* --------------------------------------------------------------- stability */

typedef enum us_Method {
  US_METHOD_LP = 0,     /* statics LP, CLP */
  US_METHOD_LPSOLVE,    /* statics LP, lp_solve 5.5, from scratch */
  US_METHOD_LCP,        /* Baraff/Dantzig LCP from scratch */
  US_METHOD_LCP_REUSE,  /* LCP with computation reuse */
  US_METHOD_LP_LCP,     /* statics LP as an LCP, Lemke's method, warm-started */
  US_METHOD_COUNT,      /* number of concrete methods */
  US_METHOD_AUTO = US_METHOD_COUNT /* (default) the fastest exact method for the
                                      structure (us_method_resolve) */
} us_Method;
/* The concrete method `auto` stands for on structure s (others map to
 * themselves). */
US_API us_Method us_method_resolve(us_Method m, const us_Structure *s);
US_API const char *us_method_name(us_Method m);
US_API int us_method_parse(const char *name, us_Method *out); /* 0 ok, -1 unknown */

typedef enum us_Verdict {
  US_STABLE = 0,
  US_UNSTABLE = 1,
  US_UNDECIDED = 2  /* a limit was hit and no fallback could decide */
} us_Verdict;
US_API const char *us_verdict_name(us_Verdict v);

/* Tolerances and limits of the LP backends (lp, lpsolve, and the LP that
 * settles the LCP's open cases). The LP works in normalized units: forces
 * in units of the total weight, torques of weight * size. */
typedef struct us_LpSettings {
  double primal_tol;    /* CLP primal feasibility tolerance (default 1e-9) */
  double warm_accept;   /* a warm-started CLP run is kept when its sum of primal
                           infeasibilities is at most this (default 1e-9) */
  double farkas_slack;  /* slack, relative to |rhs . y|, accepted when checking
                           a Farkas ray before naming a body (default 1e-9) */
  double n_column_mu;   /* contacts with mu above this also get the generator n
                           besides the two cone edges (default 1) */
} us_LpSettings;
US_API us_LpSettings us_lp_default_settings(void);

/* Progress of a stability workspace (us_StabilitySettings.progress). */
typedef struct us_Progress {
  long tests;        /* tests done by the workspace */
  int bodies;        /* movable bodies in the sub-assembly just tested */
  double elapsed;    /* seconds since the workspace was created */
  double time_left;  /* seconds to its deadline, or -1 without one */
} us_Progress;
typedef void (*us_ProgressFn)(const us_Progress *p, void *user);

typedef struct us_StabilitySettings {
  us_Method method;
  double cert_tol;    /* certificate tolerance, relative (default 1e-6) */
  int max_pivots;     /* LCP pivot limit; <= 0: automatic */
  int verbose;
  us_LpSettings lp;   /* the LP backends (us_lp_default_settings) */
  int local;          /* exact local tests (docs/local.md) for lp and auto:
                         0 (default) or 1 on, -1 off */
  int local_min_bodies; /* smaller sub-assemblies go to the full system
                           (<= 0: default 1, every size tested locally) */
  int skip_forces;    /* 1: a stable result carries its check but no forces
                         (res->forces empty; the planner's searches) */
  double time_limit;  /* > 0: tests that start or run past this many seconds
                         after us_stability_new stop undecided ("time limit";
                         counted in us_StabilityInfo.timed_out); 0: none */
  us_ProgressFn progress; /* optional: called after a test at most about 4
                             times a second (plan and verify show it) */
  void *progress_user;
} us_StabilitySettings;
/* Defaults; us_stability_new and us_stability_test expect settings that
 * started from here (or a zeroed struct: zero LP fields mean defaults). */
US_API us_StabilitySettings us_stability_default_settings(void);

/* Contact forces of one sub-assembly: for each active contact, `dim`
 * components (f_n, f_t1[, f_t2]) in the contact's frame. */
typedef struct us_Forces {
  int ncontact;      /* number of active contacts */
  int cap;
  int *contact;      /* indices into structure->contacts */
  double *f;         /* dim * ncontact */
} us_Forces;
US_API void us_forces_free(us_Forces *f);

typedef struct us_CertCheck {
  int ok;
  double max_force_residual;   /* relative to the structure's weight */
  double max_torque_residual;  /* relative to weight * scale */
  double max_cone_violation;   /* distance of a force from its friction cone,
                                  relative to weight (does not grow with mu) */
  double max_sign_violation;   /* negative normal force, relative to weight */
  int worst_body;              /* body with the largest residual, or -1 */
  int worst_contact;           /* contact with the largest violation, or -1 */
} us_CertCheck;

#define US_LOCAL_BUCKETS 16
typedef struct us_StabilityInfo {
  long tests;            /* tests run by this workspace */
  long pivots;           /* LCP pivots (total) */
  long lp_fallbacks;     /* LCP verdicts settled by the LP */
  long lcp_seeds;        /* lcp-reuse restarts from the LP's forces after a fallback */
  long lcp_skips;        /* lcp-reuse tests sent straight to the LP (back-off) */
  long lcp_retries;      /* lcp-reuse failed repairs solved again from scratch */
  long reused;           /* tests that started from the previous solution */
  double solve_time;     /* seconds in the backend */
  double check_time;     /* seconds re-checking certificates */
  /* local tests (docs/local.md) */
  long local_stable;     /* tests proven stable on a region */
  long local_unstable;   /* tests proven unstable on a region */
  long local_global;     /* tests handed to the full system */
  long local_lps;        /* region LPs solved */
  long local_region_bodies; /* sum of the deciding regions' sizes */
  long timed_out;        /* tests stopped undecided by the deadline */
  long local_settled[US_LOCAL_BUCKETS]; /* tests settled by a region of
                            2^k .. 2^(k+1) - 1 bodies (bucket 0: 0 or 1) */
  long local_plumb;      /* of local_stable: proven by plumb lines, no LP */
  long local_lever;      /* of local_stable: proven by a lever (a cantilever held
                            by its counterweight), no LP */
  long cone_lemke;       /* LCP tests settled by the cone LCP's Lemke fallback */
  long cone_lemke_failed; /* Lemke fallbacks that did not settle (to the LP) */
  long cone3_outer;      /* 3D: tests whose inner-polygon LP was infeasible, so
                            the outer polygons' LP ran (docs/cones3d.md) */
  long cone3_refined;    /* 3D: directions added to contacts' friction polygons */
  long cone3_open;       /* 3D: tests whose claim is the outer polygons' forces (no
                            direction left to add); the certificate decides */
  long band_referee;     /* tests in the boundary band, decided by the referee
                            (docs/planning.md, "The boundary band") */
  long local_global_part; /* of local_global: only the components that changed
                            solved, the rest held by the base (docs/local.md) */
  long local_global_sparse; /* of local_global: decided by the sparse simplex
                            from the base's forces (2D, docs/local.md) */
} us_StabilityInfo;

/* The certificate of an unstable verdict: a virtual motion of some bodies
 * (the others held still) on which gravity does positive work while every
 * force any contact could carry (inside its cone, normal force >= 0) does
 * work >= 0, so no contact forces can balance gravity (a Farkas ray of the
 * equilibrium system, read as velocities). Normalized so that gravity's
 * power is 1 in units of the total weight times the structure's scale. */
typedef struct us_Mechanism {
  int nbody, cap;
  int *body;             /* the moving bodies */
  double *v;             /* per body, 3 in 2D: vx, vy, omega; 6 in 3D: vx,
                            vy, vz, omega x, y, z; omega in rad per unit
                            of the structure's scale */
  int ok;                /* the independent check (us_mechanism_check) passed */
  double worst_power;    /* most negative power of a unit cone generator
                            (relative; 0 if none), or +INF when unchecked */
} us_Mechanism;
US_API void us_mechanism_free(us_Mechanism *m);
/* The independent check of a mechanism on sub-assembly `present`: gravity's
 * power (must be > 0, it is normalized to 1) and the worst power of the
 * unit generators of every active contact's cone (must be >= -tol).
 * Fills m->ok and m->worst_power; returns m->ok. */
US_API int us_mechanism_check(const us_Structure *s, const us_Bitset *present, us_Mechanism *m,
                              double tol);

typedef struct us_StabilityResult {
  us_Verdict verdict;
  us_Forces forces;        /* filled when stable */
  us_CertCheck check;      /* the independent re-check of forces */
  int unstable_body;       /* evidence when unstable, if known, else -1 */
  us_Mechanism mechanism;  /* when unstable and the solver gave a ray (lp,
                              auto): the motion, checked (nbody 0: none) */
  char note[128];          /* evidence text (solver status), may be empty */
} us_StabilityResult;
/* A result owns its force arrays and reuses them from test to test: call
 * init (or zero it) once before its first use, free when done. An
 * uninitialized result must never reach us_stability_test. */
US_API void us_stability_result_init(us_StabilityResult *r);
US_API void us_stability_result_free(us_StabilityResult *r);

typedef struct us_Stability us_Stability; /* opaque workspace */

US_API us_Stability *us_stability_new(const us_Structure *s, const us_StabilitySettings *set,
                               us_Error *err);
US_API void us_stability_free(us_Stability *w);
/* Test the sub-assembly `present` (bits over body indices; fixed bodies are
 * always present, their bits are ignored). Incremental: the workspace
 * remembers the last sub-assembly and tells the backend which bodies were
 * added or removed. res must be initialized (us_stability_result_init or
 * zeroed; a result of an earlier test is fine). Returns US_OK and fills
 * res, or an error. */
US_API us_Status us_stability_test(us_Stability *w, const us_Bitset *present, us_StabilityResult *res,
                            us_Error *err);
US_API const us_StabilityInfo *us_stability_info(const us_Stability *w);
/* Tests that run past `deadline` (a us_now() time; 0: none) stop inside
 * the solver and answer US_UNDECIDED with a note saying so. */
US_API void us_stability_set_deadline(us_Stability *w, double deadline);
/* Test the whole structure (every movable body present). */
US_API us_Status us_stability_test_full(us_Stability *w, us_StabilityResult *res, us_Error *err);

/* Tests by change (docs/planning.md, "Tests by change"): the workspace
 * holds a current sub-assembly, empty after us_stability_new, which the
 * caller changes one body at a time and then tests; a test costs what the
 * change costs, whatever the number of bodies (us_stability_test's bitset
 * costs a word-wise pass over it). add / remove: body (an index) becomes
 * present / absent; no change if it already was, nor for a fixed body
 * (always present); US_ERR_USAGE for an index out of range. set_current
 * makes the movable bits of `present` the current sub-assembly (a pass
 * over its words); us_stability_test(w, present) is set_current then
 * test_current, so both APIs can be mixed and give the same verdicts. */
US_API us_Status us_stability_add(us_Stability *w, int body, us_Error *err);
US_API us_Status us_stability_remove(us_Stability *w, int body, us_Error *err);
US_API us_Status us_stability_set_current(us_Stability *w, const us_Bitset *present,
                                          us_Error *err);
/* Test the current sub-assembly (as us_stability_test). */
US_API us_Status us_stability_test_current(us_Stability *w, us_StabilityResult *res,
                                           us_Error *err);
/* The current sub-assembly (movable bits; owned by the workspace, valid
 * until its next change) and its number of bodies. */
US_API const us_Bitset *us_stability_current(const us_Stability *w);
US_API int us_stability_current_count(const us_Stability *w);

/* Which of the many admissible force sets to show (forces are not unique;
 * src/stability/represent.c, docs/render.md "Forces"): the solver's own
 * (a vertex), the one that maximises the smallest normal force with the
 * total at most twice the least (then the least total keeping that
 * margin), the least total force (friction counted twice), or the least
 * sum of squares (a QP: the load spread evenly). */
typedef enum us_ForceSet {
  US_FORCESET_SOLVER = 0, US_FORCESET_MARGIN, US_FORCESET_MIN_SUM, US_FORCESET_MIN_NORM
} us_ForceSet;
US_API const char *us_force_set_name(us_ForceSet kind);
/* The representative forces of sub-assembly `present` by rule `kind`
 * (margin, min-sum or min-norm), solved with CLP (3D: inside the inner friction
 * polygons). res->verdict US_STABLE: res->forces passed the certificate
 * check (res->check) at set->cert_tol (set NULL: defaults); US_UNDECIDED:
 * no such set found (res->note says why; it does not mean unstable).
 * res must be initialized (us_stability_result_init). */
US_API us_Status us_stability_forces_representative(const us_Structure *s, const us_Bitset *present,
                                                    us_ForceSet kind, const us_StabilitySettings *set,
                                                    us_StabilityResult *res, us_Error *err);

/* Independent re-check of forces for a sub-assembly, without any solver. */
US_API us_CertCheck us_certificate_check(const us_Structure *s, const us_Bitset *present,
                                  const us_Forces *f, double tol);

/* Contacts active in a sub-assembly: both sides present (ground and fixed
 * bodies always are) and at least one side movable. Fills idx (capacity
 * s->ncontact) and returns the count. */
US_API int us_active_contacts(const us_Structure *s, const us_Bitset *present, int *idx);

/* ----------------------------------------------------------------- planner */

typedef enum us_Search {
  US_SEARCH_ASSEMBLE = 0, /* greedy assembly from the ground, exact decision where it is
                             stuck (docs/planning.md; default) */
  US_SEARCH_DFS,          /* depth-first search of the disassembly graph */
  US_SEARCH_BFS,          /* breadth-first search */
  US_SEARCH_RANDOM        /* randomized depth-first search with restarts */
} us_Search;
typedef enum us_Order { US_ORDER_HIGHEST = 0, US_ORDER_LOWEST, US_ORDER_INPUT } us_Order;
typedef enum us_Direction { US_DIR_DOWN = 0, US_DIR_UP } us_Direction;
/* Which removals are allowed besides stability (kinematics). */
typedef enum us_Removal {
  US_REMOVAL_ANY = 0, /* any body, whatever touches it (weak stability only) */
  US_REMOVAL_UP,      /* lifted straight up without hitting a remaining body */
  US_REMOVAL_FREE     /* some translation frees it (cone test on its contacts) */
} us_Removal;

/* Culling rules of the graph searches (DFS, BFS, random), bit flags. */
enum {
  US_RULE_MEMO = 1,       /* nodes known dead are never tested or expanded again */
  US_RULE_GROUND = 2,     /* a node with a body not connected to the ground is
                             unstable without a test */
  US_RULE_UNION = 4,      /* a node whose components are each known stable is
                             stable without a test (union theorem) */
  US_RULE_COMPONENTS = 8, /* components of the structure are planned apart */
  US_RULE_GREEDY = 16,    /* a node is dead iff greedy assembly inside it fails:
                             dead sub-graphs are never explored */
  US_RULE_ALL = 31
};

typedef enum us_PlanStatus {
  US_PLAN_FOUND = 0,
  US_PLAN_NONE,      /* proven: no order with steps of at most max_group bodies */
  US_PLAN_UNSTABLE,  /* the full structure does not stand */
  US_PLAN_LIMIT,     /* max_tests or time_limit reached */
  US_PLAN_UNDECIDED  /* no order found, but the answer depends on stability
                        tests that could not be decided (us_Verdict
                        US_UNDECIDED; stats.undecided > 0, the first one's
                        reason in us_Plan.note): neither none nor unstable
                        is proven. A found plan only ever uses nodes tested
                        certified stable. */
} us_PlanStatus;
/* Names of the planner's enums (the words of the plan files and the CLI);
 * parse returns 0, or -1 for an unknown word. */
US_API const char *us_plan_status_name(us_PlanStatus s);
US_API int us_plan_status_parse(const char *w, us_PlanStatus *out);
US_API const char *us_search_name(us_Search s);
US_API int us_search_parse(const char *w, us_Search *out);
US_API const char *us_order_name(us_Order o);
US_API int us_order_parse(const char *w, us_Order *out);
US_API const char *us_direction_name(us_Direction d);
US_API int us_direction_parse(const char *w, us_Direction *out);
US_API const char *us_removal_name(us_Removal r);
US_API int us_removal_parse(const char *w, us_Removal *out);
US_API const char *us_rule_name(int bit); /* one US_RULE_* bit */
/* "all", "none" or a comma-separated list of rule names. */
US_API int us_rules_parse(const char *list, unsigned *out);

/* Assembly actions with hands: place b (b enters held), grab a placed
 * body, release a held one (after which the placed bodies must stand with
 * the held ones fixed). */
typedef enum us_ActionVerb { US_ACTION_PLACE = 0, US_ACTION_GRAB, US_ACTION_RELEASE } us_ActionVerb;
typedef struct us_Action {
  us_ActionVerb verb;
  int body;
} us_Action;
US_API const char *us_action_name(us_ActionVerb v);
US_API int us_action_parse(const char *w, us_ActionVerb *out);

typedef struct us_PlanSettings {
  us_Search search;
  us_Order order;        /* graph searches: which body to try first */
  us_Direction direction;/* graph searches: from the full structure or the ground */
  us_Removal removal;    /* kinematics; not ANY needs a graph search */
  int max_group;         /* largest step (bodies moved at once), >= 1 (default 1);
                            0: automatic, the smallest that gives an order */
  unsigned rules;        /* US_RULE_* flags of the graph searches (default all) */
  unsigned long seed;    /* random search */
  long max_tests;        /* <= 0: unlimited */
  double time_limit;     /* seconds, <= 0: unlimited */
  long max_exact_tests;  /* tests one exact decision (where the greedy is stuck)
                            may use before the plan ends in `limit`; it is
                            exponential in the worst case (default 100000;
                            <= 0: unlimited) */
  int certificates;      /* keep a certificate per step */
  us_StabilitySettings stability;
  int hands;             /* bodies held at once (docs/planning.md, "Hands"): 1
                            (default) today's one-at-a-time plan; >= 2 an
                            action plan; 0: auto, the smallest that gives one */
} us_PlanSettings;
US_API us_PlanSettings us_plan_default_settings(void);

typedef struct us_PlanStats {
  long tests;            /* stability tests run: stable + unstable + undecided,
                            plus the certificate re-tests of a found plan */
  long stable;
  long unstable;
  long undecided;        /* tests whose verdict was undecided (taken as "not known
                            stable": never part of a found plan, never a proof) */
  long revisited;        /* nodes skipped because already known (memo rule) */
  long nodes_expanded;
  long max_depth;
  long backtracks;       /* graph searches: dead ends stepped back from */
  long saved_ground;     /* tests saved by the ground-connectivity rule */
  long saved_union;      /* tests saved by the union rule (components known stable) */
  long exact_checks;     /* greedy rule: exact decisions asked (root checks) */
  long greedy_checks;    /* greedy rule: greedy assemblies run by the rescue */
  long components;       /* independent parts planned apart (components rule) */
  long retries_skipped;  /* assemble: re-tests skipped because a body's part did not change */
  long exhaustive;       /* connected sets the greedy could not rebuild, searched exhaustively */
  long cuts;             /* connected sets proven unbuildable by the cut: no body (or group)
                            above the greedy's stuck set can stand even with it held still */
  long held_tests;       /* the cut's small LPs ("stands with the rest held still?") */
  long restarts;         /* random search */
  double time_total;     /* seconds */
  double time_setup;
  double time_search;
  double time_solve;     /* inside stability tests */
  double time_check;     /* certificate re-checks */
  size_t memo_bytes;     /* memory held by the failed-node set */
  us_StabilityInfo stability;
} us_PlanStats;

typedef struct us_Plan {
  us_PlanStatus status;
  int nsteps;            /* number of bodies removed (length of order) when found */
  int *order;            /* body indices in removal order */
  int ngroups;           /* number of steps; == nsteps when every step is one body */
  int *group_start;      /* [ngroups + 1] (NULL: one body per step): step k removes order[group_start[k] ..
                            group_start[k + 1] - 1] */
  int max_group;         /* largest step used (found), or the bound searched (none) */
  us_Forces *certs;      /* with certificates: ngroups+1 entries, certs[k] =
                            forces of the structure before step k
                            (certs[ngroups] is the empty structure) */
  /* status none: a maximal sub-assembly that can be built from the ground
     (the greedy's; it need not be unique) and the movable bodies outside it
     (no order with steps of at most max_group bodies reaches them all) */
  int nbuildable, *buildable;
  int nblocked, *blocked;
  char note[128];        /* stats.undecided > 0: the first undecided test's reason */
  us_PlanStats stats;
  /* with buildable: buildable is the greedy's placement order, in nbuild
     steps, build_start[nbuild + 1] offsets into it */
  int nbuild, *build_start;
  /* hands != 1 in the settings: the assembly actions (found) */
  int hands;             /* largest number of bodies held at once (found), or
                            the bound searched (none) */
  int hands_lower;       /* every H < hands_lower is proven impossible; the
                            minimum is proven when hands_lower == hands */
  int nactions;
  us_Action *actions;    /* [nactions] in assembly order */
  us_Forces *release_certs; /* with certificates: [nactions], action k's forces
                            when it is a release (the placed bodies, the held
                            ones fixed), else empty */
} us_Plan;
US_API void us_plan_free(us_Plan *p);

/* Plan a removal order. Outcomes (found, none, unstable, limit, undecided)
 * are in out->status; errors (bad settings, out of memory, backend
 * failures) are returned, out is then empty. err may be NULL. */
US_API us_Status us_plan(const us_Structure *s, const us_PlanSettings *set, us_Plan *out,
                  us_Error *err);

/* Re-check a removal order step by step: the full structure, then the
 * remainder after every removal, each with a fresh stability test whose
 * certificate is re-checked. A test that cannot be decided does not stop
 * the walk: a later step that falls still proves the order invalid; when
 * none falls the report is undecided. err may be NULL. */
typedef struct us_VerifyReport {
  int ok;              /* every step stands and the order removes all bodies */
  int full_unstable;   /* the full structure does not stand */
  int failed_step;     /* 0-based removal after which the remainder falls, or -1 */
  int undecided;       /* some test was undecided and nothing proves the order
                          invalid (then !ok, !full_unstable, failed_step == -1,
                          !incomplete): neither valid nor invalid is proven */
  int undecided_step;  /* undecided: the first undecided test, -1 the full
                          structure, else the 0-based removal (step) after which
                          it was made */
  char note[128];      /* undecided: that test's reason */
  int incomplete;      /* the order leaves movable bodies in place */
  int remaining;       /* bodies left after the failing step / at the end */
  int unstable_body;   /* evidence from the test, or -1 */
  int steps_checked;
  double max_force_residual, max_torque_residual; /* worst over the steps */
} us_VerifyReport;
US_API us_Status us_verify_order(const us_Structure *s, const us_StabilitySettings *set, const int *order,
                          int n, us_VerifyReport *rep, us_Error *err);
/* The same for an order in steps: group_start[ngroups + 1] offsets into order
 * (NULL: one body per step); the remainder is tested after every step. With
 * groups, failed_step is the 0-based step. */
US_API us_Status us_verify_steps(const us_Structure *s, const us_StabilitySettings *set, const int *order,
                          int n, const int *group_start, int ngroups, us_VerifyReport *rep,
                          us_Error *err);

/* Re-check an action plan (docs/format.md): never more than `hands`
 * bodies held, every body placed once, a release only of a held body, all
 * placed and none held at the end (else US_ERR_INPUT naming the action's
 * index), and after every release a fresh stability test of the placed
 * bodies with the held ones fixed, its certificate re-checked. rep as in
 * us_verify_order with failed_step the 0-based index of the action whose
 * release falls (undecided_step likewise; -1 the full structure). */
US_API us_Status us_verify_actions(const us_Structure *s, const us_StabilitySettings *set,
                                   int hands, const us_Action *actions, int n,
                                   us_VerifyReport *rep, us_Error *err);

/* Removal kinematics of an order (one body a step): before each removal the
 * body must be able to leave past the bodies still there (docs/kinematics.md).
 * failed_step: the first 0-based removal that cannot be made, or -1;
 * blocker: a body in its way (US_GROUND for the ground, -2 when unknown). */
US_API us_Status us_verify_removals(const us_Structure *s, us_Removal removal, const int *order, int n,
                             int *failed_step, int *blocker, us_Error *err);

/* -------------------------------------------------------------- generators */

typedef struct us_GenSettings {
  int n;             /* column: blocks; pyramid: rows; arch: voussoirs */
  int rows, cols;    /* wall; random: rows */
  double width;      /* block width (random: structure width in blocks) */
  double height;     /* block height */
  double radius, thickness; /* arch */
  int loose;         /* arch: unit blocks standing on the ground beside it (0) */
  double friction;   /* default coefficient written to the structure */
  double density;
  unsigned long seed;
  int max_tries;     /* random: attempts per row before giving up */
  double depth;      /* 3D block depth along y (tower, pyramid3d; default 1);
                        wall3d bricks are `thickness` deep */
  double jitter;     /* tower: largest turn of a box about the vertical, in
                        degrees (default 0) */
  int segments;      /* dome: voussoirs per course (default 12) */
  double oculus;     /* dome: half-angle of the opening at the top, degrees
                        from the vertical, in (0, 90) (default 15) */
  int cap;           /* dome: close the opening with one keystone cap (0) */
  int nremove;       /* jenga: pieces left out, remove[2k] the level (1-based */
  const int *remove; /*   from the bottom), remove[2k+1] the position 1..3 */
  int returns;       /* wall3d: a return wall of this many bricks' length
                        along +y at both ends, bonded at the corners
                        (src/gen/corner.c); 0 (default): a straight wall */
  double chamfer;    /* dome: the voussoirs' lower side edges bevelled by
                        this fraction of their width and of the course
                        height, in [0, 0.5) (default 0.02, as cut stone's
                        arrised edges; 0: sharp, see docs/format.md) */
  double deadline;   /* a us_now() time (0, the default: none): stacker
                        and random3d (between steps and inside their
                        stability tests), random (between attempts) and
                        the finalize of every generator stop past it
                        with US_ERR_TIME_LIMIT */
} us_GenSettings;
US_API us_GenSettings us_gen_default_settings(void);

US_API us_Structure *us_gen_column(const us_GenSettings *g, us_Error *err);
US_API us_Structure *us_gen_pyramid(const us_GenSettings *g, us_Error *err);
US_API us_Structure *us_gen_wall(const us_GenSettings *g, us_Error *err);
US_API us_Structure *us_gen_arch(const us_GenSettings *g, us_Error *err);
US_API us_Structure *us_gen_random(const us_GenSettings *g, us_Error *err);
/* The source-style stacker: rows of blocks at random offsets, cantilevers
 * held by the blocks above them; only the finished structure is required to
 * stand (src/gen/stacker.c). */
US_API us_Structure *us_gen_stacker(const us_GenSettings *g, us_Error *err);
/* 3D (src/gen/solid.c, regular.c): a tower of g->n boxes (width x depth x
 * height, each turned about the vertical by up to `jitter` degrees, seeded);
 * a pyramid of g->n square courses in stack bond; the running-bond wall of
 * us_gen_wall with bricks `thickness` deep, with `returns`, return walls at
 * both ends. */
US_API us_Structure *us_gen_tower(const us_GenSettings *g, us_Error *err);
US_API us_Structure *us_gen_pyramid3d(const us_GenSettings *g, us_Error *err);
US_API us_Structure *us_gen_wall3d(const us_GenSettings *g, us_Error *err);
/* A hemispherical dome on the ground (src/gen/dome.c): g->n courses of
 * g->segments voussoirs between latitude 0 and 90 - oculus degrees, inner
 * radius `radius`, `thickness` thick; with `cap`, one keystone over the
 * opening. */
US_API us_Structure *us_gen_dome(const us_GenSettings *g, us_Error *err);
/* A Jenga tower (src/gen/jenga.c): g->n levels of 3 pieces 3 w x w x h
 * (w = width, h = height), alternating direction, without the pieces
 * listed in remove. */
US_API us_Structure *us_gen_jenga(const us_GenSettings *g, us_Error *err);
/* The stacker in 3D (src/gen/random3d.c): up to g->n boxes (width x depth
 * x height) dropped at random (seeded) onto a square of g->width boxes'
 * side, each resting on the highest boxes under it and kept only while
 * the whole stands; stops at n boxes or after max_tries drops in a row
 * are discarded (then fewer: the count is s->nbody). */
US_API us_Structure *us_gen_random3d(const us_GenSettings *g, us_Error *err);

/* The generators by the names `unstack generate` gives them: the one named
 * kind (NULL when none is), and the k-th name (k = 0, 1, ...; NULL past the
 * last), for lists and bindings. */
typedef us_Structure *(*us_GenFn)(const us_GenSettings *g, us_Error *err);
US_API us_GenFn us_gen_find(const char *kind);
US_API const char *us_gen_kind(int k);

/* What a front end was told besides the settings it parsed into a
 * us_GenSettings that started as us_gen_default_settings(): the structure
 * width in blocks (random, stacker, random3d; 0: not given) and whether
 * the height, max_tries, returns and a remove list were given. */
typedef struct us_GenGiven {
  double width;
  int height, tries, returns, remove;
} us_GenGiven;
/* Why settings do not fit their generator (us_gen_settle); front ends
 * word each in their own option names. */
typedef enum us_GenMisfit {
  US_GEN_FITS = 0,
  US_GEN_REMOVE_NOT_JENGA,    /* a remove list is for jenga only */
  US_GEN_RETURNS_NOT_WALL3D,  /* returns are for wall3d only */
  US_GEN_BLOCK_WIDTH_FIXED,   /* random, stacker, random3d: the block width was set */
  US_GEN_WIDTH_NOT_RANDOM     /* a structure width for another kind */
} us_GenMisfit;
/* The kind's own defaults for what was not given (jenga's piece height,
 * random3d's tries, the random kinds' structure width), then the checks: US_GEN_FITS or why not. */
US_API us_GenMisfit us_gen_settle(us_GenFn fn, us_GenSettings *g, const us_GenGiven *given);

/* --------------------------------------------------------------------- I/O */

/* Read a structure JSON file (docs/format.md); finalized on success.
 * contact_tol > 0 overrides the derived tolerance. Errors name the file
 * and line:column (syntax) or the JSON path / body id (content). */
US_API us_Structure *us_structure_read(const char *path, double contact_tol, us_Error *err);
US_API us_Structure *us_structure_parse(const char *text, const char *name, double contact_tol,
                                 us_Error *err);
/* Settings of reading a structure; start from us_load_default_settings(). */
typedef struct us_LoadSettings {
  double contact_tol; /* > 0 overrides the derived tolerance (default 0) */
  double deadline;    /* a us_now() time (default 0: none): reading and
                         finalize stop past it with US_ERR_TIME_LIMIT */
} us_LoadSettings;
US_API us_LoadSettings us_load_default_settings(void);
/* us_structure_read and _parse with settings (set NULL: the defaults). */
US_API us_Structure *us_structure_read_with(const char *path, const us_LoadSettings *set,
                                            us_Error *err);
US_API us_Structure *us_structure_parse_with(const char *text, const char *name,
                                             const us_LoadSettings *set, us_Error *err);
/* Write atomically (temporary file + rename): no partial file on error. */
US_API us_Status us_structure_write(const us_Structure *s, const char *path, us_Error *err);

/* SVG import (docs/svg.md): rect, polygon, closed polyline, path (curves
 * flattened), circle and ellipse become polygon bodies; groups with
 * transforms, viewBox and units are followed; y is flipped so that up is
 * up, and the ground is the drawing's lowest point unless ground_at is
 * set. Start from us_svg_default_settings(). */
typedef struct us_SvgSettings {
  const char *unit;   /* output length unit: "m" (default), "cm", "mm", "in",
                         "pt", "pc", "px", or "user" (the drawing's root user
                         units, the viewBox's, as they are) */
  double scale;       /* the drawing is at 1:scale: lengths times scale (1) */
  int ground;         /* 1 (default): the ground supports the structure */
  int ground_at_set;  /* 1: the ground is the drawing's line y = ground_at
                         (root user units, y down as in the file); 0
                         (default): the lowest point of the drawing */
  double ground_at;
  double snap;        /* vertices this close to another body or the ground are
                         moved onto it: < 0 (default) 1e-3 of the pair's
                         smaller bounding-box diagonal; 0 off; > 0 this
                         distance in root user units */
  double flatten;     /* curves: largest distance of the polyline from the
                         curve, relative to the curve's size (default 1e-3;
                         0 < flatten <= 0.5) */
  double friction;    /* >= 0: the structure's default coefficient; < 0
                         (default): the root's data-friction, else 0.5 */
  double contact_tol; /* > 0: as for us_structure_read */
  void (*warn)(const char *msg, void *user); /* skipped elements (may be NULL) */
  void *warn_user;
} us_SvgSettings;
US_API us_SvgSettings us_svg_default_settings(void);

/* What an import did (optional out-parameter). */
typedef struct us_SvgInfo {
  int bodies, fixed;       /* bodies made, of them fixed */
  int skipped;             /* elements skipped with a warning */
  int curves;              /* curve segments flattened */
  int snapped;             /* vertices moved by snapping */
  int ids_generated;       /* shapes without an id */
  int ids_renamed;         /* repeated ids made unique */
  double unit;             /* output units per root user unit (x) */
  size_t entity_bytes;     /* attribute values that hold entity references:
                              their expanded bytes plus one per reference, in
                              all at most 1 MiB + 4 x the file's size */
} us_SvgInfo;

/* Read an SVG drawing into a finalized structure. Errors name the file,
 * the line and the element (US_ERR_PARSE malformed XML or attribute,
 * US_ERR_INPUT degenerate or overlapping shapes, US_ERR_IO, US_ERR_USAGE
 * bad settings); NULL then. info may be NULL. */
US_API us_Structure *us_structure_read_svg(const char *path, const us_SvgSettings *set,
                                           us_SvgInfo *info, us_Error *err);
US_API us_Structure *us_structure_parse_svg(const char *text, size_t len, const char *name,
                                            const us_SvgSettings *set, us_SvgInfo *info,
                                            us_Error *err);

/* Mesh import (docs/mesh.md; Assimp, loaded as module mesh.so): OBJ, STL,
 * PLY, glTF/GLB, 3MF, OFF and the other formats Assimp reads, into a 3D
 * structure. One body per named object (OBJ o/g, a glTF or 3MF node), per
 * connected shell where the file names none (STL, PLY, OFF); a named
 * object of several closed convex shells is one compound body. Start from
 * us_mesh_default_settings(). */
typedef struct us_MeshSettings {
  char up;            /* 'z' (default) or 'y': y-up files turned so y is up */
  double scale;       /* lengths multiplied by scale (default 1) */
  double friction;    /* >= 0 or INFINITY: the structure's coefficient;
                         < 0 (default): 0.5 */
  double density;     /* every body's density (default 1) */
  const char *fixed;  /* fnmatch(3) pattern: bodies whose ids match are
                         fixed (default NULL: none) */
  int ground;         /* 1 (default): the ground is the plane through the
                         lowest point; 0: no ground */
  double contact_tol; /* > 0: as for us_structure_read */
  double deadline;    /* a us_now() time (default 0: none): past it the
                         import stops with US_ERR_TIME_LIMIT */
} us_MeshSettings;
US_API us_MeshSettings us_mesh_default_settings(void);

/* What an import did (optional out-parameter). */
typedef struct us_MeshInfo {
  int bodies, fixed;   /* bodies made, of them fixed */
  int compounds;       /* bodies made of several convex shells */
  int shells;          /* closed shells (convex parts) in all */
  long faces;          /* faces read */
  int ids_renamed;     /* names changed to be valid and unique */
} us_MeshInfo;

/* Read a mesh file into a finalized structure. Errors name the file and
 * the object (US_ERR_IO unreadable file or unknown format, US_ERR_INPUT
 * non-finite coordinates, degenerate faces, open or non-convex shells,
 * overlapping bodies, US_ERR_USAGE bad settings, US_ERR_TIME_LIMIT); NULL
 * then. info may be NULL. */
US_API us_Structure *us_structure_read_mesh(const char *path, const us_MeshSettings *set,
                                            us_MeshInfo *info, us_Error *err);

/* Plan files. Reading maps ids to body indices of s. */
US_API us_Status us_plan_write(const us_Structure *s, const us_Plan *p, const us_PlanSettings *set,
                        const char *path, us_Error *err);
/* The same into an open stream fp (a FILE*, e.g. a temporary file for
 * `plan -o -`); `name` is the output's name for messages. On an error part
 * of the plan may have been written: write to a scratch stream. */
US_API us_Status us_plan_write_stream(const us_Structure *s, const us_Plan *p,
                                      const us_PlanSettings *set, void *fp, const char *name,
                                      us_Error *err);
/* The fingerprint of a finalized structure (src/io/fingerprint.c,
 * docs/format.md): a 64-bit FNV-1a hash of a canonical serialisation of
 * what determines its verdicts (dimension, gravity, friction, ground, each
 * body's id, fixed flag, mass or density, friction and geometry, explicit
 * contacts), written into plan files so that a plan read against another
 * structure is refused. Text form: "fnv1a64:" and 16 lowercase hex digits. */
#define US_FINGERPRINT_CHARS 25
US_API us_Status us_structure_fingerprint(const us_Structure *s, uint64_t *out, us_Error *err);
US_API void us_fingerprint_text(uint64_t fp, char out[US_FINGERPRINT_CHARS]);
typedef struct us_PlanFile {
  us_PlanStatus status;
  int n;
  int *order;
  int ngroups;        /* steps; an "order" entry may be an array of ids (a group) */
  int *group_start;   /* [ngroups + 1] offsets into order */
  int nblocked;       /* "blocked": bodies a plan with status none names */
  int *blocked;
  us_Removal removal; /* "removal" (default any): verify checks the kinematics */
  int has_fingerprint; /* the file names its structure ("fingerprint"); it
                          matched (us_plan_read refuses another's) */
  int other_structure; /* set on the refusal: the file's fingerprint is not
                          the structure's (fingerprint holds the file's) */
  char fingerprint[US_FINGERPRINT_CHARS];
  int nbuildable;      /* status none: "build" (placement order, steps as in
                          "order"), else 0 */
  int *buildable, *build_start; /* [nbuildable], [nbuild + 1] offsets */
  int nbuild;          /* steps of the build */
  int hands;          /* "hands" (0: absent, an order-only plan) */
  int hands_lower;    /* "hands_lower" (0: absent): smaller H proven impossible */
  int nactions;       /* "actions": ids checked, sequence checked by verify */
  us_Action *actions;
} us_PlanFile;
US_API us_Status us_plan_read(const us_Structure *s, const char *path, us_PlanFile *out, us_Error *err);
US_API void us_plan_file_free(us_PlanFile *pf);
/* The certificates of a plan file's "steps" (written by `plan
 * --certificates`), for the plan pf read from the same file: *certs gets
 * pf->ngroups + 1 entries as us_Plan.certs (certs[k] = the forces of the
 * structure before step k, the last one empty), each contact matched to
 * s's contact between the same bodies at the same point (within 1e-6 of
 * s->scale). A file without steps gives *certs = NULL. Steps that do not
 * follow the order, or contacts s does not have, are US_ERR_INPUT naming
 * the JSON path; so is a structure that is not 2D (not read yet). Free
 * with us_certs_free(*certs, pf->ngroups + 1). */
US_API us_Status us_plan_read_certs(const us_Structure *s, const char *path,
                                    const us_PlanFile *pf, us_Forces **certs, us_Error *err);
US_API void us_certs_free(us_Forces *certs, int n);

/* ------------------------------------------------------------------ render */

/* Body labels: AUTO the step number with an order, else the id; IDS the
 * id; STEPS the step number (bodies without a step: none); NONE. */
typedef enum us_Labels { US_LABELS_AUTO = 0, US_LABELS_IDS, US_LABELS_STEPS, US_LABELS_NONE } us_Labels;
/* What a picture marks when the structure (or a plan's remainder) does not
 * stand: the failing step (1-based step of the order after which the rest
 * falls; 0: the full structure), the body that cannot be held (-1: not
 * known) and the mechanism (the unstable verdict's motion; NULL or nbody 0:
 * none), drawn as velocity arrows and, in 2D, ghosts of the moving bodies
 * displaced along it (docs/render.md). */
typedef struct us_RenderFailure {
  int step;
  int body;
  const us_Mechanism *mechanism;
} us_RenderFailure;
typedef struct us_RenderSettings {
  const int *order;       /* removal order (may be NULL) */
  int norder;
  const int *group_start; /* steps of the order (NULL: one body each) */
  int ngroups;
  const int *blocked;     /* bodies that cannot be removed (plan status none) */
  int nblocked;
  const us_Forces *forces;/* draw as arrows (may be NULL): at each contact the
                             force of the lower body on the upper one, normal
                             and friction parts apart (docs/render.md) */
  int force_resultants;   /* 1: one arrow per pair of touching bodies, their
                             contacts' resultant at its centre of pressure */
  us_ForceSet force_set;  /* which admissible set `forces` is (the legend
                             names it; default US_FORCESET_SOLVER) */
  int show_contacts;      /* default 1 */
  int show_labels;        /* default 1 */
  double width_px;        /* default 800 */
  double height_px;       /* 0 (default): as the drawing needs, within the
                             format's limits; else exactly this, the drawing
                             fitted and centred */
  const char *title;      /* a line above the drawing (NULL: none) */
  double view_az, view_el;/* 3D: the axonometric view's azimuth and
                             elevation in degrees (default 35, 25; el in
                             [-90, 90]; docs/render.md) */
  us_Labels labels;       /* what bodies are labelled with (default
                             US_LABELS_AUTO; show_labels 0 is NONE) */
  int order_builds;       /* 1: order is a build (placement) order, the
                             buildable part of a none plan, numbered 1 =
                             placed first */
  const us_RenderFailure *failure; /* why it does not stand (NULL: no mark) */
  const unsigned char *hand_state; /* NULL, or per body at one action of a
                             plan with hands: US_HAND_* (docs/render.md) */
} us_RenderSettings;
/* A body at one action: not placed yet (drawn faint, unlabelled), placed,
 * held (outlined, and a hand mark at its centre: SVG class "held"). */
enum { US_HAND_UNPLACED = 0, US_HAND_PLACED, US_HAND_HELD };
US_API us_RenderSettings us_render_default_settings(void);
/* Draw s (docs/render.md) as SVG or PNG, written atomically: on any error
 * (bad settings: US_ERR_USAGE, before the file is opened) nothing is
 * written. A PNG is at most 16384 px a side and 64 million pixels. */
US_API us_Status us_render_svg(const us_Structure *s, const us_RenderSettings *r, const char *path,
                        us_Error *err);
US_API us_Status us_render_png(const us_Structure *s, const us_RenderSettings *r, const char *path,
                        us_Error *err);

/* The interactive plan viewer (docs/viewer.md): one self-contained HTML
 * page (a canvas, script and style; no network) with a step slider,
 * play/pause, the forces of each step, zoom, pan and hover. 2D only. */
typedef struct us_HtmlSettings {
  const char *title;        /* shown in the page (NULL: "unstack") */
  us_PlanStatus status;     /* the plan's status (used with an order or
                               blocked bodies) */
  const us_Forces *certs;   /* NULL, or nsteps + 1 entries as us_Plan.certs:
                               certs[k] = forces of the structure before step
                               k of r's order (nsteps = r's steps, 0 without
                               an order) */
  us_ForceSet force_set;    /* which admissible set certs are (the page
                               names it) */
  int verified;             /* 1: `verify` holds us_verify_steps' report on
                               r's order, shown in the page (a failing step in
                               red) */
  us_VerifyReport verify;
  int hands;                /* a plan with hands: the slider steps through its
                               nactions actions (docs/viewer.md, "Hands") */
  const us_Action *actions;
  int nactions;
} us_HtmlSettings;
US_API us_HtmlSettings us_html_default_settings(void); /* no title, found, nothing verified */
/* r: the order, steps and blocked bodies (the drawing fields are not used);
 * NULL: the structure alone. Bad settings are US_ERR_USAGE, a structure
 * that is not 2D US_ERR_INPUT, before the file is opened; the file is
 * written atomically. */
US_API us_Status us_render_html(const us_Structure *s, const us_RenderSettings *r,
                                const us_HtmlSettings *h, const char *path, us_Error *err);

/* An id quoted for a message (src/core/text.c): control characters, DEL,
 * C1 controls, bidi overrides, U+FFFE/U+FFFF and invalid UTF-8 bytes as
 * \xNN / \uNNNN escapes, a backslash as \\, cut at a character boundary
 * after at most 80 bytes with "...". Returned by value so that
 * printf("'%s'", us_id_text(id).s) works. Every message naming an id uses it. */
typedef struct us_IdText {
  char s[84];
} us_IdText;
US_API us_IdText us_id_text(const char *id);

/* Output files shared by all writers (src/core/file.c): the content goes to
 * a temporary file and is put in place at commit, nothing on abort. A new or
 * plain file is replaced by rename (keeping its mode and owner); a symlink is
 * followed; a device, FIFO or hard-linked file is written through in place.
 * A read-only file or a directory is refused (US_ERR_IO). Returns a FILE* to
 * write to; commit or abort. */
typedef struct us_AtomicFile us_AtomicFile;
US_API us_AtomicFile *us_atomic_open(const char *path, us_Error *err);
US_API void *us_atomic_stream(us_AtomicFile *af); /* FILE* */
US_API us_Status us_atomic_commit(us_AtomicFile *af, us_Error *err);
US_API void us_atomic_abort(us_AtomicFile *af);
/* Can path be written, before any work is done? Its directory exists and is
 * writable, or the file (symlinks followed) is writable; and it is none of
 * the `ninputs` input files (same st_dev/st_ino: "output would overwrite
 * input NAME"). US_OK or US_ERR_IO with a message; touches nothing. */
US_API us_Status us_output_check(const char *path, const char *const *inputs, int ninputs,
                          us_Error *err);

/* Monotonic clock in seconds. */
US_API double us_now(void);

#ifdef __cplusplus
}
#endif

#include "unstack/analysis.h"

#endif
