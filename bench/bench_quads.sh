#!/bin/sh
# Rectangular elements (--elements quad) on the whole CFM 5.3 500 m set,
# connected, top cut, as users run it, at each size given (default 2000 m):
#
#   bench/bench_quads.sh [-j N] [-b BUILD_DIR] [H ...]
#
# Prints per size: wall and CPU time and peak RSS (GNU time) of the whole
# run, the write stage's time (where the tiling happens) from report.json,
# and the rectangles' figures (count, area, flatness, junction gaps).
# Skips (exit 0) when ../shared/cfm is absent.
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
[ $# -gt 0 ] || set -- 2000
# shellcheck source=bench/lib.sh
. "$here/bench/lib.sh"
bench_data bench_quads
bench_exe bench_quads
bench_timer bench_quads
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for H in "$@"; do
    # every size fits (--no-cache), as the figures in docs/ were measured
    # shellcheck disable=SC2086
    "$timer" -f "%e %U %S %M" -o "$out/time" "$exe" remesh $jobs --quiet \
        --no-cache --size "$H" --elements quad --eqsim-coords utm -o "$out/$H" "$data" || true
    read -r wall user sys rss <"$out/time"
    /usr/bin/python3 - "$out/$H/report.json" "$H" "$wall" "$user" "$sys" "$rss" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
q, s = r["rectangles"], r["summary"]
H, wall, user, sysc, rss = sys.argv[2], *map(float, sys.argv[3:])
fs = [f for f in q["faults"] if f["elements"]]
tot = sum(f["area_triangles_m2"] for f in fs)
til = sum(f["area_rectangles_m2"] for f in fs)
out3 = sum(1 for f in fs if abs(f["area_ratio"] - 1) > 0.03)
js = q["junctions"]
print("H %s m: %.1f s wall, %.1f s CPU, %.0f MB peak; write stage %.1f s; %d rectangles; "
      "area %.4f of the triangles' (%d of %d faults outside 3 %%); flatness p99 %.0f m "
      "(%.3f H); junction gaps over H/2 on %d of %d junctions (%.1f of %.0f km); %d meeting"
      % (H, wall, user + sysc, rss / 1024, s["time_write_s"], q["elements"], til / tot, out3,
         len(fs), q["flatness_p99_m"], q["flatness_p99_of_size"],
         q["junctions_with_gap_over_half_size"], len(js),
         sum(j["length_gap_over_half_size_m"] for j in js) / 1e3,
         sum(j["length_m"] for j in js) / 1e3, q["meeting_pairs"]))
PY
done
