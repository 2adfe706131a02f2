#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "problems/bouncing_mass.hpp"
#include "tests/support/input_error.hpp"

using Catch::Detail::Approx;
using nsb::BouncingMass;
using nsb::Params;

namespace {
BouncingMass make(double e, double h0 = 1.0, double v0 = 0.0) {
  return BouncingMass(Params(BouncingMass::parameters_spec(),
                             {{"e", std::to_string(e)}, {"h0", std::to_string(h0)}, {"v0", std::to_string(v0)}}));
}
double energy(const BouncingMass& p, const nsb::State& s) {
  return 0.5 * p.parameters().real("m") * s.v[0] * s.v[0] + p.load_potential(s.u);
}
}  // namespace

TEST_CASE("bouncing mass exact: first impact solves h0 + v0 t - g t^2/2 = 0", "[problems][exact]") {
  for (double v0 : {-2.0, 0.0, 3.0}) {
    const auto p = make(0.9, 1.5, v0);
    const double t1 = p.impact_time(1), g = 9.81;
    CHECK(1.5 + v0 * t1 - 0.5 * g * t1 * t1 == Approx(0.0).margin(1e-12));
    CHECK(p.state(t1 * (1 - 1e-12))->v[0] == Approx(-p.first_impact_speed()).epsilon(1e-9));
  }
}

TEST_CASE("bouncing mass exact: restitution, flight energy E0 e^(2i), continuity at impacts", "[problems][exact]") {
  for (double e : {1.0, 0.9, 0.5}) {
    const auto p = make(e, 1.0, 0.5);
    const double E0 = energy(p, *p.state(0.0));
    CHECK(E0 == Approx(p.initial_energy()).epsilon(1e-14));
    for (int i = 1; i <= 6; ++i) {
      const double ti = p.impact_time(i), eps = 1e-9;
      const auto before = *p.state(ti - eps), after = *p.state(ti + eps);
      CHECK(before.u[0] == Approx(0.0).margin(1e-8));
      CHECK(after.u[0] == Approx(0.0).margin(1e-8));
      CHECK(after.v[0] == Approx(-e * before.v[0]).epsilon(1e-7));
      // Energy is constant in flight i and equal to E0 e^(2i).
      const double mid = 0.5 * (ti + p.impact_time(i + 1));
      CHECK(energy(p, *p.state(mid)) == Approx(p.energy_after_impact(i)).epsilon(1e-12));
      CHECK(p.energy_after_impact(i) == Approx(E0 * std::pow(e, 2 * i)).epsilon(1e-14));
    }
    // Through the Problem interface: one energy per impact before t_end, the same numbers.
    const nsb::Problem& generic = p;
    const auto energies = generic.exact()->energies_after_impacts(p.impact_time(6));
    REQUIRE(energies.size() == 6);
    REQUIRE(generic.exact()->impact_times(p.impact_time(6)).size() == 6);
    for (int i = 1; i <= 6; ++i) CHECK(energies[static_cast<std::size_t>(i - 1)] == p.energy_after_impact(i));
  }
}

TEST_CASE("bouncing mass exact: impacts accumulate at the Zeno time, then rest", "[problems][exact]") {
  const auto p = make(0.5);
  const double tz = p.zeno_time();
  CHECK(tz == Approx(p.impact_time(1) + 2 * 0.5 * p.first_impact_speed() / (9.81 * 0.5)).epsilon(1e-14));
  CHECK(p.impact_time(60) == Approx(tz).epsilon(1e-14));
  CHECK(p.impact_time(60) <= tz);
  const auto rest = *p.state(tz + 0.1);
  CHECK(rest.u[0] == 0.0);
  CHECK(rest.v[0] == 0.0);
  CHECK(std::isinf(make(1.0).zeno_time()));
  CHECK(make(0.0).zeno_time() == p.impact_time(1));
}

TEST_CASE("bouncing mass exact: e = 1 is periodic", "[problems][exact]") {
  const auto p = make(1.0, 2.0);
  const double period = 2 * p.first_impact_speed() / 9.81;
  for (double t : {0.3, 1.1, 5.7}) {
    const auto a = *p.state(t + p.impact_time(1)), b = *p.state(t + p.impact_time(1) + 10 * period);
    CHECK(a.u[0] == Approx(b.u[0]).margin(1e-9));
    CHECK(a.v[0] == Approx(b.v[0]).margin(1e-9));
  }
}

TEST_CASE("bouncing mass: field mesh, a vertex at the floor whose y is the height", "[problems][field-mesh]") {
  const BouncingMass p = make(0.9, 2.0);
  const auto mesh = p.field_mesh();
  REQUIRE(mesh.has_value());
  CHECK(mesh->dimension == 2);
  REQUIRE(mesh->npoints() == 1);
  CHECK(mesh->points.row(0) == Eigen::RowVector2d(0.0, 0.0));
  CHECK(mesh->point_dofs.row(0) == Eigen::RowVector2i(-1, 0));  // no horizontal dof; q on y
  CHECK(mesh->nbodies() == 1);
  CHECK(mesh->nelements() == 0);
  // The contact row L = [1] pushes the mass up: along the point's +y.
  CHECK(p.gap_operator().coeff(0, mesh->point_dofs(0, 1)) == 1.0);
  CHECK(p.initial_state().u[mesh->point_dofs(0, 1)] == 2.0);
}

TEST_CASE("bouncing mass exact: impact_times honours t_end or refuses it, never capped silently", "[problems][exact]") {
  // e = 1: an endless sequence, listed to its 100000th impact; t_end = 1e12 used to give 1000.
  const auto elastic = make(1.0);
  const nsb::ExactSolution& exact = elastic;
  const double period = 2.0 * elastic.first_impact_speed() / 9.81;
  const auto times = exact.impact_times(elastic.impact_time(1) + 4999.5 * period);
  CHECK(times.size() == 5000);
  CHECK(times.back() == elastic.impact_time(5000));
  CHECK(exact.impact_times(std::numeric_limits<double>::infinity()).size() == 100000);
  const std::string refused = nsb::test::input_error_text_of([&] { (void)exact.impact_times(1e12); });
  CHECK(refused.find("t_end = 1e+12") != std::string::npos);
  CHECK(refused.find("valid: t_end <= ") != std::string::npos);
  // e = 0.99: 3,098 impacts before floating point merges them with the Zeno time, all listed.
  const auto lossy = make(0.99);
  const auto zeno = lossy.impact_times(1e12);
  CHECK(zeno.size() > 1000);
  CHECK(zeno.back() < lossy.zeno_time());
  CHECK(std::is_sorted(zeno.begin(), zeno.end()));
  // At rest on the floor: no impact, whatever the restitution.
  CHECK(make(1.0, 0.0).impact_times(1e12).empty());
}
