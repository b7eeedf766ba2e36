#!/bin/bash
# Help texts list every option (issue 22): each option a command's parser
# knows (read from the sources: strcmp(a, "--name")) appears in some
# command's --help, and the top-level help names every command and
# --version.
# usage: help_test.sh FAULTMESH SRCDIR TMPDIR
set -u
exe=$1 src=$2 tmp=$3
rm -rf "$tmp" && mkdir -p "$tmp"
. "$(dirname "$0")/cli_lib.sh"

for c in info fit remesh demo synth; do
    "$exe" "$c" --help >>"$tmp/help" 2>&1 || bad "$c --help: exit $?"
done
"$exe" --help >"$tmp/top" || bad "--help: exit $?"
for c in info fit remesh demo synth; do
    grep -q "^  $c " "$tmp/top" && ok || bad "top-level help lacks $c"
done
grep -q -- "--version" "$tmp/top" && ok || bad "top-level help lacks --version"
opts=$(grep -ho 'strcmp(a, "-[^"]*")' "$src"/*.c | sed 's/.*"\(-[^"]*\)".*/\1/' | sort -u)
[ -n "$opts" ] || bad "no options found in $src"
for o in $opts; do
    grep -q -- "$o\b" "$tmp/help" && ok || bad "no --help lists $o"
done
echo "help_test: $pass passed, $fail failed"
[ "$fail" = 0 ]
