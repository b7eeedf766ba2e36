#!/bin/bash
# The synthetic fault system through `faultmesh fit`, every output read back.
set -eu
exe=$1 py=$2 dir=$3
rm -rf "$dir"
"$exe" synth -o "$dir/in" >/dev/null
"$py" "$(dirname "$0")/check_fit.py" "$exe" "$dir/out" --readers 100 "$dir/in"
