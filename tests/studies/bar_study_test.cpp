// Study bar: the space-time stress table (figure bar_space_time). Its exact panel is the
// d'Alembert stress at the element centres, and a scheme's rows start from the initial
// state's element stress and follow every step.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "problems/signorini_bar.hpp"
#include "studies/study.hpp"
#include "tests/support/registered_study.hpp"

namespace {
const nsb::StudyEntry& bar_study() { return nsb::test::registered_study("bar"); }
}  // namespace

TEST_CASE("bar study: space-time stress of the exact solution and of a scheme from its initial state", "[studies][bar]") {
  // One block of the grid (the study's meshes for cd-lagrange, lumped, alpha = 0.9): the N = 50
  // case run, the others given as declined (their rows are not looked at).
  std::vector<nsb::Json> cases, results;
  for (const auto& c : nsb::study_cases(bar_study(), {}))
    if (c["integrator"] == "cd-lagrange" && c["mass"] == "lumped" && c["alpha"] == 0.9) {
      cases.push_back(c);
      results.push_back(c["N"] == 50 ? nsb::run_study_case(bar_study(), c, {})
                                     : nsb::Json{{"status", "n/a"}, {"dt", 0.0}, {"message", "not run here"}});
    }
  REQUIRE(cases.size() >= 2);
  const auto tables = nsb::study_tables(bar_study(), cases, results, {});
  const auto it = std::find_if(tables.begin(), tables.end(), [](const nsb::Table& t) { return t.id == "bar_space_time"; });
  REQUIRE(it != tables.end());
  const nsb::Table& t = *it;
  REQUIRE(t.figures.size() == 1);
  const auto& positions = t.figures[0].positions;
  REQUIRE(positions.size() == 50);
  REQUIRE(t.columns.size() == 3 + positions.size());

  const nsb::SignoriniBar bar(nsb::Params(nsb::SignoriniBar::parameters_spec(), {{"N", "50"}, {"mass", "lumped"}}));
  Eigen::MatrixXd initial(50, static_cast<nsb::Index>(bar.field_mesh()->stress_components.size()));
  bar.cell_stress(bar.initial_state().u, initial);
  long exact_rows = 0, scheme_rows = 0, compressed = 0;
  for (const auto& row : t.rows) {
    const std::string who = std::get<std::string>(row[0]);
    const double time = std::get<double>(row[2]);
    for (std::size_t e = 0; e < positions.size(); ++e) {
      const double sigma = std::get<double>(row[3 + e]);
      if (who == "exact") {
        CHECK(sigma == bar.exact_stress(positions[e], time));
        compressed += sigma < 0.0;
      } else if (scheme_rows == 0) {
        CHECK(time == 0.0);
        CHECK(sigma == initial(static_cast<nsb::Index>(e), 0));
      }
    }
    if (who == "exact") ++exact_rows;
    else ++scheme_rows;
  }
  CHECK(exact_rows == 301);
  CHECK(compressed > 0);  // the wave is in the picture
  // Every step after the initial state: the run's steps + 1 rows.
  const auto& r = results[static_cast<std::size_t>(std::find_if(cases.begin(), cases.end(), [](const nsb::Json& c) {
                            return c["N"] == 50;
                          }) - cases.begin())];
  CHECK(scheme_rows == r["steps"].get<long>() + 1);
}
