#pragma once
// Provenance stamped into every report: which release, revision and build produced a number.
#include <string>

namespace nsb {

struct BuildInfo {
  std::string version;       // the release: CMake's project VERSION (CMakeLists.txt)
  std::string git_revision;  // short hash, "-dirty" when the work tree had changes
  std::string build_type;
  std::string compiler;
  // The files that differed from the revision when the binary was built ("a.cpp, b.hpp and 3
  // more"; "" when clean): what a run built from a dirty tree says it ran.
  std::string dirty_files;
};

const BuildInfo& build_info();

// What `<program> --version` prints: the release first, then the build that carries it.
inline std::string version_text(const std::string& program) {
  const BuildInfo& b = build_info();
  return program + " " + b.version + " (revision " + b.git_revision + ", " + b.build_type + " build, " + b.compiler + ")";
}

}  // namespace nsb
