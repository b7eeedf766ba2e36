#!/bin/bash
# What `faultmesh remesh` tells while it runs: log lines on stderr and the
# summary table on stdout by default; a progress bar with counts and ETA
# on a terminal (run under script(1) for a pseudo-terminal); a line per
# fault with --verbose; nothing but errors with --quiet.
# usage: remesh_progress_check.sh FAULTMESH TMPDIR
set -u
exe=$1 tmp=$2
rm -rf "$tmp" && mkdir -p "$tmp"
. "$(dirname "$0")/cli_lib.sh"

expect_rc 0 "synth" "$exe" synth -o "$tmp/s"
nin=$(ls "$tmp/s"/*.ts | wc -l)

expect_rc 0 "remesh, not on a terminal" "$exe" remesh --size 2000 -o "$tmp/a" "$tmp/s"
grep -q "^faultmesh: read and fit: $nin files$" "$tmp/err" && ok || bad "no fit log line: $(cat "$tmp/err")"
for stage in "read and fit" connect mesh "merge and check" write; do
    grep -q "^faultmesh: $stage: done in [0-9.]* s" "$tmp/err" && ok || bad "no end line for $stage"
done
grep -q $'\r' "$tmp/err" && bad "carriage returns in a log file" || ok
for row in "summary (" "  faults  *$nin read, $nin meshed" "  sheets " "  junctions  *[0-9]* crossing, [0-9]* T, [0-9]* corner, [0-9]* unjoined" \
    "  triangles  *[0-9]*, " "  worst quality  *smallest angle" "  worst fidelity" "  time  *read and fit"; do
    grep -q "^$row" "$tmp/out" && ok || bad "summary lacks '$row': $(cat "$tmp/out")"
done
# the summary's figures are report.json's
tri=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['summary']['triangles'])" "$tmp/a/report.json")
grep -q "^  triangles  *$tri, " "$tmp/out" && ok || bad "summary triangles differ from report.json ($tri)"

expect_rc 0 "remesh --quiet" "$exe" remesh --quiet --size 2000 -o "$tmp/q" "$tmp/s"
[ ! -s "$tmp/out" ] && [ ! -s "$tmp/err" ] && ok || bad "--quiet printed: $(cat "$tmp/out" "$tmp/err")"

expect_rc 0 "remesh --verbose" "$exe" remesh --verbose --size 2000 -o "$tmp/v" "$tmp/s"
n=$(grep -c " tri  min " "$tmp/out")
[ "$n" = "$nin" ] && ok || bad "--verbose: $n fault lines, expected $nin"

# A terminal: the bar is redrawn in place, with counts, share and ETA.
if command -v script >/dev/null 2>&1; then
    script -qec "$exe remesh --size 2000 -o $tmp/t $tmp/s" "$tmp/tty.log" >/dev/null 2>&1
    rc=$?
    [ "$rc" = 0 ] && ok || bad "remesh on a terminal: exit $rc"
    tr '\r' '\n' <"$tmp/tty.log" >"$tmp/tty.txt"
    grep -aq "^mesh  *\[#*\.*\] [0-9]*/$nin files  *[0-9]*%  .*ETA" "$tmp/tty.txt" && ok ||
        bad "no progress bar: $(head -c 600 "$tmp/tty.txt")"
    grep -aq "^mesh  *done in [0-9.]* s ($nin files)" "$tmp/tty.txt" && ok || bad "bar not closed"
    cmp -s "$tmp/t/mesh.vtu" "$tmp/a/mesh.vtu" && ok || bad "output differs on a terminal"
else
    echo "script(1) absent: terminal part skipped"
fi

echo "remesh progress: $pass passed, $fail failed"
[ "$fail" = 0 ] && rm -rf "$tmp"
[ "$fail" = 0 ]
