#pragma once
// What every nsbench benchmark of a time step reports beside its time, so that
// `nsbench-study performance` (studies/performance.cpp) can put each scheme next to its
// limit in one table:
//   counter "run_threads" the threads of the run (NSBENCH_THREADS; Google Benchmark's own
//                      "threads" field counts its benchmark threads, always 1 here)
//   counter "units"     the dofs (or elements) the step works on: the per-unit column
//   counter "limit_ns"  the limit's time per step in ns, measured in the same process,
//                       on the same data size, just before the step's own loop (so both
//                       see the same machine state)
//   label               "limit: <what the limit is>", e.g. "limit: triad over N+1 doubles"
// The limit is the cost no implementation of the step can beat on this machine: the STREAM
// triad for memory-bound explicit steps, the bare element-force loop for the block, the
// bare CHOLMOD solve (and factorisation) for implicit schemes.
// A step benchmark builds its problem, integrator, warm-up steps and the limit's data once
// (reused_setup below), not at every call of the benchmark function; the limit's least_ns is
// measured at every call all the same, just before the timed loop.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>
#include <string>
#include <typeinfo>
#include <utility>
#include <vector>

#include "core/threads.hpp"
#include "integrators/integrator.hpp"

namespace nsb::bench {

inline double min_of(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

// The least time of one call of `kernel`, in ns, over at least 5 calls and 20 ms: the
// least is the figure a quiet machine gives (noise only ever adds time).
template <class Kernel>
double least_ns(Kernel&& kernel) {
  using Clock = std::chrono::steady_clock;
  kernel();  // first touch, caches and page faults out of the way
  double best = std::numeric_limits<double>::infinity(), total = 0.0;
  for (int calls = 0; calls < 5 || total < 2e7; ++calls) {
    const auto t0 = Clock::now();
    kernel();
    const double ns = std::chrono::duration<double, std::nano>(Clock::now() - t0).count();
    best = std::min(best, ns);
    total += ns;
  }
  return best;
}

// The set-up of the benchmark named `key` (its name and arguments): a Setup built from `args`
// at the first call, the same object at the next calls with the same key. Google Benchmark
// calls a benchmark function several times to size the iteration count, then once per
// repetition; building the problem (sparse assembly, page faults: most of the run at 1e7
// elements) at each call would cost more than the timing itself. One slot for the whole
// binary: the previous set-up is freed before the next is built, so memory holds one problem
// at a time. The Setup stays where it was built (integrators keep a reference to their
// problem), and a later call's timed steps continue from where the previous call's stopped.
struct SetupSlot {
  std::string key;
  const std::type_info* type = nullptr;
  std::shared_ptr<void> setup;  // type-erased: the benchmarks of one binary differ in Setup
};
inline SetupSlot& setup_slot() {
  static SetupSlot slot;
  return slot;
}

template <class Setup, class... Args>
Setup& reused_setup(const std::string& key, Args&&... args) {
  SetupSlot& slot = setup_slot();
  if (!slot.setup || slot.key != key || *slot.type != typeid(Setup)) {
    slot.setup.reset();
    slot.setup = std::make_shared<Setup>(std::forward<Args>(args)...);
    slot.key = key;
    slot.type = &typeid(Setup);
  }
  return *static_cast<Setup*>(slot.setup.get());
}

// Records "units", "run_threads" and the inverted per-unit rate "time_per_unit" (seconds per
// unit and step, printed with an SI prefix): the counters of any benchmark, limit or not.
inline void report_units(benchmark::State& state, double units) {
  state.counters["units"] = units;
  state.counters["time_per_unit"] =
      benchmark::Counter(units, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["run_threads"] = nsb::run_threads();
}

// A step's counters: the above, its limit and the label naming it.
inline void report_limit(benchmark::State& state, double units, double limit_ns, const std::string& limit) {
  report_units(state, units);
  state.counters["limit_ns"] = limit_ns;
  state.SetLabel("limit: " + limit);
}

// The timed loop of a step benchmark: one step of `integ` per iteration.
inline void time_steps(benchmark::State& state, nsb::Integrator& integ, double dt) {
  for (auto _ : state) {
    integ.step(dt);
    benchmark::DoNotOptimize(integ.state().v.data());
    benchmark::ClobberMemory();
  }
}

// STREAM triad a = b + s c over n doubles: the memory-bandwidth yardstick. On the threads
// the steps' vector updates get (nsb::parallel_ranges), so both see the same cores.
struct Triad {
  std::vector<double> a, b, c;
  explicit Triad(long n) : a(static_cast<std::size_t>(n), 0.0), b(static_cast<std::size_t>(n), 1.0), c(static_cast<std::size_t>(n), 2.0) {}
  void operator()() {
    nsb::parallel_ranges(static_cast<std::ptrdiff_t>(a.size()), [this](std::ptrdiff_t begin, std::ptrdiff_t end) {
      double* __restrict pa = a.data();
      const double* __restrict pb = b.data();
      const double* __restrict pc = c.data();
      for (std::ptrdiff_t i = begin; i < end; ++i) pa[i] = pb[i] + 0.5 * pc[i];
    });
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
};

// Floating-point operations per ns one thread can do in this build: 24 independent
// multiply-add chains (12 SSE2 registers; enough to cover the multiply and add latencies at
// two of each per cycle). The project builds for baseline x86-64, without FMA, so that the
// rounding is the same on every machine: this is the peak that code can reach.
inline double peak_flops_per_ns() {
  constexpr int kLanes = 24;
  constexpr long kRounds = 100000;
  double acc[kLanes];
  for (int i = 0; i < kLanes; ++i) acc[i] = 1.0 + 1e-3 * i;
  const double a = 0.999999, b = 1e-7;
  const double ns = least_ns([&] {
    for (long r = 0; r < kRounds; ++r)
      for (int i = 0; i < kLanes; ++i) acc[i] = acc[i] * a + b;
    benchmark::DoNotOptimize(acc);
    benchmark::ClobberMemory();
  });
  return 2.0 * kLanes * kRounds / ns;
}

// main() of a benchmark binary whose benchmarks `register_benchmarks` registers at run time.
inline int run_benchmarks(int argc, char** argv, void (*register_benchmarks)()) {
  register_benchmarks();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace nsb::bench
