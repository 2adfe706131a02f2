// The measures of studies/measures.hpp, each on a case with a known answer.
#include <catch2/catch.hpp>
#include <cmath>
#include <fmt/format.h>

#include "integrators/cd_lagrange_adaptive.hpp"
#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "run/run.hpp"
#include "studies/measures.hpp"
#include "tests/support/allocation_counter.hpp"

using Catch::Detail::Approx;

TEST_CASE("fit_line: an exact line, and its slope and 95% interval by hand on three points", "[studies][measures]") {
  const nsb::LineFit exact = nsb::fit_line({1.0, 2.0, 3.0, 4.0}, {5.0, 7.0, 9.0, 11.0});  // y = 3 + 2 x
  CHECK(exact.slope == Approx(2.0).epsilon(1e-14));
  CHECK(exact.low == Approx(2.0).epsilon(1e-12));
  CHECK(exact.high == Approx(2.0).epsilon(1e-12));
  CHECK(exact.points == 4);
  // x = 0, 1, 2; y = 0, 1, 3: Sxx = 2, Sxy = 3, slope 3/2; residuals 1/6, -1/3, 1/6, SSR = 1/6;
  // half width t_{0.975,1} sqrt(SSR / 1 / Sxx) = 12.7062047 sqrt(1/12).
  const nsb::LineFit f = nsb::fit_line({0.0, 1.0, 2.0}, {0.0, 1.0, 3.0});
  CHECK(f.slope == Approx(1.5).epsilon(1e-14));
  CHECK(f.high - f.slope == Approx(12.7062047 * std::sqrt(1.0 / 12.0)).epsilon(1e-12));
  CHECK(f.slope - f.low == Approx(12.7062047 * std::sqrt(1.0 / 12.0)).epsilon(1e-12));
  // Two points: a slope, no interval; one point, or all x equal: nothing.
  const nsb::LineFit two = nsb::fit_line({1.0, 3.0}, {1.0, 2.0});
  CHECK(two.slope == Approx(0.5));
  CHECK(std::isnan(two.low));
  CHECK(std::isnan(nsb::fit_line({1.0}, {1.0}).slope));
  CHECK(std::isnan(nsb::fit_line({2.0, 2.0, 2.0}, {1.0, 2.0, 3.0}).slope));
}

TEST_CASE("fit_order is fit_line in log-log over the distinct steps", "[studies][measures]") {
  const std::vector<double> h{1e-3, 2e-3, 4e-3}, e{1e-6, 5e-6, 15e-6};
  std::vector<double> lh, le;
  for (std::size_t i = 0; i < h.size(); ++i) lh.push_back(std::log(h[i])), le.push_back(std::log(e[i]));
  const nsb::OrderFit order = nsb::fit_order(h, e);
  const nsb::LineFit line = nsb::fit_line(lh, le);
  CHECK(order.order == line.slope);
  CHECK(order.low == line.low);
  CHECK(order.high == line.high);
  CHECK(order.points == 3);
}

TEST_CASE("RunningSlope: the least-squares slope one point at a time", "[studies][measures]") {
  nsb::RunningSlope s;
  CHECK(std::isnan(s.slope()));
  s.add(0.0, 1.0);
  CHECK(std::isnan(s.slope()));  // one point: no slope
  std::vector<double> x{0.0}, y{1.0};
  for (int k = 1; k <= 1000; ++k) {
    const double t = 1e-3 * k, e = 1.0 - 0.25 * t + 1e-3 * std::sin(37.0 * k);  // drift -1/4 plus noise
    s.add(t, e);
    x.push_back(t), y.push_back(e);
  }
  CHECK(s.slope() == Approx(nsb::fit_line(x, y).slope).epsilon(1e-10));
  CHECK(s.slope() == Approx(-0.25).margin(1e-2));
}

TEST_CASE("ContactPhases: a phase starts after a step without impulse, more than min_flight after the last", "[studies][measures]") {
  nsb::ContactPhases any;
  const std::vector<std::pair<double, bool>> steps{{0.1, false}, {0.2, true}, {0.3, true}, {0.4, false},
                                                   {0.5, true}, {0.6, false}, {1.0, false}, {1.1, true}};
  for (const auto& [t, c] : steps) any.add(t, c);
  CHECK(any.starts() == std::vector<double>{0.2, 0.5, 1.1});
  nsb::ContactPhases chatter(0.25);  // 0.5 is 0.2 after the last impulse at 0.3: the same phase
  for (const auto& [t, c] : steps) chatter.add(t, c);
  CHECK(chatter.starts() == std::vector<double>{0.2, 1.1});
}

TEST_CASE("compared_impacts: the first count, up to the first exact flight shorter than min_flight", "[studies][measures]") {
  const std::vector<double> exact{1.0, 2.0, 2.5, 2.6, 2.62};  // flights 1, 0.5, 0.1, 0.02
  CHECK(nsb::compared_impacts(exact, 3, 0.0) == 3);
  CHECK(nsb::compared_impacts(exact, 9, 0.0) == 5);  // as many as known
  CHECK(nsb::compared_impacts(exact, 9, 0.1) == 3);  // the flight of 0.02 ends them (0.1 is kept: not shorter)
  CHECK(nsb::compared_impacts(exact, 9, 0.3) == 2);
  CHECK(nsb::compared_impacts(exact, 1, 0.3) == 1);
  CHECK(nsb::compared_impacts(exact, 9, 2.0) == 0);
  CHECK(nsb::compared_impacts({1.0, 2.0}, 9, 0.5) == 1);  // the last has no known flight
}

TEST_CASE("FlightEnergies: at the exact mid-flight time, and at the mid-flight step between the run's impacts", "[studies][measures]") {
  // Exact impacts at 1, 2, 3, energies after them 4, 2, 1. Steps of 0.25 with impulses at the
  // steps ending at 1.25 (and 1.5: one phase), 2.5 and 3.0; energy at the step ending at t: 10 t.
  const std::vector<double> impacts{1.0, 2.0, 3.0}, energies{4.0, 2.0, 1.0};
  nsb::FlightEnergies exact(impacts, energies, 2, nsb::FlightEnergies::At::exact_mid_flight);
  nsb::FlightEnergies step(impacts, energies, 2, nsb::FlightEnergies::At::mid_flight_step);
  nsb::FlightEnergies one(impacts, energies, 1, nsb::FlightEnergies::At::mid_flight_step);
  for (int k = 1; k <= 16; ++k) {
    const double t = 0.25 * k;
    const bool contact = t == 1.25 || t == 1.5 || t == 2.5 || t == 3.0;
    for (auto* f : {&exact, &step, &one}) f->add(t, contact, 10.0 * t);
  }
  // Exact mid-flights 1.5 and 2.5: E = 15 and 25 against 4 and 2.
  REQUIRE(exact.compared() == 2);
  CHECK(exact.errors()[0] == Approx(15.0 / 4.0 - 1.0));
  CHECK(exact.errors()[1] == Approx(25.0 / 2.0 - 1.0));
  CHECK(exact.largest() == Approx(11.5));
  // Phases start at the steps k = 5 (1.25), 10 (2.5), 12 (3.0): mid-flight steps 7 (1.75) and 11 (2.75).
  REQUIRE(step.compared() == 2);
  CHECK(step.errors()[0] == Approx(17.5 / 4.0 - 1.0));
  CHECK(step.errors()[1] == Approx(27.5 / 2.0 - 1.0));
  // The energies compared, each beside its exact one.
  CHECK(step.energies() == std::vector<double>{17.5, 27.5});
  CHECK(exact.energies() == std::vector<double>{15.0, 25.0});
  CHECK(step.exact() == energies);
  CHECK(one.compared() == 1);  // the flights asked for only
  // A flight whose next impact never comes is not compared; none compared: NaN.
  nsb::FlightEnergies lone(impacts, energies, 2, nsb::FlightEnergies::At::mid_flight_step);
  lone.add(1.0, true, 1.0);
  lone.add(1.5, false, 1.0);
  CHECK(lone.compared() == 0);
  CHECK(std::isnan(lone.largest()));
}

TEST_CASE("FinalRest: the first step of the last stretch at rest, if it lasts longer than min_rest; rest_bound", "[studies][measures]") {
  nsb::FinalRest rest(0.25), none(0.25), moving(0.0);
  // At rest at 0.1, moving at 0.2, at rest from 0.3 to 0.6: the rest starts at 0.3 and lasts 0.3 > 0.25.
  for (const auto& [t, still] : std::vector<std::pair<double, bool>>{{0.1, true}, {0.2, false}, {0.3, true}, {0.4, true}, {0.6, true}})
    rest.add(t, still);
  CHECK(rest.start() == 0.3);
  none.add(0.5, true);
  none.add(0.75, true);  // lasts 0.25 (exactly, in binary), not longer
  CHECK(std::isnan(none.start()));
  moving.add(0.3, true);
  moving.add(0.4, false);  // the last step moves: no rest
  CHECK(std::isnan(moving.start()));
  // 2 g dt dt as a study writes it: (19.62 dt) dt, not 19.62 (dt dt).
  const double dt = 1e-3;
  CHECK(nsb::rest_bound(19.62, 2, dt) == 19.62 * dt * dt);
  CHECK(nsb::rest_bound(19.62, 1, dt) == 19.62 * dt);
  CHECK(nsb::rest_bound(19.62, 0, dt) == 19.62);
}

TEST_CASE("MomentumBalance and ContactPhases on the bouncing mass: Moreau-Jean balances momentum, impacts on time",
          "[studies][measures]") {
  // m = 1, g = 9.81, h0 = 1: first impact at sqrt(2 h0 / g) = 0.45152 s, the next 2 e sqrt(2 h0/g) later.
  const auto problem = nsb::make_problem("bouncing-mass", {{"e", "0.9"}, {"h0", "1"}});
  auto integrator = nsb::make_integrator("moreau-jean");
  integrator->init(*problem, problem->initial_state());
  nsb::MomentumBalance balance(*problem, integrator->state().v);
  nsb::ContactPhases impacts;
  double worst = 0.0, unbalanced = 0.0;
  nsb::RunOptions options;
  options.dt = 1e-4;
  options.t_end = 1.5;
  options.record_series = false;
  nsb::run(*problem, *integrator, options, [&](const nsb::Integrator& it, const nsb::StepInfo& info) {
    unbalanced = std::max(unbalanced, std::abs(balance.momentum(it.state().v) - balance.initial()));
    balance.add(it, info.dt);
    worst = std::max(worst, balance.residual(it.state().v));
    impacts.add(it.state().t, it.impulses().sum() > 0.0);
  });
  CHECK(balance.initial() == 0.0);  // released at rest
  CHECK(unbalanced > 1.0);          // P itself changes (gravity, impacts)...
  CHECK(worst < 1e-12);             // ...by exactly the impulses of gravity and the floor
  const double t1 = std::sqrt(2.0 / 9.81), t2 = t1 + 2 * 0.9 * t1;
  REQUIRE(impacts.starts().size() == 2);
  CHECK(impacts.starts()[0] == Approx(t1).margin(2e-4));
  CHECK(impacts.starts()[1] == Approx(t2).margin(2e-3));
}

TEST_CASE("MomentumBalance on cd-lagrange-adaptive under gravity: the force weighted (tau_k + tau_{k+1})/2", "[studies][measures]") {
  // The lumped bouncing bar: gravity, floor impulses, internal forces summing to zero, steps
  // chosen by the energy balance. From the first report on (the start's half kick tau_1/2 F_0
  // is before it) the residual stays where it is, to round-off.
  const auto bar = nsb::make_problem("bouncing-bar", {{"mass", "lumped"}, {"e", "0"}, {"N", "20"}});
  auto integrator = nsb::make_integrator("cd-lagrange-adaptive");
  integrator->init(*bar, bar->initial_state());
  nsb::MomentumBalance balance(*bar, integrator->state().v);
  double first = nsb::kNaN, drift = 0.0, dt_min = 1e300, dt_max = 0.0, p_max = 0.0;
  for (int k = 0; k < 3000; ++k) {
    const nsb::StepInfo info = integrator->step(0.9 * bar->stable_step());
    balance.add(*integrator, info.dt);
    const double r = balance.residual(integrator->state().v);
    if (k == 0) first = r;
    drift = std::max(drift, std::abs(r - first));
    dt_min = std::min(dt_min, info.dt), dt_max = std::max(dt_max, info.dt);
    p_max = std::max(p_max, std::abs(balance.momentum(integrator->state().v)));
  }
  REQUIRE(integrator->state().t > 1.2);  // into the first contact (from t = 1; the steps shrink there)
  CHECK(dt_max > 1.5 * dt_min);
  CHECK(drift <= 1e-12 * p_max);
}

TEST_CASE("MomentumBalance::speed_scale: sum_i m_i |v0_i|, nonzero where the momentum P0 is zero", "[studies][measures]") {
  const auto falling = nsb::make_problem("bouncing-mass", {{"m", "3"}, {"v0", "-2"}});
  const nsb::MomentumBalance one(*falling, falling->initial_state().v);
  CHECK(one.initial() == -6.0);
  CHECK(one.speed_scale() == 6.0);
  // Two masses moving apart: P0 = 0, the scale m1 |v1| + m2 |v2| = 2 + 2.
  nsb::Vec v(2);
  v << -1.0, 1.0;
  const auto chain = nsb::make_problem("spring-chain", {{"n", "2"}, {"a", "0"}, {"v0", "0"}});
  const nsb::Vec m = chain->mass_matrix().diagonal();
  const nsb::MomentumBalance apart(*chain, v);
  CHECK(apart.initial() == Approx(m[1] - m[0]).margin(1e-15));
  CHECK(apart.speed_scale() == m[0] + m[1]);
}

TEST_CASE("cost_column: the stepping time, a timing column", "[studies][measures]") {
  const nsb::Column c = nsb::cost_column();
  CHECK(c.name == "CPU");
  CHECK(c.unit == "s");
  CHECK(c.timing);
  CHECK(c.description.find("observer excluded") != std::string::npos);
}

TEST_CASE("Chatter: the period-2 component of an alternation is its amplitude, a line has none; zeros counted", "[studies][measures]") {
  nsb::Chatter alternation, line, few;
  for (int k = 0; k < 10; ++k) {
    alternation.add(k % 2 == 0 ? 1.25 : 0.75);  // 1 +- 0.25: (o_{k+1} - 2 o_k + o_{k-1}) / 4 = -+0.25
    line.add(0.5 * k);
  }
  CHECK(alternation.rms() == 0.25);
  CHECK(alternation.zeros() == 0);
  CHECK(line.rms() == 0.0);
  CHECK(line.zeros() == 1);  // the first value, 0
  few.add(1.0);
  few.add(0.0);
  CHECK(std::isnan(few.rms()));  // no interior value
  CHECK(few.zeros() == 1);
}

TEST_CASE("ContactPhases::span: from the first step with an impulse to the last, plus one step", "[studies][measures]") {
  nsb::ContactPhases phases, none;
  const std::vector<std::pair<double, bool>> steps{{0.1, false}, {0.2, true}, {0.3, true}, {0.4, false},
                                                   {0.5, true}, {0.6, false}, {0.7, false}};
  for (const auto& [t, c] : steps) {
    phases.add(t, c);
    none.add(t, false);
  }
  CHECK(phases.span(0.1) == 0.5 - 0.2 + 0.1);  // a lost step inside does not shorten it
  CHECK(std::isnan(none.span(0.1)));
}

TEST_CASE("MeshMomentum on cd-lagrange-adaptive's variable steps: the force weighted (tau_{k+1} + tau_{k+2})/2", "[studies][measures]") {
  // The spinning block dropped on the floor: gravity and floor impulses; the adaptive step
  // ranges over three decades there. P_y and J balance to round-off with the scheme's weight
  // (variable_step_weight); weighted by the step taken, P_y was off by (tau_{k+2} - tau_{k+1})/2 m g.
  const auto block = nsb::make_problem("block-2d", {{"vx", "0.3"}, {"spin", "3"}});
  auto adaptive = nsb::make_integrator("cd-lagrange-adaptive");
  auto fixed = nsb::make_integrator("cd-lagrange");
  for (auto* it : {adaptive.get(), fixed.get()}) {
    it->init(*block, block->initial_state());
    nsb::MeshMomentum py(*block, block->initial_state(), "py");
    double dt_min = 1e300, dt_max = 0.0;
    bool weights_ok = true;
    for (int k = 0; k < 1500; ++k) {
      const nsb::StepInfo info = it->step(0.5 * block->stable_step());
      py.add(*it, info.dt);
      dt_min = std::min(dt_min, info.dt), dt_max = std::max(dt_max, info.dt);
      const auto w = nsb::variable_step_weight(*it, info.dt);
      if (it == adaptive.get()) weights_ok = weights_ok && w &&
          *w == 0.5 * (info.dt + dynamic_cast<const nsb::CdLagrangeAdaptive&>(*it).next_step());
      else weights_ok = weights_ok && !w;
    }
    CAPTURE(it->name());
    CHECK(weights_ok);
    if (it == adaptive.get()) CHECK(dt_max > 100.0 * dt_min);
    CHECK(py.largest() <= 1e-13 * py.scale());
  }
}

namespace {

// Runs `integrator` on `problem` for t_end at the step dt, feeding an EnergyBalance after every
// step and `each` with it after the add.
template <class Each>
nsb::EnergyBalance balance_run(const nsb::Problem& problem, nsb::Integrator& integrator, double dt, double t_end, Each each) {
  integrator.init(problem, problem.initial_state());
  nsb::EnergyBalance balance(problem, integrator);
  nsb::RunOptions options;
  options.dt = dt;
  options.t_end = t_end;
  options.record_series = false;
  nsb::run(problem, integrator, options, [&](const nsb::Integrator& it, const nsb::StepInfo&) {
    balance.add(it);
    each(it, balance);
  });
  return balance;
}

}  // namespace

TEST_CASE("EnergyBalance: cd-lagrange on the bouncing mass balances to round-off, impacts included", "[studies][measures]") {
  // A rigid body: Psi = 0, so the staggered residual (the strain energy's trapezoidal defect) is
  // 0 whatever the impacts; the energy itself falls by (1 - e^2) at each impact.
  const auto problem = nsb::make_problem("bouncing-mass", {{"e", "0.8"}, {"h0", "1"}});
  auto integrator = nsb::make_integrator("cd-lagrange");
  double e_min = 1e300, e_max = -1e300;
  long impacts = 0;
  const nsb::EnergyBalance b = balance_run(*problem, *integrator, 1e-3, 2.5, [&](const nsb::Integrator& it, const nsb::EnergyBalance&) {
    e_min = std::min(e_min, it.energy().total());
    e_max = std::max(e_max, it.energy().total());
    impacts += it.impulses()[0] > 0.0;
  });
  CHECK(impacts >= 3);
  CHECK(e_max - e_min > 0.3 * 9.81);  // the impacts dissipate (E0 = m g h0 = 9.81)...
  CHECK(b.closed() > 2000);
  CHECK(b.round_off() < 1e-9);
  CHECK(std::abs(b.cumulative()) <= b.round_off());  // ...exactly their work along v- and v+
  CHECK(b.largest() <= b.round_off());
}

TEST_CASE("EnergyBalance: moreau-jean theta = 1/2 on the lumped bouncing bar balances to round-off, e = 0 impacts included",
          "[studies][measures]") {
  // Linear F_int, trapezoidal rule: r = Psi(U_{k+1}) - Psi(U_k) - F_int((U_k + U_{k+1})/2)^T dU = 0.
  const auto bar = nsb::make_problem("bouncing-bar", {{"mass", "lumped"}, {"e", "0"}, {"N", "50"}});
  auto integrator = nsb::make_integrator("moreau-jean");
  const double e0 = 0.0, e_imp = 500.0;  // DEP: released at rest, E_0 = 0; impact energy rho A L V^2 / 2
  double e_end = 0.0;
  const nsb::EnergyBalance b = balance_run(*bar, *integrator, 0.9 * bar->stable_step(), 1.0 + 16.0 / 3.0,
                                           [&](const nsb::Integrator& it, const nsb::EnergyBalance&) { e_end = it.energy().total(); });
  CHECK(std::abs(e_end - e0) > 0.01 * e_imp);  // the e = 0 impacts take energy...
  CHECK(std::abs(b.cumulative()) <= b.round_off());  // ...exactly their work
  CHECK(b.round_off() < 1e-8 * e_imp);
}

TEST_CASE("EnergyBalance: moreau-jean theta = 1 dissipates h^2 m g^2 / 2 per step in free fall", "[studies][measures]") {
  // r = h (1/2 - theta) F^T (V_{k+1} - V_k) with F = -m g, V_{k+1} - V_k = -g h: -h^2 m g^2 / 2.
  const double m = 2.0, g = 9.81, h = 1e-3;
  const auto problem = nsb::make_problem("bouncing-mass", {{"m", "2"}, {"h0", "10"}});
  auto integrator = nsb::make_integrator("moreau-jean", {{"theta", "1"}});
  long checked = 0;
  balance_run(*problem, *integrator, h, 1.0, [&](const nsb::Integrator&, const nsb::EnergyBalance& b) {
    CHECK(b.residual() == Approx(-0.5 * h * h * m * g * g).epsilon(1e-8));
    ++checked;
  });
  CHECK(checked >= 999);
}

TEST_CASE("EnergyBalance: cd-lagrange on the bouncing bar leaves the strain energy's trapezoidal defect, lumped and singular",
          "[studies][measures]") {
  // r_{k+1} = 1/2 (Psi(U_{k+2}) - Psi(U_k)) - 1/2 F_int(U_{k+1})^T (U_{k+2} - U_k), recomputed here
  // from the positions of three consecutive reports; not zero on an elastic body.
  for (const std::string mass : {"lumped", "singular"}) {
    CAPTURE(mass);
    const auto bar = nsb::make_problem("bouncing-bar", {{"mass", mass}, {"e", "0"}, {"N", "20"}});
    auto integrator = nsb::make_integrator("cd-lagrange");
    nsb::Vec u2 = bar->initial_state().u, u1 = u2, f(bar->ndof());
    long closed = 0, contacts = 0;
    double worst = 0.0, defect_max = 0.0;
    const nsb::EnergyBalance b =
        balance_run(*bar, *integrator, 0.9 * bar->stable_step(), 1.0 + 16.0 / 3.0, [&](const nsb::Integrator& it, const nsb::EnergyBalance& bal) {
          contacts += it.impulses()[0] > 0.0;
          if (bal.closed() > closed) {
            closed = bal.closed();
            bar->internal_force(u1, f);
            const nsb::Vec& u = it.state().u;
            const double defect = 0.5 * (bar->strain_energy(u) - bar->strain_energy(u2)) - 0.5 * f.dot(u - u2);
            worst = std::max(worst, std::abs(bal.residual() - defect));
            defect_max = std::max(defect_max, std::abs(defect));
          }
          u2 = u1;
          u1 = it.state().u;
        });
    CHECK(contacts > 10);
    CHECK(defect_max > 1e-6 * 500.0);  // not exact...
    CHECK(worst <= 1e-9 * 500.0);      // ...and the residual is that defect, contact steps included
    CHECK(b.largest() == Approx(defect_max).epsilon(1e-6));
  }
}

TEST_CASE("EnergyBalance: cd-lagrange-adaptive holds its balance to its tolerance where its step has a root", "[studies][measures]") {
  // Its step tau_{k+2} is the root of the same residual (W_c = (1 - e)/2 Lambda^T g'_{k+1/2}
  // with the impact law), |r| <= energy_tol S, S = 1/2 P^T M^{-1} P + (|V(U_k)| + |V(U_{k+1})|)/2
  // of the step that chose it; the residual it closes is the next report's. A step counted in
  // no_root_steps took the probe of least |r| instead: there the balance is not held.
  const auto bar = nsb::make_problem("bouncing-bar", {{"mass", "lumped"}, {"e", "0"}, {"N", "20"}});
  auto integrator = nsb::make_integrator("cd-lagrange-adaptive");
  nsb::Vec u1 = bar->initial_state().u;
  double S = 0.0, no_root = 0.0, rooted_worst = 0.0, unrooted_worst = 0.0;  // |r| / S
  bool rooted = false;  // the last step found the root of the residual the next report closes
  long closed = 0, rooted_steps = 0;
  balance_run(*bar, *integrator, 0.9 * bar->stable_step(), 1.0 + 16.0 / 3.0, [&](const nsb::Integrator& it, const nsb::EnergyBalance& b) {
    if (b.closed() > closed) {
      closed = b.closed();
      double& worst = rooted ? rooted_worst : unrooted_worst;
      worst = std::max(worst, std::abs(b.residual()) / S);
      rooted_steps += rooted;
    }
    const double count = it.work().extra.at("no_root_steps");
    rooted = count == no_root;
    no_root = count;
    const nsb::Vec& u = it.state().u;
    S = it.energy().kinetic + 0.5 * (std::abs(bar->potential(u1)) + std::abs(bar->potential(u)));
    u1 = u;
  });
  CHECK(rooted_steps > 1000);
  CHECK(rooted_worst <= 1e-12 + 1e-13);  // energy_tol, and the round-off of recomputing the terms
  CHECK(rooted_worst > 0.0);
  CHECK(unrooted_worst > 1e3 * 1e-12);  // where no root was found, the balance is off (1.3e-2 S on this run)
}

TEST_CASE("EnergyBalance: refused where no balance is derived; allocation-free per step", "[studies][measures]") {
  const auto problem = nsb::make_problem("bouncing-mass", {});
  auto nsga = nsb::make_integrator("nsga");
  nsga->init(*problem, problem->initial_state());
  CHECK_THROWS_AS(nsb::EnergyBalance(*problem, *nsga), nsb::InputError);
  auto projected = nsb::make_integrator("moreau-jean", {{"projection", "position"}});
  projected->init(*problem, problem->initial_state());
  CHECK_THROWS_AS(nsb::EnergyBalance(*problem, *projected), nsb::InputError);
  auto cd = nsb::make_integrator("cd-lagrange");
  cd->init(*problem, problem->initial_state());
  nsb::EnergyBalance b(*problem, *cd);
  long allocations = 0;
  for (int k = 0; k < 600; ++k) {  // through the first impact (t = 0.45 s)
    cd->step(1e-3);
    nsb::test::CountAllocations count;
    b.add(*cd);
    allocations += count.count();
  }
  CHECK(allocations == 0);
  CHECK(b.closed() == 598);
}

TEST_CASE("Envelope: max |value| per completed window, at its midpoint", "[studies][measures]") {
  nsb::Envelope env(1.0, 0.5);
  for (const auto& [t, x] : std::vector<std::pair<double, double>>{{0.5, 9.0}, {1.0, 1.0}, {1.2, -3.0}, {1.5, 2.0}, {1.9, 0.5}, {2.1, 7.0}})
    env.add(t, x);
  CHECK(env.times() == std::vector<double>{1.25, 1.75});  // [1, 1.5), [1.5, 2); [2, 2.5) not complete; t < t0 left out
  CHECK(env.maxima() == std::vector<double>{3.0, 2.0});
  // Reserved windows: no allocation while they fill.
  nsb::Envelope reserved(0.0, 1.0, 4);
  long allocations = 0;
  for (int k = 0; k < 40; ++k) {
    nsb::test::CountAllocations count;
    reserved.add(0.1 * k, k);
    allocations += count.count();
  }
  CHECK(reserved.maxima().size() == 3);
  CHECK(allocations == 0);
}

TEST_CASE("drift_rule: a linear drift fails, a bounded oscillation passes, a drift in noise fails once the windows resolve it",
          "[studies][measures]") {
  const auto series = [](int windows, const auto& f) {
    std::pair<std::vector<double>, std::vector<double>> s;
    for (int w = 0; w < windows; ++w) s.first.push_back(w + 0.5), s.second.push_back(f(w));
    return s;
  };
  const auto [t, line] = series(10, [](int w) { return 1e-6 * (w + 0.5); });
  const nsb::Drift linear = nsb::drift_rule(t, line, 1e-12);
  CHECK(linear.drift == Approx(1e-6).epsilon(1e-9));
  CHECK(linear.low > 0.0);
  CHECK(linear.over_run == Approx(9e-6).epsilon(1e-9));
  CHECK_FALSE(linear.no_drift);
  CHECK(nsb::drift_rule(t, line, 1e-5).no_drift);  // the same drift below the round-off bound
  // A bounded oscillation sampled through Envelope (period 1.3, windows of 1): no trend.
  nsb::Envelope env(0.0, 1.0);
  for (int k = 0; k <= 20000; ++k) env.add(1e-3 * k, 2.0 * std::sin(2.0 * M_PI * 1e-3 * k / 1.3));
  REQUIRE(env.maxima().size() == 20);
  const nsb::Drift bounded = nsb::drift_rule(env.times(), env.maxima(), 0.0);
  CHECK(bounded.low < 0.0);
  CHECK(bounded.high > 0.0);
  CHECK(bounded.no_drift);
  // Drift 1e-3 per window in a scatter of +-0.05 (a deterministic sequence, sin(2 w): no period
  // commensurate with the windows, which sin(37 w) is nearly, 37 = 6 (2 pi) - 0.7, and over 8
  // windows mimics a slope of 1.2e-2): 8 windows cannot tell the drift from none (passes);
  // 2000 windows resolve it (fails), its interval about the truth.
  const auto noisy = [](int w) { return 1e-3 * (w + 0.5) + 0.05 * std::sin(2.0 * w); };
  const auto [t8, n8] = series(8, noisy);
  const auto [t2k, n2k] = series(2000, noisy);
  CHECK(nsb::drift_rule(t8, n8, 0.0).no_drift);
  const nsb::Drift resolved = nsb::drift_rule(t2k, n2k, 0.0);
  CHECK_FALSE(resolved.no_drift);
  CHECK(resolved.low <= 1e-3);
  CHECK(resolved.high >= 1e-3);
  // A steadily falling envelope fails as well (two-sided interval), its sign below 0.
  const auto [tf, fall] = series(10, [](int w) { return 1.0 - 0.01 * w; });
  const nsb::Drift falling = nsb::drift_rule(tf, fall, 1e-12);
  CHECK(falling.high < 0.0);
  CHECK_FALSE(falling.no_drift);
  // Fewer than kDriftMinWindows: not measured.
  const auto [t7, n7] = series(7, [](int w) { return 1.0 * w; });
  CHECK(std::isnan(nsb::drift_rule(t7, n7, 0.0).drift));
  CHECK_FALSE(nsb::drift_rule(t7, n7, 0.0).no_drift);
}

// Not a test of the library: the measurement issue 52 asks for (hidden; run with "[.measure]").
// The Doyen-Ern-Piperno bouncing bar (e = 0) at 0.9 of the stable step (the claims study's
// step), 50 periods after the first impact: the envelope of the cumulative balance residual per
// period, its drift per period with the 95% interval, over E_imp; the fit over the second half
// beside it (past the first periods' transient) and the envelope itself.
namespace {

void measure_bar_drift(const std::string& scheme, const std::string& mass, const std::string& N) {
  const auto bar = nsb::make_problem("bouncing-bar", {{"mass", mass}, {"e", "0"}, {"N", N}});
  const double t1 = 1.0, period = 16.0 / 3.0, e_imp = 500.0;
  auto integrator = nsb::make_integrator(scheme);
  try {
    integrator->init(*bar, bar->initial_state());
  } catch (const nsb::InputError& e) {
    fmt::print("{} N {} {}: declined: {}\n", scheme, N, mass, e.what());
    return;
  }
  nsb::Envelope envelope(t1, period, 50);
  double e_end = 0.0;
  const nsb::EnergyBalance b = balance_run(*bar, *integrator, 0.9 * bar->stable_step(), t1 + 50.0 * period + 1e-9,
                                           [&](const nsb::Integrator& it, const nsb::EnergyBalance& bal) {
                                             envelope.add(it.state().t, bal.cumulative());
                                             e_end = it.energy().total();
                                           });
  const nsb::Drift d = nsb::drift_rule(envelope.times(), envelope.maxima(), b.round_off());
  REQUIRE(d.windows == 50);
  REQUIRE(std::isfinite(d.drift));
  const std::vector<double> late_t(envelope.times().begin() + 25, envelope.times().end()),
      late_m(envelope.maxima().begin() + 25, envelope.maxima().end());
  const nsb::Drift late = nsb::drift_rule(late_t, late_m, b.round_off());
  const auto per_period = [&](double x) { return x * period / e_imp; };
  fmt::print("{} N {} {}: steps {}; drift/period/E_imp {:.4e} [{:.4e}, {:.4e}] no_drift {}; periods 26-50 {:.4e} [{:.4e}, {:.4e}] "
             "no_drift {}; over run {:.4e}; cumulative {:.4e}, largest step {:.4e}, round-off {:.3e}; E_end {:.4e} (E_imp)\n  envelope/E_imp:",
             scheme, N, mass, integrator->work().steps, per_period(d.drift), per_period(d.low), per_period(d.high), d.no_drift,
             per_period(late.drift), per_period(late.low), per_period(late.high), late.no_drift, d.over_run / e_imp,
             b.cumulative() / e_imp, b.largest() / e_imp, b.round_off() / e_imp, e_end / e_imp);
  for (double x : envelope.maxima()) fmt::print(" {:.3e}", x / e_imp);
  fmt::print("\n");
}

}  // namespace

TEST_CASE("Measured: the bouncing bar's energy-balance drift per period, cd-lagrange, each mass model", "[.measure]") {
  const std::string N = GENERATE(as<std::string>{}, "100", "200", "400");
  for (const std::string mass : {"lumped", "singular", "consistent"}) measure_bar_drift("cd-lagrange", mass, N);
  if (N == "100") measure_bar_drift("cd-lagrange-adaptive", "lumped", N);
}
