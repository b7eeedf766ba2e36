#!/bin/bash
# A closed intersection curve (issue 17): a dome through a flat, both
# wider than the circle they meet on (radius 4.5 km, 24 degrees). Remeshed
# at 1 km, connected, the independent check_connect finds no two faults
# intersecting but along shared nodes and edges (--criteria), and the two
# share the whole circle as a closed chain of edges (as many shared edges
# as shared nodes); report.json has one crossing junction and nothing
# unjoined, no gap, no island, nothing missing. Without connecting, the
# same check fails (so it can fail).
# usage: connect_loop_check.sh FAULTMESH CHECK_CONNECT TMPDIR PYTHON
set -u
exe=$1 check=$2 tmp=$3 py=$4
rm -rf "$tmp" && mkdir -p "$tmp/in"
fail=0
"$py" - "$tmp/in" <<'PY' || { echo "FAIL: writing the inputs"; exit 1; }
import sys
X0, Y0 = 500000.0, 3700000.0
def write(path, name, top, R, half=10000.0, h=500.0):
    n = int(2 * half / h)
    with open(path, 'w') as f:
        f.write('GOCAD TSurf 1\nHEADER {\nname:%s\n}\nTFACE\n' % name)
        k = 1
        for j in range(n + 1):
            for i in range(n + 1):
                x, y = -half + 2 * half * i / n, -half + 2 * half * j / n
                z = top - (x * x + y * y) / (2 * R) if R > 0 else top
                f.write('VRTX %d %.6f %.6f %.6f\n' % (k, X0 + x, Y0 + y, z))
                k += 1
        for j in range(n):
            for i in range(n):
                a = 1 + j * (n + 1) + i
                f.write('TRGL %d %d %d\nTRGL %d %d %d\n' % (a, a + 1, a + n + 2, a, a + n + 2, a + n + 1))
        f.write('END\n')
d = sys.argv[1]
write(d + '/SYNT-LOOP-DOME-Dome_fault-SYN1.ts', 'SYNT-LOOP-DOME-Dome_fault-SYN1', -5000.0, 10000.0)
write(d + '/SYNT-LOOP-FLAT-Flat_fault-SYN1.ts', 'SYNT-LOOP-FLAT-Flat_fault-SYN1', -6000.0, 0.0)
PY
"$exe" remesh --quiet --no-cache --size 1000 --formats obj -o "$tmp/on" "$tmp/in" >"$tmp/on.log" 2>&1 ||
    { echo "FAIL: faultmesh remesh"; cat "$tmp/on.log"; exit 1; }
"$check" --criteria "$tmp/on/mesh.obj" >"$tmp/on.out" 2>&1
rc=$?
cat "$tmp/on.out"
[ "$rc" = 0 ] || { echo "FAIL: check_connect --criteria exit $rc"; fail=1; }
share=$(sed -n 's/^sharing: 1 fault pairs share \([0-9]*\) vertices and \([0-9]*\) edges$/\1 \2/p' "$tmp/on.out")
set -- $share
if [ -n "$share" ] && [ "$1" -ge 25 ] && [ "$1" = "$2" ]; then
    echo "the circle: $1 shared nodes, $2 shared edges (a closed chain)"
else
    echo "FAIL: shared nodes and edges of the circle: '${share}'"; fail=1
fi
"$py" - "$tmp/on/report.json" <<'PY' || fail=1
import json, sys
r = json.load(open(sys.argv[1]))
c = r['connect']
m = c['connect_measures']
bad = []
types = [j['type'] for j in c['junctions']]
if types != ['crossing']:
    bad.append('junctions %s, expected one crossing' % types)
if m['unclosed_gap_m'] or m['islands'] or m['missing_area_m2'] or m['intersections_unjoined']:
    bad.append('connect measures %s' % {k: v for k, v in m.items() if not isinstance(v, list)})
if c['carved_triangles']:
    bad.append('%d triangles carved' % c['carved_triangles'])
for b in bad:
    print('FAIL:', b)
sys.exit(1 if bad else 0)
PY
"$exe" remesh --quiet --no-cache --no-connect --size 1000 --formats obj -o "$tmp/off" "$tmp/in" >"$tmp/off.log" 2>&1 ||
    { echo "FAIL: faultmesh remesh --no-connect"; exit 1; }
"$check" --criteria "$tmp/off/mesh.obj" >"$tmp/off.out" 2>&1
rc=$?
[ "$rc" = 1 ] || { echo "FAIL: unconnected: check_connect --criteria exit $rc, expected 1"; fail=1; }
[ "$fail" = 0 ] && rm -rf "$tmp"
exit $fail
