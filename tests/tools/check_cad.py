#!/usr/bin/python3
"""Independent check of OUTDIR/model.igs against OUTDIR/mesh.msh.

model.igs is meant to be the geometry the meshes were made from: per fault
one or more trimmed surfaces, named after the fault, whose trims follow the
meshed domain. This reads the IGES file with Gmsh (gmsh.open: OpenCASCADE's
IGES reader) and the mesh with meshio, and checks from what the two readers
give (nothing of the writer's code or report):

  faces       every face is named after a fault of the mesh, every fault has
              a face, and a fault has at least as many faces as its mesh has
              edge-connected parts (a face is one connected surface);
  area        per fault, the faces' area (OpenCASCADE's integration) is
              within --area-tol of the mesh's area, but for --outliers of
              the faults, and within --area-max for all;
  surface     points of each face (a grid over its parameter bounds, those
              OpenCASCADE classifies inside its trims; with --gmsh-mesh
              also the nodes of Gmsh's mesh of the faces, which must mesh
              every face) lie near the fault's triangles: over the faults,
              the largest distance has median <= --surface-tol H, 95th
              percentile <= --surface-p95 H, maximum <= --surface-max H.
              The mesh's nodes lie on the fitted surface; its triangles are
              chords, as far from a surface that bends within H as that
              bend (a few CFM faults: hundreds of metres at 1 km);
  boundary    mesh boundary nodes (edges of one triangle of the fault) lie
              on the faces' boundary curves (OpenCASCADE's closest point on
              the curve nearest among samples every H / 50) within
              --node-tol H (nodes at sea level are counted apart: the
              mesher may have lifted them onto the line); the faces'
              boundaries lie near the mesh boundary edges, by the same
              bounds as the surface. A sample of a face's boundary lying on
              the fault's mesh away from its boundary is a seam between two
              sheets (an edge inside the fault's mesh): left out;
  junctions   along every edge two faults' meshes share (a made junction),
              each fault ending there has its trim curve through the shared
              nodes (--node-tol) and between them on the other fault's
              mesh; where both end (a corner), the distance between the two
              faults' trim curves (the gap a CAD tool must sew): 99th
              percentile within --junction-tol H.

Usage: check_cad.py OUTDIR --size H [tolerances]; exit 0 when everything
holds, 1 otherwise, 77 when Gmsh, meshio or scipy is missing.
"""
import argparse
import collections
import math
import os
import sys
import time

try:
    import gmsh
    import meshio
    import numpy as np
    from scipy.spatial import cKDTree
except ImportError as e:
    print("missing %s: skipped" % e.name)
    sys.exit(77)

failures = []


def check(cond, what):
    print(("ok    " if cond else "FAIL  ") + what)
    if not cond:
        failures.append(what)


def seg_dist(p, a, b):
    """Distance from points p (n x 3) to segments a-b (n x 3 each)."""
    ab = b - a
    den = np.einsum("ij,ij->i", ab, ab)
    t = np.where(den > 0, np.einsum("ij,ij->i", p - a, ab) / np.where(den > 0, den, 1), 0)
    t = np.clip(t, 0, 1)
    return np.linalg.norm(p - (a + t[:, None] * ab), axis=1)


def tri_dist(p, a, b, c):
    """Distance from points p to triangles a-b-c (all n x 3)."""
    n = np.cross(b - a, c - a)
    nn = np.linalg.norm(n, axis=1)
    nn = np.where(nn > 0, nn, 1)
    n = n / nn[:, None]
    d = np.einsum("ij,ij->i", p - a, n)
    q = p - d[:, None] * n
    inside = np.ones(len(p), dtype=bool)
    for u, v in ((a, b), (b, c), (c, a)):
        inside &= np.einsum("ij,ij->i", np.cross(v - u, q - u), n) >= 0
    edge = np.minimum(np.minimum(seg_dist(p, a, b), seg_dist(p, b, c)), seg_dist(p, c, a))
    return np.where(inside, np.abs(d), edge)


class Nearest:
    """Nearest of many triangles or segments, by their centres then exact."""

    def __init__(self, corners, k=12):
        self.c = corners  # list of (m x 3) arrays: 3 for triangles, 2 for segments
        centre = sum(corners) / len(corners)
        self.tree = cKDTree(centre)
        self.k = min(k, len(centre))

    def dist(self, p):
        if len(p) == 0:
            return np.zeros(0)
        _, idx = self.tree.query(p, k=self.k)
        idx = idx.reshape(len(p), -1)
        best = np.full(len(p), np.inf)
        for j in range(idx.shape[1]):
            sel = [c[idx[:, j]] for c in self.c]
            d = tri_dist(p, *sel) if len(sel) == 3 else seg_dist(p, *sel)
            best = np.minimum(best, d)
        return best


def on_face(tag, pts, scale, inside=True, limit=np.inf):
    """Distance (m) from points to face tag's surface; with inside, inf where
    the foot lies outside the face's trims (tested where the distance is at
    most limit)."""
    if len(pts) == 0:
        return np.zeros(0)
    foot, uv = gmsh.model.getClosestPoint(2, tag, list((pts * scale).ravel()))
    d = np.linalg.norm(np.asarray(foot).reshape(-1, 3) / scale - pts, axis=1)
    if inside:
        uv = np.asarray(uv).reshape(-1, 2)
        for i in np.flatnonzero(d <= limit):  # one call per point: only where it matters
            if gmsh.model.isInside(2, tag, list(uv[i])) <= 0:
                d[i] = np.inf
    return d


def read_mesh(path):
    m = meshio.read(path)
    X = np.asarray(m.points, dtype=float)
    tri = np.asarray(m.cells_dict["triangle"])
    tags = np.asarray(m.cell_data_dict["gmsh:physical"]["triangle"])
    names = {int(v[0]): k for k, v in m.field_data.items() if int(v[1]) == 2}
    faults = {}
    for tag, name in names.items():
        T = tri[tags == tag]
        if len(T) == 0:
            continue
        count = collections.Counter()
        for t in T:
            for k in range(3):
                a, b = int(t[k]), int(t[(k + 1) % 3])
                count[(min(a, b), max(a, b))] += 1
        boundary = np.array([e for e, c in count.items() if c == 1], dtype=np.int64).reshape(-1, 2)
        # edge-connected parts
        parent = list(range(len(T)))

        def root(x):
            while parent[x] != x:
                parent[x] = parent[parent[x]]
                x = parent[x]
            return x
        first = {}
        for i, t in enumerate(T):
            for k in range(3):
                a, b = int(t[k]), int(t[(k + 1) % 3])
                e = (min(a, b), max(a, b))
                if e in first:
                    parent[root(i)] = root(first[e])
                else:
                    first[e] = i
        parts = len({root(i) for i in range(len(T))})
        A, B, C = X[T[:, 0]], X[T[:, 1]], X[T[:, 2]]
        area = 0.5 * np.linalg.norm(np.cross(B - A, C - A), axis=1).sum()
        faults[name] = dict(T=T, area=area, boundary=boundary, parts=parts, edges=set(count))
    return X, faults


def junction_edges(faults):
    """Edges of two faults' meshes: (fault a, fault b, node, node)."""
    owner = collections.defaultdict(list)
    for name, f in faults.items():
        for e in f["edges"]:
            owner[e].append(name)
    return [(o[0], o[1], e) for e, o in owner.items() if len(o) == 2]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("outdir")
    ap.add_argument("--size", type=float, required=True, help="H, metres")
    ap.add_argument("--area-tol", type=float, default=0.02, help="relative, per fault")
    ap.add_argument("--area-max", type=float, default=0.10, help="relative, every fault")
    ap.add_argument("--surface-tol", type=float, default=0.1,
                    help="fraction of H: median over the faults")
    ap.add_argument("--surface-p95", type=float, default=0.3,
                    help="fraction of H: 95th percentile over the faults")
    ap.add_argument("--surface-max", type=float, default=0.6, help="fraction of H, every fault")
    ap.add_argument("--outliers", type=float, default=0.02,
                    help="fraction of faults allowed past --area-tol")
    ap.add_argument("--node-tol", type=float, default=0.002, help="fraction of H")
    ap.add_argument("--junction-tol", type=float, default=0.05, help="fraction of H")
    ap.add_argument("--grid", type=int, default=12, help="samples per face: grid x grid")
    ap.add_argument("--gmsh-mesh", action="store_true", help="also mesh the faces with Gmsh")
    ap.add_argument("--gmsh-size", type=float, default=2.0, help="Gmsh's mesh size, in H")
    a = ap.parse_args()
    H = a.size
    t0 = time.time()
    X, faults = read_mesh(os.path.join(a.outdir, "mesh.msh"))
    print("mesh.msh: %d faults, %d triangles (%.1f s)"
          % (len(faults), sum(len(f["T"]) for f in faults.values()), time.time() - t0))

    gmsh.initialize(["check_cad"])
    gmsh.option.setNumber("General.Terminal", 0)
    # OpenCASCADE converts to its target unit, millimetres by default
    # (see check_iges.py).
    unit = gmsh.option.getString("Geometry.OCCTargetUnit").upper()
    scale = {"": 1000.0, "MM": 1000.0, "M": 1.0}.get(unit)
    check(scale is not None, "known OpenCASCADE target unit %r" % unit)
    if scale is None:
        return 1
    t0 = time.time()
    gmsh.open(os.path.join(a.outdir, "model.igs"))
    surfaces = [t for _, t in gmsh.model.getEntities(2)]
    print("model.igs: %d faces (%.1f s)" % (len(surfaces), time.time() - t0))

    # faces
    by_fault = collections.defaultdict(list)
    for tag in surfaces:
        by_fault[gmsh.model.getEntityName(2, tag).split("/")[-1]].append(tag)
    strangers = sorted(set(by_fault) - set(faults))
    check(not strangers, "every face named after a fault of the mesh (others: %s)" % strangers[:5])
    missing = sorted(set(faults) - set(by_fault))
    check(not missing, "every fault has a face (without: %s)" % missing[:5])
    few = [n for n in faults if n in by_fault and len(by_fault[n]) < faults[n]["parts"]]
    check(not few, "no fault with fewer faces than its mesh has parts (%d faces, %d parts; "
          "fewer: %s)" % (len(surfaces), sum(f["parts"] for f in faults.values()), few[:5]))

    # area
    rel = {}
    for name, tags in by_fault.items():
        if name in faults:
            area = sum(gmsh.model.occ.getMass(2, t) for t in tags) / scale ** 2
            rel[name] = abs(area - faults[name]["area"]) / faults[name]["area"]
    over = sorted(((r, n) for n, r in rel.items() if r > a.area_tol), reverse=True)
    r = np.array(list(rel.values()))
    check(len(over) <= a.outliers * len(rel) and r.max() <= a.area_max,
          "face area per fault within %.1f %% of the mesh's for all but %d faults (at most "
          "%.1f %%), within %.1f %% for all; median %.3f %%, largest %.3f %%; over: %s"
          % (100 * a.area_tol, len(over), 100 * a.outliers, 100 * a.area_max, 100 * np.median(r),
             100 * r.max(), ", ".join("%s %.2f %%" % (n, 100 * x) for x, n in over[:6])))

    # boundary samples of every face, in metres
    t0 = time.time()
    step = H / 50
    fb, fbc = {}, {}
    for name, tags in by_fault.items():
        for tag in tags:
            pts, cid = [], []
            for _, c in gmsh.model.getBoundary([(2, tag)], oriented=False):
                c = abs(c)
                lo, hi = gmsh.model.getParametrizationBounds(1, c)
                length = gmsh.model.occ.getMass(1, c) / scale
                n = max(2, int(math.ceil(length / step)) + 1)
                ts = np.linspace(lo[0], hi[0], n)
                pts.append(np.asarray(gmsh.model.getValue(1, c, ts)).reshape(-1, 3) / scale)
                cid.append(np.full(n, c))
            fb[tag] = np.vstack(pts) if pts else np.zeros((0, 3))
            fbc[tag] = np.concatenate(cid) if cid else np.zeros(0, int)

    def on_curve(p, curve):
        """Distance of point p (metres) to a face boundary curve, exactly:
        a node inside a trim curve lies between its samples."""
        q = gmsh.model.getClosestPoint(1, int(curve), list(np.asarray(p) * scale))[0]
        return float(np.linalg.norm(np.asarray(q) / scale - p))
    print("face boundaries sampled every %.0f m: %d points (%.1f s)"
          % (step, sum(len(p) for p in fb.values()), time.time() - t0))

    # surface: points of every face lie on its fault's mesh. Samples: a
    # grid over the face's parameter bounds, the points OpenCASCADE
    # classifies inside the face's trims (gmsh.model.isInside) evaluated on
    # the face; with --gmsh-mesh also the nodes of Gmsh's own mesh of the
    # faces.
    t0 = time.time()
    samples = {}
    n = a.grid
    for tag in surfaces:
        lo, hi = gmsh.model.getParametrizationBounds(2, tag)
        us = lo[0] + (hi[0] - lo[0]) * (np.arange(n) + 0.5) / n
        vs = lo[1] + (hi[1] - lo[1]) * (np.arange(n) + 0.5) / n
        uv = [(u, v) for u in us for v in vs if gmsh.model.isInside(2, tag, [u, v]) > 0]
        samples[tag] = (np.asarray(gmsh.model.getValue(2, tag, [c for p in uv for c in p]))
                        .reshape(-1, 3) / scale if uv else np.zeros((0, 3)))
    print("faces sampled on a %d x %d parameter grid (%.1f s)" % (n, n, time.time() - t0))
    if a.gmsh_mesh:
        t0 = time.time()
        gmsh.option.setNumber("Mesh.MeshSizeMax", a.gmsh_size * H * scale)
        gmsh.option.setNumber("Mesh.MeshSizeMin", 0.1 * a.gmsh_size * H * scale)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        try:
            gmsh.model.mesh.generate(2)
        except Exception as e:  # Gmsh raises on the first face it cannot mesh
            check(False, "Gmsh meshes the faces (%s)" % e)
        unmeshed = []
        for tag in surfaces:
            _, c, _ = gmsh.model.mesh.getNodes(2, tag, includeBoundary=False)
            pts = np.asarray(c).reshape(-1, 3) / scale
            if len(pts) == 0:
                unmeshed.append(tag)
            samples[tag] = np.vstack([samples[tag], pts])
        check(not unmeshed, "Gmsh meshed every face at %.0f m (%.1f s; faces without nodes: %s)"
              % (a.gmsh_size * H, time.time() - t0, unmeshed[:5]))
    surf, tri_near, empty, npts = {}, {}, [], 0
    for name, tags in by_fault.items():
        if name not in faults:
            continue
        T = faults[name]["T"]
        tri_near[name] = Nearest([X[T[:, 0]], X[T[:, 1]], X[T[:, 2]]])
        surf[name] = 0.0
        for tag in tags:
            pts = samples[tag]
            if len(pts) == 0:
                empty.append(name)
                continue
            npts += len(pts)
            surf[name] = max(surf[name], tri_near[name].dist(pts).max())
    check(len(empty) <= 0.05 * len(surfaces),
          "sample points inside all but %d faces (at most 5 %%; small faces may fall between "
          "the grid's points): %s" % (len(empty), empty[:5]))
    dist = np.array(list(surf.values()))
    over = sorted(((d, n) for n, d in surf.items() if d > a.surface_p95 * H), reverse=True)
    check(npts > 0 and np.median(dist) <= a.surface_tol * H and
          np.percentile(dist, 95) <= a.surface_p95 * H and dist.max() <= a.surface_max * H,
          "%d points of the faces: their largest distance to their fault's mesh, over the "
          "faults: median %.1f m (at most %.0f), 95th percentile %.1f m (at most %.0f), largest "
          "%.1f m (at most %.0f); faults past %.0f m: %s"
          % (npts, np.median(dist), a.surface_tol * H, np.percentile(dist, 95),
             a.surface_p95 * H, dist.max(), a.surface_max * H, a.surface_p95 * H,
             ", ".join("%s %.0f m" % (n, d) for d, n in over[:8])))

    # boundary. Mesh boundary nodes lie on the faces' trims (the trims pass
    # through them): a tight tolerance, but for nodes at sea level (z = 0
    # exactly), which the mesher may have lifted onto the line from below
    # (counted and shown). Between nodes a trim follows the surface and a
    # mesh edge is its chord: the face boundary is held to the mesh
    # boundary edges as the face is held to the mesh. A multi-face fault's face boundary lying on the fault's
    # mesh (as near as the face is, at least --surface-tol) away from its
    # boundary is a seam between two sheets, an edge inside the mesh: left
    # out.
    t0 = time.time()
    node_tol = a.node_tol * H  # distances to the curves themselves, not to samples
    worst_node, name_node, seam, bfar, lifted, lift_max = 0.0, "", 0, {}, 0, 0.0
    for name, f in faults.items():
        tags = by_fault.get(name, [])
        if not tags or len(f["boundary"]) == 0:
            continue
        tree = cKDTree(np.vstack([fb[t] for t in tags]))
        cids = np.concatenate([fbc[t] for t in tags])
        E = f["boundary"]
        nodes = np.unique(E.ravel())
        # the curves of the 8 nearest samples: the nearest sample can lie
        # on another face's curve where two sheets' faces meet
        d8, near8 = tree.query(X[nodes], k=min(8, tree.n))
        d8, near8 = d8.reshape(len(nodes), -1), near8.reshape(len(nodes), -1)
        d = d8[:, 0]
        d = np.array([min([dd] + [on_curve(X[v], c) for c in set(cids[i8])])
                      for v, dd, i8 in zip(nodes, d, near8)])
        level = X[nodes, 2] == 0
        off = level & (d > node_tol)
        lifted += int(off.sum())
        lift_max = max(lift_max, d[off].max() if off.any() else 0.0)
        d = d[~level]
        if len(d) and d.max() > worst_node:
            worst_node, name_node = d.max(), name
        near = Nearest([X[E[:, 0]], X[E[:, 1]]])
        pts = np.vstack([fb[t] for t in tags])
        d = near.dist(pts)
        if len(tags) > 1:
            lim = max(a.surface_tol * H, surf.get(name, 0) + step)
            inner = (d > lim) & (tri_near[name].dist(pts) <= lim)
            seam += int(inner.sum())
            d = d[~inner]
        bfar[name] = d.max() if len(d) else 0.0
    print("boundaries compared (%.1f s); %d face boundary samples on a seam between two sheets"
          % (time.time() - t0, seam))
    check(worst_node <= node_tol,
          "mesh boundary nodes below sea level on the faces' trim curves: within %.2f m at most "
          "(%s; tolerance %.1f m)" % (worst_node, name_node, node_tol))
    print("info  %d mesh boundary nodes at sea level lie off the trims (the mesher put them on "
          "the line), by %.1f m at most" % (lifted, lift_max))
    bd = np.array(list(bfar.values()))
    over = sorted(((d, n) for n, d in bfar.items() if d > a.surface_p95 * H), reverse=True)
    check(np.median(bd) <= a.surface_tol * H and np.percentile(bd, 95) <= a.surface_p95 * H
          and bd.max() <= a.surface_max * H,
          "faces' boundaries to the mesh boundary edges, each fault's largest distance: median "
          "%.1f m, 95th percentile %.1f m, largest %.1f m (same bounds); past %.0f m: %s"
          % (np.median(bd), np.percentile(bd, 95), bd.max(), a.surface_p95 * H,
             ", ".join("%s %.0f m" % (n, d) for d, n in over[:8])))

    # junctions: along an edge two faults' meshes share, each fault whose
    # mesh ends there has its trim curve there. At the shared nodes the
    # trims pass through the node (tight); between them each follows its
    # own surface, and where both faults end (a corner) the two trim curves
    # must stay close enough for a CAD tool to sew (--junction-tol H).
    je = junction_edges(faults)
    if je:
        t0 = time.time()
        trees = {}
        for name, tags in by_fault.items():
            allb = np.vstack([fb[t] for t in tags])
            trees[name] = (cKDTree(allb), allb, np.concatenate([fbc[t] for t in tags]))
        bset = {n: {(int(e[0]), int(e[1])) for e in f["boundary"]} for n, f in faults.items()}
        node_off, gaps, mids, onto = [], [], [], []
        for fa, fbn, e in je:
            if fa not in trees or fbn not in trees:
                continue
            P, Q = X[e[0]], X[e[1]]
            probe = np.array([P + (Q - P) * s for s in (0, 0.25, 0.5, 0.75, 1)])
            near = {}
            for x, y in ((fa, fbn), (fbn, fa)):
                if e in bset[x]:
                    d, i = trees[x][0].query(probe)
                    near[x] = trees[x][1][i]
                    i8 = trees[x][0].query(probe[[0, -1]], k=min(8, trees[x][0].n))[1]
                    i8 = i8.reshape(2, -1)
                    node_off.append(max(min([d[k]] + [on_curve(probe[k], c)
                                                      for c in set(trees[x][2][i8[e]])])
                                        for e, k in enumerate((0, -1))))
                    # the trim between the nodes lies on the other fault's mesh
                    onto.append(tri_near[y].dist(near[x][1:4]).max() if y in tri_near else 0)
            if len(near) == 2:
                g = np.linalg.norm(near[fa] - near[fbn], axis=1)
                gaps.append(g.max())
                mids.append(g[2])
        print("junctions: %d edges shared by two faults, %d with a fault ending there, %d with "
              "both (%.1f s)" % (len(je), len(node_off), len(gaps), time.time() - t0))
        if node_off:
            node_off, onto = np.array(node_off), np.array(onto)
            check(node_off.max() <= node_tol,
                  "a fault's trim at a junction passes through the shared nodes: within %.2f m "
                  "(tolerance %.1f m)" % (node_off.max(), node_tol))
            check(np.percentile(onto, 99) <= a.junction_tol * H + step,
                  "... and between them lies on the other fault's mesh: 99th percentile %.2f m, "
                  "median %.2f m, largest %.2f m" % (np.percentile(onto, 99), np.median(onto),
                                                       onto.max()))
        if gaps:
            gaps, mids = np.array(gaps), np.array(mids)
            check(np.percentile(gaps, 99) <= a.junction_tol * H + step,
                  "where both faults end (%d edges) their trim curves are apart by: at the edge's "
                  "middle median %.2f m, 99th percentile %.2f m, largest %.2f m; anywhere along "
                  "it largest %.2f m (sampled every %.0f m)"
                  % (len(gaps), np.median(mids), np.percentile(mids, 99), mids.max(),
                     gaps.max(), step))
    else:
        print("junctions: none")

    gmsh.finalize()
    print("%d failures" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
