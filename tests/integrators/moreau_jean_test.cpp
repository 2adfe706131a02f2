#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "integrators/moreau_jean.hpp"
#include "run/run.hpp"
#include "problems/bouncing_mass.hpp"

using Catch::Detail::Approx;

namespace {
nsb::BouncingMass mj_mass_with(double e, double h0 = 1.0) {
  return nsb::BouncingMass(nsb::Params(nsb::BouncingMass::parameters_spec(),
                                       {{"e", std::to_string(e)}, {"h0", std::to_string(h0)}}));
}
nsb::MoreauJean mj(double theta) {
  return nsb::MoreauJean(nsb::Params(nsb::MoreauJean::parameters_spec(), {{"theta", std::to_string(theta)}}));
}
}  // namespace

TEST_CASE("moreau-jean: free flight under gravity, theta = 1/2 exact, theta = 1 first order",
          "[integrators][moreau-jean]") {
  const auto problem = mj_mass_with(1.0, 100.0);
  const double h = 1e-2;
  for (double theta : {0.5, 1.0}) {
    auto integ = mj(theta);
    integ.init(problem, problem.initial_state());
    for (int k = 0; k < 300; ++k) integ.step(h);
    const auto exact = *problem.state(integ.state().t);
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
      const auto problem = mj_mass_with(e);
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

namespace {
nsb::MoreauJean mj(const std::string& theta, const std::string& gamma) {
  return nsb::MoreauJean(nsb::Params(nsb::MoreauJean::parameters_spec(), {{"theta", theta}, {"gamma", gamma}}));
}
}  // namespace

TEST_CASE("moreau-jean: the contact activates where g_k + gamma h g'_k <= 0 first, with the hand-computed impulse",
          "[integrators][moreau-jean][contact]") {
  // Bouncing mass, m = 1, g = 9.81, h0 = 1, v0 = 0, e = 0.6, h = 1e-2. In flight the step
  // under the constant force -m g is
  //     v_{k+1} = v_k - h g,   u_{k+1} = u_k + h (theta v_{k+1} + (1 - theta) v_k) = u_k + h v_k - theta h^2 g,
  // so v_k = -k h g and u_k = h0 - h^2 g (k (k - 1)/2 + theta k). The forecast
  //     f_k = u_k + gamma h v_k = h0 - h^2 g (k (k - 1)/2 + (theta + gamma) k)
  // first drops to <= 0 at k = k*: the step from state k* is the first with an impulse. There
  // V_free = v_k* - h g = -(k* + 1) h g, and Newton's law v_{k*+1} = -e v_k* takes
  //     Lambda = m (-e v_k* - V_free) = m h g (k* (1 + e) + 1) > 0,   v_{k*+1} = e k* h g.
  // gamma = 0 (k* the first state at or below the floor) against 1/2 and 1: at theta = 1/2
  // k* = 46 for gamma = 0 (k*^2 >= 2 h0 / (h^2 g) = 2038.7), 45 for gamma = 1/2 (k* (k* + 1)
  // >= 2038.7) and for gamma = 1.
  const double m = 1.0, g = 9.81, h0 = 1.0, e = 0.6, h = 1e-2;
  const auto problem = mj_mass_with(e, h0);
  for (const char* theta : {"0.5", "1"}) {
    std::map<std::string, int> first;
    for (const char* gamma : {"0", "0.5", "1"}) {
      const double th = std::stod(theta), ga = std::stod(gamma);
      const auto forecast = [&](int k) { return h0 - h * h * g * (0.5 * k * (k - 1) + (th + ga) * k); };
      int k_star = 0;
      while (forecast(k_star) > 0.0) ++k_star;
      // Far from 0 on both sides: rounding in the scheme cannot move the activation.
      REQUIRE(forecast(k_star) < -1e-6);
      REQUIRE(forecast(k_star - 1) > 1e-6);
      first[gamma] = k_star;
      DYNAMIC_SECTION("theta = " << theta << ", gamma = " << gamma << ": k* = " << k_star) {
        auto integ = mj(theta, gamma);
        integ.init(problem, problem.initial_state());
        for (int k = 0; k < k_star; ++k) {
          integ.step(h);
          REQUIRE(integ.impulses()[0] == 0.0);
        }
        CHECK(integ.state().v[0] == Approx(-k_star * h * g).epsilon(1e-12));
        integ.step(h);
        CHECK(integ.impulses()[0] == Approx(m * h * g * (k_star * (1 + e) + 1)).epsilon(1e-12));
        CHECK(integ.state().v[0] == Approx(e * k_star * h * g).epsilon(1e-12));
      }
    }
    if (std::string(theta) == "0.5") {
      CHECK(first["0"] == 46);  // the forecast computed above, against the numbers in the comment
      CHECK(first["0.5"] == 45);
    }
  }
}

TEST_CASE("moreau-jean: gamma unset is gamma = 1 - theta, to the bit", "[integrators][moreau-jean][contact]") {
  const auto problem = mj_mass_with(0.9);
  for (const auto& [theta, gamma] : std::vector<std::pair<std::string, std::string>>{{"0.5", "0.5"}, {"0.75", "0.25"}, {"1", "0"}}) {
    CAPTURE(theta);
    auto unset = nsb::MoreauJean(nsb::Params(nsb::MoreauJean::parameters_spec(), {{"theta", theta}}));
    auto given = mj(theta, gamma);
    unset.init(problem, problem.initial_state());
    given.init(problem, problem.initial_state());
    double impulses = 0.0;
    for (int k = 0; k < 3000; ++k) {
      unset.step(1e-3);
      given.step(1e-3);
      REQUIRE(unset.state().u == given.state().u);
      REQUIRE(unset.state().v == given.state().v);
      REQUIRE(unset.impulses() == given.impulses());
      impulses += unset.impulses()[0];
    }
    CHECK(impulses > 0.0);  // the mass did bounce
  }
}
