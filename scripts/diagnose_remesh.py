#!/usr/bin/python3
"""Splits a remeshed fault's fidelity and small-angle failures by where
they are, to tell the mesher's share from the fit's (dev only).

usage: diagnose_remesh.py OUT_DIR ORIGINAL_DIR FAULT_NAME...

Per fault (OUT_DIR/NAME.ts against ORIGINAL_DIR/NAME.ts), node distances
to the original triangulation (tests/tools/check_remesh.py's measure):
RMS and max of interior nodes, of outline nodes off sea level ("side") and
of sea-level nodes; the side nodes' share of the sum of squares; how many
side nodes lie beyond the original outline (their nearest original point
is on its boundary, so the distance is lateral: the trimming curve runs
outside) and their RMS. Then triangles under 20 degrees grouped into
clusters that share nodes, with their place and the largest distance of
their nodes. Needs numpy (Debian's python3-numpy)."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "tools"))
import check_remesh as cr  # noqa: E402  (the checker's reader and distance)


def boundary_edges(tri):
    e = np.sort(np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1)
    u, c = np.unique(e, axis=0, return_counts=True)
    return u[c == 1]


def to_segments(q, segs):
    """Distance of each point q (k, 3) to the nearest segment (m, 2, 3)."""
    a, d = segs[:, 0], segs[:, 1] - segs[:, 0]
    dd = np.maximum(np.einsum("ij,ij->i", d, d), 1e-9)
    out = np.empty(len(q))
    for i, p in enumerate(q):
        f = np.clip(np.einsum("ij,ij->i", p - a, d) / dd, 0.0, 1.0)
        r = p - a - f[:, None] * d
        out[i] = np.sqrt(np.einsum("ij,ij->i", r, r).min())
    return out


def rms(x):
    return float(np.sqrt(np.mean(x * x))) if len(x) else 0.0


def clusters(T, bad):
    parent = list(range(len(bad)))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    owner = {}
    for i, t in enumerate(bad):
        for v in T[t]:
            j = owner.setdefault(int(v), i)
            parent[root(i)] = root(j)
    groups = {}
    for i in range(len(bad)):
        groups.setdefault(root(i), []).append(bad[i])
    return sorted(groups.values(), key=lambda g: (-len(g), g[0]))


def diagnose(out_dir, orig_dir, name):
    (_, P, T), = cr.read_tsurf(os.path.join(out_dir, name + ".ts"))[:1]
    O = cr.read_tsurf(os.path.join(orig_dir, name + ".ts"))
    d = cr.distances(P, np.concatenate([p[t] for _, p, t in O]))
    outline = np.concatenate([p[boundary_edges(t)] for _, p, t in O])
    bn = np.unique(boundary_edges(T))
    top = bn[P[bn, 2] == 0.0]
    side = np.setdiff1d(bn, top)
    inner = np.setdiff1d(np.arange(len(P)), bn)
    beyond = np.zeros(0, dtype=bool)
    if len(side):
        beyond = np.abs(to_segments(P[side], outline) - d[side]) < 0.5
    ss = float(np.sum(d * d)) or 1.0
    print("%s: %d nodes, rms %.2f max %.1f m" % (name, len(P), rms(d), d.max()))
    print("  interior %5d: rms %6.2f max %7.1f" % (len(inner), rms(d[inner]), d[inner].max() if len(inner) else 0))
    print("  side     %5d: rms %6.2f max %7.1f, %3.0f%% of the sum of squares; %d beyond the original outline (rms %.2f)" % (
        len(side), rms(d[side]), d[side].max() if len(side) else 0, 100 * np.sum(d[side] ** 2) / ss,
        int(beyond.sum()), rms(d[side][beyond])))
    print("  sea level%5d: rms %6.2f" % (len(top), rms(d[top])))
    A = cr.corner_angles(P[T]).min(axis=1)
    bad = [int(t) for t in np.nonzero(A < 20)[0]]
    if bad:
        print("  %d triangles under 20 deg:" % len(bad))
    for g in clusters(T, bad)[:10]:
        nodes = np.unique(T[g])
        c = P[nodes].mean(axis=0)
        L = np.linalg.norm(P[T[g]] - np.roll(P[T[g]], -1, axis=1), axis=2)
        kind = "outline" if np.isin(nodes, bn).any() else "interior"
        print("    %3d at %.0f %.0f z %.0f (%s nodes), edges %.0f..%.0f m, min angle %.1f, node distance max %.1f" % (
            len(g), c[0], c[1], c[2], kind, L.min(), L.max(), A[g].min(), d[nodes].max()))


def main():
    if len(sys.argv) < 4:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    for name in sys.argv[3:]:
        diagnose(sys.argv[1], sys.argv[2], name[:-3] if name.endswith(".ts") else name)
    return 0


if __name__ == "__main__":
    sys.exit(main())
