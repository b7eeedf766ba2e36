#!/bin/bash
# Memory and time are bounded by the work asked: a size that calls for
# more triangles than --max-triangles (default 20 million) over a fault's
# fitted area refuses that fault, before any junction or mesh is made,
# with the estimate in the message, within a 1.5 GB address space (no
# allocation spike first); faults that fit but together exceed the limit
# refuse the run; a size larger than a fault is warned about.
# usage: remesh_bounds_test.sh FAULTMESH TMPDIR
set -u
exe=$1 tmp=$2
rm -rf "$tmp" && mkdir -p "$tmp"
. "$(dirname "$0")/cli_lib.sh"

expect_rc 0 "synth" "$exe" synth --spacing 2000 -o "$tmp/in"
# A sanitizer build reserves terabytes of address space for its shadow
# memory and cannot start under the limit: it runs without one.
limit=1500000
( ulimit -v $limit; exec "$exe" --version ) >/dev/null 2>&1 || { limit=unlimited; echo "(no address space limit: the build cannot start under one)"; }
for s in 1e-6 1e-4 1; do
    ( ulimit -v $limit; exec timeout 60 "$exe" remesh --quiet --size "$s" -o "$tmp/o$s" "$tmp/in" ) \
        >"$tmp/out" 2>"$tmp/err"
    rc=$?
    [ "$rc" = 1 ] && ok || bad "--size $s: exit $rc, expected 1 (every fault refused)"
    [ "$(grep -c 'call for about .* triangles, more than --max-triangles 20000000' "$tmp/err")" = 10 ] &&
        ok || bad "--size $s: $(head -c 400 "$tmp/err")"
    [ "$(json "$tmp/o$s/report.json" "sum(f['status'] == 'error' for f in r['faults'])")" = 10 ] &&
        ok || bad "--size $s: faults not reported as errors"
done
# each fault within the limit, all of them together over it
expect_rc 1 "the run over --max-triangles" "$exe" remesh --quiet --size 4000 --max-triangles 150 \
    -o "$tmp/run" "$tmp/in"
grep -q 'the faults call for about .* triangles, more than --max-triangles 150' "$tmp/err" && ok ||
    bad "run limit: $(cat "$tmp/err")"
[ ! -e "$tmp/run/report.json" ] && ok || bad "run limit: outputs written"
expect_rc 0 "--max-triangles 0 (no limit)" "$exe" remesh --quiet --size 4000 --max-triangles 0 \
    -o "$tmp/nolimit" "$tmp/in"
expect_rc 2 "--max-triangles -1" "$exe" remesh --quiet --max-triangles -1 -o "$tmp/bad" "$tmp/in"
# a size larger than the faults: meshed, and each warned about
expect_rc 0 "--size 1e9" "$exe" remesh --quiet --size 1e9 -o "$tmp/huge" "$tmp/in"
[ "$(json "$tmp/huge/report.json" "sum(any('larger than the fault' in w for w in f['warnings']) for f in r['faults'])")" = 10 ] &&
    ok || bad "--size 1e9: $(json "$tmp/huge/report.json" "[f['warnings'] for f in r['faults']]")"
echo "remesh bounds: $pass passed, $fail failed"
[ "$fail" = 0 ] && rm -rf "$tmp"
[ "$fail" = 0 ]
