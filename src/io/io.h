/* Private helpers of the file formats (structure and plan JSON): error
 * messages that name the file and the JSON path, typed field readers on
 * jansson values, a hash map from body ids to indices, a small streaming
 * JSON writer with shortest round-trip numbers, and the name tables of the
 * enums written to plan files. */
#ifndef US_IO_H
#define US_IO_H

#include <jansson.h>
#include <stdio.h>

#include "core/core.h"

/* Where a reader is: the file name for messages and the error sink. */
typedef struct us_IoCtx {
  const char *name; /* file name (or the caller's label) for messages */
  us_Error *err;
} us_IoCtx;

/* Set US_ERR_INPUT with "NAME: WHERE: message"; returns US_ERR_INPUT. */
us_Status us_io_bad(const us_IoCtx *c, const char *where, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* The jansson flags of every document read: numbers as doubles, duplicate
 * keys rejected (util.c). */
#define US_IO_JSON_FLAGS (JSON_DECODE_INT_AS_REAL | JSON_REJECT_DUPLICATES)
/* Parse text (len bytes) as JSON; on a syntax error set US_ERR_PARSE with
 * "NAME:LINE:COLUMN: text" and return NULL. */
json_t *us_io_parse_json(const us_IoCtx *c, const char *text, size_t len);
/* The same, stopped with US_ERR_TIME_LIMIT once the clock passes deadline
 * (0: none; read every 1 MB of text). */
json_t *us_io_parse_json_until(const us_IoCtx *c, const char *text, size_t len, double deadline);
/* structure_split.c: the byte spans of the elements of a structure file's
 * top-level "bodies" array (arr_off, arr_len: the array itself), so that
 * they can be parsed one at a time. 1 when found, 0 when the text is not
 * plainly so (the caller parses it whole), -1 out of memory; free with
 * us_io_spans_free in every case. */
typedef struct us_JsonSpan {
  size_t off, len;
} us_JsonSpan;
typedef struct us_BodySpans {
  size_t arr_off, arr_len;
  us_JsonSpan *el;
  int n, cap;
} us_BodySpans;
int us_io_split_bodies(const char *text, size_t len, us_BodySpans *out);
void us_io_spans_free(us_BodySpans *b);
/* The value of a body object's "polygon" when it is plain (at most cap
 * [x, y] pairs of short decimal numbers, see structure_split.c): its span
 * in *val, the vertices in xy; returns their count, 0 when not plain. */
int us_io_split_polygon(const char *text, size_t len, us_JsonSpan *val, double *xy, int cap);
/* A body object with nothing but a plain "id" (printable ASCII, no
 * escapes, shorter than US_LANE_ID), a plain "polygon" and maybe "fixed":
 * 1 with the id, the vertices (xy, their count nv) and fixed filled in, so
 * the reader needs no JSON tree for it; 0 when the body is not so. */
#define US_LANE_ID 64
typedef struct us_LaneBody {
  char id[US_LANE_ID];
  int nv, fixed;
} us_LaneBody;
int us_io_lane_body(const char *text, size_t len, double *xy, int cap, us_LaneBody *lb);
/* structure_read.c: the reader without the split, one JSON tree for the
 * whole text: the reference that the streamed reader must equal, message
 * for message (tests). */
us_Structure *us_io_parse_whole(const char *text, const char *name, double contact_tol,
                                us_Error *err);
/* Read a whole file into a NUL-terminated buffer (us_free it). */
char *us_io_slurp(const char *path, size_t *len, us_Error *err);

/* Every key of obj must be in `allowed` (NULL-terminated) or start with
 * '_' (comments); otherwise "unknown field 'KEY'". */
us_Status us_io_check_keys(const us_IoCtx *c, const char *where, json_t *obj,
                           const char *const *allowed);
/* A finite number. */
us_Status us_io_number(const us_IoCtx *c, const char *where, const char *field, json_t *v,
                       double *out);
/* A finite number > 0 (positive != 0) or >= 0 (positive == 0). */
us_Status us_io_sign_number(const us_IoCtx *c, const char *where, const char *field, json_t *v,
                            int positive, double *out);
/* [x, y]: an array of exactly two finite numbers. */
us_Status us_io_vec2(const us_IoCtx *c, const char *where, const char *field, json_t *v,
                     double out[2]);
/* An array of exactly n (2, 3 or 4) finite numbers: [x, y], [x, y, z],
 * [w, x, y, z]. */
us_Status us_io_vecn(const us_IoCtx *c, const char *where, const char *field, json_t *v, int n,
                     double *out);
us_Status us_io_bool(const us_IoCtx *c, const char *where, const char *field, json_t *v, int *out);


/* Streaming JSON output: numbers with the fewest digits (15..17) that read
 * back to the same double; strings escaped. `bad` records a non-finite
 * number, `bad_text` a string that is not valid UTF-8 (JSON cannot hold
 * either), which makes the writer fail. */
typedef struct us_JsonOut {
  FILE *fp;
  int bad;
  int bad_text;
} us_JsonOut;
void us_jo_number(us_JsonOut *o, double x);
void us_jo_string(us_JsonOut *o, const char *s);
void us_jo_vec2(us_JsonOut *o, const double *v); /* [x, y] */
void us_jo_vecn(us_JsonOut *o, const double *v, int n); /* [x, y(, z)] */
/* "a": id|"ground", "b": id, "point": [x, y], "normal": [nx, ny] of a
 * contact ([x, y, z] and [nx, ny, nz] in a 3D structure). */
void us_jo_contact_fields(us_JsonOut *o, const us_Structure *s, const us_Contact *c);
/* One certificate contact, force j of f: {contact fields, "force" in the
 * contact frame, "force_xyz": f_n n + f_t1 t1 [+ f_t2 t2], the force on b in
 * world axes}, so a reader can sum forces and torques per body without
 * rebuilding the tangent frames (plan steps and release certificates). */
void us_jo_cert_contact(us_JsonOut *o, const us_Structure *s, const us_Forces *f, int j);
void us_jo_raw(us_JsonOut *o, const char *s);


/* The geometry of a 3D body (structure_read3.c): "vertices" (>= 4
 * [x, y, z]), "box" ({"center", "size", "rotation" [w, x, y, z] or "euler"
 * [rx, ry, rz] degrees intrinsic z-y-x}) or "parts" (an array of objects
 * each with "vertices" or "box"), as point sets: *parts (npart entries,
 * each xyz owned) to free with us_io_solid_free. */
us_Status us_io_read_solid(const us_IoCtx *c, const char *where, json_t *body, us_PartDef **parts,
                           int *npart);
void us_io_solid_free(us_PartDef *parts, int npart);

#endif
