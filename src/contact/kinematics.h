/* Removal kinematics for the planner: besides standing, may body b leave the
 * sub-assembly `present` by a translation (US_REMOVAL_UP: straight up to
 * infinity; US_REMOVAL_FREE: some direction allowed by its contacts)?
 * kinematics.c states the two tests, their tolerances and their cost;
 * docs/kinematics.md has the proofs and measured figures.
 *
 * Assembly searches ask "may b be placed into present": that is the same
 * question (placing b is its removal played backwards, from present plus b
 * to present), so us_kinematics_can_remove answers both. Every query
 * ignores b's own bit in `present`; fixed bodies and the ground are always
 * present whatever their bits say.
 *
 * The workspace is a precomputation over one finalized 2D structure; it
 * copies what it needs, so the structure may be freed before it. Queries
 * do not allocate and do not change the workspace. Group removal is not
 * covered (one body at a time). */
#ifndef US_KINEMATICS_H
#define US_KINEMATICS_H

#include "core/core.h"

/* UP: length tolerance relative to the size of the pair of bodies tested
 * (the larger of their bounding-box diagonals), never the structure's. */
#define US_KIN_TOL_REL 1e-6
/* FREE: angular tolerance (radians) of the half-plane test; UP, bodies
 * without geometry: a contact pushes down when its normal into b has
 * n_y < -US_KIN_ANGLE_TOL. */
#define US_KIN_ANGLE_TOL 1e-6
/* Returned by us_kinematics_blocker when nothing blocks b. */
#define US_KIN_NONE (-2)

typedef struct us_Kinematics us_Kinematics;

/* Precompute for `s` (finalized, dim 2). Mode ANY keeps nothing; UP builds
 * the list of the bodies above every movable body; FREE sorts every
 * movable body's contact normals by angle. NULL with err set (err may be
 * NULL) when out of memory or when s is not a finalized 2D structure. */
us_Kinematics *us_kinematics_new(const us_Structure *s, us_Removal mode, us_Error *err);
void us_kinematics_free(us_Kinematics *k);
us_Removal us_kinematics_mode(const us_Kinematics *k);

/* 1 when b may be removed from (or placed into) `present`, 0 when blocked.
 * Mode ANY: always 1. A fixed body is never removable (0) in UP and FREE.
 * Cost: UP O(blockers of b), FREE O(contacts of b). */
int us_kinematics_can_remove(const us_Kinematics *k, const us_Bitset *present, int b);

/* For reports: a body that blocks b in `present`, US_GROUND, or
 * US_KIN_NONE when b is free (always in mode ANY; b itself when b is
 * fixed). UP: the present blocker lowest down (smallest y, then index).
 * FREE: the first present movable body, in the angle order of its
 * contacts, whose removal alone would free b; else the body of b's first
 * present contact in that order (then no single body is to blame). */
int us_kinematics_blocker(const us_Kinematics *k, const us_Bitset *present, int b);

/* Like can_remove, and when free a unit direction d that frees b and the
 * angular width (radians) of the cone of such directions: FREE, the middle
 * of the cone {d : d . n >= 0 for every normal n into b} and its width
 * (0: one direction only, e.g. straight up out of a slot; 2 pi: no
 * contact); UP, d = (0, 1) and width 0; ANY, d = (0, 1) and width 2 pi.
 * Blocked: returns 0, d = (0, 0), width 0. */
int us_kinematics_direction(const us_Kinematics *k, const us_Bitset *present, int b, double d[2],
                            double *width);

/* UP: the bodies that block b's upward removal when present, ascending
 * (US_GROUND first when listed); *n gets their count. NULL and *n = 0 in
 * the other modes. Fixed blockers are listed too. */
const int *us_kinematics_up_blockers(const us_Kinematics *k, int b, int *n);
/* UP: the number of (body, blocker) pairs stored; 0 in the other modes. */
long us_kinematics_up_pairs(const us_Kinematics *k);

#endif
