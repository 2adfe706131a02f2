// The measures of studies/measures.hpp, each on a case with a known answer.
#include <catch2/catch.hpp>
#include <cmath>

#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "run/run.hpp"
#include "studies/measures.hpp"

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
