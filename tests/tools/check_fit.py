#!/usr/bin/python3
"""Checks `faultmesh fit` output against the fit issue's criteria.

usage: check_fit.py FAULTMESH OUTDIR [--criteria] [--readers N]
                    [--known-failures FILE] INPUT...

Runs the fit, then reads fit_report.json and every model file:
  - every fault of every input produced a model (no failures), except the
    faults listed in --known-failures (each with its reason), which must
    still fail: the list only shrinks;
  - each model JSON is complete (frame, knots and control points of the
    right sizes, trimming loops with pieces) and each file exists;
  - with --criteria (the CFM acceptance): per fault RMS <= 10 m and max
    <= 100 m both ways for >= 98 % of faults, median RMS <= 3 m, outline
    deviation <= 100 m; faults outside are listed;
  - with --readers N: for the first N faults, meshio reads the VTU (the
    triangle count agrees with the samples) and Gmsh/OpenCASCADE imports the
    IGES with one surface per sheet whose area agrees with the VTU's
    within 3 %. Readers that are not installed are skipped, said so.
Exit 0 when all holds, 1 otherwise, 77 when an input is absent.
"""
import json
import math
import os
import shutil
import subprocess
import sys


def tri_area(p, t):
    a, b, c = (p[i] for i in t)
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    return 0.5 * math.sqrt(sum(x * x for x in n))


def check_model(path, problems):
    with open(path) as f:
        m = json.load(f)
    if m.get("format") != "faultmesh-model" or not m.get("sheets"):
        problems.append(f"{path}: not a complete model")
        return 0
    for s in m["sheets"]:
        srf = s["surface"]
        deg, nu, nv = srf["degree"], srf["nu"], srf["nv"]
        if len(srf["knots_u"]) != nu + deg + 1 or len(srf["knots_v"]) != nv + deg + 1:
            problems.append(f"{path}: sheet {s['index']}: knot counts")
        if len(srf["control_points"]) != nu * nv:
            problems.append(f"{path}: sheet {s['index']}: control point count")
        loops = s["trimming_loops"]
        if not loops or loops[0]["role"] != "outer" or loops[0]["area_m2"] <= 0:
            problems.append(f"{path}: sheet {s['index']}: outer loop missing or not CCW")
        for l in loops[1:]:
            if l["role"] != "hole" or l["area_m2"] >= 0:
                problems.append(f"{path}: sheet {s['index']}: hole not CW")
        for l in loops:
            for pc in l["pieces"]:
                if len(pc["knots"]) != len(pc["control_points"]) + pc["degree"] + 1:
                    problems.append(f"{path}: sheet {s['index']}: trim piece knot count")
    return len(m["sheets"])


def check_readers(out, base, nsheets, problems, notes):
    try:
        import meshio
    except ImportError:
        notes.add("meshio not installed: VTU reading skipped")
        return
    mesh = meshio.read(os.path.join(out, base + ".vtu"))
    tris = [c for c in mesh.cells if c.type == "triangle"]
    if not tris:
        problems.append(f"{base}.vtu: no triangles")
        return
    pts = mesh.points.tolist()
    area = sum(tri_area(pts, t) for t in tris[0].data.tolist())
    try:
        import gmsh
    except ImportError:
        notes.add("gmsh not installed: IGES reading skipped")
        return
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    try:
        gmsh.model.add(base)
        gmsh.model.occ.importShapes(os.path.join(out, base + ".igs"))
        gmsh.model.occ.synchronize()
        surfaces = gmsh.model.getEntities(2)
        # OpenCASCADE converts the file's metres to its own unit
        # (millimetres): measure the scale from the bounding boxes.
        box = gmsh.model.getBoundingBox(-1, -1)
        lo = [min(p[k] for p in pts) for k in range(3)]
        hi = [max(p[k] for p in pts) for k in range(3)]
        scale = math.dist(box[:3], box[3:]) / math.dist(lo, hi)
        # the box may be the untrimmed surface's: snap to the unit factor
        scale = 1000.0 if scale > 30 else 1.0
        iges_area = sum(gmsh.model.occ.getMass(2, t) for _, t in surfaces) / scale ** 2
        if len(surfaces) != nsheets:
            problems.append(f"{base}.igs: {len(surfaces)} surfaces, expected {nsheets}")
        # OpenCASCADE integrates the trimmed area with a loose default
        # precision (seen 2.3 % low on a 670 km2 face, below even its
        # projected area): 3 % separates that from a wrong trim.
        if abs(iges_area - area) > 0.03 * area:
            problems.append(f"{base}.igs: area {iges_area:.0f} m2, VTU {area:.0f} m2")
    finally:
        gmsh.finalize()


def main():
    exe, out = sys.argv[1], sys.argv[2]
    args = sys.argv[3:]
    criteria = "--criteria" in args
    readers = 0
    if "--readers" in args:
        i = args.index("--readers")
        readers = int(args[i + 1])
        del args[i:i + 2]
    known = {}
    if "--known-failures" in args:
        i = args.index("--known-failures")
        with open(args[i + 1]) as f:
            for line in f:
                name, _, why = line.partition("#")
                if name.strip():
                    known[name.strip()] = why.strip()
        del args[i:i + 2]
    inputs = [a for a in args if a != "--criteria"]
    for p in inputs:
        if not os.path.exists(p):
            print(f"skipped: {p} does not exist")
            return 77
    run = subprocess.run([exe, "fit", "-o", out] + inputs, capture_output=True, text=True)
    problems, notes = [], set()
    if run.returncode != 0 and not known:
        problems.append(f"faultmesh fit exited {run.returncode}: {run.stderr.strip()[:2000]}")
    with open(os.path.join(out, "fit_report.json")) as f:
        report = json.load(f)
    faults = report["faults"]
    ok = [f for f in faults if f["status"] == "ok"]
    for f in faults:
        name = f.get("name") or f["file"]
        if f["status"] != "ok" and name not in known:
            problems.append(f"{name}: {f.get('error')}")
        elif f["status"] != "ok":
            print(f"known failure: {name}: {known[name]}")
        elif name in known:
            problems.append(f"{name} is listed as a known failure but now fits: "
                            "remove it from the list")
    checked = 0
    for f in ok:
        base = f["output"]
        for ext in (".model.json", ".igs", ".vtu"):
            if not os.path.exists(os.path.join(out, base + ext)):
                problems.append(f"{base}{ext} missing")
        n = check_model(os.path.join(out, base + ".model.json"), problems)
        if checked < readers:
            check_readers(out, base, n, problems, notes)
            checked += 1
    rms = sorted(max(f["to_surface_rms_m"], f["from_trimmed_rms_m"]) for f in ok)
    median = rms[len(rms) // 2] if rms else float("nan")
    inside = [f for f in ok if f["within_10_100"]]
    outline_bad = [f for f in ok if f["outline_max_m"] > 100]
    share = len(inside) / len(faults) if faults else 0
    print(f"faults {len(faults)}, models {len(ok)}, within 10 m RMS / 100 m max: "
          f"{len(inside)} ({100 * share:.1f}%), median RMS {median:.2f} m, "
          f"outline > 100 m: {len(outline_bad)}")
    for f in ok:
        if not f["within_10_100"] or f["outline_max_m"] > 100:
            print(f"  outside: {f['name']}: rms {f['to_surface_rms_m']:.1f}/"
                  f"{f['from_trimmed_rms_m']:.1f} m, max {f['to_surface_max_m']:.0f}/"
                  f"{f['from_trimmed_max_m']:.0f} m, outline {f['outline_max_m']:.0f} m")
    if criteria:
        if share < 0.98:
            problems.append(f"only {100 * share:.1f}% of faults within 10/100 m (need 98%)")
        if median > 3.0:
            problems.append(f"median RMS {median:.2f} m (need <= 3 m)")
        if outline_bad:
            problems.append(f"{len(outline_bad)} faults with outline deviation > 100 m")
    for n in sorted(notes):
        print(n)
    for p in problems:
        print("FAIL:", p)
    print(f"fit check: {len(problems)} problems")
    if not problems:
        # the whole CFM writes ~2 GB of models; keep them only to debug
        shutil.rmtree(out, ignore_errors=True)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
