#!/usr/bin/python3
"""Independent check of the IGES writer: Gmsh (OpenCASCADE) reads the files.

Runs `test_iges --write DIR`, which writes
  a.igs     a planar bicubic patch (dip 60 degrees) trimmed by a circle of
            radius 3500 m with a 2000 m square hole (loops given in the wrong
            sense, so the writer has reversed them),
  b.igs     an untrimmed bowl z = -3000 + 5e-5 ((u-5000)^2 + (v-4000)^2) over
            [0, 10000] x [0, 8000], unclamped cubic knots,
  both.igs  the two as one file,
and compares what OpenCASCADE makes of them with the analytic geometry
(the same numbers as tests/unit/test_iges.c): number of surfaces, area
(OCC's own integration, and the area of Gmsh's 2D mesh), boundary length,
the bounding box of the mesh nodes, the normal, and the face name.

Usage: check_iges.py TEST_IGES DIR ; exit 0 when everything agrees, 1 on a
mismatch, 77 when Gmsh's Python API is not installed (Debian python3-gmsh).
"""
import math
import os
import subprocess
import sys

try:
    import gmsh
except ImportError:
    print("python3-gmsh not installed: skipped")
    sys.exit(77)

REL_TOL = 0.005  # the gate: 0.5 % of the analytic value
NAME_A = "WTRA-TEST-PLANE-Trimmed_disk_with_square_hole"
NAME_B = ("TEST-BOWL-DOUBLY_CURVED-untrimmed_unclamped_bicubic_patch-with_a_name_"
          "longer_than_one_parameter_line")
MESH_SIZE = 250.0  # metres

failures = []


def check(cond, what):
    print(("ok    " if cond else "FAIL  ") + what)
    if not cond:
        failures.append(what)


def gauss_legendre(n):
    nodes, weights = [], []
    for i in range(1, n + 1):
        x = math.cos(math.pi * (i - 0.25) / (n + 0.5))
        for _ in range(100):
            p0, p1 = 1.0, x
            for k in range(2, n + 1):
                p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
            dp = n * (x * p1 - p0) / (x * x - 1)
            dx = p1 / dp
            x -= dx
            if abs(dx) < 1e-16:
                break
        nodes.append(x)
        weights.append(2 / ((1 - x * x) * dp * dp))
    return nodes, weights


GL = gauss_legendre(40)


def integrate1(f, a, b, pieces=8):
    s = 0.0
    for i in range(pieces):
        lo, hi = a + (b - a) * i / pieces, a + (b - a) * (i + 1) / pieces
        for x, w in zip(*GL):
            s += w * f((lo + hi) / 2 + (hi - lo) / 2 * x) * (hi - lo) / 2
    return s


def integrate2(f, a0, a1, b0, b1, pieces=4):
    return integrate1(lambda u: integrate1(lambda v: f(u, v), b0, b1, pieces), a0, a1, pieces)


def plane_case():
    """Face (a): area, boundary length, bounding box, normal."""
    c30, s30 = math.cos(math.pi / 6), math.sin(math.pi / 6)
    c60, s60 = math.cos(math.pi / 3), math.sin(math.pi / 3)
    origin = (400000.0, 3750000.0, -500.0)
    U = (c30, s30, 0.0)
    V = (-s30 * c60, c30 * c60, -s60)
    r, side = 3500.0, 2000.0
    centre = [origin[d] + 5000 * U[d] + 4000 * V[d] for d in range(3)]
    half = [r * math.hypot(U[d], V[d]) for d in range(3)]
    box = [centre[d] - half[d] for d in range(3)] + [centre[d] + half[d] for d in range(3)]
    normal = (U[1] * V[2] - U[2] * V[1], U[2] * V[0] - U[0] * V[2], U[0] * V[1] - U[1] * V[0])
    return dict(name=NAME_A, area=math.pi * r * r - side * side,
                length=2 * math.pi * r + 4 * side, box=box, normal=normal, uv=(5000.0, 1000.0))


def bowl_case():
    """Face (b): the same quantities by Gauss-Legendre quadrature."""
    a = 5e-5

    def h(u, v):
        return -3000 + a * ((u - 5000) ** 2 + (v - 4000) ** 2)

    area = integrate2(lambda u, v: math.sqrt(1 + (2 * a * (u - 5000)) ** 2
                                             + (2 * a * (v - 4000)) ** 2), 0, 10000, 0, 8000)
    along_u = integrate1(lambda u: math.sqrt(1 + (2 * a * (u - 5000)) ** 2), 0, 10000)
    along_v = integrate1(lambda v: math.sqrt(1 + (2 * a * (v - 4000)) ** 2), 0, 8000)
    box = [380000.0, 3760000.0, h(5000, 4000), 390000.0, 3768000.0, h(0, 0)]
    # Upward normal: S_u x S_v = (-h_u, -h_v, 1), at (2000, 1000).
    hu, hv = 2 * a * (2000 - 5000), 2 * a * (1000 - 4000)
    n = math.sqrt(1 + hu * hu + hv * hv)
    return dict(name=NAME_B, area=area, length=2 * along_u + 2 * along_v, box=box,
                normal=(-hu / n, -hv / n, 1 / n), uv=(2000.0, 1000.0))


def mesh_area(tag):
    """Area of Gmsh's triangles on surface tag."""
    node_tags, coords, _ = gmsh.model.mesh.getNodes(2, tag, includeBoundary=True)
    at = {t: (coords[3 * i], coords[3 * i + 1], coords[3 * i + 2])
          for i, t in enumerate(node_tags)}
    types, _, elem_nodes = gmsh.model.mesh.getElements(2, tag)
    total, count = 0.0, 0
    for etype, en in zip(types, elem_nodes):
        if etype != 2:  # 3-node triangles only at order 1
            continue
        for k in range(0, len(en), 3):
            p, q, s = at[en[k]], at[en[k + 1]], at[en[k + 2]]
            e1 = [q[d] - p[d] for d in range(3)]
            e2 = [s[d] - p[d] for d in range(3)]
            cx = e1[1] * e2[2] - e1[2] * e2[1]
            cy = e1[2] * e2[0] - e1[0] * e2[2]
            cz = e1[0] * e2[1] - e1[1] * e2[0]
            total += 0.5 * math.sqrt(cx * cx + cy * cy + cz * cz)
            count += 1
    return total, count, [at[t] for t in node_tags]


def check_file(path, expected, scale):
    print("--", os.path.basename(path))
    gmsh.model.add(os.path.basename(path))
    gmsh.model.occ.importShapes(path)
    gmsh.model.occ.synchronize()
    surfaces = [t for _, t in gmsh.model.getEntities(2)]
    check(len(surfaces) == len(expected), "%d surfaces (expected %d)" % (len(surfaces), len(expected)))
    gmsh.option.setNumber("Mesh.MeshSizeMax", MESH_SIZE * scale)
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.5 * MESH_SIZE * scale)
    gmsh.model.mesh.generate(2)
    by_name = {}
    for tag in surfaces:
        by_name[gmsh.model.getEntityName(2, tag)] = tag
    for exp in expected:
        # Gmsh prefixes the OCC label path ("Shapes/").
        tags = [t for n, t in by_name.items() if n.endswith("/" + exp["name"]) or n == exp["name"]]
        check(len(tags) == 1, "a surface named %r (names read: %r)" % (exp["name"], list(by_name)))
        if not tags:
            continue
        tag = tags[0]
        area = gmsh.model.occ.getMass(2, tag) / scale ** 2
        rel = abs(area - exp["area"]) / exp["area"]
        check(rel < REL_TOL, "area %.6f m^2 vs %.6f (relative %.2e)" % (area, exp["area"], rel))
        length = sum(gmsh.model.occ.getMass(1, abs(c))
                     for _, c in gmsh.model.getBoundary([(2, tag)], oriented=False)) / scale
        rel = abs(length - exp["length"]) / exp["length"]
        check(rel < REL_TOL, "boundary %.6f m vs %.6f (relative %.2e)" % (length, exp["length"], rel))
        occ_box = [x / scale for x in gmsh.model.getBoundingBox(2, tag)]
        box = exp["box"]
        diag = math.dist(box[:3], box[3:])
        # OCC's box comes from control points: it may only be larger.
        check(all(occ_box[d] <= box[d] + 1e-6 * diag and occ_box[d + 3] >= box[d + 3] - 1e-6 * diag
                  for d in range(3)), "OpenCASCADE box %s contains %s" % (occ_box, box))
        marea, ntri, nodes = mesh_area(tag)
        check(ntri > 0, "2D mesh: %d triangles, %d nodes" % (ntri, len(nodes)))
        if ntri:
            marea /= scale ** 2
            rel = abs(marea - exp["area"]) / exp["area"]
            check(rel < REL_TOL, "mesh area %.3f m^2 (relative %.2e)" % (marea, rel))
            lo = [min(p[d] for p in nodes) / scale for d in range(3)]
            hi = [max(p[d] for p in nodes) / scale for d in range(3)]
            tight = all(box[d] - 1e-6 * diag <= lo[d] <= box[d] + REL_TOL * diag and
                        box[d + 3] - REL_TOL * diag <= hi[d] <= box[d + 3] + 1e-6 * diag
                        for d in range(3))
            check(tight, "mesh nodes span %s, analytic %s" % (lo + hi, box))
        normal = gmsh.model.getNormal(tag, list(exp["uv"]))
        dot = sum(normal[d] * exp["normal"][d] for d in range(3))
        check(dot > 0.999999, "normal %s along S_u x S_v %s" % (list(normal), exp["normal"]))
    gmsh.model.remove()


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: check_iges.py TEST_IGES DIR")
    out = sys.argv[2]
    subprocess.run([sys.argv[1], "--write", out], check=True)
    a, b = plane_case(), bowl_case()
    gmsh.initialize(["check_iges"])
    gmsh.option.setNumber("General.Terminal", 0)
    # OpenCASCADE converts to its default unit, millimetres, unless told
    # otherwise (Geometry.OCCTargetUnit; "M" is refused by Debian 12's
    # Gmsh 4.8 with OCCT 7.6, and Geometry.OCCScaling drops the names).
    unit = gmsh.option.getString("Geometry.OCCTargetUnit").upper()
    scale = {"": 1000.0, "MM": 1000.0, "M": 1.0}.get(unit)
    check(scale is not None, "known OpenCASCADE target unit %r" % unit)
    if scale is not None:
        check_file(os.path.join(out, "a.igs"), [a], scale)
        check_file(os.path.join(out, "b.igs"), [b], scale)
        check_file(os.path.join(out, "both.igs"), [a, b], scale)
    gmsh.finalize()
    print("%d failures" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
