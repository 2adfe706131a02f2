#include "core/environment.hpp"

#include <SuiteSparse_config.h>
#include <fmt/format.h>
#include <link.h>
#include <sys/resource.h>
#include <unistd.h>
#include <sundials/sundials_config.h>

#include <Eigen/Core>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include "core/parameters.hpp"

namespace nsb {

namespace {

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
  return "unknown";
}

// The loaded shared objects whose name holds "blas", resolved through their symlinks (the
// libblas.so.3 alternative names the implementation only in its target).
std::string loaded_blas() {
  std::string found;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* data) {
        const std::string name = info->dlpi_name ? info->dlpi_name : "";
        if (name.find("blas") != std::string::npos) {
          std::error_code ec;
          const auto real = std::filesystem::canonical(name, ec);
          auto& out = *static_cast<std::string*>(data);
          out += (out.empty() ? "" : " + ") + (ec ? name : real.string());
        }
        return 0;
      },
      &found);
  return found.empty() ? "none loaded" : found;
}

std::string shell_quote(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./=:,@+") ==
                        std::string::npos)
    return s;
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string& command_storage() {
  static std::string command;
  return command;
}

}  // namespace

const Environment& environment() {
  static const Environment env{
      cpu_model(), std::thread::hardware_concurrency(),
      fmt::format("Eigen {}.{}.{}, SUNDIALS {}, SuiteSparse {}.{}.{}, BLAS {}", EIGEN_WORLD_VERSION,
                  EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION, SUNDIALS_VERSION, SUITESPARSE_MAIN_VERSION,
                  SUITESPARSE_SUB_VERSION, SUITESPARSE_SUBSUB_VERSION, loaded_blas())};
  return env;
}

void set_command_line(int argc, const char* const* argv) {
  std::string command;
  for (int i = 0; i < argc; ++i) command += (i ? " " : "") + shell_quote(argv[i]);
  command_storage() = command;
}

const std::string& command_line() { return command_storage(); }

double memory_available(std::string& source) {
  if (const char* env = std::getenv("NSBENCH_MEMORY_LIMIT"); env && *env) {
    const auto bad = [&] {
      return InputError(fmt::format("NSBENCH_MEMORY_LIMIT must be a positive whole number of bytes, optionally with a "
                                    "K, M or G suffix (powers of 1024), e.g. 512M; got '{}'", env));
    };
    char* end = nullptr;
    errno = 0;
    const unsigned long long n = std::strtoull(env, &end, 10);
    if (end == env || !std::isdigit(static_cast<unsigned char>(env[0])) || errno == ERANGE || n == 0) throw bad();
    double scale = 1.0;
    if (*end != '\0') {
      const char s = static_cast<char>(std::toupper(static_cast<unsigned char>(*end)));
      scale = s == 'K' ? 1024.0 : s == 'M' ? 1024.0 * 1024.0 : s == 'G' ? 1024.0 * 1024.0 * 1024.0 : 0.0;
      if (scale == 0.0 || end[1] != '\0') throw bad();
    }
    source = "NSBENCH_MEMORY_LIMIT";
    return static_cast<double>(n) * scale;
  }
  double available = static_cast<double>(sysconf(_SC_AVPHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGESIZE));
  source = "free physical memory; NSBENCH_MEMORY_LIMIT overrides it";
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kib = 0.0;
  while (meminfo >> key) {
    if (key == "MemAvailable:" && meminfo >> kib) {
      available = kib * 1024.0;
      source = "MemAvailable in /proc/meminfo; NSBENCH_MEMORY_LIMIT overrides it";
      break;
    }
    meminfo.ignore(1 << 12, '\n');
  }
  // A process limit below it (ulimit -v, -d: a batch job's) is what a run may really take.
  for (const auto& [resource, name] : {std::pair{RLIMIT_AS, "RLIMIT_AS, ulimit -v"}, {RLIMIT_DATA, "RLIMIT_DATA, ulimit -d"}}) {
    rlimit limit{};
    if (::getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY && static_cast<double>(limit.rlim_cur) < available) {
      available = static_cast<double>(limit.rlim_cur);
      source = fmt::format("{}; NSBENCH_MEMORY_LIMIT overrides it", name);
    }
  }
  return available;
}

}  // namespace nsb
