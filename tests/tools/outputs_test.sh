#!/bin/bash
# Every output accounted for (issue 18, item 4): a file that cannot be
# written does not stop the others; the run exits 1; stderr and
# report.json name each file not written with the system's reason; a fault
# with a file missing is not "ok". A 1 mm fault among the others leaves
# only its own face out of model.igs. On a full disk (a small tmpfs, when
# this user may mount one) nothing partial or temporary is left.
# usage: outputs_test.sh FAULTMESH TMPDIR
set -u
exe=$1 tmp=$2
rm -rf "$tmp" && mkdir -p "$tmp"
. "$(dirname "$0")/cli_lib.sh"

expect_rc 0 "synth" "$exe" synth --spacing 2000 -o "$tmp/in"
n=$(ls "$tmp/in"/*.ts | wc -l)
first=$(ls "$tmp/in"/*.ts | head -1)
blocked=$(basename "$first")

# mesh.vtu and one fault's NAME.ts are folders: both fail, all else is written
mkdir -p "$tmp/o/mesh.vtu" "$tmp/o/$blocked"
expect_rc 1 "two outputs blocked" "$exe" remesh --size 4000 -o "$tmp/o" "$tmp/in"
for f in mesh.msh mesh.stl mesh.obj mesh.exo model.igs mesh.rsqsim mesh.eqsim names.csv report.html \
         report.json; do
    [ -f "$tmp/o/$f" ] && ok || bad "$f not written after mesh.vtu failed"
done
[ "$(ls -d "$tmp/o"/*.ts | wc -l)" = "$n" ] && ok || bad "TSurf files missing"
grep -q "not written: $tmp/o/mesh.vtu: .*Is a directory" "$tmp/err" && ok ||
    bad "stderr does not name mesh.vtu with its reason: $(cat "$tmp/err")"
grep -q "not written: $tmp/o/$blocked: .*Is a directory" "$tmp/err" && ok ||
    bad "stderr does not name $blocked"
grep -q "not written *$tmp/o/mesh.vtu" "$tmp/out" && ok || bad "summary does not list mesh.vtu"
r="$tmp/o/report.json"
[ "$(json "$r" "sorted(f['file'] for f in r['outputs']['files'] if not f['written'])")" = \
  "['$blocked', 'mesh.vtu']" ] && ok || bad "report.json outputs: $(json "$r" "r['outputs']")"
[ "$(json "$r" "all('Is a directory' in f['error'] for f in r['outputs']['files'] if not f['written'])")" = True ] &&
    ok || bad "report.json: a reason missing"
[ "$(json "$r" "r['outputs']['not_written']")" = 2 ] && ok || bad "not_written count"
# every meshed fault is in mesh.vtu: none is ok; the blocked one lacks its TSurf too
[ "$(json "$r" "sum(f['status'] == 'ok' for f in r['faults'])")" = 0 ] && ok ||
    bad "a fault missing from mesh.vtu reported ok"
[ "$(json "$r" "sum(f['status'] == 'incomplete' and f['outputs_missing'] == ['mesh.vtu'] for f in r['faults'])")" = $((n - 1)) ] &&
    ok || bad "faults not incomplete with mesh.vtu missing"
[ "$(json "$r" "[f['outputs_missing'] for f in r['faults'] if f['file'].endswith('$blocked')]")" = \
  "[['mesh.vtu', '$blocked']]" ] && ok || bad "$blocked: its own TSurf not listed as missing"
[ "$(json "$r" "r['summary']['incomplete']")" = "$n" ] && ok || bad "summary incomplete count"

# nothing blocked: every file listed as written, every fault ok
expect_rc 0 "all written" "$exe" remesh --quiet --size 4000 -o "$tmp/all" "$tmp/in"
[ "$(json "$tmp/all/report.json" "(r['outputs']['written'], r['outputs']['not_written'])")" = \
  "($((n + 10)), 0)" ] && ok || bad "outputs: $(json "$tmp/all/report.json" "r['outputs']")"

# report.html names files, never the input's absolute path, also in the
# reason a fault failed (the input here is given as an absolute path)
mkdir -p "$tmp/withbad" && cp "$tmp/in"/*.ts "$(dirname "$0")/../data/bad/trgl_four_ids.ts" "$tmp/withbad/"
expect_rc 1 "a bad fault among good ones" "$exe" remesh --quiet --size 4000 -o "$tmp/html" "$tmp/withbad"
grep -q "trgl_four_ids.ts:10" "$tmp/html/report.html" && ok || bad "report.html lacks the failure"
! grep -q "$tmp" "$tmp/html/report.html" && ok || bad "report.html holds an absolute path"

# --formats: only the files asked for (and report.json), each accounted
# for, every fault ok; the settings file's formats list the same
expect_rc 0 "--formats rsqsim,names" "$exe" remesh --quiet --size 4000 --formats rsqsim,names \
    -o "$tmp/some" "$tmp/in"
[ "$(ls "$tmp/some" | tr '\n' ' ')" = "mesh.rsqsim names.csv report.json " ] && ok ||
    bad "--formats rsqsim,names wrote: $(ls "$tmp/some" | tr '\n' ' ')"
[ "$(json "$tmp/some/report.json" "(r['outputs']['written'], sum(f['status'] == 'ok' for f in r['faults']))")" = "(2, $n)" ] &&
    ok || bad "--formats: report.json $(json "$tmp/some/report.json" "r['outputs']")"
printf 'formats = ["vtu", "eqsim"]\nsize = 4000\n' >"$tmp/formats.toml"
expect_rc 0 "formats in the settings file" "$exe" remesh --quiet --config "$tmp/formats.toml" \
    -o "$tmp/some2" "$tmp/in"
[ "$(ls "$tmp/some2" | tr '\n' ' ')" = "mesh.eqsim mesh.vtu report.json " ] && ok ||
    bad "settings formats wrote: $(ls "$tmp/some2" | tr '\n' ' ')"
expect_rc 2 "--formats rsq" "$exe" remesh --quiet --formats rsq -o "$tmp/x" "$tmp/in"
grep -q "'rsq' is not one of" "$tmp/err" && ok || bad "--formats rsq: $(cat "$tmp/err")"

# a 1 mm fault far from the others: its face alone is left out of model.igs
python3 - "$first" "$tmp/tiny.ts" <<'EOF'
import sys
out, x0 = [], None
for l in open(sys.argv[1]).read().splitlines():
    if l.startswith(('VRTX', 'PVRTX')):
        p = l.split()
        x, y, z = map(float, p[2:5])
        if x0 is None:
            x0, y0, z0 = x, y, z
        s = 1e-3 / 30000  # a 30 km fault to 1 mm
        p[2:5] = [repr(x0 + 200000 + (x - x0) * s), repr(y0 + (y - y0) * s),
                  repr(-5000 + (z - z0) * s)]
        l = ' '.join(p)
    if l.startswith('name:'):
        l = 'name:tiny_fault'
    out.append(l)
open(sys.argv[2], 'w').write('\n'.join(out) + '\n')
EOF
mkdir -p "$tmp/in_tiny" && cp "$tmp/in"/*.ts "$tmp/tiny.ts" "$tmp/in_tiny/"
"$exe" remesh --quiet --size 4000 -o "$tmp/tiny" "$tmp/in_tiny" >"$tmp/out" 2>"$tmp/err"
for f in model.igs mesh.rsqsim mesh.eqsim tiny_fault.ts; do
    [ -f "$tmp/tiny/$f" ] && ok || bad "1 mm fault: $f not written ($(cat "$tmp/err"))"
done
grep -q "tiny_fault: .*left out of model.igs" "$tmp/err" && ok ||
    bad "1 mm fault: its face not said to be left out"
[ "$(json "$tmp/tiny/report.json" "r['outputs']['not_written']")" = 0 ] && ok ||
    bad "1 mm fault: outputs not written"

# fit: the three files of a fault each tried
mkdir -p "$tmp/fit/${blocked%.ts}.igs"
expect_rc 1 "fit with NAME.igs blocked" "$exe" fit -o "$tmp/fit" "$first"
for e in model.json vtu; do
    [ -f "$tmp/fit/${blocked%.ts}.$e" ] && ok || bad "fit: .$e not written after .igs failed"
done
grep -q "not written: .*\.igs: .*Is a directory" "$tmp/err" && ok || bad "fit: stderr $(cat "$tmp/err")"
[ "$(json "$tmp/fit/fit_report.json" "r['faults'][0]['outputs_missing']")" = "['${blocked%.ts}.igs']" ] &&
    ok || bad "fit_report.json: outputs_missing"

# a full disk: a tmpfs smaller than the outputs, where this user may mount
# one (root, or a user namespace)
disk="$tmp/disk"
mkdir -p "$disk"
if mount -t tmpfs -o size=200k tmpfs "$disk" 2>/dev/null; then
    "$exe" remesh --quiet --size 4000 -o "$disk/o" "$tmp/in" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    [ "$rc" = 1 ] && ok || bad "full disk: exit $rc"
    grep -q "No space left on device" "$tmp/err" && ok || bad "full disk: no reason given"
    ! grep -Eq "write failed$|\(error -?[0-9]+\)$|cannot write$" "$tmp/err" && ok ||
        bad "full disk: a failure without its reason: $(cat "$tmp/err")"
    [ -z "$(ls -A "$disk/o" | grep '\.tmp\.')" ] && ok || bad "full disk: temporaries left"
    # each file said not written is absent; the others are there
    for f in $(sed -n "s|^faultmesh: not written: $disk/o/\([^:]*\):.*|\1|p" "$tmp/err"); do
        [ ! -e "$disk/o/$f" ] && ok || bad "full disk: $f said not written but present"
    done
    written=$(ls "$disk/o" | wc -l)
    said=$(grep -c "^faultmesh: not written: " "$tmp/err")
    [ $((written + said)) = $((n + 11)) ] && ok ||
        bad "full disk: $written present + $said not written != $((n + 11)) files"
    umount "$disk"
else
    echo "(full disk not tried: no tmpfs may be mounted here)"
fi

echo "outputs_test: $pass passed, $fail failed"
[ "$fail" = 0 ]
