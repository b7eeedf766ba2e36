#!/bin/bash
# `faultmesh remesh` and `faultmesh demo` as users meet them: exit codes
# (2 bad usage, 1 some inputs failed, 0 all processed), a bad file among
# good ones (named with FILE:LINE on stderr and in report.json, the good
# ones meshed and written), a fault wholly above sea level, a blocked
# output name, no temporary files left, identical outputs for identical
# runs.
# usage: remesh_cli_test.sh FAULTMESH DATA TMPDIR
set -u
exe=$1 data=$2/cli tmp=$3
rm -rf "$tmp" && mkdir -p "$tmp"
. "$(dirname "$0")/cli_lib.sh"

# Two small real faults from the synthetic system, and the bad file.
expect_rc 0 "synth" "$exe" synth -o "$tmp/s"
g1=$(ls "$tmp/s"/*Main_strike_slip*.ts) g2=$(ls "$tmp/s"/*Blind*.ts)
[ -f "$g1" ] && [ -f "$g2" ] && ok || bad "synthetic inputs missing"

# Bad usage: exit 2, nothing written.
expect_rc 0 "remesh --help" "$exe" remesh --help
grep -q -- "--top cut|keep" "$tmp/out" && ok || bad "remesh --help text"
expect_rc 2 "remesh without arguments" "$exe" remesh
expect_rc 2 "remesh without -o" "$exe" remesh "$g1"
expect_rc 2 "remesh without inputs" "$exe" remesh -o "$tmp/u1"
expect_rc 2 "remesh unknown option" "$exe" remesh --bogus -o "$tmp/u1" "$g1"
grep -q "unknown option '--bogus'" "$tmp/err" && ok || bad "unknown option message: $(cat "$tmp/err")"
expect_rc 2 "remesh --size abc" "$exe" remesh --size abc -o "$tmp/u1" "$g1"
expect_rc 2 "remesh --size 0" "$exe" remesh --size 0 -o "$tmp/u1" "$g1"
expect_rc 2 "remesh --size -5" "$exe" remesh --size -5 -o "$tmp/u1" "$g1"
expect_rc 2 "remesh --size without value" "$exe" remesh -o "$tmp/u1" "$g1" --size
expect_rc 2 "remesh --top bogus" "$exe" remesh --top bogus -o "$tmp/u1" "$g1"
expect_rc 2 "remesh --top extend without D" "$exe" remesh -o "$tmp/u1" "$g1" --top extend
expect_rc 2 "remesh --top extend abc" "$exe" remesh --top extend abc -o "$tmp/u1" "$g1"
expect_rc 2 "remesh --msh-version 3" "$exe" remesh --msh-version 3 -o "$tmp/u1" "$g1"
expect_rc 2 "remesh --keep-duplicate biggest" "$exe" remesh --keep-duplicate biggest -o "$tmp/u1" "$g1"
expect_rc 2 "remesh --keep-duplicate without value" "$exe" remesh -o "$tmp/u1" "$g1" --keep-duplicate
expect_rc 2 "remesh missing input" "$exe" remesh -o "$tmp/u1" "$tmp/does-not-exist.ts"
expect_rc 2 "remesh bad repair option" "$exe" remesh --weld-tol abc -o "$tmp/u1" "$g1"
[ ! -e "$tmp/u1/report.json" ] && ok || bad "bad usage wrote a report"
expect_rc 0 "demo --help" "$exe" demo --help
expect_rc 2 "demo without -o" "$exe" demo
expect_rc 2 "demo with an input" "$exe" demo -o "$tmp/u2" "$g1"
expect_rc 2 "demo unknown option" "$exe" demo --bogus -o "$tmp/u2"

# A bad file among good ones: exit 1, the bad one named with its line on
# stderr and in report.json, the good ones meshed and written.
expect_rc 1 "remesh good + bad + good" "$exe" remesh --size 2000 -o "$tmp/m" "$g1" "$data/bad.ts" "$g2"
grep -q "bad.ts:9: " "$tmp/err" && ok || bad "stderr lacks bad.ts:9: $(cat "$tmp/err")"
r=$tmp/m/report.json
if [ -f "$r" ]; then
    ok
    [ "$(json "$r" "r['summary']['faults'], r['summary']['meshed'], r['summary']['failed']")" = "3 2 1" ] &&
        ok || bad "summary: $(json "$r" "r['summary']")"
    [ "$(json "$r" "[f['status'] for f in r['faults']]")" = "['ok', 'error', 'ok']" ] && ok ||
        bad "statuses: $(json "$r" "[f['status'] for f in r['faults']]")"
    json "$r" "r['faults'][1]['error']" | grep -q "bad.ts:9: " && ok ||
        bad "report error: $(json "$r" "r['faults'][1].get('error')")"
    [ "$(json "$r" "r['faults'][1]['file'].endswith('bad.ts')")" = True ] && ok || bad "report file of the bad one"
else
    bad "no report.json"
fi
for f in mesh.vtu mesh.msh mesh.stl mesh.obj model.igs SYNT-MAIN-SS-Main_strike_slip_fault-SYN1.ts \
         SYNT-SWFB-BLND-Blind_fault-SYN1.ts; do
    [ -s "$tmp/m/$f" ] && ok || bad "$f not written"
done
n=$(ls "$tmp/m"/*.ts 2>/dev/null | wc -l)
[ "$n" = 2 ] && ok || bad "$n .ts files written, expected 2"
grep -q '"SYNT-MAIN-SS-Main_strike_slip_fault-SYN1"' "$tmp/m/mesh.msh" &&
    grep -q '"SYNT-SWFB-BLND-Blind_fault-SYN1"' "$tmp/m/mesh.msh" && ok || bad "MSH physical names"

# Same inputs, same outputs (report.json holds times).
expect_rc 1 "remesh again" "$exe" remesh --size 2000 --quiet -o "$tmp/m2" "$g1" "$data/bad.ts" "$g2"
diff -r -x report.json "$tmp/m" "$tmp/m2" >/dev/null && ok || bad "outputs differ between runs"
[ ! -s "$tmp/out" ] && ok || bad "--quiet printed: $(head -3 "$tmp/out")"

# A fault wholly above sea level: nothing to mesh with the top cut, which
# is not a failure; with --top keep it is meshed.
# (a vertical 10 x 2.5 km rectangle from z = 3000 down to 500 m, 500 m
# triangles; a coarser one, 4 triangles, trims badly: see the report)
python3 - "$tmp/above.ts" <<'PY'
import sys
n, m, lines, k = 20, 5, ["GOCAD TSurf 1", "HEADER {", "name:above_sea_level", "}", "TFACE"], 0
for j in range(m + 1):
    for i in range(n + 1):
        k += 1
        lines.append("VRTX %d %d 3750000 %d" % (k, 400000 + 500 * i, 3000 - 500 * j))
for j in range(m):
    for i in range(n):
        a = j * (n + 1) + i + 1
        lines += ["TRGL %d %d %d" % (a, a + 1, a + n + 1), "TRGL %d %d %d" % (a + 1, a + n + 2, a + n + 1)]
open(sys.argv[1], "w").write("\n".join(lines + ["END", ""]))
PY
expect_rc 0 "remesh a fault above sea level" "$exe" remesh -o "$tmp/a" "$tmp/above.ts" "$g2"
[ "$(json "$tmp/a/report.json" "[f['status'] for f in r['faults']]")" = "['empty', 'ok']" ] && ok ||
    bad "above sea level: $(json "$tmp/a/report.json" "[(f['status'], f.get('error')) for f in r['faults']]")"
n=$(ls "$tmp/a"/*.ts 2>/dev/null | wc -l)
[ "$n" = 1 ] && ok || bad "above sea level: $n .ts files, expected 1"
expect_rc 0 "remesh a fault above sea level, --top keep" "$exe" remesh --top keep --size 2000 -o "$tmp/k" "$tmp/above.ts"
[ "$(json "$tmp/k/report.json" "r['faults'][0]['status']")" = ok ] && ok || bad "--top keep did not mesh it"

# A size near the faults' own extents: each is a triangle or two, and the
# last guard would have emptied one where two still cross; it keeps both
# instead, and every file is written.
expect_rc 0 "remesh at 10,000 km" "$exe" remesh --size 1e7 --quiet -o "$tmp/huge" "$tmp/s"
[ -s "$tmp/huge/mesh.vtu" ] && [ "$(ls "$tmp/huge"/*.ts | wc -l)" = 10 ] && ok ||
    bad "at 10,000 km: $(ls "$tmp/huge")"
[ "$(json "$tmp/huge/report.json" "all(f['triangles'] > 0 for f in r['faults']) and any(c['removed_from'] is None and c['triangles_removed'] == 0 for c in r['connect']['carved'])")" = True ] && ok ||
    bad "at 10,000 km: $(json "$tmp/huge/report.json" "r['connect'].get('carved')")"

# A blocked output name: exit 1, no temporary left, no partial file.
mkdir -p "$tmp/b/mesh.vtu"
expect_rc 1 "remesh onto a blocked name" "$exe" remesh --size 2000 -o "$tmp/b" "$g1"
grep -q "mesh.vtu" "$tmp/err" && ok || bad "blocked name not named: $(cat "$tmp/err")"

[ -z "$(find "$tmp" -name '*.tmp.*')" ] && ok || bad "temporary files left: $(find "$tmp" -name '*.tmp.*')"

echo "remesh cli: $pass passed, $fail failed"
[ "$fail" = 0 ] && rm -rf "$tmp"
[ "$fail" = 0 ]
