/* Mass properties (massprops.c) and the weight measures every layer
 * normalizes by, computed so that legal inputs never overflow or
 * underflow on the way. */
#ifndef US_MODEL_MASSPROPS_H
#define US_MODEL_MASSPROPS_H

#include "core/core.h"

/* |g| without overflow (gravity components up to DBL_MAX). */
double us_gravity_norm(const double *g);
/* Total mass of the movable bodies (after mass properties). */
double us_movable_mass(const us_Structure *s);
/* Total weight W = M |g| of the movable bodies; after a successful
 * finalize it is finite and normal whenever a movable body exists. */
double us_total_weight(const us_Structure *s);

#endif
