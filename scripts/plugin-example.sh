#!/usr/bin/env bash
# The README's "Add your integrator without forking", as CI runs it: install nsbench from
# BUILD_DIR (default build, already built) into a temporary prefix, build examples/plugin
# out of tree against it, list, run and study with the plugin, and check its rows are in
# the tables. Also compiles every installed header on its own.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD_DIR:-build}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"

cmake --install "$build" --prefix "$prefix" > /dev/null
for h in $(cd "$prefix/include" && find nsbench -name '*.hpp' | sort); do
  echo "#include <$h>" | c++ -std=c++20 -fsyntax-only -x c++ - -I"$prefix/include" -I"$prefix/include/nsbench" \
    -I/usr/include/eigen3 || { echo "installed header $h does not compile on its own" >&2; exit 1; }
done

# --- the walkthrough (README.md) ---
cp -r examples/plugin "$work/my-plugin"
cmake -S "$work/my-plugin" -B "$work/my-plugin/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$work/my-plugin/build" > /dev/null
plugin="$work/my-plugin/build/symplectic_euler.so"
# Captured, not piped: `grep -q` stops reading at its match, and under pipefail the
# writer's SIGPIPE (exit 141) would fail the script on a correct listing.
listing="$("$prefix/bin/nsbench" --plugin "$plugin" list)"
grep -q '^  symplectic-euler ' <<< "$listing" || { echo "symplectic-euler not in nsbench list" >&2; exit 1; }
"$prefix/bin/nsbench" --plugin "$plugin" run --problem bouncing-mass --integrator symplectic-euler \
  --dt 1e-3 --t-end 2 --out "$work/run"
NSBENCH_PLUGINS="$plugin" "$prefix/bin/nsbench-study" bouncing --out "$work/reports"
# --- checks ---
grep -q '"file": "symplectic_euler.so"' "$work/run/summary.json"
for t in bouncing_mass bouncing_mass_orders; do
  grep -q '^symplectic-euler,' "$work/reports/$t.csv" || { echo "no symplectic-euler row in $t.csv" >&2; exit 1; }
  grep -q '^# plugins: symplectic_euler.so (fnv1a64:' "$work/reports/$t.csv" || { echo "$t.csv: no plugin stamp" >&2; exit 1; }
done
echo "plugin example: installed, built out of tree, listed, run and studied"
