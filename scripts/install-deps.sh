#!/usr/bin/env bash
# Installs nsbench's build dependencies from Debian packages (Debian 12 "bookworm").
#   scripts/install-deps.sh          what the build and the studies need
#   scripts/install-deps.sh tests    also what only the tests use (a VTK reader, LaTeX, Slurm)
set -euo pipefail
packages=(
  build-essential cmake git pkg-config
  libeigen3-dev libsundials-dev libsuitesparse-dev
  catch2 libbenchmark-dev libfmt-dev libcli11-dev nlohmann-json3-dev
  libtomlplusplus-dev  # study files (nsbench-study run FILE.toml)
  libsleef-dev  # elementary functions with the same bits on every machine (core/deterministic_math.hpp)
  python3 python3-matplotlib
  # The Python module (python/; CMake option NSBENCH_PYTHON): pybind11 to build it, numpy and
  # scipy (its matrices are scipy.sparse) to use it.
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-scipy
  # Siconos kernel: the optional peers (siconos-* integrators, CMake option NSBENCH_SICONOS).
  libsiconos-kernel-dev
  # BLAS: nsbench's own numerics call none (moreau_jean.hpp says why); the Siconos peers do.
  # The serial OpenBLAS takes over the libblas.so.3 alternative: fast, and no thread pool.
  libopenblas0-serial
  # Physics engines: the optional peers mujoco, bullet, ode (CMake option NSBENCH_ENGINES;
  # each built where its package is found).
  libmujoco-dev libbullet-dev libode-dev
)
case "${1:-}" in
  "") ;;
  tests) packages+=(
           python3-meshio  # tests/scripts/fields_test.py reads nsbench run --fields back (VTK files)
           python3-pytest  # tests/python: the Python module
           # tests/scripts/latex_test.py compiles the tables: pdflatex, booktabs, longtable, siunitx
           # (135 MB; without them the compile test is skipped, the text test still runs).
           texlive-latex-base texlive-latex-recommended texlive-science
           # tests/scripts/slurm_test.sh runs README's job array on a single-node Slurm it starts
           # (own configuration and key in a scratch directory; the packages' services unused).
           slurmctld slurmd slurm-client munge
         ) ;;
  *) echo "usage: scripts/install-deps.sh [tests]" >&2; exit 2 ;;
esac
missing=()
for p in "${packages[@]}"; do
  [ "$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null)" = "install ok installed" ] || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
