#!/usr/bin/env python3
"""Independent re-check of an unstack plan's certificates.

    check_plan.py STRUCTURE.json PLAN.json [--tol T] [--contact-tol T] [--quiet]

Reads a structure file and a plan file written by
`unstack plan STRUCTURE --certificates -o PLAN` (docs/format.md) and checks
every step's certificate from first principles, with no code shared with the
C library (Python 3 standard library only): masses and centres of mass from
the geometry (shoelace in 2D; convex hulls by brute force in 3D), then for
every step the equilibrium of every present movable body, the sign and cone
of every certificate force, and that every certificate contact is a contact
between present bodies that the geometry allows. docs/independent_check.md
describes the measures.

Exit codes: 0 every step passes; 1 a check failed (the message names the
step, the body or contact and the residual); 2 unreadable or invalid input;
3 nothing failed but some body could not be handled (skipped: the check is
incomplete).
"""

import json
import math
import sys

TOL = 1e-6          # relative tolerance of every residual
HULL_MAX = 32       # brute-force hulls up to this many points


class InputError(Exception):
    pass


class Skip(Exception):
    pass


# ---------------------------------------------------------------- vectors

def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def add(a, b):
    return [x + y for x, y in zip(a, b)]


def scale(a, s):
    return [x * s for x in a]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def norm(a):
    return math.sqrt(dot(a, a))


def cross3(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def cross2(a, b):
    return a[0] * b[1] - a[1] * b[0]


def unit(a):
    n = norm(a)
    return [x / n for x in a]


# ---------------------------------------------------------------- input helpers

def num(v, what):
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise InputError("%s: expected a finite number, got %r" % (what, v))
    return float(v)


def vec(v, dim, what):
    if not isinstance(v, list) or len(v) != dim:
        raise InputError("%s: expected %d numbers" % (what, dim))
    return [num(x, "%s[%d]" % (what, i)) for i, x in enumerate(v)]


def friction_value(v, what):
    if v == "infinite":
        return math.inf
    f = num(v, what)
    if f < 0:
        raise InputError("%s: negative friction" % what)
    return f


def quote(s):
    return repr(s) if isinstance(s, str) else str(s)


# ---------------------------------------------------------------- 2D polygons

def polygon_props(pts):
    """Area (>0), centroid, orientation sign of a simple polygon (shoelace)."""
    o = pts[0]
    a2 = 0.0
    cx = cy = 0.0
    n = len(pts)
    for i in range(n):
        p = sub(pts[i], o)
        q = sub(pts[(i + 1) % n], o)
        c = cross2(p, q)
        a2 += c
        cx += (p[0] + q[0]) * c
        cy += (p[1] + q[1]) * c
    if a2 == 0:
        raise InputError("polygon has zero area")
    area = a2 / 2
    cen = [o[0] + cx / (6 * area), o[1] + cy / (6 * area)]
    return abs(area), cen, (1 if area > 0 else -1)


def seg_dist(p, a, b):
    ab = sub(b, a)
    l2 = dot(ab, ab)
    t = 0.0 if l2 == 0 else max(0.0, min(1.0, dot(sub(p, a), ab) / l2))
    return norm(sub(p, add(a, scale(ab, t))))


# ---------------------------------------------------------------- 3D hulls

def hull3(points, what):
    """Convex hull of a small point set by brute force over triples.

    Returns (faces, verts, volume, centroid): faces as (normal, offset,
    [vertex indices, counter-clockwise seen from outside]) with normal .
    x <= offset inside. Raises Skip for sets it does not handle (too many
    points, flat, a surface that does not close)."""
    n0 = len(points)
    if n0 > HULL_MAX:
        raise Skip("%s: %d points (this checker's brute-force hull takes at most %d)"
                   % (what, n0, HULL_MAX))
    lo = [min(p[i] for p in points) for i in range(3)]
    hi = [max(p[i] for p in points) for i in range(3)]
    diag = norm(sub(hi, lo))
    if not diag > 0:
        raise Skip("%s: all points coincide" % what)
    origin = [(l + h) / 2 for l, h in zip(lo, hi)]
    eps = 1e-9 * diag
    # work relative to the box centre; merge duplicates
    pts = []
    for p in points:
        q = sub(p, origin)
        if all(norm(sub(q, r)) > eps for r in pts):
            pts.append(q)
    n = len(pts)
    if n < 4:
        raise Skip("%s: fewer than 4 distinct points" % what)
    faces = []  # [normal, set of on-plane indices]
    for i in range(n):
        for j in range(i + 1, n):
            for k in range(j + 1, n):
                nv = cross3(sub(pts[j], pts[i]), sub(pts[k], pts[i]))
                ln = norm(nv)
                if ln <= 1e-9 * diag * diag:
                    continue  # (nearly) collinear triple
                nv = scale(nv, 1 / ln)
                d = [dot(sub(p, pts[i]), nv) for p in pts]
                if max(d) <= eps:
                    pass
                elif min(d) >= -eps:
                    nv = scale(nv, -1)
                    d = [-x for x in d]
                else:
                    continue
                if min(d) >= -eps:
                    raise Skip("%s: the points lie in one plane" % what)
                on = {m for m in range(n) if d[m] >= -eps}
                for f in faces:
                    if dot(f[0], nv) > 1 - 1e-9:
                        f[1] |= on
                        break
                else:
                    faces.append([nv, on])
    if len(faces) < 4:
        raise Skip("%s: no closed hull found" % what)
    out = []
    for nv, on in faces:
        # order the face's points: 2D hull in the face plane
        u = unit(cross3(nv, [1, 0, 0] if abs(nv[0]) < 0.9 else [0, 1, 0]))
        w = cross3(nv, u)
        idx = sorted(on, key=lambda m: (dot(pts[m], u), dot(pts[m], w)))
        xy = {m: (dot(pts[m], u), dot(pts[m], w)) for m in idx}

        def turn(o, a, b):
            return ((xy[a][0] - xy[o][0]) * (xy[b][1] - xy[o][1])
                    - (xy[a][1] - xy[o][1]) * (xy[b][0] - xy[o][0]))

        def chain(seq):
            h = []
            for m in seq:
                while len(h) >= 2 and turn(h[-2], h[-1], m) <= eps * diag:
                    h.pop()
                h.append(m)
            return h

        lower = chain(idx)
        upper = chain(list(reversed(idx)))
        poly = lower[:-1] + upper[:-1]  # counter-clockwise about nv (u x w = nv)
        if len(poly) < 3:
            raise Skip("%s: a degenerate face" % what)
        # Newell normal and plane offset from the ordered polygon
        nn = [0.0, 0.0, 0.0]
        for a in range(len(poly)):
            p, q = pts[poly[a]], pts[poly[(a + 1) % len(poly)]]
            nn[0] += (p[1] - q[1]) * (p[2] + q[2])
            nn[1] += (p[2] - q[2]) * (p[0] + q[0])
            nn[2] += (p[0] - q[0]) * (p[1] + q[1])
        nn = unit(nn)
        if dot(nn, nv) < 0.99:
            raise Skip("%s: a face's orientation is inconsistent" % what)
        off = sum(dot(nn, pts[m]) for m in poly) / len(poly)
        out.append((nn, off, poly))
    # the surface must close: every edge used once in each direction
    edges = {}
    for _, _, poly in out:
        for a in range(len(poly)):
            e = (poly[a], poly[(a + 1) % len(poly)])
            edges[e] = edges.get(e, 0) + 1
    for (a, b), c in edges.items():
        if c != 1 or edges.get((b, a)) != 1:
            raise Skip("%s: the hull's faces do not close (edge %d-%d)" % (what, a, b))
    verts = sorted({m for _, _, poly in out for m in poly})
    nv_, ne, nf = len(verts), len(edges) // 2, len(out)
    if nv_ - ne + nf != 2:
        raise Skip("%s: hull fails Euler's formula (V %d, E %d, F %d)" % (what, nv_, ne, nf))
    # volume and centroid: tetrahedra from an interior point over the faces
    c0 = scale([sum(pts[m][i] for m in verts) for i in range(3)], 1 / len(verts))
    vol = 0.0
    mom = [0.0, 0.0, 0.0]
    for _, _, poly in out:
        a = sub(pts[poly[0]], c0)
        for t in range(1, len(poly) - 1):
            b = sub(pts[poly[t]], c0)
            c = sub(pts[poly[t + 1]], c0)
            v = dot(a, cross3(b, c)) / 6
            vol += v
            mom = add(mom, scale(add(add(a, b), c), v / 4))
    if not vol > 0:
        raise Skip("%s: hull volume %g" % (what, vol))
    cen = add(add(c0, scale(mom, 1 / vol)), origin)
    faces_w = [(nn, off + dot(nn, origin), poly) for nn, off, poly in out]
    verts_w = [add(pts[m], origin) for m in verts]
    return faces_w, verts_w, vol, cen


def quat_matrix(q):
    w, x, y, z = unit(q)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def euler_matrix(e):
    rx, ry, rz = (math.radians(v) for v in e)
    cx, sx, cy, sy, cz, sz = (math.cos(rx), math.sin(rx), math.cos(ry), math.sin(ry),
                              math.cos(rz), math.sin(rz))
    Rx = [[1, 0, 0], [0, cx, -sx], [0, sx, cx]]
    Ry = [[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]]
    Rz = [[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]]
    return matmul(Rz, matmul(Ry, Rx))


def box_part(bx, what):
    if not isinstance(bx, dict):
        raise InputError("%s: box must be an object" % what)
    c = vec(bx.get("center"), 3, what + ".center")
    s = vec(bx.get("size"), 3, what + ".size")
    if min(s) <= 0:
        raise InputError("%s.size: must be > 0" % what)
    if "rotation" in bx and "euler" in bx:
        raise InputError("%s: both rotation and euler" % what)
    if "euler" in bx:
        R = euler_matrix(vec(bx["euler"], 3, what + ".euler"))
    else:
        q = vec(bx.get("rotation", [1, 0, 0, 0]), 4, what + ".rotation")
        if norm(q) == 0:
            raise InputError("%s.rotation: zero quaternion" % what)
        R = quat_matrix(q)
    corners = []
    for sx in (-0.5, 0.5):
        for sy in (-0.5, 0.5):
            for sz in (-0.5, 0.5):
                loc = [sx * s[0], sy * s[1], sz * s[2]]
                corners.append([c[i] + sum(R[i][k] * loc[k] for k in range(3)) for i in range(3)])
    # mass properties directly from the box; the hull only for the surface
    faces, verts, _, _ = hull3(corners, what)
    return {"faces": faces, "verts": verts, "vol": s[0] * s[1] * s[2], "cen": c}


def vertices_part(v, what):
    if not isinstance(v, list) or len(v) < 4:
        raise InputError("%s: needs at least 4 points" % what)
    pts = [vec(p, 3, "%s[%d]" % (what, i)) for i, p in enumerate(v)]
    faces, verts, vol, cen = hull3(pts, what)
    return {"faces": faces, "verts": verts, "vol": vol, "cen": cen}


def part_sd(part, p):
    """Signed distance-like measure of p to a convex part: max over faces."""
    return max(dot(nn, p) - off for nn, off, _ in part["faces"])


# ---------------------------------------------------------------- structure

class Body:
    pass


def load_structure(path):
    try:
        with open(path, encoding="utf-8-sig") as f:
            s = json.load(f)
    except (OSError, ValueError) as e:
        raise InputError("%s: %s" % (path, e))
    if not isinstance(s, dict):
        raise InputError("%s: not a JSON object" % path)
    dim = s.get("dimension", 2)
    if dim not in (2, 3) or isinstance(dim, bool):
        raise InputError("%s: dimension must be 2 or 3" % path)
    g = vec(s.get("gravity", [0, -9.81] if dim == 2 else [0, 0, -9.81]), dim, "gravity")
    mu0 = friction_value(s.get("friction", 0.5), "friction")
    ground = s.get("ground", True)
    if not isinstance(ground, bool):
        raise InputError("%s: ground must be true or false" % path)
    blist = s.get("bodies")
    if not isinstance(blist, list):
        raise InputError("%s: bodies: expected an array" % path)
    explicit = "contacts" in s
    bodies = {}
    order = []
    skipped = []
    for i, bj in enumerate(blist):
        what = "bodies[%d]" % i
        if not isinstance(bj, dict) or not isinstance(bj.get("id"), str) or not bj["id"]:
            raise InputError("%s: %s: needs an object with a non-empty string id" % (path, what))
        b = Body()
        b.id = bj["id"]
        what = "%s (id %s)" % (what, quote(b.id))
        if b.id == "ground" or b.id in bodies:
            raise InputError("%s: %s: reserved or duplicate id" % (path, what))
        b.fixed = bj.get("fixed", False) is True
        b.mu = friction_value(bj["friction"], what + ".friction") if "friction" in bj else mu0
        b.skip = None
        b.kind = None
        b.parts = []
        b.poly = None
        vol = None
        try:
            if dim == 2 and "polygon" in bj:
                pts = bj["polygon"]
                if not isinstance(pts, list) or len(pts) < 3:
                    raise InputError("%s: polygon needs at least 3 vertices" % what)
                b.poly = [vec(p, 2, "%s.polygon[%d]" % (what, k)) for k, p in enumerate(pts)]
                vol, b.cen, b.orient = polygon_props(b.poly)
                b.kind = "polygon"
                b.pts = b.poly
            elif dim == 3 and any(k in bj for k in ("vertices", "box", "parts")):
                if "vertices" in bj:
                    parts = [vertices_part(bj["vertices"], what + ".vertices")]
                elif "box" in bj:
                    parts = [box_part(bj["box"], what + ".box")]
                else:
                    pl = bj["parts"]
                    if not isinstance(pl, list) or not pl:
                        raise InputError("%s: parts: a non-empty array" % what)
                    parts = []
                    for k, pj in enumerate(pl):
                        pw = "%s.parts[%d]" % (what, k)
                        if isinstance(pj, dict) and "vertices" in pj:
                            parts.append(vertices_part(pj["vertices"], pw + ".vertices"))
                        elif isinstance(pj, dict) and "box" in pj:
                            parts.append(box_part(pj["box"], pw + ".box"))
                        else:
                            raise InputError("%s: needs vertices or box" % pw)
                b.parts = parts
                vol = sum(p["vol"] for p in parts)
                b.cen = scale([sum(p["vol"] * p["cen"][d] for p in parts) for d in range(3)],
                              1 / vol)
                b.kind = "hull"
                b.pts = [v for p in parts for v in p["verts"]]
            elif explicit and "center" in bj:
                b.cen = vec(bj["center"], dim, what + ".center")
                b.kind = "point"
                b.pts = [b.cen]
            else:
                raise InputError("%s: no geometry (polygon / vertices / box / parts, or "
                                 "center with explicit contacts)" % what)
        except Skip as e:
            b.skip = str(e)
            skipped.append(b)
            b.cen = None
            b.pts = []
        if "mass" in bj and "density" in bj:
            raise InputError("%s: %s: both mass and density" % (path, what))
        if "mass" in bj:
            b.mass = num(bj["mass"], what + ".mass")
        elif b.kind == "point":
            if not b.fixed:
                raise InputError("%s: %s: a body without geometry needs a mass" % (path, what))
            b.mass = 0.0
        elif vol is not None:
            b.mass = num(bj.get("density", 1), what + ".density") * vol
        else:
            b.mass = None
        if b.mass is not None and not b.mass > 0 and not b.fixed:
            raise InputError("%s: %s: mass must be > 0" % (path, what))
        if b.pts:
            lo = [min(p[d] for p in b.pts) for d in range(dim)]
            hi = [max(p[d] for p in b.pts) for d in range(dim)]
            b.diag = norm(sub(hi, lo))
            b.mag = max(abs(x) for p in b.pts for x in p)
        else:
            b.diag = 0.0
            b.mag = 0.0
        bodies[b.id] = b
        order.append(b.id)
    contacts = None
    if explicit:
        cl = s["contacts"]
        if not isinstance(cl, list):
            raise InputError("%s: contacts: expected an array" % path)
        contacts = []
        for i, cj in enumerate(cl):
            what = "contacts[%d]" % i
            if not isinstance(cj, dict):
                raise InputError("%s: %s: expected an object" % (path, what))
            a, b = cj.get("a"), cj.get("b")
            if not (a == "ground" or a in bodies) or b not in bodies:
                raise InputError("%s: %s: unknown body" % (path, what))
            p = vec(cj.get("point"), dim, what + ".point")
            n = unit(vec(cj.get("normal"), dim, what + ".normal"))
            mu = friction_value(cj["friction"], what + ".friction") if "friction" in cj else None
            contacts.append((a, b, p, n, mu))
    wtot = sum(b.mass for b in bodies.values() if not b.fixed and b.mass) * norm(g)
    return {"dim": dim, "g": g, "mu": mu0, "ground": ground, "bodies": bodies,
            "order": order, "contacts": contacts, "skipped": skipped, "wtot": wtot}


# ---------------------------------------------------------------- contacts

def frame3(n):
    """The documented tangent frame: e = the axis of n's smallest component
    (in absolute value; ties go to the later axis), t1 = unit(e x n),
    t2 = n x t1."""
    an = [abs(x) for x in n]
    k = max(i for i in range(3) if an[i] == min(an))
    e = [0.0, 0.0, 0.0]
    e[k] = 1.0
    t1 = unit(cross3(e, n))
    return t1, cross3(n, t1)


def contact_mu(S, a, b):
    ma = S["mu"] if a == "ground" else S["bodies"][a].mu
    return min(ma, S["bodies"][b].mu)


def geometric_tol(S, a, b, p, base):
    bs = [S["bodies"][x] for x in (a, b) if x != "ground"]
    diags = [x.diag for x in bs if x.diag > 0]
    t = (base if base is not None else 1e-6 * min(diags)) if diags else 0.0
    mag = max([abs(x) for x in p] + [x.mag for x in bs])
    return 2 * t + 1e-12 * mag


def surface_2d(body, p, n, side, tol):
    """Distance of p from body's boundary, and whether some edge through p
    (within tol) has n as its outward (side a) or inward (side b) normal."""
    poly = body.poly
    best = math.inf
    normal_ok = False
    for i in range(len(poly)):
        u, v = poly[i], poly[(i + 1) % len(poly)]
        d = seg_dist(p, u, v)
        best = min(best, d)
        e = sub(v, u)
        out = unit([e[1], -e[0]]) if body.orient > 0 else unit([-e[1], e[0]])
        want = out if side == "a" else scale(out, -1)
        if d <= tol and norm(sub(want, n)) <= 1e-6:
            normal_ok = True
    return best, normal_ok


def surface_3d(body, p, n, side, tol):
    """Distance of p from body's surface (0 inside a face within tol), and
    whether the plane through p with normal n separates a part of the body
    that p lies on (body on the side n points away from for side a)."""
    best = math.inf
    normal_ok = False
    for part in body.parts:
        sd = part_sd(part, p)
        best = min(best, abs(sd))
        if abs(sd) <= tol:
            ext = [dot(sub(v, p), n) for v in part["verts"]]
            if (side == "a" and max(ext) <= tol) or (side == "b" and min(ext) >= -tol):
                normal_ok = True
    for part in body.parts:  # not deep inside another part
        if part_sd(part, p) < -tol:
            best = max(best, -part_sd(part, p))
    return best, normal_ok


def plausible(S, c, base_tol):
    """'' if the certificate contact (a, b, point, normal) is a contact the
    structure allows, else a message; plus the coefficient and the worst
    geometric distance relative to the tolerance."""
    a, b, p, n = c["a"], c["b"], c["point"], c["normal"]
    dim = S["dim"]
    tol = geometric_tol(S, a, b, p, base_tol)
    if S["contacts"] is not None:
        for (ea, eb, ep, en, emu) in S["contacts"]:
            if ea == a and eb == b and norm(sub(ep, p)) <= tol and norm(sub(en, n)) <= 1e-6:
                return "", (emu if emu is not None else contact_mu(S, a, b)), 0.0
        return "not one of the structure's explicit contacts", None, math.inf
    mu = contact_mu(S, a, b)
    worst = 0.0
    for side, x in (("a", a), ("b", b)):
        if x == "ground":
            up = [0.0] * dim
            up[-1] = 1.0
            d = abs(p[-1])
            if d > tol:
                return "point %g off the ground" % p[-1], mu, d / tol
            if norm(sub(n, up)) > 1e-6:
                return "a ground contact's normal is not vertical", mu, math.inf
            worst = max(worst, d / tol if tol > 0 else 0)
            continue
        body = S["bodies"][x]
        if body.skip:
            continue
        if dim == 2:
            d, nok = surface_2d(body, p, n, side, tol)
        else:
            d, nok = surface_3d(body, p, n, side, tol)
        worst = max(worst, d / tol if tol > 0 else 0)
        if d > tol:
            return "point is %.3g from the surface of %s (tolerance %.3g)" % (d, quote(x), tol), \
                mu, d / tol
    # the normal: an outward face/edge normal of a or an inward one of b at
    # p (2D), a plane through p separating the touching convex parts (3D)
    sides = (("a", a), ("b", b))
    if any(x != "ground" and S["bodies"][x].skip for _, x in sides):
        ok = True  # a skipped body: its geometry is unknown
    elif dim == 2:
        # the ground's edge normal is vertical (checked above)
        ok = a == "ground" or any(surface_2d(S["bodies"][x], p, n, s_, tol)[1]
                                  for s_, x in sides)
    else:
        ok = all(x == "ground" or surface_3d(S["bodies"][x], p, n, s_, tol)[1]
                 for s_, x in sides)
    if not ok:
        return "normal %s is not a contact normal of %s and %s at this point" % (
            [round(v, 6) for v in n], quote(a), quote(b)), mu, worst
    return "", mu, worst


def cone_distance(fn, ft, mu):
    """Distance of (fn, |ft|) from the cone |ft| <= mu fn, fn >= 0."""
    if math.isinf(mu):
        return max(0.0, -fn)
    if ft <= mu * fn:
        return 0.0
    if mu * ft <= -fn:
        return math.hypot(fn, ft)
    return (ft - mu * fn) / math.sqrt(1 + mu * mu)


# ---------------------------------------------------------------- plan

def load_plan(path, S):
    try:
        with open(path, encoding="utf-8-sig") as f:
            P = json.load(f)
    except (OSError, ValueError) as e:
        raise InputError("%s: %s" % (path, e))
    if not isinstance(P, dict) or not isinstance(P.get("status"), str):
        raise InputError("%s: not a plan (no status)" % path)
    order = P.get("order")
    if not isinstance(order, list):
        raise InputError("%s: order: expected an array" % path)
    steps = P.get("steps")
    if steps is not None and not isinstance(steps, list):
        raise InputError("%s: steps: expected an array" % path)
    dim = S["dim"]
    out = []
    for k, st in enumerate(steps or []):
        what = "%s: steps[%d]" % (path, k)
        if not isinstance(st, dict):
            raise InputError(what + ": expected an object")
        rem = st.get("remove")
        rem = [rem] if isinstance(rem, str) else rem
        if not isinstance(rem, list) or not all(isinstance(x, str) for x in rem):
            raise InputError(what + ": remove: a body id or an array of ids")
        cert = st.get("certificate")
        cl = None
        if cert is not None:
            if not isinstance(cert, dict) or not isinstance(cert.get("contacts"), list):
                raise InputError(what + ": certificate.contacts: expected an array")
            cl = []
            for i, cj in enumerate(cert["contacts"]):
                cw = "%s.certificate.contacts[%d]" % (what, i)
                if not isinstance(cj, dict) or not isinstance(cj.get("a"), str) \
                        or not isinstance(cj.get("b"), str):
                    raise InputError(cw + ": needs a and b")
                try:
                    c = {"a": cj["a"], "b": cj["b"], "point": vec(cj.get("point"), dim, "point"),
                         "normal": vec(cj.get("normal"), dim, "normal"),
                         "force": vec(cj.get("force"), dim, "force"),
                         "force_xyz": vec(cj.get("force_xyz"), dim, "force_xyz"), "i": i}
                except InputError as e:
                    raise InputError("%s: %s" % (cw, e))
                cl.append(c)
        out.append((rem, cl))
    load_actions(path, P, dim)
    return P, order, out


def parse_contacts(what, contacts, dim):
    cl = []
    for i, cj in enumerate(contacts):
        cw = "%s.contacts[%d]" % (what, i)
        if not isinstance(cj, dict) or not isinstance(cj.get("a"), str) \
                or not isinstance(cj.get("b"), str):
            raise InputError(cw + ": needs a and b")
        try:
            cl.append({"a": cj["a"], "b": cj["b"], "point": vec(cj.get("point"), dim, "point"),
                       "normal": vec(cj.get("normal"), dim, "normal"),
                       "force": vec(cj.get("force"), dim, "force"),
                       "force_xyz": vec(cj.get("force_xyz"), dim, "force_xyz"), "i": i})
        except InputError as e:
            raise InputError("%s: %s" % (cw, e))
    return cl


def load_actions(path, P, dim):
    """A plan with hands: "hands", "actions" ([verb, id] each) and, with
    certificates, "release_certificates" (per release: the held bodies and
    the forces), kept in P["_rcerts"] by action index."""
    acts = P.get("actions")
    if acts is None:
        return
    if not isinstance(acts, list) or not all(
            isinstance(a, list) and len(a) == 2 and all(isinstance(x, str) for x in a)
            for a in acts):
        raise InputError("%s: actions: expected an array of [verb, id]" % path)
    if not isinstance(P.get("hands"), int) or P["hands"] < 1:
        raise InputError("%s: hands: expected a positive integer" % path)
    rc = {}
    for k, r in enumerate(P.get("release_certificates") or []):
        what = "%s: release_certificates[%d]" % (path, k)
        if not isinstance(r, dict) or not isinstance(r.get("action"), int) \
                or not isinstance(r.get("held"), list) or not isinstance(r.get("contacts"), list):
            raise InputError(what + ": needs action, held and contacts")
        rc[r["action"]] = (r["held"], parse_contacts(what, r["contacts"], dim))
    P["_rcerts"] = rc


def tally(emit):
    """The failures and the worst measures of a check: (fails, worst, fail,
    note), fail(msg) recording and printing a failure, note(kind, val,
    where) keeping the largest value of each measure."""
    fails = []
    worst = {"force": (0.0, ""), "torque": (0.0, ""), "cone": (0.0, ""), "normal": (0.0, ""),
             "frame": (0.0, ""), "geometry": (0.0, "")}

    def fail(msg):
        fails.append(msg)
        emit("FAIL " + msg)

    def note(kind, val, where):
        if val > worst[kind][0]:
            worst[kind] = (val, where)

    return fails, worst, fail, note


def check_actions(S, P, order, tol, base_tol, quiet, emit):
    """Replay an action plan: never more than "hands" held, each body placed
    once, releases of held bodies, all placed and none held at the end,
    "order" the placements reversed, and after every release its
    certificate: the placed bodies balanced with the held ones as supports."""
    bodies = S["bodies"]
    fails, worst, fail, note = tally(emit)

    H, rc = P["hands"], P["_rcerts"]
    placed, pset, held = [], set(), set()
    skipped = bool(S["skipped"])
    nrel = 0
    for k, (verb, x) in enumerate(P["actions"]):
        if x not in bodies or bodies[x].fixed:
            fail("action %d: %s is not a movable body" % (k, quote(x)))
            continue
        if verb == "place" and x in pset:
            fail("action %d: %s placed twice" % (k, quote(x)))
        elif verb == "place":
            pset.add(x)
            placed.append(x)
            held.add(x)
        elif verb == "grab" and (x not in pset or x in held):
            fail("action %d: grab of %s, not placed or already held" % (k, quote(x)))
        elif verb == "grab":
            held.add(x)
        elif verb == "release" and x not in held:
            fail("action %d: release of %s, which is not held" % (k, quote(x)))
        elif verb == "release":
            held.discard(x)
            nrel += 1
            cert = rc.get(k)
            sname = "action %d (release %s)" % (k, quote(x))
            if cert is None:
                fail("%s: no certificate (plan with --certificates)" % sname)
                continue
            if set(cert[0]) != held:
                fail("%s: the certificate's held bodies are not the ones held" % sname)
            present = [i for i in S["order"] if i in pset]
            if check_step(S, present, set(held), cert[1], sname, tol, base_tol, quiet, emit,
                          fails, fail, note):
                skipped = True
        else:
            fail("action %d: unknown verb %s" % (k, quote(verb)))
        if len(held) > H:
            fail("action %d: %d bodies held, more than %d hands" % (k, len(held), H))
    missing = [x for x in S["order"] if not bodies[x].fixed and x not in pset]
    if missing:
        fail("plan: %d movable bodies are never placed" % len(missing))
    if held:
        fail("plan: %d bodies still held at the end" % len(held))
    if [x for x in order] != placed[::-1]:
        fail("plan: order is not the placements reversed")
    P["_nrel"] = nrel
    return fails, worst, skipped


def check(S, P, order, steps, tol, base_tol, quiet, emit):
    if P.get("actions") is not None:
        return check_actions(S, P, order, tol, base_tol, quiet, emit)
    return check_steps(S, P, order, steps, tol, base_tol, quiet, emit)


def check_step(S, present, held, cl, sname, tol, base_tol, quiet, emit, fails, fail, note):
    """One step's certificate: the bodies of `present` with those of `held`
    (and the fixed ones) as supports. Returns whether a body was skipped."""
    bodies = S["bodies"]
    pset = set(present)
    fsum = {i: [0.0] * S["dim"] for i in present}
    tsum = {i: ([0.0] * 3 if S["dim"] == 3 else [0.0]) for i in present}
    fmag = {i: 0.0 for i in present}
    lever = {i: 0.0 for i in present}
    sw = {"force": (0.0, ""), "torque": (0.0, ""), "cone": (0.0, ""),
          "normal": (0.0, ""), "frame": (0.0, ""), "geometry": (0.0, "")}
    nfail0 = len(fails)
    skipped_any = False

    def snote(kind, val, where):
        if val > sw[kind][0]:
            sw[kind] = (val, where)
        note(kind, val, "%s, %s" % (sname, where))

    for c in cl:
        a, b = c["a"], c["b"]
        cname = "contact %d (%s-%s at %s)" % (c["i"], quote(a), quote(b),
                                               [float("%.6g" % v) for v in c["point"]])
        bad = None
        if b == "ground" or b not in bodies:
            bad = "b is not a body"
        elif a == b:
            bad = "a and b are the same body"
        elif a == "ground" and not S["ground"]:
            bad = "a ground contact but the structure has no ground"
        elif a != "ground" and a not in bodies:
            bad = "unknown body %s" % quote(a)
        else:
            for x in (a, b):
                if x != "ground" and x not in pset:
                    bad = "touches body %s, which an earlier step removed" % quote(x)
        if bad:
            fail("%s: %s: %s" % (sname, cname, bad))
            continue
        n = c["normal"]
        if abs(norm(n) - 1) > 1e-9:
            fail("%s: %s: normal not of unit length (%.17g)" % (sname, cname, norm(n)))
            continue
        key = (a, b, tuple(c["point"]), tuple(n))
        msg, mu, gworst = plausible(S, c, base_tol)
        if msg:
            fail("%s: %s: implausible contact: %s" % (sname, cname, msg))
            continue
        snote("geometry", gworst, cname)
        F = c["force_xyz"]
        fl = c["force"]
        # the two forms of the force must agree
        if S["dim"] == 2:
            t = [-n[1], n[0]]
            rebuilt = add(scale(n, fl[0]), scale(t, fl[1]))
        else:
            t1, t2 = frame3(n)
            rebuilt = add(add(scale(n, fl[0]), scale(t1, fl[1])), scale(t2, fl[2]))
        ws = [bodies[x].mass * norm(S["g"]) for x in (a, b)
              if x != "ground" and not bodies[x].fixed and bodies[x].mass]
        cs = max(norm(F) + (min(ws) if ws else 0.0), 1e-12 * S["wtot"])
        fr = norm(sub(rebuilt, F)) / cs if cs > 0 else 0.0
        snote("frame", fr, cname)
        if fr > tol:
            fail("%s: %s: force %s in the contact frame is not force_xyz %s (%.3g relative)"
                 % (sname, cname, fl, F, fr))
        fn = dot(F, n)
        ft = norm(sub(F, scale(n, fn)))
        nv = max(0.0, -fn) / cs if cs > 0 else 0.0
        cv = cone_distance(fn, ft, mu) / cs if cs > 0 else 0.0
        snote("normal", nv, cname)
        snote("cone", cv, cname)
        if nv > tol:
            fail("%s: %s: negative normal force %.6g (%.3g relative)" % (sname, cname, fn, nv))
        if cv > tol:
            fail("%s: %s: outside the friction cone: |f_t| %.6g > mu %s x f_n %.6g "
                 "(%.3g relative)" % (sname, cname, ft, mu, fn, cv))
        for x, sgn in ((b, 1.0), (a, -1.0)):
            if x == "ground" or bodies[x].fixed:
                continue
            f = scale(F, sgn)
            fsum[x] = add(fsum[x], f)
            fmag[x] += norm(F)
            if bodies[x].cen is None:
                continue
            r = sub(c["point"], bodies[x].cen)
            lever[x] = max(lever[x], norm(r))
            if S["dim"] == 2:
                tsum[x][0] += cross2(r, f)
            else:
                tsum[x] = add(tsum[x], cross3(r, f))
    for x in present:
        body = bodies[x]
        if body.fixed or x in held:
            continue
        if body.skip:
            skipped_any = True
            continue
        W = scale(S["g"], body.mass)
        fs = max(norm(W) + fmag[x], 1e-12 * S["wtot"])
        L = lever[x] if lever[x] > 0 else max(body.diag, 1.0)
        fres = norm(add(fsum[x], W)) / fs if fs > 0 else 0.0
        tres = norm(tsum[x]) / (fs * L) if fs > 0 else 0.0
        snote("force", fres, "body %s" % quote(x))
        snote("torque", tres, "body %s" % quote(x))
        if fres > tol:
            fail("%s: body %s: force residual %.3g (|sum| %.6g, weight %.6g)"
                 % (sname, quote(x), fres, norm(add(fsum[x], W)), norm(W)))
        if tres > tol:
            fail("%s: body %s: torque residual %.3g (|sum| %.6g about its centre of mass)"
                 % (sname, quote(x), tres, norm(tsum[x])))
    if not quiet:
        def at(kind):
            return " (%s)" % sw[kind][1] if sw[kind][1] else ""
        emit("%s %s: %d bodies, %d contacts; force %.2g%s, torque %.2g%s, "
             "cone %.2g, normal %.2g, frame %.2g, geometry %.2g of tol" % (
                 "ok  " if len(fails) == nfail0 else "FAIL", sname, len(present), len(cl),
                 sw["force"][0], at("force"), sw["torque"][0], at("torque"),
                 sw["cone"][0], sw["normal"][0], sw["frame"][0], sw["geometry"][0]))
    return skipped_any


def check_steps(S, P, order, steps, tol, base_tol, quiet, emit):
    bodies = S["bodies"]
    fails, worst, fail, note = tally(emit)

    status = P["status"]
    # what the plan claims
    movable = [i for i in S["order"] if not bodies[i].fixed]
    seen = {}
    norder = []
    for k, e in enumerate(order):
        grp = [e] if isinstance(e, str) else e
        if not isinstance(grp, list) or not grp or not all(isinstance(x, str) for x in grp):
            fail("plan: order[%d]: not a body id or a non-empty array of ids" % k)
            grp = []
        for x in grp:
            if x not in bodies:
                fail("plan: order[%d]: unknown body %s" % (k, quote(x)))
            elif bodies[x].fixed:
                fail("plan: order[%d]: body %s is fixed" % (k, quote(x)))
            elif x in seen:
                fail("plan: order[%d]: body %s removed twice (also order[%d])" % (k, quote(x), seen[x]))
            else:
                seen[x] = k
        norder.append(grp)
    if status == "found":
        missing = [x for x in movable if x not in seen]
        if missing:
            fail("plan: status found but %d movable bodies are never removed (%s%s)" % (
                len(missing), ", ".join(quote(x) for x in missing[:5]),
                ", ..." if len(missing) > 5 else ""))
        if not steps:
            fail("plan: status found but no steps with certificates (plan with --certificates)")
    if steps and len(steps) != len(order):
        fail("plan: %d steps but %d order entries" % (len(steps), len(order)))
    removed = set()
    skipped_any = bool(S["skipped"])
    for b in S["skipped"]:
        emit("SKIP body %s: %s (its mass, equilibrium and contact geometry are not checked)"
             % (quote(b.id), b.skip))
    for k, (rem, cl) in enumerate(steps):
        sname = "step %d (remove %s)" % (k + 1, ", ".join(quote(x) for x in rem))
        if k < len(norder) and sorted(rem) != sorted(norder[k]):
            fail("%s: does not match order[%d]" % (sname, k))
        if cl is None:
            fail("%s: no certificate" % sname)
            removed |= set(rem)
            continue
        present = [i for i in S["order"] if i not in removed]
        if check_step(S, present, set(), cl, sname, tol, base_tol, quiet, emit, fails, fail, note):
            skipped_any = True
        removed |= set(rem)
    return fails, worst, skipped_any


def main(argv):
    args = []
    tol = TOL
    base_tol = None
    quiet = False
    it = iter(argv[1:])
    try:
        for a in it:
            if a == "--tol":
                tol = float(next(it))
            elif a == "--contact-tol":
                base_tol = float(next(it))
            elif a == "--quiet":
                quiet = True
            elif a in ("-h", "--help"):
                print(__doc__)
                return 0
            else:
                args.append(a)
    except (StopIteration, ValueError):
        print("check_plan: bad option value", file=sys.stderr)
        return 2
    if len(args) != 2:
        print("usage: check_plan.py STRUCTURE.json PLAN.json [--tol T] [--contact-tol T] [--quiet]",
              file=sys.stderr)
        return 2
    try:
        S = load_structure(args[0])
        P, order, steps = load_plan(args[1], S)
    except InputError as e:
        print("check_plan: %s" % e, file=sys.stderr)
        return 2

    def emit(line):
        print(line)

    fails, worst, skipped = check(S, P, order, steps, tol, base_tol, quiet, emit)
    nchecked = P["_nrel"] if "_nrel" in P else len(steps)
    print("%s: status %s, %d %s checked, %d bodies (%dD)" % (
        args[1], P["status"], nchecked, "releases" if "_nrel" in P else "steps",
        len(S["bodies"]), S["dim"]))
    for k in ("force", "torque", "cone", "normal", "frame", "geometry"):
        v, w = worst[k]
        unit_ = " of tolerance" if k == "geometry" else " relative"
        print("  worst %-8s %.3g%s%s" % (k, v, unit_, (" at " + w) if w else ""))
    if P["status"] != "found" and not steps and "_nrel" not in P:
        print("  (status %s: no steps to check; only the order was checked)" % P["status"])
    if fails:
        print("FAILED: %d problems; first: %s" % (len(fails), fails[0]))
        return 1
    if skipped:
        print("INCOMPLETE: some bodies were skipped (see SKIP lines); nothing failed")
        return 3
    print("PASSED (tolerance %g)" % tol)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
