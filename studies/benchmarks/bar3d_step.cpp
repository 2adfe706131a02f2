// Benchmark: the hex8 bar (problems/bar_3d.hpp, sides free: three dofs per node) as a cube of
// n x n x n elements, n = 16 and 32, each against its limit (limit.hpp):
//
//   BM_Bar3d/internal-force/n   one F_int evaluation, element by element (f_e = K_e u_e, one
//                               24 x 24 K_e for every element); limit: its floating-point
//                               operations at the peak multiply-add rate of this build
//                               (peak_flops_per_ns, measured in the same process)
//   BM_Bar3d/cd-lagrange/n      one CD-Lagrange step, 10 steps into the wall contact; limit:
//                               the bare F_int evaluation above on the same mesh
//
// Flops per element: the 24 x 24 matrix-vector product, 576 multiplies and 576 adds, 1152
// (the gather and the 24 scatter adds are not counted). Counter "bytes_per_element": the
// compulsory traffic of one F_int pass, u read and f written once (16 bytes per dof), over the
// elements; K_e (4.6 kB) stays in cache.
// Threads: as NSBENCH_THREADS (default all cores); the one-core figure is NSBENCH_THREADS=1.
// The machine may be shared: run with --benchmark_repetitions=5 and read the min rows.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "integrators/cd_lagrange.hpp"
#include "problems/bar_3d.hpp"
#include "studies/benchmarks/limit.hpp"

namespace {

using nsb::bench::min_of;

constexpr double kFlopsPerElement = 1152.0;

// The unit cube as n^3 elements, sides free, moving onto the wall (in contact from the start).
nsb::Bar3d cube(long n) {
  return nsb::Bar3d(nsb::Params(nsb::Bar3d::parameters_spec(),
                                {{"N", std::to_string(n)}, {"N_side", std::to_string(n)}, {"lateral", "free"}}));
}

// A deformed state, every dof different, so no product is trivial.
nsb::Vec deformed(const nsb::Bar3d& bar) {
  nsb::Vec u(bar.ndof());
  for (nsb::Index i = 0; i < u.size(); ++i) u[i] = 1e-4 * std::sin(0.37 * static_cast<double>(i));
  return u;
}

void report_bytes(benchmark::State& state, const nsb::Bar3d& bar) {
  state.counters["bytes_per_element"] = 16.0 * static_cast<double>(bar.ndof()) / static_cast<double>(bar.elements());
}

void BM_Bar3dInternalForce(benchmark::State& state) {
  const auto bar = cube(state.range(0));
  const nsb::Vec u = deformed(bar);
  nsb::Vec f(bar.ndof());
  const double elements = static_cast<double>(bar.elements());
  const double limit_ns = kFlopsPerElement * elements / (nsb::bench::peak_flops_per_ns() * nsb::run_threads());
  for (auto _ : state) {
    bar.internal_force(u, f);
    benchmark::DoNotOptimize(f.data());
    benchmark::ClobberMemory();
  }
  report_bytes(state, bar);
  nsb::bench::report_limit(state, elements, limit_ns, "1152 flops per element at the peak multiply-add rate");
}

void BM_Bar3dCdLagrangeStep(benchmark::State& state) {
  const auto bar = cube(state.range(0));
  nsb::CdLagrange integ(nsb::Params(nsb::CdLagrange::parameters_spec()));
  integ.init(bar, bar.initial_state());
  const double dt = 0.9 * bar.stable_step();
  for (int k = 0; k < 10; ++k) integ.step(dt);
  const nsb::Vec u = deformed(bar);
  nsb::Vec f(bar.ndof());
  const double limit_ns = nsb::bench::least_ns([&] {
    bar.internal_force(u, f);
    benchmark::DoNotOptimize(f.data());
    benchmark::ClobberMemory();
  });
  nsb::bench::time_steps(state, integ, dt);
  report_bytes(state, bar);
  nsb::bench::report_limit(state, static_cast<double>(bar.elements()), limit_ns, "bare F_int on the same mesh");
}

}  // namespace

BENCHMARK(BM_Bar3dInternalForce)->Name("BM_Bar3d/internal-force")->Arg(16)->Arg(32)
    ->ComputeStatistics("min", min_of)->UseRealTime();
BENCHMARK(BM_Bar3dCdLagrangeStep)->Name("BM_Bar3d/cd-lagrange")->Arg(16)->Arg(32)
    ->ComputeStatistics("min", min_of)->UseRealTime();

BENCHMARK_MAIN();
