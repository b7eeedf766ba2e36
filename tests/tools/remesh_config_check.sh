#!/bin/bash
# `faultmesh remesh --config FILE`: a project's settings in one file.
# Top-level keys are the options (the same run as with the options, byte
# for byte; options beside --config override it; paths are taken from the
# file's folder); [[fault]] sections change size, top, join, exclusion,
# rake and slip rate by name pattern, and the meshes still conform where a
# fine fault meets a coarse one; every mistake in the file is named with
# its line, exit 2.
# usage: remesh_config_check.sh FAULTMESH CHECK_CONNECT PYTHON TMPDIR
set -u
exe=$1 check=$2 py=$3 tmp=$4
rm -rf "$tmp" && mkdir -p "$tmp/proj"
. "$(dirname "$0")/cli_lib.sh"
expect_rc 0 "synth" "$exe" synth -o "$tmp/proj/syn"

# 1. Top-level settings are the options.
cat >"$tmp/proj/a.toml" <<'TOML'
# settings of a project
output = "out-a"          # taken from this file's folder
inputs = ["syn"]
size = 2_000
top = "extend"
top_extend = 400
msh_tags = "seissol"
keep_crossings = true
connect = true
report_html = false
jobs = 1
quiet = true
TOML
expect_rc 0 "remesh --config" "$exe" remesh --config "$tmp/proj/a.toml"
[ -f "$tmp/proj/out-a/mesh.vtu" ] && ok || bad "output not taken from the file's folder"
[ ! -e "$tmp/proj/out-a/report.html" ] && ok || bad "report_html = false wrote report.html"
expect_rc 0 "the same by options" "$exe" remesh --size 2000 --top extend 400 --msh-tags seissol \
    --keep-crossings --no-report-html -j 1 --quiet -o "$tmp/b" "$tmp/proj/syn"
for f in mesh.vtu mesh.msh mesh.exo mesh.rsqsim; do
    cmp -s "$tmp/proj/out-a/$f" "$tmp/b/$f" && ok || bad "$f differs between --config and options"
done
expect_rc 0 "options beside --config override it" "$exe" remesh --size 3000 --config "$tmp/proj/a.toml" -o "$tmp/c"
[ "$("$py" -c "import json,sys; print(json.load(open(sys.argv[1]))['options']['size_m'])" "$tmp/c/report.json")" = 3000 ] &&
    ok || bad "--size beside --config not applied"

# 2. Per-fault settings.
cat >"$tmp/proj/f.toml" <<'TOML'
output = "out-f"
inputs = "syn"
size = 2000
[[fault]]
match = "*Blind_fault*"
exclude = true
[[fault]]
match = ["SYNT-MAIN-SS-*", "no-such-fault"]
size = 1000
rake = 90
slip_rate = 3.5
[[fault]]
match = "*Overshooting*"
connect = false
TOML
expect_rc 0 "per-fault settings" "$exe" remesh --quiet --config "$tmp/proj/f.toml"
"$py" - "$tmp/proj/out-f" <<'PY' || fail=$((fail + 1))
import json, sys
import meshio
import numpy as np
out = sys.argv[1]
r = json.load(open(out + "/report.json"))
bad = []
st = {f["name"]: f for f in r["faults"]}
blind = [n for n in st if "Blind_fault" in n][0]
main = [n for n in st if n.startswith("SYNT-MAIN-SS-")][0]
over = [n for n in st if "Overshooting" in n][0]
if st[blind]["status"] != "excluded" or "f.toml:4" not in st[blind].get("error", ""):
    bad.append("excluded fault: %s" % st[blind])
m = meshio.read(out + "/mesh.vtu")
tri = m.cells_dict["triangle"]
fid = m.cell_data_dict["fault_id"]["triangle"] - 1
ok_names = [f["name"] for f in r["faults"] if f["status"] == "ok"]
if blind in ok_names or len(set(fid.tolist())) != len(ok_names):
    bad.append("excluded fault meshed")
def median_edge(k):
    t = tri[fid == k]
    e = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    return float(np.median(np.linalg.norm(m.points[e[:, 0]] - m.points[e[:, 1]], axis=1)))
for k, n in enumerate(ok_names):
    want = 1000 if n == main else 2000
    h = median_edge(k)
    if not 0.8 * want < h < 1.25 * want:
        bad.append("%s: median edge %.0f m, size %d asked" % (n, h, want))
rake = m.cell_data_dict["rake"]["triangle"]
rate = m.cell_data_dict["slip_rate"]["triangle"]
k = ok_names.index(main)
if not np.allclose(rake[fid == k], 90) or not np.allclose(rate[fid == k], 3.5e-3 / (365.25 * 86400)):
    bad.append("rake/slip rate of the [[fault]] section not written")
if r["simulator"]["rake_from_settings"] != 1:
    bad.append("rake_from_settings %s" % r["simulator"]["rake_from_settings"])
js = r["connect"]["junctions"]
jm = [j for j in js if main in j["faults"] and over not in j["faults"]]
jo = [j for j in js if over in j["faults"]]
if not jm or any(j["type"] == "unjoined" for j in jm):
    bad.append("the fine fault's junctions: %s" % jm)
if not jo or any(j["type"] != "unjoined" or "set not to join" not in j["reason"] for j in jo):
    bad.append("connect = false fault joined: %s" % jo)
for b in bad:
    print("FAIL:", b)
print("per-fault settings:", "ok" if not bad else "FAILED")
sys.exit(1 if bad else 0)
PY
[ $? = 0 ] && ok
# where a 1 km fault meets a 2 km one, the meshes still conform
"$check" --criteria "$tmp/proj/out-f/mesh.obj" >"$tmp/cc.out" 2>&1 && ok ||
    bad "check_connect --criteria on mixed sizes: $(tail -5 "$tmp/cc.out")"

# The example in the repository is a valid settings file (its inputs
# replaced by the command line's).
expect_rc 0 "examples/cfm.toml" "$exe" remesh --quiet --config "$(dirname "$0")/../../examples/cfm.toml" \
    -o "$tmp/ex" "$tmp/proj/syn"

# 3. Mistakes, each named with its file and line.
try() { # line-expected message-part file-text
    printf '%b' "$3" >"$tmp/bad.toml"
    expect_rc 2 "settings error: $2" "$exe" remesh --config "$tmp/bad.toml" -o "$tmp/x" "$tmp/proj/syn"
    grep -q "bad.toml:$1: .*$2" "$tmp/err" && ok || bad "no 'bad.toml:$1: ...$2' in: $(cat "$tmp/err")"
}
try 2 "unknown setting 'sise'" 'size = 1000\nsise = 3\n'
try 1 "bad value for 'size'" 'size = "big"\n'
try 3 "without match" 'size = 1000\n\n[[fault]]\nsize = 500\n'
try 2 "unknown key 'sizes'" '[[fault]]\nsizes = 3\nmatch = "x"\n'
try 1 "not closed" 'crs = "EPSG:26711\n'
try 1 "top_extend" 'top = "extend"\n'
try 1 "the only section" '[fault]\n'
try 2 "given twice" 'size = 1\nsize = 2\n'
try 3 "exclude takes true or false" '[[fault]]\nmatch = "x"\nexclude = 1\n'
expect_rc 2 "missing settings file" "$exe" remesh --config "$tmp/none.toml" -o "$tmp/x" "$tmp/proj/syn"
grep -q "none.toml" "$tmp/err" && ok || bad "missing file not named"

echo "remesh config: $pass passed, $fail failed"
[ "$fail" = 0 ] && rm -rf "$tmp"
[ "$fail" = 0 ]
