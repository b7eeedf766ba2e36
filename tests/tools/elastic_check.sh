#!/bin/bash
# The elastic interaction check through `faultmesh remesh --elastic-check`
# (issue 19): a planted near-overlap (two vertical faults 75 m apart over
# 6 km, nothing joining them) is flagged, as one group of that fault pair
# with no junction of its own (or the unjoined one connect records); a
# clean T-junction is not, nor is anything of the demo system; the
# matrices of the T (--stiffness-matrix) read back by numpy: every
# element's self-stiffness
# restoring and equal to the check's, and the rake matrix reciprocal as
# Betti's theorem has it for elements far apart (K_ij A_i = K_ji A_j).
# usage: elastic_check.sh FAULTMESH TMPDIR PYTHON
set -u
exe=$1 tmp=$2 py=$3
rm -rf "$tmp" && mkdir -p "$tmp/overlap" "$tmp/tee"
"$py" - "$tmp" <<'PY' || { echo "FAIL: writing the inputs"; exit 1; }
import sys
X0, Y0 = 500000.0, 3700000.0
def wall(path, name, x0, y0, dx, dy, length, h=500.0, top=-1000.0, depth=9000.0):
    nu, nw = int(length / h), int(depth / h)
    with open(path, 'w') as f:
        f.write('GOCAD TSurf 1\nHEADER {\nname:%s\n}\nTFACE\n' % name)
        k = 1
        for j in range(nw + 1):
            for i in range(nu + 1):
                f.write('VRTX %d %.6f %.6f %.6f\n' % (k, X0 + x0 + i * h * dx, Y0 + y0 + i * h * dy, top - j * h))
                k += 1
        for j in range(nw):
            for i in range(nu):
                a = 1 + j * (nu + 1) + i
                f.write('TRGL %d %d %d\nTRGL %d %d %d\n' % (a, a + 1, a + nu + 2, a, a + nu + 2, a + nu + 1))
        f.write('END\n')
d = sys.argv[1]
wall(d + '/overlap/SYNT-OVLP-WEST-West_strand-SYN1.ts', 'SYNT-OVLP-WEST-West_strand-SYN1', 0, 0, 0, 1, 16000)
wall(d + '/overlap/SYNT-OVLP-EAST-East_strand-SYN1.ts', 'SYNT-OVLP-EAST-East_strand-SYN1', 75, 10000, 0, 1, 16000)
wall(d + '/tee/SYNT-TEE-STEM-Stem_fault-SYN1.ts', 'SYNT-TEE-STEM-Stem_fault-SYN1', 0, 0, 0, 1, 10000)
wall(d + '/tee/SYNT-TEE-BAR-Bar_fault-SYN1.ts', 'SYNT-TEE-BAR-Bar_fault-SYN1', -10000, 0, 1, 0, 20000)
PY
fail=0
for case in overlap tee; do
  extra=()
  [ "$case" = tee ] && extra=(--stiffness-matrix "$tmp/tee.npy")
  "$exe" remesh --quiet --no-cache --size 1000 --elastic-check --formats obj,html "${extra[@]}" \
      -o "$tmp/$case.out" "$tmp/$case" >"$tmp/$case.log" 2>&1 ||
      { echo "FAIL: faultmesh remesh ($case)"; cat "$tmp/$case.log"; exit 1; }
done
"$exe" demo --quiet --no-cache --elastic-check --formats vtu -o "$tmp/demo.out" >"$tmp/demo.log" 2>&1 ||
    { echo "FAIL: faultmesh demo"; cat "$tmp/demo.log"; exit 1; }
"$py" - "$tmp" <<'PY' || fail=1
import json, sys
d = sys.argv[1]
fail = 0
def check(cond, what):
    global fail
    print(('ok: ' if cond else 'FAIL: ') + what)
    fail |= not cond
over = json.load(open(d + '/overlap.out/report.json'))
e = over['elastic']
g = e['groups']
check(e['self_wrong_sign'] == 0, 'overlap: every self-stiffness restoring')
check(len(g) == 1, 'overlap: one group (%d)' % len(g))
if g:
    g = g[0]
    check(sorted(g['faults']) == ['SYNT-OVLP-EAST-East_strand-SYN1', 'SYNT-OVLP-WEST-West_strand-SYN1'],
          'overlap: the two strands')
    check(g['pairs'] >= 20, 'overlap: %d pairs flagged' % g['pairs'])
    check(g['max_ratio'] > 0.5, 'overlap: largest ratio %.3f' % g['max_ratio'])
    check(g['min_distance_m'] < 100, 'overlap: %.1f m apart' % g['min_distance_m'])
    # grouped under the junction of the two strands, if connect made one
    js = over['connect']['junctions']
    if g['junction'] is not None:
        check(sorted(js[g['junction'] - 1]['faults']) == sorted(g['faults']),
              'overlap: junction %d is of the two strands' % g['junction'])
    else:
        check(not any(sorted(j['faults']) == sorted(g['faults']) for j in js),
              'overlap: no junction of the two strands')
html = open(d + '/overlap.out/report.html').read()
check('Elastic interaction' in html and 'SYNT-OVLP-EAST-East_strand-SYN1' in html,
      'overlap: report.html has the table')
tee = json.load(open(d + '/tee.out/report.json'))
e = tee['elastic']
check(e['pairs_evaluated'] > 0 and e['groups'] == [] and e['pairs_flagged'] == 0,
      'tee: %d pairs evaluated, none flagged (largest ratio %.3f)' % (e['pairs_evaluated'], e['max_ratio']))
check(e['self_wrong_sign'] == 0, 'tee: every self-stiffness restoring')
demo = json.load(open(d + '/demo.out/report.json'))['elastic']
check(demo['pairs_evaluated'] > 0 and demo['pairs_flagged'] == 0 and demo['self_wrong_sign'] == 0,
      'demo: %d pairs evaluated, none flagged (largest coupling %.3f), every self-stiffness '
      'restoring' % (demo['pairs_evaluated'], demo['max_ratio']))
# the matrices: numpy reads them as they are
import numpy as np
K = np.load(d + '/tee.npy')
n = K.shape[0]
check(K.shape == (n, n, 4) and K.dtype == np.dtype('<f8'), 'matrices: shape %s' % (K.shape,))
check(n == e['elements'], 'matrices: %d elements, as the check' % n)
R = K[:, :, 2]
diag = np.diag(R)
check(np.all(diag < 0), 'matrices: every self-stiffness negative')
check(np.isclose(diag.max(), e['self_stiffness_max_pa_per_m'], rtol=1e-9, atol=0) and
      np.isclose(diag.min(), e['self_stiffness_min_pa_per_m'], rtol=1e-9, atol=0),
      'matrices: diagonal range as report.json')
check(np.all(np.isfinite(K)), 'matrices: finite')
# element areas and centroids from mesh.obj, in the same order
V, T = [], []
for line in open(d + '/tee.out/mesh.obj'):
    p = line.split()
    if p and p[0] == 'v':
        V.append([float(x) for x in p[1:4]])
    elif p and p[0] == 'f':
        T.append([int(x.split('/')[0]) - 1 for x in p[1:4]])
V, T = np.array(V), np.array(T)
check(len(T) == n, 'matrices: mesh.obj has the same elements')
if len(T) == n:
    P = V[T]
    A = 0.5 * np.linalg.norm(np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]), axis=1)
    C = P.mean(axis=1)
    D = np.linalg.norm(C[:, None, :] - C[None, :, :], axis=2)
    # centroid tractions are reciprocal only where the field varies little
    # over an element: 3 km apart; pairs that interact at all
    far = D > 3000
    W = R * A[:, None]
    rel = np.abs(W - W.T)[far] / np.maximum(np.abs(W) + np.abs(W.T), 1e-30)[far]
    big = (np.abs(W) + np.abs(W.T))[far] > 1e-4 * np.abs(W).max()
    med, p90 = np.median(rel[big]), np.percentile(rel[big], 90)
    check(big.sum() > 1000 and med < 0.02 and p90 < 0.05,
          'matrices: reciprocal 3 km apart (relative asymmetry median %.4f, 90%% %.4f over %d '
          'pairs)' % (med, p90, big.sum()))
sys.exit(fail)
PY
[ "$fail" = 0 ] && rm -rf "$tmp"
exit $fail
