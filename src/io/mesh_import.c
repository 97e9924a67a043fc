/* Mesh files -> structures through Assimp (module mesh.so; docs/mesh.md):
 * the file is read by Assimp's C API, its node tree walked into the
 * neutral document of io/mesh.h, and the document built by mesh_build.c.
 *
 * Objects: every node that carries meshes is one object, named by the
 * node, holding all its meshes (glTF primitives, material sections) with
 * the node's accumulated transform applied. A node's name counts as given
 * unless the format names nothing (STL, PLY, OFF, by extension) or the
 * name is Assimp's own ("", "<...>"); an unnamed object is split into its
 * shells by mesh_build.c. OBJ files are read by mesh_obj.c instead.
 *
 * Assimp is asked for no post-processing beyond validating indices: no
 * triangulation (polygons are checked as they are), no welding, no
 * removal of degenerate faces (they are reported). */
#include "mesh.h"

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

typedef struct Reader {
  us_MeshDoc doc;
  const char *ext;  /* the file's extension ("" without one) */
  us_Error *err;
} Reader;

/* The object a node's meshes go to (named or not), or -1 out of memory. */
static int node_object(Reader *r, const struct aiNode *node) {
  const char *name = node->mName.data;
  int anonymous = !strcasecmp(r->ext, "stl") || !strcasecmp(r->ext, "ply") ||
                  !strcasecmp(r->ext, "off") || !name[0] || name[0] == '<' ||
                  !strcmp(name, "defaultobject");
  return us_mesh_object(&r->doc, name[0] == '<' ? "" : name, !anonymous, 0);
}

/* p = m x (with the translation), Assimp's row-major 4x4. */
static void apply(const struct aiMatrix4x4 *m, const struct aiVector3D *v, double p[3]) {
  double x = v->x, y = v->y, z = v->z;
  p[0] = m->a1 * x + m->a2 * y + m->a3 * z + m->a4;
  p[1] = m->b1 * x + m->b2 * y + m->b3 * z + m->b4;
  p[2] = m->c1 * x + m->c2 * y + m->c3 * z + m->c4;
}

static us_Status add_mesh(Reader *r, us_MeshObject *o, const struct aiMesh *mesh,
                          const struct aiMatrix4x4 *m) {
  int base = o->nvert;
  for (unsigned i = 0; i < mesh->mNumVertices; i++) {
    double p[3];
    apply(m, &mesh->mVertices[i], p);
    if (us_mesh_add_vertex(o, p)) return us_error_set(r->err, US_ERR_NOMEM, "out of memory");
  }
  for (unsigned f = 0; f < mesh->mNumFaces; f++) {
    const struct aiFace *face = &mesh->mFaces[f];
    if (us_mesh_add_face(o, base, face->mIndices, (int)face->mNumIndices))
      return us_error_set(r->err, US_ERR_NOMEM, "out of memory");
  }
  return US_OK;
}

/* Row-major product a b. */
static struct aiMatrix4x4 mul(const struct aiMatrix4x4 *a, const struct aiMatrix4x4 *b) {
  const float *x = &a->a1, *y = &b->a1;
  struct aiMatrix4x4 c;
  float *z = &c.a1;
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) {
      double s = 0;
      for (int k = 0; k < 4; k++) s += (double)x[4 * i + k] * y[4 * k + j];
      z[4 * i + j] = (float)s;
    }
  return c;
}

/* The node tree, depth first in the file's order, transforms accumulated. */
static us_Status walk(Reader *r, const struct aiScene *sc, const struct aiNode *node,
                      const struct aiMatrix4x4 *parent, int depth) {
  if (depth > 1000) return us_error_set(r->err, US_ERR_INPUT, "%s: nodes nested too deep", r->doc.name);
  struct aiMatrix4x4 m = mul(parent, &node->mTransformation);
  us_Status st = US_OK;
  if (node->mNumMeshes > 0) {
    int k = node_object(r, node);
    if (k < 0) return us_error_set(r->err, US_ERR_NOMEM, "out of memory");
    for (unsigned i = 0; i < node->mNumMeshes && !st; i++)
      st = add_mesh(r, &r->doc.objs[k], sc->mMeshes[node->mMeshes[i]], &m);
  }
  for (unsigned i = 0; i < node->mNumChildren && !st; i++)
    st = walk(r, sc, node->mChildren[i], &m, depth + 1);
  return st;
}

static us_Status read_scene(Reader *r, const char *path) {
  const struct aiScene *sc = aiImportFile(path, aiProcess_ValidateDataStructure);
  if (!sc || !sc->mRootNode || (sc->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    us_Status st = us_error_set(r->err, US_ERR_IO, "%s: cannot read the file as a mesh: %s", path,
                                sc ? "the scene is incomplete" : aiGetErrorString());
    if (sc) aiReleaseImport(sc);
    return st;
  }
  struct aiMatrix4x4 id;
  memset(&id, 0, sizeof id);
  id.a1 = id.b2 = id.c3 = id.d4 = 1;
  us_Status st = walk(r, sc, sc->mRootNode, &id, 0);
  aiReleaseImport(sc);
  return st;
}

/* The file's base name without its extension, and the extension. */
static void split_name(const char *path, char *stem, size_t cap, const char **ext) {
  const char *base = strrchr(path, '/');
  base = base ? base + 1 : path;
  const char *dot = strrchr(base, '.');
  *ext = dot ? dot + 1 : "";
  size_t n = dot && dot > base ? (size_t)(dot - base) : strlen(base);
  snprintf(stem, cap, "%.*s", (int)US_MIN(n, cap - 1), base);
  if (!stem[0]) snprintf(stem, cap, "mesh");
}

us_Structure *us_structure_read_mesh(const char *path, const us_MeshSettings *set,
                                     us_MeshInfo *info, us_Error *err) {
  us_MeshSettings dflt = us_mesh_default_settings();
  if (info) memset(info, 0, sizeof *info);
  if (!path) {
    us_error_set(err, US_ERR_USAGE, "us_structure_read_mesh: no path");
    return NULL;
  }
  Reader r;
  memset(&r, 0, sizeof r);
  char stem[256];
  split_name(path, stem, sizeof stem, &r.ext);
  r.doc.name = path;
  r.doc.stem = stem;
  r.err = err;
  FILE *fp = fopen(path, "rb"); /* Assimp's own words for this are vague */
  if (!fp) {
    us_error_set(err, US_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    return NULL;
  }
  fclose(fp);
  /* OBJ by our own reader (mesh_obj.c says why), the rest by Assimp */
  us_Status st = strcasecmp(r.ext, "obj") ? read_scene(&r, path) : us_mesh_read_obj(&r.doc, path, err);
  if (!st && us_past((set ? set : &dflt)->deadline))
    st = us_error_set(err, US_ERR_TIME_LIMIT, "%s: the time limit passed while reading", path);
  us_Structure *s = st ? NULL : us_mesh_build(&r.doc, set ? set : &dflt, info, err);
  us_mesh_doc_free(&r.doc);
  return s;
}
