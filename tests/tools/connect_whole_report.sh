#!/bin/bash
# The whole CFM 500 m set connected at 1 km: every fault pair the
# independent check_connect finds crossing, touching or within the join
# distance either shares edges along a junction reported made, or has its
# line in report.json with the reason it was left open
# (check_connect_report.py). Exit 77 without the CFM.
# usage: connect_whole_report.sh FAULTMESH CHECK_CONNECT TMPDIR CFMDIR PYTHON
set -u
exe=$1 check=$2 tmp=$3 cfm=$4 py=$5
[ -d "$cfm" ] || { echo "no CFM at $cfm: skipped"; exit 77; }
rm -rf "$tmp" && mkdir -p "$tmp"
"$exe" remesh --quiet --size 1000 -o "$tmp/out" "$cfm" >"$tmp/remesh.log" 2>&1 \
    || { echo "FAIL: remesh"; tail -20 "$tmp/remesh.log"; exit 1; }
"$check" --json "$tmp/cc.json" "$tmp/out/mesh.obj" | head -6
"$py" "$(dirname "$0")/check_connect_report.py" "$tmp/out" "$tmp/cc.json" || exit 1
rm -rf "$tmp"
