// Benchmark: the 2D block (problems/block_2d.hpp) on an n x n mesh, n = 64 .. 256.
//
//   BM_BlockInternalForce/n   one F_int evaluation (the element loop: the explicit schemes'
//                             compute-bound kernel)
//   BM_BlockCdLagrangeStep/n  one CD-Lagrange step (F_int plus the vector update)
// Counter time_per_element: time per call divided by the n^2 elements. Threads: as
// NSBENCH_THREADS (default all cores); the one-core kernel figure is NSBENCH_THREADS=1.
// The machine is shared: run with --benchmark_repetitions=5 and read the min rows.
#include <benchmark/benchmark.h>

#include <algorithm>

#include "integrators/cd_lagrange.hpp"
#include "problems/block_2d.hpp"

namespace {

nsb::Block2d make_block(long n) {
  return nsb::Block2d(nsb::Params(nsb::Block2d::parameters_spec(),
                                  {{"nx", std::to_string(n)}, {"ny", std::to_string(n)}, {"H", "1"}}));
}

double min_of(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

void per_element(benchmark::State& state, long elements) {
  state.counters["time_per_element"] = benchmark::Counter(
      static_cast<double>(elements), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// A deformed state (strains ~1e-3, all Gauss points different), so no branch is trivial.
nsb::Vec deformed(const nsb::Block2d& block) {
  nsb::Vec u(block.ndof());
  for (nsb::Index i = 0; i < u.size(); ++i) u[i] = 1e-4 * std::sin(0.37 * static_cast<double>(i));
  return u;
}

void BM_BlockInternalForce(benchmark::State& state) {
  const long n = state.range(0);
  const auto block = make_block(n);
  const nsb::Vec u = deformed(block);
  nsb::Vec f(block.ndof());
  for (auto _ : state) {
    block.internal_force(u, f);
    benchmark::DoNotOptimize(f.data());
    benchmark::ClobberMemory();
  }
  per_element(state, n * n);
}

void BM_BlockCdLagrangeStep(benchmark::State& state) {
  const long n = state.range(0);
  const auto block = make_block(n);
  nsb::CdLagrange integ(nsb::Params(nsb::CdLagrange::parameters_spec()));
  integ.init(block, block.initial_state());
  const double dt = 0.9 * block.stable_step();
  for (auto _ : state) {
    integ.step(dt);
    benchmark::DoNotOptimize(integ.state().v.data());
    benchmark::ClobberMemory();
  }
  per_element(state, n * n);
}

}  // namespace

BENCHMARK(BM_BlockInternalForce)->RangeMultiplier(2)->Range(64, 256)->ComputeStatistics("min", min_of)->UseRealTime();
BENCHMARK(BM_BlockCdLagrangeStep)->RangeMultiplier(2)->Range(64, 256)->ComputeStatistics("min", min_of)->UseRealTime();

BENCHMARK_MAIN();
