#!/bin/sh
# The connect issue's speed target, measured the way users run it: the
# whole CFM 5.3 500 m set connected and meshed by `faultmesh remesh` (top
# cut, default join distance), at each size given (default 1000 m).
#
#   bench/bench_remesh_connected.sh [-j N] [-b BUILD_DIR] [H ...]
#
# Prints per size: wall and CPU time (GNU time), peak RSS, the stage times
# from report.json (fit, connect, mesh), and the junction counts, so that
# a speed change that comes from joining less is seen. Skips (exit 0) when
# ../shared/cfm is absent. Target: <= 60 s wall at H = 1000 m on a 2-core
# machine.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
build="$here/build"
jobs=""
while [ $# -gt 0 ]; do
    case "$1" in
    -j) jobs="-j $2"; shift 2 ;;
    -b) build="$2"; shift 2 ;;
    *) break ;;
    esac
done
[ $# -gt 0 ] || set -- 1000
# shellcheck source=bench/lib.sh
. "$here/bench/lib.sh"
bench_data bench_remesh_connected
bench_exe bench_remesh_connected
bench_timer bench_remesh_connected
py=/usr/bin/python3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM
echo "machine: $(nproc) cores, $(uname -m), load $(cut -d' ' -f1-3 /proc/loadavg)"
for H in "$@"; do
    # every size fits (--no-cache), as the figures in docs/ were measured
    # shellcheck disable=SC2086
    $timer -f '%e %U %S %M' -o "$tmp/time" "$exe" remesh --quiet --no-cache $jobs --size "$H" \
        -o "$tmp/out" "$data" >/dev/null || true
    read -r wall user sys rss <"$tmp/time"
    "$py" - "$tmp/out/report.json" "$H" "$wall" "$user" "$sys" "$rss" <<'PY'
import json, sys
rep, H, wall, user, sys_, rss = sys.argv[1:]
r = json.load(open(rep))
s, c = r["summary"], r.get("connect", {})
print(f"H = {H} m: wall {float(wall):.1f} s, CPU {float(user) + float(sys_):.1f} s, "
      f"peak RSS {int(rss) / 1024:.0f} MB")
print(f"  stages: fit {s['time_fit_s']:.1f} s, connect {s['time_connect_s']:.1f} s, "
      f"mesh {s['time_mesh_s']:.1f} s")
print(f"  faults {s['faults']}, meshed {s['meshed']}, failed {s['failed']}, "
      f"triangles {s['triangles']}")
print(f"  junctions: crossing {c.get('crossing')}, T {c.get('T')}, corner {c.get('corner')}, "
      f"unjoined {c.get('unjoined')}, shared nodes {c.get('shared_nodes')}")
PY
    rm -rf "$tmp/out"
done
