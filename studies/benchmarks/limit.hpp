#pragma once
// What every nsbench benchmark of a time step reports beside its time, so that
// `nsbench-study performance` (studies/performance.cpp) can put each scheme next to its
// limit in one table:
//   counter "units"     the dofs (or elements) the step works on: the per-unit column
//   counter "limit_ns"  the limit's time per step in ns, measured in the same process,
//                       on the same data size, just before the step's own loop (so both
//                       see the same machine state)
//   label               "limit: <what the limit is>", e.g. "limit: triad over N+1 doubles"
// The limit is the cost no implementation of the step can beat on this machine: the STREAM
// triad for memory-bound explicit steps, the bare element-force loop for the block, the
// bare CHOLMOD solve (and factorisation) for implicit schemes.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <string>
#include <vector>

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

// Records the convention's counters and label, and the inverted per-unit rate "time_per_unit"
// (seconds per unit and step, printed with an SI prefix).
inline void report_limit(benchmark::State& state, double units, double limit_ns, const std::string& limit) {
  state.counters["units"] = units;
  state.counters["limit_ns"] = limit_ns;
  state.counters["time_per_unit"] =
      benchmark::Counter(units, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetLabel("limit: " + limit);
}

// STREAM triad a = b + s c over n doubles: the memory-bandwidth yardstick.
struct Triad {
  std::vector<double> a, b, c;
  explicit Triad(long n) : a(static_cast<std::size_t>(n), 0.0), b(static_cast<std::size_t>(n), 1.0), c(static_cast<std::size_t>(n), 2.0) {}
  void operator()() {
    double* __restrict pa = a.data();
    const double* __restrict pb = b.data();
    const double* __restrict pc = c.data();
    const long n = static_cast<long>(a.size());
    for (long i = 0; i < n; ++i) pa[i] = pb[i] + 0.5 * pc[i];
    benchmark::DoNotOptimize(pa);
    benchmark::ClobberMemory();
  }
};

}  // namespace nsb::bench
