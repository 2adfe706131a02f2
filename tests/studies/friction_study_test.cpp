// Study friction: a few of its cases, run as the study runs them. The friction schemes stop
// the sliding mass within two steps of the exact stop time and hold it below the friction
// angle without creeping; a scheme without friction gives one n/a row naming mu.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <string>

#include "studies/study.hpp"
#include "tests/support/registered_study.hpp"

namespace {
const nsb::StudyEntry& friction_study() { return nsb::test::registered_study("friction"); }

nsb::Json run(const std::string& the_case, const std::string& integrator, double dt) {
  return nsb::run_study_case(friction_study(), {{"case", the_case}, {"integrator", integrator}, {"dt", dt}}, {});
}
}  // namespace

TEST_CASE("friction study: the stop time within two steps, no creep while sticking", "[studies][friction]") {
  const double dt = 1e-3, g = 9.81;
  for (const std::string integrator : {"cd-lagrange", "moreau-jean"}) {
    SECTION(integrator) {
      const auto slide = run("slide-stop", integrator, dt);
      REQUIRE(slide["status"] == "ok");
      CHECK(slide["t_stop_err"].get<double>() <= 2 * dt);
      CHECK(slide["energy_gain"].get<double>() <= 1e-15);

      const auto stick = run("stick", integrator, dt);
      REQUIRE(stick["status"] == "ok");
      CHECK(stick["steps"].get<long>() == 100000);
      CHECK(stick["late_creep"].get<double>() == 0.0);
      if (integrator == "moreau-jean") {
        CHECK(stick["creep"].get<double>() == 0.0);
      } else {
        // CD-Lagrange's start-up half kick moves the mass by tau^2/2 g sin(alpha) along the
        // slope before the first contact impulse; it never moves again.
        const double t_end = 1e5 * dt, start = 0.5 * dt * dt * g * std::sin(20.0 * std::numbers::pi / 180.0);
        CHECK(stick["creep"].get<double>() * t_end == Approx(start).epsilon(1e-9));
      }
    }
  }
}

TEST_CASE("friction study: a scheme without friction is one n/a row naming mu", "[studies][friction]") {
  std::vector<nsb::Json> cases, results;
  for (const auto& c : nsb::study_cases(friction_study(), {}))
    if (c["integrator"] == "schatzman-paoli" && c["case"] == "slide-stop") {
      cases.push_back(c);
      results.push_back(nsb::run_study_case(friction_study(), c, {}));
      CHECK(results.back()["status"] == "n/a");
    }
  REQUIRE(cases.size() == 3);
  const auto tables = nsb::study_tables(friction_study(), cases, results, {});
  const auto sliding = std::find_if(tables.begin(), tables.end(), [](const nsb::Table& t) { return t.id == "friction_sliding"; });
  REQUIRE(sliding != tables.end());
  REQUIRE(sliding->rows.size() == 1);
  const auto& row = sliding->rows[0];
  CHECK(std::get<std::string>(row[0]) == "schatzman-paoli");
  CHECK(std::get<std::string>(row[1]) == "n/a");
  CHECK_THAT(std::get<std::string>(row.back()), Catch::Contains("mu = 0.8"));
}
