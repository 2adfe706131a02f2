// studies/builtin/hard.toml: the file reads, and its cases are the C++ study's it replaces
// (studies/hard_cases.cpp): each case (problem, in its order) run by every registered
// integrator, in the registry's order; the 10^4 impacts with --full only. (Its reports verify
// at --rtol 0 against the C++ study's: nsbench-study hard --verify reports --rtol 0.)
#include <catch2/catch.hpp>

#include <filesystem>

#include "integrators/registry.hpp"
#include "studies/study.hpp"
#include "studies/study_file.hpp"

namespace nsb {
extern const StudyEntry hard_cases_study;
}

TEST_CASE("built-in study hard: the file reads and its cases are the C++ study's", "[studies][builtin]") {
  const nsb::StudySpec spec = nsb::read_study_file(std::filesystem::path(NSBENCH_SOURCE_DIR) / "studies" / "builtin" / "hard.toml");
  const nsb::StudyEntry file = nsb::file_study(spec);
  for (const bool full : {false, true}) {
    INFO("full " << full);
    const auto cases = nsb::study_cases(file, {full});
    const auto cpp = nsb::study_cases(nsb::hard_cases_study, {full});
    REQUIRE(cases.size() == cpp.size());
    for (std::size_t k = 0; k < cases.size(); ++k) {
      CHECK(cases[k]["problem"] == cpp[k]["case"]);
      CHECK(spec.integrators[cases[k]["integrator"].get<std::size_t>()].name == cpp[k]["integrator"]);
    }
  }
}
