#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "problems/sliding_mass.hpp"

using Catch::Detail::Approx;
using nsb::Params;
using nsb::SlidingMass;

namespace {

const double g = 9.81;

SlidingMass make_slider(double alpha, double mu, double v0, double m = 1.0) {
  return SlidingMass(Params(SlidingMass::parameters_spec(), {{"alpha", std::to_string(alpha)},
                                                            {"mu", std::to_string(mu)},
                                                            {"v0", std::to_string(v0)},
                                                            {"m", std::to_string(m)}}));
}

double rad(double deg) { return deg * std::numbers::pi / 180.0; }

double x_at(const SlidingMass& p, double t) { return p.state(t)->u[0]; }
double v_at(const SlidingMass& p, double t) { return p.state(t)->v[0]; }

// Trapezoid rule on [a, b] with n panels: exact (to round-off) for a linear integrand.
template <class F>
double trapezoid_sum(F f, double a, double b, int n = 1000) {
  const double h = (b - a) / n;
  double sum = 0.5 * (f(a) + f(b));
  for (int i = 1; i < n; ++i) sum += f(a + i * h);
  return sum * h;
}

// The integral of f over [0, t_end], split at the stop time: v is linear on each side of it,
// so the trapezoid rule is exact there and any mismatch is an error of the exact solution.
template <class F>
double integral(const SlidingMass& p, F f, double t_end) {
  const double ts = p.stop_time();
  if (ts <= 0.0 || ts >= t_end) return trapezoid_sum(f, 0.0, t_end);
  return trapezoid_sum(f, 0.0, ts) + trapezoid_sum(f, ts, t_end);
}

// alpha, mu, v0, covering every branch: stop and stick down the slope, accelerate, stop going
// up then stick or slide back, start at rest and stay or slide, flat floor.
struct Case {
  double alpha, mu, v0;
};
const std::vector<Case> cases = {{20, 0.5, 2},  {30, 0.2, 2}, {30, 0.2, -3}, {10, 0.5, -3},
                                 {30, 0.2, 0},  {20, 0.5, 0}, {0, 0.5, 5},   {60, 0.9, 1.5}};

}  // namespace

TEST_CASE("sliding mass exact: x is the integral of v, v is continuous", "[problems][exact][friction]") {
  for (const auto& c : cases) {
    CAPTURE(c.alpha, c.mu, c.v0);
    const auto p = make_slider(c.alpha, c.mu, c.v0);
    const double t_end = 3.0;
    const double x_end = x_at(p, t_end);
    CHECK(integral(p, [&](double t) { return v_at(p, t); }, t_end) == Approx(x_end).epsilon(1e-12).margin(1e-12));
    // v is Lipschitz with constant a_up = g (sin + mu cos): no jump at the stop.
    const double a_max = g * (std::sin(rad(c.alpha)) + c.mu * std::cos(rad(c.alpha)));
    for (double t : {p.stop_time(), 0.7, 2.1}) {
      if (!std::isfinite(t) || t <= 0.0) continue;
      const double eps = 1e-9;
      CHECK(std::abs(v_at(p, t + eps) - v_at(p, t - eps)) <= 2 * eps * a_max + 1e-14);
      CHECK(std::abs(x_at(p, t + eps) - x_at(p, t - eps)) <= 2 * eps * (std::abs(v_at(p, t)) + 1e-6));
    }
    const auto s0 = *p.state(0.0);
    CHECK(s0.u[0] == 0.0);
    CHECK(s0.v[0] == c.v0);
    CHECK(p.state(1.3)->u[1] == 0.0);
    CHECK(p.state(1.3)->v[1] == 0.0);
  }
}

TEST_CASE("sliding mass exact: stop time and distance", "[problems][exact][friction]") {
  SECTION("down the slope, friction wins: stops at v0 / (-a) after v0^2 / (-2a), then sticks") {
    for (const auto& [alpha, mu, v0] : std::vector<Case>{{20, 0.5, 2}, {0, 0.5, 5}, {45, 1.5, 0.3}}) {
      const auto p = make_slider(alpha, mu, v0);
      const double a = g * (std::sin(rad(alpha)) - mu * std::cos(rad(alpha)));
      REQUIRE(a < 0.0);
      CHECK(p.sliding_acceleration() == Approx(a).epsilon(1e-14));
      CHECK(p.stop_time() == Approx(v0 / -a).epsilon(1e-14));
      CHECK(p.stop_distance() == Approx(v0 * v0 / (-2 * a)).epsilon(1e-14));
      CHECK(p.sticks());
      CHECK(x_at(p, p.stop_time()) == Approx(p.stop_distance()).epsilon(1e-14));
      CHECK(v_at(p, p.stop_time()) == Approx(0.0).margin(1e-14 * v0));
      for (double later : {1e-6, 1.0, 100.0}) {
        CHECK(x_at(p, p.stop_time() + later) == Approx(p.stop_distance()).epsilon(1e-14));
        CHECK(v_at(p, p.stop_time() + later) == 0.0);
      }
    }
    // Flat floor, mu = 0.5, v0 = 5: the textbook 2.548 m in 1.019 s.
    const auto flat = make_slider(0, 0.5, 5);
    CHECK(flat.stop_distance() == Approx(25.0 / (2 * 0.5 * g)).epsilon(1e-15));
    CHECK(flat.stop_time() == Approx(5.0 / (0.5 * g)).epsilon(1e-15));
  }
  SECTION("up the slope: stops at |v0| / a_up, then sticks or slides back down") {
    const auto back = make_slider(30, 0.2, -3), stay = make_slider(10, 0.5, -3);
    for (const auto* p : {&back, &stay}) {
      const double alpha = p->parameters().real("alpha"), mu = p->parameters().real("mu");
      const double a_up = g * (std::sin(rad(alpha)) + mu * std::cos(rad(alpha)));
      CHECK(p->stop_time() == Approx(3.0 / a_up).epsilon(1e-14));
      CHECK(p->stop_distance() == Approx(9.0 / (2 * a_up)).epsilon(1e-14));
      CHECK(x_at(*p, p->stop_time()) == Approx(-p->stop_distance()).epsilon(1e-14));
    }
    CHECK_FALSE(back.sticks());  // tan 30 = 0.577 > 0.2
    CHECK(stay.sticks());        // tan 10 = 0.176 <= 0.5
    const double a_down = g * (std::sin(rad(30)) - 0.2 * std::cos(rad(30))), dt = 0.8;
    CHECK(v_at(back, back.stop_time() + dt) == Approx(a_down * dt).epsilon(1e-13));
    CHECK(x_at(back, back.stop_time() + dt) == Approx(-back.stop_distance() + 0.5 * a_down * dt * dt).epsilon(1e-13));
    CHECK(x_at(stay, stay.stop_time() + 5.0) == Approx(-stay.stop_distance()).epsilon(1e-14));
  }
  SECTION("never stops when gravity wins going down") {
    const auto p = make_slider(30, 0.2, 2);
    CHECK(std::isinf(p.stop_time()));
    CHECK(std::isinf(p.stop_distance()));
    const double a = g * (std::sin(rad(30)) - 0.2 * std::cos(rad(30)));
    CHECK(x_at(p, 2.0) == Approx(2 * 2.0 + 0.5 * a * 4.0).epsilon(1e-14));
  }
  SECTION("from rest: stays when tan(alpha) <= mu, else slides down with a_down") {
    const auto stays = make_slider(20, 0.5, 0), slides = make_slider(30, 0.2, 0);
    CHECK(stays.stop_time() == 0.0);
    CHECK(stays.sticks());
    CHECK(x_at(stays, 10.0) == 0.0);
    CHECK(v_at(stays, 10.0) == 0.0);
    CHECK_FALSE(slides.sticks());
    CHECK(x_at(slides, 2.0) == Approx(0.5 * slides.sliding_acceleration() * 4.0).epsilon(1e-15));
  }
  SECTION("mu = tan(alpha) exactly: a = 0, v0 kept for ever, or rest kept") {
    for (const auto& [alpha, mu] : std::vector<std::pair<std::string, std::string>>{{"45", "1"}, {"30", "0.57735026918962573"}}) {
      CAPTURE(alpha, mu);
      const SlidingMass moving(Params(SlidingMass::parameters_spec(), {{"alpha", alpha}, {"mu", mu}, {"v0", "2"}}));
      CHECK(moving.sliding_acceleration() == 0.0);
      CHECK(std::isinf(moving.stop_time()));
      CHECK(v_at(moving, 1e4) == 2.0);
      CHECK(x_at(moving, 1e4) == 2e4);
      const SlidingMass resting(Params(SlidingMass::parameters_spec(), {{"alpha", alpha}, {"mu", mu}, {"v0", "0"}}));
      CHECK(resting.sticks());
      CHECK(x_at(resting, 1e4) == 0.0);
    }
  }
}

TEST_CASE("sliding mass exact: the energy falls by the friction work mu m g cos(alpha) * path", "[problems][exact][friction]") {
  for (const auto& c : cases) {
    CAPTURE(c.alpha, c.mu, c.v0);
    const double m = 2.5;
    const auto p = make_slider(c.alpha, c.mu, c.v0, m);
    const auto energy = [&](double t) {
      const auto s = *p.state(t);
      return 0.5 * m * s.v.squaredNorm() + p.load_potential(s.u);
    };
    const double normal = m * g * std::cos(rad(c.alpha));
    for (double t : {0.4, 1.7, 3.0}) {
      // Path length: the integral of |v| (linear on each side of the stop, where v changes sign).
      const double path = integral(p, [&](double s) { return std::abs(v_at(p, s)); }, t);
      CHECK(energy(0.0) - energy(t) == Approx(c.mu * normal * path).epsilon(1e-11).margin(1e-12));
    }
  }
}

TEST_CASE("sliding mass exact: the friction force stays in the cone and opposes sliding", "[problems][exact][friction]") {
  for (const auto& c : cases) {
    CAPTURE(c.alpha, c.mu, c.v0);
    const auto p = make_slider(c.alpha, c.mu, c.v0);
    const double a = rad(c.alpha), bound = c.mu * g * std::cos(a);  // per unit mass
    for (double t = 0.05; t < 3.0; t += 0.05) {
      if (std::abs(t - p.stop_time()) < 1e-3) continue;  // the difference quotient straddles the kink
      // v is linear in t away from the stop, so the central difference is exact up to
      // round-off ~ eps |v| / h = 1e-10.
      const double h = 1e-6, acc = (v_at(p, t + h) - v_at(p, t - h)) / (2 * h);
      const double friction = acc - g * std::sin(a);
      CHECK(std::abs(friction) <= bound + 1e-8);
      const double v = v_at(p, t);
      if (v != 0.0) CHECK(friction == Approx(-std::copysign(bound, v)).margin(1e-8));
      else CHECK(friction == Approx(-g * std::sin(a)).margin(1e-8));  // static friction holds gravity
    }
  }
}

TEST_CASE("sliding mass exact: mu = 0 is free sliding x = v0 t + g sin(alpha) t^2 / 2", "[problems][exact][friction]") {
  for (double v0 : {-2.0, 0.0, 1.5})
    for (double alpha : {0.0, 25.0, 80.0}) {
      const auto p = make_slider(alpha, 0.0, v0);
      CHECK_FALSE(p.contacts().has_friction());
      CHECK(p.contacts().tangent.rows() == 0);
      // Going up it stops (unless the plane is flat) and comes back without sticking.
      const double inf = std::numeric_limits<double>::infinity();
      const bool never = v0 > 0.0 || (v0 < 0.0 && alpha == 0.0);
      CHECK(p.stop_time() == Approx(never ? inf : (v0 == 0.0 ? 0.0 : -v0 / (g * std::sin(rad(alpha))))));
      CHECK(p.sticks() == (alpha == 0.0));
      for (double t : {0.3, 2.0}) {
        CHECK(x_at(p, t) == Approx(v0 * t + 0.5 * g * std::sin(rad(alpha)) * t * t).epsilon(1e-14).margin(1e-15));
        CHECK(v_at(p, t) == Approx(v0 + g * std::sin(rad(alpha)) * t).epsilon(1e-14).margin(1e-15));
      }
    }
}

TEST_CASE("sliding mass: model data and contacts", "[problems][exact][friction]") {
  for (double mu : {0.0, 0.5}) {
    const auto p = make_slider(20, mu, 2);
    CHECK_NOTHROW(nsb::check_contacts(p.contacts(), p.ndof(), p.name()));
    CHECK(p.contacts().has_friction() == (mu > 0.0));
    CHECK(Eigen::MatrixXd(p.gap_operator()) == Eigen::RowVector2d(0, 1));
    if (mu > 0.0) {
      CHECK(Eigen::MatrixXd(p.contacts().tangent) == Eigen::RowVector2d(1, 0));
      CHECK(p.contacts().mu[0] == mu);
      CHECK(p.contacts().tangent_velocity[0] == 0.0);
    }
    // F_ext = -grad V_load (V_load is linear: differences are exact up to round-off).
    nsb::Vec f(2), u0 = nsb::Vec::Zero(2), ex = nsb::Vec::Unit(2, 0), ey = nsb::Vec::Unit(2, 1);
    p.external_force(0.0, f);
    CHECK(f[0] == Approx(p.load_potential(u0) - p.load_potential(ex)).epsilon(1e-14));
    CHECK(f[1] == Approx(p.load_potential(u0) - p.load_potential(ey)).epsilon(1e-14));
    const auto s = p.initial_state();
    CHECK(p.gap_offset()[0] + (p.gap_operator() * s.u)[0] == 0.0);  // starts on the plane
    CHECK(s.v[0] == 2.0);
    std::vector<double> out(p.observable_names().size());
    REQUIRE(out.size() == 4);
    p.observe(*p.state(10.0), nsb::Vec(), 0.0, out);
    for (double o : out) CHECK(std::isfinite(o));
    CHECK(out[0] == out[2]);
  }
}

TEST_CASE("sliding mass: bad parameters are rejected", "[problems][exact][friction][bad-input]") {
  const std::vector<std::map<std::string, std::string>> bad = {{{"mu", "-1"}},    {{"mu", "nan"}},   {{"mu", "inf"}},
                                                               {{"alpha", "90"}}, {{"alpha", "-1"}}, {{"m", "0"}},
                                                               {{"g", "0"}},      {{"v0", "inf"}}};
  for (const auto& b : bad) {
    CAPTURE(b.begin()->first, b.begin()->second);
    CHECK_THROWS_AS(SlidingMass(Params(SlidingMass::parameters_spec(), b)), nsb::InputError);
  }
  CHECK_NOTHROW(SlidingMass(Params(SlidingMass::parameters_spec(), {{"alpha", "89.9"}, {"mu", "0"}})));
}

TEST_CASE("sliding mass: field mesh, a vertex in the plane's frame (x down the slope, y normal)", "[problems][field-mesh]") {
  const SlidingMass p = make_slider(30.0, 0.2, 1.0);
  const auto mesh = p.field_mesh();
  REQUIRE(mesh.has_value());
  CHECK(mesh->dimension == 2);
  REQUIRE(mesh->npoints() == 1);
  CHECK(mesh->points.row(0) == Eigen::RowVector2d(0.0, 0.0));
  CHECK(mesh->point_dofs.row(0) == Eigen::RowVector2i(0, 1));
  CHECK(mesh->nbodies() == 1);
  // The normal row acts on y, the tangent row on x.
  CHECK(p.gap_operator().coeff(0, mesh->point_dofs(0, 1)) == 1.0);
  CHECK(p.contacts().tangent.coeff(0, mesh->point_dofs(0, 0)) == 1.0);
}
