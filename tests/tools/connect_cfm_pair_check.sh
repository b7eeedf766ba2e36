#!/bin/bash
# A few CFM faults that meet, remeshed together (connected, the default),
# then check_remesh.py (remesh_cfm_check.sh) on the output with the
# criteria given: one junction, checked in seconds.
# usage: connect_cfm_pair_check.sh FAULTMESH PYTHON TMPDIR CFMDIR NAME... [-- CHECK_ARGS...]
# NAME: a .ts file of CFMDIR. Exit 77 without the CFM (or the readers).
set -u
exe=$1 py=$2 tmp=$3 cfm=$4
shift 4
names=()
while [ $# -gt 0 ] && [ "$1" != -- ]; do names+=("$1"); shift; done
[ $# -gt 0 ] && shift
rm -rf "$tmp" && mkdir -p "$tmp/in"
for n in "${names[@]}"; do
    [ -f "$cfm/$n" ] || { echo "no $cfm/$n: skipped"; exit 77; }
    ln -s "$cfm/$n" "$tmp/in/"
done
exec bash "$(dirname "$0")/remesh_cfm_check.sh" "$exe" "$py" "$tmp/out" "$tmp/in" --size 1000 -- \
    --size 1000 "$@"
