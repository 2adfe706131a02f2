// Generic properties every registered integrator must have on the bouncing mass (a new
// integrator is tested here without editing this file): impulses are non-negative and
// act only on closed or closing contacts; impact times within O(dt) of the exact ones;
// energy in flight i within O(dt) of E0 e^(2i).
#include <catch2/catch.hpp>
#include <cmath>

#include "integrators/registry.hpp"
#include "integrators/run.hpp"
#include "tests/integrators/every_integrator.hpp"
#include "problems/bouncing_mass.hpp"

namespace {

struct Observed {
  std::vector<double> impact_times;
  std::vector<double> flight_energy;  // energy sampled at mid-flight of flight i (i = 1, 2, ...)
  double min_impulse = 0.0;
  long impulses_on_open_gap = 0;
  nsb::ImpactAccuracy accuracy;
};

Observed observe_bounces(const std::string& integrator_name, double e, double dt, int impacts) {
  const nsb::BouncingMass problem(nsb::Params(nsb::BouncingMass::parameters_spec(), {{"e", std::to_string(e)}}));
  auto integrator = nsb::make_integrator(integrator_name);
  integrator->init(problem, problem.initial_state());
  nsb::RunOptions options;
  options.dt = dt;
  options.t_end = problem.impact_time(impacts) + 0.5 * (problem.impact_time(impacts + 1) - problem.impact_time(impacts));
  options.record_series = false;

  Observed obs;
  obs.accuracy = integrator->impact_accuracy();
  const double g = 9.81;
  double q_prev = problem.initial_state().u[0], v_prev = problem.initial_state().v[0];
  bool in_contact = false;
  std::size_t next_mid = 1;
  nsb::run(problem, *integrator, options, [&](const nsb::Integrator& it, const nsb::StepInfo& info) {
    const double lambda = it.impulses()[0];
    const double q = it.state().u[0], v = it.state().v[0];
    obs.min_impulse = std::min(obs.min_impulse, lambda);
    // A contact open at both ends of the step, by more than it can close in one step.
    const double reach = info.dt * std::max(std::abs(v_prev), std::abs(v)) + g * info.dt * info.dt;
    if (lambda != 0.0 && std::min(q_prev, q) > reach) ++obs.impulses_on_open_gap;
    if (lambda > 0.0 && !in_contact) obs.impact_times.push_back(it.state().t);
    in_contact = lambda > 0.0;
    if (next_mid <= static_cast<std::size_t>(impacts) &&
        it.state().t >= 0.5 * (problem.impact_time(next_mid) + problem.impact_time(next_mid + 1))) {
      obs.flight_energy.push_back(it.energy().total());
      ++next_mid;
    }
    q_prev = q;
    v_prev = v;
  });
  return obs;
}

}  // namespace

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
        if (!nsb::testing::init_or_decline(entry, problem)) {
          WARN(entry.name << " declines the bouncing mass with e = " << e);
          continue;
        }
        const Observed obs = observe_bounces(entry.name, e, dt, impacts);
        CHECK(obs.min_impulse >= 0.0);
        CHECK(obs.impulses_on_open_gap == 0);
        REQUIRE(!obs.impact_times.empty());
        // A compliant contact's restitution is its own (tested with the scheme), and with it
        // the later impact times; at e = 1 it must still keep the energy and the timing.
        if (!obs.accuracy.restitution_exact && e < 1.0) continue;
        // The engines' restitution is their own even at e = 1 (nsb::testing::is_engine_peer).
        if (nsb::testing::is_engine_peer(entry.name)) continue;
        REQUIRE(obs.impact_times.size() >= static_cast<std::size_t>(impacts));
        for (int i = 1; i <= impacts; ++i) {
          // Each impact adds at most the phase lag the scheme's own law implies
          // (nsb::ImpactAccuracy: 2 steps for a one-step impulse law).
          const double err = obs.impact_times[i - 1] - problem.impact_time(i);
          CAPTURE(i, err, obs.accuracy.lag_steps);
          CHECK(std::abs(err) <= obs.accuracy.lag_steps * i * dt);
        }
        REQUIRE(obs.flight_energy.size() == static_cast<std::size_t>(impacts));
        for (int i = 1; i <= impacts; ++i) {
          // The phase error above (<= lag_steps dt per impact) changes the impact speed by
          // at most lag_steps g dt per impact, an absolute error carried into flight i whose
          // speed is e^i w1: relative energy error <= 2 * (lag_steps g dt i) / (e^i w1).
          const double rel = std::abs(obs.flight_energy[i - 1] / problem.energy_after_impact(i) - 1.0);
          CAPTURE(i, rel);
          CHECK(rel <= 2.0 * obs.accuracy.lag_steps * 9.81 * dt * i / (std::pow(e, i) * problem.first_impact_speed()));
        }
      }
    }
  }
}
