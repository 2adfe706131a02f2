// The Doyen-Ern-Piperno bouncing bar's exact solution (problems/bouncing_bar.hpp): the fall,
// the wave fronts, the contact force, energy, periodicity, u against u_t and sigma, and the
// semi-discrete modal-exact solution converging to it.
#include <catch2/catch.hpp>
#include <cmath>

#include "problems/bouncing_bar.hpp"
#include "problems/registry.hpp"
#include "problems/signorini_bar.hpp"
#include "reference/modal_exact.hpp"

using Catch::Detail::Approx;
using nsb::BouncingBarExact;
using nsb::Params;
using nsb::SignoriniBar;

namespace {

constexpr double kTau = 1.0 / 3.0, kPeriod = 16.0 / 3.0;

Params dep(const std::map<std::string, std::string>& set = {}) {
  return Params(SignoriniBar::bouncing_parameters_spec(), set);
}

// Times of one period off every front (fronts sit at multiples of tau / 30 for x on the grid
// used below), with their x.
const std::vector<double> kXs = {0.0, 1.234, 3.77, 5.0001, 8.9, 10.0};
std::vector<double> sample_times() {
  std::vector<double> t;
  for (int k = 0; k < 97; ++k) t.push_back(1e-3 + kPeriod * (k + 0.37) / 97.0);
  return t;
}

}  // namespace

TEST_CASE("bouncing-bar: registry defaults are DEP's data; v0 = 0 accepted", "[problems][bouncing-bar]") {
  auto p = nsb::make_problem("bouncing-bar", {});
  const auto& prm = p->parameters();
  CHECK(prm.real("L") == 10.0);
  CHECK(prm.real("E") == 900.0);
  CHECK(prm.real("g") == 10.0);
  CHECK(prm.real("v0") == 0.0);
  CHECK(prm.real("g0") == 5.0);
  CHECK(p->initial_state().v.isZero(0.0));
  CHECK_THROWS_AS(nsb::make_problem("bouncing-bar", {{"v0", "-1"}}), nsb::InputError);
  const BouncingBarExact ex(prm, 1.0);
  CHECK(ex.impact_time() == Approx(1.0).epsilon(1e-15));
  CHECK(ex.impact_speed() == Approx(10.0).epsilon(1e-15));
  CHECK(ex.wave_time() == Approx(kTau).epsilon(1e-15));
  CHECK_THROWS_AS(BouncingBarExact(dep({{"g", "0"}}), 1.0), nsb::InputError);
}

TEST_CASE("bouncing-bar exact: rigid fall, then the compression front; points stay rigid until it arrives",
          "[problems][bouncing-bar]") {
  const BouncingBarExact ex(dep(), 3.0);
  for (double x : kXs) {
    CHECK(ex.displacement(x, 0.5) == Approx(-1.25).epsilon(1e-14));  // -g t^2 / 2
    CHECK(ex.velocity(x, 0.5) == Approx(-5.0).epsilon(1e-14));
    CHECK(ex.stress(x, 0.5) == 0.0);
  }
  // x = 6 meets the front at s = x / c = 0.2: ahead it falls freely, behind it moves at
  // -g x / c = -2 under the stress -rho c (V + g (s - x/c)).
  const double x = 6.0, s_front = 0.2, e = 1e-9;
  CHECK(ex.velocity(x, 1.0 + s_front - e) == Approx(-10.0 - 10.0 * s_front).epsilon(1e-9));
  CHECK(ex.stress(x, 1.0 + s_front - e) == Approx(0.0).margin(1e-12));
  CHECK(ex.velocity(x, 1.0 + s_front + e) == Approx(-2.0).epsilon(1e-7));
  CHECK(ex.stress(x, 1.0 + s_front + e) == Approx(-300.0).epsilon(1e-9));
  CHECK(ex.velocity(x, 1.0 + 0.3) == Approx(-2.0).epsilon(1e-12));
  CHECK(ex.stress(x, 1.0 + 0.3) == Approx(-30.0 * (10.0 + 10.0 * 0.1)).epsilon(1e-12));
  // u is continuous across the front.
  CHECK(ex.displacement(x, 1.0 + s_front + e) == Approx(ex.displacement(x, 1.0 + s_front - e)).margin(1e-7));
}

TEST_CASE("bouncing-bar exact: contact force rho A c (V + g s) then DEP's second contact, none in flight",
          "[problems][bouncing-bar]") {
  const BouncingBarExact ex(dep(), 8.0);
  const double e = 1e-9;
  CHECK(ex.contact_force(1.0 - e) == 0.0);
  CHECK(ex.contact_force(1.0 + e) == Approx(300.0).epsilon(1e-8));
  CHECK(ex.contact_force(1.0 + kTau) == Approx(400.0).epsilon(1e-12));
  CHECK(ex.contact_force(1.0 + 2 * kTau - e) == Approx(500.0).epsilon(1e-8));
  for (double s : {2 * kTau + e, 3 * kTau, 5.5 * kTau, 8 * kTau - e, 10 * kTau + e, 12 * kTau, 16 * kTau - e})
    CHECK(ex.contact_force(1.0 + s) == Approx(0.0).margin(1e-9));
  CHECK(ex.contact_force(1.0 + 8 * kTau + e) == Approx(500.0).epsilon(1e-8));
  CHECK(ex.contact_force(1.0 + 9 * kTau) == Approx(400.0).epsilon(1e-12));
  CHECK(ex.contact_force(1.0 + 10 * kTau - e) == Approx(300.0).epsilon(1e-8));
  // Contact end on the wall exactly while pushed, above it otherwise.
  CHECK(ex.displacement(0.0, 1.0 + kTau) == Approx(-5.0).epsilon(1e-14));
  CHECK(ex.displacement(0.0, 1.0 + 9 * kTau) == Approx(-5.0).epsilon(1e-14));
  CHECK(ex.displacement(0.0, 1.0 + 5 * kTau) > -5.0 + 1.0);
  // Rigid flight from s = 10 tau: leaves at V, at rest at its initial height at s = 13 tau.
  for (double x : kXs) {
    CHECK(ex.velocity(x, 1.0 + 10.5 * kTau) == Approx(10.0 - 10.0 * 0.5 * kTau).epsilon(1e-12));
    CHECK(ex.displacement(x, 1.0 + 13 * kTau) == Approx(0.0).margin(1e-12));
  }
}

TEST_CASE("bouncing-bar exact: periodic with period 16 L/c; energy conserved over 20 periods",
          "[problems][bouncing-bar]") {
  const BouncingBarExact ex(dep(), 21 * kPeriod);
  double worst_u = 0.0, worst_v = 0.0, worst_f = 0.0, worst_e = 0.0;
  for (double t : sample_times()) {
    for (double x : kXs) {
      worst_u = std::max(worst_u, std::abs(ex.displacement(x, t + 20 * kPeriod) - ex.displacement(x, t)));
      worst_v = std::max(worst_v, std::abs(ex.velocity(x, t + 3 * kPeriod) - ex.velocity(x, t)));
    }
    worst_f = std::max(worst_f, std::abs(ex.contact_force(t + 7 * kPeriod) - ex.contact_force(t)));
    worst_e = std::max({worst_e, std::abs(ex.field_energy(t)), std::abs(ex.field_energy(t + 19 * kPeriod))});
  }
  CHECK(worst_u <= 1e-10);
  CHECK(worst_v <= 1e-10);
  CHECK(worst_f <= 1e-9);
  CHECK(ex.energy() == 0.0);  // v0 = 0: the drop's potential is the origin
  CHECK(worst_e <= 1e-11 * ex.impact_energy());
  CHECK(ex.pieces() < 200);   // one piece per 2 tau and per mode change
  // Not a tautology of the sampler: with a gap of 6 it is no longer 16 tau-periodic.
  const BouncingBarExact other(dep({{"g0", "6"}}), 3 * kPeriod);
  double other_shift = 0.0;
  for (double t : sample_times())
    other_shift = std::max(other_shift, std::abs(other.displacement(5.0, t + kPeriod) - other.displacement(5.0, t)));
  CHECK(other_shift > 0.1);
  CHECK(std::abs(other.field_energy(2 * kPeriod)) <= 1e-11 * other.impact_energy());
}

TEST_CASE("bouncing-bar exact: u_t and sigma are the derivatives of u (central differences)",
          "[problems][bouncing-bar]") {
  const BouncingBarExact ex(dep({{"v0", "2"}}), 2 * kPeriod);
  const double h = 1e-6;
  double worst_t = 0.0, worst_x = 0.0;
  for (double t : sample_times())
    for (double x : {1.234, 3.77, 8.9}) {
      const double ut = (ex.displacement(x, t + h) - ex.displacement(x, t - h)) / (2 * h);
      const double ux = (ex.displacement(x + h, t) - ex.displacement(x - h, t)) / (2 * h);
      worst_t = std::max(worst_t, std::abs(ut - ex.velocity(x, t)));
      worst_x = std::max(worst_x, std::abs(900.0 * ux - ex.stress(x, t)));
    }
  CHECK(worst_t <= 1e-6);
  CHECK(worst_x <= 1e-4);
}

TEST_CASE("bouncing-bar: modal-exact's contact end converges to the continuum one as N grows",
          "[problems][bouncing-bar][modal-exact]") {
  // Singular mass (no impacts: the semi-discrete bar keeps its energy), one period. Error:
  // max over 400 times of |u_0 - u_exact(0, t)| [m]. Dispersion of the fronts makes it slow,
  // about h^(1/2) (measured: 0.43, 0.20, 0.088 m at h = 0.4, 0.1, 0.025): the tolerance is
  // 0.8 h^(1/2) m, and each refinement by 4 must cut the error by at least 0.6.
  const double t_end = 1.0 + kPeriod;
  const BouncingBarExact ex(dep(), t_end);
  std::vector<double> err;
  for (int N : {25, 100, 400}) {
    SignoriniBar p(dep({{"N", std::to_string(N)}, {"mass", "singular"}}));
    nsb::ModalExact me(Params(nsb::ModalExact::parameters_spec()));
    me.init(p, p.initial_state());
    double worst = 0.0;
    for (int k = 1; k <= 400; ++k) {
      const double t = t_end * k / 400.0;
      me.advance_to(t);
      worst = std::max(worst, std::abs(me.displacement(0) - ex.displacement(0.0, t)));
    }
    INFO("N = " << N << ": " << worst);
    CHECK(worst <= 0.8 * std::sqrt(10.0 / N));
    err.push_back(worst);
  }
  CHECK(err[1] < 0.6 * err[0]);
  CHECK(err[2] < 0.6 * err[1]);
}

TEST_CASE("bouncing-bar exact: momentum is rho A int u_t dx; dP/dt = lambda - rho A L g", "[problems][bouncing-bar]") {
  const BouncingBarExact ex(dep({{"v0", "2"}}), 12.0);
  const double m = 10.0, g = 10.0;
  // The rigid fall before the impact: P = -m (v0 + g t).
  CHECK(ex.momentum(0.3) == Approx(-m * (2.0 + g * 0.3)).epsilon(1e-14));
  for (double t : {0.1, 0.9, 1.4, 2.05, 3.3, 5.7, 7.9, 11.2}) {
    CAPTURE(t);
    // Against the velocity field integrated by the midpoint rule (piecewise smooth: 1e-4).
    const int n = 20000;
    double p = 0.0;
    for (int k = 0; k < n; ++k) p += ex.velocity((k + 0.5) * 10.0 / n, t) * 10.0 / n;
    CHECK(ex.momentum(t) == Approx(p).margin(0.1));  // fronts: |jump| dx / 2 each, of |P| ~ 300
    // Balance of momentum: the contact force against gravity (central difference).
    const double h = 1e-6;
    CHECK((ex.momentum(t + h) - ex.momentum(t - h)) / (2 * h) ==
          Approx(ex.contact_force(t) - m * g).margin(1e-3 * m * g));
  }
}

TEST_CASE("bouncing-bar and signorini-bar with g > 0: the *_exact observables and exact_state are the exact solution",
          "[problems][bouncing-bar]") {
  // Issue 20: every *_exact column read NaN although the problem has an exact solution.
  for (const auto& [name, set] : std::vector<std::pair<std::string, std::map<std::string, std::string>>>{
           {"bouncing-bar", {}}, {"signorini-bar", {{"g", "2"}, {"g0", "0.1"}, {"v0", "0.5"}}}}) {
    CAPTURE(name);
    const auto p = nsb::make_problem(name, set);
    const BouncingBarExact ex(p->parameters(), 40.0);
    const auto names = p->observable_names();
    std::vector<double> out(names.size());
    for (double t : {0.0, 0.4, 1.2, 3.1, 17.0, 39.5}) {
      CAPTURE(t);
      auto s = p->initial_state();
      s.t = t;
      p->observe(s, nsb::Vec(), 0.0, out);
      const auto col = [&](const std::string& c) { return out[std::find(names.begin(), names.end(), c) - names.begin()]; };
      CHECK(col("u_contact_exact") == ex.displacement(0.0, t));
      CHECK(col("v_contact_exact") == ex.velocity(0.0, t));
      CHECK(col("contact_force_exact") == ex.contact_force(t));
      CHECK(col("momentum_exact") == ex.momentum(t));
      const auto exact = p->exact()->state(t);
      REQUIRE(exact);
      CHECK(exact->u[0] == ex.displacement(0.0, t));
      CHECK(exact->v[p->ndof() - 1] == ex.velocity(p->parameters().real("L"), t));
    }
  }
  // The stiff/soft bar has none: NaN, said as such.
  const auto soft = nsb::make_problem("bouncing-bar", {{"stiff_ratio", "2"}});
  std::vector<double> out(soft->observable_names().size());
  soft->observe(soft->initial_state(), nsb::Vec(), 0.0, out);
  CHECK(std::isnan(out[3]));
  CHECK_FALSE(soft->exact()->state(1.0));
}

TEST_CASE("bouncing-bar's ExactSolution: contact_start is the fall's end t1, wave_time L / c; one period later it lands again",
          "[problems][bouncing-bar]") {
  // DEP's data: t1 = 1 (g0 = g t1^2 / 2 with g0 = 5, g = 10), L / c = 10 / 30; the study files'
  // horizons (t_end_exact = { contact_start = 1, wave_time = 16 }) are these times.
  const auto p = nsb::make_problem("bouncing-bar", {});
  const nsb::ExactSolution& exact = *p->exact();
  const BouncingBarExact ex(p->parameters(), 20.0);
  REQUIRE(exact.event_time(nsb::ExactEvent::contact_start));
  CHECK(*exact.event_time(nsb::ExactEvent::contact_start) == 1.0);
  CHECK(*exact.event_time(nsb::ExactEvent::contact_start) == ex.impact_time());
  CHECK(exact.value(nsb::ExactValue::wave_time).value() == Approx(kTau).epsilon(1e-15));
  CHECK(exact.value(nsb::ExactValue::wave_time).value() == ex.wave_time());
  // Periodic with period 16 L / c: at t1 + 16 tau the contact end lands again at speed V = 10,
  // unstressed (just before: falling at V).
  const double land = 1.0 + 16.0 * exact.value(nsb::ExactValue::wave_time).value();
  CHECK(exact.state(land - 1e-9)->v[0] == Approx(-10.0).epsilon(1e-7));
  CHECK(exact.state(land - 1e-9)->u[0] == Approx(-5.0).margin(1e-7));
  // Other data: the root of g0 = v0 t1 + g t1^2 / 2, and the gap closes there.
  const auto other = nsb::make_problem("bouncing-bar", {{"v0", "2"}, {"g0", "6"}});
  const double t1 = other->exact()->event_time(nsb::ExactEvent::contact_start).value();
  CHECK(2.0 * t1 + 5.0 * t1 * t1 == Approx(6.0).epsilon(1e-15));
  CHECK(other->exact()->state(t1)->u[0] == Approx(-6.0).margin(1e-12));
  // The stiff/soft bar has no exact solution: neither time.
  const auto soft = nsb::make_problem("bouncing-bar", {{"stiff_ratio", "2"}});
  CHECK_FALSE(soft->exact()->event_time(nsb::ExactEvent::contact_start));
  CHECK_FALSE(soft->exact()->value(nsb::ExactValue::wave_time));
  // Without gravity the bar's contact start stays g0 / v0 (its d'Alembert solution).
  const auto bar = nsb::make_problem("signorini-bar", {{"g0", "0.5"}, {"v0", "2"}});
  CHECK(bar->exact()->event_time(nsb::ExactEvent::contact_start).value() == 0.25);
  CHECK(bar->exact()->value(nsb::ExactValue::wave_time).value() == 1.0);
}
