#include <catch2/catch.hpp>
#include <cmath>

#include "integrators/cd_lagrange.hpp"
#include "run/run.hpp"
#include "problems/bouncing_mass.hpp"

using Catch::Detail::Approx;

namespace {
nsb::BouncingMass mass_with(double e, double h0 = 1.0) {
  return nsb::BouncingMass(nsb::Params(nsb::BouncingMass::parameters_spec(),
                                       {{"e", std::to_string(e)}, {"h0", std::to_string(h0)}}));
}
nsb::CdLagrange cd() { return nsb::CdLagrange(nsb::Params(nsb::CdLagrange::parameters_spec())); }
}  // namespace

TEST_CASE("cd-lagrange: discrete energy is exact in free flight under gravity", "[integrators][cd-lagrange]") {
  const auto problem = mass_with(1.0, 100.0);
  auto integ = cd();
  integ.init(problem, problem.initial_state());
  integ.step(1e-2);
  const double E_first = integ.energy().total();
  for (int k = 0; k < 300; ++k) integ.step(1e-2);
  REQUIRE(integ.impulses()[0] == 0.0);
  CHECK(integ.energy().total() == Approx(E_first).epsilon(1e-13));
}

TEST_CASE("cd-lagrange: impulse only on a closed gap, Newton restitution on the first contact step",
          "[integrators][cd-lagrange][contact]") {
  for (double e : {1.0, 0.7, 0.0}) {
    const auto problem = mass_with(e);
    auto integ = cd();
    integ.init(problem, problem.initial_state());
    int impacts = 0;
    bool was_in_contact = false;
    for (int k = 0; k < 20000 && impacts < 4; ++k) {
      const double v_before = integ.state().v[0];
      integ.step(1e-3);
      const double lambda = integ.impulses()[0];
      const double gap = integ.state().u[0];
      if (gap > 0.0) REQUIRE(lambda == 0.0);
      if (lambda > 0.0 && !was_in_contact && v_before < 0.0) {
        ++impacts;
        // P_{k+3/2} = P_free + Lambda with Lambda = -m (g'_free + e g'_{k+1/2}).
        CHECK(integ.state().v[0] == Approx(-e * v_before).margin(1e-12));
      }
      was_in_contact = lambda > 0.0;
    }
    CHECK(impacts >= (e > 0.0 ? 4 : 1));
  }
}

TEST_CASE("cd-lagrange: the mass comes to rest after the Zeno time with bounded penetration",
          "[integrators][cd-lagrange][contact]") {
  const auto problem = mass_with(0.5);
  auto integ = cd();
  integ.init(problem, problem.initial_state());
  const double dt = 1e-4;
  nsb::RunOptions opt{dt, problem.zeno_time() + 0.5, 1, false};
  const auto r = nsb::run(problem, integ, opt);
  CHECK(r.status == nsb::RunStatus::Ok);
  // Penetration before the contact acts is at most one step of travel at impact speed.
  CHECK(r.max_penetration <= dt * problem.first_impact_speed() * 1.01);
  CHECK(std::abs(integ.state().v[0]) <= 9.81 * dt);
  CHECK(integ.impulses()[0] == Approx(9.81 * dt).epsilon(1e-9));  // holds the weight m g dt
}
