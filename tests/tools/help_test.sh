#!/bin/bash
# Help texts list every option (issue 22): each option a command's parser
# knows (read from the sources: strcmp(a, "--name")) appears in some
# command's --help, and the top-level help names every command and
# --version; and the man page faultmesh(1) lists every option.
# With BUILDDIR, `cmake --install` puts the command and the man page in place.
# usage: help_test.sh FAULTMESH SRCDIR TMPDIR [BUILDDIR]
set -u
exe=$1 src=$2 tmp=$3 build=${4:-}
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
# the man page lists them too (troff's \- read as -)
man=$(dirname "$0")/../../docs/faultmesh.1
sed 's/\\-/-/g; s/\\f[BIRP]//g' "$man" >"$tmp/man"
for o in $opts; do
    grep -q -- "$o\b" "$tmp/man" && ok || bad "the man page lacks $o"
done
if command -v groff >/dev/null; then
    groff -man -Tutf8 -ww -z "$man" 2>"$tmp/groff" && [ ! -s "$tmp/groff" ] && ok ||
        bad "the man page does not render cleanly: $(cat "$tmp/groff")"
fi
if [ -n "$build" ]; then
    cmake --install "$build" --prefix "$tmp/prefix" >"$tmp/install" 2>&1 || bad "install: $(cat "$tmp/install")"
    [ -x "$tmp/prefix/bin/faultmesh" ] && [ -f "$tmp/prefix/share/man/man1/faultmesh.1" ] && ok ||
        bad "install: no bin/faultmesh or share/man/man1/faultmesh.1"
fi
echo "help_test: $pass passed, $fail failed"
[ "$fail" = 0 ]
