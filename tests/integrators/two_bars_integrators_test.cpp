// Every integrator on the two bars (problems/two_bars.hpp): a contact row with entries on two
// bodies. Lumped mass, L1 = 1, L2 = 2, N1 = 50, N2 = 100 (h = 0.02), dt = 0.9 h/c.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/two_bars.hpp"
#include "tests/integrators/every_integrator.hpp"

namespace {

nsb::TwoBars make_two_bars(const std::string& mass) {
  return nsb::TwoBars(nsb::Params(nsb::TwoBars::parameters_spec(),
                                  {{"L1", "1"}, {"L2", "2"}, {"N1", "50"}, {"N2", "100"}, {"mass", mass}}));
}

}  // namespace

TEST_CASE("every integrator on two bars: contact duration 2 L1/c within 3 h/c, bar 1 left at rest within "
          "2 v0 c dt / L1, momentum conserved; or an InputError",
          "[integrators][two-bars]") {
  const auto p = make_two_bars("lumped");
  const double h = p.element_size(1), c = p.wave_speed(), v0 = 1.0, L1 = 1.0;
  const double dt = 0.9 * h / c, level = p.contact_force_level();
  for (const auto& entry : nsb::integrator_registry()) {
    DYNAMIC_SECTION(entry.name) {
      auto integ = nsb::testing::init_or_decline(entry, p);
      if (!integ) {
        SUCCEED("declined");  // e.g. event-driven and modal-exact: node-to-rigid contacts only
        continue;
      }
      const double P0 = p.momentum(integ->state().v);
      // The contact: from the first step with an impulse (its start) to the last step whose
      // force impulse/dt is at least half the level F0 (its end): the exact force is F0 on
      // (0, 2 L1/c) and the discrete one crosses F0/2 at the smeared fronts. After 2 L1/c the
      // gap stays closed with F = 0 until bar 2's pulse returns (2 L2/c = 4); the schemes leave
      // small impulses there (chatter well below F0/2): not counted. t_end = 4.5: the gap has
      // opened.
      double start = NAN, end = NAN;
      const auto r = nsb::run(p, *integ, {dt, 4.5, 1, false}, [&](const nsb::Integrator& it, const nsb::StepInfo& info) {
        const double lambda = it.impulses()[0], t = it.state().t;
        if (lambda > 0.0 && std::isnan(start)) start = t - info.dt;
        if (lambda >= 0.5 * level * info.dt && t < 3.0) end = t;
      });
      REQUIRE(r.status == nsb::RunStatus::Ok);
      REQUIRE(!std::isnan(end));
      CAPTURE(start, end);
      // Measured at N = 50: |error| <= 1.9 dt = 1.7 h/c for the fixed-step schemes. The
      // adaptive CD-Lagrange collapses its step to tau_min after the impact and ends the
      // contact 0.36 late (20 h/c; 0.12 at N = 100): it is held to converging, below.
      const double error = end - start - 2.0 * L1 / c;
      if (entry.name == "cd-lagrange-adaptive") CHECK(std::abs(error) <= 0.5 * L1 / c);
      else CHECK(std::abs(error) <= 3.0 * h / c);
      // Bar 1's residual velocity: measured 0.15 to 0.55 v0 c dt / L1, newmark-lm 1.6.
      const double v1 = p.mean_velocity(1, integ->state().v);
      CAPTURE(v1);
      CHECK(std::abs(v1) <= 2.0 * v0 * c * dt / L1);
      // No external force: the impulses are internal, the momentum stays (round-off).
      CHECK(std::abs(p.momentum(integ->state().v) - P0) <= 1e-11 * p.exact_momentum());
    }
  }
}

TEST_CASE("singular mass on both bars: cd-lagrange declines (a contact on massless dofs of two bodies)",
          "[integrators][cd-lagrange][two-bars]") {
  const auto p = make_two_bars("singular");
  auto integ = nsb::make_integrator("cd-lagrange");
  try {
    integ->init(p, p.initial_state());
    FAIL("cd-lagrange accepted a contact row on two massless dofs");
  } catch (const nsb::InputError& e) {
    CHECK(std::string(e.what()).find("contacts on that dof only") != std::string::npos);
  }
}

TEST_CASE("singular mass on both bars: the schemes that accept it keep the momentum and leave bar 1 at rest",
          "[integrators][two-bars]") {
  // Measured: moreau-jean, newmark-lm and nsga accept it (W or the iteration matrix stays
  // regular for massless dofs); the explicit schemes need M^{-1} and decline.
  const auto p = make_two_bars("singular");
  const double dt = 0.9 * p.stable_step(), v0 = 1.0, c = p.wave_speed();
  for (const auto& entry : nsb::integrator_registry()) {
    DYNAMIC_SECTION(entry.name) {
      auto integ = nsb::testing::init_or_decline(entry, p);
      if (!integ) {
        SUCCEED("declined");
        continue;
      }
      const double P0 = p.momentum(integ->state().v);
      const auto r = nsb::run(p, *integ, {dt, 4.5, 1, false});
      REQUIRE(r.status == nsb::RunStatus::Ok);
      CHECK(std::abs(p.momentum(integ->state().v) - P0) <= 1e-11 * p.exact_momentum());
      CHECK(std::abs(p.mean_velocity(1, integ->state().v)) <= 2.0 * v0 * c * dt);
    }
  }
}
