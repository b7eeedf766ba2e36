#!/usr/bin/python3
"""Independent check of `faultmesh info --json`.

Re-reads every TSurf file with a separate, deliberately plain implementation
(Python, exact rational arithmetic where a decision depends on it) and
compares: file vertices and triangles, parts, welded vertices, triangles
after cleaning, area, components, non-manifold edges, boundary loops and
holes, z range. Definitions follow docs/guide.md's description of `info`:
exact welding of identical coordinates, removal of zero-area and duplicate
triangles, then of fragments (< 10 triangles and < 0.1 % of the largest
component's area), edge-connected components, and boundary loops of the
cleaned surface.

Usage: check_info.py FAULTMESH PATH... ; exit 0 when everything agrees,
1 on a mismatch, 77 when a PATH does not exist (data absent: skip).
"""
import json
import os
import subprocess
import sys
from fractions import Fraction

MIN_FRAGMENT_TRIANGLES = 10
MIN_FRAGMENT_FRACTION = 0.001


def read_tsurf(path):
    """Returns a list of objects: dict(name, parts, vertices, triangles)."""
    with open(path, "rb") as f:
        text = f.read().decode("latin-1")
    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
    objects = []
    obj = None
    in_header = False
    zsign = 1.0
    for line in lines:
        tok = line.split()
        if not tok:
            continue
        key = tok[0]
        if key == "GOCAD":
            obj = {"name": "", "parts": 0, "nverts": 0, "pos": {}, "tris": []}
            zsign = 1.0
            continue
        if obj is None:
            continue
        if in_header:
            if "}" in line:
                in_header = False
            s = line.strip()
            if s.startswith("name:"):
                obj["name"] = s[5:].strip()
            continue
        if key == "HEADER":
            rest = line[line.index("HEADER") + 6:]
            if "}" not in rest:
                in_header = True
            elif "name:" in rest:
                obj["name"] = rest.split("name:")[1].split("}")[0].strip()
            continue
        if key == "ZPOSITIVE":
            zsign = -1.0 if tok[1].lower() == "depth" else 1.0
        elif key == "TFACE":
            obj["parts"] += 1
        elif key in ("VRTX", "PVRTX"):
            x, y, z = float(tok[2]), float(tok[3]), float(tok[4]) * zsign
            obj["pos"][int(tok[1])] = (x + 0.0, y + 0.0, z + 0.0)
            obj["nverts"] += 1
        elif key in ("ATOM", "PATOM"):
            obj["pos"][int(tok[1])] = obj["pos"][int(tok[2])]
            obj["nverts"] += 1
        elif key == "TRGL":
            obj["tris"].append((int(tok[1]), int(tok[2]), int(tok[3])))
        elif key == "END":
            objects.append(obj)
            obj = None
    return objects


def cross(a, b, c):
    u = (b[0] - a[0], b[1] - a[1], b[2] - a[2])
    v = (c[0] - a[0], c[1] - a[1], c[2] - a[2])
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def zero_area(a, b, c):
    n = cross(a, b, c)
    scale = max(abs(x) for x in a + b + c) or 1.0
    if max(abs(x) for x in n) > 1e-6 * scale * scale * 1e-6:
        return False
    fa, fb, fc = ([Fraction(x) for x in p] for p in (a, b, c))
    return all(x == 0 for x in cross(fa, fb, fc))


def area(a, b, c):
    n = cross(a, b, c)
    return 0.5 * (n[0] ** 2 + n[1] ** 2 + n[2] ** 2) ** 0.5


class DSU:
    def __init__(self, n):
        self.p = list(range(n))

    def find(self, x):
        while self.p[x] != x:
            self.p[x] = self.p[self.p[x]]
            x = self.p[x]
        return x

    def union(self, a, b):
        a, b = self.find(a), self.find(b)
        if a != b:
            self.p[max(a, b)] = min(a, b)


def analyse(obj):
    pos = obj["pos"]
    keys = {}
    tris = []
    for t in obj["tris"]:
        ks = []
        for vid in t:
            p = pos[vid]
            ks.append(keys.setdefault(p, len(keys)))
        tris.append(tuple(ks))
    pts = [None] * len(keys)
    for p, k in keys.items():
        pts[k] = p
    # degenerate and duplicate triangles
    seen = set()
    clean = []
    for t in tris:
        if len(set(t)) < 3 or zero_area(pts[t[0]], pts[t[1]], pts[t[2]]):
            continue
        s = tuple(sorted(t))
        if s in seen:
            continue
        seen.add(s)
        clean.append(t)
    # edge-connected components
    edges = {}
    for i, t in enumerate(clean):
        for k in range(3):
            a, b = t[k], t[(k + 1) % 3]
            edges.setdefault((min(a, b), max(a, b)), []).append(i)
    dsu = DSU(len(clean))
    for tl in edges.values():
        for i in tl[1:]:
            dsu.union(tl[0], i)
    comp = {}
    for i in range(len(clean)):
        comp.setdefault(dsu.find(i), []).append(i)
    comps = list(comp.values())
    comp_area = [sum(area(*(pts[v] for v in clean[i])) for i in c) for c in comps]
    largest = max(comp_area) if comp_area else 0.0
    big = max(range(len(comps)), key=lambda i: (comp_area[i], -min(comps[i]))) if comps else -1
    keep = []
    for ci, c in enumerate(comps):
        if ci != big and len(c) < MIN_FRAGMENT_TRIANGLES and \
                comp_area[ci] < MIN_FRAGMENT_FRACTION * largest:
            continue
        keep.extend(c)
    keep.sort()
    kept = [clean[i] for i in keep]
    ncomp_kept = sum(1 for ci, c in enumerate(comps)
                     if not (ci != big and len(c) < MIN_FRAGMENT_TRIANGLES and
                             comp_area[ci] < MIN_FRAGMENT_FRACTION * largest))
    # figures of the kept surface
    used = sorted({v for t in kept for v in t})
    edges = {}
    for t in kept:
        for k in range(3):
            a, b = t[k], t[(k + 1) % 3]
            e = (min(a, b), max(a, b))
            edges[e] = edges.get(e, 0) + 1
    nonmanifold = sum(1 for c in edges.values() if c > 2)
    boundary = [e for e, c in edges.items() if c == 1]
    # boundary loops = components of the boundary-edge graph, valid when
    # every boundary vertex has degree 2 (no pinches)
    deg = {}
    for a, b in boundary:
        deg[a] = deg.get(a, 0) + 1
        deg[b] = deg.get(b, 0) + 1
    simple = nonmanifold == 0 and all(d == 2 for d in deg.values())
    bv = sorted(deg)
    index = {v: i for i, v in enumerate(bv)}
    bd = DSU(len(bv))
    for a, b in boundary:
        bd.union(index[a], index[b])
    loops = len({bd.find(i) for i in range(len(bv))})
    # components that have a boundary: each has one outer loop
    vcomp = {}
    dsu2 = DSU(len(pts))
    for t in kept:
        dsu2.union(t[0], t[1])
        dsu2.union(t[0], t[2])
    with_boundary = len({dsu2.find(v) for v in bv})
    return {
        "name": obj["name"],
        "parts": obj["parts"],
        "file_vertices": obj["nverts"],
        "file_triangles": len(obj["tris"]),
        "vertices": len(used),
        "triangles": len(kept),
        "area_km2": sum(area(*(pts[v] for v in t)) for t in kept) * 1e-6,
        "components": ncomp_kept,
        "nonmanifold_edges": nonmanifold,
        "z_min": min(pts[v][2] for v in used) if used else 0.0,
        "z_max": max(pts[v][2] for v in used) if used else 0.0,
        "simple": simple,
        "boundary_loops": loops,
        "holes": loops - with_boundary,
    }


def main():
    exe, paths = sys.argv[1], sys.argv[2:]
    for p in paths:
        if not os.path.exists(p):
            print(f"skipped: {p} does not exist")
            return 77
    out = subprocess.run([exe, "info", "--json"] + paths, capture_output=True, text=True)
    if out.returncode != 0:
        print(f"faultmesh info exited {out.returncode}:\n{out.stderr}")
        return 1
    report = json.loads(out.stdout)
    problems = 0
    nfiles = nobjects = nloops_checked = 0
    for f in report["files"]:
        nfiles += 1
        if f["status"] != "ok":
            print(f"{f['path']}: faultmesh failed: {f.get('error')}")
            problems += 1
            continue
        mine = [analyse(o) for o in read_tsurf(f["path"])]
        if len(mine) != len(f["objects"]):
            print(f"{f['path']}: {len(f['objects'])} objects, expected {len(mine)}")
            problems += 1
            continue
        for exp, got in zip(mine, f["objects"]):
            nobjects += 1
            keys = ["name", "parts", "file_vertices", "file_triangles", "vertices",
                    "triangles", "components", "nonmanifold_edges"]
            if exp["simple"]:
                keys += ["boundary_loops", "holes"]
                nloops_checked += 1
            for k in keys:
                if exp[k] != got[k]:
                    print(f"{f['path']}: {k}: faultmesh {got[k]}, expected {exp[k]}")
                    problems += 1
            for k in ("area_km2", "z_min", "z_max"):
                if abs(exp[k] - got[k]) > 1e-7 * max(1.0, abs(exp[k])):
                    print(f"{f['path']}: {k}: faultmesh {got[k]}, expected {exp[k]}")
                    problems += 1
    print(f"checked {nfiles} files, {nobjects} objects "
          f"({nloops_checked} with boundary loops compared): {problems} mismatches")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
