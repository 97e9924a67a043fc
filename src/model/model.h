/* Private interface of the structure model: the steps of finalize, each in
 * its own file, so that validation, mass properties and contact detection
 * can be tested separately. */
#ifndef US_MODEL_H
#define US_MODEL_H

#include "core/core.h"

/* validate.c: geometry checks of every body (>= 3 vertices, finite, non-zero
 * area, simple, not below the ground when there is one), orienting each
 * polygon counter-clockwise. Explicit-contact structures: point bodies need
 * a finite centre and positive mass. Messages name the body. */
us_Status us_model_validate(us_Structure *s, us_Error *err);

/* massprops.c: mass (from density unless given), centre of mass and polar
 * inertia about it, for every polygon body. */
us_Status us_model_mass_properties(us_Structure *s, us_Error *err);

/* structure.c: bounding box, scale and total weight (contact_tol is left
 * as the caller set it). */
void us_model_measure(us_Structure *s);

/* Fill the tangent basis of a contact from its normal. */
void us_contact_frame(int dim, us_Contact *c);

#endif
