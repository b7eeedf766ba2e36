#!/bin/bash
# The synthetic system through `faultmesh info`, checked independently.
set -eu
exe=$1 py=$2 dir=$3
rm -rf "$dir"
"$exe" synth -o "$dir" >/dev/null
"$py" "$(dirname "$0")/check_info.py" "$exe" "$dir"
