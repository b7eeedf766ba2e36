#!/usr/bin/env python3
"""report.html in a real browser: headless Chromium (Debian's chromium)
opens the page of a run with one fault's panel open, once with WebGL
(SwiftShader, the software renderer) and once with WebGL switched off,
which the page must survive by drawing its 3D view on a 2D canvas.
A probe script put before the page's own records every script error,
unhandled rejection and console error, sorts the fault table by its
triangles and filters the junction table to the unjoined ones. Checked:
no error; the page's script ran to its end; the panel shows the fault
asked for with its very number of triangles decoded, and its neighbours'
in the 3D view (report.json's junctions name them); the sort and the
filter work; a click on the map where only that fault has a node opens
its panel; the DOM the browser made holds the figures of report.json
(check_report_html.py on it, with the packed triangles against mesh.obj);
a screenshot is saved (OUTDIR/report_panel.png) and is not blank.
usage: report_browser_check.py FAULTMESH OUTDIR [INPUTDIR]
  without INPUTDIR: `faultmesh demo`; with it: `faultmesh remesh --size
  1000 INPUTDIR`, skipped (exit 77) when INPUTDIR is absent. Exit 77 too
  when chromium is not installed (scripts/setup.sh installs it)."""
import json
import os
import shutil
import subprocess
import sys
import urllib.parse
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))

PROBE = """<script>(function () {
  var root = document.documentElement, errors = [];
  function note(m) { errors.push(String(m)); root.setAttribute('data-probe-errors', errors.join(' | ')); }
  window.addEventListener('error', function (e) { note(e.message || 'a resource failed to load'); }, true);
  window.addEventListener('unhandledrejection', function (e) {
    note('unhandled rejection: ' + (e.reason && e.reason.message || e.reason)); });
  var ce = console.error;
  console.error = function () { note(Array.prototype.join.call(arguments, ' ')); ce.apply(console, arguments); };
  window.addEventListener('load', function () { setTimeout(function () {
    try {
      var click = CLICK;
      if (click) {
        var img = document.querySelector('#fm-map img'), b = img.getBoundingClientRect();
        img.dispatchEvent(new MouseEvent('click', { bubbles: true,
          clientX: b.left + click[0] * b.width / img.naturalWidth,
          clientY: b.top + click[1] * b.height / img.naturalHeight }));
      }
      var t = document.getElementById('fault-table');
      t.tHead.rows[0].cells[3].click();
      var v = [].map.call(t.tBodies[0].rows, function (r) { return r.cells[3].textContent.trim(); })
        .filter(function (x) { return x !== ''; }).map(Number);
      root.setAttribute('data-probe-sorted', v.every(function (x, i) { return !i || v[i - 1] <= x; }) ? 'yes' : 'no');
      var box = document.querySelector('.filter[data-for="junction-table"]');
      if (box) {
        var sel = box.querySelector('select');
        sel.value = 'unjoined';
        sel.dispatchEvent(new Event('input'));
        root.setAttribute('data-probe-unjoined', [].filter.call(
          document.getElementById('junction-table').tBodies[0].rows, function (r) { return !r.hidden; }).length);
      }
    } catch (e) { note('probe: ' + e.message); }
  }, 0); });
})();</script>"""


def map_point(out, page, name):
    """A pixel of the map where fault `name` has a node and no other fault
    one within 3 pixels (the page opens the fault of the node nearest to a
    click), from mesh.obj and the map's frame; None when there is none."""
    import math
    import re
    x0, y1, k = map(float, re.search(r'id="fm-map" data-frame="([^"]*)"', page).group(1).split())
    V, owner, faults, cur = [], {}, [], None
    for line in open(os.path.join(out, "mesh.obj")):
        if line.startswith("v "):
            V.append(tuple(float(x) for x in line.split()[1:3]))
        elif line.startswith("o "):
            cur = line[2:].strip()
            faults.append(cur)
        elif line.startswith("f "):
            for x in line.split()[1:4]:
                owner.setdefault(int(x.split("/")[0]) - 1, set()).add(cur)
    cell = 3 / k
    grid = {}
    for v, who in owner.items():
        grid.setdefault((math.floor(V[v][0] / cell), math.floor(V[v][1] / cell)), []).append(v)
    for v, who in sorted(owner.items()):
        if who != {name}:
            continue
        cx, cy = math.floor(V[v][0] / cell), math.floor(V[v][1] / cell)
        near = [u for dx in (-1, 0, 1) for dy in (-1, 0, 1) for u in grid.get((cx + dx, cy + dy), [])]
        if all(owner[u] == {name} or math.dist(V[u], V[v]) > cell for u in near):
            return [(V[v][0] - x0) * k, (y1 - V[v][1]) * k]
    return None


def chromium():
    for name in ("chromium", "chromium-browser"):
        path = shutil.which(name)
        if path:
            return path
    return None


def browse(exe, profile, url, *extra):
    cmd = [exe, "--headless", "--no-sandbox", "--enable-unsafe-swiftshader",
           "--user-data-dir=" + profile, "--no-first-run", "--virtual-time-budget=30000",
           "--hide-scrollbars", *extra, url]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    return r.stdout


def attrs(dom):
    """The attributes of the <html> element of a dumped DOM."""
    head = dom[dom.find("<html"):]
    head = head[:head.find(">")]
    out = {}
    for part in head.split('" ')[0:]:
        if "=" in part:
            k, v = part.split("=", 1)
            out[k.split()[-1]] = v.strip('"')
    return out


def blank(png_path):
    data = open(png_path, "rb").read()
    at, idat = 8, b""
    while at < len(data):
        n = int.from_bytes(data[at:at + 4], "big")
        if data[at + 4:at + 8] == b"IDAT":
            idat += data[at + 8:at + 8 + n]
        at += 12 + n
    return len(set(zlib.decompress(idat))) < 32


def main():
    faultmesh, outdir = sys.argv[1], sys.argv[2]
    inputdir = sys.argv[3] if len(sys.argv) > 3 else None
    exe = chromium()
    if not exe:
        print("skipped: no chromium (scripts/setup.sh installs it)")
        return 77
    if inputdir and not os.path.isdir(inputdir):
        print("skipped: %s is absent" % inputdir)
        return 77
    shutil.rmtree(outdir, ignore_errors=True)
    os.makedirs(outdir)
    out = os.path.join(outdir, "run")
    run = ([faultmesh, "remesh", "--size", "1000", "--quiet", "-o", out, inputdir] if inputdir
           else [faultmesh, "demo", "--quiet", "-o", out])
    if subprocess.run(run).returncode:
        print("FAIL: %s" % " ".join(run))
        return 1
    rep = json.load(open(os.path.join(out, "report.json")))
    faults = {f["name"]: f for f in rep["faults"]}
    ok = [f for f in rep["faults"] if f["status"] == "ok"]
    pick = next((f for f in ok if f.get("warnings")), ok[0])
    name = pick["name"]
    nb = set()
    for j in rep["connect"].get("junctions", []):
        if name in j["faults"]:
            nb |= set(j["faults"]) - {name}
    want3d = pick["triangles"] + sum(faults[n].get("triangles", 0) for n in nb
                                     if faults[n]["status"] == "ok")
    page = open(os.path.join(out, "report.html"), encoding="utf-8").read()
    at = page.index("<head>") + len("<head>")
    probe = os.path.join(outdir, "probe.html")
    open(probe, "w", encoding="utf-8").write(page[:at] + PROBE.replace("CLICK", "null") + page[at:])
    click = map_point(out, page, name)
    probe_map = os.path.join(outdir, "probe_map.html")
    open(probe_map, "w", encoding="utf-8").write(
        page[:at] + PROBE.replace("CLICK", json.dumps(click)) + page[at:])
    url = "file://" + urllib.parse.quote(probe) + "#fault=" + urllib.parse.quote(name)
    profile = os.path.join(outdir, "profile")
    fails = []
    for label, extra, view in (("WebGL", (), ("webgl",)), ("no WebGL", ("--disable-3d-apis",), ("2d",))):
        dom = browse(exe, profile, url, "--dump-dom", *extra)
        a = attrs(dom)
        if "data-probe-errors" in a:
            fails.append("%s: script errors: %s" % (label, a["data-probe-errors"]))
        checks = [("data-fm-ready", "1"), ("data-fm-panel", name),
                  ("data-fm-triangles", str(pick["triangles"])),
                  ("data-fm-3d-triangles", str(want3d)), ("data-probe-sorted", "yes")]
        if rep["connect"].get("enabled"):
            checks.append(("data-probe-unjoined", str(rep["connect"]["unjoined"])))
        for k, v in checks:
            if a.get(k) != v:
                fails.append("%s: %s = %r, expected %r" % (label, k, a.get(k), v))
        if a.get("data-fm-view") not in view:
            fails.append("%s: 3D view drawn by %r, expected %s" % (label, a.get("data-fm-view"), view))
        if not fails:
            print("ok    %s: no script error; panel of %s: %s triangles, %s in 3D with %d "
                  "neighbours (%s); sort and filter work" % (
                      label, name, a["data-fm-triangles"], a["data-fm-3d-triangles"], len(nb),
                      a["data-fm-view"]))
        if label == "WebGL":
            domfile = os.path.join(outdir, "dom.html")
            open(domfile, "w", encoding="utf-8").write(dom)
            check = [sys.executable, os.path.join(HERE, "check_report_html.py"), out,
                     "--page", domfile, "--max-mb", "3"]
            if subprocess.run(check).returncode:
                fails.append("the page as the browser made it disagrees with report.json")
    # the map: a click on a node of the fault opens its panel
    if click is None:
        fails.append("no pixel of the map where %s alone has a node" % name)
    else:
        a = attrs(browse(exe, profile, "file://" + urllib.parse.quote(probe_map), "--dump-dom"))
        if a.get("data-fm-panel") != name or "data-probe-errors" in a:
            fails.append("a click on the map at %s opened %r, not %s (%s)" % (
                click, a.get("data-fm-panel"), name, a.get("data-probe-errors", "no error")))
        else:
            print("ok    a click on the map at (%.0f, %.0f) opens %s" % (click[0], click[1], name))
    shot = os.path.join(outdir, "report_panel.png")
    browse(exe, profile, url, "--screenshot=" + shot, "--window-size=1400,1800")
    if not os.path.exists(shot) or blank(shot):
        fails.append("no screenshot, or a blank one")
    else:
        print("ok    screenshot %s (%d bytes)" % (shot, os.path.getsize(shot)))
    for f in fails:
        print("FAIL: " + f)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
