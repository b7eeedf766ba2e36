#!/bin/sh
# The whole-CFM run on 1 thread and on N (default: every core), the way
# users run it (`faultmesh remesh` on the CFM 5.3 500 m set, connected,
# every format written): wall times, the speedup, and whether the outputs
# are byte-identical (report.json, which records timings, aside). Issue 7's
# target: at least 1.7x with 2 cores. Run it on an otherwise idle machine;
# it prints the load average first.
#
#   bench/bench_jobs_speedup.sh [-b BUILD_DIR] [-n N] [H]
#
# Skips (exit 0) when ../shared/cfm is absent.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
build="$here/build"
n=$(nproc 2>/dev/null || echo 2)
while [ $# -gt 0 ]; do
    case "$1" in
    -b) build="$2"; shift 2 ;;
    -n) n="$2"; shift 2 ;;
    *) break ;;
    esac
done
H=${1:-1000}
# shellcheck source=bench/lib.sh
. "$here/bench/lib.sh"
bench_data bench_jobs_speedup
bench_exe bench_jobs_speedup
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM
now() { date +%s.%N; }
echo "machine: $(nproc) cores, $(uname -m), load $(cut -d' ' -f1-3 /proc/loadavg)"
run() { # jobs
    t0=$(now)
    # both runs fit (--no-cache): the second would read the first's models
    "$exe" remesh --quiet --no-cache -j "$1" --size "$H" -o "$tmp/j$1" "$data" >/dev/null 2>"$tmp/err$1" || true
    t1=$(now)
    echo "$t0 $t1" | awk '{printf "%.2f", $2 - $1}'
}
w1=$(run 1)
wn=$(run "$n")
same=yes
for f in "$tmp/j1"/*; do
    b=$(basename "$f")
    [ "$b" = report.json ] && continue
    cmp -s "$f" "$tmp/j$n/$b" || { same="no ($b differs)"; break; }
done
[ "$(ls "$tmp/j1" | wc -l)" = "$(ls "$tmp/j$n" | wc -l)" ] || same="no (different files)"
echo "H = $H m: -j 1 $w1 s, -j $n $wn s, speedup $(echo "$w1 $wn" | awk '{printf "%.2f", $1 / $2}')x" \
    "(target >= 1.7x with 2 cores); outputs byte-identical: $same"
