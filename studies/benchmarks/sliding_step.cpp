// Benchmark: one CD-Lagrange step of the two stacked blocks (problems/two_blocks.hpp) with
// large sliding, against the same step with small sliding on the same blocks:
//
//   BM_Sliding/cd-lagrange-large   the step finding each upper bottom node's segment and xi
//                                  at U_{k+1}, g, L, T there (worst-case pattern) and the
//                                  Delassus products of the closed contacts from them
//                                  (integrators/impulse_contact.hpp); limit: the small-sliding
//                                  step, timed in the same process (the ratio is issue 32's
//                                  cost of large sliding: at most 1.3)
//   BM_Sliding/cd-lagrange-small   the small-sliding step alone, timed the same way
//
// The blocks start touching (upper_gap 0) at rest under gravity with mu = 0.3, so every step
// solves the same coupled Coulomb problem on the lower block's floor contacts and the eight
// node-to-segment contacts in both, and with the faces flat the rows of both are equal: the
// ratio is the evaluation's cost. Each benchmark first runs kSettle steps so that both time
// the settled stack. The machine may be shared: run with --benchmark_repetitions=5 and read
// the min rows.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <string>

#include "integrators/cd_lagrange.hpp"
#include "problems/two_blocks.hpp"
#include "studies/benchmarks/limit.hpp"

namespace {

using nsb::bench::min_of;

constexpr double kDt = 1e-4;
constexpr int kSettle = 2000;  // 0.2 s: the stack at rest

nsb::TwoBlocks stack(const std::string& sliding) {
  const std::map<std::string, std::string> set = {
      {"upper_gap", "0"}, {"upper_vy", "0"}, {"mu", "0.3"}, {"sliding", sliding}};
  return nsb::TwoBlocks(nsb::Params(nsb::TwoBlocks::parameters_spec(), set));
}

// The Gauss-Seidel sweeps per step of the timed loop: the solve both steps share, whose count
// follows the state (the stack vibrates), beside the evaluation the ratio is about.
void time_steps_counting_sweeps(benchmark::State& state, nsb::CdLagrange& integ) {
  const long sweeps0 = integ.work().lcp_iterations, steps0 = integ.work().steps;
  nsb::bench::time_steps(state, integ, kDt);
  state.counters["sweeps_per_step"] =
      double(integ.work().lcp_iterations - sweeps0) / double(std::max(1L, integ.work().steps - steps0));
}

// `integ` on `blocks`, settled.
void settle(nsb::CdLagrange& integ, const nsb::TwoBlocks& blocks) {
  integ.init(blocks, blocks.initial_state());
  for (int k = 0; k < kSettle; ++k) integ.step(kDt);
}

void BM_SlidingLargeStep(benchmark::State& state) {
  const nsb::TwoBlocks small = stack("small");
  nsb::CdLagrange reference(nsb::Params(nsb::CdLagrange::parameters_spec()));
  settle(reference, small);
  const double limit_ns = nsb::bench::least_ns([&] {
    reference.step(kDt);
    benchmark::DoNotOptimize(reference.state().v.data());
    benchmark::ClobberMemory();
  });
  const nsb::TwoBlocks large = stack("large");
  nsb::CdLagrange integ(nsb::Params(nsb::CdLagrange::parameters_spec()));
  settle(integ, large);
  time_steps_counting_sweeps(state, integ);
  // > 1: the node-to-segment contacts carry the upper block.
  state.counters["between_impulse"] = integ.impulses().tail(large.ncontacts() - large.floor_contacts()).sum();
  nsb::bench::report_limit(state, static_cast<double>(large.ncontacts()), limit_ns,
                           "the small-sliding step of the same blocks");
}

// The small-sliding step alone, timed as the large one (on a shared machine compare the two
// rows' CPU times or their min rows: the limit above is the least single call, which a loaded
// machine's descheduling does not reach in the loop's mean).
void BM_SlidingSmallStep(benchmark::State& state) {
  const nsb::TwoBlocks small = stack("small");
  nsb::CdLagrange integ(nsb::Params(nsb::CdLagrange::parameters_spec()));
  settle(integ, small);
  time_steps_counting_sweeps(state, integ);
  state.counters["between_impulse"] = integ.impulses().tail(small.ncontacts() - small.floor_contacts()).sum();
  nsb::bench::report_units(state, static_cast<double>(small.ncontacts()));
}

}  // namespace

BENCHMARK(BM_SlidingLargeStep)->Name("BM_Sliding/cd-lagrange-large")->ComputeStatistics("min", min_of)->UseRealTime();
BENCHMARK(BM_SlidingSmallStep)->Name("BM_Sliding/cd-lagrange-small")->ComputeStatistics("min", min_of)->UseRealTime();

BENCHMARK_MAIN();
