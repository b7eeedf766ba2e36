#!/bin/bash
# GNU option conventions (issue 22): --name=value, -j2, -oDIR, bundled
# short flags and -- give the same run as the plain forms; a flag given a
# value is a usage error (exit 2, one line).
# usage: gnu_options_test.sh FAULTMESH TMPDIR
set -u
exe=$1 tmp=$2
rm -rf "$tmp" && mkdir -p "$tmp"
. "$(dirname "$0")/cli_lib.sh"

expect_rc 0 "synth" "$exe" synth --spacing 2000 -o "$tmp/in"
expect_rc 0 "plain forms" "$exe" remesh --quiet --size 4000 -j 2 -o "$tmp/plain" "$tmp/in"
expect_rc 0 "--name=value, -j2, -oDIR" "$exe" remesh --quiet --size=4000 -j2 -o"$tmp/gnu" "$tmp/in"
expect_rc 0 "--output=DIR" "$exe" remesh -q --size=4000 --jobs=2 --output="$tmp/long" "$tmp/in"
for d in gnu long; do
    same=1
    for f in "$tmp/plain"/*.ts "$tmp/plain"/mesh.*; do
        cmp -s "$f" "$tmp/$d/$(basename "$f")" || same=0
    done
    [ "$same" = 1 ] && ok || bad "$d: outputs differ from the plain forms'"
done
# bundled flags: -qv is -q -v (quiet wins for the summary: nothing on stdout)
expect_rc 0 "bundled -qv" "$exe" remesh -qv --size 4000 -o "$tmp/bundle" "$tmp/in"
# -- ends the options: an input whose name begins with '-'
mkdir -p "$tmp/dash" && cp "$(ls "$tmp/in"/*.ts | head -1)" "$tmp/dash/-odd.ts"
(cd "$tmp/dash" && "$exe" remesh --quiet --size 4000 -o ../dashout -- -odd.ts) >"$tmp/out" 2>"$tmp/err" &&
    ok || bad "-- then -odd.ts: $(cat "$tmp/err")"
[ -f "$tmp/dashout/mesh.vtu" ] && ok || bad "-- then -odd.ts: nothing meshed"
# a flag given a value: one line, exit 2
expect_rc 2 "--quiet=yes" "$exe" remesh --quiet=yes --size 4000 -o "$tmp/x" "$tmp/in"
[ "$(wc -l <"$tmp/err")" = 1 ] && grep -q "^faultmesh: option '--quiet' takes no value" "$tmp/err" &&
    ok || bad "--quiet=yes: $(cat "$tmp/err")"
# a value-taking option still checks its value
expect_rc 2 "--size=abc" "$exe" remesh --quiet --size=abc -o "$tmp/x" "$tmp/in"

echo "gnu_options_test: $pass passed, $fail failed"
[ "$fail" = 0 ]
