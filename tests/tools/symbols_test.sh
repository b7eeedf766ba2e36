#!/bin/bash
# libfaultmesh.so exports the installed API and nothing else (issue 21):
# every dynamic symbol it defines is fm_-prefixed and declared FM_API in
# include/faultmesh, every FM_API declaration is exported, and the Python
# package's prototype table (python/faultmesh/_lib.py) names exactly those
# functions, since ctypes checks no prototype against the headers.
#
# usage: symbols_test.sh LIBFAULTMESH.so SOURCE [PYTHON]
set -euo pipefail
lib=$1 src=$2 py=${3:-}
fail=0
exported=$(nm -D --defined-only "$lib" | awk '{print $3}' | sort)
declared=$(cat "$src"/include/faultmesh/*.h "$src"/include/faultmesh/*.h.in |
           grep -E '^FM_API ' | sed -E 's/^[^(]*[ *]([A-Za-z_0-9]+)\(.*/\1/' | sort)
n=$(echo "$exported" | wc -l)
bad=$(echo "$exported" | grep -v '^fm_' || true)
if [ -n "$bad" ]; then
    echo "FAIL: exported without the fm_ prefix:"
    echo "$bad"
    fail=1
fi
if [ "$exported" != "$declared" ]; then
    echo "FAIL: exported (<) and declared FM_API (>) differ:"
    diff <(echo "$exported") <(echo "$declared") || true
    fail=1
fi
if [ -n "$py" ]; then
    table=$(cd "$src/python" && "$py" -c 'from faultmesh import _lib; print("\n".join(sorted(_lib.PROTOTYPES)))')
    if [ "$table" != "$declared" ]; then
        echo "FAIL: python/faultmesh/_lib.py's prototypes (<) and FM_API (>) differ:"
        diff <(echo "$table") <(echo "$declared") || true
        fail=1
    fi
fi
[ "$fail" = 0 ] && echo "ok: $n symbols exported, all fm_ and declared FM_API"
exit $fail
