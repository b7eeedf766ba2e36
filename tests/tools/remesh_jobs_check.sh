#!/bin/bash
# `faultmesh remesh` of a spread of CFM faults (every EVERY-th file) with
# one thread and with two, twice: every output but report.json (which
# holds times) must be byte-identical. Faults fitted side by side share
# the BLAS and solver libraries, so this is where a thread-unsafe or
# thread-count-dependent library shows.
# usage: remesh_jobs_check.sh FAULTMESH OUTDIR INPUTDIR [EVERY]
# exit 77 when INPUTDIR is missing.
set -u
exe=$1 out=$2 in=$3 every=${4:-12}
[ -d "$in" ] || { echo "skipped: $in does not exist"; exit 77; }
rm -rf "$out"
mkdir -p "$out/in"
n=0
for f in $(ls "$in"/*.ts | sort | awk -v e="$every" 'NR % e == 1'); do
  ln -s "$(cd "$(dirname "$f")" && pwd)/$(basename "$f")" "$out/in/"
  n=$((n + 1))
done
echo "$n faults"
for run in j1:1 j2a:2 j2b:2; do
  name=${run%%:*} jobs=${run##*:}
  # every run fits (no models from the fit cache): the fits are what
  # depends on the libraries' threads
  "$exe" remesh --quiet --no-cache -j "$jobs" -o "$out/$name" "$out/in"
  rc=$?
  if [ "$rc" != 0 ] && [ "$rc" != 1 ]; then echo "FAIL: remesh -j $jobs exit $rc"; exit 1; fi
done
fail=0
for f in $(cd "$out/j1" && ls | grep -v '^report.json$'); do
  for other in j2a j2b; do
    if ! cmp -s "$out/j1/$f" "$out/$other/$f"; then
      echo "FAIL: $f differs between -j 1 and $other"
      fail=1
    fi
  done
done
nfiles=$(cd "$out/j1" && ls | grep -vc '^report.json$')
[ "$fail" = 0 ] && echo "$nfiles output files byte-identical with -j 1, -j 2 and -j 2 again" && rm -rf "$out"
exit $fail
