/* Transitional umbrella: the stability layer's private interface now lives
 * in one header per concept. Include those directly; this file only keeps
 * older includes compiling.
 *   backend.h      the backend interface, us_stability_new_backend
 *   equilibrium.h  the equilibrium system of a sub-assembly
 *   lp_gen.h       the LP's cone-generator form
 *   certificate.h  the allocation-free certificate check
 */
#ifndef US_STABILITY_H
#define US_STABILITY_H

#include "backend.h"
#include "certificate.h"
#include "equilibrium.h"
#include "lp_gen.h"

#endif
