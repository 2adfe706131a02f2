#include "reference/penalty.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <fmt/format.h>

#include "problems/block_2d.hpp"
#include "problems/bouncing_mass.hpp"
#include "reference/event_driven.hpp"
#include "studies/study.hpp"

using nsb::BouncingMass;
using nsb::Params;
using nsb::PenaltyBdf;

namespace {

BouncingMass make(const std::map<std::string, std::string>& p) { return BouncingMass(Params(BouncingMass::parameters_spec(), p)); }

template <class I>
void advance(I& integrator, double t_end, double dt) {
  while (integrator.state().t < t_end - 1e-12) integrator.step(std::min(dt, t_end - integrator.state().t));
}

}  // namespace

TEST_CASE("penalty-bdf: the damping ratio gives the clamped spring-dashpot the requested restitution",
          "[reference][penalty]") {
  for (double e : {1.0, 0.9, 0.5, std::exp(-2.0), 0.05, 1e-3}) {
    CAPTURE(e);
    CHECK(PenaltyBdf::restitution(PenaltyBdf::damping_ratio(e)) == Approx(e).epsilon(1e-10));
  }
  // The under- and over-damped closed forms meet at critical damping.
  CHECK(PenaltyBdf::restitution(1.0 - 1e-7) == Approx(std::exp(-2.0)).epsilon(1e-6));
  CHECK(PenaltyBdf::restitution(1.0 + 1e-7) == Approx(std::exp(-2.0)).epsilon(1e-6));
}

TEST_CASE("penalty-bdf: an isolated contact rebounds with the problem's restitution", "[reference][penalty]") {
  // Gravity 1e-6 m/s^2: its effect on the rebound, g / (omega v) = 1e-11, is negligible.
  for (double e : {1.0, 0.7, 0.1}) {
    CAPTURE(e);
    const BouncingMass p = make({{"e", std::to_string(e)}, {"g", "1e-6"}, {"h0", "1e-3"}, {"v0", "-1"}});
    PenaltyBdf pen(Params(PenaltyBdf::parameters_spec(), {{"rtol", "1e-10"}}));
    pen.init(p, p.initial_state());
    // Contact from 1e-3 s for about 3e-5 s. The impulses (left out of CVODE's error test)
    // add up to the momentum change m (1 + e) |v0|.
    double impulse = 0.0;
    while (pen.state().t < 2e-3 - 1e-12) {
      pen.step(1e-4);
      CHECK(pen.impulses().minCoeff() >= 0.0);
      impulse += pen.impulses().sum();
    }
    CHECK(pen.state().v[0] == Approx(e).epsilon(1e-6));
    CHECK(impulse == Approx(1.0 + e).epsilon(1e-6));
    CHECK(pen.work().extra.at("switches") == 2);
  }
}

TEST_CASE("penalty-bdf converges to the event-driven reference as the penalty stiffens, at rate 1/2 in k",
          "[reference][penalty]") {
  // The contact lasts ~ pi sqrt(m / k) and shifts every later flight by about that much:
  // the state error after a few impacts is O(k^-1/2), the next term O(k^-1) (gravity during
  // the contact, g / (omega v) ~ 2e-3 at k = 1e6) bends the fitted slope by about that.
  const BouncingMass p = make({{"e", "0.9"}});
  const double T = 0.5 * (p.impact_time(3) + p.impact_time(4));  // mid-flight after 3 impacts
  nsb::EventDriven ed(Params(nsb::EventDriven::parameters_spec(), {}));
  ed.init(p, p.initial_state());
  advance(ed, T, 0.01);
  std::vector<double> ks = {1e6, 1e7, 1e8, 1e9}, errors;
  for (double k : ks) {
    PenaltyBdf pen(Params(PenaltyBdf::parameters_spec(), {{"stiffness", fmt::format("{}", k)}, {"rtol", "1e-11"}, {"atol", "1e-14"}}));
    pen.init(p, p.initial_state());
    advance(pen, T, 0.01);
    errors.push_back(std::abs(pen.state().u[0] - ed.state().u[0]) + std::abs(pen.state().v[0] - ed.state().v[0]));
  }
  for (std::size_t i = 1; i < errors.size(); ++i) CHECK(errors[i] < errors[i - 1]);
  // fitted_order works on steps h; here h = k^-1.
  std::vector<double> compliance;
  for (double k : ks) compliance.push_back(1.0 / k);
  const double rate = nsb::fitted_order(compliance, errors);
  CAPTURE(errors, rate);
  CHECK(std::abs(rate - 0.5) <= 0.05);
}

TEST_CASE("penalty-bdf on the block: no contact is lost at a switch, so the energy never rises above E0",
          "[reference][penalty]") {
  // The hard study's block cases (8 x 4, e = 0: the dashpots are at the damping cap). Before
  // the fix a contact switched on at a root where its gap was exactly zero, CVODE restarted
  // with a first step of 1e-17 s (below the resolution of t) and reported the same root
  // again, the contact was switched off while still closing, and it sank 3.4 mm into the
  // floor unseen until the next output: switched on there, its spring held 23 E0.
  for (double alpha : {0.9, 1.01, 2.0}) {
    CAPTURE(alpha);
    const nsb::Block2d b(Params(nsb::Block2d::parameters_spec(), {}));
    PenaltyBdf pen(Params(PenaltyBdf::parameters_spec(), {}));
    pen.init(b, b.initial_state());
    const double E0 = pen.energy().total();
    const double dt = alpha * b.stable_step();
    double growth = 0.0, penetration = 0.0;
    while (pen.state().t < 0.3) {
      pen.step(dt);
      growth = std::max(growth, pen.energy().total() - E0);
      const nsb::Vec g = b.gap_operator() * pen.state().u + b.gap_offset();
      penetration = std::max(penetration, -g.minCoeff());
    }
    // The penalty model dissipates (dashpots, clamping): E <= E0 up to the tolerances.
    CHECK(growth <= 1e-6 * E0);
    // Static penetration m_i g / k ~ 1e-9 m, dynamic ~ v sqrt(m_i / k) ~ 1e-5 m.
    CHECK(penetration < 1e-4);
    CHECK(pen.work().extra.at("missed_switches") == 0);
    // Every root switched its contact: none was reported again after its restart.
    CHECK(pen.work().extra.at("unconfirmed_roots") == 0);
  }
}
