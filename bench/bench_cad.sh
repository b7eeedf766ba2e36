#!/bin/sh
# The CAD model of the whole CFM: how large model.igs is and how long Gmsh
# (OpenCASCADE) takes to import it with every face, the issue's targets
# being <= 30 MB and <= 20 s.
#
#   bench/bench_cad.sh [-b BUILD_DIR] [H]
#
# Writes only model.igs (--formats igs) of the 500 m set at H (default
# 1000 m), connected, top cut; then imports it with the system Python's
# gmsh module (Debian python3-gmsh) and prints size, entity counts by
# IGES type, faces imported and the import's wall time. Skips (exit 0)
# when ../shared/cfm or gmsh is absent.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
build="$here/build"
while [ $# -gt 0 ]; do
    case "$1" in
    -b) build="$2"; shift 2 ;;
    *) break ;;
    esac
done
H=${1:-1000}
# shellcheck source=bench/lib.sh
. "$here/bench/lib.sh"
bench_data bench_cad
py=/usr/bin/python3
"$py" -c "import gmsh" 2>/dev/null || { echo "bench_cad: no gmsh module, skipped"; exit 0; }
bench_exe bench_cad
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM
echo "machine: $(nproc) cores, $(uname -m), load $(cut -d' ' -f1-3 /proc/loadavg)"
"$exe" remesh --quiet --size "$H" --formats igs -o "$tmp/out" "$data" >/dev/null || true
"$py" - "$tmp/out/model.igs" <<'PY'
import collections, os, sys, time
import gmsh
path = sys.argv[1]
count = collections.Counter()
with open(path) as f:
    d = [l for l in f if len(l) > 72 and l[72] == "D"]
for i in range(0, len(d), 2):
    count[int(d[i][:8])] += 1
print("model.igs: %.1f MB; entities %s" % (os.path.getsize(path) / 1e6,
      ", ".join("%d x %d" % (n, t) for t, n in sorted(count.items()))))
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
t = time.time()
gmsh.open(path)
faces = len(gmsh.model.getEntities(2))
print("Gmsh %s imports it in %.1f s: %d faces of %d" % (gmsh.__version__, time.time() - t,
      faces, count[144]))
gmsh.finalize()
PY
