// Benchmark: the memory of a run against its length (issue 20). `nsbench run` of the
// bouncing mass (cd-lagrange, dt = 1e-5, every step sampled into series.csv) for 1e5 and
// 1e6 steps, in a child process; its peak resident set (wait4's ru_maxrss, the child's
// alone) is the counter peak_rss_mb:
//
//   BM_PeakRss/bouncing-mass/steps   one whole run (time: the run's; units: its steps)
//
// The series is streamed to disk as the run goes (CsvSeriesFile, run/run.hpp), so
// the peak is the program's fixed footprint and must not grow with the number of steps
// (holding the series in memory, 2e6 steps took 966 MB). The CSV (about 200 bytes a
// step, 0.2 GB at 1e6) goes to a temporary directory removed after each run. A factor 10 in
// length shows whether the peak grows; 1e6 steps take about 20 s (most of it writing CSV).
#include <benchmark/benchmark.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "studies/benchmarks/limit.hpp"

extern char** environ;

namespace {

struct ChildRun {
  double peak_rss_mb;
  int status;
};

ChildRun run_child(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (const int err = ::posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ); err != 0)
    throw std::runtime_error(fmt::format("cannot start {}: error {}", args[0], err));
  int status = 0;
  rusage usage{};
  if (::wait4(pid, &status, 0, &usage) != pid) throw std::runtime_error("wait4 failed");
  return {static_cast<double>(usage.ru_maxrss) / 1024.0, status};  // ru_maxrss in KiB
}

void BM_PeakRss(benchmark::State& state) {
  const long steps = state.range(0);
  const double dt = 1e-5;
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / fmt::format("nsbench_bench_memory_{}", static_cast<long>(::getpid()));
  double peak = 0.0;
  for (auto _ : state) {
    const ChildRun r = run_child({NSBENCH_EXE, "run", "--problem", "bouncing-mass", "--integrator", "cd-lagrange", "--dt",
                                  fmt::format("{:.17g}", dt), "--t-end", fmt::format("{:.17g}", steps * dt), "--out",
                                  out.string()});
    std::filesystem::remove_all(out);
    if (!WIFEXITED(r.status) || WEXITSTATUS(r.status) != 0) {
      state.SkipWithError("nsbench run failed");
      return;
    }
    peak = std::max(peak, r.peak_rss_mb);
  }
  state.counters["peak_rss_mb"] = peak;
  state.counters["units"] = static_cast<double>(steps);
}

void register_all() {
  benchmark::RegisterBenchmark("BM_PeakRss/bouncing-mass", BM_PeakRss)
      ->Arg(100000)
      ->Arg(1000000)
      ->Unit(benchmark::kMillisecond)
      ->ComputeStatistics("min", nsb::bench::min_of)
      ->UseRealTime();
}

}  // namespace

int main(int argc, char** argv) { return nsb::bench::run_benchmarks(argc, argv, register_all); }
