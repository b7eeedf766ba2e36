#!/usr/bin/env python3
"""report.html of a remesh run, checked against its report.json: one
self-contained page (no external references), every fault named in it,
the junction counts the same, and its pictures PNGs that decode (the map,
four histograms, one 360 x 200 view per fault with an original) and
are not blank. Standard library only (zlib for the PNG data).
usage: check_report_html.py DIR"""
import base64
import html
import json
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


def main():
    out = sys.argv[1]
    page = open(out + "/report.html", encoding="utf-8").read()
    rep = json.load(open(out + "/report.json"))
    fails = []
    if re.search(r'(src|href)="(?!data:)', page):
        fails.append("report.html refers to another file")
    for f in rep["faults"]:
        name = f.get("name", f["file"])
        if "<b>%s</b>" % html.escape(name) not in page:
            fails.append("fault %s missing" % name)
    c = rep["connect"]
    if c.get("enabled"):
        line = "%d junctions: %d crossing, %d T, %d corner, %d unjoined" % (
            len(c["junctions"]), c["crossing"], c["T"], c["corner"], c["unjoined"])
        if line not in page:
            fails.append("no '%s'" % line)
    imgs = re.findall(r'src="data:image/png;base64,([^"]*)"', page)
    want = 5 + len(rep["faults"])  # every demo fault was read
    if len(imgs) != want:
        fails.append("%d pictures, expected %d" % (len(imgs), want))
    for k, b in enumerate(imgs):
        try:
            w, h, raw = png(base64.b64decode(b))
        except Exception as e:  # noqa: BLE001 (any decoding failure is a failure)
            fails.append("picture %d: %s" % (k, e))
            continue
        if k >= 5 and (w, h) != (360, 200):
            fails.append("fault picture %d is %d x %d" % (k, w, h))
        if len(set(raw)) < 16:
            fails.append("picture %d looks blank" % k)
    for f in fails:
        print("FAIL: report.html: " + f)
    if not fails:
        print("ok    report.html: %d faults, %d pictures, %.1f MB" % (
            len(rep["faults"]), len(imgs), len(page) / 1e6))
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
