#!/usr/bin/env python3
"""report.html of a remesh run, checked against its report.json and its
mesh.obj: one self-contained page (no external references, nothing from
the network), problems before the overview, every fault's row with the
figures report.json has (at the precision shown) and its number in
names.csv, every junction's row numbered from 1, the junction counts,
the summary's triangle and edge counts the same as the histograms', a
badge word per kind (never "ok" on a fault with warnings), a dropped
near-duplicate described by the shares the 50 % rule decides on, the
pictures PNGs that decode and are not blank, and the packed triangles the
page draws decoded here (base64, zlib, the format of
src/report/mesh_pack.c) into each fault's very triangles of mesh.obj, to
H/16, with its junction edges those it shares with another fault, and
its original's outline chains around it.
Standard library only.
usage: check_report_html.py DIR [--page FILE] [--max-mb X]
  --page: check FILE (the DOM a browser made of the page) instead of
          DIR/report.html"""
import base64
import html.parser
import json
import math
import os
import re
import struct
import sys
import zlib


def png(data):
    """(width, height, raw scanlines) of a PNG; raises on a broken one."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("no PNG signature")
    at, idat, w = 8, b"", None
    while at < len(data):
        n, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + n]
        crc = struct.unpack(">I", data[at + 8 + n:at + 12 + n])[0]
        if zlib.crc32(kind + body) & 0xffffffff != crc:
            raise ValueError("bad CRC in %s" % kind)
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            if depth != 8 or ctype not in (2, 6):
                raise ValueError("unexpected PNG type %d/%d" % (depth, ctype))
            channels = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
        at += 12 + n
    raw = zlib.decompress(idat)
    if len(raw) != h * (1 + w * channels):
        raise ValueError("%d bytes of pixels for %d x %d" % (len(raw), w, h))
    return w, h, raw


class Tables(html.parser.HTMLParser):
    """Cell texts of every table with an id, row by row (tbody rows only),
    and the class of each cell's first span (the badge)."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.tables, self.stack, self.row, self.cell = {}, [], None, None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "table":
            self.stack.append(a.get("id"))
            if a.get("id"):
                self.tables[a["id"]] = []
        elif tag == "tr" and self.stack and self.stack[-1]:
            self.row = []
        elif tag in ("td", "th") and self.row is not None:
            self.cell = [tag, ""]
        elif tag in ("div", "br") and self.cell is not None:
            self.cell[1] += "\n"

    def handle_endtag(self, tag):
        if tag == "table" and self.stack:
            self.stack.pop()
        elif tag in ("td", "th") and self.cell is not None and self.row is not None:
            self.row.append(self.cell)
            self.cell = None
        elif tag == "tr" and self.row is not None:
            if any(c[0] == "td" for c in self.row):
                self.tables[self.stack[-1]].append([c[1].strip() for c in self.row])
            self.row = None

    def handle_data(self, data):
        if self.cell is not None:
            self.cell[1] += data


def unpack(b, ntags):
    """Per tag: (grid coordinates of its vertices, triangles, junction
    edges), decoded as the page's script decodes them."""
    at = [0]

    def uint():
        x, s = 0, 0
        while True:
            c = b[at[0]]
            at[0] += 1
            x |= (c & 127) << s
            s += 7
            if not c & 128:
                return x

    def sint():
        u = uint()
        return -(u + 1) // 2 if u & 1 else u // 2

    out = []
    for _ in range(ntags):
        nt = uint()
        T, Q, last, parent = [], [], [0, 0, 0], 0

        def vertex(pred):
            r = uint()
            if r:
                return len(Q) - r
            p = pred if pred else list(last)
            for c in range(3):
                last[c] = p[c] + sint()
            Q.append(tuple(last))
            return len(Q) - 1

        for _t in range(nt):
            sym = uint()
            if not sym:
                T.append((vertex(None), vertex(None), vertex(None)))
            else:
                parent += (sym - 1) // 3
                e = (sym - 1) % 3
                pa = T[parent]
                a, bb, o = pa[e], pa[(e + 1) % 3], pa[(e + 2) % 3]
                pred = [Q[a][k] + Q[bb][k] - Q[o][k] for k in range(3)]
                T.append((bb, a, vertex(pred)))
        nj = uint()
        J = [(uint(), uint()) for _ in range(nj)]
        O, at0 = [], [0, 0, 0]
        for _c in range(uint()):
            chain = []
            for _p in range(uint()):
                for k in range(3):
                    at0[k] += sint()
                chain.append(tuple(at0))
            O.append(chain)
        out.append((Q, T, J, O))
    if at[0] != len(b):
        raise ValueError("%d bytes left over" % (len(b) - at[0]))
    return out


def read_obj(path):
    """Vertices and, per object (fault, in order), its triangles."""
    V, faults = [], []
    for line in open(path):
        if line.startswith("v "):
            V.append(tuple(float(x) for x in line.split()[1:4]))
        elif line.startswith("o "):
            faults.append([])
        elif line.startswith("f "):
            faults[-1].append(tuple(int(x.split("/")[0]) - 1 for x in line.split()[1:4]))
    return V, faults


def check_mesh(page, data, out, fails):
    m = re.search(r'id="fm-mesh">([^<]*)<', page)
    if not m:
        fails.append("no packed triangles (fm-mesh)")
        return
    try:
        tags = unpack(zlib.decompress(base64.b64decode(m.group(1))), data["ntags"])
    except Exception as e:  # noqa: BLE001 (any decoding failure is a failure)
        fails.append("packed triangles do not decode: %s" % e)
        return
    if not os.path.exists(out + "/mesh.obj"):
        return
    V, faults = read_obj(out + "/mesh.obj")
    if len(faults) != len(tags):
        fails.append("%d tags packed, mesh.obj has %d faults" % (len(tags), len(faults)))
        return
    step, origin = data["step"], data["origin"]

    def cell(v):  # llround of a non-negative number, as mesh_pack.c rounds
        return tuple(math.floor((v[k] - origin[k]) / step + 0.5) for k in range(3))

    cells = [cell(v) for v in V]
    edges = {}
    for h, ftris in enumerate(faults):
        for t in ftris:
            for k in range(3):
                edges.setdefault(frozenset((t[k], t[(k + 1) % 3])), set()).add(h)
    bad = 0
    for g, ((Q, T, J, O), tris) in enumerate(zip(tags, faults)):
        # the same triangles, corner by corner on the grid; as many vertices
        mine = {v for t in tris for v in t}
        got = sorted(tuple(sorted(Q[v] for v in t)) for t in T)
        want = sorted(tuple(sorted(cells[v] for v in t)) for t in tris)
        if got != want or len(Q) != len(mine):
            fails.append("fault %d: packed triangles (%d, %d vertices) differ from mesh.obj's "
                         "(%d, %d vertices)" % (g + 1, len(T), len(Q), len(tris), len(mine)))
            bad += 1
            continue
        # junction edges: those of its triangles another fault's have too
        want_j = {frozenset((t[k], t[(k + 1) % 3])) for t in tris for k in range(3)}
        want_j = sorted(tuple(sorted(cells[v] for v in e)) for e in want_j if len(edges[e]) > 1)
        got_j = sorted(tuple(sorted((Q[a], Q[b]))) for a, b in J)
        if got_j != want_j:
            fails.append("fault %d: %d junction edges packed, %d shared in mesh.obj" % (
                g + 1, len(got_j), len(want_j)))
            bad += 1
        # its original's outline: chains (closed but where a branching
        # fault's sheets meet) around the new mesh's extent (the mesh is the
        # original trimmed, cut or extended a little)
        if not O or any(len(c) < 2 for c in O) or sum(c[0] == c[-1] for c in O) == 0:
            fails.append("fault %d: its original's outline has no closed chain" % (g + 1))
            bad += 1
            continue
        lo = [min(q[k] for q in Q) for k in range(3)]
        hi = [max(q[k] for q in Q) for k in range(3)]
        olo = [min(q[k] for c in O for q in c) for k in range(3)]
        ohi = [max(q[k] for c in O for q in c) for k in range(3)]
        slack = 20 * 16  # 20 H: extensions to sea level and gaps closed
        if any(olo[k] > hi[k] or ohi[k] < lo[k] or abs(olo[k] - lo[k]) > slack
               or (k < 2 and abs(ohi[k] - hi[k]) > slack) for k in range(3)):
            fails.append("fault %d: its original's outline (%s..%s) far from its mesh (%s..%s)" % (
                g + 1, olo, ohi, lo, hi))
            bad += 1
    if not bad:
        print("ok    report.html: the packed triangles of %d faults are mesh.obj's on a grid of "
              "%g m, junction edges too; their originals' outlines around them"
              % (len(tags), step))


def why(j):
    """A junction's reason as the page words it: report.json's, and the gap
    left where one fault stops short of the other."""
    parts = [j["reason"]] if j.get("reason") else []
    if j.get("stops_short"):
        parts.append("a gap of %.0f m is left: %s stops short" % (j["gap_left_m"], j["stops_short"]))
    return "; ".join(parts)


def near(text, value, digits):
    try:
        return abs(float(text) - value) <= 0.5 * 10 ** -digits + 1e-9 * abs(value)
    except ValueError:
        return False


def main():
    args = sys.argv[1:]
    out = args[0]
    page_path = args[args.index("--page") + 1] if "--page" in args else out + "/report.html"
    max_mb = float(args[args.index("--max-mb") + 1]) if "--max-mb" in args else None
    page = open(page_path, encoding="utf-8").read()
    rep = json.load(open(out + "/report.json"))
    fails = []
    if re.search(r'(src|href)="(?!data:|#)', page) or re.search(r"https?://|@import|url\(", page):
        fails.append("report.html refers to another file or the network")
    size = os.path.getsize(out + "/report.html")
    if max_mb is not None and size > max_mb * 1e6:
        fails.append("report.html is %.2f MB, over %.2f MB" % (size / 1e6, max_mb))
    order = [page.find('id="%s"' % k) for k in ("problems", "map", "quality", "faults", "junctions")]
    if -1 in order or order != sorted(order):
        fails.append("sections out of order (problems first): %s" % order)
    if '<nav class="toc">' not in page:
        fails.append("no table of contents")
    p = Tables()
    p.feed(page)
    t = p.tables
    data = json.loads(re.search(r'id="fm-data">(.*?)</script>', page, re.S).group(1))

    # every fault: its row, in report.json's order, with its figures
    rows = {r[1]: r for r in t.get("fault-table", [])}
    numbers = {}
    if os.path.exists(out + "/names.csv"):
        for line in open(out + "/names.csv").read().splitlines()[1:]:
            n, name = line.split(",")[:2]
            numbers[name] = n
    checked = 0
    for f in rep["faults"]:
        name = f.get("name", f["file"])
        r = rows.get(name)
        if not r:
            fails.append("fault %s has no row" % name)
            continue
        if numbers and r[0] != numbers.get(name, ""):
            fails.append("%s: # %r, names.csv %r" % (name, r[0], numbers.get(name, "")))
        warned = bool(f.get("warnings"))
        carved = bool(f.get("carved_triangles"))
        badge = {"ok": "cut back" if carved else "warnings" if warned else "ok",
                 "dropped": "dropped", "empty": "empty", "excluded": "excluded"}.get(
                     f["status"], "failed")
        if r[2] != badge:
            fails.append("%s: badge %r, expected %r" % (name, r[2], badge))
        if f["status"] != "ok":
            if f.get("error") and f["error"].split(": ")[0].split("/")[-1] not in page:
                fails.append("%s: its reason is missing" % name)
            continue
        q, s, fid = f["quality"], f["size"], f["fidelity"]
        want = [(3, f["triangles"], 0), (4, q["min_angle_deg"], 1),
                (5, 100 * q["triangles_below_30_deg"] / f["triangles"], 2),
                (6, 100 * s["edges_within_0.7_1.4"] / s["edges"], 2),
                (7, fid["node_to_original_rms_m"], 1), (8, fid["node_to_original_max_m"], 1),
                (9, fid["coverage"], 3)]
        for col, v, d in want:
            if not near(r[col], v, d):
                fails.append("%s: column %d shows %r, report.json %.6g" % (name, col, r[col], v))
        for w in f.get("warnings", []):
            if w not in r[10]:
                fails.append("%s: warning missing: %s" % (name, w))
        checked += 1
    if len(rows) != len(rep["faults"]):
        fails.append("%d fault rows, report.json has %d faults" % (len(rows), len(rep["faults"])))

    # dropped near-duplicates: the share the 50 % rule decides on is shown
    for f in rep["faults"]:
        if f["status"] != "dropped" or "near-duplicate of" not in f.get("error", ""):
            continue
        shares = [float(x) for x in re.findall(r"(\d+)% of th[a-z]+ one", f["error"])]
        if len(shares) != 2 or max(shares) < 50:
            fails.append("%s: dropped, but no share of 50%% or more is given: %s" % (
                f["name"], f["error"]))

    # junctions numbered from 1, with report.json's figures
    c = rep["connect"]
    if c.get("enabled"):
        line = "%d junctions: %d crossing, %d T, %d corner, %d unjoined" % (
            len(c["junctions"]), c["crossing"], c["T"], c["corner"], c["unjoined"])
        if line not in page:
            fails.append("no '%s'" % line)
        jrows = t.get("junction-table", [])
        if len(jrows) != len(c["junctions"]):
            fails.append("%d junction rows, report.json has %d" % (len(jrows), len(c["junctions"])))
        for i, (r, j) in enumerate(zip(jrows, c["junctions"])):
            ok = (r[0] == str(i + 1) and r[1:3] == j["faults"] and r[3] == j["type"]
                  and near(r[4], j["gap_closed_m"], 0) and near(r[5], j["overshoot_trimmed_m"], 0)
                  and near(r[6], j["curve_length_m"], 0)
                  and near(r[7], j["min_crossing_angle_deg"], 1)
                  and r[8] == why(j))
            if not ok:
                fails.append("junction %d: row %s, report.json %s" % (i + 1, r, j))
                break

    # the summary's counts, the histograms' captions
    sm = rep["summary"]
    facts = {r[0]: r[1] for r in t.get("summary-table", [])}
    for key, label, cap in (("triangles", "triangles", r"(\d+) triangles, \d+ \("),
                            ("edges", "edges", r"(\d+) edges \(each once per fault")):
        if not facts.get(label, "").startswith("%d;" % sm[key]):
            fails.append("summary %s %r, report.json %d" % (label, facts.get(label), sm[key]))
        m = re.search(cap, page)
        if not m or int(m.group(1)) != sm[key]:
            fails.append("histogram caption: %s %s, report.json %d" % (
                key, m.group(1) if m else None, sm[key]))

    imgs = re.findall(r'src="data:image/png;base64,([^"]*)"', page)
    if len(imgs) != 5:
        fails.append("%d pictures, expected the map and 4 histograms" % len(imgs))
    for k, b in enumerate(imgs):
        try:
            w, h, raw = png(base64.b64decode(b))
        except Exception as e:  # noqa: BLE001 (any decoding failure is a failure)
            fails.append("picture %d: %s" % (k, e))
            continue
        if len(set(raw)) < 16:
            fails.append("picture %d looks blank" % k)
    check_mesh(page, data, out, fails)
    for f in fails:
        print("FAIL: report.html: " + f)
    if not fails:
        print("ok    report.html: %d faults (%d meshed checked figure by figure), %d junctions, "
              "%.2f MB" % (len(rep["faults"]), checked, len(c.get("junctions", [])), size / 1e6))
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
