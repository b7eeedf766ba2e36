#!/bin/bash
# The simulator outputs (mesh.rsqsim, mesh.eqsim, the VTU's strike, dip,
# rake and slip_rate, report.json's attributes) read back by check_sim.py,
# which is written from the formats' documentation.
#   demo:  the synthetic system with a --slip CSV, EQSim rectangular (its
#          default: no real CRS) and, with --crs EPSG:26711, spherical; a
#          copy with one RSQSim corner moved and one with an EQSim latitude
#          moved by 1e-5 degrees must fail the check (it can fail); bad
#          --slip files and values are usage errors naming file:line.
#   cfm:   the whole CFM 500 m set at 1 km, connected, the metadata found
#          beside the input folder, spherical.
# usage: sim_check.sh FAULTMESH PYTHON TMPDIR demo
#        sim_check.sh FAULTMESH PYTHON TMPDIR cfm CFMDIR
# exit 77 when the readers (meshio, numpy, pyproj) or the CFM are missing.
set -u
exe=$1 py=$2 tmp=$3 what=$4
check=$(dirname "$0")/check_sim.py
rm -rf "$tmp" && mkdir -p "$tmp"
fail=0
run() { # description command...
    local what=$1; shift
    "$@"; local rc=$?
    [ "$rc" = 77 ] && { echo "skipped: $what"; exit 77; }
    [ "$rc" = 0 ] || { echo "FAIL: $what (exit $rc)"; fail=1; }
}
expect_fail() { # description command...
    local what=$1; shift
    "$@" >"$tmp/out.txt" 2>&1; local rc=$?
    [ "$rc" = 77 ] && { echo "skipped: $what"; exit 77; }
    if [ "$rc" = 0 ]; then echo "FAIL: $what passed"; fail=1; else echo "ok    $what fails (exit $rc)"; fi
}
cat >"$tmp/slip.csv" <<'CSV'
fault,rake,slip rate (mm/yr)
# the main fault: right-lateral, 25 mm/yr
SYNT-MAIN-SS-Main_strike_slip_fault-SYN1,180,25
SAFS-SAFZ-*,,20
"WTRA-ORFZ-SFNV-Northridge_Frew_fault-CFM2",95,1.5
*THRUST*,90,
*,,2
CSV
if [ "$what" = demo ]; then
    run "demo (EQSim rectangular)" "$exe" demo --quiet --slip "$tmp/slip.csv" -o "$tmp/rect"
    run "check demo (rectangular)" "$py" "$check" "$tmp/rect" --slip "$tmp/slip.csv" --expect-coords rectangular
    run "demo (EPSG:26711, EQSim spherical)" "$exe" demo --quiet --slip "$tmp/slip.csv" \
        --crs EPSG:26711 --eqsim-coords spherical -o "$tmp/sph"
    run "check demo (spherical)" "$py" "$check" "$tmp/sph" --slip "$tmp/slip.csv" --expect-coords spherical
    # The checker can fail: one RSQSim corner 1 mm off, one latitude 1e-5 degrees off.
    cp -r "$tmp/sph" "$tmp/bad1"
    awk 'NR == 100 { $1 = $1 + 0.001 } { print }' "$tmp/sph/mesh.rsqsim" >"$tmp/bad1/mesh.rsqsim"
    expect_fail "check of an RSQSim file with a corner moved" "$py" "$check" "$tmp/bad1" --slip "$tmp/slip.csv"
    cp -r "$tmp/sph" "$tmp/bad2"
    awk '$1 == 202 && $2 == 50 { $3 = $3 + 1e-5 } { print }' "$tmp/sph/mesh.eqsim" >"$tmp/bad2/mesh.eqsim"
    expect_fail "check of an EQSim file with a latitude moved" "$py" "$check" "$tmp/bad2" --slip "$tmp/slip.csv"
    expect_fail "check with other slip rules" "$py" "$check" "$tmp/sph"
    # Usage errors.
    printf 'fault,rake,rate\nA,90,1\nB,ninety,1\n' >"$tmp/bad.csv"
    "$exe" demo --quiet --slip "$tmp/bad.csv" -o "$tmp/x" 2>"$tmp/err.txt"; rc=$?
    if [ "$rc" = 2 ] && grep -q "bad.csv:3: rake 'ninety'" "$tmp/err.txt"; then
        echo "ok    a bad --slip file is a usage error naming file:line"
    else echo "FAIL: bad --slip file: exit $rc, $(cat "$tmp/err.txt")"; fail=1; fi
    "$exe" demo --quiet --eqsim-coords polar -o "$tmp/x" 2>/dev/null; rc=$?
    [ "$rc" = 2 ] && echo "ok    --eqsim-coords polar is a usage error" || { echo "FAIL: --eqsim-coords polar: exit $rc"; fail=1; }
    "$exe" demo --quiet --metadata "$tmp/none.csv" -o "$tmp/x" 2>"$tmp/err.txt"; rc=$?
    [ "$rc" = 2 ] && grep -q "none.csv" "$tmp/err.txt" && echo "ok    a missing --metadata file is a usage error" \
        || { echo "FAIL: missing --metadata: exit $rc"; fail=1; }
    # No silent placeholders: without --slip every element is at rate 0 and
    # every rake defaulted, and stderr says so, with how many and why; with
    # rules for every fault, nothing is said.
    "$exe" demo --size 4000 -o "$tmp/plain" >/dev/null 2>"$tmp/err.txt"
    n=$("$py" -c "import json; print(json.load(open('$tmp/plain/report.json'))['summary']['triangles'])")
    if grep -q "no CFM5.3_Metadata.csv beside the inputs" "$tmp/err.txt" &&
       grep -q "warning: mesh.rsqsim, mesh.eqsim: $n of $n elements (10 of 10 faults) have slip rate 0" "$tmp/err.txt" &&
       grep -q "warning: mesh.rsqsim, mesh.eqsim: $n elements (10 faults) have the default rake 180: no CFM metadata CSV" "$tmp/err.txt"; then
        echo "ok    rate 0 and defaulted rakes are said on stderr, with counts and why"
    else echo "FAIL: placeholders not said: $(cat "$tmp/err.txt")"; fail=1; fi
    printf 'fault,rake,slip rate\n*,90,1\n' >"$tmp/all.csv"
    "$exe" demo --size 4000 --slip "$tmp/all.csv" -o "$tmp/ruled" >/dev/null 2>"$tmp/err.txt"
    ! grep -q "warning: mesh.rsqsim" "$tmp/err.txt" && echo "ok    every fault ruled: no placeholder warning" \
        || { echo "FAIL: warned with every fault ruled: $(cat "$tmp/err.txt")"; fail=1; }
    # Spherical without a real CRS is a usage error, before any meshing.
    "$exe" demo --quiet --eqsim-coords spherical -o "$tmp/nocrs" 2>"$tmp/err.txt"; rc=$?
    if [ "$rc" = 2 ] && [ ! -e "$tmp/nocrs/mesh.vtu" ] && grep -q "PROJ cannot convert" "$tmp/err.txt"; then
        echo "ok    spherical EQSim without a known CRS: a usage error, nothing meshed"
    else echo "FAIL: spherical without a CRS: exit $rc"; fail=1; fi
else
    cfm=$5
    [ -d "$cfm/CFM5.3/500m" ] || { echo "skipped: no CFM at $cfm"; exit 77; }
    "$py" -c "import meshio, numpy, pyproj" 2>/dev/null || { echo "skipped: meshio, numpy or pyproj missing"; exit 77; }
    start=$(date +%s)
    run "remesh CFM 500m at 1 km" "$exe" remesh --quiet --size 1000 --slip "$tmp/slip.csv" \
        -o "$tmp/out" "$cfm/CFM5.3/500m"
    echo "remesh with simulator outputs: $(( $(date +%s) - start )) s"
    ls -l "$tmp/out"/mesh.* | awk '{ print $5, $9 }'
    run "check CFM (spherical)" "$py" "$check" "$tmp/out" --slip "$tmp/slip.csv" \
        --metadata "$cfm/CFM5.3/CFM5.3_Metadata.csv" --expect-coords spherical
    grep -q '"metadata": ".*CFM5.3_Metadata.csv"' "$tmp/out/report.json" \
        && echo "ok    the metadata beside the input folder was found" \
        || { echo "FAIL: metadata not found beside the input"; fail=1; }
fi
[ -z "$(find "$tmp" -name '*.tmp.*')" ] || { echo "FAIL: temporary files left"; fail=1; }
[ "$fail" = 0 ] && rm -rf "$tmp"
echo "sim $what: $([ "$fail" = 0 ] && echo passed || echo FAILED)"
exit $fail
