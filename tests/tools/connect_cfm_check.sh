#!/bin/bash
# Conforming meshes on a CFM group of the pilot study: the Puente Hills
# thrust system (every WTRA-PHTS fault of the CFM 500 m set: the four
# Puente Hills thrust segments, Las Cienagas, San Vicente, Upper Elysian
# Park, Peralta Hills) remeshed at 1 km, connected by default, with
# --keep-crossings so that the junctions alone must conform (no fault
# carved where it met another). The
# independent check_connect must find no two faults crossing or touching
# anywhere but along shared nodes and edges, and the faults that meet must
# share nodes; with PYTHON, check_connect_report.py holds report.json to
# check_connect's pairs (every near pair sharing no edge has a reason).
# Exit 77 without the CFM.
# usage: connect_cfm_check.sh FAULTMESH CHECK_CONNECT TMPDIR CFMDIR [PYTHON]
set -u
exe=$1 check=$2 tmp=$3 cfm=$4 py=${5:-}
ls "$cfm"/WTRA-PHTS-*.ts >/dev/null 2>&1 || { echo "no CFM at $cfm: skipped"; exit 77; }
rm -rf "$tmp" && mkdir -p "$tmp/in"
for f in "$cfm"/WTRA-PHTS-*.ts; do ln -s "$f" "$tmp/in/"; done
"$exe" remesh --quiet --keep-crossings --size 1000 -o "$tmp/out" "$tmp/in" >"$tmp/remesh.log" 2>&1 \
    || { echo "FAIL: remesh"; cat "$tmp/remesh.log"; exit 1; }
"$check" --criteria --json "$tmp/cc.json" "$tmp/out/mesh.obj" | tee "$tmp/cc.out"
rc=${PIPESTATUS[0]}
[ "$rc" = 0 ] || { echo "FAIL: check_connect --criteria exit $rc"; exit 1; }
grep -q "fault pairs share" "$tmp/cc.out" || { echo "FAIL: no fault pair shares nodes"; exit 1; }
shared=$(sed -n 's/^sharing: \([0-9]*\) fault pairs share.*/\1/p' "$tmp/cc.out")
[ "${shared:-0}" -ge 2 ] || { echo "FAIL: only ${shared:-0} fault pairs share nodes"; exit 1; }
if [ -n "$py" ]; then
    "$py" "$(dirname "$0")/check_connect_report.py" "$tmp/out" "$tmp/cc.json" \
        || { echo "FAIL: report.json misses near pairs"; exit 1; }
fi
echo "connect cfm (Puente Hills): ok, $shared fault pairs share nodes"
