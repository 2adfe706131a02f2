#pragma once
// Runs independent study cases on the available cores. Results are stored by case index,
// so tables come out in the same order whatever the scheduling (deterministic output);
// each case's CPU time is its own thread's (run() uses CLOCK_THREAD_CPUTIME_ID).
// Progress goes to stderr at most once a second: "label: case k/n, elapsed, eta".
// Cores: NSBENCH_JOBS if set, else std::thread::hardware_concurrency(). Each case runs
// single-threaded (a ThreadScope(1) per worker, core/threads.hpp): no oversubscription.
//
// A case may name a process-wide lock its run holds (IntegratorEntry::shared_lock: Siconos'
// BLAS, Python's GIL). Two cases holding the same lock at once would take turns on it while a
// core waited, so a worker takes the first case in order whose lock no running case holds, and
// waits only when every case left is held up that way.
#include <functional>
#include <string>
#include <vector>

namespace nsb {

int study_jobs();

// Calls task(i) for i in [0, n), never two tasks with the same non-empty locks[i] at once
// (locks empty or of size n); the first exception thrown by a task is rethrown after all
// threads stop.
void parallel_for(std::size_t n, const std::function<void(std::size_t)>& task, const std::string& label,
                  const std::vector<std::string>& locks = {});

template <class R, class F>
std::vector<R> parallel_map(std::size_t n, F&& f, const std::string& label, const std::vector<std::string>& locks = {}) {
  std::vector<R> results(n);
  parallel_for(n, [&](std::size_t i) { results[i] = f(i); }, label, locks);
  return results;
}

}  // namespace nsb
