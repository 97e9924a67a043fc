/* Writing structure files (docs/format.md), atomically: the text goes to a
 * temporary file that is renamed over the target only when everything was
 * written, so an error never leaves a partial file.
 *
 * Layout: top-level settings, then one body per line and one contact per
 * line (readable, diff-friendly, and streamed in linear time for large
 * structures). Numbers use the shortest exact round-trip form, so
 * reading the file back gives bit-identical coordinates. Only what the
 * reader needs is written: density when it is not the default 1, mass when
 * it was given, friction when the body has its own, and the contacts only
 * when they were explicit (detected contacts are re-detected on reading).
 * An infinite friction coefficient is written as the string "infinite"
 * (JSON numbers cannot hold it), which the reader maps back to INFINITY.
 * 3D bodies are written as their hulls' vertices ("vertices", or "parts"
 * of {"vertices"} for a compound): the hull of a hull's vertices is the
 * same hull, and the coordinates are the ones read or generated, bit for
 * bit, so a box written as its 8 corners reads back as the same box. */
#include <math.h>

#include "io.h"

/* `lead` then the friction field (", " inside a line, ",\n  " at the top). */
static void write_friction(us_JsonOut *o, const char *lead, double mu) {
  us_jo_raw(o, lead);
  us_jo_raw(o, "\"friction\": ");
  if (isinf(mu) && mu > 0)
    us_jo_raw(o, "\"infinite\"");
  else
    us_jo_number(o, mu);
}

static void write_material(us_JsonOut *o, const us_Body *b) {
  if (b->mass_given && b->mass > 0) {
    us_jo_raw(o, ", \"mass\": ");
    us_jo_number(o, b->mass);
  } else if ((b->nvert > 0 || b->npart > 0) && b->density != 1.0) {
    us_jo_raw(o, ", \"density\": ");
    us_jo_number(o, b->density);
  }
  if (b->fixed) us_jo_raw(o, ", \"fixed\": true");
  if (b->friction >= 0) write_friction(o, ", ", b->friction);
}

/* "[[x, y, z], ...]" of one part's vertices. */
static void write_points(us_JsonOut *o, const us_Polyhedron *p) {
  us_jo_raw(o, "[");
  for (int k = 0; k < p->nvert; k++) {
    if (k) us_jo_raw(o, ", ");
    us_jo_vecn(o, p->verts + 3 * k, 3);
  }
  us_jo_raw(o, "]");
}

static void write_solid(us_JsonOut *o, const us_Body *b) {
  if (b->npart == 1) {
    us_jo_raw(o, ", \"vertices\": ");
    write_points(o, &b->parts[0]);
    return;
  }
  us_jo_raw(o, ", \"parts\": [");
  for (int k = 0; k < b->npart; k++) {
    us_jo_raw(o, k ? ", {\"vertices\": " : "{\"vertices\": ");
    write_points(o, &b->parts[k]);
    us_jo_raw(o, "}");
  }
  us_jo_raw(o, "]");
}

static void write_body(us_JsonOut *o, const us_Body *b, int dim) {
  us_jo_raw(o, "    {\"id\": ");
  us_jo_string(o, b->id);
  if (b->npart > 0) {
    write_solid(o, b);
  } else if (b->nvert > 0) {
    us_jo_raw(o, ", \"polygon\": [");
    for (int k = 0; k < b->nvert; k++) {
      if (k) us_jo_raw(o, ", ");
      us_jo_vec2(o, b->verts + 2 * k);
    }
    us_jo_raw(o, "]");
  } else {
    us_jo_raw(o, ", \"center\": ");
    us_jo_vecn(o, b->com, dim);
    if (b->inertia > 0) {
      us_jo_raw(o, ", \"inertia\": ");
      us_jo_number(o, b->inertia);
    }
  }
  write_material(o, b);
  us_jo_raw(o, "}");
}

static void write_contact(us_JsonOut *o, const us_Structure *s, const us_Contact *c) {
  us_jo_raw(o, "    {");
  us_jo_contact_fields(o, s, c);
  write_friction(o, ", ", c->mu);
  us_jo_raw(o, "}");
}

static void write_structure(us_JsonOut *o, const us_Structure *s) {
  us_jo_raw(o, s->dim == 3 ? "{\n  \"dimension\": 3,\n  \"gravity\": "
                           : "{\n  \"dimension\": 2,\n  \"gravity\": ");
  us_jo_vecn(o, s->gravity, s->dim == 3 ? 3 : 2);
  write_friction(o, ",\n  ", s->friction);
  us_jo_raw(o, s->ground ? ",\n  \"ground\": true,\n  \"bodies\": ["
                         : ",\n  \"ground\": false,\n  \"bodies\": [");
  for (int i = 0; i < s->nbody; i++) {
    us_jo_raw(o, i ? ",\n" : "\n");
    write_body(o, &s->bodies[i], s->dim == 3 ? 3 : 2);
  }
  us_jo_raw(o, s->nbody ? "\n  ]" : "]");
  if (s->explicit_contacts) {
    us_jo_raw(o, ",\n  \"contacts\": [");
    for (int k = 0; k < s->ncontact; k++) {
      us_jo_raw(o, k ? ",\n" : "\n");
      write_contact(o, s, &s->contacts[k]);
    }
    us_jo_raw(o, s->ncontact ? "\n  ]" : "]");
  }
  us_jo_raw(o, "\n}\n");
}

us_Status us_structure_write(const us_Structure *s, const char *path, us_Error *err) {
  if (!s || !path)
    return us_error_set(err, US_ERR_USAGE, "us_structure_write: no structure or path");
  if (s->dim != 2 && s->dim != 3)
    return us_error_set(err, US_ERR_INPUT, "%s: dimension %d cannot be written", path, s->dim);
  us_AtomicFile *af = us_atomic_open(path, err);
  if (!af) return err ? err->code : US_ERR_IO;
  us_JsonOut o = {us_atomic_stream(af), 0, 0};
  write_structure(&o, s);
  if (o.bad || o.bad_text) {
    us_atomic_abort(af);
    return us_error_set(err, US_ERR_INPUT, "%s: the structure holds %s (JSON cannot store it)",
                        path, o.bad ? "a non-finite number" : "an id that is not valid UTF-8");
  }
  return us_atomic_commit(af, err);
}
