#!/usr/bin/env python3
"""Write a planar structure (2D JSON, docs/format.md) extruded into prisms
as a mesh file, for the import-mesh tests (tests/cli/import_mesh.sh).

usage: mesh_write.py IN.json OUT FORMAT [--up y] [--depth D]
                     [--compound NAME=ID,ID,...]

FORMAT: obj, stl (ASCII), stlb (binary), ply, off, gltf, glb, 3mf. The
planar y is the vertical: z in a z-up file, y in a y-up one (--up y; glTF
is always y-up, as its specification says). A body's prism is its polygon
at depth 0 and D (default 1), with the caps as polygons (triangle fans
where the format has triangles only). OBJ, glTF and 3MF name each prism
by its body id; --compound writes the listed bodies as groups (OBJ `g`),
primitives (glTF) or shells of one mesh (3MF) of one object NAME. STL, PLY and OFF
name nothing: the importer finds the bodies as connected shells."""
import base64, json, struct, sys, zipfile


def prisms(bodies, depth, up):
    """Each body's (id, vertices, faces) with its caps and sides outward."""
    out = []
    for b in bodies:
        poly = [tuple(p) for p in b["polygon"]]
        area = sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1]))
        if area < 0:
            poly.reverse()
        n = len(poly)
        # planar (x, y), depth d -> z-up (x, d, y) or y-up (x, y, -d): both right-handed
        pt = (lambda x, y, d: (x, d, y)) if up == "z" else (lambda x, y, d: (x, y, -d))
        verts = [pt(x, y, 0.0) for x, y in poly] + [pt(x, y, depth) for x, y in poly]
        # outward: the cap at d = 0 faces -d (the polygon is counter-clockwise in x, y,
        # and (x, y, d) is left-handed in (x, d, y)); the sides follow from it
        front = list(range(n))
        back = [n + k for k in reversed(range(n))]
        sides = [[k, n + k, n + (k + 1) % n, (k + 1) % n] for k in range(n)]
        faces = [front, back] + sides
        out.append((b["id"], verts, faces))
    return out


def triangles(faces):
    return [[f[0], f[k], f[k + 1]] for f in faces for k in range(1, len(f) - 1)]


def normal(v, f):
    a, b, c = (v[i] for i in f[:3])
    u = [b[i] - a[i] for i in range(3)]
    w = [c[i] - a[i] for i in range(3)]
    return (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])


def write_obj(path, groups):
    lines, base = [], 1
    for name, members in groups:
        lines.append("o %s" % name)
        for gid, v, faces in members:
            if len(members) > 1:
                lines.append("g %s" % gid)
            lines += ["v %r %r %r" % p for p in v]
            lines += ["f " + " ".join(str(base + i) for i in f) for f in faces]
            base += len(v)
    open(path, "w").write("\n".join(lines) + "\n")


def write_stl(path, bodies, binary):
    tris = [(v, t) for _, v, faces in bodies for t in triangles(faces)]
    if binary:
        data = bytearray(b"binary stl written by mesh_write.py".ljust(80, b" "))
        data += struct.pack("<I", len(tris))
        for v, t in tris:
            data += struct.pack("<3f", *normal(v, t))
            for i in t:
                data += struct.pack("<3f", *v[i])
            data += b"\0\0"
        open(path, "wb").write(bytes(data))
        return
    lines = ["solid planar"]
    for v, t in tris:
        lines.append("facet normal %r %r %r" % normal(v, t))
        lines.append("outer loop")
        lines += ["vertex %r %r %r" % v[i] for i in t]
        lines += ["endloop", "endfacet"]
    lines.append("endsolid planar")
    open(path, "w").write("\n".join(lines) + "\n")


def flat(bodies):
    verts, faces = [], []
    for _, v, fs in bodies:
        faces += [[len(verts) + i for i in f] for f in fs]
        verts += v
    return verts, faces


def write_ply(path, bodies):
    verts, faces = flat(bodies)
    lines = ["ply", "format ascii 1.0", "element vertex %d" % len(verts),
             "property float x", "property float y", "property float z",
             "element face %d" % len(faces), "property list uchar int vertex_indices", "end_header"]
    lines += ["%r %r %r" % p for p in verts]
    lines += ["%d %s" % (len(f), " ".join(map(str, f))) for f in faces]
    open(path, "w").write("\n".join(lines) + "\n")


def write_off(path, bodies):
    verts, faces = flat(bodies)
    lines = ["OFF", "%d %d 0" % (len(verts), len(faces))]
    lines += ["%r %r %r" % p for p in verts]
    lines += ["%d %s" % (len(f), " ".join(map(str, f))) for f in faces]
    open(path, "w").write("\n".join(lines) + "\n")


def gltf_doc(groups):
    """A glTF 2.0 document and its one binary buffer: a node per group,
    a mesh per node with a primitive per member."""
    buf, views, accs, meshes, nodes = bytearray(), [], [], [], []
    for name, members in groups:
        prims = []
        for _, v, faces in members:
            tris = triangles(faces)
            pos = b"".join(struct.pack("<3f", *p) for p in v)
            idx = b"".join(struct.pack("<3I", *t) for t in tris)
            for data, target in ((pos, 34962), (idx, 34963)):
                views.append({"buffer": 0, "byteOffset": len(buf), "byteLength": len(data),
                              "target": target})
                buf += data
                buf += b"\0" * (-len(buf) % 4)
            lo = [min(p[i] for p in v) for i in range(3)]
            hi = [max(p[i] for p in v) for i in range(3)]
            accs.append({"bufferView": len(views) - 2, "componentType": 5126, "count": len(v),
                         "type": "VEC3", "min": lo, "max": hi})
            accs.append({"bufferView": len(views) - 1, "componentType": 5125,
                         "count": 3 * len(tris), "type": "SCALAR"})
            prims.append({"attributes": {"POSITION": len(accs) - 2}, "indices": len(accs) - 1})
        meshes.append({"name": name, "primitives": prims})
        nodes.append({"name": name, "mesh": len(meshes) - 1})
    doc = {"asset": {"version": "2.0", "generator": "mesh_write.py"},
           "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes,
           "meshes": meshes, "accessors": accs, "bufferViews": views,
           "buffers": [{"byteLength": len(buf)}]}
    return doc, bytes(buf)


def write_gltf(path, groups, binary):
    doc, buf = gltf_doc(groups)
    if not binary:
        doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + \
            base64.b64encode(buf).decode()
        open(path, "w").write(json.dumps(doc))
        return
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    body = struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(buf), 0x004E4942) + buf
    open(path, "wb").write(struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body)


def write_3mf(path, groups):
    """An object per group; a compound's members are shells of one mesh
    (Assimp 5.2 reads 3MF components as separate objects)."""
    objs, items = [], []
    for oid, (name, members) in enumerate(groups, 1):
        v, faces = flat(members)
        vs = "".join('<vertex x="%r" y="%r" z="%r"/>' % p for p in v)
        ts = "".join('<triangle v1="%d" v2="%d" v3="%d"/>' % tuple(t) for t in triangles(faces))
        objs.append('<object id="%d" name="%s" type="model"><mesh><vertices>%s</vertices>'
                    '<triangles>%s</triangles></mesh></object>' % (oid, name, vs, ts))
        items.append('<item objectid="%d"/>' % oid)
    model = ('<?xml version="1.0" encoding="UTF-8"?>\n<model unit="millimeter" xml:lang="en-US" '
             'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>%s'
             '</resources><build>%s</build></model>\n' % ("".join(objs), "".join(items)))
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("[Content_Types].xml", '<?xml version="1.0" encoding="UTF-8"?>\n<Types xmlns='
                   '"http://schemas.openxmlformats.org/package/2006/content-types"><Default '
                   'Extension="rels" ContentType="application/vnd.openxmlformats-package.'
                   'relationships+xml"/><Default Extension="model" ContentType="application/'
                   'vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>')
        z.writestr("_rels/.rels", '<?xml version="1.0" encoding="UTF-8"?>\n<Relationships xmlns='
                   '"http://schemas.openxmlformats.org/package/2006/relationships"><Relationship '
                   'Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dman'
                   'ufacturing/2013/01/3dmodel"/></Relationships>')
        z.writestr("3D/3dmodel.model", model)


def main(argv):
    src, out, fmt = argv[1:4]
    up, depth, compounds = "z", 1.0, {}
    rest = argv[4:]
    while rest:
        opt, val, rest = rest[0], rest[1], rest[2:]
        if opt == "--up":
            up = val
        elif opt == "--depth":
            depth = float(val)
        elif opt == "--compound":
            name, ids = val.split("=")
            compounds[name] = ids.split(",")
    if fmt in ("gltf", "glb"):
        up = "y"
    bodies = prisms(json.load(open(src))["bodies"], depth, up)
    byid = {b[0]: b for b in bodies}
    merged = {i for ids in compounds.values() for i in ids}
    groups = [(n, [byid[i] for i in ids]) for n, ids in compounds.items()]
    groups += [(b[0], [b]) for b in bodies if b[0] not in merged]
    if fmt == "obj":
        write_obj(out, groups)
    elif fmt in ("stl", "stlb"):
        write_stl(out, bodies, fmt == "stlb")
    elif fmt == "ply":
        write_ply(out, bodies)
    elif fmt == "off":
        write_off(out, bodies)
    elif fmt in ("gltf", "glb"):
        write_gltf(out, groups, fmt == "glb")
    elif fmt == "3mf":
        write_3mf(out, groups)
    else:
        sys.exit("unknown format " + fmt)


if __name__ == "__main__":
    main(sys.argv)
