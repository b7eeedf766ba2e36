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
# The log agrees with the summary: each stage's "done in" is the summary's
# time for it (mesh with its rounds of meshing again), and a share is the
# share of the count done, not of bytes.
python3 - "$tmp/err" "$tmp/out" <<'PY' && ok || bad "log and summary disagree"
import re, sys
log, out = open(sys.argv[1]).read(), open(sys.argv[2]).read()
done = {}
for stage, s in re.findall(r"^faultmesh: ([a-z ]+): done in ([0-9.]+) s", log, re.M):
    done[stage] = done.get(stage, 0) + float(s)
done["mesh"] = done.get("mesh", 0) + done.pop("mesh again", 0)
m = re.search(r"read and fit ([0-9.]+) s, connect ([0-9.]+) s, mesh ([0-9.]+) s.*merge and check "
              r"([0-9.]+) s, write ([0-9.]+) s", out)
summary = dict(zip(("read and fit", "connect", "mesh", "merge and check", "write"),
                   map(float, m.groups())))
rounds = len(re.findall(r"^faultmesh: mesh again: done", log, re.M))
bad = [(k, done.get(k), v) for k, v in summary.items()
       if done.get(k) is None or abs(done[k] - v) > 0.051 * (2 + rounds)]
for d, n, pct in re.findall(r": (\d+)/(\d+) [a-z ]+, (\d+)%", log):
    if abs(100 * int(d) / int(n) - int(pct)) > 1:
        bad.append(("share", d + "/" + n, pct))
print("log %s, summary %s" % (done, summary))
sys.exit(1 if bad else 0)
PY
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
