#!/bin/bash
# Installs what faultmesh needs to build and test, from Debian's packages.
# Run as root (or through sudo) on Debian 12 or later.
set -euo pipefail
packages=(
  build-essential cmake      # C17 compiler, CMake
  libsuitesparse-dev         # CHOLMOD: sparse least squares of the surface fit
  libopenblas0-pthread       # thread-safe optimised BLAS for CHOLMOD's supernodal factor
                             # (run on one thread per fault, see src/fit/solve.c)
  liblapacke-dev             # LAPACKE: banded least squares of the trimming curves
  libproj-dev proj-data      # PROJ: EQSim geometry to WGS 84 lat/lon; proj-data holds the
                             # NAD27 -> WGS 84 grids PROJ picks (network access stays off)
  python3                    # Debian's interpreter for the independent test checks
  python3-meshio python3-gmsh  # real readers of our outputs (VTU, MSH, IGES) in the tests
  libexodusii-dev libnetcdf-dev  # Exodus II writer (mesh.exo), on netCDF
  python3-netcdf4            # meshio's Exodus II reader in the tests
  python3-pyproj             # independent lat/lon conversion in the EQSim test (check_sim.py)
  libcairo2-dev              # cairo: the pictures of report.html, drawn to PNG
  zlib1g-dev                 # zlib: deflates the triangles report.html draws itself
  chromium                   # headless browser: report.html opened, its script run and
                             # checked, a screenshot taken (report_browser_*); without it
                             # those tests skip
  libjson-c-dev              # json-c: the deformation model's GeoJSON fault sections
  pkg-config                 # how CMake finds cairo and fontconfig (only recommended by
                             # the -dev packages, which --no-install-recommends skips)
  python3-scipy              # k-d trees of the CAD model check (check_cad.py); without it
                             # cad_demo and cfm_cad_500m_1000 skip
  python3-numpy              # the Python package's arrays (python/faultmesh; install_python)
  doxygen                    # the API documentation (cmake --build build --target doc);
                             # without it the target is left out
)
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO=sudo; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null
echo "faultmesh: build dependencies installed"
