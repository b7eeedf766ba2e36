#!/bin/bash
# `faultmesh demo` as a new user runs it, checked by check_remesh.py with
# every acceptance criterion of the mesh issue (the synthetic fault system
# must pass them all): default options (MSH 4.1, top cut), then
# --msh-version 2.2 --top keep (readers, quality, fidelity, tops kept), and
# the outputs of two identical runs (the second without the fit cache)
# must be byte-identical (report.json holds times and is left out;
# report.html holds none). report.html is
# checked against report.json (check_report_html.py); --no-report-html
# leaves it out.
# usage: remesh_demo_check.sh FAULTMESH PYTHON TMPDIR ; exit 77 when the
# readers (meshio, Gmsh, numpy) are missing.
set -u
exe=$1 py=$2 tmp=$3
check=$(dirname "$0")/check_remesh.py
rm -rf "$tmp" && mkdir -p "$tmp"
fail=0
run() { # description command...
    local what=$1; shift
    "$@"; local rc=$?
    [ "$rc" = 77 ] && { echo "skipped: $what"; exit 77; }
    [ "$rc" = 0 ] || { echo "FAIL: $what (exit $rc)"; fail=1; }
}
run "demo (4.1, top cut)" "$exe" demo -o "$tmp/cut"
run "check demo (4.1, top cut)" "$py" "$check" "$tmp/cut" --original "$tmp/cut/input" \
    --msh-version 4.1 --top cut --criteria all --verbose
run "report.html (4.1, top cut)" "$py" "$(dirname "$0")/check_report_html.py" "$tmp/cut"
# fitted afresh, whether or not the first run read its models from the
# fit cache: the same outputs either way
run "demo again" "$exe" demo --quiet --no-cache -o "$tmp/cut2"
if diff -r -x report.json "$tmp/cut" "$tmp/cut2" >/dev/null; then
    echo "ok    two demo runs give byte-identical outputs"
else
    echo "FAIL: two demo runs differ:"; diff -rq -x report.json "$tmp/cut" "$tmp/cut2"; fail=1
fi
run "demo (2.2, top keep)" "$exe" demo --msh-version 2.2 --top keep --no-report-html -o "$tmp/keep"
if [ -e "$tmp/keep/report.html" ]; then
    echo "FAIL: --no-report-html wrote report.html"; fail=1
else
    echo "ok    --no-report-html writes no report.html"
fi
run "check demo (2.2, top keep)" "$py" "$check" "$tmp/keep" --original "$tmp/keep/input" \
    --msh-version 2.2 --top keep --criteria all --verbose
[ -z "$(find "$tmp" -name '*.tmp.*')" ] || { echo "FAIL: temporary files left"; fail=1; }
[ "$fail" = 0 ] && rm -rf "$tmp"
echo "remesh demo: $([ "$fail" = 0 ] && echo passed || echo FAILED)"
exit $fail
