#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "problems/rolling_disk.hpp"
#include "tests/support/input_error.hpp"

using Catch::Detail::Approx;
using nsb::Params;
using nsb::RollingDisk;

namespace {

const double kG = 9.81;

RollingDisk make_disk(std::map<std::string, std::string> set) { return RollingDisk(Params(RollingDisk::parameters_spec(), set)); }

std::string str(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

struct Disk {
  double m = 1.0, R = 0.1, kappa = 0.5, mu = 0.3, v0 = 1.0, omega0 = 0.0, h0 = 0.0, e = 0.5;
  RollingDisk make() const {
    return make_disk({{"m", str(m)}, {"R", str(R)}, {"kappa", str(kappa)}, {"mu", str(mu)}, {"v0", str(v0)},
                   {"omega0", str(omega0)}, {"h0", str(h0)}, {"e", str(e)}});
  }
  double slip0() const { return v0 + R * omega0; }
  double energy(const RollingDisk& p, const nsb::State& s) const {
    return 0.5 * m * (s.v[0] * s.v[0] + s.v[1] * s.v[1]) + 0.5 * kappa * m * R * R * s.v[2] * s.v[2] + p.load_potential(s.u);
  }
  // Angular momentum about the contact point (below the centre), counter-clockwise.
  double contact_momentum(const nsb::State& s) const { return kappa * m * R * R * s.v[2] - m * R * s.v[0]; }
};

double slip(const RollingDisk& p, double t) {
  const auto s = *p.state(t);
  return s.v[0] + p.parameters().real("R") * s.v[2];
}

// Trapezoid rule: exact (to round-off) for an integrand linear on [a, b].
template <class F>
double trapezoid_rule(F f, double a, double b, int n = 1000) {
  const double h = (b - a) / n;
  double sum = 0.5 * (f(a) + f(b));
  for (int i = 1; i < n; ++i) sum += f(a + i * h);
  return sum * h;
}

// Midpoint rule: exact for a linear integrand too, and never samples the ends of [a, b], where
// an impact makes the velocity jump.
template <class F>
double midpoint(F f, double a, double b, int n) {
  const double h = (b - a) / n;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += f(a + (i + 0.5) * h);
  return sum * h;
}

// On the floor from t = 0: forward slip, backspin winning, spin only, a ball, a ring.
std::vector<Disk> floor_cases() {
  std::vector<Disk> c(5);
  c[1].omega0 = -30.0;  // s0 = -2
  c[2].v0 = 0.0, c[2].omega0 = 20.0;
  c[3].kappa = 0.4, c[3].mu = 0.2, c[3].v0 = 3.0, c[3].omega0 = 10.0, c[3].m = 2.0;
  c[4].kappa = 1.0, c[4].v0 = -2.0, c[4].R = 0.5;
  return c;
}

}  // namespace

TEST_CASE("rolling disk exact, on the floor: slip falls at mu g (1 + 1/kappa), then rolling at v_f", "[problems][exact][friction]") {
  for (const auto& d : floor_cases()) {
    CAPTURE(d.kappa, d.mu, d.v0, d.omega0);
    const auto p = d.make();
    const double s0 = d.slip0(), rate = d.mu * kG * (1 + 1 / d.kappa), t_star = std::abs(s0) / rate;
    CHECK(p.slip_decay_rate() == Approx(rate).epsilon(1e-15));
    CHECK(p.rest_time() == 0.0);
    CHECK(p.impacts().empty());
    CHECK(p.rolling_onset_time() == Approx(t_star).epsilon(1e-14));
    for (double f : {0.0, 0.25, 0.5, 0.9})
      CHECK(slip(p, f * t_star) == Approx(s0 - std::copysign(rate, s0) * f * t_star).epsilon(1e-13).margin(1e-14));
    const double v_f = (d.v0 - d.kappa * d.R * d.omega0) / (1 + d.kappa);
    CHECK(p.final_velocity() == Approx(v_f).epsilon(1e-13).margin(1e-14));
    CHECK(p.final_spin() == Approx(-v_f / d.R).epsilon(1e-13).margin(1e-13));
    for (double after : {0.0, 1e-6, 0.5, 10.0}) {
      const auto s = *p.state(t_star + after);
      CHECK(s.v[0] == Approx(v_f).epsilon(1e-13).margin(1e-14));
      CHECK(s.v[0] + d.R * s.v[2] == Approx(0.0).margin(1e-14 * std::abs(s0)));
      CHECK(s.u[1] == 0.0);
      CHECK(s.v[1] == 0.0);
    }
    // Sliding direction: the friction force -sign(s) mu m g decelerates x' at mu g.
    const double dt = 0.3 * t_star;
    CHECK(p.state(dt)->v[0] - d.v0 == Approx(-std::copysign(d.mu * kG, s0) * dt).epsilon(1e-12));
  }
}

TEST_CASE("rolling disk exact, on the floor: x, theta integrate v, omega; angular momentum about the contact point is conserved", "[problems][exact][friction]") {
  for (const auto& d : floor_cases()) {
    CAPTURE(d.kappa, d.mu, d.v0, d.omega0);
    const auto p = d.make();
    const double ts = p.rolling_onset_time(), t_end = ts + 1.0;
    const auto v = [&](double t) { return p.state(t)->v[0]; };
    const auto w = [&](double t) { return p.state(t)->v[2]; };
    const auto end = *p.state(t_end);
    // Split at the onset: v and omega are linear on each side.
    CHECK(trapezoid_rule(v, 0, ts) + trapezoid_rule(v, ts, t_end) == Approx(end.u[0]).epsilon(1e-12).margin(1e-13));
    CHECK(trapezoid_rule(w, 0, ts) + trapezoid_rule(w, ts, t_end) == Approx(end.u[2]).epsilon(1e-12).margin(1e-12));
    const double L0 = d.contact_momentum(*p.state(0.0));
    CHECK(L0 == Approx(d.kappa * d.m * d.R * d.R * d.omega0 - d.m * d.R * d.v0).epsilon(1e-15));
    for (double f : {0.1, 0.5, 0.99, 1.5, 4.0})
      CHECK(d.contact_momentum(*p.state(f * ts)) == Approx(L0).epsilon(1e-13).margin(1e-14 * d.m * d.R * std::abs(d.v0 + d.R * d.omega0)));
  }
}

TEST_CASE("rolling disk exact, on the floor: energy lost m kappa s0^2 / (2 (1 + kappa)) = friction work", "[problems][exact][friction]") {
  for (const auto& d : floor_cases()) {
    CAPTURE(d.kappa, d.mu, d.v0, d.omega0);
    const auto p = d.make();
    const double ts = p.rolling_onset_time(), s0 = d.slip0();
    const double lost = d.energy(p, *p.state(0.0)) - d.energy(p, *p.state(ts + 2.0));
    CHECK(lost == Approx(d.m * d.kappa * s0 * s0 / (2 * (1 + d.kappa))).epsilon(1e-12));
    // Friction work: mu m g int |s| dt (|s| linear until the onset, 0 after).
    CHECK(lost == Approx(d.mu * d.m * kG * trapezoid_rule([&](double t) { return std::abs(slip(p, t)); }, 0.0, ts)).epsilon(1e-12));
    // Energy only decreases.
    double previous = d.energy(p, *p.state(0.0));
    for (double t = 0.01; t < ts + 0.5; t += 0.01) {
      const double now = d.energy(p, *p.state(t));
      CHECK(now <= previous + 1e-14);
      previous = now;
    }
  }
}

TEST_CASE("rolling disk exact, dropped: every impact obeys Newton and Coulomb", "[problems][exact][friction]") {
  // h0 = 0.4: V = 2.80, a full slip at impact k cuts |s| by mu (1 + 1/kappa) (1 + e) V e^(k-1).
  std::vector<Disk> cases(4);
  for (auto& d : cases) d.h0 = 0.4;
  cases[0].omega0 = 60.0;                                          // s0 = 7: slips 3 times, sticks at the 4th
  cases[1].omega0 = 80.0, cases[1].e = 0.0;                        // one slipping impact, then slides on the floor
  cases[2].omega0 = -300.0, cases[2].e = 0.3, cases[2].mu = 0.1;   // slips at every impact, slides after Zeno
  cases[3].e = 1.0, cases[3].omega0 = 60.0, cases[3].kappa = 0.4;  // bounces for ever, sticks at the 2nd
  const std::vector<int> first_stuck = {4, 0, 0, 2};               // 0: never
  for (std::size_t n = 0; n < cases.size(); ++n) {
    const auto& d = cases[n];
    CAPTURE(d.e, d.mu, d.omega0);
    const auto p = d.make();
    const double V = std::sqrt(2 * kG * d.h0), t1 = std::sqrt(2 * d.h0 / kG), s0 = d.slip0();
    const double J = d.v0 - d.kappa * d.R * d.omega0;
    REQUIRE(!p.impacts().empty());
    CHECK(p.impacts()[0].t == Approx(t1).epsilon(1e-15));
    double cone_used = 0.0;  // sum of the slip reductions mu (1 + 1/kappa) Lambda_N / m
    bool stuck_before = false;
    for (std::size_t k = 0; k < p.impacts().size(); ++k) {
      const auto& im = p.impacts()[k];
      CAPTURE(k);
      const double Vk = std::pow(d.e, k) * V;
      if (d.e < 1.0) {
        CHECK(im.t == Approx(t1 + 2 * V / kG * d.e * (1 - std::pow(d.e, k)) / (1 - d.e)).epsilon(1e-14));
      } else {
        CHECK(im.t == Approx(t1 + 2 * V / kG * k).epsilon(1e-14));
      }
      CHECK(im.V == Approx(Vk).epsilon(1e-14));
      CHECK(im.Lambda_N == Approx(d.m * (1 + d.e) * Vk).epsilon(1e-14));
      CHECK(std::abs(im.Lambda_T) <= d.mu * im.Lambda_N * (1 + 1e-15));
      // The slip never reverses; once stuck it stays stuck with no impulse.
      CHECK(im.slip_after * std::copysign(1.0, im.slip_before) >= -1e-14 * std::abs(s0));
      if (stuck_before) {
        CHECK(im.stuck);
        CHECK(std::abs(im.Lambda_T) <= 1e-14 * d.m * std::abs(s0));
      }
      if (im.stuck) {
        CHECK(im.slip_after == Approx(0.0).margin(1e-14 * std::abs(s0)));
        CHECK(im.Lambda_T == Approx(-d.m * d.kappa * im.slip_before / (1 + d.kappa)).margin(1e-15));
      } else {
        CHECK(im.Lambda_T == Approx(-std::copysign(d.mu * im.Lambda_N, im.slip_before)).epsilon(1e-15));
        cone_used += d.mu * (1 + 1 / d.kappa) * im.Lambda_N / d.m;
        // Closed form: |s_k| = |s0| - mu (1 + 1/kappa) (1 + e) V sum_{j<k} e^j while slipping.
        CHECK(std::abs(im.slip_after) == Approx(std::abs(s0) - cone_used).epsilon(1e-12));
      }
      stuck_before = stuck_before || im.stuck;
      // The exact state jumps by the impulses: M dv = L^T Lambda_N + T^T Lambda_T.
      const double eps = 1e-10 * Vk / kG;
      const auto before = *p.state(im.t - eps), after = *p.state(im.t + eps);
      if (eps > 1e-13) {
        CHECK(after.v[0] - before.v[0] == Approx(im.Lambda_T / d.m).margin(1e-12));
        CHECK(after.v[2] - before.v[2] == Approx(im.Lambda_T / (d.kappa * d.m * d.R)).margin(1e-10));
        CHECK(before.v[1] == Approx(-Vk).epsilon(1e-8));
        CHECK(after.v[1] == Approx(d.e * Vk).epsilon(1e-8).margin(1e-12));
        // Kinetic energy change: (Lambda_N (v_N- + v_N+) + Lambda_T (s- + s+)) / 2 <= 0.
        const double dE = d.energy(p, after) - d.energy(p, before);
        const double law = 0.5 * (im.Lambda_N * (d.e - 1) * Vk + im.Lambda_T * (im.slip_before + im.slip_after));
        CHECK(dE == Approx(law).margin(1e-8 * d.m * (V * V + s0 * s0)));
        CHECK(im.Lambda_T * (im.slip_before + im.slip_after) <= 1e-15);
      }
      // J = x' - kappa R theta' is untouched by every impulse along T.
      CHECK(im.v - d.kappa * d.R * im.omega == Approx(J).epsilon(1e-13).margin(1e-13));
    }
    const double left = std::abs(p.impacts().back().slip_after);
    const double slide = left / p.slip_decay_rate();
    if (d.e < 1.0) {
      CHECK(p.rest_time() == Approx(d.e == 0 ? t1 : t1 + 2 * d.e * V / (kG * (1 - d.e))).epsilon(1e-14));
      CHECK(p.rolling_onset_time() == Approx(p.rest_time() + slide).epsilon(1e-13));
      CHECK(p.final_velocity() == Approx(J / (1 + d.kappa)).epsilon(1e-12));
    } else {
      CHECK(std::isinf(p.rest_time()));
      CHECK(std::isinf(p.rolling_onset_time()));
    }
    int stuck_at = 0;
    for (std::size_t k = 0; k < p.impacts().size() && stuck_at == 0; ++k)
      if (p.impacts()[k].stuck) stuck_at = static_cast<int>(k) + 1;
    CHECK(stuck_at == first_stuck[n]);
  }
}

TEST_CASE("rolling disk exact, dropped: x, theta integrate v, omega through the impacts; continuous at rest", "[problems][exact][friction]") {
  // e = 0.99 runs past the 1000 marched impacts (e^1000 = 4e-5) before its Zeno time.
  for (double e : {0.5, 0.0, 0.99}) {
    CAPTURE(e);
    Disk d;
    d.h0 = 0.3, d.e = e, d.omega0 = 70.0, d.v0 = -0.5;
    const auto p = d.make();
    const double t_end = p.rolling_onset_time() + 0.5;
    // Breakpoints: v and omega are constant between impacts and linear on the floor, so the
    // midpoint rule is exact on every piece.
    std::vector<double> cuts = {0.0};
    for (const auto& im : p.impacts())
      if (im.t > cuts.back()) cuts.push_back(im.t);
    for (double t : {p.rest_time(), p.rolling_onset_time(), t_end})
      if (t > cuts.back()) cuts.push_back(t);
    double x = 0.0, theta = 0.0;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      x += midpoint([&](double t) { return p.state(t)->v[0]; }, cuts[i], cuts[i + 1], 4);
      theta += midpoint([&](double t) { return p.state(t)->v[2]; }, cuts[i], cuts[i + 1], 4);
    }
    const auto end = *p.state(t_end);
    CHECK(x == Approx(end.u[0]).epsilon(1e-12));
    CHECK(theta == Approx(end.u[2]).epsilon(1e-12));
    // The disk lands on the floor continuously: position, and the height and its rate.
    const double tr = p.rest_time(), eps = 1e-9;
    const auto before = *p.state(tr - eps), after = *p.state(tr + eps);
    const double v_max = std::max(std::abs(before.v[0]), std::abs(after.v[0]));
    const double omega_max = std::max(std::abs(before.v[2]), std::abs(after.v[2]));
    CHECK(std::abs(after.u[0] - before.u[0]) <= 2 * eps * v_max * (1 + 1e-6));
    CHECK(std::abs(after.u[2] - before.u[2]) <= 2 * eps * omega_max * (1 + 1e-6));
    CHECK(before.u[1] == Approx(0.0).margin(1e-8));
    CHECK(after.u[1] == 0.0);
  }
}

TEST_CASE("rolling disk exact: the rotating bouncing ball of Capobianco, Harsch, Eugster, Leine (2021)", "[problems][exact][friction]") {
  // Ball m = 1, R = 0.1, kappa = 2/5, dropped from centre height 1 (h0 = 0.9) with x' = 1,
  // omega = 50: s0 = 6 > 0.
  Disk d;
  d.kappa = 0.4, d.mu = 0.2, d.e = 0.5, d.v0 = 1.0, d.omega0 = 50.0, d.h0 = 0.9;
  const auto p = d.make();
  const double V = std::sqrt(2 * kG * 0.9), c = 0.2 * 3.5 * 1.5 * V;  // slip reduction of a full slip at impact 1
  REQUIRE(p.impacts().size() > 3);
  const auto& i1 = p.impacts()[0];
  const auto& i2 = p.impacts()[1];
  // Impact 1 slips: Lambda_T = -mu Lambda_N, the ball's x' reverses, slip 6 - c = 1.588 left.
  CHECK_FALSE(i1.stuck);
  CHECK(i1.Lambda_T == Approx(-0.2 * 1.5 * V).epsilon(1e-14));
  CHECK(i1.v == Approx(1.0 - 0.3 * V).epsilon(1e-14));
  CHECK(i1.v < 0.0);
  CHECK(i1.slip_after == Approx(6.0 - c).epsilon(1e-14));
  // Impact 2 (half the normal impulse, capacity c / 2 > 1.588) sticks, the rest stay stuck.
  CHECK(i2.stuck);
  CHECK(i2.Lambda_T == Approx(-0.4 / 1.4 * (6.0 - c)).epsilon(1e-13));
  CHECK(i2.slip_after == Approx(0.0).margin(1e-14));
  for (std::size_t k = 2; k < p.impacts().size(); ++k) {
    CHECK(p.impacts()[k].stuck);
    CHECK(p.impacts()[k].Lambda_T == Approx(0.0).margin(1e-15));
  }
  CHECK(p.final_velocity() == Approx(-1.0 / 1.4).epsilon(1e-13));
  CHECK(p.final_spin() == Approx(1.0 / 1.4 / 0.1).epsilon(1e-13));
  CHECK(p.rolling_onset_time() == Approx(p.rest_time()).epsilon(1e-14));
  CHECK(p.rest_time() == Approx(std::sqrt(2 * 0.9 / kG) + 2 * V / kG).epsilon(1e-14));
  // Their plastic cases (e = 0): omega 50 slides on after the impact, omega 10 sticks at once.
  d.e = 0.0, d.v0 = 0.0;
  const auto slides = d.make();
  REQUIRE(slides.impacts().size() == 1);
  CHECK_FALSE(slides.impacts()[0].stuck);
  CHECK(slides.rolling_onset_time() == Approx(std::sqrt(2 * 0.9 / kG) + (5.0 - 0.2 * 3.5 * V) / (0.2 * kG * 3.5)).epsilon(1e-13));
  d.omega0 = 10.0;
  const auto sticks = d.make();
  REQUIRE(sticks.impacts().size() == 1);
  CHECK(sticks.impacts()[0].stuck);
  CHECK(sticks.rolling_onset_time() == Approx(std::sqrt(2 * 0.9 / kG)).epsilon(1e-14));
  CHECK(sticks.final_velocity() == Approx(-0.4 * 0.1 * 10.0 / 1.4).epsilon(1e-13));
}

TEST_CASE("rolling disk exact: limits mu = 0, tiny kappa, e = 1", "[problems][exact][friction]") {
  SECTION("mu = 0: x' and omega never change") {
    for (double h0 : {0.0, 0.3}) {
      Disk d;
      d.mu = 0.0, d.h0 = h0, d.e = 0.7, d.v0 = 1.5, d.omega0 = 7.0;
      const auto p = d.make();
      CHECK_FALSE(p.contacts().has_friction());
      CHECK(std::isinf(p.rolling_onset_time()));
      for (double t : {0.0, 0.1, 0.5, 2.0, 50.0}) {
        const auto s = *p.state(t);
        CHECK(s.v[0] == 1.5);
        CHECK(s.v[2] == 7.0);
        CHECK(s.u[0] == Approx(1.5 * t).epsilon(1e-14));
        CHECK(s.u[2] == Approx(7.0 * t).epsilon(1e-14));
      }
      CHECK(p.final_velocity() == 1.5);
      CHECK(p.final_spin() == 7.0);
    }
  }
  SECTION("kappa -> 0: the spin adjusts at once, x' is kept") {
    Disk d;
    d.kappa = 1e-9, d.v0 = 2.0, d.omega0 = 5.0;
    const auto p = d.make();
    CHECK(p.rolling_onset_time() == Approx(2.5 / (0.3 * kG * (1 + 1e9))).epsilon(1e-13));
    CHECK(p.final_velocity() == Approx(2.0).epsilon(1e-8));
    CHECK(p.final_spin() == Approx(-20.0).epsilon(1e-8));
    const double lost = d.energy(p, *p.state(0.0)) - d.energy(p, *p.state(1.0));
    CHECK(lost == Approx(1e-9 * 2.5 * 2.5 / (2 * (1 + 1e-9))).epsilon(1e-6));
  }
  SECTION("e = 1: periodic bouncing, never at rest") {
    Disk d;
    d.e = 1.0, d.h0 = 0.2, d.omega0 = 30.0;
    const auto p = d.make();
    const double period = 2 * std::sqrt(2 * kG * 0.2) / kG;
    CHECK(p.impacts().size() == 1000);
    CHECK(p.impact_times(std::numeric_limits<double>::infinity()).size() == 1000);
    // Past the march, a finite t_end is refused rather than answered with the first 1000.
    const std::string refused = nsb::test::input_error_text_of([&] { (void)p.impact_times(1e9); });
    CHECK(refused.find("t_end = 1e+09") != std::string::npos);
    CHECK(refused.find("valid: t_end <= ") != std::string::npos);
    const auto a = *p.state(0.3 + 5000 * period), b = *p.state(0.3 + 5001 * period);
    CHECK(a.u[1] == Approx(b.u[1]).margin(1e-9));
    CHECK(a.u[1] > 0.0);
    CHECK(a.v[0] == b.v[0]);
    CHECK(a.v[0] == Approx(p.final_velocity()).epsilon(1e-15));
  }
}

TEST_CASE("rolling disk exact: heights between impacts, impact times, finite observables", "[problems][exact][friction]") {
  Disk d;
  d.h0 = 0.5, d.e = 0.8, d.omega0 = -40.0;
  const auto p = d.make();
  const auto times = p.impact_times(p.rest_time());
  REQUIRE(times.size() == p.impacts().size());
  CHECK(p.impact_times(times[2]).size() == 3);
  for (std::size_t k = 0; k + 1 < 10; ++k) {
    CHECK(p.state(times[k])->u[1] == Approx(0.0).margin(1e-12));
    CHECK(p.state(0.5 * (times[k] + times[k + 1]))->u[1] > 0.0);
  }
  std::vector<double> out(p.observable_names().size());
  REQUIRE(out.size() == 8);
  for (double t : {0.0, 0.2, times[5], p.rest_time(), p.rest_time() + 0.1, 1e6}) {
    p.observe(*p.state(t), nsb::Vec(), 0.0, out);
    for (double o : out) CHECK(std::isfinite(o));
    CHECK(out[6] == Approx(out[7]).margin(1e-15));
  }
}

TEST_CASE("rolling disk: model data and contacts", "[problems][exact][friction]") {
  for (double mu : {0.0, 0.3}) {
    Disk d;
    d.mu = mu, d.h0 = 0.2, d.R = 0.25;
    const auto p = d.make();
    CHECK_NOTHROW(nsb::check_contacts(p.contacts(), p.ndof(), p.name()));
    CHECK(p.contacts().has_friction() == (mu > 0.0));
    CHECK(Eigen::MatrixXd(p.gap_operator()) == Eigen::RowVector3d(0, 1, 0));
    CHECK(p.restitution() == 0.5);
    if (mu > 0.0) CHECK(Eigen::MatrixXd(p.contacts().tangent) == Eigen::RowVector3d(1, 0, 0.25));
    CHECK(Eigen::MatrixXd(p.mass_matrix()).diagonal() == Eigen::Vector3d(1, 1, 0.5 * 0.25 * 0.25));
    nsb::Vec f(3);
    p.external_force(0.0, f);
    CHECK(f == Eigen::Vector3d(0, -kG, 0));
    const auto s = p.initial_state();
    CHECK(s.u == Eigen::Vector3d(0, 0.2, 0));
    CHECK(s.v == Eigen::Vector3d(1, 0, 0));
    CHECK(p.load_potential(s.u) == Approx(kG * 0.2));
  }
}

TEST_CASE("rolling disk: bad parameters are rejected", "[problems][exact][friction][bad-input]") {
  const std::vector<std::map<std::string, std::string>> bad = {
      {{"mu", "-1"}},   {{"mu", "nan"}}, {{"mu", "inf"}}, {{"kappa", "0"}}, {{"kappa", "-0.5"}}, {{"R", "0"}},
      {{"R", "-0.1"}}, {{"e", "1.1"}},  {{"e", "-0.1"}}, {{"h0", "-1"}},   {{"m", "0"}},        {{"g", "0"}}};
  for (const auto& b : bad) {
    CAPTURE(b.begin()->first, b.begin()->second);
    CHECK_THROWS_AS(make_disk(b), nsb::InputError);
  }
}

TEST_CASE("rolling disk: field mesh, the centre as a vertex; the rotation in body arrays, exactly",
          "[problems][field-mesh][friction]") {
  const RollingDisk p = make_disk({{"R", "0.2"}});
  const auto mesh = p.field_mesh();
  REQUIRE(mesh.has_value());
  CHECK(mesh->dimension == 2);
  REQUIRE(mesh->npoints() == 1);
  CHECK(mesh->points.row(0) == Eigen::RowVector2d(0.0, 0.2));  // the centre when the lowest point is at y = 0
  CHECK(mesh->point_dofs.row(0) == Eigen::RowVector2i(0, 1));
  REQUIRE(mesh->body_columns() == 6);
  CHECK(mesh->body_arrays[3].name == "orientation");
  // The centre's position is its reference plus (x, y); the marker turns with theta: a
  // quarter turn counter-clockwise takes it from +x to +y.
  nsb::State s = p.initial_state();
  for (const double theta : {0.0, 0.5 * std::numbers::pi, -2.5}) {
    s.u << 0.3, 0.05, theta;
    s.v << 1.0, -2.0, 7.0;
    Eigen::MatrixXd out(1, 6);
    p.body_data(s, out);
    CHECK(out(0, 0) == 0.2);
    CHECK(out(0, 1) == theta);
    CHECK(out(0, 2) == 7.0);
    CHECK(out(0, 3) == Approx(std::cos(theta)).margin(1e-15));
    CHECK(out(0, 4) == Approx(std::sin(theta)).margin(1e-15));
    CHECK(out(0, 5) == 0.0);
    CHECK(std::hypot(out(0, 3), out(0, 4)) == Approx(1.0).epsilon(1e-15));
  }
  s.u << 0.0, 0.0, 0.5 * std::numbers::pi;
  Eigen::MatrixXd quarter(1, 6);
  p.body_data(s, quarter);
  CHECK(quarter(0, 3) == Approx(0.0).margin(1e-15));
  CHECK(quarter(0, 4) == Approx(1.0).epsilon(1e-15));
}
