// The built-in study files (studies/builtin/): each parses, and its case list is the one of the C++
// study it replaces.
#include <catch2/catch.hpp>
#include <tuple>
#include <vector>

#include "integrators/registry.hpp"
#include "studies/registry.hpp"
#include "studies/study_file.hpp"

namespace nsb {
extern const StudyEntry work_precision_study;
}

namespace {

using CaseKey = std::tuple<std::size_t, std::string, double>;  // problem, integrator, dt

nsb::StudySpec builtin_spec(const std::string& path) {
  const nsb::EmbeddedStudyFile* file = nsb::builtin_study_file(path);
  REQUIRE(file != nullptr);
  return nsb::parse_study_text(std::string(file->text), path, false);
}

std::vector<CaseKey> file_case_keys(const nsb::StudySpec& spec, bool full) {
  std::vector<CaseKey> keys;
  for (const auto& c : nsb::study_cases(nsb::file_study(spec), {full})) {
    CHECK(c["tol"].is_null());
    keys.emplace_back(c["problem"].get<std::size_t>(), spec.integrators[c["integrator"].get<std::size_t>()].name, c["dt"].get<double>());
  }
  return keys;
}

}  // namespace

TEST_CASE("builtin precision.toml: the case list of the C++ study precision, default and --full", "[studies]") {
  const nsb::StudySpec spec = builtin_spec("studies/builtin/precision.toml");
  for (const bool full : {false, true}) {
    std::vector<CaseKey> cpp;
    for (const auto& c : nsb::study_cases(nsb::work_precision_study, {full}))
      cpp.emplace_back(c["problem"].get<std::size_t>(), c["integrator"].get<std::string>(), c["dt"].get<double>());
    INFO("full " << full);
    CHECK(cpp.size() == (full ? 25u : 18u) * nsb::integrator_registry().size());
    CHECK(file_case_keys(spec, full) == cpp);
  }
}
