#!/bin/bash
# Exodus II, the MSH tag conventions and the CRS in every output, checked
# by tests/tools/check_fe_formats.py (meshio, netCDF4, Gmsh).
# Usage: fe_formats_check.sh FAULTMESH PYTHON TMPDIR demo
#        fe_formats_check.sh FAULTMESH PYTHON TMPDIR CFM_DIR SIZE
# demo: the synthetic system in every convention, -j 1 / -j 2 byte
# identity, the usage errors, and a checker that fails on a wrong
# convention or a tampered node set. CFM: the set at SIZE, connected, in
# every convention (77 without the data).
set -u
fm=$1 py=$2 tmp=$3 what=$4
tools=$(cd "$(dirname "$0")" && pwd)
"$py" -c "import meshio, netCDF4, gmsh" 2>/dev/null || { echo "skipped: readers missing"; exit 77; }
rm -rf "$tmp"
mkdir -p "$tmp"
fail=0
say() { echo "$*"; }
bad() { echo "FAIL: $*"; fail=1; }

if [ "$what" = demo ]; then
    run() { "$fm" demo --quiet -o "$@" > /dev/null; }
    crs="local metres (synthetic)"
    for c in default tandem seissol pylith; do
        run "$tmp/$c" -j 2 --msh-tags "$c" || bad "demo --msh-tags $c"
        "$py" "$tools/check_fe_formats.py" "$tmp/$c" "$c" --crs "$crs" || bad "check $c"
    done
    # fitted afresh: the runs above may have read their models from the
    # fit cache
    run "$tmp/j1" -j 1 --no-cache || bad "demo -j 1"
    for f in mesh.exo mesh.msh; do
        cmp -s "$tmp/j1/$f" "$tmp/default/$f" || bad "$f differs between -j 1 and -j 2"
    done
    # --crs is what every output records
    run "$tmp/crs" -j 2 --crs EPSG:32611 || bad "demo --crs"
    "$py" "$tools/check_fe_formats.py" "$tmp/crs" default --crs EPSG:32611 || bad "check --crs"
    # --crs-out: every output in the target CRS, each node where pyproj
    # (written apart from faultmesh) puts the input's; z unchanged; the
    # CRS recorded everywhere; EQSim and RSQSim in it too
    "$fm" demo --quiet --size 3000 --crs EPSG:26711 --eqsim-coords utm -o "$tmp/in26711" >/dev/null ||
        bad "demo --crs EPSG:26711"
    "$fm" demo --quiet --size 3000 --crs EPSG:26711 --crs-out EPSG:32611 --eqsim-coords utm \
        -o "$tmp/out32611" >/dev/null || bad "demo --crs-out EPSG:32611"
    "$py" "$tools/check_fe_formats.py" "$tmp/out32611" default --crs EPSG:32611 || bad "check --crs-out"
    "$py" - "$tmp/in26711" "$tmp/out32611" <<'PY' || bad "--crs-out: nodes not where pyproj puts them"
import sys, meshio, numpy as np, pyproj
a = meshio.read(sys.argv[1] + "/mesh.vtu")
b = meshio.read(sys.argv[2] + "/mesh.vtu")
t = pyproj.Transformer.from_crs("EPSG:26711", "EPSG:32611", always_xy=True)
x, y = t.transform(a.points[:, 0], a.points[:, 1])
d = np.hypot(x - b.points[:, 0], y - b.points[:, 1])
moved = np.hypot(a.points[:, 0] - b.points[:, 0], a.points[:, 1] - b.points[:, 1])
print("--crs-out: %d nodes moved %.1f m on average, %.2e m at most from pyproj's" %
      (len(d), moved.mean(), d.max()))
ra = np.loadtxt(sys.argv[1] + "/mesh.rsqsim", usecols=range(9))
rb = np.loadtxt(sys.argv[2] + "/mesh.rsqsim", usecols=range(9))
rx, ry = t.transform(ra[:, 0::3].ravel(), ra[:, 1::3].ravel())
dr = np.hypot(rx - rb[:, 0::3].ravel(), ry - rb[:, 1::3].ravel())
ok = d.max() <= 1e-3 and moved.mean() > 100 and np.array_equal(a.points[:, 2], b.points[:, 2]) \
    and dr.max() <= 1e-3 and np.array_equal(ra[:, 2::3], rb[:, 2::3])
sys.exit(0 if ok else 1)
PY
    grep -q '"crs_out": "EPSG:32611"' "$tmp/out32611/report.json" || bad "report.json lacks crs_out"
    grep -q "CRS: EPSG:32611" "$tmp/out32611/model.igs" || bad "model.igs does not name the target CRS"
    "$fm" demo --quiet --crs EPSG:26711 --crs-out EPSG:999999 -o "$tmp/badcrs" >/dev/null 2>"$tmp/err"
    rc=$?
    [ "$rc" = 1 ] && grep -q "crs-out: PROJ cannot convert" "$tmp/err" && [ ! -e "$tmp/badcrs/mesh.vtu" ] ||
        bad "--crs-out EPSG:999999: exit $rc, $(cat "$tmp/err")"
    # Tandem reads MSH 2.2 only
    "$fm" demo --quiet -o "$tmp/bad" --msh-tags tandem --msh-version 4.1 > /dev/null 2>&1
    [ $? -eq 2 ] || bad "--msh-tags tandem --msh-version 4.1 is a usage error"
    "$fm" demo --quiet -o "$tmp/bad" --msh-tags abaqus > /dev/null 2>&1
    [ $? -eq 2 ] || bad "--msh-tags abaqus is a usage error"
    # the checker can fail: a wrong convention, a junction node set moved
    "$py" "$tools/check_fe_formats.py" "$tmp/tandem" seissol > /dev/null 2>&1 && bad "checker took tandem for seissol"
    cp -r "$tmp/default" "$tmp/tampered"
    "$py" - "$tmp/tampered/mesh.exo" <<'PY' || bad "could not tamper"
import sys, netCDF4
nc = netCDF4.Dataset(sys.argv[1], "a")
names = [k for k in nc.variables if k.startswith("node_ns")]
last = nc.variables["node_ns%d" % len(names)]
v = last[:]
v[0] = nc.variables["connect1"][0][0] if v[0] != nc.variables["connect1"][0][0] else nc.variables["connect2"][0][0]
last[:] = v
nc.close()
PY
    "$py" "$tools/check_fe_formats.py" "$tmp/tampered" default > /dev/null 2>&1 && bad "checker took a tampered junction node set"
    # inputs naming a CRS: the TSurf files written name it, read back
    run "$tmp/named" -j 2 --crs EPSG:26711 || bad "demo --crs EPSG:26711"
    "$fm" remesh --quiet -j 2 -o "$tmp/reread" "$tmp/named"/*.ts > /dev/null || bad "remesh of named TSurf"
    "$py" - "$tmp/reread/report.json" <<'PY' || bad "CRS read from the inputs"
import json, sys
o = json.load(open(sys.argv[1]))["options"]
print("reread crs:", o["crs"], o["crs_source"])
sys.exit(0 if (o["crs"], o["crs_source"]) == ("EPSG:26711", "input") else 1)
PY
else
    cfm=$4 size=$5
    [ -d "$cfm" ] || { echo "skipped: no CFM at $cfm"; exit 77; }
    for c in default tandem seissol pylith; do
        t0=$(date +%s)
        "$fm" remesh --quiet --size "$size" -o "$tmp/$c" --msh-tags "$c" "$cfm" > /dev/null
        rc=$?
        say "remesh --msh-tags $c: exit $rc, $(( $(date +%s) - t0 )) s"
        [ -f "$tmp/$c/mesh.exo" ] || { bad "no mesh.exo ($c)"; continue; }
        "$py" "$tools/check_fe_formats.py" "$tmp/$c" "$c" --crs EPSG:26711 > "$tmp/check_$c.log"
        [ $? -eq 0 ] || bad "check $c"
        grep -v "^  ok   block" "$tmp/check_$c.log"
        # keep the disk use down: the next convention only changes the MSH
        [ "$c" = default ] || rm -rf "$tmp/$c"
    done
fi
[ $fail -eq 0 ] && echo "fe_formats: all passed"
exit $fail
