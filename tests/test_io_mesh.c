/* Tests of the mesh import (src/io/mesh_*.c, docs/mesh.md): the checks
 * and bodies on documents built by hand (boxes with known answers: shells
 * of touching blocks told apart about their shared edges, whatever the
 * order of faces and corners; compounds; convexity against each shell's
 * own tolerance; open, degenerate, non-finite and badly wound meshes named
 * by object; --up, --scale, the ground, --fixed, ids), out-of-memory at
 * every allocation, and one file read through module mesh.so. */
#define _XOPEN_SOURCE 700
#include "test.h"
#include "tmpfiles.h"

#include "io/mesh.h"

/* Corner k of the box [lo, hi] (bit 0: x, bit 1: y, bit 2: z). */
static void corner(const double lo[3], const double hi[3], int k, double p[3]) {
  for (int a = 0; a < 3; a++) p[a] = (k >> a) & 1 ? hi[a] : lo[a];
}

/* The six faces, counter-clockwise seen from outside. */
static const unsigned box_faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                         {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};

/* Append the box [lo, hi] to object o: its faces turned by `rot` corners
 * (the same polygon) and reversed when `flip`. */
static int add_box(us_MeshObject *o, const double lo[3], const double hi[3], int rot, int flip) {
  int base = o->nvert;
  for (int k = 0; k < 8; k++) {
    double p[3];
    corner(lo, hi, k, p);
    if (us_mesh_add_vertex(o, p)) return -1;
  }
  for (int f = 0; f < 6; f++) {
    unsigned idx[4];
    for (int i = 0; i < 4; i++) idx[i] = box_faces[f][(i + rot) % 4];
    if (flip) {
      unsigned t = idx[1];
      idx[1] = idx[3], idx[3] = t;
    }
    if (us_mesh_add_face(o, base, idx, 4)) return -1;
  }
  return 0;
}

static int add_unit_box(us_MeshDoc *d, int obj, double x, double y, double z) {
  double lo[3] = {x, y, z}, hi[3] = {x + 1, y + 1, z + 1};
  return add_box(&d->objs[obj], lo, hi, 0, 0);
}

/* The bounding box of body i's parts: lo[3], hi[3]. */
static void bounds(const us_Structure *s, int i, double box[6]) {
  for (int a = 0; a < 3; a++) box[a] = INFINITY, box[a + 3] = -INFINITY;
  const us_Body *b = &s->bodies[i];
  for (int p = 0; p < b->npart; p++)
    for (int k = 0; k < b->parts[p].nvert; k++)
      for (int a = 0; a < 3; a++) {
        box[a] = fmin(box[a], b->parts[p].verts[3 * k + a]);
        box[a + 3] = fmax(box[a + 3], b->parts[p].verts[3 * k + a]);
      }
}

static us_MeshDoc doc(void) {
  us_MeshDoc d;
  memset(&d, 0, sizeof d);
  d.name = "t.obj";
  d.stem = "t";
  return d;
}

static us_Structure *build(const us_MeshDoc *d, const us_MeshSettings *set, us_MeshInfo *info,
                           us_Error *err) {
  us_MeshSettings dflt = us_mesh_default_settings();
  us_error_clear(err);
  return us_mesh_build(d, set ? set : &dflt, info, err);
}

/* The import fails with US_ERR_INPUT and a message holding each text. */
static int refused(const us_MeshDoc *d, const char *t1, const char *t2) {
  us_Error err;
  us_Structure *s = build(d, NULL, NULL, &err);
  if (s) {
    us_structure_free(s);
    fprintf(stderr, "accepted, wanted '%s'\n", t1);
    return 0;
  }
  int ok = err.code == US_ERR_INPUT && strstr(err.msg, t1) && (!t2 || strstr(err.msg, t2));
  if (!ok) fprintf(stderr, "message: [%s] %s (wanted '%s', '%s')\n", us_status_name(err.code), err.msg, t1, t2 ? t2 : "");
  return ok;
}

/* A 2 x 2 x 2 block of unit cubes in one unnamed object: the edges and the
 * vertex at the centre are on 8 cubes, so every shell must be found by
 * pairing faces about shared edges; the answer must not depend on the
 * order of faces or on which corner a face starts at. */
static void touching_cubes(void) {
  unsigned long long rng = 7;
  for (int trial = 0; trial < 6; trial++) {
    us_MeshDoc d = doc();
    int o = us_mesh_object(&d, "", 0, 0);
    CHECK(o == 0);
    int order[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    for (int k = 7; k > 0 && trial; k--) { /* shuffled boxes, turned faces */
      int j = (int)(test_rnd(&rng) * (k + 1)), t = order[k];
      order[k] = order[j], order[j] = t;
    }
    for (int k = 0; k < 8; k++) {
      double lo[3] = {order[k] & 1, (order[k] >> 1) & 1, (order[k] >> 2) & 1};
      double hi[3] = {lo[0] + 1, lo[1] + 1, lo[2] + 1};
      CHECK(add_box(&d.objs[0], lo, hi, (int)(test_rnd(&rng) * 4), 0) == 0);
    }
    us_Error err;
    us_MeshInfo info;
    us_Structure *s = build(&d, NULL, &info, &err);
    us_mesh_doc_free(&d);
    if (!s) fprintf(stderr, "%s\n", err.msg);
    CHECK(s);
    int nb = s->nbody, np = s->bodies[0].npart;
    us_structure_free(s);
    CHECK_INT(nb, ==, 8);
    CHECK_INT(info.shells, ==, 8);
    CHECK_INT(info.compounds, ==, 0);
    CHECK_INT(np, ==, 1); /* a single convex part */
  }
}

/* Names: an unnamed object's shells are STEM-k (or NAME-k); a named one
 * is one body, a compound of its shells; repeats and "ground" renamed;
 * bytes that are not printable UTF-8 become '_'. */
static void names_and_compounds(void) {
  us_MeshDoc d = doc();
  CHECK(us_mesh_object(&d, "", 0, 0) == 0);
  CHECK(add_unit_box(&d, 0, 0, 0, 0) == 0 && add_unit_box(&d, 0, 0, 0, 1) == 0);
  CHECK(us_mesh_object(&d, "ell", 1, 0) == 1);
  CHECK(add_unit_box(&d, 1, 3, 0, 0) == 0 && add_unit_box(&d, 1, 4, 0, 0) == 0 &&
        add_unit_box(&d, 1, 3, 0, 1) == 0);
  CHECK(us_mesh_object(&d, "ground", 1, 0) == 2 && add_unit_box(&d, 2, 6, 0, 0) == 0);
  CHECK(us_mesh_object(&d, "ell", 1, 0) == 3 && add_unit_box(&d, 3, 8, 0, 0) == 0);
  CHECK(us_mesh_object(&d, "a b\x01\xff", 1, 0) == 4 && add_unit_box(&d, 4, 10, 0, 0) == 0);
  us_Error err;
  us_MeshInfo info;
  us_Structure *s = build(&d, NULL, &info, &err);
  us_mesh_doc_free(&d);
  CHECK(s);
  const char *want[] = {"t-1", "t-2", "ell", "ground-2", "ell-2", "a_b__"};
  int nb = s->nbody, ok = nb == 6;
  for (int i = 0; ok && i < 6; i++) ok = us_structure_find_body(s, want[i]) == i;
  int ell_parts = ok ? s->bodies[2].npart : 0;
  us_structure_free(s);
  CHECK_INT(nb, ==, 6);
  CHECK(ok);
  CHECK_INT(ell_parts, ==, 3);
  CHECK_INT(info.compounds, ==, 1);
  CHECK_INT(info.shells, ==, 8);
  CHECK_INT(info.ids_renamed, ==, 3);
}

/* A shell touching another must be wound outward: reversed, the shared
 * edges' faces cannot be paired and the message says so; a shell that
 * touches nothing may be wound either way. */
static void winding(void) {
  us_MeshDoc d = doc();
  double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, lo2[3] = {0, 0, 1}, hi2[3] = {1, 1, 2};
  double lo3[3] = {5, 0, 0}, hi3[3] = {6, 1, 1};
  CHECK(us_mesh_object(&d, "", 0, 0) == 0);
  CHECK(add_box(&d.objs[0], lo3, hi3, 1, 1) == 0); /* alone, inward: fine */
  us_Error err;
  us_Structure *s = build(&d, NULL, NULL, &err);
  int alone = s != NULL;
  us_structure_free(s);
  CHECK(add_box(&d.objs[0], lo, hi, 0, 0) == 0 && add_box(&d.objs[0], lo2, hi2, 0, 1) == 0);
  int ok = refused(&d, "not all wound the same way", "(0, 0, 1)");
  us_mesh_doc_free(&d);
  CHECK(alone);
  CHECK(ok);
}

/* The unit cube at the origin with its top as 4 triangles round a centre
 * vertex `dent` below the top. */
static int add_dented_box(us_MeshObject *o, double dent) {
  double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, c[3] = {0.5, 0.5, 1 - dent};
  int base = o->nvert;
  for (int k = 0; k < 8; k++) {
    double p[3];
    corner(lo, hi, k, p);
    if (us_mesh_add_vertex(o, p)) return -1;
  }
  if (us_mesh_add_vertex(o, c)) return -1;
  static const unsigned top[4][3] = {{4, 5, 8}, {5, 7, 8}, {7, 6, 8}, {6, 4, 8}};
  for (int f = 0; f < 6; f++)
    if (f != 1 && us_mesh_add_face(o, base, box_faces[f], 4)) return -1;
  for (int f = 0; f < 4; f++)
    if (us_mesh_add_face(o, base, top[f], 3)) return -1;
  return 0;
}

/* Convexity against the shell's own size: a cube's top dented by 1e-8 of
 * its size is accepted, by 1e-3 refused naming the object; a big block far
 * away (another object, or another shell of the same unnamed object)
 * changes neither answer. */
static void convexity_tolerance(void) {
  for (int far = 0; far < 3; far++)
    for (int big = 0; big < 2; big++) {
      us_MeshDoc d = doc();
      CHECK(us_mesh_object(&d, far == 2 ? "" : "cube", far != 2, 0) == 0);
      CHECK(add_dented_box(&d.objs[0], big ? 1e-3 : 1e-8) == 0);
      if (far) {
        double blo[3] = {1000, 1000, 0}, bhi[3] = {3000, 3000, 2000};
        int o = far == 1 ? us_mesh_object(&d, "far", 1, 0) : 0;
        CHECK(o >= 0 && add_box(&d.objs[o], blo, bhi, 0, 0) == 0);
      }
      us_Error err;
      us_Structure *s = build(&d, NULL, NULL, &err);
      int accepted = s != NULL;
      us_structure_free(s);
      int msg = !big || (err.code == US_ERR_INPUT && strstr(err.msg, "not convex") &&
                         strstr(err.msg, far == 2 ? "without a name" : "object 'cube'"));
      if (!msg) fprintf(stderr, "far %d: %s\n", far, err.msg);
      us_mesh_doc_free(&d);
      CHECK_INT(accepted, ==, !big);
      CHECK(msg);
    }
}

/* An L-shaped prism as one shell is refused; as two boxes of one object,
 * a compound. */
static void non_convex_or_compound(void) {
  us_MeshDoc d = doc();
  CHECK(us_mesh_object(&d, "ell", 1, 0) == 0);
  us_MeshObject *o = &d.objs[0];
  /* the L (0,0)-(2,0)-(2,1)-(1,1)-(1,2)-(0,2) in x, z, 1 deep in y */
  const double L[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  for (int k = 0; k < 12; k++) {
    double p[3] = {L[k % 6][0], k < 6 ? 0 : 1, L[k % 6][1]};
    CHECK(us_mesh_add_vertex(o, p) == 0);
  }
  unsigned cap0[6] = {0, 1, 2, 3, 4, 5}, cap1[6] = {11, 10, 9, 8, 7, 6};
  CHECK(us_mesh_add_face(o, 0, cap0, 6) == 0 && us_mesh_add_face(o, 0, cap1, 6) == 0);
  for (unsigned k = 0; k < 6; k++) {
    unsigned q[4] = {k, k + 6, (k + 1) % 6 + 6, (k + 1) % 6};
    CHECK(us_mesh_add_face(o, 0, q, 4) == 0);
  }
  int ok = refused(&d, "object 'ell'", "convex parts");
  us_mesh_doc_free(&d);
  CHECK(ok);
  d = doc();
  double a0[3] = {0, 0, 0}, a1[3] = {2, 1, 1}, b0[3] = {0, 0, 1}, b1[3] = {1, 1, 2};
  CHECK(us_mesh_object(&d, "ell", 1, 0) == 0);
  CHECK(add_box(&d.objs[0], a0, a1, 0, 0) == 0 && add_box(&d.objs[0], b0, b1, 0, 0) == 0);
  us_Error err;
  us_Structure *s = build(&d, NULL, NULL, &err);
  us_mesh_doc_free(&d);
  CHECK(s);
  int nb = s->nbody, np = s->bodies[0].npart;
  us_structure_free(s);
  CHECK_INT(nb, ==, 1);
  CHECK_INT(np, ==, 2);
}

/* Bad meshes, each named by file and object. */
static void bad_meshes(void) {
  us_MeshDoc d = doc();
  CHECK(us_mesh_object(&d, "A", 1, 0) == 0 && add_unit_box(&d, 0, 0, 0, 0) == 0);
  d.objs[0].xyz[4] = NAN;
  int nan_ok = refused(&d, "t.obj: object 'A'", "non-finite");
  d.objs[0].xyz[4] = INFINITY;
  int inf_ok = refused(&d, "t.obj: object 'A'", "non-finite");
  d.objs[0].xyz[4] = 0;
  d.objs[0].nface--, d.objs[0].nidx -= 4; /* a face missing */
  int open_ok = refused(&d, "object 'A'", "open mesh");
  d.objs[0].nface++, d.objs[0].nidx += 4;
  int s1 = d.objs[0].fidx[1], s2 = d.objs[0].fidx[2];
  d.objs[0].fidx[1] = d.objs[0].fidx[2] = d.objs[0].fidx[0]; /* bottom face: 2 distinct corners */
  int deg_ok = refused(&d, "object 'A'", "degenerate");
  d.objs[0].fidx[1] = s1, d.objs[0].fidx[2] = s2;
  d.objs[0].xyz[3 * 7 + 2] += 1e-3; /* corner (1, 1, 1) lifted: three faces bent */
  int planar_ok = refused(&d, "object 'A'", "not planar");
  us_mesh_doc_free(&d);
  CHECK(nan_ok);
  CHECK(inf_ok);
  CHECK(open_ok);
  CHECK(deg_ok);
  CHECK(planar_ok);
  /* a zero-area face: a box squashed flat along z */
  d = doc();
  double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 0};
  CHECK(us_mesh_object(&d, "flat", 1, 0) == 0 && add_box(&d.objs[0], lo, hi, 0, 0) == 0);
  int flat_ok = refused(&d, "object 'flat'", "degenerate");
  us_mesh_doc_free(&d);
  CHECK(flat_ok);
  /* overlapping bodies: finalize's message, with the file */
  d = doc();
  CHECK(us_mesh_object(&d, "A", 1, 0) == 0 && add_unit_box(&d, 0, 0, 0, 0) == 0);
  CHECK(us_mesh_object(&d, "B", 1, 0) == 1 && add_unit_box(&d, 1, 0.5, 0, 0) == 0);
  int over_ok = refused(&d, "t.obj: ", "'B'");
  us_mesh_doc_free(&d);
  CHECK(over_ok);
  d = doc();
  int empty_ok = refused(&d, "no meshes", NULL);
  CHECK(empty_ok);
}

/* --up y turns (x, y, z) into (x, -z, y); --scale; the lowest point on
 * the ground; --fixed by pattern; density. */
static void placement_and_settings(void) {
  us_MeshDoc d = doc();
  double lo[3] = {1, 5, -3}, hi[3] = {2, 7, -2}; /* y-up: 2 high, floating at y = 5 */
  CHECK(us_mesh_object(&d, "slab_1", 1, 0) == 0 && add_box(&d.objs[0], lo, hi, 0, 0) == 0);
  double lo2[3] = {1, 7, -3}, hi2[3] = {2, 8, -2};
  CHECK(us_mesh_object(&d, "top", 1, 0) == 1 && add_box(&d.objs[1], lo2, hi2, 0, 0) == 0);
  us_MeshSettings set = us_mesh_default_settings();
  set.up = 'y';
  set.scale = 10;
  set.fixed = "slab_*";
  set.density = 2;
  us_Error err;
  us_Structure *s = build(&d, &set, NULL, &err);
  CHECK(s);
  double box[6];
  bounds(s, 0, box);
  int fixed0 = s->bodies[0].fixed, fixed1 = s->bodies[1].fixed;
  double m1 = s->bodies[1].mass;
  us_structure_free(s);
  set.up = 'x';
  int bad_up = build(&d, &set, NULL, &err) == NULL && err.code == US_ERR_USAGE;
  set.up = 'z', set.scale = 0;
  int bad_scale = build(&d, &set, NULL, &err) == NULL && err.code == US_ERR_USAGE;
  us_mesh_doc_free(&d);
  CHECK_NEAR(box[0], 10, 1e-9); /* x: 1..2 scaled */
  CHECK_NEAR(box[3], 20, 1e-9);
  CHECK_NEAR(box[1], 20, 1e-9); /* y = -z: 2..3 scaled */
  CHECK_NEAR(box[4], 30, 1e-9);
  CHECK_NEAR(box[2], 0, 1e-9); /* z = y: 5..7, on the ground */
  CHECK_NEAR(box[5], 20, 1e-9);
  CHECK_INT(fixed0, ==, 1);
  CHECK_INT(fixed1, ==, 0);
  CHECK_NEAR(m1, 2 * 1000, 1e-6); /* 10 x 10 x 10 at density 2 */
  CHECK(bad_up);
  CHECK(bad_scale);
}

/* Every allocation failing in turn: US_ERR_NOMEM and no leak, until the
 * import goes through. */
static void out_of_memory(void) {
  us_MeshDoc d = doc();
  CHECK(us_mesh_object(&d, "", 0, 0) == 0);
  for (int k = 0; k < 3; k++) CHECK(add_unit_box(&d, 0, 0, 0, k) == 0);
  CHECK(us_mesh_object(&d, "ell", 1, 0) == 1);
  CHECK(add_unit_box(&d, 1, 3, 0, 0) == 0 && add_unit_box(&d, 1, 4, 0, 0) == 0);
  us_MeshSettings set = us_mesh_default_settings();
  set.fixed = "t-1";
  long live0 = us_alloc_live();
  int done = 0;
  for (long n = 0; n < 100000 && !done; n++) {
    us_Error err;
    us_error_clear(&err);
    us_alloc_fail_after(n);
    us_Structure *s = us_mesh_build(&d, &set, NULL, &err);
    us_alloc_fail_after(-1);
    if (s) done = 1;
    else if (err.code != US_ERR_NOMEM) {
      fprintf(stderr, "n=%ld: [%s] %s\n", n, us_status_name(err.code), err.msg);
      us_mesh_doc_free(&d);
      CHECK(0);
    }
    us_structure_free(s);
    if (us_alloc_live() != live0) us_mesh_doc_free(&d);
    CHECK_INT(us_alloc_live(), ==, live0);
  }
  us_mesh_doc_free(&d);
  CHECK(done);
}

/* Write text to the scratch file `name`; its path in buf. */
static int write_file(const char *name, const char *text, char *buf, size_t n) {
  FILE *fp = test_tmp_path(name, buf, n) ? fopen(buf, "w") : NULL;
  if (!fp) return -1;
  fputs(text, fp);
  return fclose(fp);
}

/* The OBJ reader (mesh_obj.c): corners i, i/t, i//n, i/t/n and negative;
 * groups before an o are objects, after it part of it; names kept whole;
 * attribute lines skipped; unknown and free-form statements, and corners
 * past the vertices, refused naming the line. */
static void obj_reader(void) {
  static const char text[] =
      "# two tetrahedra and a compound\n"
      "mtllib x.mtl\nvt 0 0\nvn 0 0 1\n"
      "g first group\n"
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
      "f 1/1 3/1 2/1\nf 1//1 2//1 4//1\nusemtl red\nf 1/1/1 4/1/1 3/1/1\ns off\nf -3 -2 -1\n"
      "o the ell\ng part a\n"
      "v 3 0 0\nv 4 0 0\nv 3 1 0\nv 3 0 1\n"
      "f -4 -2 -3\nf -4 -3 -1\nf -4 -1 -2\nf -3 -2 -1\n"
      "g part b\n"
      "v 3 0 2\nv 4 0 2\nv 3 1 2\nv 3 0 3\n"
      "f 9 11 10\nf 9 10 12\nf 9 12 11\nf 10 11 12\n";
  char path[256];
  CHECK(write_file("t.obj", text, path, sizeof path) == 0);
  us_MeshDoc d = doc();
  us_Error err;
  us_error_clear(&err);
  us_Status st = us_mesh_read_obj(&d, path, &err);
  int nobj = d.nobj, named0 = nobj > 0 && d.objs[0].named, faces1 = nobj > 1 ? d.objs[1].nface : 0;
  int names = nobj == 2 && !strcmp(d.objs[0].name, "first group") && !strcmp(d.objs[1].name, "the ell");
  us_Structure *s = st ? NULL : build(&d, NULL, NULL, &err);
  us_mesh_doc_free(&d);
  if (st || !s) fprintf(stderr, "%s\n", err.msg);
  CHECK(s);
  int nb = s->nbody, np = s->bodies[1].npart, ell = us_structure_find_body(s, "the_ell");
  us_structure_free(s);
  CHECK_INT(nobj, ==, 2);
  CHECK(named0);
  CHECK(names);
  CHECK_INT(faces1, ==, 8);
  CHECK_INT(nb, ==, 2);
  CHECK_INT(np, ==, 2);
  CHECK_INT(ell, ==, 1);
  static const char *const bad[][2] = {{"v 0 0 0\nf 1 2 3\n", ":2: face corner 2: no such vertex"},
                                       {"v 0 0\n", ":1: a vertex needs three numbers"},
                                       {"\nsurf 0 1 0 1 1 2 3\n", ":2: free-form geometry"},
                                       {"hello\n", ":1: not an OBJ statement: 'hello'"},
                                       {"v 0 0 0\nf 0 1 1\n", ":2: face corner 0"}};
  for (int k = 0; k < 5; k++) {
    CHECK(write_file("bad.obj", bad[k][0], path, sizeof path) == 0);
    d = doc();
    us_error_clear(&err);
    st = us_mesh_read_obj(&d, path, &err);
    us_mesh_doc_free(&d);
    if (!strstr(err.msg, bad[k][1])) fprintf(stderr, "case %d: %s\n", k, err.msg);
    CHECK_INT(st, ==, US_ERR_PARSE);
    CHECK(strstr(err.msg, bad[k][1]) != NULL);
  }
}

/* The OBJ path through the module with every allocation failing in
 * turn: US_ERR_NOMEM, no leak, until it goes through. */
static void out_of_memory_obj(void) {
  char path[256];
  CHECK(write_file("oom.obj", "o a b\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                   "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\ng c\nv 2 0 0\nv 3 0 0\nv 2 1 0\n"
                   "v 2 0 1\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n", path, sizeof path) == 0);
  us_Error err;
  us_structure_free(us_structure_read_mesh(path, NULL, NULL, &err)); /* the module loaded first */
  long live0 = us_alloc_live();
  int done = 0;
  for (long n = 0; n < 100000 && !done; n++) {
    us_error_clear(&err);
    us_alloc_fail_after(n);
    us_Structure *s = us_structure_read_mesh(path, NULL, NULL, &err);
    us_alloc_fail_after(-1);
    if (s) done = 1;
    else if (err.code != US_ERR_NOMEM) fprintf(stderr, "n=%ld: [%s] %s\n", n, us_status_name(err.code), err.msg);
    CHECK(s || err.code == US_ERR_NOMEM);
    us_structure_free(s);
    CHECK_INT(us_alloc_live(), ==, live0);
  }
  CHECK(done);
}

/* One OBJ file through the public entry point and module mesh.so: two
 * named cubes stacked, and a missing file. */
static void module_reads_obj(void) {
  char path[256];
  CHECK(test_tmp_path("mesh.obj", path, sizeof path));
  FILE *fp = fopen(path, "w");
  CHECK(fp);
  for (int b = 0; b < 2; b++) {
    double lo[3] = {0, 0, b}, hi[3] = {1, 1, b + 1};
    fprintf(fp, "o cube%d\n", b);
    for (int k = 0; k < 8; k++) {
      double p[3];
      corner(lo, hi, k, p);
      fprintf(fp, "v %g %g %g\n", p[0], p[1], p[2]);
    }
    for (int f = 0; f < 6; f++)
      fprintf(fp, "f %u %u %u %u\n", 8 * b + box_faces[f][0] + 1, 8 * b + box_faces[f][1] + 1,
              8 * b + box_faces[f][2] + 1, 8 * b + box_faces[f][3] + 1);
  }
  fclose(fp);
  us_Error err;
  us_MeshInfo info;
  us_Structure *s = us_structure_read_mesh(path, NULL, &info, &err);
  if (!s) fprintf(stderr, "%s\n", err.msg);
  CHECK(s);
  int nb = s->nbody, top = us_structure_find_body(s, "cube1"), nc = s->ncontact;
  us_structure_free(s);
  remove(path);
  CHECK_INT(nb, ==, 2);
  CHECK_INT(top, ==, 1);
  CHECK_INT(nc, >, 0);
  CHECK_INT(info.faces, ==, 12);
  s = us_structure_read_mesh(path, NULL, NULL, &err);
  CHECK(!s);
  CHECK_INT(err.code, ==, US_ERR_IO);
  CHECK(strstr(err.msg, path) != NULL);
}

US_TEST_MAIN(T(touching_cubes), T(names_and_compounds), T(winding), T(convexity_tolerance),
             T(non_convex_or_compound), T(bad_meshes), T(placement_and_settings),
             T(out_of_memory), T(obj_reader), T(out_of_memory_obj), T(module_reads_obj))
