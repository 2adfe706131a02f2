#pragma once
// Threads for the loops inside one run (element loops, vector updates): NSBENCH_THREADS if
// set (an integer >= 1), else all cores. Results never depend on it: a parallel loop either
// writes disjoint entries or sums in an order fixed by the mesh, never by the schedule
// (no atomic or per-thread floating-point sums).
// Studies already run whole cases in parallel (NSBENCH_JOBS): each of their workers holds a
// ThreadScope(1), so a case runs on its worker's thread only and the cores are not oversubscribed.
#include <omp.h>

#include <algorithm>
#include <cstddef>

namespace nsb {

// Threads available to the calling thread's loops; throws InputError for a bad NSBENCH_THREADS.
int run_threads();

// While alive, run_threads() returns n on the thread that made it (n >= 1).
class ThreadScope {
 public:
  explicit ThreadScope(int n);
  ~ThreadScope();
  ThreadScope(const ThreadScope&) = delete;
  ThreadScope& operator=(const ThreadScope&) = delete;

 private:
  int saved_;
};

// Threads worth starting for n work items when each thread should get at least
// min_per_thread of them (below that, starting and joining threads costs more than it saves):
// between 1 and run_threads().
inline int threads_for(std::ptrdiff_t n, std::ptrdiff_t min_per_thread) {
  return static_cast<int>(std::clamp<std::ptrdiff_t>(n / min_per_thread, 1, run_threads()));
}

// Calls f(i) for i = first, first + stride, ... below end: on `threads` threads (OpenMP,
// static schedule) when threads > 1, else in a plain loop, because an OpenMP region starts
// a team (and allocates, in libgomp) even when its if clause keeps it on one thread. For
// work whose calls write disjoint entries.
template <class F>
void strided_for(std::ptrdiff_t first, std::ptrdiff_t end, std::ptrdiff_t stride, int threads, F&& f) {
  if (threads <= 1) {
    for (std::ptrdiff_t i = first; i < end; i += stride) f(i);
    return;
  }
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::ptrdiff_t i = first; i < end; i += stride) f(i);
}

// Calls f(begin, end) on contiguous pieces of [0, n), in parallel on run_threads() threads
// when n is large enough to pay for them. For element-wise work (each index written by one
// call only), so results do not depend on the split.
template <class F>
void parallel_ranges(std::ptrdiff_t n, F&& f) {
  const int threads = threads_for(n, 4096);
  if (threads == 1) {
    f(std::ptrdiff_t{0}, n);
    return;
  }
#pragma omp parallel num_threads(threads)
  {
    const std::ptrdiff_t t = omp_get_thread_num(), nt = omp_get_num_threads();
    f(n * t / nt, n * (t + 1) / nt);
  }
}

}  // namespace nsb
