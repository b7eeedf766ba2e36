#!/usr/bin/python3
"""Independent check of `faultmesh remesh/demo --elements quad` (issue 23).

Written from the readers' behaviour and docs/formats.md, not from the writer:

EQSim (mesh.eqsim), read as OpenSHA's EQSIMv06FileReader reads a geometry
  file: every line starts with an integer record kind; the first is 101
  EQSim_Input_Geometry_2 with spec level >= 4; 200 gives n_section,
  n_vertex, n_triangle, n_rectangle; each 201 (sid, one-token name,
  n_vertex, n_triangle, n_rectangle, 8 numbers, fault_id) is followed by
  exactly its 202 vertices (id, lat, lon, depth, das, integer trace flag)
  and then its 204 rectangles (id, 4 vertex ids, rake, slip rate, aseismic
  factor, strike, dip, integer perfect flag); a section with triangles is
  refused ("Don't yet support triangles"); the totals of 200 hold; vertex
  and element ids are their positions + 1. As Virtual Quake's reader (a
  generic EQSim parser driven by the descriptors) also needs: the 120/121
  descriptors give record 204 eleven fields and no record 203 appears.
  Geometry: rectangular coordinates (coord_sys 1) equal the VTU's points
  exactly; every element is a rectangle (right angles, equal opposite
  sides, planar) whose corners run counterclockwise seen from above, the
  first and last on its top edge (horizontal), strike and dip those of its
  corners; trace flags only on top corners.
RSQSim (mesh.rsqsim), as RSQSim's readFault decides the element kind by
  the column count: 10 columns (rectangles: x y z L W strike dip rake
  slip_rate sect_num, fewer than a triangle file's 11-13), the centre the
  mean of the VTU corners, L and W the sides, strike/dip as the EQSim's,
  rake and slip rate as the EQSim's.
Faults: no two rectangles of different faults run through each other (the
  line where their planes cross inside both; sharing an edge or ending on
  the other is allowed).
report.json "rectangles": the counts agree with the files; with
  --limits, the issue's targets are printed (area within 3 % per fault,
  with the faults outside it, flatness p99 <= 5 % of the size, junction
  gaps <= size / 2) and must hold, the area on every fault.

Usage: check_quads.py DIR [--no-crossing-check]; exit 0 when everything
agrees, 1 otherwise, 77 without meshio or numpy.
"""
import argparse
import json
import math
import sys

try:
    import meshio
    import numpy as np
except ImportError:
    print("skipped: needs python3-meshio and numpy")
    sys.exit(77)

fails = 0


def check(ok, what):
    global fails
    if not ok:
        fails += 1
        print("FAIL  " + what)
    return ok


def read_eqsim(path):
    lines = open(path).read().splitlines()
    kinds = [int(l.split()[0]) for l in lines]  # every line starts with an integer
    first = lines[0].split()
    check(first[0] == "101" and first[1] == "EQSim_Input_Geometry_2" and int(first[2]) >= 4,
          "EQSim: signature line")
    # descriptors (what Virtual Quake's parser is driven by)
    desc = {}
    for l in lines:
        f = l.split()
        if f[0] == "120":
            desc[int(f[1])] = int(f[3])
    check(desc.get(204) == 11 and 203 not in desc, "EQSim: record 204 has 11 fields, no 203")
    check(203 not in kinds, "EQSim: no triangle records (203)")
    it = iter(enumerate(lines))
    summary = None
    sections, verts, rects = [], [], []
    for i, l in it:
        f = l.split()
        k = int(f[0])
        if k == 200:
            summary = [int(x) for x in f[1:5]]
        elif k == 201:
            sid, name, nv, nt, nr = int(f[1]), f[2], int(f[3]), int(f[4]), int(f[5])
            fault_id = int(f[14])
            if not check(nt == 0, "EQSim: section %s has no triangles" % name):
                continue
            sec = {"sid": sid, "name": name, "fault_id": fault_id, "v0": len(verts),
                   "r0": len(rects), "nv": nv, "nr": nr}
            for _ in range(nv):
                j, l2 = next(it)
                g = l2.split()
                check(g[0] == "202", "EQSim line %d: a 202 vertex" % (j + 1))
                verts.append((int(g[1]), float(g[2]), float(g[3]), float(g[4]), float(g[5]),
                              int(g[6])))
            for _ in range(nr):
                j, l2 = next(it)
                g = l2.split()
                check(g[0] == "204" and len(g) >= 12, "EQSim line %d: a 204 rectangle" % (j + 1))
                rects.append((int(g[1]), [int(x) for x in g[2:6]], float(g[6]), float(g[7]),
                              float(g[8]), float(g[9]), float(g[10]), int(g[11]), sid))
            sections.append(sec)
    check(summary is not None, "EQSim: a 200 summary")
    check(summary[0] == len(sections) and summary[1] == len(verts) and summary[2] == 0
          and summary[3] == len(rects), "EQSim: 200 counts %s against %d/%d/%d" %
          (summary, len(sections), len(verts), len(rects)))
    check(all(v[0] == i + 1 for i, v in enumerate(verts)), "EQSim: vertex ids 1..n in order")
    check(all(r[0] == i + 1 for i, r in enumerate(rects)), "EQSim: rectangle ids 1..n in order")
    coord = int(lines[kinds.index(200)].split()[11])
    return sections, verts, rects, coord


def strike_dip(c):
    """Strike and dip of corners c (4x3) by docs/formats.md's convention."""
    n = np.cross(c[1] - c[0], c[3] - c[0])
    h = math.hypot(n[0], n[1])
    dip = math.degrees(math.atan2(h, abs(n[2])))
    s = (math.degrees(math.atan2(n[0], n[1])) - 90) % 360 if h > 0 else 0.0
    return s, min(dip, 90.0)


def ang_diff(a, b):
    return abs((a - b + 180) % 360 - 180)


def rect_meets(a, b, tol=1e-6):
    """Whether rectangles a and b (4x3 corners) run through each other: the
    line where their planes cross passes through the inside of both (1e-6 m
    in from every edge) over more than 1e-6 m. Touching, as two faults'
    last elements sharing the edge where the faults meet, or one ending on
    the other, is not meeting; parallel rectangles are not looked at."""
    na, nb = np.cross(a[1] - a[0], a[3] - a[0]), np.cross(b[1] - b[0], b[3] - b[0])
    na, nb = na / np.linalg.norm(na), nb / np.linalg.norm(nb)
    d = np.cross(na, nb)
    dn = np.linalg.norm(d)
    if dn < 1e-9:
        return False
    d = d / dn
    ha, hb = np.dot(na, a[0]), np.dot(nb, b[0])
    # the point of both planes nearest the origin's projection
    p0 = (ha * np.cross(nb, d) + hb * np.cross(d, na)) / np.dot(np.cross(na, nb), d)

    def interval(r):
        o, lo, hi = r[0], -np.inf, np.inf
        for e in (r[3] - r[0], r[1] - r[0]):
            ee = np.dot(e, e)
            m = tol / math.sqrt(ee)
            a0, a1 = np.dot(p0 - o, e) / ee, np.dot(d, e) / ee
            if abs(a1) < 1e-15:
                if not (m < a0 < 1 - m):
                    return None
                continue
            t0, t1 = sorted(((m - a0) / a1, (1 - m - a0) / a1))
            lo, hi = max(lo, t0), min(hi, t1)
        return (lo, hi) if lo < hi else None

    ia, ib = interval(a), interval(b)
    return ia is not None and ib is not None and min(ia[1], ib[1]) - max(ia[0], ib[0]) > tol


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--no-crossing-check", action="store_true")
    ap.add_argument("--limits", action="store_true")
    a = ap.parse_args()
    d = a.dir
    m = meshio.read(d + "/mesh.vtu")
    quads = [c for c in m.cells if c.type == "quad"]
    check(len(quads) == 1 and len(m.cells) == 1, "VTU: quadrilaterals only")
    q = quads[0].data
    P = m.points[q]  # n x 4 x 3
    fid = m.cell_data["fault_id"][0] - 1  # the fault number, from 1
    n = len(q)
    sections, verts, rects, coord = read_eqsim(d + "/mesh.eqsim")
    check(len(rects) == n, "EQSim: %d rectangles, the VTU's %d" % (len(rects), n))
    V = np.array([[v[2], v[1], v[3]] for v in verts])  # lon/x, lat/y, depth
    bad_geom = bad_order = bad_sd = bad_trace = bad_exact = 0
    for i, r in enumerate(rects[:n]):
        c = V[[k - 1 for k in r[1]]]
        if coord == 1 and not np.array_equal(c, P[i]):
            bad_exact += 1
        p = P[i]
        e1, e2, e3, e4 = p[1] - p[0], p[2] - p[1], p[3] - p[2], p[0] - p[3]
        L = max(np.linalg.norm(e2), 1e-9)
        ok = (abs(np.dot(e1, e2)) <= 1e-6 * L * L and np.allclose(e1, -e3, atol=1e-6 * L)
              and np.allclose(e2, -e4, atol=1e-6 * L) and abs(p[0][2] - p[3][2]) <= 1e-6 * L)
        bad_geom += not ok
        nrm = np.cross(p[1] - p[0], p[3] - p[0])
        bad_order += nrm[2] < -1e-9 * L * L
        s, dp = strike_dip(p)
        if coord == 1 and (ang_diff(s, r[5]) > 0.01 and dp > 0.01 or abs(dp - r[6]) > 0.01):
            bad_sd += 1
        tr = [verts[k - 1][5] for k in r[1]]
        bad_trace += tr[1] != 0 or tr[2] != 0
    check(bad_exact == 0, "EQSim: %d rectangles' corners differ from the VTU's" % bad_exact)
    check(bad_geom == 0, "VTU: %d elements are not rectangles with a horizontal top" % bad_geom)
    check(bad_order == 0, "%d elements' corners run clockwise from above" % bad_order)
    check(bad_sd == 0, "EQSim: %d strikes/dips differ from their corners'" % bad_sd)
    check(bad_trace == 0, "EQSim: %d rectangles with trace flags on bottom corners" % bad_trace)
    # RSQSim rectangles
    rows = [l.split() for l in open(d + "/mesh.rsqsim") if l.strip()]
    check(all(len(x) == 10 for x in rows), "RSQSim: 10 columns on every line (rectangles)")
    R = np.array([[float(v) for v in x[:9]] + [int(x[9])] for x in rows])
    check(len(R) == n, "RSQSim: %d lines for %d elements" % (len(R), n))
    if len(R) == n:
        cen = P.mean(axis=1)
        Ls = np.linalg.norm(P[:, 3] - P[:, 0], axis=1)
        Ws = np.linalg.norm(P[:, 1] - P[:, 0], axis=1)
        check(np.allclose(R[:, :3], cen, atol=1e-6), "RSQSim: centres are the corners' means")
        check(np.allclose(R[:, 3], Ls, rtol=1e-9) and np.allclose(R[:, 4], Ws, rtol=1e-9),
              "RSQSim: L and W are the sides")
        check(np.array_equal(R[:, 9].astype(int), fid + 1), "RSQSim: section = fault index + 1")
        er = np.array([[r[2], r[3]] for r in rects])
        check(np.allclose(R[:, 7], er[:, 0]) and np.allclose(R[:, 8], er[:, 1]),
              "RSQSim: rake and slip rate as the EQSim's")
        check(bool(np.all((R[:, 5] >= 0) & (R[:, 5] < 360) & (R[:, 6] >= 0) & (R[:, 6] <= 90))),
              "RSQSim: strike in [0, 360), dip in [0, 90]")
    # no two faults' rectangles meet
    if not a.no_crossing_check:
        lo, hi = P.min(axis=1), P.max(axis=1)
        cell = float(np.max(hi - lo)) + 1
        grid = {}
        for i in range(n):
            for key in {tuple(((lo[i] + (hi[i] - lo[i]) * f) // cell).astype(int))
                        for f in (0, 1)}:
                grid.setdefault(key, []).append(i)
        meet = 0
        seen = set()
        for i in range(n):
            k0 = (lo[i] // cell).astype(int)
            for dx in (-1, 0, 1):
                for dy in (-1, 0, 1):
                    for dz in (-1, 0, 1):
                        for j in grid.get((k0[0] + dx, k0[1] + dy, k0[2] + dz), ()):
                            if j <= i or fid[j] == fid[i] or (i, j) in seen:
                                continue
                            seen.add((i, j))
                            if np.all(lo[i] <= hi[j]) and np.all(lo[j] <= hi[i]) and \
                                    rect_meets(P[i], P[j]):
                                meet += 1
        check(meet == 0, "%d pairs of rectangles of different faults meet" % meet)
    rep = json.load(open(d + "/report.json"))
    rr = rep.get("rectangles")
    if check(rr is not None, "report.json: rectangles"):
        check(rr["elements"] == n and rr["meeting_pairs"] == 0,
              "report.json: %d elements, %d meeting" % (rr["elements"], rr["meeting_pairs"]))
        if a.limits:
            H = rr["size_m"]
            # every fault with surface: one with no rectangle left (ratio 0)
            # is outside too
            fs = [f for f in rr["faults"] if f["area_triangles_m2"] > 0]
            out = [f for f in fs if abs(f["area_ratio"] - 1) > 0.03]
            tot = sum(f["area_triangles_m2"] for f in fs)
            til = sum(f["area_rectangles_m2"] for f in fs)
            print("area: all faults %.4f of the triangles'; %d of %d faults outside 3 %%"
                  % (til / tot, len(out), len(fs)))
            for f in sorted(out, key=lambda f: f["area_ratio"]):
                print("  area %.4f  %s" % (f["area_ratio"], f["name"]))
            check(not out, "%d of %d faults outside 3 %% of their area" % (len(out), len(fs)))
            print("flatness p99 %.1f m = %.3f of the size (target 0.05)"
                  % (rr["flatness_p99_m"], rr["flatness_p99_of_size"]))
            check(rr["flatness_p99_of_size"] <= 0.05,
                  "flatness p99 %.3f of the size, over 0.05" % rr["flatness_p99_of_size"])
            js = rr["junctions"]
            print("junction gaps: max %.0f m; %d of %d junctions over size / 2, over %.1f of "
                  "%.1f km" % (rr["junction_gap_max_m"], rr["junctions_with_gap_over_half_size"],
                               len(js), sum(j["length_gap_over_half_size_m"] for j in js) / 1e3,
                               sum(j["length_m"] for j in js) / 1e3))
            over = [j for j in js if j["gap_max_m"] > H / 2]
            check(not over and rr["junctions_with_gap_over_half_size"] == 0,
                  "%d junctions with a gap over size / 2: %s" % (len(over), ", ".join(
                      "%s / %s %.0f m" % (j["a"], j["b"], j["gap_max_m"]) for j in over)))
    print("%d rectangles in %d sections: %s" % (n, len(sections), "ok" if not fails else
                                               "%d failures" % fails))
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
