/* The independent certificate check (certificate.c), in a form that needs
 * no allocation (the public us_certificate_check allocates its scratch). */
#ifndef US_STABILITY_CERTIFICATE_H
#define US_STABILITY_CERTIFICATE_H

#include "core/core.h"

/* us_certificate_check with caller scratch (acc: 6 * nbody doubles, seen:
 * ncontact bytes), so that it cannot fail on memory. Returns 0, or -1
 * when the forces are malformed (out->ok = 0). */
int us_certificate_check_buf(const us_Structure *s, const us_Bitset *present,
                             const us_Forces *f, double tol, double *acc, unsigned char *seen,
                             us_CertCheck *out);

/* Euclidean distance of the 2D/3D contact force (f_n, |f_t|) from the cone
 * |f_t| <= mu f_n (mu = INFINITY: the half-space f_n >= 0). It does not
 * grow with mu: a force just outside a wide cone is just outside it. */
double us_cone_distance(double fn, double ft, double mu);

#endif
