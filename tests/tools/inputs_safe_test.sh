#!/bin/bash
# Inputs are never put at risk: an output folder that holds an input file
# (an output of the same name would replace it), is an input folder or
# lies inside one is refused before any work, exit 2, every input left
# byte for byte as it was, for `remesh` and `fit`. Folder walks read each
# real folder once: symbolic links back up the tree (one, two, through a
# subfolder) are reported and skipped, never read again or looped on; a
# dangling link is one failed input; a link out of the tree is followed.
# A folder with no .ts file, a folder as the settings file and numbers
# that are not decimal are usage errors (exit 2).
# usage: inputs_safe_test.sh FAULTMESH TMPDIR
set -u
exe=$1 tmp=$2
rm -rf "$tmp" && mkdir -p "$tmp"
. "$(dirname "$0")/cli_lib.sh"

expect_rc 0 "synth" "$exe" synth --spacing 2000 -o "$tmp/s"
main=SYNT-MAIN-SS-Main_strike_slip_fault-SYN1.ts
tj=SYNT-MAIN-TJNC-T_junction_gap_fault-SYN1.ts
mkdir -p "$tmp/d/sub"
cp "$tmp/s/$main" "$tmp/d/"
cp "$tmp/s/$tj" "$tmp/d/sub/"
sums() { (cd "$tmp/d" && find . -type f -exec md5sum {} + | sort); }
before=$(sums)
for cmd in remesh fit; do
    for o in "$tmp/d" "$tmp/d/" "$tmp/d/." "$tmp/d/sub/.." "$tmp/d/out" "$tmp/d/sub/new/deeper"; do
        expect_rc 2 "$cmd -o $o into its input folder" "$exe" "$cmd" -o "$o" "$tmp/d"
    done
    expect_rc 2 "$cmd -o the folder of an input file" "$exe" "$cmd" -o "$tmp/d" "$tmp/d/$main"
    expect_rc 2 "$cmd -o the folder of an input file, other spelling" "$exe" "$cmd" \
        -o "$tmp/d/sub/.." "$tmp/d/$main"
done
[ "$(sums)" = "$before" ] && ok || bad "inputs changed"
[ ! -e "$tmp/d/out" ] && [ ! -e "$tmp/d/sub/new" ] && ok || bad "a refused output folder was created"
# an output folder beside the inputs, or above them, is fine
expect_rc 0 "remesh -o beside" "$exe" remesh --quiet --size 4000 -o "$tmp/beside" "$tmp/d"
expect_rc 0 "remesh -o a folder holding the input folder" "$exe" remesh --quiet --size 4000 \
    -o "$tmp" "$tmp/d/sub"
[ "$(sums)" = "$before" ] && ok || bad "inputs changed by a run beside them"

# symbolic link loops: each fault read once, each loop reported once
ln -s . "$tmp/d/x"
ln -s .. "$tmp/d/sub/y"
ln -s "$tmp/d" "$tmp/d/sub/z"
out=$(timeout 60 "$exe" info --json "$tmp/d" 2>"$tmp/loop.err")
rc=$?
[ "$rc" = 0 ] && ok || bad "info on a folder with link loops: exit $rc"
n=$(printf '%s' "$out" | python3 -c "import json,sys; print(len(json.load(sys.stdin)['files']))")
[ "$n" = 2 ] && ok || bad "link loops: $n files read, expected 2"
[ "$(grep -c 'read already' "$tmp/loop.err")" = 3 ] && ok || bad "link loops: $(cat "$tmp/loop.err")"
# a dangling link fails as one input; a link out of the tree is followed
ln -s "$tmp/nowhere.ts" "$tmp/d/dangling.ts"
mkdir -p "$tmp/other" && cp "$tmp/s/$main" "$tmp/other/copy.ts"
ln -s "$tmp/other" "$tmp/d/outside"
expect_rc 1 "remesh with a dangling link" timeout 120 "$exe" remesh --quiet --size 4000 \
    -o "$tmp/links" "$tmp/d"
[ "$(json "$tmp/links/report.json" "len(r['faults'])")" = 4 ] && ok ||
    bad "dangling and outside links: $(json "$tmp/links/report.json" "[f['file'] for f in r['faults']]")"
[ "$(sums)" = "$before" ] && ok || bad "inputs changed by the link runs"
# usage that used to pass for something else: a folder with no .ts file,
# a folder given as the settings file, numbers other than decimal
mkdir -p "$tmp/none"
for cmd in remesh fit; do
    expect_rc 2 "$cmd on a folder with no .ts file" "$exe" "$cmd" -o "$tmp/none-out" "$tmp/none"
    grep -q "no .ts files found" "$tmp/err" && ok || bad "$cmd no .ts: $(cat "$tmp/err")"
done
expect_rc 2 "--config naming a folder" "$exe" remesh --config "$tmp/none" -o "$tmp/cfg" "$tmp/s"
grep -q "a folder, not a settings file" "$tmp/err" && ok || bad "--config folder: $(cat "$tmp/err")"
for v in 0x10 inf nan 1e3x; do
    expect_rc 2 "--size $v" "$exe" remesh --size "$v" -o "$tmp/num" "$tmp/s"
done
[ ! -e "$tmp/none-out" ] && [ ! -e "$tmp/num" ] && ok || bad "a refused run created its output folder"
echo "inputs safe: $pass passed, $fail failed"
[ "$fail" = 0 ] && rm -rf "$tmp"
[ "$fail" = 0 ]
