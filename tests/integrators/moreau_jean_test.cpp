#include <catch2/catch.hpp>
#include <cmath>

#include "integrators/moreau_jean.hpp"
#include "integrators/run.hpp"
#include "problems/bouncing_mass.hpp"

using Catch::Detail::Approx;

namespace {
nsb::BouncingMass mass_with(double e, double h0 = 1.0) {
  return nsb::BouncingMass(nsb::Params(nsb::BouncingMass::parameters_spec(),
                                       {{"e", std::to_string(e)}, {"h0", std::to_string(h0)}}));
}
nsb::MoreauJean mj(double theta) {
  return nsb::MoreauJean(nsb::Params(nsb::MoreauJean::parameters_spec(), {{"theta", std::to_string(theta)}}));
}
}  // namespace

TEST_CASE("moreau-jean: free flight under gravity, theta = 1/2 exact, theta = 1 first order",
          "[integrators][moreau-jean]") {
  const auto problem = mass_with(1.0, 100.0);
  const double h = 1e-2;
  for (double theta : {0.5, 1.0}) {
    auto integ = mj(theta);
    integ.init(problem, problem.initial_state());
    for (int k = 0; k < 300; ++k) integ.step(h);
    const auto exact = *problem.exact_state(integ.state().t);
    CHECK(integ.state().v[0] == Approx(exact.v[0]).epsilon(1e-12));
    // Trapezoidal position update is exact for constant acceleration; theta = 1 is off by
    // (1/2) g h t.
    const double expected_error = theta == 0.5 ? 0.0 : 0.5 * 9.81 * h * integ.state().t;
    CHECK(exact.u[0] - integ.state().u[0] == Approx(expected_error).margin(1e-9));
  }
}

TEST_CASE("moreau-jean: impulse only on the predicted-active set, Newton restitution in one step",
          "[integrators][moreau-jean][contact]") {
  for (double theta : {0.5, 0.75, 1.0}) {
    for (double e : {1.0, 0.6, 0.0}) {
      const auto problem = mass_with(e);
      auto integ = mj(theta);
      integ.init(problem, problem.initial_state());
      const double h = 1e-3;
      int impacts = 0;
      for (int k = 0; k < 20000 && impacts < 3; ++k) {
        const double q = integ.state().u[0], v = integ.state().v[0];
        integ.step(h);
        const double lambda = integ.impulses()[0];
        CHECK(lambda >= 0.0);
        if (q + h * (1 - theta) * v > 0.0) REQUIRE(lambda == 0.0);
        if (lambda > 0.0 && v < 0.0) {
          ++impacts;
          CHECK(integ.state().v[0] == Approx(-e * v).margin(1e-12));
        }
      }
      CHECK(impacts >= 1);
    }
  }
}
