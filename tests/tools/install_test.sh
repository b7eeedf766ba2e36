#!/bin/bash
# The installed library as a consumer sees it (issue 21): `cmake --install`
# into a temporary prefix, then examples/shared_nodes.c built against it
# four ways (pkg-config, pkg-config --static, find_package shared and
# static) or examples/shared_nodes.py run by Debian's python3 on the
# installed package; each must find the shared-node count of
# `faultmesh remesh`'s mesh.obj for the same two faults (vertices the faces
# of both faults' groups use, counted here).
# Always on two synthetic faults (faultmesh synth), so that a fresh clone
# tests it too; also on two CFM faults when ../shared/cfm is there.
#
# usage: install_test.sh c|python BUILD SOURCE PYTHON CFMDIR TMPDIR
set -euo pipefail
mode=$1 build=$(cd "$2" && pwd) src=$(cd "$3" && pwd) py=$4 tmp=$6
cfm=$(cd "$5" 2>/dev/null && pwd || echo "$5")
cc=${CC:-cc}
rm -rf "$tmp"
mkdir -p "$tmp"
tmp=$(cd "$tmp" && pwd)
prefix=$tmp/prefix
# the fit cache of every run here: nothing written to the user's, and the
# CLI and the examples share its models (which come out bit for bit)
export XDG_CACHE_HOME=$tmp/cache

cmake --install "$build" --prefix "$prefix" >"$tmp/install.log"
fm=$prefix/bin/faultmesh
libdir=$(dirname "$(find "$prefix" -name 'libfaultmesh.so' | head -1)")
[ -n "$libdir" ] || { echo "FAIL: no libfaultmesh.so installed"; exit 1; }
pcdir=$libdir/pkgconfig

fail=0
check() { # NAME EXPECTED OUTPUT-FILE
    local got
    got=$(sed -n 's/^shared nodes: //p' "$3")
    if [ "$got" = "$2" ]; then
        echo "ok: $1: $got shared nodes"
    else
        echo "FAIL: $1: '$got' shared nodes, faultmesh remesh's mesh.obj has $2"
        cat "$3"
        fail=1
    fi
}

# the two inputs of each case
"$fm" synth -o "$tmp/synth" >/dev/null
cases=(synth)
synth_a=$(ls "$tmp"/synth/SYNT-MAIN-SS-*.ts)
synth_b=$(ls "$tmp"/synth/SYNT-MAIN-TJNC-*.ts)
cfm_a=$cfm/CFM5.3/500m/OCBA-CBFZ-NCBF-Coronado_Bank_fault_north-CFM5_500m.ts
cfm_b=$cfm/CFM5.3/500m/OCBA-CBFZ-WEST-Coronado_Bank_west_splay-CFM5_500m.ts
if [ -f "$cfm_a" ] && [ -f "$cfm_b" ]; then
    cases+=(cfm)
else
    echo "note: no CFM in $cfm: the synthetic faults only"
fi
declare -A A B N
A[synth]=$synth_a B[synth]=$synth_b A[cfm]=$cfm_a B[cfm]=$cfm_b
for c in "${cases[@]}"; do
    "$fm" remesh -q --size 1000 -o "$tmp/ref_$c" "${A[$c]}" "${B[$c]}" 2>/dev/null
    N[$c]=$("$py" - "$tmp/ref_$c/mesh.obj" <<'EOF'
import sys
group, users = None, {}
for line in open(sys.argv[1]):
    if line.startswith("g "):
        group = line[2:].strip()
    elif line.startswith("f "):
        for v in line.split()[1:]:
            users.setdefault(v.split("/")[0], set()).add(group)
print(sum(1 for g in users.values() if len(g) > 1))
EOF
)
    [ "${N[$c]}" -gt 0 ] || { echo "FAIL: $c: the two faults share no node"; exit 1; }
done

run_all() { # NAME PROGRAM...
    local name=$1
    shift
    for c in "${cases[@]}"; do
        "$@" "${A[$c]}" "${B[$c]}" >"$tmp/$name.$c.out" 2>"$tmp/$name.$c.err" ||
            { echo "FAIL: $name on $c:"; cat "$tmp/$name.$c.err"; fail=1; continue; }
        check "$name $c" "${N[$c]}" "$tmp/$name.$c.out"
    done
}

if [ "$mode" = c ]; then
    ex=$src/examples/shared_nodes.c
    export PKG_CONFIG_PATH=$pcdir
    # pkg-config, the shared library (the loader told where it is)
    # shellcheck disable=SC2046
    "$cc" -std=c17 -Wall -Wextra -Werror -o "$tmp/pc_shared" "$ex" \
        $(pkg-config --cflags --libs faultmesh) -Wl,-rpath,"$libdir"
    run_all pkg-config "$tmp/pc_shared"
    # pkg-config --static: libfaultmesh.a, its Libs.private, and its
    # Requires.private as shared libraries. A plain --static would expand
    # those dependencies' own static dependencies (PROJ's curl, ssh, ldap,
    # ...), whose -dev packages Debian does not pull in; depth 2 is
    # faultmesh's own entries.
    libs="$(pkg-config --static --maximum-traverse-depth=2 --libs faultmesh |
            sed 's/-lfaultmesh\b/-l:libfaultmesh.a/')"
    libs+=" $(pkg-config --libs $(pkg-config --print-requires-private faultmesh | awk '{print $1}'))"
    # shellcheck disable=SC2086
    "$cc" -std=c17 -Wall -Wextra -Werror -o "$tmp/pc_static" "$ex" \
        $(pkg-config --cflags faultmesh) $libs
    if ldd "$tmp/pc_static" | grep -q libfaultmesh; then
        echo "FAIL: pkg-config --static: linked libfaultmesh.so"
        fail=1
    fi
    run_all pkg-config-static "$tmp/pc_static"
    # find_package, shared and static
    for kind in shared static; do
        cmake -S "$src/tests/install" -B "$tmp/cmake_$kind" -DCMAKE_PREFIX_PATH="$prefix" \
            -DFAULTMESH_EXAMPLE="$ex" -DFAULTMESH_KIND=$kind >"$tmp/cmake_$kind.log" 2>&1 ||
            { echo "FAIL: find_package ($kind):"; cat "$tmp/cmake_$kind.log"; exit 1; }
        cmake --build "$tmp/cmake_$kind" >>"$tmp/cmake_$kind.log" 2>&1 ||
            { echo "FAIL: build with find_package ($kind):"; cat "$tmp/cmake_$kind.log"; exit 1; }
        run_all "find_package-$kind" "$tmp/cmake_$kind/shared_nodes"
    done
    if ldd "$tmp/cmake_static/shared_nodes" | grep -q libfaultmesh; then
        echo "FAIL: find_package static: linked libfaultmesh.so"
        fail=1
    fi
elif [ "$mode" = python ]; then
    pkg=$(dirname "$(find "$prefix" -path '*/faultmesh/__init__.py' | head -1)")
    [ -n "$pkg" ] || { echo "FAIL: no Python package installed"; exit 1; }
    # the installed package only: not the source tree's, not a build tree
    # beside it, and the library it finds from where it lies
    cd "$tmp"
    unset FAULTMESH_LIBRARY FAULTMESH_BUILD
    export PYTHONPATH
    PYTHONPATH=$(dirname "$pkg")
    "$py" -c 'import faultmesh, sys; sys.exit(not faultmesh.__file__.startswith(sys.argv[1]))' \
        "$prefix" || { echo "FAIL: the package imported is not the installed one"; exit 1; }
    run_all python "$py" "$src/examples/shared_nodes.py"
else
    echo "usage: install_test.sh c|python BUILD SOURCE PYTHON CFMDIR TMPDIR" >&2
    exit 2
fi
exit $fail
