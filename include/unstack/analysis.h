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
const char *us_count_method_name(us_CountMethod m);
int us_count_method_parse(const char *name, us_CountMethod *out); /* 0 ok, -1 unknown */

/* Outcomes: exact, or refused at a limit (no value then). */
typedef enum us_CountStatus {
  US_COUNT_EXACT = 0,
  US_COUNT_REFUSED_SIZE,    /* more bodies than the settings allow */
  US_COUNT_REFUSED_TIME,    /* time_limit reached */
  US_COUNT_REFUSED_MEMORY,  /* the state tables would pass max_memory_mb */
  US_COUNT_STATUS_COUNT
} us_CountStatus;
const char *us_count_status_name(us_CountStatus s);

typedef struct us_CountSettings {
  us_CountMethod method;  /* default AUTO */
  int max_tree_bodies;    /* tree formula: refuse past this (default 1,000,000; <= 0: none) */
  int max_bodies;         /* frontier / contraction: refuse past this (default 10,000;
                             <= 0: none); bodies connected to the ground are counted */
  double time_limit;      /* seconds, <= 0: none (default 10); general methods only:
                             the tree formula is linear */
  double max_memory_mb;   /* state tables and memo, <= 0: none (default 2048) */
} us_CountSettings;
us_CountSettings us_count_default_settings(void);

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
us_Status us_count_subgraphs(const us_Structure *s, const us_CountSettings *set, us_Count *out,
                             us_Error *err);
void us_count_free(us_Count *c);

/* ------------------------------------------------------------- classify */
/* (src/plan/classify.c, src/plan/friction.c) */

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
  us_Forces forces;        /* stands: contact forces at mu_high = mu_critical */
  us_CertCheck check;      /* stands: us_certificate_check of forces with every
                              contact's mu = mu_critical */
} us_FrictionResult;
void us_friction_result_free(us_FrictionResult *r);

/* Critical friction of sub-assembly `present` (NULL: every movable body)
 * under the stability settings `set` (NULL: defaults, method lp). tol: the
 * absolute tolerance on mu (<= 0: 1e-7); mu_max: the largest coefficient
 * tried (<= 0: 1e3). Standing, not standing and "not for any mu up to
 * mu_max" are outcomes in `out`; errors are bad arguments (US_ERR_USAGE),
 * memory (US_ERR_NOMEM) and backend failures. err may be NULL. */
us_Status us_critical_friction(const us_Structure *s, const us_Bitset *present,
                               const us_StabilitySettings *set, double tol, double mu_max,
                               us_FrictionResult *out, us_Error *err);

#ifdef __cplusplus
}
#endif
#endif
