#!/usr/bin/env bash
# The benchmarks behind the `performance` report: every nsbench-bench-* binary of BUILD_DIR
# (default build, already built) with JSON output into OUT/benchmarks (default
# reports/benchmarks), the block and the hex8 bar (bar3d) also on one thread for the
# speed-up and the one-thread kernel against the peak rate, the moving-contact steps (rocking,
# sliding) on one thread, then
# `nsbench-study performance` writes OUT/performance.{csv,md,tex}, and scripts/python_bench.py
# OUT/python_overhead.md where the Python module is built. Run on a quiet machine:
# the table reads the least of the repetitions (3 of at least 0.1 s each). About 2 minutes on
# 2 quiet cores (measured at b9214af: 102 s wall; the step benchmarks build their set-up once,
# studies/benchmarks/limit.hpp).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD_DIR:-build}"
out="${1:-reports}"
mkdir -p "$out/benchmarks"
# The build's revision goes into each JSON file's context (scripts/report_revisions.py reads it).
version="$("$build/studies/nsbench-study" --version)"
revision="$(sed -n 's/.*(revision \([^,]*\),.*/\1/p' <<< "$version")"
flags=(--benchmark_repetitions=3 --benchmark_report_aggregates_only=true --benchmark_min_time=0.1
       --benchmark_out_format=json "--benchmark_context=git_revision=$revision")
run() {  # run NAME THREADS
  local name="$1" threads="$2"
  echo "benchmarks: nsbench-bench-$name, $threads thread(s)" >&2
  NSBENCH_THREADS="$threads" "$build/studies/nsbench-bench-$name" "${flags[@]}" \
    --benchmark_out="$out/benchmarks/$name-$threads.json" > /dev/null
}
cores="$(nproc)"
run bar "$cores"
run block 1
[ "$cores" -eq 1 ] || run block "$cores"
run bar3d 1
[ "$cores" -eq 1 ] || run bar3d "$cores"
run implicit "$cores"
# Moving contacts against the same step with constant rows: small problems, one thread.
run rocking 1
run sliding 1
# The memory bound: one run per length is enough (the peak RSS does not vary), 20 s at 1e6 steps.
echo "benchmarks: nsbench-bench-memory" >&2
"$build/studies/nsbench-bench-memory" --benchmark_out_format=json "--benchmark_context=git_revision=$revision" --benchmark_out="$out/benchmarks/memory-1.json" > /dev/null
# The Python module's overhead (scripts/python_bench.py), where the module is built.
if [ -d "$build/python/nsbench" ]; then
  echo "benchmarks: scripts/python_bench.py" >&2
  { echo "# Python module overhead"; echo; echo "scripts/python_bench.py: nsbench.run against the command line, and the per-step"
    echo "cost of an integrator written in Python (least of 3 runs each)."; echo
    PYTHONPATH="$build/python" /usr/bin/python3 scripts/python_bench.py --build "$build"
    echo; echo "<sub>$version</sub>"; } > "$out/python_overhead.md"
fi
files=()
for f in "$out"/benchmarks/*.json; do files+=("$f"); done
"$build/studies/nsbench-study" performance "${files[@]}" --out "$out"
