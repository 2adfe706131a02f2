// nsga, newmark-lm and moreau-jean with projection = position (integrators/nsga.hpp,
// newmark_lm.hpp, moreau_jean.hpp): smooth-window order against modal-exact on the
// wall-free spring chain, no penetration at the step's end, newmark-lm's energy on the
// singular and the lumped bar, nsga's high-frequency dissipation.
#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <cmath>

#include "integrators/registry.hpp"
#include "problems/bouncing_mass.hpp"
#include "problems/signorini_bar.hpp"
#include "problems/spring_chain.hpp"
#include "reference/modal_exact.hpp"

namespace {

using nsb::Params;

void advance(nsb::Integrator& integ, double t_end, double dt) {
  while (integ.state().t < t_end - 1e-12) integ.step(std::min(dt, t_end - integ.state().t));
}

nsb::SpringChain chain_of(const std::map<std::string, std::string>& p) {
  return nsb::SpringChain(Params(nsb::SpringChain::parameters_spec(), p));
}

nsb::SignoriniBar bar_of(const std::string& mass, int N) {
  return nsb::SignoriniBar(Params(nsb::SignoriniBar::parameters_spec(), {{"mass", mass}, {"N", std::to_string(N)}}));
}

// Max-norm error of (u, v) at t_end against modal-exact.
double chain_error(const std::string& name, const std::map<std::string, std::string>& overrides, double dt) {
  const auto p = chain_of({{"n", "5"}, {"wall", "none"}});
  const double t_end = 1.0;
  auto integ = nsb::make_integrator(name, overrides);
  integ->init(p, p.initial_state());
  advance(*integ, t_end, dt);
  nsb::ModalExact exact(Params(nsb::ModalExact::parameters_spec()));
  exact.init(p, p.initial_state());
  advance(exact, t_end, t_end);
  return std::max((integ->state().u - exact.state().u).lpNorm<Eigen::Infinity>(),
                  (integ->state().v - exact.state().v).lpNorm<Eigen::Infinity>());
}

double observed_order(const std::string& name, const std::map<std::string, std::string>& overrides, double dt = 1.0 / 200) {
  const double e1 = chain_error(name, overrides, dt), e2 = chain_error(name, overrides, dt / 2);
  CAPTURE(name, e1, e2);
  return std::log2(e1 / e2);
}

// Smallest gap at any step's end, relative to the travel per step.
double min_gap(const nsb::Problem& p, const std::string& name, const std::map<std::string, std::string>& overrides,
               double dt, double t_end) {
  auto integ = nsb::make_integrator(name, overrides);
  integ->init(p, p.initial_state());
  double lowest = INFINITY;
  while (integ->state().t < t_end) {
    integ->step(dt);
    const nsb::Vec g = p.gap_offset() + p.gap_operator() * integ->state().u;
    lowest = std::min(lowest, g.minCoeff());
  }
  return lowest;
}

}  // namespace

TEST_CASE("nsga, newmark-lm, projected moreau-jean: order in a smooth window (wall-free chain vs modal-exact)",
          "[integrators][order]") {
  const double nsga = observed_order("nsga", {}), nsga_06 = observed_order("nsga", {{"rho_inf", "0.6"}}),
               nlm = observed_order("newmark-lm", {}), mj = observed_order("moreau-jean", {{"projection", "position"}});
  CAPTURE(nsga, nsga_06, nlm, mj);
  CHECK(nsga >= 1.9);
  CHECK(nsga_06 >= 1.9);
  CHECK(nlm >= 1.9);
  CHECK(mj >= 1.9);
  // theta = 1 is backward Euler in velocity: first order (its damping exp(-w^2 h t / 2) needs
  // w^2 h t << 1 to be asymptotic: w_max^2 = 300 here).
  const double o1 = observed_order("moreau-jean", {{"projection", "position"}, {"theta", "1"}}, 1.0 / 4000);
  CAPTURE(o1);
  CHECK(o1 > 0.9);
  CHECK(o1 < 1.1);
}

TEST_CASE("position-level schemes: no penetration at the step's end", "[integrators][contact]") {
  const nsb::BouncingMass mass(Params(nsb::BouncingMass::parameters_spec(), {{"e", "0.8"}}));
  const auto lumped = bar_of("lumped", 50), singular = bar_of("singular", 50);
  const double h_bar = 1.0 / 50;  // L = c = 1
  const std::map<std::string, std::string> projected = {{"projection", "position"}};
  const double tiny = -1e-14;
  CHECK(min_gap(mass, "nsga", {}, 1e-2, 2.0) >= tiny);
  CHECK(min_gap(mass, "nsga", {{"rho_inf", "0.5"}}, 1e-2, 2.0) >= tiny);
  CHECK(min_gap(mass, "moreau-jean", projected, 1e-2, 2.0) >= tiny);
  for (const auto* p : {&lumped, &singular}) {
    CAPTURE(p->parameters().choice("mass"));
    CHECK(min_gap(*p, "nsga", {}, 0.9 * h_bar, 2.5) >= tiny);
    CHECK(min_gap(*p, "newmark-lm", {}, 0.9 * h_bar, 2.5) >= tiny);
    CHECK(min_gap(*p, "moreau-jean", projected, 0.9 * h_bar, 2.5) >= tiny);
  }
  // Without the projection Moreau-Jean does penetrate (velocity-level law): the check above can fail.
  CHECK(min_gap(mass, "moreau-jean", {}, 1e-2, 2.0) < -1e-6);
}

TEST_CASE("newmark-lm: energy over one contact of the bar, singular mass kept, lumped mass jumps",
          "[integrators][energy]") {
  // N = 100, dt = h / 2c, to t = 2.5 (contact lasts 2L/c = 2).
  auto max_energy_error = [](const std::string& mass) {
    const auto p = bar_of(mass, 100);
    auto integ = nsb::make_integrator("newmark-lm");
    integ->init(p, p.initial_state());
    const double e0 = integ->energy().total();
    double worst = 0.0;
    while (integ->state().t < 2.5) {
      integ->step(0.5 / 100);
      worst = std::max(worst, std::abs(integ->energy().total() / e0 - 1.0));
    }
    return worst;
  };
  const double singular = max_energy_error("singular"), lumped = max_energy_error("lumped");
  CAPTURE(singular, lumped);
  CHECK(singular < 5e-3);
  CHECK(lumped > 2e-2);
}

TEST_CASE("newmark-lm: the lumped bar's energy jumps are the multipliers' work, exactly",
          "[integrators][energy]") {
  // beta = 1/4, gamma = 1/2 on a linear problem without load: E_{k+1} - E_k =
  // (g_{k+1} - g_k) (lambda_k + lambda_{k+1}) / 2, and impulses() = h (lambda_k + lambda_{k+1}) / 2.
  // With complementarity this is (lambda_k g_{k+1} - lambda_{k+1} g_k) / 2: work done at
  // releases and closures of the chattering contact node, which the scheme cannot avoid.
  const auto p = bar_of("lumped", 100);
  const double dt = 0.5 / 100;
  auto integ = nsb::make_integrator("newmark-lm");
  integ->init(p, p.initial_state());
  const double e0 = integ->energy().total();
  double e_prev = e0, g_prev = p.gap_offset()[0] + integ->state().u[0], worst = 0.0;
  while (integ->state().t < 2.5) {
    integ->step(dt);
    const double e = integ->energy().total(), g = p.gap_offset()[0] + integ->state().u[0];
    worst = std::max(worst, std::abs((e - e_prev) - (g - g_prev) * integ->impulses()[0] / dt));
    e_prev = e;
    g_prev = g;
  }
  CHECK(worst < 1e-10 * e0);
}

TEST_CASE("newmark-lm declines an impact law it cannot honour", "[integrators][input]") {
  const nsb::BouncingMass mass(Params(nsb::BouncingMass::parameters_spec(), {{"e", "0.5"}}));
  auto integ = nsb::make_integrator("newmark-lm");
  CHECK_THROWS_AS(integ->init(mass, mass.initial_state()), nsb::InputError);
}

TEST_CASE("nsga: rho_inf = 1 keeps the free chain's energy, rho_inf < 1 damps the high modes only",
          "[integrators][energy]") {
  const int n = 40;
  const auto p = chain_of({{"n", std::to_string(n)}, {"wall", "none"}, {"mass_ratio", "1"}});
  Eigen::MatrixXd K, M;
  nsb::SpMat Ks;
  p.tangent_stiffness(nsb::Vec::Zero(n), Ks);
  K = Eigen::MatrixXd(Ks);
  M = Eigen::MatrixXd(p.mass_matrix());
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(K, M);
  const double w_low = std::sqrt(modes.eigenvalues()[1]), w_high = std::sqrt(modes.eigenvalues()[n - 1]);
  const double dt = 10.0 / w_high;  // w_high dt = 10, w_low dt ~ 0.4
  auto energy_ratio = [&](int mode, const std::string& rho, int steps) {
    auto integ = nsb::make_integrator("nsga", {{"rho_inf", rho}});
    nsb::State s{0.0, modes.eigenvectors().col(mode), nsb::Vec::Zero(n)};
    integ->init(p, s);
    const double e0 = integ->energy().total();
    for (int k = 0; k < steps; ++k) integ->step(dt);
    return integ->energy().total() / e0;
  };
  CAPTURE(w_low * dt, w_high * dt);
  for (int mode : {1, n - 1}) CHECK(std::abs(energy_ratio(mode, "1", 200) - 1.0) < 1e-10);
  const double low = energy_ratio(1, "0.5", 20), high = energy_ratio(n - 1, "0.5", 20);
  CAPTURE(low, high);
  CHECK(low > 0.95);
  CHECK(high < 1e-3);
}
