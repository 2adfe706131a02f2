// Generic properties every registered integrator must have on the bouncing mass (a new
// integrator is tested here without editing this file): impulses are non-negative and
// act only on closed or closing contacts; impact times within O(dt) of the exact ones;
// energy in flight i within O(dt) of E0 e^(2i). The measurements are the library's
// (check/conformance.hpp), which `nsbench check` runs on plugins.
#include <catch2/catch.hpp>
#include <cmath>

#include "check/conformance.hpp"
#include "integrators/registry.hpp"
#include "problems/bouncing_mass.hpp"
#include "tests/integrators/every_integrator.hpp"

TEST_CASE("every integrator: contact law, impact times and flight energies on the bouncing mass",
          "[integrators][contact]") {
  const int impacts = 5;
  const double dt = 1e-4;
  for (const auto& entry : nsb::integrator_registry()) {
    for (double e : {1.0, 0.9, 0.5}) {
      DYNAMIC_SECTION(entry.name << " e=" << e) {
        const nsb::BouncingMass problem(nsb::Params(nsb::BouncingMass::parameters_spec(), {{"e", std::to_string(e)}}));
        // A scheme without a velocity-level impact law declines a restitution it cannot
        // honour (InputError at init, e.g. newmark-lm); it is tested on its own problems.
        if (!nsb::init_or_decline(entry, problem)) {
          WARN(entry.name << " declines the bouncing mass with e = " << e);
          continue;
        }
        const nsb::BounceObservation obs = nsb::observe_bounces(entry, problem, dt, impacts);
        CHECK(obs.min_impulse >= 0.0);
        CHECK(obs.impulses_on_open_gap == 0);
        REQUIRE(!obs.impact_times.empty());
        // A compliant contact's restitution is its own (tested with the scheme), and with it
        // the later impact times; at e = 1 it must still keep the energy and the timing.
        if (!obs.accuracy.restitution_exact && e < 1.0) continue;
        // The engines' restitution is their own even at e = 1 (nsb::testing::is_engine_peer).
        if (nsb::testing::is_engine_peer(entry.name)) continue;
        REQUIRE(obs.impact_times.size() >= static_cast<std::size_t>(impacts));
        REQUIRE(obs.flight_energy.size() == static_cast<std::size_t>(impacts));
        // Errors over bounds (nsb::bounce_ratios): impact i lags at most lag_steps i dt, and the
        // flight energy follows within the speed error that lag implies.
        const nsb::BounceRatios r = nsb::bounce_ratios(obs, problem, dt, impacts);
        CAPTURE(obs.accuracy.lag_steps, r.impact_time, r.flight_energy);
        CHECK(r.impact_time <= 1.0);
        CHECK(r.flight_energy <= 1.0);
      }
    }
  }
}
