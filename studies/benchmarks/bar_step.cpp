// Benchmark: one explicit time step on the Signorini bar (problems/signorini_bar.hpp),
// N = 1e3 .. 1e6 (cd-lagrange on the singular bar also 1e7), each against its limit, the
// STREAM triad over the same N + 1 doubles (limit.hpp):
//
//   BM_Step/<integrator>/<mass>/N   one step, 10 steps into the contact first (the bar, the
//                                   integrator and those steps built once per benchmark, not
//                                   at each of Google Benchmark's calls; later calls step on)
//   BM_Triad/N                      the triad alone, N = 1e3 .. 1e7 (the 1e7 one, 240 MB, is
//                                   beyond any cache: the DRAM bandwidth; its arrays, too,
//                                   allocated once per benchmark)
//
// Why the step cannot come within 2x of the triad at large N: CD-Lagrange's step makes three
// passes over the dofs, and the Problem interface keeps them apart (F_int is the problem's,
// the two updates the integrator's):
//   u = u_prev + h v                         reads u_prev, v; writes u
//   F_int(u)                                 reads u, the element stiffnesses; writes F_int
//   v = v_prev + h M^-1 (F_ext - F_int)      reads v_prev, M^-1, F_ext, F_int; writes v
// 11 arrays streamed, plus 3 write-allocate reads of the written lines: 14 transfers of 8
// bytes per dof, against the triad's 4 (2 reads, 1 write, 1 write-allocate). At the memory
// limit the step costs 14/4 = 3.5 triads; fusing the passes would need a fused force-and-
// update entry point in every Problem. The step's traffic over its time against the
// triad's is the bandwidth ratio the note reports.
// The machine may be shared: run with --benchmark_repetitions=5
// --benchmark_report_aggregates_only=true and read the min rows.
#include <benchmark/benchmark.h>

#include <fmt/format.h>

#include <map>
#include <memory>
#include <optional>
#include <string>

#include "integrators/registry.hpp"
#include "problems/signorini_bar.hpp"
#include "studies/benchmarks/limit.hpp"

namespace {

using nsb::bench::min_of;

// A registered integrator on the bar at alpha h/c, 10 steps into the contact, and the triad
// over N + 1 doubles: built once per benchmark (limit.hpp's reused_setup).
struct BarStep {
  nsb::SignoriniBar bar;
  std::unique_ptr<nsb::Integrator> integ;
  double dt;
  std::optional<nsb::bench::Triad> triad;  // allocated last: the assembly's temporaries are gone by then
  BarStep(long N, const std::string& integrator, const std::map<std::string, std::string>& params, const std::string& mass,
          double alpha)
      : bar(nsb::Params(nsb::SignoriniBar::parameters_spec(), {{"N", std::to_string(N)}, {"mass", mass}})),
        integ(nsb::make_integrator(integrator, params)),
        dt(alpha * bar.stable_step()) {
    integ->init(bar, bar.initial_state());
    for (int k = 0; k < 10; ++k) integ->step(dt);
    triad.emplace(N + 1);
  }
};

// One step against the triad, measured at each call just before the timed loop.
void step_bench(benchmark::State& state, const std::string& integrator, const std::map<std::string, std::string>& params,
                const std::string& mass, double alpha) {
  const long N = state.range(0);
  auto& setup = nsb::bench::reused_setup<BarStep>(fmt::format("BM_Step/{}/{}/{}", integrator, mass, N), N, integrator,
                                                  params, mass, alpha);
  const double limit_ns = nsb::bench::least_ns(*setup.triad);
  nsb::bench::time_steps(state, *setup.integ, setup.dt);
  nsb::bench::report_limit(state, static_cast<double>(N + 1), limit_ns, "triad over N+1 doubles");
}

void BM_Triad(benchmark::State& state) {
  const long n = state.range(0) + 1;
  auto& triad = nsb::bench::reused_setup<nsb::bench::Triad>(fmt::format("BM_Triad/{}", n - 1), n);
  for (auto _ : state) triad();
  nsb::bench::report_units(state, static_cast<double>(n));
}

void register_all() {
  struct Case {
    const char* integrator;
    std::map<std::string, std::string> params;
    const char* mass;
    double alpha;  // dt / (h/c); cd-penalty's contact spring lowers its stable step to 0.71 h/c
    long largest;
  };
  const std::vector<Case> cases = {
      {"cd-lagrange", {}, "singular", 0.9, 10000000},
      {"cd-lagrange", {}, "lumped", 0.9, 1000000},
      {"cd-penalty", {}, "lumped", 0.7, 1000000},
      {"d1-minus-linear", {}, "lumped", 0.9, 1000000},
      {"schatzman-paoli", {}, "lumped", 0.9, 1000000},
  };
  for (const auto& c : cases)
    benchmark::RegisterBenchmark(fmt::format("BM_Step/{}/{}", c.integrator, c.mass).c_str(), step_bench, c.integrator,
                                 c.params, c.mass, c.alpha)
        ->RangeMultiplier(10)
        ->Range(1000, c.largest)
        ->ComputeStatistics("min", min_of)
        ->UseRealTime();
  benchmark::RegisterBenchmark("BM_Triad", BM_Triad)->RangeMultiplier(10)->Range(1000, 10000000)->ComputeStatistics("min", min_of)->UseRealTime();
}

}  // namespace

int main(int argc, char** argv) { return nsb::bench::run_benchmarks(argc, argv, register_all); }
