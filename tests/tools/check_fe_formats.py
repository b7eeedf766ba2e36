#!/usr/bin/python3
"""Independent check of a remesh's Exodus II and MSH files and their CRS.

Usage: check_fe_formats.py OUTDIR CONVENTION [--crs CRS]

Reads OUTDIR/mesh.exo with meshio and with netCDF4 (the Exodus II data
model: variables connectN, eb_names, node_nsN, ns_names, info_records,
qa_records) and OUTDIR/mesh.msh with meshio and Gmsh's Python API, and
compares them with OUTDIR/mesh.obj (the same set as Wavefront OBJ, one
group per fault) and OUTDIR/report.json:

  Exodus  one TRI3 block per fault named after it, with that fault's OBJ
          triangles (same corners, same winding); a node set per fault
          holding exactly the nodes of its block; one node set per
          junction report.json marks made, named "junction I: A / B", whose
          nodes are nodes of both A's and B's blocks and hold at least one
          edge of both; info records give the CRS; QA record "faultmesh"
          with a date and time (SOURCE_DATE_EPOCH's, else the epoch's).
  MSH     meshio and Gmsh read it; the physical tags and names of the
          convention (default: fault i -> i + 1 named after it; tandem: all
          3 "fault", MSH 2.2, node tags 1..n; seissol: all 103 "fault";
          pylith: i + 1, a label of [A-Za-z0-9_] starting with a letter,
          distinct); the elementary tag of every triangle is its fault
          index + 1; the $Comments section names the CRS.
  CRS     report.json options.crs (crs_out when --crs-out was given), VTU
          field data "crs", STL header, OBJ
          comment, the TSurf blocks' NAME and the Exodus info records all
          give the same CRS (--crs: and equal it).

Exit 0 when all agree, 1 on a mismatch, 77 when a reader is missing.
"""
import json
import os
import re
import sys

from fm_short_names import short_names

try:
    import numpy as np
    import meshio
    import netCDF4
    import gmsh
except ImportError as e:  # pragma: no cover
    print("skipped: %s" % e)
    sys.exit(77)

FAILED = []


def check(cond, what):
    print("  %-4s %s" % ("ok" if cond else "FAIL", what))
    if not cond:
        FAILED.append(what)


def read_obj(path):
    """Vertices, and per group name its triangles (0-based vertex indices)."""
    verts, groups, cur, comments = [], {}, None, []
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("#"):
                comments.append(line[1:].strip())
            elif line.startswith("v "):
                verts.append([float(t) for t in line.split()[1:4]])
            elif line.startswith("g "):
                cur = line[2:].strip()
                groups.setdefault(cur, [])
            elif line.startswith("f "):
                groups[cur].append([int(t.split("/")[0]) - 1 for t in line.split()[1:4]])
    return np.array(verts), {k: np.array(v, dtype=np.int64) for k, v in groups.items()}, comments


def obj_name(name):
    return re.sub(r"[\s#]", "_", name)


def chars(var):
    var.set_auto_mask(False)
    return [b"".join(row).decode("utf-8") for row in var[:]]


def check_exodus(out, faults, crs, junctions, verts, groups):
    path = os.path.join(out, "mesh.exo")
    print("-- exodus", path)
    m = meshio.read(path)
    check(len(m.cells) == len(faults), "meshio: %d blocks for %d faults" % (len(m.cells), len(faults)))
    check(all(c.type == "triangle" for c in m.cells), "meshio: every block triangles")
    nc = netCDF4.Dataset(path)
    eb = chars(nc.variables["eb_names"])
    ns_names = chars(nc.variables["ns_names"])
    # junction sets: "junction I: A / B", I the number (from 1) of its line
    # in report.json, cut by the short-name rule with the fault names
    made = {i: j for i, j in enumerate(junctions) if j["type"] != "unjoined"}
    full_sets = []
    for name in ns_names[len(faults):]:
        mt = re.match(r"junction_(\d+)_", name)
        ji = int(mt.group(1)) - 1 if mt else -1
        full_sets.append("junction %d: %s / %s" % (ji + 1, *made[ji]["faults"]) if ji in made else "")
    short = short_names(faults + full_sets, 32)
    check(all(len(n) <= 32 for n in eb + ns_names) and len(set(eb)) == len(eb) and
          len(set(ns_names)) == len(ns_names),
          "block and node set names at most 32 characters, unique")
    check(eb == short[:len(faults)], "block names are the fault names by the short-name rule, in order")
    pts = np.asarray(m.points)
    block_nodes = []
    for i, name in enumerate(faults):
        conn = nc.variables["connect%d" % (i + 1)]
        etype = conn.elem_type
        check(etype == "TRI3", "block %d type TRI3 (%s)" % (i + 1, etype)) if i < 3 else None
        tri = np.asarray(conn[:], dtype=np.int64) - 1
        block_nodes.append(set(tri.ravel().tolist()))
        want = groups.get(obj_name(name))
        ok = want is not None and len(want) == len(tri)
        if ok:
            # same corners in the same order (the OBJ keeps every vertex,
            # the Exodus file only those used: compare coordinates)
            ok = np.array_equal(pts[tri], verts[want])
        if not ok or i < 3:
            check(ok, "block %d (%s): %d triangles, corners and winding as the OBJ" %
                  (i + 1, name, len(tri)))
    check(all(etype == "TRI3" for etype in
              (nc.variables["connect%d" % (i + 1)].elem_type for i in range(len(faults)))),
          "every block TRI3")
    check(ns_names[:len(faults)] == short[:len(faults)],
          "node sets 1..%d are the faults, named" % len(faults))
    bad = [faults[i] for i in range(len(faults))
           if set((np.asarray(nc.variables["node_ns%d" % (i + 1)][:]) - 1).tolist()) != block_nodes[i]]
    check(not bad, "each fault's node set = the nodes of its block (%d differ)" % len(bad))
    # junctions made, from report.json
    sets = ns_names[len(faults):]
    fidx = {n: i for i, n in enumerate(faults)}
    edges = []
    for i in range(len(faults)):
        tri = np.asarray(nc.variables["connect%d" % (i + 1)][:], dtype=np.int64) - 1
        e = np.sort(np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1)
        edges.append(set(map(tuple, e.tolist())))
    bad_names, bad_nodes, no_edge, total, covered = [], [], [], 0, {}
    with_set = set()
    for k, name in enumerate(sets):
        mt = re.match(r"junction_(\d+)_", name)
        ji = int(mt.group(1)) - 1 if mt else -1
        if ji not in made or name != short[len(faults) + k]:
            bad_names.append(name)
            continue
        with_set.add(ji)
        a, b = made[ji]["faults"]
        nodes = set((np.asarray(nc.variables["node_ns%d" % (len(faults) + k + 1)][:]) - 1).tolist())
        total += len(nodes)
        if not nodes or not nodes <= block_nodes[fidx[a]] or not nodes <= block_nodes[fidx[b]]:
            bad_nodes.append(name)
        common = {e for e in edges[fidx[a]] & edges[fidx[b]] if e[0] in nodes and e[1] in nodes}
        if not common:
            no_edge.append(name)
        covered.setdefault((a, b), set()).update(common)
    check(not bad_names, "every junction node set is named 'junction I: A / B' (short) after a "
          "junction report.json marks made (%s)" % bad_names[:2])
    check(not bad_nodes, "every junction node set's nodes are nodes of both faults' blocks "
          "(%d sets, %d nodes; bad: %s)" % (len(sets), total, bad_nodes[:3]))
    check(not no_edge, "every junction node set holds an edge of both faults (%s)" % no_edge[:3])
    # a junction made without a set: its faults must share no edge that a
    # set of theirs leaves out (else the set is missing)
    missing, no_shared = [], []
    for ji, j in made.items():
        if ji in with_set:
            continue
        a, b = j["faults"]
        shared = (edges[fidx[a]] & edges[fidx[b]]) - covered.get((a, b), set())
        (missing if shared else no_shared).append(ji)
    check(not missing, "%d junctions made, %d node sets; no made junction whose faults share "
          "edges lacks its set (%s)" % (len(made), len(sets), missing[:5]))
    if no_shared:
        print("  note report.json marks %d junctions made whose faults' blocks share no edge "
              "(no node set): %s" % (len(no_shared), no_shared[:10]))
    info = chars(nc.variables["info_records"])
    got = "".join(l[5:] for l in info if l.startswith("crs: ") or l.startswith("crs+ "))
    check(got == crs, "info records give the CRS %r (%r)" % (crs, got))
    qa = [chars_row for chars_row in nc.variables["qa_records"][0]]
    qa0 = b"".join(np.asarray(qa[0]).tolist()).decode()
    check(qa0 == "faultmesh", "QA record names faultmesh (%r)" % qa0)
    qd = [b"".join(np.asarray(qa[k]).tolist()).decode() for k in (2, 3)]
    check(re.fullmatch(r"\d{4}-\d\d-\d\d", qd[0]) is not None and
          re.fullmatch(r"\d\d:\d\d:\d\d", qd[1]) is not None,
          "QA record date and time filled (%s %s)" % tuple(qd))
    check(np.allclose(pts, verts[np.asarray(nc.variables["node_num_map"][:]) - 1], rtol=0, atol=0),
          "node_num_map gives each node's vertex (OBJ line), coordinates exact")
    nc.close()
    return m


def check_side_sets(out, conv):
    """Exodus II side sets against the MSH's physical curves: the same
    groups in the same order (side set k, curve k), each the same edges
    (element and TRI3 side turned into its two nodes, node numbers into
    vertices by node_num_map; MSH node tags are vertex + 1)."""
    import gmsh
    nc = netCDF4.Dataset(os.path.join(out, "mesh.exo"))
    nmap = np.asarray(nc.variables["node_num_map"][:]) - 1
    conn = []
    b = 1
    while "connect%d" % b in nc.variables:
        conn.append(np.asarray(nc.variables["connect%d" % b][:]) - 1)
        b += 1
    conn = np.concatenate(conn) if conn else np.zeros((0, 3), int)
    exo = []
    k = 1
    while "elem_ss%d" % k in nc.variables:
        e = np.asarray(nc.variables["elem_ss%d" % k][:]) - 1
        s = np.asarray(nc.variables["side_ss%d" % k][:]) - 1
        check(bool(np.all((s >= 0) & (s <= 2))), "side set %d: TRI3 sides 1-3" % k)
        a, c = conn[e, s], conn[e, (s + 1) % 3]
        exo.append({tuple(sorted((int(nmap[x]), int(nmap[y])))) for x, y in zip(a, c)})
        k += 1
    nc.close()
    if conv in ("tandem", "seissol"):
        check(len(exo) > 0, "Exodus: %d side sets" % len(exo))
        return
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.open(os.path.join(out, "mesh.msh"))
    msh = []
    for dim, p in sorted(gmsh.model.getPhysicalGroups(1)):
        pairs = set()
        for ent in gmsh.model.getEntitiesForPhysicalGroup(1, p):
            _, _, nodes = gmsh.model.mesh.getElements(1, ent)
            for q in range(0, len(nodes[0]) if len(nodes) else 0, 2):
                pairs.add(tuple(sorted((int(nodes[0][q]) - 1, int(nodes[0][q + 1]) - 1))))
        msh.append(pairs)
    gmsh.finalize()
    check(len(exo) == len(msh) and len(exo) > 0 and all(a == b for a, b in zip(exo, msh)),
          "Exodus side sets = MSH physical curves (%d and %d groups, %d alike)" %
          (len(exo), len(msh), sum(a == b for a, b in zip(exo, msh))))


CONV = {"default", "tandem", "seissol", "pylith"}


def check_msh(out, faults, crs, conv, verts, groups):
    path = os.path.join(out, "mesh.msh")
    print("-- msh", path, conv)
    text = open(path, encoding="utf-8").read()
    version = text.split("\n")[1].split()[0]
    if conv == "tandem":
        check(version == "2.2", "tandem: MSH 2.2 (%s)" % version)
    com = re.search(r"\$Comments\n(.*?)\$EndComments\n", text, re.S)
    check(com is not None and ('"crs %s"' % crs.replace('"', "'")) in com.group(1),
          "$Comments names the CRS")
    m = meshio.read(path)
    tri_blocks = [i for i, c in enumerate(m.cells) if c.type == "triangle"]
    phys = np.concatenate([m.cell_data["gmsh:physical"][i] for i in tri_blocks])
    geom = np.concatenate([m.cell_data["gmsh:geometrical"][i] for i in tri_blocks])
    ntri = sum(len(v) for v in groups.values())
    check(len(phys) == ntri, "meshio: %d triangles" % len(phys))
    fd = {k: tuple(v) for k, v in m.field_data.items()}
    if conv in ("tandem", "seissol"):
        tag = 3 if conv == "tandem" else 103
        check(set(phys.tolist()) == {tag}, "%s: every triangle physical tag %d" % (conv, tag))
        check(fd == {"fault": (tag, 2)}, "%s: one physical group 'fault' = %d (%s)" % (conv, tag, fd))
    else:
        check(set(phys.tolist()) == set(range(1, len(faults) + 1)),
              "%s: physical tags 1..%d" % (conv, len(faults)))
        check(np.array_equal(phys, geom), "physical tag = elementary tag = fault index + 1")
        names = {v[0]: k for k, v in fd.items()}
        if conv == "pylith":
            labels = [names.get(i + 1, "") for i in range(len(faults))]
            check(all(re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", l) for l in labels),
                  "pylith: every label [A-Za-z][A-Za-z0-9_]*")
            check(len(set(labels)) == len(labels), "pylith: labels distinct")
        else:
            check(all(names.get(i + 1) == f.replace('"', "'").replace("\\", "/")[:200]
                      for i, f in enumerate(faults)), "default: group i + 1 named after fault i")
    # elementary tags: per fault its OBJ triangle count
    counts = np.bincount(geom, minlength=len(faults) + 1)[1:]
    want = [len(groups[obj_name(f)]) for f in faults]
    check(list(counts) == want, "triangles per elementary tag = per fault in the OBJ")
    # Gmsh reads it too
    gmsh.initialize(["check_fe_formats"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.open(path)
    groups_g = gmsh.model.getPhysicalGroups(2)
    ntag = {2: sum(len(gmsh.model.mesh.getElements(2, e)[1][0])
                   for e in [t for _, t in gmsh.model.getEntities(2)])}
    check(ntag[2] == ntri, "gmsh: %d triangles" % ntag[2])
    if conv in ("tandem", "seissol"):
        tag = 3 if conv == "tandem" else 103
        check([t for _, t in groups_g] == [tag] and gmsh.model.getPhysicalName(2, tag) == "fault",
              "gmsh: one physical surface %d 'fault'" % tag)
        ents = gmsh.model.getEntitiesForPhysicalGroup(2, tag)
        check(len(ents) == len(faults), "gmsh: it holds all %d fault entities" % len(faults))
    else:
        check(len(groups_g) == len(faults), "gmsh: %d physical surfaces" % len(groups_g))
    tags, _, _ = gmsh.model.mesh.getNodes()
    if conv == "tandem":
        check(sorted(tags.tolist()) == list(range(1, len(tags) + 1)), "tandem: node tags 1..n")
    gmsh.finalize()


def check_crs(out, crs, faults):
    print("-- crs", crs)
    rep = json.load(open(os.path.join(out, "report.json")))
    check(rep["options"].get("crs_out", rep["options"]["crs"]) == crs,
          "report.json options.crs (crs_out when given)")
    vtu = meshio.read(os.path.join(out, "mesh.vtu"))
    used = np.unique(np.concatenate([c.data.ravel() for c in vtu.cells]))
    check(len(used) == len(vtu.points), "VTU: every point is a corner of some triangle "
          "(%d points, %d used)" % (len(vtu.points), len(used)))
    got = vtu.field_data.get("crs")
    got = "".join(chr(c) for c in np.asarray(got).ravel() if c) if got is not None else None
    check(got == crs, "VTU field data crs (%r)" % got)
    head = open(os.path.join(out, "mesh.stl"), "rb").read(80)
    # the header holds what fits of the CRS after "CRS "
    at = head.find(b"CRS ")
    rest = head[at + 4:].rstrip(b"\0 ").decode("utf-8", "replace") if at >= 0 else ""
    check(len(rest) >= min(len(crs), 10) and crs.startswith(rest),
          "STL header names the CRS (%r)" % rest)
    _, _, comments = read_obj(os.path.join(out, "mesh.obj"))
    check(any(crs in c for c in comments), "OBJ comment names the CRS")
    bad = 0
    ts = [f for f in os.listdir(out) if f.endswith(".ts")]
    for f in ts:
        with open(os.path.join(out, f), encoding="utf-8") as fp:
            head = fp.read(2000)
        bad += ("\nNAME %s\n" % crs) not in head
    check(len(ts) == len(faults) and bad == 0, "%d TSurf files name the CRS in their block" % len(ts))
    return rep


def main():
    args = sys.argv[1:]
    if len(args) < 2 or args[1] not in CONV:
        print(__doc__)
        return 2
    out, conv = args[0], args[1]
    want_crs = args[args.index("--crs") + 1] if "--crs" in args else None
    rep = json.load(open(os.path.join(out, "report.json")))
    # the outputs' CRS: --crs-out's when given, else the input's
    crs = rep["options"].get("crs_out", rep["options"]["crs"])
    if want_crs is not None:
        check(crs == want_crs, "report.json CRS %r is %r" % (crs, want_crs))
    check(rep["options"].get("msh_tags") == conv, "report.json msh_tags %s" % conv)
    faults = [f["name"] for f in rep["faults"] if f.get("status") == "ok"]
    junctions = rep.get("connect", {}).get("junctions", [])
    verts, groups, _ = read_obj(os.path.join(out, "mesh.obj"))
    check_crs(out, crs, faults)
    check_exodus(out, faults, crs, junctions, verts, groups)
    check_msh(out, faults, crs, conv, verts, groups)
    check_side_sets(out, conv)
    if FAILED:
        print("FAILED: %d checks" % len(FAILED))
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
