#!/usr/bin/python3
"""Independent check of a `faultmesh remesh` (or `faultmesh demo`) output
folder against the mesh issue's acceptance criteria.

usage: check_remesh.py [options] DIR

Everything is recomputed from the output files; report.json is only
cross-checked against the recomputation (a disagreement is a failure).

Always checked (structure, readers):
  - meshio reads DIR/mesh.vtu, mesh.msh, mesh.stl and mesh.obj; every
    format holds the same triangles (as sets of corners per fault: exact
    for VTU, MSH, OBJ, the float32 rounding of them for STL), the same
    number per fault, and the fault names agree (VTU field data
    fault_names, MSH physical names, OBJ groups, TSurf HEADER names);
  - Gmsh opens mesh.msh: one physical surface per fault, named after it,
    holding that fault's triangles; the MSH version is the expected one
    (--msh-version);
  - one NAME.ts per fault in DIR with that fault's triangles;
  - report.json agrees with what the files give: faults, triangles,
    nodes, area, triangles under 30 and 20 degrees, forced ones, edges and
    edges in band, z max, and with --original the node distances.
Measured per fault and over all faults (3D, from the VTU):
  - min-angle-30  share of triangles whose smallest angle is >= 30 deg
                  (>= 99.5 %, over all triangles);
  - angle-20      triangles under 20 deg sit at a boundary corner whose
                  interior angle (sum of the triangle angles there) is
                  under 40 deg, or at a node shared with another fault (a
                  junction curve, fixed as planned: at most 0.1 % of all
                  triangles), or with another sheet of its fault (the
                  VTU's cell data "sheet", when there is one: the curve
                  where a branching fault's parts are joined);
  - edge-band     share of edges (each once per fault) within
                  [0.7 H, 1.4 H] (>= 95 %);
  - boundary-edge every boundary edge of a fault (an edge of one of its
                  triangles) at most 2 H: refinement splits every boundary
                  piece it knows the curve of, so a longer one is an
                  outline stretch the domain lost (a chord across the
                  fault);
  - failures      report.json lists no failed fault and, with --original,
                  every object of the inputs that reaches below sea level
                  (or any, with --top keep) is in the mesh, unless the
                  report gives it up as a near-duplicate ("dropped");
  - distance-max, distance-rms  (--original) every node within 100 m of the
                  original triangulation inside its outline, RMS <= 10 m
                  per fault (gap closers excepted). A node more than
                  100 m off is past the original's edge when its nearest
                  point on the original lies within 100 m of the
                  original's outline (its edges used by one triangle,
                  seams of sheets whose ends lie within 1 m of another's
                  welded), measured here from the .ts files; else it is
                  inside, and fails. Past the edge, a node lies in a
                  closed gap when a node the fault shares with a fault it
                  closes a gap to (a made junction with gap_closed_m in
                  report.json: the curve it was extended to) is within
                  the node's own distance to the original + H, or the node
                  lies between the original's edge and that curve (its
                  distances to the two add up to at most that junction's
                  gap_closed_m + H: the inner rows of a fill); there it
                  may reach 100 m + the fault's largest closed gap, or as
                  far as report.json's fidelity beyond_outline_max_m says
                  the fill past its edge reaches (which must agree with
                  the checker's own figure within 1 m). Past the edge
                  anywhere else (an outline bulging out far from any such
                  curve) it is held to 100 m;
  - top           (--top cut / extend) every node z <= 0; boundary nodes
                  less than --level-tol (1 m) below sea level are on it
                  exactly (no top edge a hair below), and every fault whose original
                  crosses sea level has a top edge on z = 0 (its length is
                  printed); (--top keep) every fault whose original rises
                  above sea level still does;
  - coverage      (--original) nothing of the fault lost: the mesh's extent /
                  the original's (below sea level when cut) >= --min-coverage
                  (default 0.97) per fault, extent being area projected on the
                  original's best-fit plane. The 3D area ratio is printed too:
                  it also counts relief finer than H, which no mesh at H can
                  have (a wrinkled original can have 7 % more area than any
                  smooth surface over the same extent). A fault whose
                  overshoot past a junction was trimmed (report.json) is
                  excepted, as is one the report says stops short of
                  another (an unjoined junction's "stops_short"). A fault
                  that gave way where it ran through another (report.json's
                  "carved_area_m2") is allowed that area on top of the
                  mesh's, as a share of the original's, and no more.
--criteria LIST (comma-separated names above, or "all") asserts those;
the others are printed only. Without --original the distance and
coverage figures are not measured.

Options: --size H (default: options.size_m of report.json, cross-checked),
--top cut|keep|extend (the mode used; default cut), --msh-version 4.1|2.2
(expected; default: either), --original PATH... (input .ts files or
folders, searched recursively), --sample N (every N-th node for the
distances), --min-coverage F, --level-tol M, --verbose (a line per fault;
otherwise only faults outside a criterion), --no-gmsh.

Distances: per fault, a uniform 3D grid over the original triangles (each
listed in the cells its box grown by 150 m touches) finds the exact nearest
triangle of every node within 150 m; nodes farther away are measured
against all the fault's triangles. The whole CFM 500 m set (1.8 M
triangles) against 250 k nodes takes about 15 s.

Exit 0 when everything asserted holds, 1 otherwise, 77 when meshio, Gmsh
or numpy is missing (Debian python3-meshio, python3-gmsh) or DIR / an
original is absent.
"""
import argparse
import json
import math
import os
import sys
import time

try:
    import numpy as np
    import meshio
except ImportError as e:
    print("%s: skipped" % e)
    sys.exit(77)

ALL_CRITERIA = ["failures", "min-angle-30", "angle-20", "edge-band", "boundary-edge",
                "distance-max", "distance-rms", "top", "coverage"]
MSH_NAME_MAX = 200

failures = []


def fail(what):
    print("FAIL  " + what)
    failures.append(what)


def check(cond, what, quiet_ok=False):
    if cond:
        if not quiet_ok:
            print("ok    " + what)
    else:
        fail(what)
    return cond


# ---------------------------------------------------------------- TSurf

def read_tsurf(path):
    """[(name, points (n, 3), triangles (m, 3) 0-based)] of every object in
    a GoCAD TSurf file: VRTX / PVRTX / ATOM / PATOM / TRGL, HEADER name,
    ZPOSITIVE Depth (z negated to elevation)."""
    with open(path, "rb") as fh:
        text = fh.read().decode("utf-8", "replace")
    objects = []
    cur = None

    def finish():
        if cur is None:
            return
        ids = np.array(cur["ids"], dtype=np.int64)
        xyz = np.array(cur["xyz"], dtype=float).reshape(-1, 3)
        if cur["depth"]:
            xyz[:, 2] = -xyz[:, 2]
        order = np.argsort(ids, kind="stable")
        sids = ids[order]
        tri = np.array(cur["trgl"], dtype=np.int64).reshape(-1, 3)
        if len(tri):
            pos = np.searchsorted(sids, tri)
            pos = np.minimum(pos, len(sids) - 1)
            if not np.all(sids[pos] == tri):
                raise ValueError("%s: TRGL names an unknown vertex" % path)
            tri = order[pos]
        objects.append((cur["name"] or os.path.basename(path), xyz, tri))

    in_header = False
    for raw in text.splitlines():
        line = raw.strip()
        if not line:
            continue
        if line.startswith("GOCAD ") and "TSurf" in line:
            finish()
            cur = {"name": "", "ids": [], "xyz": [], "trgl": [], "depth": False, "atoms": []}
            continue
        if cur is None:
            continue
        if in_header:
            body = line
            if body.endswith("}"):
                in_header = False
                body = body[:-1]
            if body.startswith("name:"):
                cur["name"] = body[5:].strip()
            continue
        if line.startswith("HEADER"):
            rest = line[6:].strip()
            if rest.startswith("{"):
                rest = rest[1:].strip()
                if rest.endswith("}"):
                    rest = rest[:-1].strip()
                else:
                    in_header = True
                if rest.startswith("name:"):
                    cur["name"] = rest[5:].strip()
            continue
        tok = line.split()
        key = tok[0]
        if key in ("VRTX", "PVRTX"):
            cur["ids"].append(int(tok[1]))
            cur["xyz"] += [float(tok[2]), float(tok[3]), float(tok[4])]
        elif key in ("ATOM", "PATOM"):
            # an atom is a new id for an existing vertex's position
            ref = int(tok[2])
            try:
                k = cur["ids"].index(ref)
            except ValueError:
                raise ValueError("%s: ATOM refers to unknown vertex %d" % (path, ref))
            cur["ids"].append(int(tok[1]))
            cur["xyz"] += cur["xyz"][3 * k:3 * k + 3]
        elif key == "TRGL":
            cur["trgl"] += [int(tok[1]), int(tok[2]), int(tok[3])]
        elif key == "ZPOSITIVE":
            cur["depth"] = tok[1].lower() == "depth"
        elif key == "END":
            finish()
            cur = None
    finish()
    return objects


def ts_files(paths):
    out = []
    for p in paths:
        if os.path.isdir(p):
            for root, dirs, files in os.walk(p):
                dirs.sort()
                out += [os.path.join(root, f) for f in sorted(files) if f.endswith(".ts")]
        else:
            out.append(p)
    return out


# ---------------------------------------------------------------- geometry

def tri_corners(points, cells):
    return np.asarray(points, dtype=float)[np.asarray(cells)]


def corner_angles(P):
    """Angles (degrees) at the three corners of triangles P (m, 3, 3)."""
    ang = np.empty(P.shape[:2])
    for k in range(3):
        a, b, c = P[:, k], P[:, (k + 1) % 3], P[:, (k + 2) % 3]
        u, v = b - a, c - a
        cr = np.linalg.norm(np.cross(u, v), axis=1)
        ang[:, k] = np.degrees(np.arctan2(cr, np.einsum("ij,ij->i", u, v)))
    return ang


def tri_areas(P):
    return 0.5 * np.linalg.norm(np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]), axis=1)


def area_below(P, level=0.0):
    """Area of each triangle's part with z <= level (clipped polygon)."""
    z = P[:, :, 2] - level
    out = np.zeros(len(P))
    full = np.all(z <= 0, axis=1)
    out[full] = tri_areas(P[full])
    part = ~full & np.any(z < 0, axis=1)
    for t in np.nonzero(part)[0]:
        poly = []
        for i in range(3):
            u, v = P[t, i], P[t, (i + 1) % 3]
            du, dv = z[t, i], z[t, (i + 1) % 3]
            if du <= 0:
                poly.append(u)
            if (du < 0 < dv) or (dv < 0 < du):
                poly.append(u + du / (du - dv) * (v - u))
        for i in range(1, len(poly) - 1):
            out[t] += 0.5 * np.linalg.norm(np.cross(poly[i] - poly[0], poly[i + 1] - poly[0]))
    return out


def normals(P):
    """Unit normals of triangles P (k, 3, 3); zero for degenerate ones."""
    n = np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0])
    ln = np.linalg.norm(n, axis=1)
    return n / np.where(ln > 0, ln, 1.0)[:, None]


def plane_normal(P, w):
    """Normal of the best-fit plane of triangles P, weighted by w (area)."""
    c = P.mean(axis=1)
    ws = w.sum()
    if not ws > 0:
        return np.array([0.0, 0.0, 1.0])
    m = (c * w[:, None]).sum(0) / ws
    d = (c - m) * np.sqrt(w)[:, None]
    return np.linalg.svd(d, full_matrices=False)[2][2]


def point_triangle_d2(p, a, b, c):
    """Squared distance from points p to triangles (a, b, c), all (k, 3)."""
    e0, e1, w = b - a, c - a, p - a
    d00 = np.einsum("ij,ij->i", e0, e0)
    d01 = np.einsum("ij,ij->i", e0, e1)
    d11 = np.einsum("ij,ij->i", e1, e1)
    d20 = np.einsum("ij,ij->i", w, e0)
    d21 = np.einsum("ij,ij->i", w, e1)
    den = d00 * d11 - d01 * d01
    ok = den > 1e-12 * np.maximum(d00 * d11, 1e-300)
    sden = np.where(ok, den, 1.0)
    v = (d11 * d20 - d01 * d21) / sden
    t = (d00 * d21 - d01 * d20) / sden
    inside = ok & (v >= 0) & (t >= 0) & (v + t <= 1)
    n = np.cross(e0, e1)
    nn = np.einsum("ij,ij->i", n, n)
    h = np.einsum("ij,ij->i", w, n)
    best = np.where(inside, h * h / np.where(inside, nn, 1.0), np.inf)

    def seg(q, s0, s1):
        d = s1 - s0
        dd = np.einsum("ij,ij->i", d, d)
        f = np.clip(np.einsum("ij,ij->i", q - s0, d) / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
        r = q - s0 - f[:, None] * d
        return np.einsum("ij,ij->i", r, r)

    best = np.minimum(best, seg(p, a, b))
    best = np.minimum(best, seg(p, b, c))
    best = np.minimum(best, seg(p, c, a))
    return best


def distances(nodes, T, radius=150.0, chunk=3_000_000):
    """Distance of every node to the nearest of triangles T (m, 3, 3).

    A uniform 3D grid: each triangle is listed in every cell its bounding
    box grown by `radius` touches, so a node whose nearest triangle is
    within `radius` finds it among the triangles of its own cell (exact);
    nodes that find nothing that near are measured against all triangles."""
    n = len(nodes)
    if n == 0:
        return np.zeros(0)
    if len(T) == 0:
        return np.full(n, np.inf)
    origin = nodes.mean(axis=0)
    X = nodes - origin
    T = T - origin
    edge = np.median(np.linalg.norm(T[:, 1] - T[:, 0], axis=1))
    cell = max(1.5 * edge, 2.0 * radius, 1.0)
    tlo, thi = T.min(axis=1) - radius, T.max(axis=1) + radius
    g0 = tlo.min(axis=0)
    lo = np.floor((tlo - g0) / cell).astype(np.int64)
    hi = np.floor((thi - g0) / cell).astype(np.int64)
    G = hi.max(axis=0) + 1
    span = hi - lo + 1
    cnt = span.prod(axis=1)
    tid = np.repeat(np.arange(len(T)), cnt)
    k = np.arange(cnt.sum()) - np.repeat(np.cumsum(cnt) - cnt, cnt)
    sx, sy = span[tid, 0], span[tid, 1]
    ix = lo[tid, 0] + k % sx
    iy = lo[tid, 1] + (k // sx) % sy
    iz = lo[tid, 2] + k // (sx * sy)
    key = ix + G[0] * (iy + G[1] * iz)
    order = np.argsort(key, kind="stable")
    key, tid = key[order], tid[order]
    c = np.floor((X - g0) / cell).astype(np.int64)
    inside = np.all((c >= 0) & (c < G), axis=1)
    nkey = np.where(inside, c[:, 0] + G[0] * (c[:, 1] + G[1] * c[:, 2]), -1)
    start = np.searchsorted(key, nkey, "left")
    ncand = np.where(inside, np.searchsorted(key, nkey, "right") - start, 0)
    best = np.full(n, np.inf)
    csum = np.cumsum(ncand)
    i0 = 0
    while i0 < n:
        base = csum[i0 - 1] if i0 else 0
        i1 = int(np.searchsorted(csum, base + chunk, "right"))
        i1 = max(i1, i0 + 1)
        i1 = min(i1, n)
        cc = ncand[i0:i1]
        tot = int(cc.sum())
        if tot:
            node = np.repeat(np.arange(i0, i1), cc)
            off = np.arange(tot) - np.repeat(np.cumsum(cc) - cc, cc)
            tri = tid[np.repeat(start[i0:i1], cc) + off]
            d2 = point_triangle_d2(X[node], T[tri, 0], T[tri, 1], T[tri, 2])
            has = np.nonzero(cc)[0]
            seg_start = (np.cumsum(cc) - cc)[has]
            best[i0 + has] = np.minimum.reduceat(d2, seg_start)
        i0 = i1
    far = np.nonzero(~(best <= radius * radius))[0]
    for f0 in range(0, len(far), 64):
        ids = far[f0:f0 + 64]
        for i in ids:
            m = len(T)
            d2 = point_triangle_d2(np.broadcast_to(X[i], (m, 3)), T[:, 0], T[:, 1], T[:, 2])
            best[i] = d2.min()
    return np.sqrt(best)


def point_triangle_foot(p, a, b, c):
    """Closest point of each triangle (a[i], b[i], c[i]) to p[i]."""
    ab, ac = b - a, c - a
    n = np.cross(ab, ac)
    nn = np.einsum("ij,ij->i", n, n)
    q = p - (np.einsum("ij,ij->i", p - a, n) / np.where(nn > 0, nn, 1.0))[:, None] * n
    d00, d01, d11 = (np.einsum("ij,ij->i", ab, ab), np.einsum("ij,ij->i", ab, ac),
                     np.einsum("ij,ij->i", ac, ac))
    d20, d21 = np.einsum("ij,ij->i", q - a, ab), np.einsum("ij,ij->i", q - a, ac)
    den = d00 * d11 - d01 * d01
    v = (d11 * d20 - d01 * d21) / np.where(den > 0, den, 1.0)
    w = (d00 * d21 - d01 * d20) / np.where(den > 0, den, 1.0)
    inside = (nn > 0) & (den > 0) & (v >= 0) & (w >= 0) & (v + w <= 1)
    best, bd = q.copy(), np.where(inside, 0.0, np.inf)
    for s0, s1 in ((a, b), (b, c), (c, a)):
        d = s1 - s0
        dd = np.einsum("ij,ij->i", d, d)
        f = np.clip(np.einsum("ij,ij->i", p - s0, d) / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
        r = s0 + f[:, None] * d
        rd = np.einsum("ij,ij->i", p - r, p - r)
        take = ~inside & (rd < bd)
        best[take], bd[take] = r[take], rd[take]
    return best


def outline_segments(T, weld=1.0):
    """The outline of triangles T (m, 3, 3): their edges used by one
    triangle only, vertices told apart by position (an ATOM repeats a
    vertex's position under another id), as (k, 2, 3) end points."""
    V, inv = np.unique(T.reshape(-1, 3), axis=0, return_inverse=True)
    inv = inv.reshape(-1, 3)
    e = np.sort(np.concatenate([inv[:, [0, 1]], inv[:, [1, 2]], inv[:, [2, 0]]]), axis=1)
    u, c = np.unique(e, axis=0, return_counts=True)
    b = u[c == 1]
    S = np.stack([V[b[:, 0]], V[b[:, 1]]], axis=1)
    # A seam is no outline: two sheets side by side whose vertices along
    # the join are a few millimetres apart (Big Bear rupture) each use
    # the edges there once. An edge whose ends lie within `weld` of those
    # of another such edge is dropped.
    if len(S) > 1:
        def near(P, Q):
            return np.linalg.norm(P[:, None, :] - Q[None, :, :], axis=2) <= weld
        same = (near(S[:, 0], S[:, 0]) & near(S[:, 1], S[:, 1])) | \
            (near(S[:, 0], S[:, 1]) & near(S[:, 1], S[:, 0]))
        np.fill_diagonal(same, False)
        S = S[~same.any(axis=1)]
    return S


def beyond_outline(nodes, T, S, tol):
    """For each of nodes (a few, each farther than tol from T): whether its
    nearest point on T lies within tol of T's outline S, i.e. the node is
    past the original's edge rather than over its inside. Brute force."""
    out = np.zeros(len(nodes), dtype=bool)
    for k, p in enumerate(nodes):
        P = np.broadcast_to(p, (len(T), 3))
        j = int(np.argmin(point_triangle_d2(P, T[:, 0], T[:, 1], T[:, 2])))
        foot = point_triangle_foot(p[None], T[j:j + 1, 0], T[j:j + 1, 1], T[j:j + 1, 2])[0]
        if len(S):
            d = S[:, 1] - S[:, 0]
            dd = np.einsum("ij,ij->i", d, d)
            f = np.clip(np.einsum("ij,ij->i", foot - S[:, 0], d) / np.where(dd > 0, dd, 1.0), 0, 1)
            r = foot - S[:, 0] - f[:, None] * d
            out[k] = np.sqrt(np.einsum("ij,ij->i", r, r).min()) <= tol
    return out


# ---------------------------------------------------------------- readers

def triangles_of(m, what):
    blocks = [i for i, c in enumerate(m.cells) if c.type == "triangle"]
    # MSH carries the faults' outline and junction curves as lines
    others = sorted({c.type for c in m.cells
                     if c.type != "triangle" and not (c.type == "line" and what.endswith(".msh"))})
    check(not others, "%s: only triangles%s" % (what, " (also %s)" % others if others else ""))
    if not blocks:
        return np.zeros((0, 3), dtype=np.int64), {}
    cells = np.concatenate([m.cells[i].data for i in blocks]).astype(np.int64)
    data = {k: np.concatenate([np.asarray(v[i]) for i in blocks]) for k, v in m.cell_data.items()}
    return cells, data


def field_strings(field):
    raw = bytes(np.asarray(field, dtype=np.uint8).ravel())
    return [s.decode("utf-8", "replace") for s in raw.split(b"\0")[:-1]]


def msh_name(name):
    s = name.replace('"', "'").replace("\\", "/").encode()
    if len(s) > MSH_NAME_MAX:
        s = s[:MSH_NAME_MAX]
        while s and (s[-1] & 0xC0) == 0x80:
            s = s[:-1]
        if s and s[-1] >= 0xC0:
            s = s[:-1]
    return s.decode()


def canon(C, fault):
    """Triangles as a sorted (m, 10) array: fault, then the 9 coordinates."""
    A = np.concatenate([np.asarray(fault, dtype=float)[:, None], C.reshape(len(C), 9)], axis=1)
    order = np.lexsort(A.T[::-1])
    return A[order]


def msh_version(path):
    with open(path, "rb") as fh:
        head = fh.read(200).decode("ascii", "replace").split()
    return head[1] if len(head) > 1 and head[0] == "$MeshFormat" else "?"


# ---------------------------------------------------------------- main

def main():
    np.seterr(divide="ignore", invalid="ignore")
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dir")
    ap.add_argument("--size", type=float)
    ap.add_argument("--top", choices=["cut", "keep", "extend"], default="cut")
    ap.add_argument("--msh-version", choices=["4.1", "2.2"])
    ap.add_argument("--original", nargs="+", default=[])
    ap.add_argument("--sample", type=int, default=1)
    ap.add_argument("--min-coverage", type=float, default=0.97)
    ap.add_argument("--level-tol", type=float, default=1.0)
    ap.add_argument("--criteria", default="")
    ap.add_argument("--verbose", action="store_true")
    ap.add_argument("--no-gmsh", action="store_true")
    a = ap.parse_args()
    crit = set()
    for c in a.criteria.split(","):
        c = c.strip()
        if c == "all":
            crit |= set(ALL_CRITERIA)
        elif c:
            if c not in ALL_CRITERIA:
                ap.error("unknown criterion %r (known: %s, all)" % (c, ", ".join(ALL_CRITERIA)))
            crit.add(c)
    gmsh = None
    if not a.no_gmsh:
        try:
            import gmsh
        except ImportError as e:
            print("%s: skipped" % e)
            return 77
    out = a.dir
    for p in [out] + a.original:
        if not os.path.exists(p):
            print("skipped: %s does not exist" % p)
            return 77
    t_start = time.time()

    with open(os.path.join(out, "report.json")) as fh:
        report = json.load(fh)
    rfaults = report["faults"]
    rok = [f for f in rfaults if f.get("status") == "ok"]
    H = a.size if a.size else report["options"]["size_m"]
    check(report["options"]["size_m"] == H, "report size_m %g = H %g" % (report["options"]["size_m"], H))
    check(report["options"]["top"] == a.top, "report top mode %r" % report["options"]["top"])

    # --- VTU: the reference for everything measured
    print("-- meshio mesh.vtu")
    vtu = meshio.read(os.path.join(out, "mesh.vtu"))
    X = np.asarray(vtu.points, dtype=float)
    tris, cdata = triangles_of(vtu, "mesh.vtu")
    # fault_id is the fault number, from 1; fid the index
    fid = np.asarray(cdata.get("fault_id", np.full(len(tris), 0)), dtype=np.int64) - 1
    names = field_strings(vtu.field_data.get("fault_names", []))
    nf = len(names)
    check("fault_id" in cdata, "mesh.vtu: cell data fault_id")
    check(len(fid) == 0 or (fid.min() >= 0 and fid.max() < nf),
          "mesh.vtu: fault_id within 1..%d" % nf)
    check(len(tris) == 0 or (tris.min() >= 0 and tris.max() < len(X)),
          "mesh.vtu: connectivity within %d points" % len(X))
    check(np.all(np.isfinite(X)), "mesh.vtu: finite coordinates")
    check([f["name"] for f in rok] == names,
          "%d faults in fault_names, in report order" % nf)
    per_fault = np.bincount(fid, minlength=nf) if nf else np.zeros(0, dtype=np.int64)
    check(np.all(per_fault > 0), "every fault has triangles")
    C = tri_corners(X, tris)
    ref = canon(C, fid)
    print("   %d triangles, %d points, %d faults" % (len(tris), len(X), nf))

    # --- MSH with meshio
    mpath = os.path.join(out, "mesh.msh")
    ver = msh_version(mpath)
    print("-- meshio mesh.msh (version %s)" % ver)
    if a.msh_version:
        check(ver == a.msh_version, "mesh.msh is MSH %s (%s)" % (a.msh_version, ver))
    msh = meshio.read(mpath)
    mt, md = triangles_of(msh, "mesh.msh")
    phys = np.asarray(md.get("gmsh:physical", np.full(len(mt), -1)), dtype=np.int64)
    pnames = {int(v[0]): k for k, v in msh.field_data.items() if int(v[1]) == 2}
    want = {msh_name(n): i for i, n in enumerate(names)}
    check(sorted(pnames.values()) == sorted(want),
          "mesh.msh: physical surface names = fault names")
    tag2fault = {t: want.get(n, -1) for t, n in pnames.items()}
    mf = np.array([tag2fault.get(int(p), -1) for p in phys], dtype=np.int64)
    check(len(mt) == len(tris), "mesh.msh: %d triangles (VTU %d)" % (len(mt), len(tris)))
    check(len(mt) == len(tris) and np.array_equal(canon(tri_corners(msh.points, mt), mf), ref),
          "mesh.msh: the same triangles, corners bit for bit, per fault")

    # --- STL, OBJ
    print("-- meshio mesh.stl, mesh.obj")
    stl = meshio.read(os.path.join(out, "mesh.stl"))
    st, _ = triangles_of(stl, "mesh.stl")
    check(len(st) == len(tris), "mesh.stl: %d triangles" % len(st))
    if len(st) == len(tris):
        S = tri_corners(stl.points, st).astype(np.float32)
        same = np.array_equal(canon(S.astype(float), np.zeros(len(S))),
                              canon(C.astype(np.float32).astype(float), np.zeros(len(C))))
        rounding = np.abs(C.astype(np.float32).astype(float) - C).max() if len(C) else 0.0
        check(same, "mesh.stl: the same triangles to float32 (rounding up to %.3f m)" % rounding)
    obj = meshio.read(os.path.join(out, "mesh.obj"))
    ot, od = triangles_of(obj, "mesh.obj")
    og = np.asarray(od.get("obj:group_ids", np.full(len(ot), -1)), dtype=np.int64)
    check(len(ot) == len(tris), "mesh.obj: %d triangles" % len(ot))
    check(len(ot) == len(tris) and np.array_equal(canon(tri_corners(obj.points, ot), og), ref),
          "mesh.obj: the same triangles bit for bit, group = fault")
    with open(os.path.join(out, "mesh.obj"), encoding="utf-8") as fh:
        gnames = [ln[2:].rstrip("\n") for ln in fh if ln.startswith("g ")]
    objname = [n.replace(" ", "_").replace("\t", "_").replace("#", "_") for n in names]
    check(gnames == objname, "mesh.obj: g names = fault names")

    # --- one TSurf per fault
    print("-- TSurf per fault")
    tsd = {}
    for f in sorted(os.listdir(out)):
        if f.endswith(".ts"):
            for name, p, t in read_tsurf(os.path.join(out, f)):
                tsd.setdefault(name, []).append((f, len(t), p, t))
    check(sorted(tsd) == sorted(names) and all(len(v) == 1 for v in tsd.values()),
          "%d .ts files, one per fault, named inside by HEADER name" % len(tsd))
    bad = [n for i, n in enumerate(names) if n in tsd and tsd[n][0][1] != per_fault[i]]
    check(not bad, "every .ts has its fault's triangles%s" % (" (not: %s)" % bad[:5] if bad else ""))
    badc = []
    for i, n in enumerate(names):
        if n in tsd and tsd[n][0][1] == per_fault[i]:
            _, _, p, t = tsd[n][0]
            if not np.array_equal(canon(tri_corners(p, t), np.zeros(len(t))),
                                  canon(C[fid == i], np.zeros(per_fault[i]))):
                badc.append(n)
    check(not badc, "every .ts has its fault's corners bit for bit%s"
          % (" (not: %s)" % badc[:5] if badc else ""))

    # --- Gmsh
    if gmsh is not None:
        print("-- gmsh mesh.msh")
        gmsh.initialize(["check_remesh"])
        gmsh.option.setNumber("General.Terminal", 0)
        try:
            gmsh.open(mpath)
            groups = gmsh.model.getPhysicalGroups(2)
            gnames = {}
            gcount = {}
            for dim, tag in groups:
                nm = gmsh.model.getPhysicalName(dim, tag)
                gnames[tag] = nm
                n = 0
                for e in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
                    et, etags, _ = gmsh.model.mesh.getElements(2, e)
                    for ty, tg in zip(et, etags):
                        n += len(tg) if ty == 2 else 0
                        if ty != 2:
                            fail("gmsh: group %d holds elements of type %d" % (tag, ty))
                gcount[nm] = n
            check(sorted(gnames.values()) == sorted(want),
                  "gmsh: %d physical surfaces named after the faults" % len(groups))
            badg = [n for i, n in enumerate(names) if gcount.get(msh_name(n)) != per_fault[i]]
            check(not badg, "gmsh: every group holds its fault's triangles%s"
                  % (" (not: %s)" % badg[:5] if badg else ""))
            ntag, _, _ = gmsh.model.mesh.getNodes()
            check(len(ntag) == len(np.unique(tris)),
                  "gmsh: %d nodes = vertices used by triangles" % len(ntag))
        finally:
            gmsh.finalize()

    # --- quality, per fault (edges and corners are a fault's own)
    print("-- quality and size (H = %g m)" % H)
    ang = corner_angles(C) if len(C) else np.zeros((0, 3))
    minang = ang.min(axis=1) if len(C) else np.zeros(0)
    amin_at = np.argmin(ang, axis=1) if len(C) else np.zeros(0, dtype=np.int64)
    nv = len(X)
    # (fault, vertex) keys: a node shared by two faults is a corner of each
    fv = fid[:, None] * nv + tris
    e_a = np.concatenate([tris[:, 0], tris[:, 1], tris[:, 2]])
    e_b = np.concatenate([tris[:, 1], tris[:, 2], tris[:, 0]])
    e_f = np.tile(fid, 3)
    emin, emax = np.minimum(e_a, e_b), np.maximum(e_a, e_b)
    ekey = (e_f * nv + emin) * nv + emax
    uk, ecount = np.unique(ekey, return_counts=True)
    ef = uk // (nv * nv)
    eu, ev = (uk // nv) % nv, uk % nv
    elen = np.linalg.norm(X[eu] - X[ev], axis=1)
    inband = (elen >= 0.7 * H) & (elen <= 1.4 * H)
    bnd = ecount == 1
    bkey = np.unique(np.concatenate([ef[bnd] * nv + eu[bnd], ef[bnd] * nv + ev[bnd]]))
    akey, ainv = np.unique(fv.ravel(), return_inverse=True)
    asum = np.bincount(ainv, weights=ang.ravel())
    is_b = np.isin(akey, bkey)
    sharp_keys = akey[is_b & (asum < 40.0)]
    corner_key = fv[np.arange(len(fv)), amin_at] if len(fv) else np.zeros(0, dtype=np.int64)
    below30 = minang < 30.0
    below20 = minang < 20.0
    forced = below20 & np.isin(corner_key, sharp_keys)
    sharp_f = np.bincount(sharp_keys // nv, minlength=nf)
    # Nodes of more than one fault lie on junction curves, which stay as
    # the plan sampled them: triangles there are counted apart (issue 5
    # allows at most 0.1 % of all triangles).
    vf = np.unique(np.stack([tris.ravel(), np.repeat(fid, 3)], axis=1), axis=0) if len(tris) else np.zeros((0, 2), np.int64)
    shared_v = np.zeros(nv, dtype=bool)
    if len(vf):
        vcount = np.bincount(vf[:, 0], minlength=nv)
        shared_v = vcount > 1
    # ... and so do nodes of an edge of more than two triangles of one
    # fault: the curve where a branching fault's sheets meet (a T or a
    # crossing of two sheets), joined as two faults are
    nm = ecount > 2
    shared_v[eu[nm]] = True
    shared_v[ev[nm]] = True
    # ... and nodes of two sheets of one fault, where the sheets end at
    # their curve (a corner): its edges are then used twice, as any
    if "sheet" in cdata and len(tris):
        sheet = np.asarray(cdata["sheet"], dtype=np.int64)
        part = fid * (sheet.max() + 1) + sheet
        vp = np.unique(np.stack([tris.ravel(), np.repeat(part, 3)], axis=1), axis=0)
        shared_v |= np.bincount(vp[:, 0], minlength=nv) > 1
    at_junction = below20 & ~forced & (shared_v[tris].any(axis=1) if len(tris) else np.zeros(0, bool))
    # sea level: boundary nodes
    bnode = np.unique(np.concatenate([eu[bnd], ev[bnd]]))
    top_e = bnd & (X[eu, 2] == 0.0) & (X[ev, 2] == 0.0)
    near = bnode[(X[bnode, 2] > -a.level_tol) & (X[bnode, 2] != 0.0)]
    near_nm = int(np.sum((X[bnode, 2] > -1e-6) & (X[bnode, 2] < 0.0)))
    area = tri_areas(C)

    def fsum(mask, w=None, over=fid):
        return np.bincount(over[mask], weights=None if w is None else w[mask], minlength=nf)

    F = {
        "triangles": per_fault,
        "below_30": fsum(below30), "below_20": fsum(below20), "forced": fsum(forced),
        "edges": np.bincount(ef, minlength=nf), "band": fsum(inband, over=ef),
        "area": np.bincount(fid, weights=area, minlength=nf),
        "top_edges": fsum(top_e, over=ef), "top_len": fsum(top_e, elen, over=ef),
        "sharp": sharp_f,
    }
    F["bmax"] = np.zeros(nf)
    np.maximum.at(F["bmax"], ef[bnd], elen[bnd])
    F["min_angle"] = np.full(nf, np.inf)
    np.minimum.at(F["min_angle"], fid, minang)
    F["zmax"] = np.full(nf, -np.inf)
    np.maximum.at(F["zmax"], np.repeat(fid, 3), C[:, :, 2].ravel())
    fnode = np.unique(fv.ravel())
    F["nodes"] = np.bincount(fnode // nv, minlength=nf)
    F["near_miss"] = np.zeros(nf, dtype=np.int64)
    if len(near):
        nk = fnode[np.isin(fnode % nv, near)]
        F["near_miss"] = np.bincount(nk // nv, minlength=nf)

    # --- originals: distances, presence, coverage
    orig = {}
    F["rms"] = np.full(nf, np.nan)
    F["dmax"] = np.full(nf, np.nan)
    F["dmax_in"] = np.full(nf, np.nan)
    F["dmax_out"] = np.full(nf, np.nan)
    F["dmax_gap"] = np.full(nf, np.nan)
    F["dmax_stray"] = np.full(nf, np.nan)
    F["orig_area"] = np.full(nf, np.nan)
    F["extent"] = np.full(nf, np.nan)
    F["orig_extent"] = np.full(nf, np.nan)
    F["orig_zmax"] = np.full(nf, np.nan)
    if a.original:
        t0 = time.time()
        files = ts_files(a.original)
        for path in files:
            for name, p, t in read_tsurf(path):
                if len(t):
                    orig.setdefault(name, []).append(tri_corners(p, t))
        orig = {k: np.concatenate(v) for k, v in orig.items()}
        print("-- distances to the originals (%d objects in %d files, read in %.1f s)"
              % (len(orig), len(files), time.time() - t0))
        t0 = time.time()
        nsampled = 0
        # per fault, the nodes it shares with the faults it closes a gap to
        # (the curves of those junctions; report.json names the junctions)
        fnodes = {n: np.unique(tris[fid == k]) for k, n in enumerate(names)}
        if "sheet" in cdata and len(tris):
            sh_ = np.asarray(cdata["sheet"], dtype=np.int64)
            nsheets = np.array([len(np.unique(sh_[fid == k])) for k in range(nf)])
        else:
            nsheets = np.ones(nf, dtype=np.int64)
        curve_nodes, curve_gaps = {}, {}
        for jn in report.get("connect", {}).get("junctions", []):
            if jn.get("type") == "unjoined" or not jn.get("gap_closed_m", 0) > 0:
                continue
            f0, f1 = jn["faults"]
            if f0 in fnodes and f1 in fnodes:
                sh = np.intersect1d(fnodes[f0], fnodes[f1])
                for f in (f0, f1):
                    curve_nodes[f] = np.union1d(curve_nodes.get(f, np.zeros(0, np.int64)), sh)
                    if len(sh):
                        curve_gaps.setdefault(f, []).append((sh, float(jn["gap_closed_m"])))
        for i, n in enumerate(names):
            if n not in orig:
                fail("fault %s: no original object of that name" % n)
                continue
            T = orig[n]
            nodes = np.unique(tris[fid == i])[::max(1, a.sample)]
            nsampled += len(nodes)
            d = distances(X[nodes], T)
            F["rms"][i] = math.sqrt(float(np.mean(d * d))) if len(d) else 0.0
            F["dmax"][i] = float(d.max()) if len(d) else 0.0
            # Nodes over 100 m off: past the original's edge (its nearest
            # point within 100 m of the outline) or over its inside.
            far = d > 100.0
            past = beyond_outline(X[nodes[far]], T, outline_segments(T), 100.0) if far.any() \
                else np.zeros(0, bool)
            dfar = d[far]
            F["dmax_in"][i] = max(float(d[~far].max()) if (~far).any() else 0.0,
                                  float(dfar[~past].max()) if (~past).any() else 0.0)
            F["dmax_out"][i] = float(dfar[past].max()) if past.any() else 0.0
            # A node past the edge lies in a closed gap when it is near a
            # curve of a junction at which this fault closes a gap: within
            # its own distance to the original (the fill spans from the
            # original's edge to the curve) + H (curve nodes are H apart),
            # or between the original's edge and that curve: its distances
            # to the two add up to at most the junction's gap + H (a fill
            # of several rows, at H = 500 m, has nodes near the edge and a
            # gap's width from the curve). Past the edge anywhere else (a
            # bulge of the outline far from any such curve) it is held to
            # 100 m like a node inside.
            # A branching fault (sheets in the VTU's "sheet" data) is one
            # original: a sheet's fill over a closed gap may pass over
            # another sheet's inside, whose points are then its nearest.
            # Its far nodes count as past the edge wherever they are, and
            # are held to the same closed-gap rule.
            if nsheets[i] > 1 and far.any():
                past = np.ones(int(far.sum()), bool)
                F["dmax_in"][i] = float(d[~far].max()) if (~far).any() else 0.0
            xp, dp = X[nodes[far]][past], dfar[past]
            cn = curve_nodes.get(n)
            near = np.zeros(len(xp), bool)
            if cn is not None and len(xp):
                C2 = X[cn]
                near = np.array([np.linalg.norm(C2 - p, axis=1).min() <= dd + H for p, dd in zip(xp, dp)])
                for sh, g in curve_gaps.get(n, []):
                    Cj = X[sh]
                    near |= np.array([np.linalg.norm(Cj - p, axis=1).min() + dd <= g + H
                                      for p, dd in zip(xp, dp)])
            F["dmax_gap"][i] = float(dp[near].max()) if near.any() else 0.0
            F["dmax_stray"][i] = float(dp[~near].max()) if (~near).any() else 0.0
            F["orig_zmax"][i] = T[:, :, 2].max()
            oa = tri_areas(T) if a.top == "keep" else area_below(T)
            F["orig_area"][i] = oa.sum()
            w = plane_normal(T, oa)
            F["orig_extent"][i] = (oa * np.abs(normals(T) @ w)).sum()
            M = C[fid == i]
            F["extent"][i] = (tri_areas(M) * np.abs(normals(M) @ w)).sum()
        print("   %d nodes against %d triangles in %.1f s"
              % (nsampled, sum(len(orig[n]) for n in names if n in orig), time.time() - t0))

    # --- report.json against the files
    print("-- report.json against the files")
    check(report["summary"]["meshed"] == nf and report["summary"]["triangles"] == len(tris),
          "summary: %d meshed, %d triangles" % (report["summary"]["meshed"],
                                                report["summary"]["triangles"]))
    border = np.abs(minang - 30.0) < 1e-6
    border20 = np.abs(minang - 20.0) < 1e-6
    eborder = (np.abs(elen - 0.7 * H) < 1e-6 * H) | (np.abs(elen - 1.4 * H) < 1e-6 * H)
    mism = []
    for i, r in enumerate(rok[:nf]):
        q, s, fi, tp = r["quality"], r["size"], r.get("fidelity", {}), r.get("top", {})
        tol30 = int(fsum(border)[i])
        tol20 = int(fsum(border20)[i])
        tolb = int(fsum(eborder, over=ef)[i])
        pairs = [
            ("triangles", r["triangles"], F["triangles"][i], 0),
            ("nodes", r["nodes"], F["nodes"][i], 0),
            ("below 30", q["triangles_below_30_deg"], F["below_30"][i], tol30),
            ("below 20", q["triangles_below_20_deg"], F["below_20"][i], tol20),
            ("below 20 forced", q["triangles_below_20_deg_at_sharp_corners"], F["forced"][i], tol20),
            ("sharp corners", q["sharp_corners"], F["sharp"][i], 0),
            ("edges", s["edges"], F["edges"][i], 0),
            ("edges in band", s["edges_within_0.7_1.4"], F["band"][i], tolb),
            ("min angle", q["min_angle_deg"], F["min_angle"][i], 1e-6),
            ("area", r["area_m2"], F["area"][i], 1e-8 * F["area"][i] + 1e-6),
            ("z max", tp.get("z_max_m", F["zmax"][i]), F["zmax"][i], 1e-9 * H),
        ]
        if a.original and not math.isnan(F["dmax"][i]) and a.sample == 1:
            pairs += [("node distance max", fi["node_to_original_max_m"], F["dmax"][i], 1e-3),
                      ("node distance rms", fi["node_to_original_rms_m"], F["rms"][i], 1e-3),
                      # how far the nodes past the original's edge reach:
                      # the checker measures it on its own (1 m: a foot
                      # right at 100 m from the outline may fall either way)
                      ("node distance past the outline", fi.get("beyond_outline_max_m", -1),
                       F["dmax_out"][i], 1.0)]
        for what, rep, mine, tol in pairs:
            # report.json numbers carry 10 significant digits
            if not abs(float(rep) - float(mine)) <= tol + 1e-9 * abs(float(mine)):
                mism.append("%s: %s report %s, files %s" % (names[i], what, rep, mine))
    for m in mism[:20]:
        print("      " + m)
    check(not mism, "per-fault figures of report.json agree with the files (%d disagree)" % len(mism))
    S = report["summary"]
    tot = [("triangles_below_30_deg", int(below30.sum())), ("triangles_below_20_deg", int(below20.sum())),
           ("triangles_below_20_deg_at_sharp_corners", int(forced.sum())),
           ("edges", len(elen)), ("edges_within_0.7_1.4", int(inband.sum()))]
    badt = [(k, S[k], v) for k, v in tot if abs(S[k] - v) > int(border.sum() + eborder.sum() + border20.sum())]
    check(not badt, "summary figures agree%s" % (" (not: %s)" % badt if badt else ""))

    # --- criteria
    results = []   # (criterion, measured, required, ok: True, False or None)
    nt = max(len(tris), 1)
    failed_faults = [f for f in rfaults if f.get("status") == "error"]
    empty_faults = [f for f in rfaults if f.get("status") == "empty"]
    # A near-duplicate given up by the connect stage is reported, not lost.
    dropped = {f.get("name") for f in rfaults if f.get("status") == "dropped"}
    # A fault extended over a closed gap has nodes up to the gap off its
    # original (issue 5: fidelity holds "except inside closed gaps").
    # Its RMS counts the filled gap too, and a fault trimmed at a junction
    # loses the flap it had beyond it (coverage).
    gap_allow, trimmed = {}, set()
    for jn in report.get("connect", {}).get("junctions", []):
        if jn.get("type") == "unjoined":
            # left unjoined, but one fault stopped short of the other
            # rather than run through it: that one lost its flap
            if jn.get("stops_short") and jn.get("overshoot_trimmed_m", 0) > 0:
                trimmed.add(jn["stops_short"])
            continue
        if jn.get("gap_closed_m", 0) > 0:
            for n in jn["faults"]:
                gap_allow[n] = max(gap_allow.get(n, 0.0), float(jn["gap_closed_m"]))
        if jn.get("overshoot_trimmed_m", 0) > 0:
            trimmed.update(jn["faults"])
    # Area a fault lost where it gave way to another it ran through.
    carved = {f.get("name"): float(f.get("carved_area_m2", 0.0)) for f in rok}
    # Reported reach of the nodes past the original's edge, per fault.
    beyond = {f.get("name"): float(f.get("fidelity", {}).get("beyond_outline_max_m", 0.0))
              for f in rok}

    def fault_distance_over():
        """(over, inside_bad, largest fill): over 100 m inside the outline
        or past it away from the curves of the gaps it closes, or past it
        near such a curve farther than 100 m + the largest gap the fault
        closes and farther than report.json says the fill past its edge
        reaches (a fault that closes no gap has no allowance)."""
        inside_bad = (F["dmax_in"] > 100) | (F["dmax_stray"] > 100)
        # (+1 m: the checker's own figure may differ from the report's by
        # that much, as the agreement check allows)
        allow = np.array([max(100 + gap_allow[n], beyond.get(n, 0.0) + 1.0) if n in gap_allow
                          else 100.0 for n in names]) if nf else np.zeros(0)
        over = inside_bad | (F["dmax_gap"] > allow)
        fill = max([beyond.get(n, 0.0) for n in names if n in gap_allow] + [0.0])
        return over, inside_bad, fill
    missing = []
    if a.original:
        for n, T in sorted(orig.items()):
            reaches = T[:, :, 2].min() < 0 if a.top != "keep" else True
            if reaches and n not in names and n not in dropped:
                missing.append(n)
    results.append(("failures", "%d failed, %d empty, %s" % (
        len(failed_faults), len(empty_faults),
        "%d below-sea-level originals missing" % len(missing) if a.original else "originals not given"),
        "0 failed, none missing", not failed_faults and not missing))
    share30 = 1 - below30.sum() / nt
    results.append(("min-angle-30", "%.3f%% of %d triangles >= 30 deg (min %.2f deg)"
                    % (100 * share30, len(tris), minang.min() if len(minang) else 0),
                    ">= 99.5%", share30 >= 0.995))
    njunc = int(at_junction.sum())
    unforced = int(below20.sum() - forced.sum()) - njunc
    # where the ones neither at a corner nor at a junction are
    loose = np.bincount(fid[below20 & ~forced & ~at_junction], minlength=nf) if len(tris) else np.zeros(nf, int)
    where = ", ".join("%s %d" % (names[i], loose[i]) for i in np.argsort(-loose, kind="stable")[:6] if loose[i] > 0)
    results.append(("angle-20", "%d under 20 deg, %d at corners < 40 deg (%d sharp corners), %d at "
                    "junction curves (%.3f%% of triangles), %d elsewhere%s"
                    % (below20.sum(), forced.sum(), sharp_f.sum(), njunc, 100.0 * njunc / nt, unforced,
                       " (" + where + ")" if where else ""),
                    "all at sharp corners (or <= 0.1% at junctions)",
                    unforced == 0 and njunc <= 0.001 * nt))
    shareb = inband.sum() / max(len(elen), 1)
    results.append(("edge-band", "%.2f%% of %d edges in [%.0f, %.0f] m" % (
        100 * shareb, len(elen), 0.7 * H, 1.4 * H), ">= 95%", shareb >= 0.95))
    blong = F["bmax"] > 2 * H
    results.append(("boundary-edge", "longest %.0f m (%d faults with one over 2 H)" % (
        F["bmax"].max() if nf else 0, int(blong.sum())), "<= 2 H", not bool(blong.any())))
    if a.original:
        dmax = np.nanmax(F["dmax"]) if nf else 0
        rmsmax = np.nanmax(F["rms"]) if nf else 0
        over_rms = int(np.sum(F["rms"] > 10))
        over, inside_bad, fill = fault_distance_over()
        gapped = int(np.sum((F["dmax"] > 100) & ~over))
        results.append(("distance-max", "%.1f m (%d faults over 100 m: %d inside their original's "
                        "outline, worst %.0f m, %d past it away from a closed gap, worst %.0f m; %d more "
                        "over it only in closed gaps, fill up to %.0f m reported)"
                        % (dmax, int(np.sum(over)), int(np.sum(F["dmax_in"] > 100)),
                           np.nanmax(F["dmax_in"]) if nf else 0, int(np.sum(F["dmax_stray"] > 100)),
                           np.nanmax(F["dmax_stray"]) if nf else 0, gapped, fill),
                        "<= 100 m inside the outline (past it: closed gap)", not bool(np.any(over))))
        gap_rms = np.array([n in gap_allow for n in names], dtype=bool) if nf else np.zeros(0, bool)
        rms_bad = (F["rms"] > 10) & ~gap_rms
        results.append(("distance-rms", "worst fault %.2f m, median %.2f m (%d over 10 m; %d more "
                        "that close a gap)" % (rmsmax, np.nanmedian(F["rms"]) if nf else 0,
                                               int(np.sum(rms_bad)), over_rms - int(np.sum(rms_bad))),
                        "<= 10 m (but gap closers)", not bool(np.any(rms_bad))))
        cov = F["extent"] / F["orig_extent"]
        cov3 = F["area"] / F["orig_area"]
        excused = np.array([n in trimmed for n in names], dtype=bool) if nf else np.zeros(0, bool)
        cut = np.array([carved.get(n, 0.0) for n in names]) / F["orig_area"] if nf else np.zeros(0)
        low = int(np.sum((cov + cut < a.min_coverage) & ~excused))
        results.append(("coverage", "extent / original%s: min %.3f, median %.3f, max %.3f (%d under); "
                        "3D area / original: min %.3f, median %.3f (%d under)"
                        % ("" if a.top == "keep" else " below sea level", np.nanmin(cov),
                           np.nanmedian(cov), np.nanmax(cov), low, np.nanmin(cov3),
                           np.nanmedian(cov3), int(np.sum(cov3 < a.min_coverage))),
                        ">= %.2f" % a.min_coverage, low == 0 and not missing))
    else:
        for c in ("distance-max", "distance-rms", "coverage"):
            results.append((c, "not measured (no --original)", "", None))
    zmax_all = float(X[np.unique(tris), 2].max()) if len(tris) else 0.0
    if a.top == "keep":
        if a.original:
            lost = [n for i, n in enumerate(names) if F["orig_zmax"][i] > 0 and F["zmax"][i] <= 0]
            results.append(("top", "z max %.1f m; %d faults rising above sea level, %d of them cut"
                            % (zmax_all, int(np.sum(F["orig_zmax"] > 0)), len(lost)),
                            "tops kept", not lost))
        else:
            results.append(("top", "z max %.1f m" % zmax_all, "(keep)", None))
    else:
        above = int(np.sum(X[np.unique(tris), 2] > 0)) if len(tris) else 0
        nmiss = int(F["near_miss"].sum())
        noedge = []
        if a.original:
            noedge = [n for i, n in enumerate(names)
                      if F["orig_zmax"][i] > 0 and F["top_edges"][i] == 0]
        results.append(("top", "%d nodes above 0 (z max %g m), %d boundary nodes within %g m "
                        "below 0 but not on it (%d within 1e-6 m), %d top edges (%.1f km) on z = 0%s"
                        % (above, zmax_all, nmiss, a.level_tol, near_nm, F["top_edges"].sum(),
                           F["top_len"].sum() / 1e3,
                           ", %d crossing faults without a top edge" % len(noedge)
                           if a.original else ""),
                        "z <= 0, top on z = 0", above == 0 and nmiss == 0 and not noedge))

    # --- per-fault table
    def outside(i):
        o = []
        if F["below_30"][i] / max(F["triangles"][i], 1) > 0.005:
            o.append("<30")
        if F["below_20"][i] > F["forced"][i]:
            o.append("<20")
        if F["band"][i] / max(F["edges"][i], 1) < 0.95:
            o.append("band")
        if F["bmax"][i] > 2 * H:
            o.append("bedge %.0f m" % F["bmax"][i])
        if a.original and fault_distance_over()[0][i]:
            o.append("max" if F["dmax_in"][i] > 100 else
                     "max past outline" if F["dmax_stray"][i] > 100 else "max past gap fill")
        if F["rms"][i] > 10 and names[i] not in gap_allow:
            o.append("rms")
        if a.top != "keep" and (F["zmax"][i] > 0 or F["near_miss"][i]):
            o.append("top")
        if (a.original and F["extent"][i] / F["orig_extent"][i]
                + carved.get(names[i], 0.0) / F["orig_area"][i] < a.min_coverage
                and names[i] not in trimmed):
            o.append("cov")
        return o

    rows = [i for i in range(nf) if a.verbose or outside(i)]
    print("\n%-56s %7s %6s %6s %5s %6s %7s %7s %6s %9s  %s" % (
        "fault" if a.verbose else "faults outside a criterion (per fault)", "tri", "min", "<30%",
        "<20", "band%", "rms", "max", "cover", "top km", "outside"))
    for i in rows:
        print("%-56.56s %7d %6.1f %6.2f %2d/%-2d %6.1f %7.2f %7.1f %6.3f %9.2f  %s" % (
            names[i], F["triangles"][i], F["min_angle"][i],
            100 * F["below_30"][i] / max(F["triangles"][i], 1), F["below_20"][i], F["forced"][i],
            100 * F["band"][i] / max(F["edges"][i], 1), F["rms"][i], F["dmax"][i],
            F["extent"][i] / F["orig_extent"][i] if a.original else float("nan"),
            F["top_len"][i] / 1e3, ",".join(outside(i))))
    for f in failed_faults + empty_faults:
        print("%-56.56s %s: %s" % (f.get("name") or f.get("file"), f["status"], f.get("error", "")))
    for n in missing:
        print("%-56.56s missing from the mesh" % n)

    print("\n%-13s %-8s %-26s %s" % ("criterion", "result", "required", "measured"))
    for c, measured, required, ok in results:
        ok = None if ok is None else bool(ok)
        if ok is None:
            res = "-"
        elif c in crit:
            res = "PASS" if ok else "FAIL"
        else:
            res = "(ok)" if ok else "(no)"
        print("%-13s %-8s %-26s %s" % (c, res, required, measured))
        if c in crit and ok is False:
            failures.append("criterion %s: %s (required %s)" % (c, measured, required))
        if c in crit and ok is None:
            failures.append("criterion %s asserted but not measurable: %s" % (c, measured))
    print("(PASS/FAIL: asserted with --criteria; (ok)/(no): printed only)")
    print("remesh check of %s: %d faults, %d triangles, %.1f s, %d failures"
          % (out, nf, len(tris), time.time() - t_start, len(failures)))
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
