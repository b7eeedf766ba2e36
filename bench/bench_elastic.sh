#!/bin/sh
# The elastic interaction check (issue 19) on the whole CFM 5.3 500 m set
# at H (default 1000 m), connected, top cut: the run without the check
# and with it (`--elastic-check`), both reading the fits from the fit
# cache (filled by the first run), so that the difference is the check.
#
#   bench/bench_elastic.sh [-j N] [-b BUILD_DIR] [H]
#
# Prints wall, CPU and peak RSS (GNU time) of both runs, the check's own
# time (its log line), its counts, and its largest groups (fault pair,
# junction, pairs, ratio, distance). Skips (exit 0) when ../shared/cfm is
# absent.
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
H=${1:-1000}
# shellcheck source=bench/lib.sh
. "$here/bench/lib.sh"
bench_data bench_elastic
bench_exe bench_elastic
bench_timer bench_elastic
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM
echo "machine: $(nproc) cores, $(uname -m), load $(cut -d' ' -f1-3 /proc/loadavg)"
for run in plain elastic; do
    flag=""
    [ "$run" = elastic ] && flag="--elastic-check"
    # shellcheck disable=SC2086
    $timer -f '%e %U %S %M' -o "$tmp/time.$run" "$exe" remesh $jobs $flag --size "$H" \
        --formats vtu -o "$tmp/$run" "$data" >/dev/null 2>"$tmp/log.$run" || true
    read -r wall user sys rss <"$tmp/time.$run"
    echo "$run: wall $wall s, CPU $(echo "$user + $sys" | bc) s, peak RSS $((rss / 1024)) MB"
done
grep 'elastic check' "$tmp/log.elastic" || true
/usr/bin/python3 - "$tmp/elastic/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
e = r.get("elastic")
if not e or "groups" not in e:
    print("no elastic section:", e)
    sys.exit(0)
js = r.get("connect", {}).get("junctions", [])
print(f"elements {e['elements']} (left out: {e['left_out_above_surface']} above the surface, "
      f"{e['left_out_degenerate']} degenerate), self-stiffness {e['self_stiffness_min_pa_per_m']:.3g}"
      f" .. {e['self_stiffness_max_pa_per_m']:.3g} Pa/m, wrong sign {e['self_wrong_sign']}")
print(f"pairs evaluated {e['pairs_evaluated']}, singular {e['pairs_singular']}, flagged "
      f"{e['pairs_flagged']} in {len(e['groups'])} groups "
      f"({sum(1 for g in e['groups'] if g['junction'] is None)} without a junction), "
      f"largest ratio {e['max_ratio']:.2f}")
for g in sorted(e["groups"], key=lambda g: -g["pairs"])[:15]:
    jn = g["junction"]
    kind = js[jn - 1]["type"] if jn else "none"
    print(f"  {g['faults'][0]} / {g['faults'][1]}: junction {jn} ({kind}), {g['pairs']} pairs, "
          f"ratio {g['max_ratio']:.2f}, {g['min_distance_m']:.0f} m")
PY
