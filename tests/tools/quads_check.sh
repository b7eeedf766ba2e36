#!/bin/bash
# Rectangular elements (--elements quad, issue 23) read back by
# check_quads.py the way OpenSHA's and Virtual Quake's EQSim readers and
# RSQSim's readFault read them.
#   demo:  the synthetic system, EQSim rectangular and (with EPSG:26711)
#          spherical; a slip rule's rake and rate reach every rectangle;
#          copies with a triangle record, a renumbered vertex, an RSQSim
#          line of 13 columns, and one rectangle moved through another
#          fault's must fail the check (it can fail); formats that hold
#          only triangles are a usage error.
#   cfm:   the whole CFM 500 m set at 2 km with the NSHM23 kinematics when
#          present; the issue's figures printed.
# usage: quads_check.sh FAULTMESH PYTHON TMPDIR demo
#        quads_check.sh FAULTMESH PYTHON TMPDIR cfm CFMDIR [KINEMATICSDIR]
# exit 77 when meshio or numpy, or the CFM, are missing.
set -u
exe=$1 py=$2 tmp=$3 what=$4
check=$(dirname "$0")/check_quads.py
rm -rf "$tmp" && mkdir -p "$tmp"
fail=0
run() { # description command...
    local what=$1; shift
    "$@"; local rc=$?
    [ "$rc" = 77 ] && { echo "skipped: $what"; exit 77; }
    [ "$rc" = 0 ] || { echo "FAIL: $what (exit $rc)"; fail=1; }
}
expect_fail() { # description pattern command...
    local what=$1 pattern=$2; shift 2
    "$@" >"$tmp/out.txt" 2>&1; local rc=$?
    [ "$rc" = 77 ] && { echo "skipped: $what"; exit 77; }
    if [ "$rc" = 0 ]; then echo "FAIL: $what passed"; fail=1;
    elif ! grep -q "$pattern" "$tmp/out.txt"; then
        echo "FAIL: $what failed without '$pattern'"; cat "$tmp/out.txt"; fail=1
    else echo "ok    $what fails (exit $rc)"; fi
}
if [ "$what" = demo ]; then
    printf 'fault,rake,slip rate (mm/yr)\nSYNT-MAIN-SS-Main_strike_slip_fault-SYN1,180,25\n*,,2\n' \
        >"$tmp/slip.csv"
    run "demo --elements quad (EQSim rectangular)" "$exe" demo --quiet --elements quad \
        --slip "$tmp/slip.csv" --eqsim-coords utm -o "$tmp/rect"
    run "check (rectangular)" "$py" "$check" "$tmp/rect" --limits
    run "demo --elements quad (EQSim spherical)" "$exe" demo --quiet --elements quad \
        --crs EPSG:26711 --eqsim-coords spherical -o "$tmp/sph"
    run "check (spherical)" "$py" "$check" "$tmp/sph" --no-crossing-check
    # the slip rule on every rectangle: the main fault's vertical elements
    # right-lateral at 25 mm/yr, every other at 2 mm/yr
    "$py" - "$tmp/rect" <<'PY' || fail=1
import sys
import numpy as np
r = np.loadtxt(sys.argv[1] + "/mesh.rsqsim")
mmyr = r[:, 8] * 1000 * 365.25 * 86400
main = r[:, 9] == 1
ok = np.allclose(mmyr[main], 25) and np.allclose(mmyr[~main], 2) and \
    np.all(np.abs(np.abs(r[main & (r[:, 6] > 89.9), 7]) - 180) < 1e-6)
print(("ok    " if ok else "FAIL  ") + "slip rule: 25 mm/yr right-lateral on the main fault, 2 elsewhere")
sys.exit(0 if ok else 1)
PY
    # The checker can fail.
    cp -r "$tmp/rect" "$tmp/bad1"
    awk '$1 == 204 && $2 == 7 { $1 = 203 } { print }' "$tmp/rect/mesh.eqsim" >"$tmp/bad1/mesh.eqsim"
    expect_fail "an EQSim file with a triangle record" "203" "$py" "$check" "$tmp/bad1" --no-crossing-check
    cp -r "$tmp/rect" "$tmp/bad2"
    awk '$1 == 202 && $2 == 9 { $2 = 10 } { print }' "$tmp/rect/mesh.eqsim" >"$tmp/bad2/mesh.eqsim"
    expect_fail "an EQSim file with a vertex renumbered" "vertex ids" "$py" "$check" "$tmp/bad2" --no-crossing-check
    cp -r "$tmp/rect" "$tmp/bad3"
    awk 'NR == 5 { $0 = $0 " 0 0 0" } { print }' "$tmp/rect/mesh.rsqsim" >"$tmp/bad3/mesh.rsqsim"
    expect_fail "an RSQSim line of 13 columns" "10 columns" "$py" "$check" "$tmp/bad3" --no-crossing-check
    cp -r "$tmp/rect" "$tmp/bad4"
    "$py" - "$tmp/rect" "$tmp/bad4" <<'PY'
import sys
import meshio
import numpy as np
m = meshio.read(sys.argv[1] + "/mesh.vtu")
q, fid = m.cells[0].data, m.cell_data["fault_id"][0] - 1
# the first rectangle of fault 1 made a copy of fault 0's first one turned
# a quarter about the vertical through its centre: through it
a, b = q[np.where(fid == 1)[0][0]], q[np.where(fid == 0)[0][0]]
c = m.points[b].mean(axis=0)
p = (m.points[b] - c) @ np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1]])
m.points[a] = p + c
meshio.write(sys.argv[2] + "/mesh.vtu", m)
PY
    expect_fail "a rectangle moved through another fault's" "meet" "$py" "$check" "$tmp/bad4"
    # formats that hold only triangles
    "$exe" demo --quiet --elements quad --formats vtu,stl -o "$tmp/x" 2>"$tmp/err.txt"; rc=$?
    if [ "$rc" = 2 ] && grep -q "triangles only" "$tmp/err.txt"; then
        echo "ok    --elements quad with stl is a usage error"
    else echo "FAIL: --elements quad --formats vtu,stl: exit $rc, $(cat "$tmp/err.txt")"; fail=1; fi
    "$exe" demo --quiet --elements hex -o "$tmp/x" 2>"$tmp/err.txt"; rc=$?
    if [ "$rc" = 2 ] && grep -q "tri or quad" "$tmp/err.txt"; then
        echo "ok    --elements hex is a usage error"
    else echo "FAIL: --elements hex: exit $rc, $(cat "$tmp/err.txt")"; fail=1; fi
else
    cfm=$5 kin=${6:-}
    [ -d "$cfm/CFM5.3/500m" ] || { echo "skipped: no CFM at $cfm"; exit 77; }
    opts=()
    fsd=$kin/nshm23/NSHM23_FSD_v3.geojson dm=$kin/nshm23/NSHM23_GeologicDeformationModel.geojson
    [ -n "$kin" ] && [ -f "$fsd" ] && [ -f "$dm" ] && opts=(--kinematics "$fsd" --kinematics "$dm")
    run "remesh --elements quad, whole CFM at 2 km" "$exe" remesh --quiet --size 2000 \
        --elements quad --eqsim-coords utm "${opts[@]}" -o "$tmp/out" "$cfm/CFM5.3/500m"
    run "check" "$py" "$check" "$tmp/out" --limits
fi
exit $fail
