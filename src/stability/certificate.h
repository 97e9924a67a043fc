/* The independent certificate check (certificate.c), in a form that needs
 * no allocation (the public us_certificate_check allocates its scratch). */
#ifndef US_STABILITY_CERTIFICATE_H
#define US_STABILITY_CERTIFICATE_H

#include "core/core.h"

/* The boundary band (docs/planning.md, "The boundary band"): a stable
 * certificate whose worst measure (each relative to its own body or
 * contact) exceeds US_BAND_CERT, or an unstable mechanism whose margin
 * (us_mechanism_margin, relative to the moving bodies) is below
 * US_BAND_MECH, is within tolerance of tipping, and its verdict is the
 * referee's, whatever method found it. */
#define US_BAND_CERT 1e-10
#define US_BAND_MECH 1e-7

/* Room for n forces in f (0, or -1 out of memory). Three components per
 * force whatever the dimension, so that a result reused across 2D and 3D
 * structures stays large enough. */
int us_forces_reserve(us_Forces *f, int n);

/* Accumulator doubles per body of the check. */
#define US_CERT_ACC 8

/* us_certificate_check with caller scratch (acc: US_CERT_ACC * nbody doubles, seen:
 * ncontact bytes), so that it cannot fail on memory. Returns 0, or -1
 * when the forces are malformed (out->ok = 0). */
int us_certificate_check_buf(const us_Structure *s, const us_Bitset *present,
                             const us_Forces *f, double tol, double *acc, unsigned char *seen,
                             us_CertCheck *out);

/* The check in a given mode: bilateral 1 checks the equilibrium residuals
 * only (joints: every force component free in sign, no cone; classify's
 * equality constraints); 0 is us_certificate_check_buf. */
int us_certificate_check_mode(const us_Structure *s, const us_Bitset *present,
                              const us_Forces *f, double tol, int bilateral, double *acc,
                              unsigned char *seen, us_CertCheck *out);

/* us_mechanism_check in a given mode: bilateral 1 asks every active
 * contact touching a moving body for zero relative velocity (a joint can
 * give any force, so any slip or separation lets it do negative work). */
int us_mechanism_check_mode(const us_Structure *s, const us_Bitset *present, us_Mechanism *m,
                            double tol, int bilateral);

/* The local re-check of the local tests (local.c), with the same
 * measures: the equilibrium of each listed present movable body under the
 * forces fc (normalized by the total weight; dim components per
 * structure contact, read for the active contacts only), every active
 * contact touching it counted, and the cone and sign of those contacts.
 * inc_start / inc list the contacts of each body. mass: the structure's
 * movable mass, which the caller sums once (the check costs O(listed
 * bodies and their contacts) then; < 0: summed here, O(bodies)). */
void us_certificate_check_bodies(const us_Structure *s, const us_Bitset *present,
                                 const int *bodies, int nb, const int *inc_start, const int *inc,
                                 const double *fc, double mass, double tol, us_CertCheck *out);

/* The same check, each active contact's force measured once (both its
 * sides' sums from one evaluation when both are listed): the local tests'
 * (their regions' contacts are mostly between listed bodies). Caller
 * scratch: slot[nbody], all -1 on entry and on return; acc, US_CERT_ACC
 * doubles per listed body. The sums' order differs from
 * us_certificate_check_bodies', so residuals may differ in their last
 * bits (tests/test_stability_plumb.c compares the two). */
void us_certificate_check_list(const us_Structure *s, const us_Bitset *present,
                               const int *bodies, int nb, const int *inc_start, const int *inc,
                               const double *fc, double mass, double tol, int *slot,
                               double *acc, us_CertCheck *out);

/* us_mechanism_check over the contacts in list (NULL: all) with caller
 * scratch slot[nbody], all -1 on entry and on return. */
int us_mechanism_check_list(const us_Structure *s, const us_Bitset *present, us_Mechanism *m,
                            double tol, int *slot, const int *list, int nlist);

/* How clearly a normalized mechanism m (gravity's power 1, as left by
 * us_mechanism_check) tips: gravity's power over the sum, over its
 * bodies, of each body's weight times the fastest speed of a point of
 * that body (|v| + |omega| times its farthest vertex from the centre of
 * mass). Relative to the moving bodies alone: a block rolling over a
 * corner its centre of mass is d past gets about d / its own size. 0 for a
 * mechanism that does not move. */
double us_mechanism_margin(const us_Structure *s, const us_Mechanism *m);

/* Euclidean distance of the 2D/3D contact force (f_n, |f_t|) from the cone
 * |f_t| <= mu f_n (mu = INFINITY: the half-space f_n >= 0). It does not
 * grow with mu: a force just outside a wide cone is just outside it. */
double us_cone_distance(double fn, double ft, double mu);

#endif
