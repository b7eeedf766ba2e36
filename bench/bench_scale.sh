#!/bin/sh
# Speed and scale (issue 20): the whole CFM 5.3 500 m set run the way users
# run it (`faultmesh remesh`, connected, top cut, every output written), cold,
# at each size given (default 2000 1000 500 250 m):
#
#   bench/bench_scale.sh [-j N] [-b BUILD_DIR] [-r REPEAT] [-w] [H ...]
#
# -w: warm instead, as a user re-running at another size: a fresh cache is
# filled by one run at 3000 m (not timed), and every size is then run with
# it (fits, the junction plan's neighbours and traced curves read, not made).
#
# Prints the machine, then per size: wall and CPU time and peak RSS (GNU
# time), triangles, and the stage times from report.json (fit, connect, mesh,
# merge and check, write); then how each grows with the triangle count, as
# d log(time) / d log(triangles) between consecutive sizes and as the
# least-squares slope over all sizes. Targets: mesh, merge and check, and
# write no faster than N^1.05 from 2 km to 250 m. Passes --no-cache when
# `faultmesh remesh --help` offers it, so that nothing is served from a fit
# cache. 250 m takes minutes and about 2.5 GB. Run it on an otherwise idle
# machine: the load average is printed; on a shared one, -r REPEAT runs each
# size REPEAT times and keeps the run of least wall time. Skips (exit 0) when
# ../shared/cfm is absent.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
build="$here/build"
jobs=""
repeat=1
warm=""
while [ $# -gt 0 ]; do
    case "$1" in
    -j) jobs="-j $2"; shift 2 ;;
    -b) build="$2"; shift 2 ;;
    -r) repeat="$2"; shift 2 ;;
    -w) warm=1; shift ;;
    *) break ;;
    esac
done
[ $# -gt 0 ] || set -- 2000 1000 500 250
# shellcheck source=bench/lib.sh
. "$here/bench/lib.sh"
bench_data bench_scale
bench_exe bench_scale
bench_timer bench_scale
py=/usr/bin/python3
cold=""
if "$exe" remesh --help 2>&1 | grep -q -e '--no-cache'; then
    cold="--no-cache"
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM
if [ -n "$warm" ]; then
    cold="--cache $tmp/cache"
    "$exe" remesh --quiet $jobs --top cut $cold --size 3000 -o "$tmp/fill" "$data" >/dev/null ||
        { echo "bench_scale: filling the cache failed" >&2; exit 1; }
    rm -rf "$tmp/fill"
fi
model=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
echo "machine: $(nproc) cores, $model, $(uname -m), load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "run: $exe remesh --quiet ${jobs:+$jobs }--top cut${cold:+ $cold} --size H" \
    "(cache: ${warm:+warm, filled at 3000 m, }${cold:-none offered}), best of $repeat"
: >"$tmp/rows"
for H in "$@"; do
    : >"$tmp/runs"
    i=0
    while [ "$i" -lt "$repeat" ]; do
        i=$((i + 1))
        rc=0
        # shellcheck disable=SC2086
        $timer -f '%e %U %S %M' -o "$tmp/time" "$exe" remesh --quiet $jobs --top cut $cold \
            --size "$H" -o "$tmp/out" "$data" >/dev/null || rc=$?
        # its last line: GNU time puts "Command exited with non-zero status" first
        read -r wall user sys rss <<EOF
$(tail -n 1 "$tmp/time")
EOF
        if ! "$py" - "$tmp/out/report.json" "$H" "$wall" "$user" "$sys" "$rss" "$rc" \
            >>"$tmp/runs" <<'PY'
import json, sys
rep, H, wall, user, sys_, rss, rc = sys.argv[1:]
s = json.load(open(rep))["summary"]
print(H, wall, float(user) + float(sys_), int(rss) / 1024, s["triangles"], s["time_fit_s"],
      s["time_connect_s"], s["time_mesh_s"], s["time_merge_s"], s["time_write_s"], rc)
PY
        then
            echo "bench_scale: H = $H m: no report.json (exit status $rc)" >&2
            exit 1
        fi
        rm -rf "$tmp/out"
    done
    sort -g -k 2 "$tmp/runs" | head -n 1 >>"$tmp/rows"
    tail -n 1 "$tmp/rows" | "$py" -c '
import sys
H, wall, cpu, rss, tri, fit, con, mesh, merge, write, rc = sys.stdin.read().split()
print(f"H = {H} m: wall {float(wall):.1f} s, CPU {float(cpu):.1f} s, peak RSS {float(rss):.0f} MB, "
      f"triangles {int(tri)}" + (f", exit status {rc}" if rc != "0" else ""))
print(f"  stages: fit {float(fit):.1f} s, connect {float(con):.1f} s, mesh {float(mesh):.1f} s, "
      f"merge and check {float(merge):.1f} s, write {float(write):.1f} s")'
done
"$py" - "$tmp/rows" <<'PY'
import math, sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
rows = [[float(x) for x in r] for r in rows]
rows.sort(key=lambda r: r[4])  # by triangles, fewest first
if len(rows) < 2:
    sys.exit(0)
cols = [("fit", 5), ("connect", 6), ("mesh", 7), ("merge+check", 8), ("write", 9),
        ("wall", 1), ("CPU", 2), ("peak RSS", 3)]
target = {"mesh", "merge+check", "write"}
def slope(pts):
    pts = [(math.log(n), math.log(t)) for n, t in pts if n > 0 and t > 0]
    if len(pts) < 2:
        return float("nan")
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    sxx = sum((x - mx) ** 2 for x, _ in pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sxx if sxx else float("nan")
pairs = [f"{a[0]:g}->{b[0]:g}" for a, b in zip(rows, rows[1:])]
print("growth d log(x) / d log(triangles)   (target <= 1.05 for mesh, merge+check, write)")
print(f"  {'':12s}" + "".join(f"{p:>12s}" for p in pairs) + f"{'all (LSQ)':>12s}")
for name, c in cols:
    cells = [slope([(a[4], a[c]), (b[4], b[c])]) for a, b in zip(rows, rows[1:])]
    overall = slope([(r[4], r[c]) for r in rows])
    mark = "  over" if name in target and overall > 1.05 else ""
    print(f"  {name:12s}" + "".join(f"{x:12.2f}" for x in cells) + f"{overall:12.2f}{mark}")
PY
