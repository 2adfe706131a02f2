// Smooth-window order of every registered (non-reference) integrator: the wall-free spring
// chain (no contact, linear) against modal-exact, its exact semi-discrete solution. The
// error is the largest displacement error at the final time (displacements only: the
// schemes report different velocities, e.g. CD-Lagrange the half-step one); the order is
// log2 of the error ratio between steps dt and dt/2 at the two finest steps.
// Every integrator must declare its expected order below: a new one fails until it does.
#include <catch2/catch.hpp>
#include <cmath>
#include <map>

#include "integrators/registry.hpp"
#include "problems/spring_chain.hpp"
#include "reference/modal_exact.hpp"
#include "tests/integrators/every_integrator.hpp"

namespace {

// Smooth-phase order of each scheme at its default parameters.
const std::map<std::string, double> kExpectedOrder = {
    {"cd-lagrange", 2.0},      {"cd-lagrange-adaptive", 2.0}, {"moreau-jean", 2.0},      // theta = 1/2
    {"schatzman-paoli", 2.0},  {"cd-penalty", 2.0},           {"d1-minus-linear", 2.0},
    {"nsga", 2.0},             {"newmark-lm", 2.0},
    {"siconos-moreau-jean", 2.0},  // theta = 1/2
    // Siconos' SchatzmanPaoliOSI starts from q(t0) := q0 + h v0 with q0 as the previous step
    // (initializeWorkVectorsForDS): an O(h) start-up error, so first order (the scheme is second).
    {"siconos-schatzman-paoli", 1.0},
    {"siconos-d1-minus-linear", 2.0},
    // The out-of-tree example plugin (examples/plugin/), which the tests load: velocity-first
    // symplectic Euler gives the leapfrog's positions (its velocity is the half-step one).
    {"symplectic-euler", 2.0},
};

// Largest displacement error at the end of a run of `steps` steps of dt.
double final_error(const nsb::IntegratorEntry& entry, const nsb::Problem& chain, double dt, int steps) {
  auto integ = entry.make(nsb::Params(entry.parameters()));
  integ->init(chain, chain.initial_state());
  for (int k = 0; k < steps; ++k) integ->step(dt);
  nsb::ModalExact exact(nsb::Params(nsb::ModalExact::parameters_spec()));
  exact.init(chain, chain.initial_state());
  exact.step(integ->state().t - chain.initial_state().t);
  return (integ->state().u - exact.state().u).lpNorm<Eigen::Infinity>();
}

}  // namespace

TEST_CASE("every integrator: smooth-window order on the wall-free spring chain against modal-exact",
          "[integrators][order]") {
  const nsb::SpringChain chain(nsb::Params(nsb::SpringChain::parameters_spec(), {{"n", "5"}, {"wall", "none"}}));
  const double dt = chain.stable_step() / 8.0;
  const int steps = 64;  // about 1.3 periods of the slowest mode at the coarsest step
  for (const auto& entry : nsb::integrator_registry()) {
    if (entry.reference) continue;
    DYNAMIC_SECTION(entry.name) {
      // The physics-engine peers run rigid bodies only and decline the chain (engines_test.cpp).
      if (!nsb::testing::init_or_decline(entry, chain)) {
        WARN(entry.name << " declines the spring chain");
        continue;
      }
      const auto expected = kExpectedOrder.find(entry.name);
      INFO("integrator " << entry.name << " has no expected smooth order: declare it in kExpectedOrder "
                         "(tests/integrators/smooth_order_test.cpp)");
      REQUIRE(expected != kExpectedOrder.end());
      const double e1 = final_error(entry, chain, dt / 2.0, 2 * steps);
      const double e2 = final_error(entry, chain, dt / 4.0, 4 * steps);
      const double order = std::log2(e1 / e2);
      CAPTURE(e1, e2, order);
      CHECK(order >= expected->second - 0.1);
      CHECK(order <= expected->second + 0.5);  // not an accident of error cancellation
    }
  }
}
