#!/usr/bin/env bash
# The gain of the NSBENCH_NATIVE build option (CMakeLists.txt: -march=native -ffp-contract=fast)
# on the element-force kernels and the explicit steps: the hex8 bar (nsbench-bench-bar3d) and
# the 2D block (nsbench-bench-block) built twice, portable (BUILD_DIR, default build) and native
# (NATIVE_BUILD_DIR, default build-native, configured here with the peers and Python off), run
# one after the other in three alternating rounds on one thread, each row the least time over
# all its repetitions. Prints a Markdown table: benchmark, portable and native time per step,
# gain = portable / native. Run on a quiet machine; docs/measurements.md keeps its numbers.
#   bash scripts/native-gain.sh
set -euo pipefail
cd "$(dirname "$0")/.."
portable="${BUILD_DIR:-build}"
native="${NATIVE_BUILD_DIR:-build-native}"
jobs="${JOBS:-$(nproc)}"
targets=(--target nsbench-bench-bar3d nsbench-bench-block)
cmake -S . -B "$native" -DCMAKE_BUILD_TYPE=Release -DNSBENCH_NATIVE=ON -DNSBENCH_BENCHMARKS=ON \
      -DNSBENCH_PYTHON=OFF -DNSBENCH_SICONOS=OFF -DNSBENCH_ENGINES=OFF > /dev/null
cmake --build "$native" -j "$jobs" "${targets[@]}" > /dev/null
cmake --build "$portable" -j "$jobs" "${targets[@]}" > /dev/null
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
for round in 1 2 3; do
  for build in portable native; do
    dir="$portable"; [ "$build" = native ] && dir="$native"
    for bench in bar3d block; do
      NSBENCH_THREADS=1 "$dir/studies/nsbench-bench-$bench" --benchmark_filter='internal-force|cd-lagrange/' \
        --benchmark_repetitions=3 --benchmark_min_time=0.1 --benchmark_out_format=json \
        --benchmark_out="$out/$build-$bench-$round.json" > /dev/null
    done
  done
done
/usr/bin/python3 - "$out" <<'EOF'
import glob, json, sys
best = {}
for path in glob.glob(sys.argv[1] + "/*.json"):
    build = path.rsplit("/", 1)[1].split("-")[0]
    for b in json.load(open(path))["benchmarks"]:
        if b.get("run_type") == "iteration":
            key = (b["run_name"], build)
            us = b["real_time"] * {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}[b["time_unit"]]
            best[key] = min(best.get(key, float("inf")), us)
print("| benchmark (1 thread) | portable [us] | native [us] | gain |")
print("| --- | --- | --- | --- |")
for name in sorted({n for n, _ in best}):
    p, n = best[(name, "portable")], best[(name, "native")]
    print(f"| {name} | {p:.4g} | {n:.4g} | {p / n:.2f} |")
EOF
