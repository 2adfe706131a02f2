#include "core/threads.hpp"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <thread>

#include "core/parameters.hpp"

namespace nsb {

namespace {
thread_local int scoped_threads = 0;  // 0: no ThreadScope alive

int configured_threads() {
  const char* env = std::getenv("NSBENCH_THREADS");
  if (!env || !*env) return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  char* end = nullptr;
  const long n = std::strtol(env, &end, 10);
  if (*end != '\0' || n < 1 || n > 4096)
    throw InputError("NSBENCH_THREADS must be an integer in [1, 4096], got '" + std::string(env) + "'");
  return static_cast<int>(n);
}
}  // namespace

int run_threads() {
  if (scoped_threads > 0) return scoped_threads;
  static const int threads = configured_threads();
  return threads;
}

ThreadScope::ThreadScope(int n) : saved_(scoped_threads) { scoped_threads = std::max(1, n); }
ThreadScope::~ThreadScope() { scoped_threads = saved_; }

}  // namespace nsb
