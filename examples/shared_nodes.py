#!/usr/bin/python3
"""Remeshes two faults with the faultmesh Python package and prints the
nodes they share: where two faults meet, their meshes are joined, so the
nodes along the junction belong to both.

    shared_nodes.py [--size M] [A.ts B.ts]

Without files: two faults of the SCEC CFM 5.3 (500 m set) that meet, read
from ../shared/cfm as seen from the repository's root. The package is
found on sys.path (an installed faultmesh), else in ../python beside this
script (the source tree, with the library in build/).
"""

import os
import sys

try:
    import faultmesh
except ImportError:
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
    import faultmesh

CFM = "../shared/cfm/CFM5.3/500m/"
DEFAULT = [CFM + "OCBA-CBFZ-NCBF-Coronado_Bank_fault_north-CFM5_500m.ts",
           CFM + "OCBA-CBFZ-WEST-Coronado_Bank_west_splay-CFM5_500m.ts"]


def say(level, message):
    """The run's warnings and errors, as the command line shows them."""
    if level <= faultmesh.LOG_WARN:
        print("faultmesh: " + message, file=sys.stderr)


def main(argv):
    size = 1000.0
    if len(argv) >= 2 and argv[0] == "--size":
        size = float(argv[1])
        argv = argv[2:]
    if len(argv) not in (0, 2):
        print("usage: shared_nodes.py [--size M] [A.ts B.ts]", file=sys.stderr)
        return 2
    paths = argv or DEFAULT
    try:
        res = faultmesh.remesh(paths, size=size, log=say)
    except faultmesh.FaultmeshError as e:
        print("faultmesh: %s" % e, file=sys.stderr)
        return 1
    for f in res.faults:
        print("fault %d: %s: %s%s" % (f.index, f.name, f.status, ": " + f.why if f.why else ""))
    shared = res.shared_nodes(0, 1)
    print("shared nodes: %d" % len(shared))
    for x, y, z in res.points[shared]:
        print("  %.3f %.3f %.3f" % (x, y, z))
    # each fault's mesh goes on to meshio as it is (its own node numbering)
    m = res.faults[0].to_meshio()
    assert len(m.cells[0].data) == len(res.faults[0].triangles)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
