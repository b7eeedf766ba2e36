#!/usr/bin/python3
"""The Python package (python/faultmesh) on the build tree's library:
results as the library and report.json give them, faults handed back in
memory, meshio, outputs, option errors, cancelling, the log.

usage: python_package_test.py FAULTMESH LIBFAULTMESH.so TMPDIR
(FAULTMESH: the CLI, which makes the synthetic faults)
"""

import glob
import os
import shutil
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "python"))


def main(cli, lib, tmp):
    os.environ["FAULTMESH_LIBRARY"] = lib
    os.environ["XDG_CACHE_HOME"] = os.path.join(tmp, "cache")
    import numpy as np

    import faultmesh

    shutil.rmtree(tmp, ignore_errors=True)
    os.makedirs(tmp)
    subprocess.run([cli, "synth", "-o", os.path.join(tmp, "synth")], check=True,
                   stdout=subprocess.DEVNULL)
    files = sorted(glob.glob(os.path.join(tmp, "synth", "*.ts")))
    fails = []

    def check(cond, what):
        if not cond:
            fails.append(what)
            print("FAIL:", what)

    check(faultmesh.version() == faultmesh._lib_handle().fm_version_string().decode(), "version")
    logged = []
    whole = os.path.join(tmp, "whole")
    res = faultmesh.remesh(files, size=2000, threads=2, out=whole, formats=["obj"],
                           log=lambda lv, m: logged.append(lv))
    check(len(res.faults) == len(files), "a fault per file")
    check(res.nfailed == 0, "no fault failed")
    check(all(f.status == "ok" for f in res.faults), "every fault ok")
    check(sum(len(f.triangles) for f in res.faults) == len(res.triangles),
          "per-fault triangles add up to the set's")
    check(res.report["summary"]["triangles"] == len(res.triangles),
          "report.json's triangles are the mesh's")
    # nodes used by two faults or more, as mesh.obj has them (its faces
    # grouped by fault)
    owners = {}
    for f in res.faults:
        for v in f.vertices:
            owners[v] = owners.get(v, 0) + 1
    shared = sum(1 for n in owners.values() if n > 1)
    group, users = None, {}
    with open(os.path.join(whole, "mesh.obj")) as fp:
        for line in fp:
            if line.startswith("g "):
                group = line[2:].strip()
            elif line.startswith("f "):
                for v in line.split()[1:]:
                    users.setdefault(v.split("/")[0], set()).add(group)
    check(shared > 0 and shared == sum(1 for g in users.values() if len(g) > 1),
          "shared nodes as mesh.obj has them")
    for f in res.faults:
        check(np.array_equal(f.points[f.triangles], res.points[f.vertices[f.triangles]]),
              "%s: its mesh is the set's" % f.name)
        check(f.to_meshio().cells[0].data.shape == f.triangles.shape, "%s: meshio" % f.name)
    check(res.summary.startswith("\nsummary") or "summary" in res.summary, "the summary text")
    check(logged and all(1 <= lv <= 3 for lv in logged), "log records up to INFO")

    # faults in memory: the result's meshes handed back in
    again = faultmesh.remesh(res.faults[:2], size=2000, crs="EPSG:26711", threads=1)
    check([f.name for f in again.faults] == [f.name for f in res.faults[:2]],
          "in-memory faults keep their names")
    check(all(f.status == "ok" for f in again.faults), "in-memory faults mesh")

    # outputs into a folder, read back by meshio
    out = os.path.join(tmp, "out")
    res2 = faultmesh.remesh(files[:2], size=2000, out=out, formats=["vtu", "obj"])
    check(sorted(os.listdir(out)) == ["mesh.obj", "mesh.vtu", "report.json"],
          "only the formats asked for, and report.json: %s" % sorted(os.listdir(out)))
    import meshio

    m = meshio.read(os.path.join(out, "mesh.vtu"))
    check(len(m.points) == len(res2.points) and len(m.cells[0].data) == len(res2.triangles),
          "mesh.vtu holds the result's mesh")

    # bad options: refused before any work
    for kw, exc in (({"nonsense": 1}, TypeError), ({"size": -5}, faultmesh.FaultmeshError),
                    ({"top": "sideways"}, ValueError)):
        try:
            faultmesh.remesh(files[:1], **kw)
            check(False, "%s refused" % kw)
        except exc:
            pass
    try:
        faultmesh.remesh([("bad", np.zeros((3, 3)), np.array([[0, 1, 7]]))])
        check(False, "an index out of range refused")
    except faultmesh.FaultmeshError as e:
        check(e.status == 4 and "out of range" in str(e), "FM_ERR_INVALID, and why")

    # a progress callback that says stop cancels the run
    try:
        faultmesh.remesh(files, size=2000, progress=lambda stage, done, count: True)
        check(False, "cancelled")
    except faultmesh.FaultmeshError as e:
        check(e.status == 7, "FM_ERR_CANCELLED (%d)" % e.status)

    if fails:
        return 1
    print("ok: the Python package (%d faults, %d shared nodes)" % (len(res.faults), shared))
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))
