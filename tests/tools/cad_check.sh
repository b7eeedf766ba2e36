#!/bin/bash
# model.igs, the CAD model `faultmesh remesh` writes, checked by
# check_cad.py against the mesh it came with (Gmsh reads the IGES, meshio
# the MSH).
#  demo: `faultmesh demo` (top cut), its faces also meshed by Gmsh; then
#        the check must fail on a mismatched pair (the model.igs of
#        `demo --top keep`, whose faces run above sea level, with the cut
#        mesh), so that it can fail.
#  cfm:  the whole CFM set INPUTDIR at 1 km, connected, with
#        --keep-crossings: the model is the trimmed surfaces as meshed, and
#        the notches the last guard cuts into a mesh where two faults still
#        ran through each other are not in it (the output, some hundreds of
#        MB, is removed when the check passes).
# usage: cad_check.sh FAULTMESH PYTHON TMPDIR demo
#        cad_check.sh FAULTMESH PYTHON TMPDIR cfm INPUTDIR
# exit 77 when Gmsh, meshio or scipy (or the CFM) is missing.
set -u
exe=$1 py=$2 tmp=$3 mode=$4
check=$(dirname "$0")/check_cad.py
"$py" -c "import gmsh, meshio, numpy, scipy" 2>/dev/null ||
    { echo "skipped: gmsh / meshio / numpy / scipy missing"; exit 77; }
rm -rf "$tmp" && mkdir -p "$tmp"
if [ "$mode" = cfm ]; then
    in=$5
    [ -d "$in" ] || { echo "skipped: $in does not exist"; exit 77; }
    start=$(date +%s)
    "$exe" remesh --quiet --keep-crossings --size 1000 -o "$tmp/out" "$in"
    rc=$?
    echo "faultmesh remesh: exit $rc in $(( $(date +%s) - start )) s"
    if [ "$rc" != 0 ] && [ "$rc" != 1 ]; then echo "FAIL: faultmesh remesh exit $rc"; exit 1; fi
    "$py" "$check" "$tmp/out" --size 1000
    rc=$?
    [ "$rc" = 0 ] && rm -rf "$tmp"
    exit $rc
fi
fail=0
"$exe" demo --quiet -o "$tmp/cut" || { echo "FAIL: demo"; exit 1; }
"$py" "$check" "$tmp/cut" --size 1000 --gmsh-mesh --surface-p95 0.1 --surface-max 0.15
rc=$?
[ "$rc" = 77 ] && exit 77
[ "$rc" = 0 ] || fail=1
"$exe" demo --quiet --top keep -o "$tmp/keep" || { echo "FAIL: demo --top keep"; exit 1; }
mkdir -p "$tmp/mixed"
cp "$tmp/cut/mesh.msh" "$tmp/keep/model.igs" "$tmp/mixed/"
"$py" "$check" "$tmp/mixed" --size 1000 > "$tmp/mixed.log" 2>&1
rc=$?
if [ "$rc" = 1 ]; then
    echo "ok    the check fails on the model.igs of --top keep with the mesh of --top cut:"
    grep FAIL "$tmp/mixed.log"
else
    echo "FAIL: the check passed (exit $rc) a model.igs that is not of its mesh"; fail=1
fi
[ "$fail" = 0 ] && rm -rf "$tmp"
echo "cad demo: $([ "$fail" = 0 ] && echo passed || echo FAILED)"
exit $fail
