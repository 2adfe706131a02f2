#pragma once
// Scratch directories and file contents for the tests.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace nsb::test {

// A scratch directory named for its test file and this process (CTest runs the test cases in
// parallel processes), emptied on entry (made when `create`) and removed on exit.
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& tag, bool create = false)
      : path(std::filesystem::temp_directory_path() / ("nsbench_" + tag + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path);
    if (create) std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
};

// The whole file as text ("" when it cannot be read).
inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace nsb::test
