#!/bin/bash
# GNU option conventions (issue 22): --name=value, -j2, -oDIR, bundled
# short flags and -- give the same run as the plain forms; a flag given a
# value, a missing -o, an output that is a file, a bad or missing value
# and an unknown option are usage errors: exit 2, one line, one prefix.
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

# usage errors: exit 2, one line with one prefix, saying what is wrong
one_line() { # description pattern
    [ "$(wc -l <"$tmp/err")" = 1 ] && grep -q "^faultmesh: $2" "$tmp/err" && ok ||
        bad "$1: $(cat "$tmp/err")"
}
expect_rc 2 "no -o" "$exe" remesh --quiet "$tmp/in"
one_line "no -o" "remesh needs -o DIR"
touch "$tmp/afile"
expect_rc 2 "-o a file" "$exe" remesh --quiet -o "$tmp/afile" "$tmp/in"
one_line "-o a file" "-o .*afile is a file, not a folder"
expect_rc 2 "--size -5" "$exe" remesh --quiet --size -5 -o "$tmp/x" "$tmp/in"
one_line "--size -5" "--size needs a positive number, got '-5'"
expect_rc 2 "--size 0" "$exe" remesh --quiet --size 0 -o "$tmp/x" "$tmp/in"
one_line "--size 0" "--size needs a positive number, got '0'"
expect_rc 2 "--size last" "$exe" remesh --quiet -o "$tmp/x" "$tmp/in" --size
one_line "--size last" "--size needs a value"
expect_rc 2 "unknown option" "$exe" remesh --quiet --sise 4000 -o "$tmp/x" "$tmp/in"
one_line "unknown option" "unknown option '--sise'"

echo "gnu_options_test: $pass passed, $fail failed"
[ "$fail" = 0 ]
