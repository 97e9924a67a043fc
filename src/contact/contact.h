/* Private interface of contact detection: the broad phase (candidate body
 * pairs), the narrow phase (overlap check and vertex-on-edge contacts of one
 * pair) and the candidate list they fill. See detect.c for the rules. */
#ifndef US_CONTACT_H
#define US_CONTACT_H

#include "geometry/geometry.h"

/* cos of the largest angle between two normals still taken as the same
 * direction (1e-3 rad): used to merge duplicates and spot coincident
 * edges. */
#define US_CONTACT_NORMAL_COS 0.9999995
/* sin of the largest angle by which an edge of a body may point into the
 * other body's side at a corner-on-corner contact (1e-3 rad). */
#define US_CONTACT_DIR_SIN 1e-3

typedef struct us_BodyPair {
  int i, j; /* i < j */
} us_BodyPair;

/* A contact found but not yet added to the structure. */
typedef struct us_Cand {
  int a, b;     /* a: edge owner or US_GROUND; b: vertex owner */
  us_Vec2 p, n; /* point, unit normal from a into b */
} us_Cand;

typedef struct us_CandList {
  us_Cand *c;
  int n, cap;
} us_CandList;

/* Append; 0 or -1 on OOM. */
int us_cand_push(us_CandList *l, int a, int b, us_Vec2 p, us_Vec2 n);

/* Pairs of polygon bodies whose boxes, each inflated by its body's own
 * tolerance tol[i], overlap, except pairs of two fixed bodies; sorted by
 * (i, j). *pairs is allocated (free with us_free) even when empty. Sort
 * and sweep along the axis where the box centres spread most. */
us_Status us_broadphase(const us_Structure *s, const double *tol, us_BodyPair **pairs,
                        int *npairs, us_Error *err);
/* The reference: every pair of polygon bodies but two fixed ones. */
us_Status us_broadphase_all(const us_Structure *s, us_BodyPair **pairs, int *npairs,
                            us_Error *err);

/* One detection run: the structure, each body's own tolerance and each
 * polygon's edge index, built on first use with the body's own tolerance
 * as padding (at least any pair tolerance of the body), kept to the end.
 * Small polygons (at most US_EDGE_GRID_MIN edges) need no index, only a
 * result buffer: they take one of two slots (the least recently used
 * goes), enough for the two bodies of a pair, so the per-body array is
 * never touched for them (23 MB of pages at 100,000 blocks). */
typedef struct us_Detect {
  const us_Structure *s;
  int reference; /* us_ContactSettings.reference: no index, no filter */
  const double *tol;
  us_EdgeGrid *grid;
  unsigned char *built;
  us_EdgeGrid slot[2];
  int slot_body[2], slot_last; /* body in each slot (-1: none), last used */
} us_Detect;

/* Body i's edge index; NULL when out of memory. */
us_EdgeGrid *us_detect_grid(us_Detect *d, int i);

/* detect3.c: the contacts of a 3D structure into out (its old entries
 * dropped), with each body's own tolerance tol[i]; reference: every pair
 * of bodies instead of the broad phase's. */
us_Status us_detect_contacts3(const us_Structure *s, const double *tol, int reference,
                              double deadline, us_ContactList *out, us_Error *err);
/* detect.c: us_detect_contacts stopped with US_ERR_TIME_LIMIT once the
 * clock passes deadline (read every 1024 pairs of bodies; 0: none). */
us_Status us_detect_contacts_until(const us_Structure *s, const us_ContactSettings *set,
                                   double deadline, us_ContactList *out, us_Error *err);
/* The error of detection cut by its deadline after `done` of `total` pairs. */
us_Status us_detect_timeout(int done, int total, us_Error *err);

/* Interpenetration of bodies i and j beyond tol: US_ERR_INPUT naming both. */
us_Status us_pair_overlap(us_Detect *d, int i, int j, double tol, us_Error *err);

/* Vertex-on-edge contacts between i and j, duplicates merged, appended to
 * out in a deterministic order. */
us_Status us_pair_contacts(us_Detect *d, int i, int j, double tol, us_CandList *out,
                           us_Error *err);

#endif
