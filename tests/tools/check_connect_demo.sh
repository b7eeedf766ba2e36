#!/bin/bash
# check_connect on `faultmesh demo` output: it must succeed (no
# --criteria here; connect_demo asserts it) and write sane,
# deterministic JSON. With a Python interpreter the JSON is also read back
# and its totals, order and counts checked against the OBJ itself.
# usage: check_connect_demo.sh FAULTMESH CHECK_CONNECT TMPDIR [PYTHON]
set -u
exe=$1 check=$2 tmp=$3 py=${4:-}
rm -rf "$tmp" && mkdir -p "$tmp"
fail=0
"$exe" demo --quiet -o "$tmp/demo" >"$tmp/demo.log" 2>&1 || { echo "FAIL: faultmesh demo"; cat "$tmp/demo.log"; exit 1; }
for run in 1 2; do
    "$check" --json "$tmp/cc$run.json" "$tmp/demo/mesh.obj" >"$tmp/cc$run.out" 2>&1
    rc=$?
    [ "$rc" = 0 ] || { echo "FAIL: check_connect exit $rc"; cat "$tmp/cc$run.out"; fail=1; }
done
cat "$tmp/cc1.out"
cmp -s "$tmp/cc1.json" "$tmp/cc2.json" || { echo "FAIL: two runs give different JSON"; fail=1; }
if [ -n "$py" ] && [ "$fail" = 0 ]; then
    "$py" - "$tmp/cc1.json" "$tmp/demo/mesh.obj" <<'PY' || fail=1
import json, sys
j = json.load(open(sys.argv[1]))
names, nv, nt = [], 0, 0
for line in open(sys.argv[2]):
    if line.startswith('v '): nv += 1
    elif line.startswith('f '): nt += 1
    elif line.startswith('o '): names.append(line[2:].strip())
bad = []
def want(cond, what):
    if not cond: bad.append(what)
want(j['faults'] == len(names) == 10, 'fault count')
want(j['vertices'] == nv and j['triangles'] == nt, 'vertex / triangle counts')
want(j['distance'] == 1000 and j['self_checked'] is True, 'options')
idx = {n: i for i, n in enumerate(names)}
keys = [(idx[p['a']], idx[p['b']]) for p in j['pairs']]
want(all(a < b for a, b in keys) and keys == sorted(keys) and len(set(keys)) == len(keys), 'pairs sorted, a < b')
ip = j['intersecting_pairs']
want(j['intersections']['fault_pairs'] == len(ip), 'intersecting fault pairs')
want(j['intersections']['triangle_pairs'] == sum(p['triangle_pairs'] for p in ip), 'intersecting triangle pairs')
want(all(1 <= len(p['examples']) <= 3 for p in ip), 'examples')
for p in ip:
    for e in p['examples']:
        want(all(1 <= t <= nt for t in e['triangles']) and len(e['corners']) == 2, 'example triangles')
want(j['self_intersections']['triangle_pairs'] == sum(f['triangle_pairs'] for f in j['self_intersecting_faults']),
     'self-intersections')
sh = j['sharing']
want(sh['vertices'] == sum(p['shared_vertices'] for p in j['pairs'])
     and sh['edges'] == sum(p['shared_edges'] for p in j['pairs']), 'sharing totals')
near = j['near_pairs_not_sharing']
want(j['proximity']['near_pairs_not_sharing'] == len(near), 'near pairs count')
want(all(0 <= p['distance'] <= 1000 for p in near), 'near pair distances')
want(j['proximity']['unjoined_near_edges'] == sum(p['near_edges_a'] + p['near_edges_b'] for p in j['pairs']),
     'unjoined near edges')
# the branched splay's sheets rejoined at a T: the edges of its ~12 km
# branch line carry three triangles each, as the branching input did
want(j['degenerate_triangles'] == 0 and 8 <= j['nonmanifold_edges'] <= 20, 'demo mesh is clean')
for w in bad:
    print('FAIL: JSON:', w)
print('JSON checked: %d pairs, %d intersecting, %d near not sharing' % (len(j['pairs']), len(ip), len(near)))
sys.exit(1 if bad else 0)
PY
fi
[ "$fail" = 0 ] && rm -rf "$tmp"
echo "check_connect demo: $([ "$fail" = 0 ] && echo passed || echo FAILED)"
exit $fail
