#!/usr/bin/python3
"""Draws the README's pictures of a fit: the original CFM triangulation
beside the fitted, trimmed surface coloured by its distance to the original.

usage: plot_fit.py ORIGINAL.ts FIT_DIR/NAME.vtu OUT.png [TITLE]
Needs Debian's python3-meshio and python3-matplotlib (not needed to build
or test faultmesh).
"""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import meshio
import numpy as np


def read_ts(path):
    pos, tris = {}, []
    with open(path, "rb") as f:
        for raw in f.read().decode("latin-1").splitlines():
            t = raw.split()
            if not t:
                continue
            if t[0] in ("VRTX", "PVRTX"):
                pos[int(t[1])] = [float(v) for v in t[2:5]]
            elif t[0] in ("ATOM", "PATOM"):
                pos[int(t[1])] = pos[int(t[2])]
            elif t[0] == "TRGL":
                tris.append([int(v) for v in t[1:4]])
    ids = sorted(pos)
    index = {k: i for i, k in enumerate(ids)}
    return np.array([pos[k] for k in ids]), np.array([[index[v] for v in t] for t in tris])


def main():
    ts, vtu, out = sys.argv[1:4]
    title = sys.argv[4] if len(sys.argv) > 4 else ""
    p0, t0 = read_ts(ts)
    m = meshio.read(vtu)
    p1, t1 = m.points, m.cells[0].data
    d = m.point_data["distance_to_original"]
    origin = p0.min(axis=0)
    fig = plt.figure(figsize=(13, 5.2))
    for k, (p, t, label) in enumerate(((p0, t0, "CFM 5.3 triangulation (500 m)"),
                                      (p1, t1, "faultmesh fit: trimmed B-spline surface"))):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        q = (p - origin) / 1000.0
        if k == 0:
            ax.plot_trisurf(q[:, 0], q[:, 1], q[:, 2], triangles=t, color="0.85",
                            edgecolor="0.25", linewidth=0.25)
        else:
            surf = ax.plot_trisurf(q[:, 0], q[:, 1], q[:, 2], triangles=t, cmap="viridis",
                                   linewidth=0, antialiased=False)
            surf.set_array(d[t].mean(axis=1))
            surf.set_clim(0, max(10.0, float(np.percentile(d, 99))))
            cb = fig.colorbar(surf, ax=ax, shrink=0.6, pad=0.08)
            cb.set_label("distance to the original (m)")
        ax.set_title(label, fontsize=10)
        ax.set_xlabel("east (km)")
        ax.set_ylabel("north (km)")
        ax.set_zlabel("z (km)")
        ax.view_init(elev=28, azim=-60)
        ax.set_box_aspect((np.ptp(q[:, 0]), np.ptp(q[:, 1]), max(np.ptp(q[:, 2]), 1e-3)))
    fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    fig.savefig(out, dpi=80)


if __name__ == "__main__":
    main()
