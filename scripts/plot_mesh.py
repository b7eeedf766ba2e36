#!/usr/bin/python3
"""Draws the README's pictures of remeshed faults: every fault of a
`faultmesh remesh` or `faultmesh demo` output in 3D, coloured by fault,
with the triangle edges, and optionally the original triangulation of one
fault beside its new mesh.

usage: plot_mesh.py OUT_DIR/mesh.vtu OUT.png [TITLE] [--fault NAME --original FILE.ts]
                    [--shared] [--view ELEV AZIM]
--shared draws the edges two faults share (their junction curves) in red.
Needs Debian's python3-meshio and python3-matplotlib (not needed to build
or test faultmesh).
"""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import meshio
import numpy as np
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

from plot_fit import read_ts  # the same TSurf reading as the fit pictures


def names_of(m):
    raw = bytes(np.asarray(m.field_data["fault_names"]).astype(np.uint8).ravel())
    return [s.decode() for s in raw.split(b"\0") if s]


def draw(ax, p, t, colours, origin, edge="k", lw=0.15):
    q = (p - np.array([origin[0], origin[1], 0.0])) / 1000.0
    polys = q[t]
    pc = Poly3DCollection(polys, facecolors=colours, edgecolors=edge, linewidths=lw)
    ax.add_collection3d(pc)
    used = polys.reshape(-1, 3)
    lo, hi = used.min(axis=0), used.max(axis=0)
    c, r = (lo + hi) / 2, (hi - lo).max() / 2
    ax.set_xlim(c[0] - r, c[0] + r)
    ax.set_ylim(c[1] - r, c[1] + r)
    ax.set_zlim(lo[2] - 0.5, max(hi[2], 0.0) + 0.5)
    ax.set_box_aspect((1, 1, 0.45))
    ax.set_xlabel("east (km)")
    ax.set_ylabel("north (km)")
    ax.set_zlabel("z (km)")


def shared_edges(t, fid):
    """Edges used by triangles of more than one fault."""
    e = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    e.sort(axis=1)
    f = np.tile(fid, 3)
    key = np.unique(np.stack([e[:, 0], e[:, 1], f], axis=1), axis=0)
    pairs, count = np.unique(key[:, :2], axis=0, return_counts=True)
    return pairs[count > 1]


def main():
    args = sys.argv[1:]
    fault = original = None
    shared = "--shared" in args
    if shared:
        args.remove("--shared")
    view = (28, -60)
    if "--view" in args:
        i = args.index("--view")
        view = (float(args[i + 1]), float(args[i + 2]))
        del args[i:i + 3]
    if "--fault" in args:
        i = args.index("--fault")
        fault = args[i + 1]
        del args[i:i + 2]
    if "--original" in args:
        i = args.index("--original")
        original = args[i + 1]
        del args[i:i + 2]
    vtu, out = args[0], args[1]
    title = args[2] if len(args) > 2 else ""
    m = meshio.read(vtu)
    p, t = m.points, m.cells_dict["triangle"]
    fid = np.asarray(m.cell_data["fault_id"][0]) - 1  # fault numbers are from 1
    names = names_of(m)
    cmap = plt.get_cmap("tab10")
    if fault is None:
        fig = plt.figure(figsize=(11, 7))
        ax = fig.add_subplot(1, 1, 1, projection="3d")
        origin = p.min(axis=0)
        draw(ax, p, t, [cmap(f % 10) for f in fid], origin)
        if shared:
            # drawn last and on top: mplot3d's depth sort would bury lines
            # lying on the surfaces they join
            ax.computed_zorder = False
            q = (p - np.array([origin[0], origin[1], 0.0])) / 1000.0
            lines = Line3DCollection(q[shared_edges(t, fid)], colors="red", linewidths=2.0)
            lines.set_zorder(10)
            ax.add_collection3d(lines)
        ax.view_init(elev=view[0], azim=view[1])
        ax.set_title(title or "%d faults, %d triangles" % (len(names), len(t)))
    else:
        k = names.index(fault)
        sel = t[fid == k]
        p0, t0 = read_ts(original)
        origin = p0.min(axis=0)
        fig = plt.figure(figsize=(13, 5.2))
        for j, (pp, tt, label) in enumerate(((p0, t0, "CFM 5.3 triangulation"),
                                            (p, sel, "faultmesh remesh"))):
            ax = fig.add_subplot(1, 2, j + 1, projection="3d")
            draw(ax, pp, tt, "0.85" if j == 0 else "#9ecae1", origin, lw=0.1 if j == 0 else 0.3)
            ax.view_init(elev=25, azim=-70)
            ax.set_title(label)
        fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
