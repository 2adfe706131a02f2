// The 0.1.0 problem API kept for one minor version (problems/plugin_compat.hpp): a problem
// that overrides 0.1.0's observe(s, out), exact_state and impact_times is observed and solved
// exactly through the 0.2.0 interface; the built-ins (their own ExactSolution) are not taken
// for 0.1.0 plugins. The warnings: tests/compat/0.1.0, built out of tree (scripts/plugin-example.sh).
#include <catch2/catch.hpp>

#include <string>
#include <typeinfo>

#include "problems/registry.hpp"
#include "problems/rigid_problem.hpp"

namespace {

using namespace nsb;

// A 0.1.0 problem: a free point mass at rest, observed by observe(s, out), exact by exact_state.
class OldProblem final : public RigidProblem {
 public:
  explicit OldProblem(const Params& p) : params_(p) {
    mass_ = Vec::Ones(1);
    load_ = Vec::Zero(1);
    contacts_.normal.resize(0, 1);
    contacts_.gap_offset = Vec::Zero(0);
  }
  static ParamSpecs parameters_spec() { return {}; }
  std::string name() const override { return "old-problem"; }
  const Params& parameters() const override { return params_; }
  State initial_state() const override { return {0.0, Vec::Constant(1, 2.0), Vec::Zero(1)}; }
  std::vector<std::string> observable_names() const override { return {"q"}; }
  void observe(const State& s, std::span<double> out) const override { out[0] = s.u[0]; }
  std::optional<State> exact_state(double t) const override { return State{t, Vec::Constant(1, 2.0), Vec::Zero(1)}; }
  std::vector<double> impact_times(double) const override { return {0.5}; }

 private:
  Params params_;
};

}  // namespace

TEST_CASE("plugin compat 0.1.0: a problem's old overrides are found, the built-ins have none", "[problems][plugin]") {
  STATIC_REQUIRE(compat_0_1::overrides_observe_state<OldProblem>);
  STATIC_REQUIRE(compat_0_1::overrides_exact_state<OldProblem>);
  STATIC_REQUIRE(compat_0_1::overrides_impact_times<OldProblem>);
  STATIC_REQUIRE_FALSE(compat_0_1::overrides_observe_step<OldProblem>);
  for (const auto& entry : problem_registry()) {
    INFO(entry.name);
    const auto problem = make_entry(entry, {});
    // A built-in's exact() is its own, never the 0.1.0 view.
    if (const ExactSolution* exact = problem->exact())
      CHECK(std::string(typeid(*exact).name()).find("LegacyExact") == std::string::npos);
  }
}

TEST_CASE("plugin compat 0.1.0: a problem's observe(s, out) and exact_state run through the new interface",
          "[problems][plugin]") {
  const auto made = make_from_params<Problem, OldProblem>(Params(ParamSpecs{}, {}));
  std::vector<double> out(1);
  made->observe(made->initial_state(), Vec::Zero(0), 0.0, out);
  CHECK(out[0] == 2.0);
  REQUIRE(made->exact() != nullptr);
  CHECK(made->exact()->state(1.0)->u[0] == 2.0);
  CHECK(made->exact()->impact_times(1.0) == std::vector<double>{0.5});
  // A copy's view reads the copy.
  const OldProblem copy = dynamic_cast<const OldProblem&>(*made);
  REQUIRE(copy.exact() != nullptr);
  CHECK(copy.exact()->impact_times(1.0) == std::vector<double>{0.5});
  // Without make_from_params (no 0.1.0 override seen), no view.
  const OldProblem direct(Params(ParamSpecs{}, {}));
  CHECK(direct.exact() == nullptr);
}
