#!/usr/bin/env bash
# Docs are tests: every command line README.md, the docs it links and examples/plugin/README.md show, extracted
# from them by scripts/doc-commands.py and run as written (those marked smoke in the doc at
# --help level), in a scratch directory that looks like a checkout with BUILD_DIR (default
# build, already built) as build/ and HOME inside it (the walkthrough installs nsbench into
# $HOME/nsbench). Then checks what the plugin walkthrough produced: the plugin's rows in
# the tables, its stamp, its `nsbench check` verdict. Also compiles every installed header
# on its own.
set -euo pipefail
cd "$(dirname "$0")/.."
repo="$(pwd)"
build="$(cd "${BUILD_DIR:-build}" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# A checkout-like sandbox: the sources read-only by symlink, reports/ a copy (written to).
sandbox="$work/checkout"
mkdir -p "$sandbox"
for d in scripts studies examples docs; do ln -s "$repo/$d" "$sandbox/$d"; done
ln -s "$build" "$sandbox/build"
cp -r "$repo/reports" "$sandbox/reports"
export HOME="$work/home"
mkdir -p "$HOME"

run_doc() {  # FILE DIR [--smoke]: the file's commands, run in DIR
  local file="$1" dir="$2" mode="${3:-}" cmds
  cmds="$(/usr/bin/python3 "$repo/scripts/doc-commands.py" "$repo/$file" $mode)"
  while IFS= read -r cmd; do
    [ -n "$cmd" ] || continue
    echo "+ ($file) $cmd" >&2
    (cd "$dir" && bash -euo pipefail -c "$cmd" > "$work/last.log" 2>&1) || {
      cat "$work/last.log" >&2; echo "$file: this documented command failed: $cmd" >&2; exit 1; }
  done <<< "$cmds"
}

SECONDS=0
# README, then the docs it links, in README's order (the walkthrough of extending.md installs
# nsbench into $HOME/nsbench, which the example's README below uses).
docs=(README.md docs/running.md docs/studies.md docs/cluster.md docs/study_files.md docs/extending.md docs/python.md
      docs/measurements.md)
for doc in "${docs[@]}"; do run_doc "$doc" "$sandbox"; done
for doc in "${docs[@]}"; do run_doc "$doc" "$sandbox" --smoke; done
prefix="$HOME/nsbench"

# The example's own README, in a copy of the example.
cp -r examples/plugin "$work/example"
run_doc examples/plugin/README.md "$work/example"

# The plugins of the last release's documented API (tests/compat/0.1.0), built out of tree as
# they were: they compile, each override 0.2.0 replaced warned about with its replacement, and run.
compat="$work/compat"
cp -r tests/compat/0.1.0 "$compat"
cmake -S "$compat" -B "$compat/build" -DCMAKE_PREFIX_PATH="$prefix" > "$work/compat.log" 2>&1 &&
  cmake --build "$compat/build" > "$work/compat.log" 2>&1 || {
    cat "$work/compat.log" >&2; echo "the 0.1.0 plugins (tests/compat/0.1.0) no longer compile" >&2; exit 1; }
for replaced in "remove the name() override" "override advance(dt) instead of step(dt)" \
    "the conditionally_stable() override by .explicit_step" "the treats_friction() override by .friction" \
    "include <nsbench/solvers/lcp.hpp> instead of <nsbench/integrators/lcp.hpp>" \
    "override observe(s, impulses, dt, out) instead of observe(s, out)" "move exact_state() and impact_times()"; do
  grep -qF "$replaced" "$work/compat.log" || {
    cat "$work/compat.log" >&2; echo "the 0.1.0 plugins' build does not warn: '$replaced'" >&2; exit 1; }
done
grep -qF "Plugin API: what to change" CHANGELOG.md || { echo "CHANGELOG.md has no 'Plugin API: what to change'" >&2; exit 1; }
nsb="$prefix/bin/nsbench"
"$nsb" --plugin "$compat/build/symplectic_euler.so" check --integrator symplectic-euler > "$work/compat.log" 2>&1 || {
  cat "$work/compat.log" >&2; echo "the 0.1.0 symplectic-euler plugin fails nsbench check" >&2; exit 1; }
"$nsb" --plugin "$compat/build/moreau_midpoint.so" run --problem sliding-mass --integrator moreau-midpoint --dt 1e-3 \
  --t-end 1 --out "$work/compat-friction" > "$work/compat.log" 2>&1 || {
  cat "$work/compat.log" >&2; echo "the 0.1.0 moreau-midpoint plugin (treats_friction) does not run a friction problem" >&2; exit 1; }
"$nsb" --plugin "$compat/build/dropped_ball.so" run --problem dropped-ball --integrator moreau-jean --dt 1e-3 \
  --t-end 2 --out "$work/compat-problem" > "$work/compat.log" 2>&1 &&
  /usr/bin/python3 - "$work/compat-problem/series.csv" <<'EOF' || {
import csv, sys
rows = list(csv.DictReader(line for line in open(sys.argv[1]) if not line.startswith("#")))
worst = max(abs(float(r["q"]) - float(r["q_exact"])) for r in rows)
print(f"dropped-ball: {len(rows)} rows, largest |q - q_exact| {worst:.2e} m")
# The column must be the plugin's exact solution: q_exact = q = h0 at t = 0, and within a tenth
# of h0 = 1 m after (a wrong one is off by about h0; moreau-jean's own error here is 1.7e-2 m).
sys.exit(0 if rows[0]["q"] == rows[0]["q_exact"] and worst < 0.1 else 1)
EOF
  cat "$work/compat.log" >&2; echo "the 0.1.0 dropped-ball plugin (observe, exact_state) does not run with its exact solution" >&2; exit 1; }
echo "compat: the 0.1.0 plugins built with their deprecation warnings, checked and run"

for h in $(cd "$prefix/include" && find nsbench -name '*.hpp' | sort); do
  echo "#include <$h>" | c++ -std=c++20 -fsyntax-only -x c++ - -I"$prefix/include" -I"$prefix/include/nsbench" \
    -I/usr/include/eigen3 || { echo "installed header $h does not compile on its own" >&2; exit 1; }
done
[ -x "$prefix/bin/nsbench-figures" ] || { echo "nsbench-figures is not installed" >&2; exit 1; }

# --- what the walkthrough produced ---
grep -q '"file": "symplectic_euler.so"' "$sandbox/run/summary.json"
# Built as a user builds it (no CMAKE_BUILD_TYPE): optimised, and stamped so.
grep -q '"optimized": true' "$sandbox/run/summary.json" || { echo "the walkthrough's plugin was not built optimised" >&2; exit 1; }
for t in bouncing_plugin_orders bouncing_plugin_work_precision; do
  for r in "$sandbox/my-reports" "$work/example/reports"; do
    grep -q '^"bouncing mass, e = 0.9",symplectic-euler,' "$r/$t.csv" || { echo "no symplectic-euler row in $r/$t.csv" >&2; exit 1; }
    grep -q '^# plugins: symplectic_euler.so (fnv1a64:[0-9a-f]*; Release (nsbench_add_plugin.s default: no CMAKE_BUILD_TYPE), optimised, flags .*-O3' \
      "$r/$t.csv" || { echo "$r/$t.csv: no plugin stamp with its optimised build" >&2; exit 1; }
  done
done
# The problem plugin: checked (every property holds, or `nsbench check` exited 1 above) and run.
grep -q '"problem": "bowl"' "$work/example/bowl-run/summary.json" && grep -q '"status": "ok"' "$work/example/bowl-run/summary.json" ||
  { echo "the example's problem plugin (bowl) did not run to its end" >&2; exit 1; }
echo "docs: every command of README.md, ${docs[*]:1} and examples/plugin/README.md ran as written (${SECONDS} s): the plugin" \
  "installed, built out of tree, checked (nsbench check exits 1 on a failed property), run and studied; the problem plugin checked and run"
