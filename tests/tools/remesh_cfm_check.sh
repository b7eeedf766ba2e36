#!/bin/bash
# `faultmesh remesh` on a whole CFM set, then check_remesh.py on its output
# (distances to the CFM originals included). Every figure is printed; the
# criteria named in CHECK_ARGS (--criteria ...) are asserted.
# usage: remesh_cfm_check.sh FAULTMESH PYTHON OUTDIR INPUTDIR [REMESH_ARGS...] -- [CHECK_ARGS...]
# exit 77 when INPUTDIR or the readers are missing. The output (hundreds of
# MB) is removed when the check passes and kept to debug when it fails.
set -u
exe=$1 py=$2 out=$3 in=$4
shift 4
margs=() cargs=()
while [ $# -gt 0 ] && [ "$1" != -- ]; do margs+=("$1"); shift; done
[ $# -gt 0 ] && shift
cargs=("$@")
[ -d "$in" ] || { echo "skipped: $in does not exist"; exit 77; }
"$py" -c "import numpy, meshio, gmsh" 2>/dev/null || { echo "skipped: meshio / gmsh / numpy missing"; exit 77; }
rm -rf "$out"
start=$(date +%s)
"$exe" remesh --quiet "${margs[@]}" -o "$out" "$in"
rc=$?
echo "faultmesh remesh: exit $rc in $(( $(date +%s) - start )) s"
# 1: some faults failed (listed in report.json, judged by the check's
# `failures` criterion); anything else is a crash or bad usage.
if [ "$rc" != 0 ] && [ "$rc" != 1 ]; then echo "FAIL: faultmesh remesh exit $rc"; exit 1; fi
"$py" "$(dirname "$0")/check_remesh.py" "$out" --original "$in" "${cargs[@]}"
rc=$?
[ "$rc" = 0 ] && rm -rf "$out"
exit $rc
