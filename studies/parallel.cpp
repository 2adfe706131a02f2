#include "studies/parallel.hpp"

#include <fmt/format.h>

#include <charconv>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <thread>

#include "core/parameters.hpp"
#include "core/threads.hpp"

namespace nsb {

namespace {

constexpr int kMaxJobs = 4096;

// The cases not yet started, handed out in order but for those whose lock a running case holds.
// Used with the pool's mutex held.
class CaseQueue {
 public:
  CaseQueue(std::size_t n, const std::vector<std::string>& locks) : locks_(locks), started_(n, false) {}

  // The first case not started whose lock is free, now started (its lock held); none when every
  // case left waits for a lock.
  std::optional<std::size_t> take() {
    for (std::size_t i = first_; i < started_.size(); ++i) {
      if (started_[i] || held_.count(lock_of(i))) continue;
      started_[i] = true;
      if (!lock_of(i).empty()) held_.insert(lock_of(i));
      while (first_ < started_.size() && started_[first_]) ++first_;
      return i;
    }
    return std::nullopt;
  }
  void finish(std::size_t i) { held_.erase(lock_of(i)); }
  bool all_started() const { return first_ == started_.size(); }
  void stop() { first_ = started_.size(); }  // hand out no more cases

 private:
  const std::string& lock_of(std::size_t i) const { return locks_.empty() ? kNoLock : locks_[i]; }

  static inline const std::string kNoLock;
  const std::vector<std::string>& locks_;
  std::vector<bool> started_;
  std::size_t first_ = 0;  // every case before it has started
  std::set<std::string> held_;
};

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

void parallel_for(std::size_t n, const std::function<void(std::size_t)>& task, const std::string& label,
                  const std::vector<std::string>& locks) {
  if (!locks.empty() && locks.size() != n)
    throw std::logic_error(fmt::format("parallel_for: {} locks for {} cases", locks.size(), n));
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  std::size_t done = 0;
  std::exception_ptr failure;
  std::mutex mutex;
  std::condition_variable case_done;
  CaseQueue queue(n, locks);
  auto last_report = start;

  const auto report_progress = [&]() {
    const auto now = clock::now();
    if (now - last_report >= std::chrono::seconds(1) || done == n) {
      const double elapsed = std::chrono::duration<double>(now - start).count();
      fmt::print(stderr, "{}: case {}/{}, elapsed {:.1f} s, eta {:.1f} s\n", label, done, n, elapsed,
                 elapsed / static_cast<double>(done) * static_cast<double>(n - done));
      last_report = now;
    }
  };
  const auto worker = [&]() {
    const ThreadScope serial(1);  // the cases are the parallelism: each runs on one thread
    std::unique_lock lock(mutex);
    while (!queue.all_started()) {
      const std::optional<std::size_t> i = queue.take();
      if (!i) {  // every case left waits for a lock that a running case holds
        case_done.wait(lock);
        continue;
      }
      lock.unlock();
      std::exception_ptr thrown;
      try {
        task(*i);
      } catch (...) {
        thrown = std::current_exception();
      }
      lock.lock();
      if (thrown && !failure) failure = thrown;
      if (thrown) queue.stop();
      queue.finish(*i);
      ++done;
      report_progress();
      case_done.notify_all();
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
