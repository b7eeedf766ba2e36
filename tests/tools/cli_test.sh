#!/bin/bash
# The command line as users meet it: exit codes, messages naming FILE:LINE,
# good files processed beside bad ones, deterministic and atomic outputs.
set -u
exe=$1 data=$2/cli tmp=$3
rm -rf "$tmp" && mkdir -p "$tmp"
. "$(dirname "$0")/cli_lib.sh"

expect_rc 2 "no arguments" "$exe"
expect_rc 2 "unknown command" "$exe" frobnicate
expect_rc 0 "help" "$exe" --help
expect_rc 2 "info without files" "$exe" info
expect_rc 2 "info unknown option" "$exe" info --bogus "$data/good.ts"
expect_rc 2 "info missing path" "$exe" info "$tmp/does-not-exist.ts"
expect_rc 2 "info bad number" "$exe" info --weld-tol abc "$data/good.ts"

expect_rc 0 "info good file" "$exe" info "$data/good.ts"
grep -q "tiny_good: 1 part, 4 vertices (0 welded), 2 triangles, 1.000 km2" "$tmp/out" && ok ||
    bad "info text: $(cat "$tmp/out")"

# A bad file among good ones: the good ones are reported, the bad one named
# with its line, exit status 1.
expect_rc 1 "info good + bad" "$exe" info "$data/good.ts" "$data/bad.ts" "$data/good.ts"
[ "$(grep -c tiny_good "$tmp/out")" = 2 ] && ok || bad "good files not both reported"
grep -q "bad.ts:9: " "$tmp/err" && ok || bad "bad file message lacks FILE:LINE: $(cat "$tmp/err")"
grep -q "1 of 3 files failed" "$tmp/err" && ok || bad "failure count missing"

expect_rc 1 "info --json good + bad" "$exe" info --json "$data/good.ts" "$data/bad.ts"
grep -q '"status": "error"' "$tmp/out" && grep -q '"status": "ok"' "$tmp/out" && ok ||
    bad "json statuses"
grep -q '"failed": 1' "$tmp/out" && ok || bad "json summary"

# synth: deterministic, byte for byte.
expect_rc 0 "synth" "$exe" synth -o "$tmp/s1"
expect_rc 0 "synth again" "$exe" synth -o "$tmp/s2"
diff -r "$tmp/s1" "$tmp/s2" >/dev/null && ok || bad "synth output differs between runs"
n=$(ls "$tmp/s1"/*.ts 2>/dev/null | wc -l)
[ "$n" -ge 8 ] && ok || bad "synth wrote $n .ts files"
expect_rc 0 "info on synth folder" "$exe" info "$tmp/s1"
expect_rc 2 "synth without -o" "$exe" synth

# Atomic output: when a file cannot be put in place, nothing partial and no
# temporary is left behind, and the command fails.
first=$(basename "$(ls "$tmp/s1"/*.ts | head -n 1)")
mkdir -p "$tmp/s3/$first"
expect_rc 1 "synth onto a blocked name" "$exe" synth -o "$tmp/s3"
[ -z "$(find "$tmp/s3" -name '*.tmp.*')" ] && ok || bad "temporary files left behind"

echo "cli: $pass passed, $fail failed"
[ "$fail" = 0 ]
