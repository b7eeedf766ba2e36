#!/bin/bash
# The CLI is a thin front end of the installed library (issue 21): it
# includes only the installed headers (include/faultmesh, as
# <faultmesh/NAME.h>) and its own (src/cli), and its CMake target links
# the library target and adds no include folder of its own; and its .c
# files stay under LIMIT lines, so that the work goes to the library.
#
# usage: cli_public_api_test.sh SOURCE [LIMIT]
set -euo pipefail
src=$1 limit=${2:-1800}
cli=$src/src/cli
fail=0
while IFS= read -r hit; do
    file=${hit%%:*}
    inc=$(echo "$hit" | sed -E 's/^[^#]*#[[:space:]]*include[[:space:]]*//')
    name=$(echo "$inc" | sed -E 's/^[<"]([^>"]+)[>"].*/\1/')
    case $inc in
    \"*)
        # quoted: one of the CLI's own headers
        if [ ! -f "$cli/$name" ]; then
            echo "FAIL: ${file#$src/} includes \"$name\", not a header of src/cli"
            fail=1
        fi ;;
    \<faultmesh/*)
        base=${name#faultmesh/}
        if [ ! -f "$src/include/faultmesh/$base" ] && [ ! -f "$src/include/faultmesh/$base.in" ]; then
            echo "FAIL: ${file#$src/} includes <$name>, not an installed header"
            fail=1
        fi ;;
    *)
        # a system header, but none of the library's private ones by <>
        if [ -n "$(find "$src/src" -name "$(basename "$name")" -not -path "$cli/*" | head -1)" ]; then
            echo "FAIL: ${file#$src/} includes <$name>, a private header of the library"
            fail=1
        fi ;;
    esac
done < <(grep -HE '^[[:space:]]*#[[:space:]]*include' "$cli"/*.c "$cli"/*.h)
# CMake: the library target, no private include folder
cm=$cli/CMakeLists.txt
if grep -qE 'target_include_directories|include_directories\(' "$cm"; then
    echo "FAIL: src/cli/CMakeLists.txt adds include folders"
    fail=1
fi
if ! grep -qE 'target_link_libraries\(faultmesh_cli PRIVATE faultmesh::faultmesh( Threads::Threads)?\)' "$cm"; then
    echo "FAIL: src/cli/CMakeLists.txt links something else than faultmesh::faultmesh"
    grep -n target_link_libraries "$cm"
    fail=1
fi
lines=$(cat "$cli"/*.c | wc -l)
if [ "$lines" -ge "$limit" ]; then
    echo "FAIL: src/cli/*.c has $lines lines, the limit is $limit: move the work to the library"
    fail=1
fi
[ "$fail" = 0 ] && echo "ok: src/cli includes only include/faultmesh and its own headers; $lines lines of .c (limit $limit)"
exit $fail
