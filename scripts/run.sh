#!/usr/bin/env bash
# One entry point for a fresh Debian machine:
#   scripts/run.sh studies   install dependencies, build, run the default studies into reports/,
#                            then the benchmarks and their performance table (scripts/benchmarks.sh)
#   scripts/run.sh tests     install dependencies, build, run the test suite (CTest), then
#                            README's commands (among them the bouncing study verified against
#                            reports/) and the out-of-tree plugin walkthrough (scripts/plugin-example.sh)
#   scripts/run.sh sanitize  the test suite built with AddressSanitizer + UBSan (build-asan/)
#   scripts/run.sh sanitize-build  that build alone, no tests (CI compiles it beside the tests)
# Environment: BUILD_DIR (default build), JOBS (default: number of cores).
set -euo pipefail
cd "$(dirname "$0")/.."
what="${1:-}"
case "$what" in
  # studies builds only what it runs: the study driver and the benchmarks (no tests, no plugins),
  # as a unity build like the tests' (CMakeLists.txt: NSBENCH_UNITY_BUILD; the same numbers).
  studies) build="${BUILD_DIR:-build}"; config=(-DCMAKE_BUILD_TYPE=Release -DNSBENCH_BENCHMARKS=ON -DNSBENCH_UNITY_BUILD=ON)
           targets=(--target nsbench-study nsbench-benchmarks) ;;
  # tests builds everything: README's commands (run after CTest) call the benchmarks too.
  # The test binary is a unity build here (NSBENCH_UNITY_BUILD: CMakeLists.txt says why).
  tests) build="${BUILD_DIR:-build}"; config=(-DCMAKE_BUILD_TYPE=Release -DNSBENCH_BENCHMARKS=ON -DNSBENCH_UNITY_BUILD=ON); targets=() ;;
  # -O1 -g1: a third of -O2 -g's compile time under the sanitizers (measured on
  # integrators/moreau_jean.cpp: 11.7 s against 43.3 s), line numbers kept for their reports.
  # The Python module is left out: python3 itself is not built with ASan, so loading an
  # instrumented extension into it needs the ASan runtime preloaded (LD_PRELOAD) and reports
  # CPython's own allocations; its C++ side is the same core the sanitized tests cover.
  sanitize|sanitize-build) build="${BUILD_DIR:-build-asan}"
            config=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
                    -DNSBENCH_SANITIZE=ON -DNSBENCH_BENCHMARKS=OFF -DNSBENCH_PYTHON=OFF -DNSBENCH_UNITY_BUILD=ON); targets=() ;;
  *) echo "usage: scripts/run.sh studies|tests|sanitize|sanitize-build" >&2; exit 2 ;;
esac
jobs="${JOBS:-$(nproc)}"
# Single-threaded BLAS for the cost tables (Siconos' dense algebra calls OpenBLAS).
export OPENBLAS_NUM_THREADS=1

# The studies need no test-only packages (a VTK reader, LaTeX).
if [ "$what" = studies ]; then bash scripts/install-deps.sh; else bash scripts/install-deps.sh tests; fi
cmake -S . -B "$build" "${config[@]}"
cmake --build "$build" -j "$jobs" "${targets[@]}"
if [ "$what" = sanitize-build ]; then exit 0; fi

if [ "$what" != studies ]; then
  # The Slurm round trip (label slurm) runs in the tests stage only: it tests the job script
  # and the daemons, which the sanitizers do not look into (the shard code's own tests run here too).
  skip=()
  if [ "$what" = sanitize ]; then skip=(-LE slurm); fi
  ctest --test-dir "$build" --output-on-failure -j "$jobs" "${skip[@]}"
  # Then README's commands, among them the check that the committed reports reproduce
  # (`nsbench-study bouncing --verify reports`), and the plugin walkthrough. The sanitizer
  # build's tests already load the example plugin (tests/support/example_plugin.cpp).
  if [ "$what" = tests ]; then BUILD_DIR="$build" bash scripts/plugin-example.sh; fi
else
  # From scratch into reports.new, swapped in only when every study and figure succeeded.
  rm -rf reports.new
  "$build"/studies/nsbench-study all --out reports.new
  "$build"/studies/nsbench-study run studies/examples/bouncing_quick.toml --out reports.new/bouncing_quick
  /usr/bin/python3 scripts/figures.py reports.new  # Debian python: matplotlib from python3-matplotlib
  /usr/bin/python3 scripts/figures.py reports.new/bouncing_quick
  BUILD_DIR="$build" bash scripts/benchmarks.sh reports.new
  rm -rf reports
  mv reports.new reports
fi
