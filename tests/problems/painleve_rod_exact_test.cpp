#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>

#include "problems/painleve_rod_exact.hpp"
#include "tests/support/input_error.hpp"

using Catch::Detail::Approx;
using nsb::PainleveRodExact;
using nsb::PainleveRodSpec;

namespace {

constexpr double kPi = std::numbers::pi;
const PainleveRodSpec cardillo{1.0, 1.0, 31.0, 30.0, 5.0 / 3.0, 10.0};

// The test's own integration of the sliding phase, for the jam time: classical RK4 with a
// fixed step in tau (dt / dtau = D), z = (t, phi, phi'), until D < 1e-8, then the remaining
// time D / (-D' phi'). phi alone obeys J phi'' = -s lambda (cos phi - mu sin phi), lambda =
// m (g - s phi'^2 sin phi) / D, so this integrates 3 equations where the class integrates 7.
double rk4_jam_time(double dtau) {
  const double s = 1.0, m = 1.0, J = 1.0 / 3.0, mu = 5.0 / 3.0, g = 10.0, k = m * s * s / J;
  const auto D = [&](double phi) { return 1.0 + k * std::cos(phi) * (std::cos(phi) - mu * std::sin(phi)); };
  const auto f = [&](const Eigen::Vector3d& z) {
    const double N = m * (g - s * z(2) * z(2) * std::sin(z(1)));
    return Eigen::Vector3d(D(z(1)), D(z(1)) * z(2), -s * N * (std::cos(z(1)) - mu * std::sin(z(1))) / J);
  };
  Eigen::Vector3d z(0.0, 31.0 * kPi / 180.0, 0.0);
  while (D(z(1)) > 1e-8) {
    const Eigen::Vector3d k1 = f(z), k2 = f(z + 0.5 * dtau * k1), k3 = f(z + 0.5 * dtau * k2), k4 = f(z + dtau * k3);
    z += dtau / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  const double D_prime = -k * (std::sin(2.0 * z(1)) + mu * std::cos(2.0 * z(1)));
  return z(0) + D(z(1)) / (-D_prime * z(2));
}

}  // namespace

TEST_CASE("painleve rod: end A's gap, normal and tangent rows against finite differences", "[painleve_rod_exact]") {
  const PainleveRodExact rod(cardillo);
  std::mt19937 rng(32);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto end_a = [](const Eigen::Vector3d& U) {
    return Eigen::Vector2d(U(0) + std::cos(U(2)), U(1) - std::sin(U(2)));  // s = 1
  };
  const double d = 1e-6;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d U(u(rng), u(rng), 1.5 * u(rng));
    const auto k = rod.end_contact(U);
    CHECK(k.gap == Approx(end_a(U)(1)).margin(1e-15));
    for (int j = 0; j < 3; ++j) {
      Eigen::Vector3d plus = U, minus = U;
      plus(j) += d, minus(j) -= d;
      const Eigen::Vector2d slope = (end_a(plus) - end_a(minus)) / (2.0 * d);
      CHECK(k.normal_row(j) == Approx((rod.end_contact(plus).gap - rod.end_contact(minus).gap) / (2.0 * d)).margin(1e-9));
      CHECK(k.tangent_row(j) == Approx(slope(0)).margin(1e-9));
    }
  }
}

TEST_CASE("painleve rod: the sliding phase keeps end A on the floor; lambda from the momentum", "[painleve_rod_exact]") {
  const PainleveRodExact rod(cardillo);
  const double m = 1.0, mu = 5.0 / 3.0, g = 10.0, J = 1.0 / 3.0;
  for (const double t : {0.1, 0.3, 0.5, 0.7, 0.8, 0.81}) {
    INFO("t = " << t);
    const auto s = *rod.state(t);
    CHECK(s.t == t);
    // The constraint: its gap and normal velocity at round-off (the y equation carries lambda).
    CHECK(std::abs(rod.end_height(s)) < 1e-13);
    CHECK(std::abs(s.vy - std::cos(s.phi) * s.vphi) < 1e-13);
    CHECK(s.vx - std::sin(s.phi) * s.vphi > 0.0);  // still sliding forward
    // The momentum's rate by fourth-order central differences against the forces with
    // lambda(phi, phi') (error O(dt^4) times the fifth derivative, which grows near the jam).
    const double dt = 2e-5;
    const auto m2 = *rod.state(t - 2 * dt), m1 = *rod.state(t - dt), p1 = *rod.state(t + dt), p2 = *rod.state(t + 2 * dt);
    const auto rate = [&](double a2, double a1, double b1, double b2) { return (a2 - 8 * a1 + 8 * b1 - b2) / (12 * dt); };
    const double x_acc = rate(m2.vx, m1.vx, p1.vx, p2.vx), y_acc = rate(m2.vy, m1.vy, p1.vy, p2.vy);
    const double phi_acc = rate(m2.vphi, m1.vphi, p1.vphi, p2.vphi);
    const double lambda = rod.normal_force(s.phi, s.vphi);
    CHECK(lambda > 0.0);
    CHECK(m * y_acc + m * g == Approx(lambda).epsilon(1e-8));
    CHECK(m * x_acc == Approx(-mu * lambda).epsilon(1e-8));
    CHECK(J * phi_acc == Approx(-lambda * (std::cos(s.phi) - mu * std::sin(s.phi))).epsilon(1e-8));
    // End A's vertical acceleration is zero: y'' - s cos(phi) phi'' + s sin(phi) phi'^2.
    CHECK(std::abs(y_acc - std::cos(s.phi) * phi_acc + std::sin(s.phi) * s.vphi * s.vphi) < 1e-8 * lambda);
  }
}

TEST_CASE("painleve rod: the energy falls by the friction work", "[painleve_rod_exact]") {
  const PainleveRodExact rod(cardillo);
  const double m = 1.0, J = 1.0 / 3.0, mu = 5.0 / 3.0, g = 10.0;
  const auto energy = [&](const PainleveRodExact::State& s) {
    return 0.5 * m * (s.vx * s.vx + s.vy * s.vy) + 0.5 * J * s.vphi * s.vphi + m * g * s.y;
  };
  // Simpson's rule on the friction power -mu lambda |x'_A| over [0, 0.7].
  const int n = 400;
  const double T = 0.7, h = T / n;
  double work = 0.0;
  for (int i = 0; i <= n; ++i) {
    const auto s = *rod.state(i * h);
    const double power = -mu * rod.normal_force(s.phi, s.vphi) * std::abs(s.vx - std::sin(s.phi) * s.vphi);
    work += (i == 0 || i == n ? 1.0 : i % 2 ? 4.0 : 2.0) * power;
  }
  work *= h / 3.0;
  CHECK(energy(*rod.state(T)) - energy(*rod.state(0.0)) == Approx(work).epsilon(1e-9));
}

TEST_CASE("painleve rod: the cardillo data jam at phi = 45 degrees", "[painleve_rod_exact]") {
  const PainleveRodExact rod(cardillo);
  REQUIRE(rod.ending() == PainleveRodExact::Ending::jam);
  // D(phi) = 1 + 3 cos(phi) (cos(phi) - (5/3) sin(phi)) vanishes at 45 degrees exactly, where
  // the numerator vanishes too: s phi'^2 sin(phi) = g.
  CHECK(rod.denominator(kPi / 4) == Approx(0.0).margin(1e-15));
  const auto& end = rod.end_state();
  CHECK(end.phi == Approx(kPi / 4).epsilon(1e-9));
  CHECK(end.vphi == Approx(std::sqrt(10.0 / std::sin(kPi / 4))).epsilon(1e-5));
  CHECK(rod.normal_force(end.phi, end.vphi) > 1e4);
  // The jam time: measured 0.81454965867007 (it moves by 4e-15 when the threshold on D goes
  // from 1e-10 to 1e-8, by 5e-13 when the extrapolation's tolerance is loosened from 1e-15 to
  // 1e-13); the test's own RK4 (error O(dtau^4)) agrees.
  CHECK(rod.end_time() == Approx(0.81454965867007).margin(1e-12));
  CHECK(rk4_jam_time(2e-4) == Approx(rod.end_time()).margin(1e-10));
  // Near the jam lambda ~ u^(kappa - 1) + O(1), u = phi* - phi, kappa = 2/3: the slope of
  // log(lambda) against log(u) between u ~ 4e-7 and 4e-9 is -1/3 up to the O(u^(1/3)) term.
  const auto s1 = *rod.state(rod.end_time() - 1e-7), s2 = *rod.state(rod.end_time() - 1e-9);
  const double slope = std::log(rod.normal_force(s2.phi, s2.vphi) / rod.normal_force(s1.phi, s1.vphi)) /
                       std::log((kPi / 4 - s2.phi) / (kPi / 4 - s1.phi));
  CHECK(slope == Approx(-1.0 / 3.0).margin(0.01));
  // cardillo's marker (t = 0.83) lies after it: the sliding phase has ended there.
  CHECK_FALSE(rod.state(0.83).has_value());
}

TEST_CASE("painleve rod: the other endings", "[painleve_rod_exact]") {
  // End A trailing (v0 < 0): D > 0 always, no jam; the rod falls flat.
  const PainleveRodExact trailing(PainleveRodSpec{1.0, 1.0, 31.0, -30.0, 5.0 / 3.0, 10.0});
  CHECK(trailing.ending() == PainleveRodExact::Ending::leaves_range);
  CHECK(trailing.end_state().phi == Approx(0.0).margin(1e-12));
  // Slow slide: the slip stops first.
  const PainleveRodExact slow(PainleveRodSpec{1.0, 1.0, 31.0, 1.0, 5.0 / 3.0, 10.0});
  CHECK(slow.ending() == PainleveRodExact::Ending::slip_stops);
  const auto& e = slow.end_state();
  CHECK(std::abs(e.vx - std::sin(e.phi) * e.vphi) < 1e-13);
}

TEST_CASE("painleve rod: bad input is one line naming the parameter and its range", "[painleve_rod_exact]") {
  struct Case {
    const char* name;
    PainleveRodSpec spec;
    const char* range;
  };
  const Case cases[] = {
      {"s", {0.0, 1.0, 31.0, 30.0, 5.0 / 3.0, 10.0}, "(0, inf)"},
      {"m", {1.0, -1.0, 31.0, 30.0, 5.0 / 3.0, 10.0}, "(0, inf)"},
      {"mu", {1.0, 1.0, 31.0, 30.0, -0.5, 10.0}, "[0, inf)"},
      {"phi0", {1.0, 1.0, 0.0, 30.0, 5.0 / 3.0, 10.0}, "(0, 90) degrees"},
      {"phi0", {1.0, 1.0, 50.0, 30.0, 5.0 / 3.0, 10.0}, "> 0"},  // D(50 degrees) < 0
      {"v0", {1.0, 1.0, 31.0, 0.0, 5.0 / 3.0, 10.0}, "sliding phase"},
  };
  for (const auto& c : cases) {
    const std::string text = nsb::test::input_error_text<PainleveRodExact>(c.spec);
    INFO(text);
    CHECK(text.find(std::string(c.name) + " = ") != std::string::npos);
    CHECK(text.find(c.range) != std::string::npos);
    CHECK(text.find('\n') == std::string::npos);
  }
}

// Not a check: prints the numbers docs/rigid_bodies.md quotes. Hidden; run it by its tag:
// build/tests/nsbench_tests "[rigid_numbers]"
TEST_CASE("painleve rod: the numbers of docs/rigid_bodies.md", "[.][rigid_numbers]") {
  const PainleveRodExact rod(cardillo);
  const auto& end = rod.end_state();
  std::printf("painleve rod, cardillo data: jam at t* = %.15f s, phi -> %.12f deg, phi' -> %.9f rad/s "
              "(sqrt(g / (s sin 45 deg)) = %.9f), lambda = %.6g at D = %.1e; x' = %.9f m/s; "
              "RK4 (dtau 2e-4) %.15f s\n",
              rod.end_time(), end.phi * 180.0 / kPi, end.vphi, std::sqrt(10.0 / std::sin(kPi / 4)),
              rod.normal_force(end.phi, end.vphi), rod.denominator(end.phi), end.vx, rk4_jam_time(2e-4));
  for (const double t : {0.2, 0.4, 0.6, 0.8}) {
    const auto s = *rod.state(t);
    std::printf("  t %.1f: phi %.12f deg, x_end %.12f m, normal_force %.12f N\n", t, s.phi * 180.0 / kPi, rod.x_end(s),
                rod.normal_force(s.phi, s.vphi));
  }
}
