/* unstack analysis: counting sub-assemblies and classifying structures.
 * Part of the public API; included by unstack/unstack.h. */
#ifndef UNSTACK_ANALYSIS_H
#define UNSTACK_ANALYSIS_H

#include "unstack/unstack.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ count */
/* (src/analysis/count.c, docs/count.md) The number of connected
 * sub-assemblies containing the ground: the subsets S of the movable bodies
 * such that S and the ground G induce a connected sub-graph of the contact
 * graph (nodes: the movable bodies and G, with the ground and every fixed
 * body merged into G; an edge where at least one contact joins two nodes).
 * The empty S counts. A search with the ground rule and a memo of its
 * verdicts tests no other sub-assembly, and none twice: this bounds its
 * number of stability tests. Exact, in decimal (the value outgrows 64 bits
 * at about 64 bodies). */

typedef enum us_CountMethod {
  US_COUNT_AUTO = 0,  /* the tree formula when G's component is a tree, else frontier */
  US_COUNT_TREE,      /* the tree formula, linear; US_ERR_USAGE when not a tree */
  US_COUNT_FRONTIER,  /* connectivity dynamic programme along a vertex order */
  US_COUNT_CONTRACT,  /* deletion-contraction with memo, tree formula at trees */
  US_COUNT_METHOD_COUNT
} us_CountMethod;
US_API const char *us_count_method_name(us_CountMethod m);
US_API int us_count_method_parse(const char *name, us_CountMethod *out); /* 0 ok, -1 unknown */

/* Outcomes: exact, or refused at a limit (no value then). */
typedef enum us_CountStatus {
  US_COUNT_EXACT = 0,
  US_COUNT_REFUSED_SIZE,    /* more bodies than the settings allow */
  US_COUNT_REFUSED_TIME,    /* time_limit reached */
  US_COUNT_REFUSED_MEMORY,  /* the state tables would pass max_memory_mb */
  US_COUNT_STATUS_COUNT
} us_CountStatus;
US_API const char *us_count_status_name(us_CountStatus s);

typedef struct us_CountSettings {
  us_CountMethod method;  /* default AUTO */
  int max_tree_bodies;    /* tree formula: refuse past this (default 1,000,000; <= 0: none) */
  int max_bodies;         /* frontier / contraction: refuse past this (default 10,000;
                             <= 0: none); bodies connected to the ground are counted */
  double time_limit;      /* seconds, <= 0: none (default 10); general methods only:
                             the tree formula is linear */
  double max_memory_mb;   /* state tables and memo, <= 0: none (default 2048) */
} us_CountSettings;
US_API us_CountSettings us_count_default_settings(void);

typedef struct us_Count {
  us_CountStatus status;
  char *value;            /* decimal digits when EXACT, else NULL */
  us_CountMethod method;  /* the algorithm that ran: TREE, FRONTIER or CONTRACT */
  int is_tree;            /* G's connected component is a tree */
  int nbody;              /* movable bodies */
  int nconnected;         /* movable bodies connected to G (the others add nothing) */
  int nedge;              /* edges of the contact graph, G's included */
  int width;              /* frontier: the largest frontier of its vertex order */
  long work;              /* tree: nodes; frontier: states processed; contraction: calls */
  long peak;              /* frontier: the largest layer of states; contraction: memo entries */
  double seconds;
  char note[128];         /* the order used, or why the count was refused */
} us_Count;

/* Count for structure s (finalized: its contacts are read). set NULL: the
 * defaults. A refusal is an outcome (out->status), not an error; errors are
 * bad arguments and out of memory. us_count_free(out) afterwards, also
 * after an error. */
US_API us_Status us_count_subgraphs(const us_Structure *s, const us_CountSettings *set, us_Count *out,
                             us_Error *err);
US_API void us_count_free(us_Count *c);

/* ------------------------------------------------------------- classify */
/* (src/plan/classify.c, src/analysis/friction.c) */

/* Critical friction (src/analysis/friction.c, docs/classify.md): the
 * smallest Coulomb coefficient mu which, put on every contact of the
 * structure alike (the contacts' own coefficients are ignored), lets the
 * sub-assembly stand. Standing is monotone in mu, so the value is found by
 * bisection on stability tests of a private copy of the structure whose
 * contacts carry the probe's mu. */
typedef struct us_FrictionResult {
  int stands_frictionless; /* stands at mu = 0 (then mu_critical = 0) */
  int stands;              /* stands at mu_max; 0: no coefficient up to mu_max works */
  double mu_critical;      /* stands: the smallest stable probe, within tol above
                              the true value; INFINITY when !stands */
  double mu_low, mu_high;  /* bracket: not standing at mu_low (or mu_low = 0 and it
                              stands there), standing at mu_high (INFINITY when !stands) */
  int probes;              /* stability tests run */
  int undecided;           /* probes whose verdict was undecided (taken as not standing) */
  int timed_out;           /* the search stopped at the settings' time_limit (the
                              whole search's, not each probe's): mu_critical = mu_high
                              is then an upper bound when stands, and nothing else
                              (not frictionless, no mu up to mu_max) is proven */
  us_Forces forces;        /* stands: contact forces at mu_high = mu_critical */
  us_CertCheck check;      /* stands: us_certificate_check of forces with every
                              contact's mu = mu_critical */
} us_FrictionResult;
US_API void us_friction_result_free(us_FrictionResult *r);

/* Critical friction of sub-assembly `present` (NULL: every movable body)
 * under the stability settings `set` (NULL: defaults, method lp). tol: the
 * absolute tolerance on mu (<= 0: 1e-7); mu_max: the largest coefficient
 * tried (<= 0: 1e3). Standing, not standing and "not for any mu up to
 * mu_max" are outcomes in `out`; errors are bad arguments (US_ERR_USAGE),
 * memory (US_ERR_NOMEM) and backend failures. err may be NULL. */
US_API us_Status us_critical_friction(const us_Structure *s, const us_Bitset *present,
                               const us_StabilitySettings *set, double tol, double mu_max,
                               us_FrictionResult *out, us_Error *err);

/* Strong stability with friction (src/analysis/strong*.c, docs/classify.md,
 * "Strong stability with friction"): does EVERY solution of the contact
 * dynamics at rest (accelerations complementary to normal forces, static
 * Coulomb friction: sliding contacts carry mu f_n against the slip) leave
 * every body at rest? A structure that does not stand (weakly) is not
 * strongly stable either. Answers: 1 yes (a proof: no complementary
 * solution with gravity power above tol, from the exhaustive mode search or
 * the MIP's bound), 0 no (with a witness motion that us_strong_check
 * re-checked without the solver), -1 undecided (a budget, a refusal). */
typedef enum us_StrongMethod {
  US_STRONG_AUTO = 0, /* the MIP (CBC module) when it loads, else enumeration */
  US_STRONG_ENUM,     /* exhaustive contact-mode search with lp_solve */
  US_STRONG_MIP       /* one mixed-integer program, CBC (module cbc) */
} us_StrongMethod;

typedef enum us_ContactMode {
  US_MODE_SEPARATES = 0, /* f = 0, normal acceleration >= 0 */
  US_MODE_STICKS,        /* closed, no slip: |f_t| <= mu f_n */
  US_MODE_SLIDES_POS,    /* closed, slip along +t: f_t = -mu f_n */
  US_MODE_SLIDES_NEG     /* closed, slip along -t: f_t = +mu f_n */
} us_ContactMode;

typedef struct us_StrongSettings {
  us_StrongMethod method;
  long max_nodes;      /* enumeration: LPs at most (default 100,000); MIP: nodes */
  double time_limit;   /* wall-clock seconds (default 10; <= 0: none) */
  double tol;          /* normalized gravity power that counts as motion
                          (default 1e-7; see docs) */
} us_StrongSettings;
US_API us_StrongSettings us_strong_default_settings(void);

typedef struct us_StrongResult {
  int strong;          /* 1 yes, 0 no, -1 undecided */
  us_StrongMethod method; /* the one that answered */
  char note[160];      /* how it was decided, or why undecided */
  long nodes;          /* LPs (enumeration) or branch-and-bound nodes (MIP) */
  double power;        /* best normalized gravity power found (>= 0) */
  double bound;        /* proven upper bound on it (yes: <= tol) */
  double seconds;
  /* the witness motion (strong == 0 and has_witness): accelerations of the
     present movable bodies (2D: ax, ay, alpha; 3D: ax, ay, az, alpha x, y,
     z; in m/s^2, rad/s^2), and per active contact its index in
     s->contacts, force (2D: f_n, f_t; 3D: f_n and f_t along t[0], t[1];
     in newtons) and mode (3D: any slide is US_MODE_SLIDES_POS) */
  int has_witness;
  int nbody, *body;
  double *accel;       /* [nbody * 3] (3D: [nbody * 6]) */
  int ncontact, *contact;
  double *force;       /* [ncontact * 2] (3D: [ncontact * 3]) */
  us_ContactMode *mode;/* [ncontact] */
  int dim;             /* of the witness: 2 or 3 */
} us_StrongResult;
US_API void us_strong_result_free(us_StrongResult *r);

/* Decide strong stability of sub-assembly `present` (NULL: every movable
 * body) of a 2D or 3D structure (3D: the mode search with inner and outer
 * polygonal cones; "yes" and "no" hold for the circular cone, else
 * undecided; docs/classify.md). Outcomes in out; errors: bad arguments
 * (US_ERR_USAGE), memory, a solver failure. err may be NULL. */
US_API us_Status us_strong_stability(const us_Structure *s, const us_Bitset *present,
                                     const us_StrongSettings *set, us_StrongResult *out,
                                     us_Error *err);

/* The independent check of a witness motion (no solver): Newton-Euler on
 * every body (m a = m g + sum of contact forces, I alpha = their torques),
 * the contact accelerations computed from the body accelerations, normal
 * complementarity, the Coulomb cone, sliding friction against the slip,
 * and gravity power above tol (relative to the weight and |g|). 1 when it
 * passes, else 0 with the first failure in why (may be NULL). */
US_API int us_strong_check(const us_Structure *s, const us_Bitset *present,
                           const us_StrongResult *w, double tol, char *why, size_t why_size);

/* Classification (src/plan/classify.c, docs/classify.md): the classes of
 * the research proposal, each decided exactly by the library's own tests
 * and searches, with its evidence:
 *   1. stands: one stability test of the full structure (its own friction);
 *   2. stands frictionless / only with friction: us_critical_friction;
 *   3. top-down: the source's plain DFS (order highest, direction down,
 *      rule memo only) finds an order without a single unstable move or
 *      dead end, i.e. "remove the highest body" always works;
 *   4. a one-at-a-time sequence exists: the assemble search (max_group 1);
 *      when none, the bodies outside the greedy's maximal buildable
 *      sub-assembly are the evidence;
 *   5. the smallest group size K: the assemble search with max_group 0;
 *      no K at all exactly when the full structure does not stand
 *      (the searches of 3-5 stop at time_limit: the class is then unknown);
 *   6. frictionless, strong and weak stability coincide (Gauss's principle,
 *      docs/classify.md); with friction, strong stability is decided by
 *      us_strong_stability (yes / no with a witness motion / undecided);
 *   7. needs buttressing: no sequence (4), and the smallest number of
 *      hands holding bodies still that builds it (plan --hands auto),
 *      proven or bounded;
 * and the count of connected sub-assemblies containing the ground, an upper
 * bound on the tests of a search with the ground rule and a memo. */
typedef struct us_ClassifySettings {
  us_StabilitySettings stability; /* backend of every test (default lp) */
  long max_tests;          /* test limit of the top-down DFS probe (default
                              20,000; <= 0: none) */
  double time_limit;       /* seconds for each search of classes 3-5 (default
                              60; <= 0: none): past it a class is unknown */
  double count_time_limit; /* seconds for the count (default 2; <= 0: none) */
  int strong;              /* 6. decide strong stability with friction (default
                              0: not asked; the CLI asks) */
  us_StrongSettings strong_settings; /* its method and budgets (default
                              us_strong_default_settings; its time limit is
                              capped by time_limit) */
} us_ClassifySettings;
US_API us_ClassifySettings us_classify_default_settings(void);

typedef struct us_Classification {
  int nbody;               /* movable bodies */
  /* 1. */
  int stands;              /* the full structure stands with its own friction */
  int stands_undecided;    /* its test was undecided (stands = 0 proves nothing) */
  int unstable_body;       /* !stands: the body the test names, or -1 */
  /* 2. */
  int stands_frictionless; /* stands with every mu = 0 */
  int stands_some_mu;      /* stands for some mu up to 1e3 */
  double mu_critical;      /* the smallest such mu to 1e-7 (0 when frictionless,
                              INFINITY when none up to 1e3) */
  int friction_probes;
  int friction_undecided;  /* probes whose test was undecided (taken as not standing:
                              mu_critical is then an upper bound, and "stands for
                              no mu" or "not frictionless" is unproven) */
  int friction_timed_out;  /* the bisection stopped at time_limit: mu_critical is an
                              upper bound when stands_some_mu, nothing else is known */
  double mu_low;           /* the bracket's lower end (mu* > mu_low unless undecided) */
  /* 3. */
  int topdown;             /* 1 yes, 0 no, -1 unknown (the DFS hit max_tests or
                              time_limit before any move failed, or one of its
                              tests was undecided) */
  us_PlanStatus dfs_status;/* the plain DFS: found, none, unstable, limit or
                              undecided */
  long dfs_tests;          /* its stability tests */
  long dfs_undecided;      /* ... of which undecided */
  long rejected;           /* moves it tested and found unstable */
  long backtracks;         /* dead ends it stepped back from */
  /* 4. */
  us_PlanStatus sequence_status; /* found, none (a proof), unstable (the full
                              structure does not stand), limit (unknown) or
                              undecided (none or unstable rest on undecided tests) */
  int sequence;            /* sequence_status == US_PLAN_FOUND */
  long sequence_tests;
  int nbuildable;          /* none: the size of a maximal buildable
                              sub-assembly (the greedy's) */
  int nblocked, *blocked;  /* none: the movable bodies outside it */
  /* 5. */
  us_PlanStatus group_status; /* found: min_group is the smallest K;
                              unstable: no K (the full structure does not
                              stand); none: K > group_bound, the planner's
                              bound (64); limit: unknown, K > group_bound;
                              undecided: some test was undecided, K > group_bound
                              and, when min_group > 0, K <= min_group */
  int min_group;           /* found: the smallest K with an order of steps of
                              at most K bodies; undecided: an upper bound or 0;
                              else 0 */
  int group_bound;         /* see group_status */
  long group_tests;
  /* 6. */
  int strong_equals_weak;  /* stands frictionless: strong = weak there */
  int undecided;           /* some class above is undecided because a stability test
                              was (the fields say which) */
  /* the bound on a search's tests */
  us_CountStatus count_status;
  char *count;             /* decimal digits when exact, else NULL */
  char count_note[128];    /* why the count was refused */
  double seconds;          /* the whole classification */
  double t_stands, t_friction, t_topdown, t_sequence, t_group, t_count;
  /* 7. needs buttressing (docs/planning.md, "Hands"): when no one-at-a-time
     sequence exists, plan --hands auto: found with hands (the smallest when
     hands_lower == hands, else an upper bound: hands_lower .. hands - 1
     unproven), or its status (limit, undecided); 0 when not asked */
  us_PlanStatus hands_status;
  int hands, hands_lower;
  long hands_tests;
  double t_hands;
  /* 8. stands only with equality constraints (docs/classify.md): when it
     does not stand, one test of the full structure with bilateral joints
     (every contact force component free in sign, no friction cone):
     equality 1 it stands so, 0 it stands already or not even so, -1
     unknown (a test undecided); stands_bilateral the second test's verdict
     (1, 0, -1 undecided or not run); when not even bilateral:
     bilateral_body the body its evidence names (-1: none),
     bilateral_loose 1 when that body touches nothing, bilateral_mechanism
     1 when a mechanism (every joint closed, gravity doing work) was
     checked without the solver */
  int equality, stands_bilateral;
  int bilateral_body, bilateral_loose, bilateral_mechanism;
  double t_equality;
  /* 6. strong stability with friction (us_strong_stability): strong 1 yes
     (a proof: frictionless and standing, Gauss's principle; or the search),
     0 no (does not stand, or a checked witness motion in strong_result),
     -1 undecided (strong_result.note says why), -2 not
     asked */
  int strong;
  us_StrongResult strong_result;
  double t_strong;
} us_Classification;

/* Classify structure s (finalized). set NULL: the defaults. Every class is
 * an outcome in out; errors are bad arguments, out of memory and backend
 * failures (out is then empty). err may be NULL. us_classification_free(out)
 * afterwards (also harmless after an error). */
US_API us_Status us_classify(const us_Structure *s, const us_ClassifySettings *set,
                      us_Classification *out, us_Error *err);
US_API void us_classification_free(us_Classification *c);

#ifdef __cplusplus
}
#endif
#endif
