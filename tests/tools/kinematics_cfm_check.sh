#!/bin/bash
# Slip rate and rake of every element from NSHM23 (issue 19, item 1): the
# whole CFM 500 m set at 1 km with the NSHM23 fault sections and geologic
# deformation model must give the published rates and rakes to the
# well-known faults, a non-zero rate to at least 75 % of the meshed area,
# and list every fault left on the fallback; mesh.rsqsim carries each
# element's own values.
# usage: kinematics_cfm_check.sh FAULTMESH PYTHON TMPDIR CFMDIR KINEMATICSDIR
# exit 77 without the CFM or the kinematics data.
set -u
exe=$1 py=$2 tmp=$3 cfm=$4 kin=$5
fsd=$kin/nshm23/NSHM23_FSD_v3.geojson dm=$kin/nshm23/NSHM23_GeologicDeformationModel.geojson
[ -d "$cfm" ] && [ -f "$fsd" ] && [ -f "$dm" ] || { echo "skipped: no CFM or no NSHM23 data"; exit 77; }
rm -rf "$tmp" && mkdir -p "$tmp"
"$exe" remesh --size 1000 --kinematics "$fsd" --kinematics "$dm" -o "$tmp/out" "$cfm" \
    >"$tmp/stdout" 2>"$tmp/stderr" || { echo "FAIL: remesh exit $?"; tail "$tmp/stderr"; exit 1; }
grep "kinematics" "$tmp/stderr"
"$py" - "$tmp/out" <<'PY'
import json, sys
import numpy as np
out = sys.argv[1]
r = json.load(open(out + "/report.json"))
fail = 0
def check(ok, what):
    global fail
    print(("ok    " if ok else "FAIL  ") + what)
    fail += not ok
k = r["simulator"]["kinematics"]
faults = {f["name"]: f for f in r["faults"] if f["status"] == "ok"}
# the area share at a non-zero rate, from the per-element values
rs = np.loadtxt(out + "/mesh.rsqsim", usecols=range(11))
p = rs[:, :9].reshape(-1, 3, 3)
area = 0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)
share = area[rs[:, 10] > 0].sum() / area.sum()
check(share >= 0.75, "%.1f %% of the meshed area at a non-zero rate (>= 75 %%)" % (100 * share))
check(k["matched_area_share"] >= 0.75, "%.1f %% of the area took a section" % (100 * k["matched_area_share"]))
on_fallback = sorted(n for n, f in faults.items()
                     if f["attributes"]["kinematics"]["matched_area_share"] == 0)
check(sorted(k["faults_on_fallback"]) == on_fallback and len(on_fallback) > 0,
      "%d faults on the fallback, each listed" % len(on_fallback))
# (CFM fault, its main NSHM23 section, rate mm/yr, rake): NSHM23 PrefRate
known = [("SAFS-SAFZ-COAV-Southern_San_Andreas_fault-CFM4_500m", "San Andreas (Coachella)", 20, 180),
         ("GRFS-GRFZ-WEST-Garlock_fault-CFM5_500m", "Garlock (west)", 7.6, 0),
         ("WTRA-ORFZ-SFNV-Northridge_Frew_fault-CFM2_500m", "Northridge", 1.5, 90),
         ("WTRA-PHTS-LABS-Puente_Hills_Thrust_fault-CFM1_500m", "Puente Hills (Los Angeles)", 1.2, 90),
         ("OCBA-NIRC-DANA-Newport_Inglewood_fault-CFM5_500m", "Newport - Inglewood (offshore)", 1.0, 180),
         ("PNRA-SJFZ-ANZA-Clark_fault_north-CFM4_500m", "San Jacinto (Anza)", 14, 180),
         ("PNRA-ELSZ-WHIT-Whittier_fault-CFM4_500m", "Whittier", 2.5, 150)]
for name, sec, rate, rake in known:
    f = faults.get(name)
    if not f:
        check(False, "%s meshed" % name)
        continue
    ks = f["attributes"]["kinematics"]["sections"]
    main = max(ks, key=lambda s: s["area_share"]) if ks else None
    ok = main and main["name"] == sec and main["rate_mm_yr"] == rate and main["rake_deg"] == rake \
        and main["area_share"] >= 0.5
    check(ok, "%s: %s, %g mm/yr, rake %g (%s)" % (name, sec, rate, rake,
          main and (main["name"], main["rate_mm_yr"], main["rake_deg"], round(main["area_share"], 2))))
# each element's own rate: the Coachella fault's file rates include 20 mm/yr
yr = 365.25 * 86400
sect = np.loadtxt(out + "/mesh.rsqsim", usecols=[11], dtype=int)
names = [f["name"] for f in r["faults"] if f["status"] == "ok"]
i = names.index(known[0][0]) + 1
mm = rs[sect == i, 10] * yr * 1000
check(abs(np.median(mm) - 20) < 1e-6, "mesh.rsqsim: the Coachella fault's elements at 20 mm/yr "
      "(median %.4f)" % np.median(mm))
sys.exit(1 if fail else 0)
PY
