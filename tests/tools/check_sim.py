#!/usr/bin/python3
"""Independent check of the simulator outputs of `faultmesh remesh`/`demo`.

Written from the formats' documented semantics (docs/formats.md: "RSQSim fault
file", "EQSim input geometry", "Element attributes"), not from the writer:

RSQSim (mesh.rsqsim): one triangle per line, `x1 y1 z1 x2 y2 z2 x3 y3 z3
  rake slip_rate sect_num sect_name`; read back, every triangle must be a
  triangle of the VTU (meshio) of the same fault, in the fault's mesh
  order, faults in index order, with its corners exactly equal, ordered so
  that the normal (p2 - p1) x (p3 - p1) points up (a vertical one: strike
  in [0, 180)); rake and slip rate (m/s) those the rules give (below),
  section number = fault index + 1, section name = the fault name as one
  token.
EQSim (mesh.eqsim): the container (101 signature and spec level first,
  metadata, 102, descriptors 120/121 with the field counts of records
  200-203, 103, data, 999 End last), record 200 and 201 counts and bounds
  against the data, vertex and triangle indices consecutive from 1, every
  triangle's corners in its own section; vertices against the VTU:
  spherical (coord_sys 0): the VTU point converted with pyproj (the input
  CRS to EPSG:4326) within 1e-6 degrees, depth = z exactly; rectangular:
  lat = y and lon = x exactly; strike and dip recomputed from the file's
  corners (spherical: geodetic to ECEF with pyproj, then a local east-
  north-up frame) within 0.1 degree (strike only where dip >= 1 degree,
  below which it is ill-defined), corners counterclockwise seen from above;
  das a distance along one horizontal direction (a linear function of
  position with a unit gradient, 0 at its lowest); trace flags 0-3 with one
  2 at the lowest and one 3 at the highest das of the trace.
VTU cell arrays strike, dip (grid north) recomputed from the geometry
  within 0.1 degree; rake, slip_rate equal to the RSQSim values.
report.json: per fault "attributes" agree with all of the above.

Rules for rake and slip rate, re-implemented from docs/formats.md: a --slip
rule (exact name first, else the first glob in file order; the name as it
is or without a trailing _<digits>m), else the rake of the metadata's Slip
Sense code, else 180 degrees; slip rate mm/yr from the rule, else 0;
m/s = mm/yr / 1000 / (365.25 * 86400).

Usage: check_sim.py DIR [--slip CSV] [--metadata CSV] [--expect-coords
spherical|rectangular] ; exit 0 when everything agrees, 1 otherwise, 77
without meshio, numpy or pyproj.
"""
import argparse
import csv
import fnmatch
import json
import math
import os
import re
import sys

from fm_short_names import short_names
import warnings

# pyproj warns that grids it would rank higher are not installed: that is
# the point of the file naming the operation it used.
warnings.filterwarnings("ignore", message="Best transformation is not available")

try:
    import meshio
    import numpy as np
    import pyproj
except ImportError as e:
    print("%s: skipped" % e)
    sys.exit(77)

failures = []


def check(cond, what):
    print(("ok    " if cond else "FAIL  ") + what)
    if not cond:
        failures.append(what)


SENSE_RAKE = {"rlss": 180, "llss": 0, "r": 90, "t": 90, "n": -90, "orlr": 135, "ollr": 45,
              "orln": -135, "olln": -45, "right-lateral": 180, "left-lateral": 0,
              "reverse": 90, "thrust": 90, "normal": -90, "strike-slip": 180}
YEAR = 365.25 * 86400


def base_name(name):
    m = re.match(r"^(.*)_\d+m$", name)
    return m.group(1) if m and m.group(1) else None


def read_metadata(path):
    with open(path, newline="", encoding="utf-8-sig") as f:
        rows = list(csv.reader(f))
    head = rows[0]
    ni = next(i for i, h in enumerate(head) if "Fault Object Name" in h)
    si = head.index("Slip Sense")
    out = {}
    for r in rows[1:]:
        if not any(c.strip() for c in r[1:]):
            continue
        out[r[ni].strip()] = r[si].strip()
    return out


def read_rules(path):
    rules = []
    with open(path, newline="", encoding="utf-8-sig") as f:
        first = True
        for r in csv.reader(f):
            if not r or not any(c.strip() for c in r) or r[0].strip().startswith("#"):
                continue
            pat, rake, rate = (c.strip() for c in r[:3])
            try:
                rake_v = float(rake) if rake else None
            except ValueError:
                if first:
                    first = False
                    continue
                raise
            first = False
            rules.append((pat, rake_v, float(rate) if rate else None))
    return rules


def expected_slip(name, md, rules):
    sense = None
    if md is not None:
        sense = md.get(name)
        if sense is None and base_name(name):
            sense = md.get(base_name(name))
    rake = SENSE_RAKE.get((sense or "").lower(), 180.0)
    rate = 0.0
    cands = [name] + ([base_name(name)] if base_name(name) else [])
    hit = None
    for pat, rk, rt in rules:
        if not any(c in pat for c in "*?[") and pat in cands:
            hit = (rk, rt)
            break
    if hit is None:
        for pat, rk, rt in rules:
            if any(c in pat for c in "*?[") and any(fnmatch.fnmatchcase(c, pat) for c in cands):
                hit = (rk, rt)
                break
    if hit:
        if hit[0] is not None:
            rake = hit[0]
        if hit[1] is not None:
            rate = hit[1]
    rake = math.fmod(rake, 360.0)
    if rake > 180:
        rake -= 360
    elif rake <= -180:
        rake += 360
    return rake, rate


def strike_dip(n):
    """Strike (clockwise from the frame's north, [0, 360)) and dip of a
    plane whose normal n (east, north, up) is taken as the upward one."""
    h = math.hypot(n[0], n[1])
    dip = math.degrees(math.atan2(h, abs(n[2])))
    strike = (math.degrees(math.atan2(n[0], n[1])) - 90) % 360 if h > 0 else 0.0
    return strike, dip


def angle_diff(a, b):
    return abs((a - b + 180) % 360 - 180)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--slip")
    ap.add_argument("--metadata")
    ap.add_argument("--expect-coords", choices=["spherical", "rectangular"])
    a = ap.parse_args()
    d = a.dir
    rep = json.load(open(os.path.join(d, "report.json")))
    crs = rep["options"]["crs"]
    faults = [f for f in rep["faults"] if "attributes" in f]
    faults.sort(key=lambda f: f["attributes"]["section"])
    nf = len(faults)
    names = [f["name"] for f in faults]
    check([f["attributes"]["section"] for f in faults] == list(range(1, nf + 1)),
          "report.json: sections 1..%d, one per meshed fault" % nf)
    md = read_metadata(a.metadata) if a.metadata else None
    rules = read_rules(a.slip) if a.slip else []
    exp = [expected_slip(n, md, rules) for n in names]
    bad = [n for n, e, f in zip(names, exp, faults)
           if abs(f["attributes"]["rake_deg"] - e[0]) > 1e-12
           or abs(f["attributes"]["slip_rate_mm_yr"] - e[1]) > 1e-12
           or abs(f["attributes"]["slip_rate_m_s"] - e[1] / 1000 / YEAR) > 1e-9 * e[1] / 1000 / YEAR]
    check(not bad, "report.json: rake and slip rate of every fault as the rules give (%d faults)%s"
          % (nf, "; first wrong: " + bad[0] if bad else ""))
    unknown = sum(1 for f in faults if f["attributes"]["rake_from"] == "default")
    warned = sum(1 for f in faults if f["attributes"]["rake_from"] == "default"
                 and any("rake unknown" in w for w in f["attributes"]["warnings"]))
    check(unknown == warned, "report.json: each of the %d faults with the default rake has a warning"
          % unknown)
    no_rate = sum(1 for f in faults if f["attributes"]["slip_rate_from"] == "default")
    rate_warned = sum(1 for f in faults if f["attributes"]["slip_rate_from"] == "default"
                      and any("slip rate unknown" in w for w in f["attributes"]["warnings"]))
    check(no_rate == rate_warned and rep["simulator"]["slip_rate_default"] == no_rate and
          rep["simulator"]["rake_default"] == unknown,
          "report.json: each of the %d faults with the default slip rate has a warning; "
          "the summary counts agree" % no_rate)

    # --- VTU (meshio): the reference geometry ---
    m = meshio.read(os.path.join(d, "mesh.vtu"))
    pts = np.asarray(m.points, dtype=float)
    tri = np.asarray(m.cells_dict["triangle"])
    cd = {k: np.asarray(v[0]).ravel() for k, v in m.cell_data.items()}
    fid = cd["fault_id"].astype(int) - 1  # the fault number, from 1
    nt = len(tri)
    print("VTU: %d points, %d triangles, %d faults" % (len(pts), nt, nf))
    P = pts[tri]  # nt x 3 x 3
    nrm = np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0])
    ln = np.linalg.norm(nrm, axis=1)
    vertical = np.abs(nrm[:, 2]) <= 1e-9 * ln
    up = np.where((nrm[:, 2] < 0)[:, None], -nrm, nrm)
    h = np.hypot(up[:, 0], up[:, 1])
    dip = np.degrees(np.arctan2(h, np.abs(up[:, 2])))
    strike = np.where(h > 0, (np.degrees(np.arctan2(up[:, 0], up[:, 1])) - 90) % 360, 0.0)
    strike = np.where(vertical, strike % 180, strike)
    ds = np.abs((cd["strike"] - strike + 180) % 360 - 180)
    ds = np.where(dip >= 1, ds, 0)
    check(float(np.max(np.abs(cd["dip"] - dip))) < 0.1 and float(np.max(ds)) < 0.1,
          "VTU strike/dip = recomputed from the geometry (max diff %.2g / %.2g deg)"
          % (float(np.max(ds)), float(np.max(np.abs(cd["dip"] - dip)))))
    check(float(np.max(cd["dip"])) <= 90 and float(np.min(cd["dip"])) >= 0 and
          float(np.min(cd["strike"])) >= 0 and float(np.max(cd["strike"])) < 360,
          "VTU dip in [0, 90], strike in [0, 360)")
    rk = np.array([exp[i][0] for i in range(nf)])
    rt = np.array([exp[i][1] / 1000 / YEAR for i in range(nf)])
    check(np.array_equal(cd["rake"], rk[fid]) and np.allclose(cd["slip_rate"], rt[fid], rtol=1e-12, atol=0),
          "VTU rake and slip_rate per triangle = the fault's")
    order = np.argsort(fid, kind="stable")  # faults in index order, mesh order within

    # --- RSQSim ---
    lines = open(os.path.join(d, "mesh.rsqsim")).read().split("\n")
    check(lines[-1] == "", "RSQSim: ends with a newline")
    lines = lines[:-1]
    check(len(lines) == nt, "RSQSim: one line per triangle (%d)" % len(lines))
    ok_fields = all(len(l.split()) == 13 for l in lines)
    check(ok_fields, "RSQSim: 13 whitespace-separated fields per line")
    if ok_fields and len(lines) == nt:
        cols = [l.split() for l in lines]
        xyz = np.array([[float(v) for v in c[:9]] for c in cols]).reshape(nt, 3, 3)
        rrake = np.array([float(c[9]) for c in cols])
        rrate = np.array([float(c[10]) for c in cols])
        sect = np.array([int(c[11]) for c in cols])
        sname = [c[12] for c in cols]
        ref = P[order]
        swapped = ref[:, [0, 2, 1]]
        same = np.all(xyz == ref, axis=(1, 2))
        same_sw = np.all(xyz == swapped, axis=(1, 2))
        check(bool(np.all(same | same_sw)),
              "RSQSim: every triangle = the VTU's (fault order, mesh order; corners exact, "
              "%d re-ordered)" % int(np.sum(~same)))
        rn = np.cross(xyz[:, 1] - xyz[:, 0], xyz[:, 2] - xyz[:, 0])
        rl = np.linalg.norm(rn, axis=1)
        rvert = np.abs(rn[:, 2]) <= 1e-9 * rl
        st_v = (np.degrees(np.arctan2(rn[:, 0], rn[:, 1])) - 90) % 360
        good = np.where(rvert, (st_v < 180) | (st_v > 360 - 1e-9), rn[:, 2] > 0)
        check(bool(np.all(good | (rl == 0))),
              "RSQSim: every normal points up (vertical: strike in [0, 180)); %d vertical"
              % int(np.sum(rvert)))
        check(np.array_equal(sect, fid[order] + 1), "RSQSim: sect_num = fault index + 1")
        short = short_names(names, 50)
        check(all(s == short[k - 1] for s, k in zip(sname, sect)),
              "RSQSim: sect_name = the fault name by the short-name rule (50)")
        check(max(len(s) for s in short) <= 50 and len(set(short)) == len(short),
              "RSQSim: section names at most 50 characters, unique")
        # as rsqsim-python-tools reads it: genfromtxt, the name as U50
        g = np.genfromtxt(os.path.join(d, "mesh.rsqsim"), dtype=None, encoding="utf-8",
                          names=["x1", "y1", "z1", "x2", "y2", "z2", "x3", "y3", "z3", "rake",
                                 "slip_rate", "fault_num", "fault_name"],
                          converters={12: lambda b: b}, autostrip=True)
        got = {}
        for num, nm in zip(np.atleast_1d(g["fault_num"]), np.atleast_1d(g["fault_name"])):
            got.setdefault(int(num), set()).add(str(np.str_(nm)[:50]))
        check(all(got.get(k + 1) == {short[k]} for k in range(nf)) and
              len({next(iter(v)) for v in got.values()}) == len(got),
              "RSQSim read as rsqsim-python-tools does (U50): one distinct name per section")
        # names.csv leads from each short name back to the full one
        with open(os.path.join(d, "names.csv"), newline="") as fp:
            rows = list(csv.DictReader(fp))
        check(len(rows) == nf and
              all(r["number"] == str(k + 1) and r["name"] == names[k] and
                  r["section_name"] == short[k] and
                  r["exodus_name"] == short_names(names, 32)[k] and
                  os.path.isfile(os.path.join(d, r["tsurf_file"])) for k, r in enumerate(rows)),
              "names.csv: number, full name, TSurf file, section and Exodus names of every fault")
        check(np.array_equal(rrake, rk[fid[order]]) and
              np.allclose(rrate, rt[fid[order]], rtol=1e-15, atol=0),
              "RSQSim: rake (deg) and slip rate (m/s) as the rules give")
        check(float(np.max(xyz[:, :, 2])) <= float(np.max(pts[:, 2])),
              "RSQSim: z is elevation (max %.1f m)" % float(np.max(xyz[:, :, 2])))

    # --- EQSim ---
    recs = [l.split(None, 1) for l in open(os.path.join(d, "mesh.eqsim")).read().split("\n") if l]
    kinds = [int(r[0]) for r in recs]
    check(recs[0][0] == "101" and recs[0][1].split()[:2] == ["EQSim_Input_Geometry_2", "4"],
          "EQSim: signature EQSim_Input_Geometry_2, spec level 4")
    check(kinds[-1] == 999, "EQSim: 999 End last")
    i102, i103 = kinds.index(102), kinds.index(103)
    check(all(k in (110, 111, 112, 113) for k in kinds[1:i102]), "EQSim: metadata records before 102")
    desc = {}
    cur = None
    for r in recs[i102 + 1:i103]:
        f = r[1].split()
        if r[0] == "120":
            cur = int(f[0])
            desc[cur] = (int(f[2]), [])
        elif r[0] == "121":
            desc[cur][1].append((int(f[0]), f[1], int(f[2])))
        else:
            check(False, "EQSim: only 120/121 between 102 and 103")
    want = {200: 11, 201: 14, 202: 6, 203: 9}
    check(all(k in desc and desc[k][0] == n and [x[0] for x in desc[k][1]] == list(range(1, n + 1))
              for k, n in want.items()),
          "EQSim: descriptors of records 200-203 with 11/14/6/9 fields")
    data = recs[i103 + 1:-1]
    check(data and data[0][0] == "200" and sum(1 for r in data if r[0] == "200") == 1,
          "EQSim: one 200 summary first")
    s200 = data[0][1].split()
    coord = int(s200[10])
    sph = coord == 0
    if a.expect_coords:
        check(sph == (a.expect_coords == "spherical"), "EQSim: coord_sys %d (%s)" % (coord, a.expect_coords))
    sections, cur = [], None
    for r in data[1:]:
        f = r[1].split()
        if r[0] == "201":
            cur = {"f": f, "v": [], "t": []}
            sections.append(cur)
        elif r[0] == "202":
            cur["v"].append([int(f[0]), float(f[1]), float(f[2]), float(f[3]), float(f[4]), int(f[5])])
        elif r[0] == "203":
            cur["t"].append([int(f[0]), int(f[1]), int(f[2]), int(f[3])] + [float(x) for x in f[4:9]])
        else:
            check(False, "EQSim: unexpected record %s" % r[0])
    check(len(sections) == nf == int(s200[0]), "EQSim: %d sections (200 says %s)" % (len(sections), s200[0]))
    allv = [v for s in sections for v in s["v"]]
    allt = [t for s in sections for t in s["t"]]
    check([v[0] for v in allv] == list(range(1, len(allv) + 1)) and len(allv) == int(s200[1]),
          "EQSim: %d vertices numbered 1.. (200 says %s)" % (len(allv), s200[1]))
    check([t[0] for t in allt] == list(range(1, len(allt) + 1)) and len(allt) == int(s200[2]) == nt
          and int(s200[3]) == 0, "EQSim: %d triangles numbered 1.., no rectangles" % len(allt))
    V = np.array([v[1:5] for v in allv])
    check(float(s200[4]) == V[:, 0].min() and float(s200[5]) == V[:, 0].max() and
          float(s200[6]) == V[:, 1].min() and float(s200[7]) == V[:, 1].max() and
          float(s200[8]) == V[:, 2].min() and float(s200[9]) == V[:, 2].max(),
          "EQSim: 200 bounds = the vertices'")
    if sph:
        # The file names the one PROJ operation it used for every vertex and
        # gives its pipeline: it must be one of PROJ's own candidates from
        # the input CRS to EPSG:4326, and pyproj runs it here.
        meta = [r[1] for r in recs[:i102] if r[0] == "110"]
        opname = next((m.split(": ", 1)[1].rsplit(", accuracy", 1)[0] for m in meta
                       if m.startswith("PROJ operation")), None)
        pipe = next((m.split(": ", 1)[1] for m in meta if m.startswith("PROJ pipeline")), None)
        group = pyproj.transformer.TransformerGroup(crs, "EPSG:4326", always_xy=True)
        op_names = [t.description.split(" + axis order change")[0] for t in group.transformers]
        check(opname in op_names, "EQSim: the PROJ operation named (%s) is one of PROJ's for %s to "
              "EPSG:4326" % (opname, crs))
        check(pipe is not None, "EQSim: a 110 record gives the PROJ pipeline")
        if pipe is None:
            print("%d FAILED" % len(failures))
            return 1
        tr = pyproj.Transformer.from_pipeline(pipe)
        lon_r, lat_r = tr.transform(pts[:, 0], pts[:, 1])
        ll = np.column_stack([lat_r, lon_r])
        # pyproj's default transformer picks per point (another shift
        # offshore): within 1e-4 degrees (10 m) all the same.
        d_lon, d_lat = pyproj.Transformer.from_crs(crs, "EPSG:4326", always_xy=True).transform(
            pts[:, 0], pts[:, 1])
        dd = float(np.max(np.hypot(d_lon - lon_r, d_lat - lat_r)))
        check(dd < 1e-4, "EQSim: pyproj's per-point default within %.2g deg of the file's one "
              "operation" % dd)
        ecef = pyproj.Transformer.from_crs("EPSG:4979", "EPSG:4978", always_xy=True)
    else:
        ll = np.column_stack([pts[:, 1], pts[:, 0]])
    worst_ll, worst_sd, bad_sec, bad_tri, bad_das, bad_trace, bad_slip = 0.0, [0.0, 0.0], [], 0, [], [], 0
    ti = 0
    for k, s in enumerate(sections):
        f = s["f"]
        sid, nm = int(f[0]), f[1]
        nv, ntri = int(f[2]), int(f[3])
        mine = order[ti:ti + ntri]
        ti += ntri
        vv = np.array([v[1:5] for v in s["v"]]) if s["v"] else np.zeros((0, 4))
        idx = {v[0]: j for j, v in enumerate(s["v"])}
        ok = (sid == k + 1 and int(f[13]) == k + 1 and nm == short_names(names, 50)[k] and nv == len(s["v"])
              and ntri == len(s["t"]) and int(f[4]) == 0 and np.all(fid[mine] == k))
        ok = ok and float(f[5]) == vv[:, 0].min() and float(f[6]) == vv[:, 0].max() and \
            float(f[7]) == vv[:, 1].min() and float(f[8]) == vv[:, 1].max() and \
            float(f[9]) == vv[:, 2].min() and float(f[10]) == vv[:, 2].max() and \
            float(f[11]) == 0 and float(f[12]) == vv[:, 3].max() and vv[:, 3].min() == 0
        used = np.unique(tri[mine])
        ok = ok and len(used) == nv
        if not ok:
            bad_sec.append(nm)
        corners = np.array([[idx.get(t[c], -1) for c in (1, 2, 3)] for t in s["t"]])
        if np.any(corners < 0):
            bad_tri += 1
            continue
        ref = tri[mine]
        # Each triangle's corners against the VTU triangle (as is or with the
        # last two swapped): coordinates within 1e-6 degrees (spherical) or
        # exact (rectangular), depth exact.
        got = vv[corners]  # ntri x 3 x 4
        a0 = ll[ref]
        a1 = ll[ref[:, [0, 2, 1]]]
        z0 = pts[ref][:, :, 2]
        z1 = pts[ref[:, [0, 2, 1]]][:, :, 2]
        e0 = np.max(np.abs(got[:, :, :2] - a0), axis=(1, 2))
        e1 = np.max(np.abs(got[:, :, :2] - a1), axis=(1, 2))
        m0 = (e0 <= (1e-6 if sph else 0)) & np.all(got[:, :, 2] == z0, axis=1)
        m1 = (e1 <= (1e-6 if sph else 0)) & np.all(got[:, :, 2] == z1, axis=1)
        if not np.all(m0 | m1):
            bad_tri += int(np.sum(~(m0 | m1)))
        worst_ll = max(worst_ll, float(np.max(np.minimum(e0, e1))) if len(e0) else 0.0)
        # Strike and dip from the file's own corners.
        if sph:
            X, Y, Z = ecef.transform(got[:, :, 1].ravel(), got[:, :, 0].ravel(), got[:, :, 2].ravel())
            E = np.column_stack([X, Y, Z]).reshape(-1, 3, 3)
            c = E.mean(axis=1)
            lat_c = np.radians(got[:, :, 0].mean(axis=1))
            lon_c = np.radians(got[:, :, 1].mean(axis=1))
            east = np.column_stack([-np.sin(lon_c), np.cos(lon_c), np.zeros_like(lon_c)])
            north = np.column_stack([-np.sin(lat_c) * np.cos(lon_c), -np.sin(lat_c) * np.sin(lon_c), np.cos(lat_c)])
            upv = np.column_stack([np.cos(lat_c) * np.cos(lon_c), np.cos(lat_c) * np.sin(lon_c), np.sin(lat_c)])
            loc = E - c[:, None, :]
            L = np.stack([np.einsum("ijk,ik->ij", loc, east), np.einsum("ijk,ik->ij", loc, north),
                          np.einsum("ijk,ik->ij", loc, upv)], axis=2)
        else:
            L = got[:, :, [1, 0, 2]].copy()
        n = np.cross(L[:, 1] - L[:, 0], L[:, 2] - L[:, 0])
        tt = np.array([t[4:9] for t in s["t"]])
        for j in range(len(n)):
            st, dp = strike_dip(n[j])
            nl = np.linalg.norm(n[j])
            if nl == 0:
                continue
            if n[j][2] < -1e-6 * nl:
                bad_tri += 1
            worst_sd[1] = max(worst_sd[1], abs(dp - tt[j, 4]))
            if dp >= 1:
                worst_sd[0] = max(worst_sd[0], angle_diff(st, tt[j, 3]))
        if not (np.all(tt[:, 0] == rk[k]) and np.allclose(tt[:, 1], rt[k], rtol=1e-15, atol=0)
                and np.all(tt[:, 2] == 0)):
            bad_slip += 1
        # das: distance along the section's mean strike (the report's, given
        # to 10 digits: 1e-3 m over a fault's length), 0 at its lowest.
        das = vv[:, 3]
        az = math.radians(faults[k]["attributes"]["mean_strike_deg"])
        xy = pts[used][:, :2]
        pred = math.sin(az) * xy[:, 0] + math.cos(az) * xy[:, 1]
        pred -= pred.min()
        if len(das) and float(np.max(np.abs(pred - das))) > 1e-3 + 1e-9 * float(das.max()):
            bad_das.append("%s (off by %.3g m)" % (nm, float(np.max(np.abs(pred - das)))))
        fl = np.array([v[5] for v in s["v"]])
        tr_idx = np.where(fl > 0)[0]
        if len(tr_idx):
            dt = das[tr_idx]
            okt = (np.sum(fl == 2) == 1 and np.sum(fl == 3) == 1 and
                   das[fl == 2][0] == dt.min() and das[fl == 3][0] == dt.max() and np.all(fl <= 3))
            if not okt:
                bad_trace.append(nm)
    check(not bad_sec, "EQSim: every 201 (sid, fault_id, name token, counts, bounds, das range) "
          "agrees with its data and the VTU%s" % (": " + bad_sec[0] if bad_sec else ""))
    check(bad_tri == 0, "EQSim: every triangle's corners = the VTU's, in its section, counterclockwise "
          "from above (%d bad)" % bad_tri)
    check(worst_ll <= (1e-6 if sph else 0),
          "EQSim: vertices %s (worst %.3g)" % ("within 1e-6 deg of pyproj's conversion from " + crs
                                               if sph else "= the VTU's y, x exactly", worst_ll))
    check(worst_sd[0] < 0.1 and worst_sd[1] < 0.1,
          "EQSim: strike/dip = recomputed from the corners (worst %.3g / %.3g deg)" % tuple(worst_sd))
    check(bad_slip == 0, "EQSim: rake, slip rate, aseismic factor 0 per triangle")
    check(not bad_das, "EQSim: das along the report's mean strike, 0 at its lowest%s"
          % (": " + bad_das[0] if bad_das else ""))
    ntrace = sum(1 for s in sections if any(v[5] for v in s["v"]))
    check(not bad_trace, "EQSim: trace flags (one 2 at the lowest das, one 3 at the highest); "
          "%d sections with a trace" % ntrace)
    if failures:
        print("%d FAILED" % len(failures))
        return 1
    print("all passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
