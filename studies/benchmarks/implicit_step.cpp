// Benchmark: one time step of the implicit schemes with contact on the Signorini bar
// (problems/signorini_bar.hpp), N = 1e3 .. 1e5, against moreau-jean (bar_step.cpp's model):
//
//   BM_Step/<integrator>/<mass>/N   one step in contact (10 steps taken first, so the
//                                   factorisation and the contact responses are cached)
//
// moreau-jean (lumped; with projection = position), nsga and newmark-lm (lumped and
// singular). Each linear scheme factorises S once (K constant) and then does one sparse
// solve per step plus the contact LCP: the cost should be linear in N and within a small
// factor of moreau-jean's. Counter time_per_dof: CPU time per step over N + 1. The machine
// is shared: run with --benchmark_repetitions=5 --benchmark_report_aggregates_only=true and
// read the min rows.
#include <benchmark/benchmark.h>

#include <algorithm>

#include "integrators/registry.hpp"
#include "problems/signorini_bar.hpp"

namespace {

double min_of(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

void step_bench(benchmark::State& state, const std::string& integrator,
                const std::map<std::string, std::string>& overrides, const std::string& mass) {
  const long N = state.range(0);
  const nsb::SignoriniBar bar(nsb::Params(nsb::SignoriniBar::parameters_spec(), {{"N", std::to_string(N)}, {"mass", mass}}));
  auto integ = nsb::make_integrator(integrator, overrides);
  integ->init(bar, bar.initial_state());
  const double dt = 0.9 * bar.stable_step();
  for (int k = 0; k < 10; ++k) integ->step(dt);  // in contact, caches built
  for (auto _ : state) {
    integ->step(dt);
    benchmark::DoNotOptimize(integ->state().v.data());
    benchmark::ClobberMemory();
  }
  state.SetComplexityN(N + 1);
  state.counters["time_per_dof"] = benchmark::Counter(static_cast<double>(N + 1),
                                                      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void register_all() {
  struct Case {
    const char* label;
    const char* integrator;
    std::map<std::string, std::string> overrides;
    const char* mass;
  };
  const std::vector<Case> cases = {
      {"moreau-jean/lumped", "moreau-jean", {}, "lumped"},
      {"moreau-jean-projected/lumped", "moreau-jean", {{"projection", "position"}}, "lumped"},
      {"nsga/lumped", "nsga", {}, "lumped"},
      {"nsga/singular", "nsga", {}, "singular"},
      {"newmark-lm/lumped", "newmark-lm", {}, "lumped"},
      {"newmark-lm/singular", "newmark-lm", {}, "singular"},
  };
  for (const auto& c : cases)
    benchmark::RegisterBenchmark((std::string("BM_Step/") + c.label).c_str(), step_bench, c.integrator, c.overrides, c.mass)
        ->RangeMultiplier(10)
        ->Range(1000, 100000)
        ->Complexity(benchmark::oN)
        ->ComputeStatistics("min", min_of);
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
