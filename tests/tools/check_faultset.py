#!/usr/bin/python3
"""Independent check of the fault-set writers with meshio and Gmsh.

Runs `test_faultset_write --write DIR`, which writes the sample fault set of
tests/unit/test_faultset_write.c (three vertical faults meeting on a shared
vertical line, 40 vertices, 54 triangles added row by row across the faults)
as set.vtu, set41.msh, set22.msh, tags41.msh (physical tags 101, 7, 55),
set.stl, set.obj and ts/*.ts. The geometry is rebuilt here from the same
formulas, and each file is read back:
  meshio  VTU, MSH 4.1, MSH 2.2, STL, OBJ: triangle count, every triangle's
          corners (exact; STL to float32), fault_id / gmsh:physical /
          gmsh:geometrical / OBJ group per triangle, names, CRS;
  Gmsh    both MSH files: physical groups, their names and entities, the
          triangles and node tags per group, node coordinates by tag;
  by hand the STL attribute words and normals, the OBJ group names and
          the TSurf files (name, VRTX and TRGL counts, corners).

Usage: check_faultset.py TEST_FAULTSET_WRITE DIR ; exit 0 when everything
agrees, 1 on a mismatch, 77 when meshio or Gmsh's Python API is missing
(Debian python3-meshio, python3-gmsh).
"""
import math
import os
import struct
import subprocess
import sys

try:
    import gmsh
    import meshio
    import numpy as np
except ImportError as e:
    print("%s: skipped" % e)
    sys.exit(77)

NAMES = ["CRFA-BPPM-WEST-Big_Pine_fault-CFM4",
         'San Andreas fault (Mojave, "south") 1857',
         "Falla de San Andr\u00e9s / Ca\u00f1\u00f3n"]
TS_FILES = ["CRFA-BPPM-WEST-Big_Pine_fault-CFM4.ts",
            "San_Andreas_fault_Mojave_south_1857.ts",
            "Falla_de_San_Andr_s_Ca_n.ts"]
CRS = "EPSG:26711"
CUSTOM_TAGS = [101, 7, 55]

failures = []


def check(cond, what):
    print(("ok    " if cond else "FAIL  ") + what)
    if not cond:
        failures.append(what)


def msh_name(name):
    """What the writer puts between the quotes (see fm_faultset_write.h)."""
    return name.replace('"', "'").replace("\\", "/")


def sample():
    """Vertices, triangles and fault per triangle, as the C test builds them."""
    def sx(i):
        return 400000.1 + 997.3 * i

    def sy(i):
        return 3750000.3 + 13.7 * i

    pts = []
    for j in range(4):
        for i in range(5):
            pts.append((sx(i), sy(i), 250.25 - 1234.5 * j))
    for j in range(4):
        for k in range(1, 4):
            pts.append((sx(4) + 500.7 * k, sy(4) + 811.1 * k, 250.25 - 1234.5 * j))
    for j in range(4):
        for k in range(1, 3):
            pts.append((sx(4) + 600.2 * k, sy(4) - 700.9 * k, 250.25 - 1234.5 * j))

    def col(f, c, j):
        if f == 0 or c == 0:
            return j * 5 + (c if f == 0 else 4)
        return 20 + j * 3 + c - 1 if f == 1 else 32 + j * 2 + c - 1

    tris, tags = [], []
    for j in range(3):
        for f, ncols in enumerate((5, 4, 3)):
            for c in range(ncols - 1):
                a, b, cc, d = col(f, c, j), col(f, c + 1, j), col(f, c + 1, j + 1), col(f, c, j + 1)
                if (c + j) % 2 == 0:
                    tris += [(a, b, cc), (a, cc, d)]
                else:
                    tris += [(a, b, d), (b, cc, d)]
                tags += [f, f]
    return np.array(pts), np.array(tris), np.array(tags)


PTS, TRIS, TAGS = sample()
NT = len(TRIS)
# MSH 4.1, OBJ: triangles grouped by fault, mesh order within a fault.
BY_FAULT = sorted(range(NT), key=lambda t: (TAGS[t], t))


def corners(points, cells):
    return np.asarray(points)[np.asarray(cells)]


def meshio_triangles(m, lines=False):
    """All triangle blocks of a meshio mesh concatenated, and cell data alike
    (lines: MSH's curves may come besides)."""
    blocks = [i for i, c in enumerate(m.cells) if c.type == "triangle"]
    others = [c.type for c in m.cells if c.type != "triangle" and not (lines and c.type == "line")]
    check(not others, "only triangles%s (%s)" % (" and lines" if lines else "",
                                                 [c.type for c in m.cells]))
    cells = np.concatenate([m.cells[i].data for i in blocks])
    data = {k: np.concatenate([v[i] for i in blocks]) for k, v in m.cell_data.items()}
    return cells, data


def strings(field):
    """A UInt8 field-data array of NUL-terminated UTF-8 strings."""
    raw = bytes(np.asarray(field, dtype=np.uint8))
    return [s.decode() for s in raw.split(b"\0")[:-1]]


def check_vtu(path):
    print("-- meshio", os.path.basename(path))
    m = meshio.read(path)
    cells, data = meshio_triangles(m)
    check(len(cells) == NT, "%d triangles" % len(cells))
    check(np.array_equal(m.points, PTS), "points bit for bit")
    check(np.array_equal(cells, TRIS), "connectivity and winding as in the mesh")
    check(np.array_equal(data.get("fault_id"), TAGS + 1), "fault_id per triangle: the fault number, tag + 1")
    areas = [0.5 * np.linalg.norm(np.cross(PTS[b] - PTS[a], PTS[c] - PTS[a])) for a, b, c in TRIS]
    check(np.allclose(data.get("area"), areas, rtol=1e-12, atol=0), "extra cell array 'area'")
    check(strings(m.field_data.get("fault_names", [])) == NAMES, "fault_names field data")
    check(strings(m.field_data.get("crs", [])) == [CRS], "crs field data")


def edge_kind(u, v, w):
    """docs/formats.md's kind of outline edge u-v of a triangle with third
    corner w: which way it faces within the triangle against up dip."""
    pu, pv, pw = PTS[u], PTS[v], PTS[w]
    n = np.cross(pv - pu, pw - pu)
    n = n / np.linalg.norm(n)
    up = np.array([0.0, 0.0, 1.0]) - n[2] * n
    e = pv - pu
    o = (pu + pv) / 2 - pw
    o = o - np.dot(o, e) / np.dot(e, e) * e
    if np.linalg.norm(up) < 1e-6:
        return "ends"
    c = np.dot(o, up) / (np.linalg.norm(o) * np.linalg.norm(up))
    if c > math.sqrt(0.5):
        return "top" if pu[2] >= -1e-6 and pv[2] >= -1e-6 else "buried top"
    return "bottom" if c < -math.sqrt(0.5) else "ends"


def outline_edges():
    """Every outline edge (a side of one triangle only, as a sorted pair of
    vertex indices) with the name of its group, and every side's holders."""
    holders = {}
    for t, (a, b, c) in enumerate(TRIS):
        for u, v, w in ((a, b, c), (b, c, a), (c, a, b)):
            holders.setdefault((min(u, v), max(u, v)), []).append((t, w))
    want = {}
    for (u, v), hs in holders.items():
        if len(hs) == 1:
            t, w = hs[0]
            want[(u, v)] = "%s: %s" % (msh_name(NAMES[TAGS[t]]), edge_kind(u, v, w))
    return want, holders


def check_msh_curves(m):
    """The curves: every outline edge of a fault (a side of one triangle
    only) in the group of its fault and kind, once; nothing else there."""
    want, holders = outline_edges()
    names1 = {v[0]: k for k, v in m.field_data.items() if v[1] == 1}
    got, dup = {}, 0
    for i, c in enumerate(m.cells):
        if c.type != "line":
            continue
        for (a, b), p in zip(c.data, m.cell_data["gmsh:physical"][i]):
            key = (min(a, b), max(a, b))
            name = names1.get(int(p), "?")
            if key in holders and len(holders[key]) == 1:
                dup += key in got
                got[key] = name
    check(got == want and dup == 0,
          "outline edges by fault and kind (%d of %d as expected, %d twice)" %
          (sum(got.get(k) == n for k, n in want.items()), len(want), dup))


def check_msh_meshio(path, grouped, phys):
    print("-- meshio", os.path.basename(path))
    m = meshio.read(path)
    cells, data = meshio_triangles(m, lines=True)
    check_msh_curves(m)
    order = BY_FAULT if grouped else list(range(NT))
    check(len(cells) == NT and len(m.points) == len(PTS),
          "%d triangles, %d points" % (len(cells), len(m.points)))
    check(np.array_equal(corners(m.points, cells), corners(PTS, TRIS[order])),
          "every triangle's corners bit for bit, wound as in the mesh")
    check(np.array_equal(data.get("gmsh:physical"), [phys[TAGS[t]] for t in order]),
          "gmsh:physical per triangle")
    check(np.array_equal(data.get("gmsh:geometrical"), [TAGS[t] + 1 for t in order]),
          "gmsh:geometrical per triangle")
    want = {msh_name(n): [phys[i], 2] for i, n in enumerate(NAMES)}
    got = {k: list(v) for k, v in m.field_data.items() if v[1] == 2}
    check(got == want, "physical names %r" % got)


def check_msh_gmsh(path, phys):
    print("-- gmsh", os.path.basename(path))
    gmsh.open(path)
    groups = sorted(gmsh.model.getPhysicalGroups(2))
    check(groups == sorted((2, p) for p in phys), "physical surfaces %s" % groups)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    check(len(tags) == len(PTS) and len(set(tags)) == len(tags), "%d distinct nodes" % len(tags))
    xyz = {int(t): tuple(coords[3 * i:3 * i + 3]) for i, t in enumerate(tags)}
    check(all(xyz.get(v + 1) == tuple(PTS[v]) for v in range(len(PTS))),
          "node tag = vertex index + 1, coordinates bit for bit")
    for f, p in enumerate(phys):
        name = gmsh.model.getPhysicalName(2, p)
        check(name == msh_name(NAMES[f]), "group %d named %r" % (p, name))
        ents = list(gmsh.model.getEntitiesForPhysicalGroup(2, p))
        check(ents == [f + 1], "group %d on surface %s" % (p, ents))
        want = [t for t in range(NT) if TAGS[t] == f]
        etypes, etags, enodes = gmsh.model.mesh.getElements(2, ents[0] if ents else -1)
        check(list(etypes) == [2], "group %d: 3-node triangles only (%s)" % (p, list(etypes)))
        if list(etypes) == [2]:
            check(len(etags[0]) == len(want),
                  "group %d: %d triangles (expected %d)" % (p, len(etags[0]), len(want)))
            check(sorted(int(e) for e in etags[0]) == [t + 1 for t in want],
                  "group %d: element tag = triangle index + 1" % p)
            got = {int(e): tuple(int(n) for n in enodes[0][3 * i:3 * i + 3])
                   for i, e in enumerate(etags[0])}
            check(all(got.get(t + 1) == tuple(int(v) + 1 for v in TRIS[t]) for t in want),
                  "group %d: nodes and winding of every triangle" % p)
    # the curves as Gmsh reads them: every outline edge in its group
    want, holders = outline_edges()
    got = {}
    for dim, p in gmsh.model.getPhysicalGroups(1):
        name = gmsh.model.getPhysicalName(1, p)
        for ent in gmsh.model.getEntitiesForPhysicalGroup(1, p):
            etypes, _, enodes = gmsh.model.mesh.getElements(1, ent)
            check(list(etypes) == [1], "curve %r: 2-node lines" % name)
            for k in range(0, len(enodes[0]) if len(enodes) else 0, 2):
                key = tuple(sorted((int(enodes[0][k]) - 1, int(enodes[0][k + 1]) - 1)))
                if len(holders.get(key, ())) == 1:
                    got[key] = name
    check(got == want, "Gmsh: %d outline edges in their groups (of %d)" %
          (sum(got.get(k) == n for k, n in want.items()), len(want)))
    gmsh.clear()


def check_stl(path):
    print("-- meshio and by hand", os.path.basename(path))
    m = meshio.read(path)
    cells, _ = meshio_triangles(m)
    check(len(cells) == NT, "%d triangles" % len(cells))
    f32 = PTS.astype(np.float32)
    check(np.array_equal(corners(m.points, cells), corners(f32, TRIS)),
          "corners equal the float32 of the mesh's, in mesh order")
    err = np.max(np.abs(corners(m.points, cells).astype(float) - corners(PTS, TRIS)))
    check(err <= 0.25, "float32 rounding %.3f m (<= 0.25 m below 4.2e6 m)" % err)
    with open(path, "rb") as fh:
        raw = fh.read()
    header = raw[:80].rstrip(b"\0").decode()
    check(header.startswith("faultmesh ") and header.endswith(", CRS " + CRS),
          "header %r" % header)
    check(len(raw) == 84 + 50 * NT and struct.unpack("<I", raw[80:84])[0] == NT,
          "binary layout (%d bytes)" % len(raw))
    attrs, normals_ok = [], True
    for t in range(NT):
        rec = raw[84 + 50 * t:84 + 50 * (t + 1)]
        n = np.array(struct.unpack("<3f", rec[:12]))
        a, b, c = PTS[TRIS[t]]
        want = np.cross(b - a, c - a)
        want /= np.linalg.norm(want)
        normals_ok &= bool(np.allclose(n, want, atol=1e-6))
        attrs.append(struct.unpack("<H", rec[48:50])[0])
    check(normals_ok, "unit normals along (b - a) x (c - a)")
    check(attrs == list(TAGS), "attribute word = fault index")


def check_obj(path):
    print("-- meshio and by hand", os.path.basename(path))
    m = meshio.read(path)
    cells, data = meshio_triangles(m)
    check(len(cells) == NT, "%d triangles" % len(cells))
    check(np.array_equal(m.points, PTS), "points bit for bit, in mesh order")
    check(np.array_equal(cells, TRIS[BY_FAULT]), "faces grouped by fault, mesh order within")
    check(np.array_equal(data.get("obj:group_ids"), TAGS[BY_FAULT]), "obj:group_ids = fault")
    with open(path, encoding="utf-8") as fh:
        lines = fh.read().splitlines()
    want = [n.replace(" ", "_") for n in NAMES]
    check([ln[2:] for ln in lines if ln.startswith("g ")] == want, "g names %s" % want)
    check([ln[2:] for ln in lines if ln.startswith("o ")] == want, "o names")
    check("# CRS " + CRS in lines, "CRS comment")


def check_tsurf(folder):
    print("-- by hand", folder)
    check(sorted(os.listdir(folder)) == sorted(TS_FILES), "files %s" % sorted(os.listdir(folder)))
    for f, file in enumerate(TS_FILES):
        path = os.path.join(folder, file)
        if not os.path.exists(path):
            continue
        with open(path, encoding="utf-8") as fh:
            lines = fh.read().splitlines()
        vrtx = {int(ln.split()[1]): tuple(float(x) for x in ln.split()[2:5])
                for ln in lines if ln.startswith("VRTX ")}
        trgl = [tuple(int(x) for x in ln.split()[1:4]) for ln in lines if ln.startswith("TRGL ")]
        want = [t for t in range(NT) if TAGS[t] == f]
        check("name:" + NAMES[f] in lines, "%s: name" % file)
        check(len(vrtx) == len(set(TRIS[want].ravel())), "%s: %d vertices" % (file, len(vrtx)))
        same = len(trgl) == len(want) and all(
            [vrtx.get(i) for i in tr] == [tuple(PTS[v]) for v in TRIS[t]]
            for tr, t in zip(trgl, want))
        check(same, "%s: %d triangles, corners and winding" % (file, len(trgl)))


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: check_faultset.py TEST_FAULTSET_WRITE DIR")
    out = sys.argv[2]
    subprocess.run([sys.argv[1], "--write", out], check=True)
    phys = [1, 2, 3]
    check_vtu(os.path.join(out, "set.vtu"))
    check_msh_meshio(os.path.join(out, "set41.msh"), True, phys)
    check_msh_meshio(os.path.join(out, "tags41.msh"), True, CUSTOM_TAGS)
    check_msh_meshio(os.path.join(out, "set22.msh"), False, phys)
    check_stl(os.path.join(out, "set.stl"))
    check_obj(os.path.join(out, "set.obj"))
    check_tsurf(os.path.join(out, "ts"))
    gmsh.initialize(["check_faultset"])
    gmsh.option.setNumber("General.Terminal", 0)
    check_msh_gmsh(os.path.join(out, "set41.msh"), phys)
    check_msh_gmsh(os.path.join(out, "tags41.msh"), CUSTOM_TAGS)
    check_msh_gmsh(os.path.join(out, "set22.msh"), phys)
    gmsh.finalize()
    print("%d failures" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
