// Benchmark: the 2D block (problems/block_2d.hpp, Saint Venant-Kirchhoff) on an n x n mesh,
// n = 64 .. 256, each against its limit (limit.hpp):
//
//   BM_Block/internal-force/n   one F_int evaluation, the explicit schemes' compute-bound
//                               kernel; limit: its floating-point operations at the peak
//                               rate of this build (peak_flops_per_ns, same threads)
//   BM_Block/cd-lagrange/n      one CD-Lagrange step; limit: the bare F_int evaluation above
//                               on the same mesh (the step adds two vector updates and the
//                               contact)
//   BM_Block/cd-lagrange-friction/n  one CD-Lagrange step of the block sliding on the floor
//                               with Coulomb friction (mu 0.5, its bottom row in contact);
//                               limit: the frictionless step of the same sliding block, timed
//                               in the same process (the friction's cost is the ratio)
//
// Flops per element, as block_2d.cpp's add_row_forces writes them (4 Gauss points, 4 nodes):
//   grad U at a point   4 nodes x 4 entries x (mul + add)            32
//   Green-Lagrange E    E00 5, E11 5, E01 7                          17
//   SVK stress S        lambda tr E 2, S00 2, S11 2, S01 1            7
//   P = (I + H) S       4 entries x (2 mul + 2 add)                  16
//   per point 72, x 4 points                                        288
//   nodal forces        4 nodes x 4 points x 2 comps x (2 mul + 2 add) 128, scatter 8
//   per element                                                     424
// Threads: as NSBENCH_THREADS (default all cores); the one-core kernel figure is
// NSBENCH_THREADS=1. The machine may be shared: run with --benchmark_repetitions=5 and read
// the min rows.
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <string>

#include "integrators/cd_lagrange.hpp"
#include "problems/block_2d.hpp"
#include "studies/benchmarks/limit.hpp"

namespace {

using nsb::bench::min_of;

constexpr double kFlopsPerElement = 424.0;

nsb::Block2d make_block(long n, std::map<std::string, std::string> overrides = {}) {
  overrides.insert({{"nx", std::to_string(n)}, {"ny", std::to_string(n)}, {"H", "1"}});
  return nsb::Block2d(nsb::Params(nsb::Block2d::parameters_spec(), overrides));
}

// Resting on the floor (bottom row closed from the first step), sliding along it.
nsb::Block2d sliding_block(long n, const std::string& mu) {
  return make_block(n, {{"height", "0"}, {"tilt", "0"}, {"vy", "0"}, {"vx", "1"}, {"mu", mu}});
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
  const double elements = static_cast<double>(n * n);
  const double limit_ns = kFlopsPerElement * elements / (nsb::bench::peak_flops_per_ns() * nsb::run_threads());
  for (auto _ : state) {
    block.internal_force(u, f);
    benchmark::DoNotOptimize(f.data());
    benchmark::ClobberMemory();
  }
  nsb::bench::report_limit(state, elements, limit_ns, "424 flops per element at the peak multiply-add rate");
}

void BM_BlockCdLagrangeStep(benchmark::State& state) {
  const long n = state.range(0);
  const auto block = make_block(n);
  nsb::CdLagrange integ(nsb::Params(nsb::CdLagrange::parameters_spec()));
  integ.init(block, block.initial_state());
  const double dt = 0.9 * block.stable_step();
  const nsb::Vec u = deformed(block);
  nsb::Vec f(block.ndof());
  const double limit_ns = nsb::bench::least_ns([&] {
    block.internal_force(u, f);
    benchmark::DoNotOptimize(f.data());
    benchmark::ClobberMemory();
  });
  nsb::bench::time_steps(state, integ, dt);
  nsb::bench::report_limit(state, static_cast<double>(n * n), limit_ns, "bare F_int on the same mesh");
}

void BM_BlockCdLagrangeFrictionStep(benchmark::State& state) {
  const long n = state.range(0);
  const auto frictionless = sliding_block(n, "0");
  nsb::CdLagrange reference(nsb::Params(nsb::CdLagrange::parameters_spec()));
  reference.init(frictionless, frictionless.initial_state());
  const double dt = 0.9 * frictionless.stable_step();
  const double limit_ns = nsb::bench::least_ns([&] {
    reference.step(dt);
    benchmark::DoNotOptimize(reference.state().v.data());
    benchmark::ClobberMemory();
  });
  const auto block = sliding_block(n, "0.5");
  nsb::CdLagrange integ(nsb::Params(nsb::CdLagrange::parameters_spec()));
  integ.init(block, block.initial_state());
  nsb::bench::time_steps(state, integ, dt);
  state.counters["tangential_impulse"] = integ.tangential_impulses().cwiseAbs().sum();  // > 0: friction acted
  nsb::bench::report_limit(state, static_cast<double>(n * n), limit_ns, "the frictionless step of the same sliding block");
}

}  // namespace

BENCHMARK(BM_BlockInternalForce)->Name("BM_Block/internal-force")->RangeMultiplier(2)->Range(64, 256)
    ->ComputeStatistics("min", min_of)->UseRealTime();
BENCHMARK(BM_BlockCdLagrangeStep)->Name("BM_Block/cd-lagrange")->RangeMultiplier(2)->Range(64, 256)
    ->ComputeStatistics("min", min_of)->UseRealTime();

BENCHMARK(BM_BlockCdLagrangeFrictionStep)->Name("BM_Block/cd-lagrange-friction")->Arg(128)
    ->ComputeStatistics("min", min_of)->UseRealTime();

BENCHMARK_MAIN();
