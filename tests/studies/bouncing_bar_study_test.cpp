// Study bouncing-bar: its grid covers every registered integrator and mass model, and one case
// measures what it says (the singular bar solved exactly keeps its energy per period, the
// lumped one loses energy at its plastic node impacts).
#include <catch2/catch.hpp>
#include <cmath>
#include <set>

#include "integrators/registry.hpp"
#include "studies/study.hpp"
#include "tests/support/registered_study.hpp"

namespace {
const nsb::StudyEntry& bouncing_bar_study() { return nsb::test::registered_study("bouncing-bar"); }
}  // namespace

TEST_CASE("bouncing-bar study: every integrator x mass model; N 50..400 and 20 periods by default", "[studies][bouncing-bar]") {
  const auto cases = nsb::study_cases(bouncing_bar_study(), {});
  std::set<std::string> integrators, masses;
  std::set<long> meshes;
  for (const auto& c : cases) {
    integrators.insert(c["integrator"].get<std::string>());
    masses.insert(c["mass"].get<std::string>());
    meshes.insert(c["N"].get<long>());
    CHECK(c["periods"].get<int>() == 20);
  }
  CHECK(integrators.size() == nsb::integrator_registry().size());
  CHECK(masses == std::set<std::string>{"lumped", "consistent", "singular"});
  CHECK(meshes == std::set<long>{50, 100, 200, 400});
}

TEST_CASE("bouncing-bar study: energy per period, exact semi-discrete singular bar vs lumped", "[studies][bouncing-bar]") {
  const auto run = [](const std::string& mass) {
    return nsb::run_study_case(bouncing_bar_study(), {{"integrator", "modal-exact"}, {"mass", mass}, {"N", 25L}, {"alpha", 0.9}, {"periods", 2}}, {});
  };
  const auto singular = run("singular"), lumped = run("lumped");
  REQUIRE(singular["status"] == "ok");
  REQUIRE(lumped["status"] == "ok");
  REQUIRE(singular["e_period"].size() == 2);
  REQUIRE(lumped["e_period"].size() == 2);
  for (const auto& e : singular["e_period"]) CHECK(std::abs(e.get<double>()) < 1e-9);
  CHECK(lumped["e_period"][1].get<double>() < lumped["e_period"][0].get<double>());
  CHECK(lumped["e_period"][0].get<double>() < -1e-3);
  // Over the first period the contact end follows the exact one to within the mesh's error.
  CHECK(singular["u_max1"].get<double>() < 0.2);
  CHECK(singular["force_osc"].get<double>() > 0.0);
}
