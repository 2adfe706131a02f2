#pragma once
// Runs independent study cases on the available cores. Results are stored by case index,
// so tables come out in the same order whatever the scheduling (deterministic output);
// each case's CPU time is its own thread's (run() uses CLOCK_THREAD_CPUTIME_ID).
// Progress goes to stderr at most once a second: "label: case k/n, elapsed, eta".
// Cores: NSBENCH_JOBS if set, else std::thread::hardware_concurrency(). Each case runs
// single-threaded (a ThreadScope(1) per worker, core/threads.hpp): no oversubscription.
#include <functional>
#include <string>
#include <vector>

namespace nsb {

int study_jobs();

// Calls task(i) for i in [0, n); the first exception thrown by a task is rethrown after
// all threads stop.
void parallel_for(std::size_t n, const std::function<void(std::size_t)>& task, const std::string& label);

template <class R, class F>
std::vector<R> parallel_map(std::size_t n, F&& f, const std::string& label) {
  std::vector<R> results(n);
  parallel_for(n, [&](std::size_t i) { results[i] = f(i); }, label);
  return results;
}

}  // namespace nsb
