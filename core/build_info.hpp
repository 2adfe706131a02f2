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

// What `program` prints once, before its first step, when it was built from changed sources:
// "<program>: note: built from revision R with changes to FILES\n" (its numbers are not the
// revision's); "" for a clean build. One wording for nsbench run and nsbench-study.
inline std::string dirty_build_note(const std::string& program) {
  const BuildInfo& b = build_info();
  if (b.dirty_files.empty()) return {};
  return program + ": note: built from revision " + b.git_revision + " with changes to " + b.dirty_files + "\n";
}

}  // namespace nsb
