// Study bodies: a few of its cases, run as the study runs them. On the touching cradle the
// complementarity schemes give Moreau's simultaneous outcome in the verdict column (and the
// sequential one with gaps); a scheme that declines the problem is one n/a row with its reason;
// CD-Lagrange on two blocks keeps the momentum identity and iterates its LCP only together.
#include <catch2/catch.hpp>
#include <string>

#include "studies/study.hpp"
#include "tests/support/registered_study.hpp"

namespace {
const nsb::StudyEntry& bodies_study() { return nsb::test::registered_study("bodies"); }

// The tables of the given cases, run.
std::vector<nsb::Table> tables_of(const std::vector<nsb::Json>& cases) {
  std::vector<nsb::Json> results;
  for (const auto& c : cases) results.push_back(nsb::run_study_case(bodies_study(), c, {}));
  return nsb::study_tables(bodies_study(), cases, results, {});
}

const nsb::Table& table_with_id(const std::vector<nsb::Table>& tables, const std::string& id) {
  const auto t = std::find_if(tables.begin(), tables.end(), [&](const nsb::Table& x) { return x.id == id; });
  REQUIRE(t != tables.end());
  return *t;
}

std::size_t column_named(const nsb::Table& t, const std::string& name) {
  for (std::size_t i = 0; i < t.columns.size(); ++i)
    if (t.columns[i].name == name) return i;
  FAIL("no column " << name);
  return 0;
}
}  // namespace

TEST_CASE("bodies study: the touching cradle gives Moreau's outcome, the cradle with gaps the sequential one",
          "[studies][bodies]") {
  for (const std::string integrator : {"cd-lagrange", "moreau-jean"}) {
    SECTION(integrator) {
      const auto tables = tables_of({{{"case", "cradle-touching-e1"}, {"integrator", integrator}, {"knob", 1e-3}},
                                     {{"case", "cradle-gap-e05"}, {"integrator", integrator}, {"knob", 0.1}}});
      const nsb::Table& cradle = table_with_id(tables, "bodies_cradle");
      REQUIRE(cradle.rows.size() == 2);
      const std::size_t verdict = column_named(cradle, "verdict"), d_sim = column_named(cradle, "d simultaneous");
      CHECK(std::get<std::string>(cradle.rows[0][verdict]) == "simultaneous");
      CHECK(std::get<double>(cradle.rows[0][d_sim]) <= 1e-10);
      CHECK(std::get<std::string>(cradle.rows[1][verdict]) == "sequential");
    }
  }
}

TEST_CASE("bodies study: a declining scheme is one n/a row with its reason", "[studies][bodies]") {
  std::vector<nsb::Json> cases;
  for (const auto& c : nsb::study_cases(bodies_study(), {}))
    if (c["integrator"] == "event-driven" && c["case"].get<std::string>().rfind("cradle", 0) == 0) cases.push_back(c);
  REQUIRE(cases.size() == 10);
  const auto tables = tables_of(cases);
  const nsb::Table& cradle = table_with_id(tables, "bodies_cradle");
  REQUIRE(cradle.rows.size() == 1);
  const auto& row = cradle.rows[0];
  CHECK(std::get<std::string>(row[0]) == "event-driven");
  CHECK(std::get<std::string>(row[1]) == "n/a");
  CHECK_THAT(std::get<std::string>(row.back()), Catch::Contains("needs node-to-rigid contacts"));
}

TEST_CASE("bodies study: cd-lagrange on two blocks keeps the momentum identity, iterates its LCP only together",
          "[studies][bodies]") {
  const auto r = nsb::run_study_case(bodies_study(), {{"case", "blocks"}, {"integrator", "cd-lagrange"}, {"knob", 1e-4}}, {});
  REQUIRE(r["status"] == "ok");
  CHECK(r["p_residual"].get<double>() <= 1e-14);
  CHECK(r["between"].get<double>() > 1.0);  // the upper block did land on the lower one
  CHECK(r["e_gain"].get<double>() <= 1e-12);
  CHECK(r["lcp_step"].get<double>() > 1.0);
  CHECK(r["lcp_apart"].get<double>() == 0.0);  // apart: the closed form, no iteration
}
