// Benchmark: one time step on the Signorini bar (problems/signorini_bar.hpp), N = 1e3 .. 1e6.
//
//   BM_CdLagrangeStep/N   one CD-Lagrange step (singular mass, massless contact node on the
//                         wall)
//   BM_Triad/N            STREAM triad a = b + s c over N + 1 doubles: the memory-bandwidth
//                         yardstick in the same binary
//   BM_MoreauJeanStep/N   one Moreau-Jean step (lumped mass, in contact; factorised once in
//                         setup), with Google Benchmark's O(N) fit (coefficient and RMS)
//   BM_CdPenaltyStep/N, BM_D1MinusLinearStep/N, BM_SchatzmanPaoliStep/N   the explicit field
//                         schemes (lumped mass, in contact), against BM_CdLagrangeLumpedStep
//                         (CD-Lagrange on the same lumped bar)
//   BM_SchatzmanPaoliImplicitStep/N   schatzman-paoli theta = 1/4 (lumped, factorised once in
//                         setup), against BM_MoreauJeanStep
// Counter time_per_dof: CPU time per step (per triad pass) divided by N + 1. The triad also
// runs at N = 1e7 (240 MB, beyond any cache): the DRAM bandwidth; at N = 1e6 its 24 MB may
// still sit in a large L3 while the step's 10 arrays (80 MB) do not.
//
// The explicit step streams 10 arrays of N doubles (u_prev, v read and u written; u read and
// F_int written; v_prev, minv, F_ext, F_int read and v written), the triad 3: at large N a
// bandwidth-bound step costs about 10/3 triads. The machine is shared: run with
//   --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// and read the min rows (the statistic registered below).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <string>

#include "integrators/cd_lagrange.hpp"
#include "integrators/registry.hpp"
#include "integrators/moreau_jean.hpp"
#include "problems/signorini_bar.hpp"

namespace {

nsb::SignoriniBar make_bar(long N, const std::string& mass) {
  return nsb::SignoriniBar(nsb::Params(nsb::SignoriniBar::parameters_spec(), {{"N", std::to_string(N)}, {"mass", mass}}));
}

double min_of(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

void per_dof(benchmark::State& state, long ndof) {
  // Inverted rate: seconds per (dof x step), printed with an SI prefix (e.g. 880ps).
  state.counters["time_per_dof"] = benchmark::Counter(static_cast<double>(ndof),
                                                      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_CdLagrangeStep(benchmark::State& state) {
  const long N = state.range(0);
  const auto bar = make_bar(N, "singular");
  nsb::CdLagrange integ(nsb::Params(nsb::CdLagrange::parameters_spec()));
  integ.init(bar, bar.initial_state());
  const double dt = 0.9 * bar.stable_step();
  for (int k = 0; k < 10; ++k) integ.step(dt);  // in contact, past the start
  for (auto _ : state) {
    integ.step(dt);
    benchmark::DoNotOptimize(integ.state().v.data());
    benchmark::ClobberMemory();
  }
  per_dof(state, N + 1);
}

void BM_Triad(benchmark::State& state) {
  const long n = state.range(0) + 1;
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const double s = 0.5;
  for (auto _ : state) {
    double* __restrict pa = a.data();
    const double* __restrict pb = b.data();
    const double* __restrict pc = c.data();
    for (long i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  per_dof(state, n);
}

void BM_MoreauJeanStep(benchmark::State& state) {
  const long N = state.range(0);
  const auto bar = make_bar(N, "lumped");
  nsb::MoreauJean integ(nsb::Params(nsb::MoreauJean::parameters_spec()));
  integ.init(bar, bar.initial_state());
  const double dt = 0.9 * bar.stable_step();
  for (int k = 0; k < 10; ++k) integ.step(dt);  // factorisation and contact response cached
  for (auto _ : state) {
    integ.step(dt);
    benchmark::DoNotOptimize(integ.state().v.data());
    benchmark::ClobberMemory();
  }
  state.SetComplexityN(N + 1);
  per_dof(state, N + 1);
}

// One step of a registered integrator on the lumped bar at 0.9 h/c (0.7 h/c for cd-penalty,
// whose contact spring lowers the stable step to 0.71 h/c), after 10 steps into the contact.
void registered_step(benchmark::State& state, const std::string& name, const std::map<std::string, std::string>& params, double alpha) {
  const long N = state.range(0);
  const auto bar = make_bar(N, "lumped");
  auto integ = nsb::make_integrator(name, params);
  integ->init(bar, bar.initial_state());
  const double dt = alpha * bar.stable_step();
  for (int k = 0; k < 10; ++k) integ->step(dt);
  for (auto _ : state) {
    integ->step(dt);
    benchmark::DoNotOptimize(integ->state().v.data());
    benchmark::ClobberMemory();
  }
  state.SetComplexityN(N + 1);
  per_dof(state, N + 1);
}

void BM_CdLagrangeLumpedStep(benchmark::State& state) { registered_step(state, "cd-lagrange", {}, 0.9); }
void BM_CdPenaltyStep(benchmark::State& state) { registered_step(state, "cd-penalty", {}, 0.7); }
void BM_D1MinusLinearStep(benchmark::State& state) { registered_step(state, "d1-minus-linear", {}, 0.9); }
void BM_SchatzmanPaoliStep(benchmark::State& state) { registered_step(state, "schatzman-paoli", {}, 0.9); }
void BM_SchatzmanPaoliImplicitStep(benchmark::State& state) { registered_step(state, "schatzman-paoli", {{"theta", "0.25"}}, 0.9); }

}  // namespace

BENCHMARK(BM_CdLagrangeLumpedStep)->RangeMultiplier(10)->Range(1000, 1000000)->ComputeStatistics("min", min_of);
BENCHMARK(BM_CdPenaltyStep)->RangeMultiplier(10)->Range(1000, 1000000)->ComputeStatistics("min", min_of);
BENCHMARK(BM_D1MinusLinearStep)->RangeMultiplier(10)->Range(1000, 1000000)->ComputeStatistics("min", min_of);
BENCHMARK(BM_SchatzmanPaoliStep)->RangeMultiplier(10)->Range(1000, 1000000)->ComputeStatistics("min", min_of);
BENCHMARK(BM_SchatzmanPaoliImplicitStep)->RangeMultiplier(10)->Range(1000, 1000000)->Complexity(benchmark::oN)->ComputeStatistics("min", min_of);
BENCHMARK(BM_CdLagrangeStep)->RangeMultiplier(10)->Range(1000, 1000000)->ComputeStatistics("min", min_of);
BENCHMARK(BM_Triad)->RangeMultiplier(10)->Range(1000, 10000000)->ComputeStatistics("min", min_of);
BENCHMARK(BM_MoreauJeanStep)->RangeMultiplier(10)->Range(1000, 1000000)->Complexity(benchmark::oN)->ComputeStatistics("min", min_of);

BENCHMARK_MAIN();
