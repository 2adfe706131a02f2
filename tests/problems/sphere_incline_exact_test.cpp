#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "problems/extrapolation_ode.hpp"
#include "problems/sphere_incline_exact.hpp"
#include "tests/support/input_error.hpp"

using Catch::Detail::Approx;
using nsb::SphereInclineExact;
using nsb::SphereInclineSpec;

namespace {

constexpr double deg = std::numbers::pi / 180.0;

SphereInclineSpec spec(double alpha, double mu, double vx0, double vy0, double wx0, double wy0, double wz0 = 0.0) {
  SphereInclineSpec s;
  s.R = 0.1, s.alpha = alpha, s.mu = mu, s.m = 2.0, s.g = 9.81;
  s.vx0 = vx0, s.vy0 = vy0, s.wx0 = wx0, s.wy0 = wy0, s.wz0 = wz0;
  return s;
}

// The sliding sphere's equations of motion, integrated on their own (no closed form): the state
// (x, y, v_x, v_y, omega_x, omega_y, omega_z, int |w|), friction -mu m g cos(alpha) w / |w|.
struct SlidingSphere {
  double R, g, alpha, mu;
  nsb::extrapolation::Vec<8> operator()(double, const nsb::extrapolation::Vec<8>& y) const {
    const Eigen::Vector2d w(y(2) - R * y(5), y(3) + R * y(4));
    const Eigen::Vector2d f = -mu * g * std::cos(alpha) * w / w.norm();  // F / m
    const double spin = 2.5 / R;                                         // m R / I
    nsb::extrapolation::Vec<8> d;
    d << y(2), y(3), g * std::sin(alpha) + f.x(), f.y(), spin * f.y(), -spin * f.x(), 0.0, w.norm();
    return d;
  }
};

nsb::extrapolation::Vec<8> initial(const SphereInclineSpec& s) {
  nsb::extrapolation::Vec<8> y;
  y << 0.0, 0.0, s.vx0, s.vy0, s.wx0, s.wy0, s.wz0, 0.0;
  return y;
}

double scaled_error(const SphereInclineExact::State& st, double length, const nsb::extrapolation::Vec<8>& y) {
  nsb::extrapolation::Vec<8> c;
  c << st.position.x(), st.position.y(), st.velocity.x(), st.velocity.y(), st.omega.x(), st.omega.y(), st.omega.z(),
      length;
  return ((c - y).cwiseQuotient(nsb::extrapolation::Vec<8>::Ones() + y.cwiseAbs())).cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("sphere on an incline: the closed form against the equations integrated to round-off", "[sphere_incline_exact]") {
  // Launched across the slope with a spin not aligned with it: the slip turns towards e_x.
  for (const auto& s : {spec(20.0, 0.3, 1.0, 0.5, 4.0, -3.0, 2.0), spec(30.0, 0.4, -1.0, 0.2, 0.0, 5.0),
                        spec(30.0, 0.1, 0.5, -1.0, 3.0, 0.0)}) {
    const SphereInclineExact exact(s);
    const SlidingSphere f{s.R, s.g, s.alpha * deg, s.mu};
    const double t_end = std::isfinite(exact.roll_time()) ? 0.9 * exact.roll_time() : 2.0;
    double h = 1e-3, t = 0.0;
    auto y = initial(s);
    for (int i = 1; i <= 4; ++i) {
      const double t_next = t_end * i / 4.0;
      y = nsb::extrapolation::integrate_to<8>(f, t, y, t_next, h);
      t = t_next;
      INFO("alpha " << s.alpha << " mu " << s.mu << " t " << t);
      CHECK(scaled_error(exact.state(t), exact.slip_path_length(t), y) < 1e-13);
    }
  }
}

TEST_CASE("sphere on an incline: the roll onset located on the integrated motion", "[sphere_incline_exact]") {
  const auto s = spec(20.0, 0.3, 1.0, 0.5, 4.0, -3.0);
  const SphereInclineExact exact(s);
  const double a = s.g * std::sin(s.alpha * deg), b = 3.5 * s.mu * s.g * std::cos(s.alpha * deg), k = b / a;
  REQUIRE(k > 1.0);
  // t_roll = (A / (k - 1) + B / (k + 1)) / a from the initial slip.
  const Eigen::Vector2d w0(s.vx0 - s.R * s.wy0, s.vy0 + s.R * s.wx0);
  const double A = 0.5 * (w0.norm() + w0.x()), B = 0.5 * (w0.norm() - w0.x());
  CHECK(exact.roll_time() == Approx((A / (k - 1.0) + B / (k + 1.0)) / a).epsilon(1e-15));
  // Integrated until |w| = eps |w0|; the last stretch, where the slip lies along e_x and falls
  // at the rate b - a, added: its error is of order eps times the angle squared.
  const double eps = 1e-9;
  const SlidingSphere f{s.R, s.g, s.alpha * deg, s.mu};
  const auto small = [&](double, const nsb::extrapolation::Vec<8>& y) {
    return std::hypot(y(2) - s.R * y(5), y(3) + s.R * y(4)) - eps * w0.norm();
  };
  const auto hit = nsb::extrapolation::find_event<8>(f, small, 0.0, initial(s), 10.0, 1e-3);
  REQUIRE(hit.found);
  const double t_roll = hit.t + eps * w0.norm() / (b - a);
  CHECK(exact.roll_time() == Approx(t_roll).epsilon(1e-12));
  // Slip zero from then on; the centre accelerates at (5/7) g sin(alpha) down the slope.
  const double t = exact.roll_time();
  CHECK(exact.slip_speed(t) == 0.0);
  CHECK(exact.slip_speed(t * (1.0 - 1e-6)) > 0.0);
  const auto v1 = exact.state(t + 1.0).velocity, v0 = exact.state(t).velocity;
  CHECK((v1 - v0 - Eigen::Vector3d(5.0 / 7.0 * a, 0.0, 0.0)).norm() < 1e-14 * v1.norm());
  const auto rolling = exact.state(t + 2.0);
  CHECK(std::abs(rolling.velocity.x() - s.R * rolling.omega.y()) < 1e-14 * rolling.velocity.norm());
  CHECK(std::abs(rolling.velocity.y() + s.R * rolling.omega.x()) < 1e-14 * rolling.velocity.norm());
}

TEST_CASE("sphere on an incline: the invariants of the motion", "[sphere_incline_exact]") {
  for (const auto& s : {spec(20.0, 0.3, 1.0, 0.5, 4.0, -3.0, 2.0), spec(35.0, 0.1, 0.0, -2.0, 1.0, 1.0, -1.0),
                        spec(0.0, 0.2, 1.0, -1.0, 2.0, 3.0, 1.0)}) {
    const SphereInclineExact exact(s);
    const auto start = exact.state(0.0);
    const auto L0 = exact.contact_angular_momentum(start);
    const double E0 = exact.energy(start), N = s.m * s.g * std::cos(s.alpha * deg);
    const double t_roll = exact.roll_time();
    for (const double t : {0.01, 0.1, 0.3, 1.0, 3.0}) {
      INFO("alpha " << s.alpha << " t " << t << " t_roll " << t_roll);
      const auto st = exact.state(t);
      // Friction and the normal force act at the contact point: only gravity's moment there.
      const Eigen::Vector3d dL(0.0, s.m * s.g * s.R * std::sin(s.alpha * deg) * t, 0.0);
      CHECK((exact.contact_angular_momentum(st) - L0 - dL).norm() < 1e-14 * (1.0 + L0.norm() + dL.norm()));
      CHECK(st.omega.z() == s.wz0);
      CHECK(st.position.z() == s.R);
      // Energy falls by the friction work, mu N int |w|.
      const double work = s.mu * N * exact.slip_path_length(t);
      CHECK(exact.energy(st) - E0 == Approx(-work).margin(1e-14 * (std::abs(E0) + work + 1.0)));
      // The slip velocity satisfies its equation (central differences, step 1e-6).
      if (t < 0.99 * t_roll || !std::isfinite(t_roll)) {
        const double dt = 1e-6;
        const Eigen::Vector2d rate = (exact.slip(t + dt) - exact.slip(t - dt)) / (2.0 * dt);
        const Eigen::Vector2d w = exact.slip(t);
        const Eigen::Vector2d rhs = Eigen::Vector2d(s.g * std::sin(s.alpha * deg), 0.0) -
                                    3.5 * s.mu * s.g * std::cos(s.alpha * deg) * w / w.norm();
        CHECK((rate - rhs).norm() < 1e-6 * (1.0 + rhs.norm()));
      }
    }
  }
}

TEST_CASE("sphere on an incline: level floor and launches along the slope", "[sphere_incline_exact]") {
  // Level floor: the slip keeps its direction and vanishes at 2 |w0| / (7 mu g).
  const auto level = spec(0.0, 0.25, 2.0, -1.0, 3.0, 5.0, 1.0);
  const SphereInclineExact flat(level);
  const Eigen::Vector2d w0(level.vx0 - level.R * level.wy0, level.vy0 + level.R * level.wx0);
  CHECK(flat.roll_time() == Approx(2.0 * w0.norm() / (7.0 * level.mu * level.g)).epsilon(1e-15));
  const Eigen::Vector2d mid = flat.slip(0.5 * flat.roll_time());
  CHECK((mid - 0.5 * w0).norm() < 1e-15 * w0.norm());
  // Final velocity v0 - (2/7) w0: the 2D rolling disk's (v0 + kappa R omega0) / (1 + kappa), kappa = 2/5.
  const auto end = flat.state(flat.roll_time() + 1.0);
  CHECK(end.velocity.x() == Approx((level.vx0 + 0.4 * level.R * level.wy0) / 1.4).epsilon(1e-14));
  CHECK(end.velocity.y() == Approx((level.vy0 - 0.4 * level.R * level.wx0) / 1.4).epsilon(1e-14));
  // A slope of 1e-6 degrees: k ~ 1e7, no overflow, and t_roll within a / b of the level floor's.
  SphereInclineSpec gentle = level;
  gentle.alpha = 1e-6;
  const SphereInclineExact nearly_flat(gentle);
  CHECK(nearly_flat.roll_time() == Approx(flat.roll_time()).epsilon(2.0 / nearly_flat.k()));
  CHECK(std::isfinite(nearly_flat.state(0.5 * flat.roll_time()).position.norm()));
  // Down the slope without spin: w stays along e_x, falling at b - a; up the slope at a + b.
  const double alpha = 15.0, mu = 0.3, g = 9.81;
  const double a = g * std::sin(alpha * deg), b = 3.5 * mu * g * std::cos(alpha * deg);
  const SphereInclineExact down(spec(alpha, mu, 3.0, 0.0, 0.0, 0.0));
  CHECK(down.roll_time() == Approx(3.0 / (b - a)).epsilon(1e-14));
  CHECK(down.slip(0.5 * down.roll_time()).y() == 0.0);
  CHECK(down.slip(0.5 * down.roll_time()).x() == Approx(1.5).epsilon(1e-13));
  const SphereInclineExact up(spec(alpha, mu, -3.0, 0.0, 0.0, 0.0));
  CHECK(up.roll_time() == Approx(3.0 / (a + b)).epsilon(1e-14));
  // Up the slope with too little friction: the slip passes zero and grows down the slope.
  const double mu_low = 0.05;
  const double b_low = 3.5 * mu_low * g * std::cos(alpha * deg);
  const SphereInclineExact back(spec(alpha, mu_low, -3.0, 0.0, 0.0, 0.0));
  CHECK(back.roll_time() == std::numeric_limits<double>::infinity());
  const double t_zero = 3.0 / (a + b_low);
  CHECK(back.slip(t_zero + 1.0).x() == Approx(a - b_low).epsilon(1e-12));
  // Released with no slip: rolling from the start when friction holds it.
  const SphereInclineExact at_rest(spec(alpha, mu, 0.0, 0.0, 0.0, 0.0));
  CHECK(at_rest.roll_time() == 0.0);
  CHECK(at_rest.state(1.0).velocity.x() == Approx(5.0 / 7.0 * a).epsilon(1e-15));
}

TEST_CASE("sphere on an incline: sliding for ever when mu <= (2/7) tan(alpha)", "[sphere_incline_exact]") {
  const double alpha = 30.0, g = 9.81;
  const double a = g * std::sin(alpha * deg);
  // mu < (2/7) tan(alpha): |w| grows like (a - b) t, its direction turning to e_x.
  const double mu = 0.1, b = 3.5 * mu * g * std::cos(alpha * deg);
  const SphereInclineExact slides(spec(alpha, mu, 0.5, -1.0, 3.0, 0.0));
  CHECK(slides.roll_time() == std::numeric_limits<double>::infinity());
  const Eigen::Vector2d late = slides.slip(200.0);
  CHECK(std::abs(late.y()) < 1e-6 * late.x());
  CHECK(late.x() / 200.0 == Approx(a - b).epsilon(1e-2));
  // mu = (2/7) tan(alpha) (k = 1): the slip tends to ((|w0| + w_x0) / 2, 0), never zero.
  SphereInclineSpec edge = spec(alpha, 2.0 / 7.0 * std::tan(alpha * deg), 0.5, -1.0, 3.0, 0.0);
  const SphereInclineExact critical(edge);
  REQUIRE(critical.k() == Approx(1.0).epsilon(1e-15));
  CHECK(critical.roll_time() == std::numeric_limits<double>::infinity());
  const Eigen::Vector2d w0(edge.vx0 - edge.R * edge.wy0, edge.vy0 + edge.R * edge.wx0);
  const Eigen::Vector2d limit = critical.slip(1e4);
  CHECK(limit.x() == Approx(0.5 * (w0.norm() + w0.x())).epsilon(1e-6));
  CHECK(std::abs(limit.y()) < 1e-6);
}

TEST_CASE("sphere on an incline: bad input is one line naming the parameter and its range", "[sphere_incline_exact]") {
  struct Case {
    const char* name;
    void (*set)(SphereInclineSpec&);
    const char* range;
  };
  const Case cases[] = {
      {"alpha", [](SphereInclineSpec& s) { s.alpha = 90.0; }, "[0, 90) degrees"},
      {"alpha", [](SphereInclineSpec& s) { s.alpha = -1.0; }, "[0, 90) degrees"},
      {"mu", [](SphereInclineSpec& s) { s.mu = -0.1; }, "[0, inf)"},
      {"R", [](SphereInclineSpec& s) { s.R = 0.0; }, "(0, inf)"},
      {"m", [](SphereInclineSpec& s) { s.m = -1.0; }, "(0, inf)"},
      {"wz0", [](SphereInclineSpec& s) { s.wz0 = std::nan(""); }, "(-inf, inf)"},
  };
  for (const auto& c : cases) {
    SphereInclineSpec s;
    c.set(s);
    const std::string text = nsb::test::input_error_text<SphereInclineExact>(s);
    INFO(text);
    CHECK(text.find(std::string(c.name) + " = ") != std::string::npos);
    CHECK(text.find(c.range) != std::string::npos);
    CHECK(text.find('\n') == std::string::npos);
  }
}

// Not a check: prints the numbers docs/three_d.md quotes. Hidden; run it by its tag:
// build/tests/nsbench_tests "[three_d_numbers]"
TEST_CASE("sphere on an incline: the numbers of docs/three_d.md", "[.][three_d_numbers]") {
  const auto s = spec(20.0, 0.3, 1.0, 0.5, 4.0, -3.0, 2.0);
  const SphereInclineExact exact(s);
  const auto end = exact.state(exact.roll_time());
  std::printf("R 0.1 alpha 20 mu 0.3 v0 (1, 0.5) omega0 (4, -3, 2): k %.15f t_roll %.15f s, v(t_roll) (%.15f, %.15f)\n",
              exact.k(), exact.roll_time(), end.velocity.x(), end.velocity.y());
  const SlidingSphere f{s.R, s.g, s.alpha * deg, s.mu};
  double h = 1e-3;
  const double t = 0.9 * exact.roll_time();
  const auto y = nsb::extrapolation::integrate_to<8>(f, 0.0, initial(s), t, h);
  std::printf("closed form against the integrated equations at 0.9 t_roll: max scaled difference %.2e\n",
              scaled_error(exact.state(t), exact.slip_path_length(t), y));
  const double a = s.g * std::sin(s.alpha * deg), b = 3.5 * s.mu * s.g * std::cos(s.alpha * deg);
  const double eps = 1e-9, w0 = std::hypot(s.vx0 - s.R * s.wy0, s.vy0 + s.R * s.wx0);
  const auto small = [&](double, const nsb::extrapolation::Vec<8>& z) {
    return std::hypot(z(2) - s.R * z(5), z(3) + s.R * z(4)) - eps * w0;
  };
  const auto hit = nsb::extrapolation::find_event<8>(f, small, 0.0, initial(s), 10.0, 1e-3);
  std::printf("t_roll from the integrated equations %.15f s (relative difference %.2e)\n",
              hit.t + eps * w0 / (b - a), std::abs(hit.t + eps * w0 / (b - a) - exact.roll_time()) / exact.roll_time());
}
