// The built-in study files (studies/builtin/): each parses, and its case list is the one of the C++
// study it replaces (while that exists; after, what the study promises).
#include <catch2/catch.hpp>

#include <algorithm>
#include <tuple>
#include <vector>

#include "integrators/registry.hpp"
#include "problems/registry.hpp"
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

// hard.toml says what the hard study promises: each case (a [[problem]], in its order) run by
// every registered integrator, in the registry's order, at the case's own step; the 10^4
// impacts with --full only. Its reports verify at --rtol 0 against those of the C++ study it
// replaced (studies/hard_cases.cpp, whose case list this file's equalled before it was deleted:
// commit 85de2c9): nsbench-study hard --verify reports --rtol 0.
TEST_CASE("built-in study hard: every case run by every registered integrator at its own step; 10^4 impacts with --full only",
          "[studies]") {
  const nsb::StudySpec spec = builtin_spec("studies/builtin/hard.toml");
  const auto& registry = nsb::integrator_registry();
  REQUIRE(spec.problems.size() == 18);
  REQUIRE(spec.integrators.size() == registry.size());
  const auto& hard = *std::find_if(nsb::study_registry().begin(), nsb::study_registry().end(),
                                   [](const nsb::StudyEntry& e) { return e.name == "hard"; });
  CHECK(hard.source == "studies/builtin/hard.toml");
  for (const bool full : {false, true}) {
    INFO("full " << full);
    const auto cases = nsb::study_cases(hard, {full});
    REQUIRE(cases.size() == (full ? 18 : 17) * registry.size());
    std::size_t k = 0;
    for (std::size_t p = 0; p < spec.problems.size(); ++p) {
      if (spec.problems[p].full_only && !full) continue;
      const auto own = nsb::make_problem(spec.problems[p].name, spec.problems[p].parameters)->stable_step();
      for (std::size_t i = 0; i < registry.size(); ++i, ++k) {
        CHECK(cases[k]["problem"] == p);
        CHECK(spec.integrators[cases[k]["integrator"].get<std::size_t>()].name == registry[i].name);
        const nsb::FileSweep& sweep = spec.integrators[i].sweep_for(spec.problems[p].label);
        REQUIRE(sweep.steps.size() + sweep.stable_fractions.size() == 1);  // one run per case
        const double dt = sweep.steps.empty() ? sweep.stable_fractions[0] * own : sweep.steps[0];
        CHECK(cases[k]["dt"].get<double>() == dt);
      }
    }
  }
  // Only the 10^4 impacts is --full only.
  CHECK(std::count_if(spec.problems.begin(), spec.problems.end(), [](const nsb::FileProblem& p) { return p.full_only; }) == 1);
  CHECK(spec.problems[2].label == "10^4 impacts, e = 1");
  CHECK(spec.problems[2].full_only);
}
