// The report index (studies/report_index.hpp): a study's table ids are its own in the report
// (issue 56: two study files declaring [[table]] id = "runs" into one --out, the second
// replaced the first's runs.* and index.md linked the first's entry to the second's data).
#include "studies/report_index.hpp"

#include <catch2/catch.hpp>

#include "core/parameters.hpp"
#include "studies/study_file.hpp"
#include "tests/support/files.hpp"

namespace {

std::string study_with_table(const std::string& id) {
  return R"([study]
title = "t"
t_end = 0.1

[[problem]]
name = "bouncing-mass"

[[integrator]]
name = "cd-lagrange"
steps = [1e-2]

[reference]
solution = "exact"

[[measure]]
kind = "error"

[[table]]
id = ")" + id + R"("
title = "runs"
columns = ["problem", "integrator", "dt", "outcome"]
)";
}

}  // namespace

TEST_CASE("report index: a table id another study of the report holds, or the index's own, is refused", "[studies][report_index]") {
  const nsb::test::TempDir tmp("report_index_test", true);
  const auto out = tmp.path / "report";
  nsb::run_study_file(nsb::parse_study_text(study_with_table("runs"), "first.toml", false), out);
  const std::string first_runs = nsb::test::read_text(out / "runs.csv");
  REQUIRE_FALSE(first_runs.empty());
  CHECK_THROWS_WITH(nsb::run_study_file(nsb::parse_study_text(study_with_table("runs"), "second.toml", false), out),
                    Catch::StartsWith("study second: table runs is study first's in this report"));
  CHECK_THROWS_WITH(nsb::run_study_file(nsb::parse_study_text(study_with_table("index"), "third.toml", false), out),
                    Catch::StartsWith("study third: table id 'index' is the report's own (index.md)"));
  CHECK(nsb::test::read_text(out / "runs.csv") == first_runs);  // written whole or not at all
  CHECK_FALSE(std::filesystem::exists(out / ".index" / "second.json"));
  // The same study run again keeps its own ids.
  nsb::run_study_file(nsb::parse_study_text(study_with_table("runs"), "first.toml", false), out);
}
