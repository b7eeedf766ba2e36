#!/bin/bash
# fit and remesh name their per-fault files by one rule (fm_names.h): two
# faults of one name, names that differ only in unsafe bytes or in case,
# and a 300-byte name each get a file of their own, the same stem in both
# commands, nothing overwritten (issue 18, item 5).
# usage: names_test.sh FAULTMESH TMPDIR
set -u
exe=$1 tmp=$2
rm -rf "$tmp" && mkdir -p "$tmp"
. "$(dirname "$0")/cli_lib.sh"

expect_rc 0 "synth" "$exe" synth --spacing 2000 -o "$tmp/s"
src="$tmp/s/SYNT-SWFB-BLND-Blind_fault-SYN1.ts"
long=$(printf 'L%.0s' $(seq 300))
i=0
for n in dup dup "a/b" "a:b" "A:B" "$long"; do
    i=$((i + 1))
    # the same blind fault, moved 30 km apart each time so none meet
    awk -v n="$n" -v dx=$((i * 30000)) '
        /^name:/ { print "name:" n; next }
        $1 == "VRTX" || $1 == "PVRTX" { $3 = $3 + dx } { print }' "$src" > "$tmp/in$i.ts"
done
mkdir -p "$tmp/in" && mv "$tmp"/in[0-9].ts "$tmp/in/"
expect_rc 0 "fit" "$exe" fit -o "$tmp/fit" "$tmp/in"
expect_rc 0 "remesh" "$exe" remesh --quiet --size 4000 -o "$tmp/rem" "$tmp/in"
stems="dup dup-2 a_b a_b-2 A_B-3 $(printf 'L%.0s' $(seq 200))"
for s in $stems; do
    [ -f "$tmp/fit/$s.model.json" ] && [ -f "$tmp/fit/$s.igs" ] && [ -f "$tmp/fit/$s.vtu" ] && ok ||
        bad "fit: no $s.* ($(ls "$tmp/fit" | head -20 | tr '\n' ' '))"
    [ -f "$tmp/rem/$s.ts" ] && ok || bad "remesh: no $s.ts ($(ls "$tmp/rem" | head -20 | tr '\n' ' '))"
done
[ "$(ls "$tmp/fit"/*.model.json | wc -l)" = 6 ] && ok || bad "fit: not 6 models"
[ "$(ls "$tmp/rem"/*.ts | wc -l)" = 6 ] && ok || bad "remesh: not 6 faults"
echo "names: $pass passed, $fail failed"
[ "$fail" = 0 ] && rm -rf "$tmp"
[ "$fail" = 0 ]
