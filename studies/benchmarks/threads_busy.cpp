// Benchmark: the threads of one run on a busy machine. A CD-Lagrange run of the 2D block
// (128 x 128 elements, kStepsPerRun steps through nsb::run, as `nsbench run` steps) on all
// the run's threads (NSBENCH_THREADS, default all cores) against the same run on one thread:
//
//   BM_Threads/quiet   nothing else started
//   BM_Threads/busy    every core but one busy: cores - 1 busy-loop processes started by the
//                      benchmark, ended when it ends (and by SIGALRM after kBusySeconds at
//                      most, or when the benchmark dies: PR_SET_PDEATHSIG)
//
// Each iteration runs on one thread, then on all threads (two integrators on the same block,
// so both do the same work), each run timed on the wall clock: both see the same machine.
// Counters: one_thread_ns and threads_ns (per step) and
//   ratio = threads_ns / one_thread_ns
// < 1 where the threads pay, > 1 where they lose to one thread (on busy cores the team waits
// for its member that shares a core: core/team_size.hpp, core/wait_policy.hpp). The machine
// may be shared: run with --benchmark_repetitions=5 and read the median rows.
#include <benchmark/benchmark.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "core/threads.hpp"
#include "core/wait_policy.hpp"
#include "integrators/cd_lagrange.hpp"
#include "run/run.hpp"
#include "problems/block_2d.hpp"

namespace {

constexpr long kMesh = 128;
constexpr int kStepsPerRun = 300;
constexpr unsigned kBusySeconds = 600;  // a busy loop outlives no benchmark run by more

// cores - 1 processes spinning until the destructor ends them.
class BusyCores {
 public:
  explicit BusyCores(int count) {
    for (int i = 0; i < count; ++i) {
      const pid_t pid = fork();
      if (pid == 0) spin();
      if (pid > 0) pids_.push_back(pid);
    }
  }
  ~BusyCores() {
    for (const pid_t pid : pids_) kill(pid, SIGKILL);
    for (const pid_t pid : pids_) waitpid(pid, nullptr, 0);
  }
  BusyCores(const BusyCores&) = delete;
  BusyCores& operator=(const BusyCores&) = delete;
  int started() const { return static_cast<int>(pids_.size()); }

 private:
  [[noreturn]] static void spin() {
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    alarm(kBusySeconds);
    volatile unsigned long counter = 0;
    for (;;) counter = counter + 1;
  }
  std::vector<pid_t> pids_;
};

// Wall-clock ns of a run of kStepsPerRun steps of `integ` on at most `threads` threads.
double run_ns(const nsb::Problem& problem, nsb::Integrator& integ, double dt, int threads) {
  const nsb::ThreadScope scope(threads);
  nsb::RunOptions options;
  options.dt = dt;
  options.t_end = integ.state().t + kStepsPerRun * dt;
  options.sample_every = kStepsPerRun;
  const auto t0 = std::chrono::steady_clock::now();
  const auto result = nsb::run(problem, integ, options);
  benchmark::DoNotOptimize(integ.state().v.data());
  const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
  return ns / static_cast<double>(result.steps);
}

void BM_Threads(benchmark::State& state, bool busy) {
  const int threads = nsb::run_threads();
  if (threads < 2) {
    state.SkipWithError("one thread (NSBENCH_THREADS=1 or one core): nothing to compare");
    return;
  }
  const nsb::Block2d block(nsb::Params(nsb::Block2d::parameters_spec(),
                                       {{"nx", std::to_string(kMesh)}, {"ny", std::to_string(kMesh)}, {"H", "1"}}));
  const double dt = 0.9 * block.stable_step();
  nsb::CdLagrange one(nsb::Params(nsb::CdLagrange::parameters_spec())), many(nsb::Params(nsb::CdLagrange::parameters_spec()));
  one.init(block, block.initial_state());
  many.init(block, block.initial_state());
  const BusyCores busy_cores(busy ? static_cast<int>(std::thread::hardware_concurrency()) - 1 : 0);
  double one_ns = 0, many_ns = 0;  // per step, summed over the iterations
  for (auto _ : state) {
    one_ns += run_ns(block, one, dt, 1);
    many_ns += run_ns(block, many, dt, threads);
  }
  const double iterations = static_cast<double>(state.iterations());
  state.counters["one_thread_ns"] = one_ns / iterations;
  state.counters["threads_ns"] = many_ns / iterations;
  state.counters["ratio"] = many_ns / one_ns;
  state.counters["run_threads"] = threads;
  state.counters["busy_processes"] = busy_cores.started();
}

}  // namespace

BENCHMARK_CAPTURE(BM_Threads, quiet, false)->Name("BM_Threads/quiet")->Iterations(3)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Threads, busy, true)->Name("BM_Threads/busy")->Iterations(3)->UseRealTime()->Unit(benchmark::kMillisecond);

// The waiting policy nsbench and nsbench-study run with (unless OMP_WAIT_POLICY or
// GOMP_SPINCOUNT is set: GOMP_SPINCOUNT=300000 measures libgomp's default).
int main(int argc, char** argv) {
  nsb::choose_openmp_wait_policy(argv);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
