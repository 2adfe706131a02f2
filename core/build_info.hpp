#pragma once
// Provenance stamped into every report: which revision and build produced a number.
#include <string>

namespace nsb {

struct BuildInfo {
  std::string git_revision;  // short hash, "-dirty" when the work tree had changes
  std::string build_type;
  std::string compiler;
};

const BuildInfo& build_info();

}  // namespace nsb
