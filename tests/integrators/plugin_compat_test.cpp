// The 0.1.0 integrator API kept for one minor version (integrators/plugin_compat.hpp): the
// overrides are found by the class that declares them, a new-style scheme has none, and a
// 0.1.0 scheme's capability overrides reach what its entry declares. The deprecation warnings
// themselves are checked where a plugin author sees them, in an out-of-tree build of
// tests/compat/0.1.0 (scripts/plugin-example.sh).
#include <catch2/catch.hpp>

#include "integrators/registry.hpp"

namespace {

using namespace nsb;

// A 0.1.0 scheme: it names itself, declares its stability and friction by overrides and keeps
// the time and the step count in step().
class OldScheme final : public Integrator {
 public:
  explicit OldScheme(const Params& p) : Integrator(p) {}
  static ParamSpecs parameters_spec() { return {}; }
  std::string name() const override { return "old-scheme"; }
  bool conditionally_stable() const override { return true; }
  bool treats_friction() const override { return true; }
  void init(const Problem& problem, const State& initial) override { bind(problem, initial); }
  StepInfo step(double h) override {
    state_.t += h;
    ++work_.steps;
    return {.dt = h};
  }
};

class NewScheme final : public Integrator {
 public:
  explicit NewScheme(const Params& p) : Integrator(p) {}
  static ParamSpecs parameters_spec() { return {}; }
  void init(const Problem& problem, const State& initial) override { bind(problem, initial); }
  StepInfo advance(double h) override { return {.dt = h}; }
};

}  // namespace

TEST_CASE("plugin compat 0.1.0: an integrator's old overrides are found, a new scheme has none", "[integrators][plugin]") {
  STATIC_REQUIRE(compat_0_1::overrides_name<OldScheme>);
  STATIC_REQUIRE(compat_0_1::overrides_conditionally_stable<OldScheme>);
  STATIC_REQUIRE(compat_0_1::overrides_treats_friction<OldScheme>);
  STATIC_REQUIRE(compat_0_1::overrides_step<OldScheme>);
  STATIC_REQUIRE_FALSE(compat_0_1::overrides_name<NewScheme>);
  STATIC_REQUIRE_FALSE(compat_0_1::overrides_conditionally_stable<NewScheme>);
  STATIC_REQUIRE_FALSE(compat_0_1::overrides_treats_friction<NewScheme>);
  STATIC_REQUIRE_FALSE(compat_0_1::overrides_step<NewScheme>);
}

TEST_CASE("plugin compat 0.1.0: the capability overrides reach the entry's declaration", "[integrators][plugin]") {
  const IntegratorEntry old_entry{"old-scheme", "", &OldScheme::parameters_spec,
                                  &make_from_params<Integrator, OldScheme>, false};
  const auto old_scheme = old_entry.make(Params(ParamSpecs{}, {}));
  CHECK(old_scheme->capabilities().explicit_step);
  CHECK(old_scheme->capabilities().friction);
  CHECK(old_scheme->name() == "old-scheme");
  const IntegratorEntry new_entry{"new-scheme", "", &NewScheme::parameters_spec,
                                  &make_from_params<Integrator, NewScheme>, false};
  const auto new_scheme = new_entry.make(Params(ParamSpecs{}, {}));
  CHECK_FALSE(new_scheme->capabilities().explicit_step);
  CHECK_FALSE(new_scheme->capabilities().friction);
}
