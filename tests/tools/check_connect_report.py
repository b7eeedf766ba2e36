#!/usr/bin/python3
"""Holds report.json to what the independent check_connect measured.

usage: check_connect_report.py OUT_DIR CHECK_CONNECT_JSON

The connect issue asks that every pair of faults that crosses or comes
within the join distance shares nodes along a common curve, unless the
report gives a reason, and that no outline edge near another fault is left
unjoined without one. check_connect finds those pairs from the meshes alone
(exact triangle tests, boundary edges within D); this script looks each of
them up in report.json's junction table:
  - a pair that shares no node must have a junction entry, and every entry
    of that pair must be 'unjoined' with a non-empty reason;
  - a pair that shares edges must have at least one made junction
    (crossing, T or corner): otherwise they are shared by accident; a pair
    that shares nodes but no edge meets at triple points (the node of the
    curves of both with a third fault) and is treated as sharing none;
  - a pair left with unjoined near edges needs an entry of either kind
    (a made junction with part of the outline near but not on the curve,
    or an unjoined one with its reason).
Faults given up as near-duplicates (status 'dropped') are absent from the
mesh and so from check_connect's pairs. Prints the counts; exit 1 on any
pair without its line in the report.
"""
import collections
import json
import sys


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    rep = json.load(open(sys.argv[1] + "/report.json"))
    cc = json.load(open(sys.argv[2]))
    junctions = collections.defaultdict(list)
    for j in rep.get("connect", {}).get("junctions", []):
        junctions[frozenset(j["faults"])].append(j)
    bad = []
    n_near = n_shared = n_reasoned = n_points = 0
    for p in cc["pairs"]:
        key = frozenset((p["a"], p["b"]))
        js = junctions.get(key, [])
        made = [j for j in js if j["type"] != "unjoined"]
        near = p["near_edges_a"] + p["near_edges_b"] > 0
        if p["shared_edges"] > 0:
            n_shared += 1
            if not made:
                bad.append((p, "shares edges but the report has no junction made"))
            continue
        if p["shared_vertices"] > 0:
            n_points += 1
        if not (near or p["intersections"] > 0 or p["distance"] <= cc["distance"]):
            continue
        n_near += 1
        if not js:
            if p["shared_vertices"] > 0 and not near and p["intersections"] == 0:
                n_reasoned += 1  # touching only at a triple point: nothing to join
                continue
            bad.append((p, "within the join distance, no line in the report"))
        elif made:
            bad.append((p, "a junction is reported made but no node is shared"))
        elif any(not j.get("reason") for j in js):
            bad.append((p, "unjoined without a reason"))
        else:
            n_reasoned += 1
    print(f"check_connect_report: {n_shared} fault pairs share edges with a junction made; "
          f"{n_near} near pairs share none ({n_points} of them only triple points), "
          f"{n_reasoned} of them with a reported reason or touching only at a triple point")
    for p, why in bad[:20]:
        print(f"  {p['a']} ~ {p['b']}: {why} (distance {p['distance']:.1f} m)")
    if bad:
        print(f"FAIL: {len(bad)} fault pairs without their line in the report")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
