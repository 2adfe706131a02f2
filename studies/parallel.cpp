#include "studies/parallel.hpp"

#include <fmt/format.h>

#include <atomic>
#include <charconv>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <thread>

#include "core/parameters.hpp"
#include "core/threads.hpp"

namespace nsb {

namespace {
constexpr int kMaxJobs = 4096;
}  // namespace

int study_jobs() {
  if (const char* env = std::getenv("NSBENCH_JOBS"); env && *env) {
    int j = 0;
    const std::string_view text(env);
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), j);
    if (ec != std::errc() || end != text.data() + text.size() || j < 1 || j > kMaxJobs)
      throw InputError(fmt::format("NSBENCH_JOBS='{}': expected a whole number of parallel cases; valid: 1 to {} "
                                   "(unset: the number of cores)", text, kMaxJobs));
    return j;
  }
  return std::max(1u, std::thread::hardware_concurrency());
}

void parallel_for(std::size_t n, const std::function<void(std::size_t)>& task, const std::string& label) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  std::atomic<std::size_t> next{0}, done{0};
  std::exception_ptr failure;
  std::mutex mutex;
  auto last_report = start;

  const auto worker = [&]() {
    const ThreadScope serial(1);  // the cases are the parallelism: each runs on one thread
    for (std::size_t i = next++; i < n; i = next++) {
      try {
        task(i);
      } catch (...) {
        std::lock_guard lock(mutex);
        if (!failure) failure = std::current_exception();
        next = n;  // stop handing out cases
      }
      const std::size_t k = ++done;
      std::lock_guard lock(mutex);
      const auto now = clock::now();
      if (now - last_report >= std::chrono::seconds(1) || k == n) {
        const double elapsed = std::chrono::duration<double>(now - start).count();
        fmt::print(stderr, "{}: case {}/{}, elapsed {:.1f} s, eta {:.1f} s\n", label, k, n, elapsed,
                   elapsed / static_cast<double>(k) * static_cast<double>(n - k));
        last_report = now;
      }
    }
  };
  const int jobs = std::min<int>(study_jobs(), static_cast<int>(std::max<std::size_t>(n, 1)));
  std::vector<std::thread> threads;
  for (int j = 1; j < jobs; ++j) threads.emplace_back(worker);
  worker();
  for (auto& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace nsb
