// Study bouncing-bar (studies/builtin/bouncing-bar.toml): its grid covers every registered
// integrator and mass model, and one case measures what it says (the singular bar solved exactly
// keeps its energy per period, the lumped one loses energy at its plastic node impacts).
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <set>

#include "integrators/registry.hpp"
#include "studies/registry.hpp"
#include "studies/study.hpp"
#include "studies/study_file.hpp"

namespace {

nsb::StudySpec bouncing_bar_spec() {
  const nsb::EmbeddedStudyFile* file = nsb::builtin_study_file("studies/builtin/bouncing-bar.toml");
  REQUIRE(file != nullptr);
  return nsb::parse_study_text(std::string(file->text), "studies/builtin/bouncing-bar.toml", false);
}

std::size_t measure_index(const nsb::StudySpec& spec, const std::string& label) {
  const auto m = std::find_if(spec.measures.begin(), spec.measures.end(), [&](const nsb::FileMeasure& x) { return x.label == label; });
  REQUIRE(m != spec.measures.end());
  return static_cast<std::size_t>(m - spec.measures.begin());
}

}  // namespace

TEST_CASE("bouncing-bar study: every integrator x mass model; N 50..400 and 20 periods by default", "[studies][bouncing-bar]") {
  const nsb::StudySpec spec = bouncing_bar_spec();
  std::set<std::string> integrators, masses, meshes;
  for (const auto& c : nsb::study_cases(nsb::file_study(spec), {})) {
    const nsb::FileProblem& p = spec.problems[c["problem"].get<std::size_t>()];
    integrators.insert(spec.integrators[c["integrator"].get<std::size_t>()].name);
    masses.insert(p.parameters.at("mass"));
    meshes.insert(p.parameters.at("N"));
    CHECK(spec.t_end_of(p) == 1.0 + 20 * (16.0 * (10.0 / 30.0)));
  }
  CHECK(integrators.size() == nsb::integrator_registry().size());
  CHECK(masses == std::set<std::string>{"lumped", "consistent", "singular"});
  CHECK(meshes == std::set<std::string>{"50", "100", "200", "400"});
}

TEST_CASE("bouncing-bar study: energy per period, exact semi-discrete singular bar vs lumped", "[studies][bouncing-bar]") {
  // The file's N = 50 problems at N = 25, run for two periods.
  nsb::StudySpec spec = bouncing_bar_spec();
  spec.t_end = 1.0 + 2 * (16.0 * (10.0 / 30.0));
  for (auto& p : spec.problems)
    if (p.parameters.count("N") && p.parameters.at("N") == "50") p.parameters["N"] = "25";
  const nsb::StudyEntry entry = nsb::file_study(spec);
  const auto run = [&](const std::string& mass) {
    for (const auto& c : nsb::study_cases(entry, {})) {
      const nsb::FileProblem& p = spec.problems[c["problem"].get<std::size_t>()];
      if (spec.integrators[c["integrator"].get<std::size_t>()].name == "modal-exact" && p.parameters.at("N") == "25" &&
          p.parameters.at("mass") == mass)
        return nsb::run_study_case(entry, c, {});
    }
    FAIL("no modal-exact case on the " << mass << " bar at N = 25");
    throw;
  };
  const auto singular = run("singular"), lumped = run("lumped");
  REQUIRE(singular["status"] == "ok");
  REQUIRE(lumped["status"] == "ok");
  const nsb::Json& es = singular["run"]["periodic"]["E err end"];
  const nsb::Json& el = lumped["run"]["periodic"]["E err end"];
  REQUIRE(es.size() == 2);
  REQUIRE(el.size() == 2);
  for (const auto& e : es) CHECK(std::abs(e.get<double>()) < 1e-9);
  CHECK(el[1].get<double>() < el[0].get<double>());
  CHECK(el[0].get<double>() < -1e-3);
  CHECK(singular["values"][measure_index(spec, "periods")].get<double>() == 2.0);
  // Over the first period the contact end follows the exact one to within the mesh's error.
  CHECK(singular["values"][measure_index(spec, "u max err 1")].get<double>() < 0.2);
  CHECK(singular["values"][measure_index(spec, "force osc.")].get<double>() > 0.0);
}
