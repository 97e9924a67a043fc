/* The independent certificate check (certificate.c), in a form that needs
 * no allocation (the public us_certificate_check allocates its scratch). */
#ifndef US_STABILITY_CERTIFICATE_H
#define US_STABILITY_CERTIFICATE_H

#include "core/core.h"

/* Accumulator doubles per body of the check. */
#define US_CERT_ACC 8

/* us_certificate_check with caller scratch (acc: US_CERT_ACC * nbody doubles, seen:
 * ncontact bytes), so that it cannot fail on memory. Returns 0, or -1
 * when the forces are malformed (out->ok = 0). */
int us_certificate_check_buf(const us_Structure *s, const us_Bitset *present,
                             const us_Forces *f, double tol, double *acc, unsigned char *seen,
                             us_CertCheck *out);

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

/* us_mechanism_check over the contacts in list (NULL: all) with caller
 * scratch slot[nbody], all -1 on entry and on return. */
int us_mechanism_check_list(const us_Structure *s, const us_Bitset *present, us_Mechanism *m,
                            double tol, int *slot, const int *list, int nlist);

/* Euclidean distance of the 2D/3D contact force (f_n, |f_t|) from the cone
 * |f_t| <= mu f_n (mu = INFINITY: the half-space f_n >= 0). It does not
 * grow with mu: a force just outside a wide cone is just outside it. */
double us_cone_distance(double fn, double ft, double mu);

#endif
