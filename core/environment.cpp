#include "core/environment.hpp"

#include <SuiteSparse_config.h>
#include <fmt/format.h>
#include <link.h>
#include <sundials/sundials_config.h>

#include <Eigen/Core>
#include <filesystem>
#include <fstream>
#include <thread>

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

}  // namespace nsb
