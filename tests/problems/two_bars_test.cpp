#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <cmath>

#include "problems/registry.hpp"
#include "problems/two_bars.hpp"

using Catch::Detail::Approx;
using nsb::Params;
using nsb::TwoBars;

namespace {

TwoBars bars(const std::map<std::string, std::string>& set = {}) { return TwoBars(Params(TwoBars::parameters_spec(), set)); }

// Energy and momentum of bar `bar`'s exact field, midpoint rule on `cells` cells: the fields
// are piecewise constant with at most 4 jumps, so the error is below 4 jumps x one cell.
struct TwoBarsIntegrals {
  double energy = 0.0, momentum = 0.0;
};
TwoBarsIntegrals integrate_two_bars_exact(const TwoBars& p, int bar, double t, int cells = 20000) {
  const auto& prm = p.parameters();
  const double len = prm.real(bar == 1 ? "L1" : "L2"), E = prm.real("E"), rho = prm.real("rho"), A = prm.real("A");
  const double dx = len / cells;
  TwoBarsIntegrals r;
  for (int i = 0; i < cells; ++i) {
    const double x = (i + 0.5) * dx, v = p.exact_velocity(bar, x, t), sig = p.exact_stress(bar, x, t);
    r.energy += dx * A * (0.5 * rho * v * v + 0.5 * sig * sig / E);
    r.momentum += dx * rho * A * v;
  }
  return r;
}

double exact_gap(const TwoBars& p, double t) {
  return p.parameters().real("g0") + p.exact_displacement(2, 0.0, t) - p.exact_displacement(1, p.parameters().real("L1"), t);
}

}  // namespace

TEST_CASE("two bars exact: the wave fronts at half the contact, jumps obey rho c [v] = -[sigma]",
          "[problems][exact][two-bars]") {
  const auto p = bars({{"L1", "1"}, {"L2", "1.5"}, {"g0", "0.2"}, {"v0", "0.5"}, {"E", "4"}});
  const double c = p.wave_speed(), v0 = 0.5, rho = 1.0, tc = p.contact_start();
  REQUIRE(c == 2.0);
  REQUIRE(tc == Approx(0.4));
  // s = 0.3: both fronts 0.6 from the contact ends, compressed behind them.
  const double t = tc + 0.3, xf1 = 1.0 - 0.6, xf2 = 0.6, eps = 1e-9;
  CHECK(p.exact_velocity(1, xf1 + 0.1, t) == Approx(v0 / 2));
  CHECK(p.exact_velocity(1, xf1 - 0.1, t) == Approx(v0));
  CHECK(p.exact_velocity(2, xf2 - 0.1, t) == Approx(v0 / 2));
  CHECK(p.exact_velocity(2, xf2 + 0.1, t) == 0.0);
  CHECK(p.exact_stress(1, xf1 + 0.1, t) == Approx(-rho * c * v0 / 2));
  CHECK(p.exact_stress(2, xf2 - 0.1, t) == Approx(-rho * c * v0 / 2));
  CHECK(p.exact_stress(1, xf1 - 0.1, t) == 0.0);
  CHECK(p.exact_stress(2, xf2 + 0.1, t) == 0.0);
  // Continuity of u and the jump condition across both fronts (bar 1's moves towards -x).
  for (int bar : {1, 2}) {
    const double xf = bar == 1 ? xf1 : xf2, speed = bar == 1 ? -c : c;
    CAPTURE(bar);
    CHECK(p.exact_displacement(bar, xf - eps, t) == Approx(p.exact_displacement(bar, xf + eps, t)).margin(1e-8));
    const double dv = p.exact_velocity(bar, xf + eps, t) - p.exact_velocity(bar, xf - eps, t);
    const double dsig = p.exact_stress(bar, xf + eps, t) - p.exact_stress(bar, xf - eps, t);
    CHECK(rho * speed * dv == Approx(-dsig));
  }
  // The unloading front in bar 1 after its reflection (s = 0.8: 0.6 from the free end).
  const double t2 = tc + 0.8;
  CHECK(p.exact_velocity(1, 0.5, t2) == 0.0);
  CHECK(p.exact_velocity(1, 0.7, t2) == Approx(v0 / 2));
  CHECK(p.exact_stress(1, 0.5, t2) == 0.0);
}

TEST_CASE("two bars exact: u_t = v and E u_x = sigma away from the fronts", "[problems][exact][two-bars]") {
  const auto p = bars({{"L1", "1"}, {"L2", "1.7"}, {"g0", "0.3"}, {"v0", "2"}, {"E", "2.25"}});
  const double E = 2.25, d = 1e-7;
  int checked = 0;
  for (int bar : {1, 2}) {
    const double len = bar == 1 ? 1.0 : 1.7;
    for (double t : {0.05, 0.3, 0.71, 1.1, 1.9, 2.6, 3.3, 4.7, 7.9}) {
      for (double x = 0.013; x < len; x += 0.0937) {
        // Skip points within 1e-5 of a front (the finite differences straddle the jump).
        if (std::abs(p.exact_velocity(bar, x, t - 1e-5) - p.exact_velocity(bar, x, t + 1e-5)) > 0.0) continue;
        if (std::abs(p.exact_stress(bar, x - 1e-5, t) - p.exact_stress(bar, x + 1e-5, t)) > 0.0) continue;
        CAPTURE(bar, t, x);
        const double ut = (p.exact_displacement(bar, x, t + d) - p.exact_displacement(bar, x, t - d)) / (2 * d);
        const double ux = (p.exact_displacement(bar, x + d, t) - p.exact_displacement(bar, x - d, t)) / (2 * d);
        CHECK(ut == Approx(p.exact_velocity(bar, x, t)).margin(1e-6));
        CHECK(E * ux == Approx(p.exact_stress(bar, x, t)).margin(1e-6));
        ++checked;
      }
    }
  }
  CHECK(checked > 150);
}

TEST_CASE("two bars exact: momentum and energy conserved, mean velocities, the gap closes then opens",
          "[problems][exact][two-bars]") {
  for (double L2 : {1.0, 1.3, 2.0}) {
    const auto p = bars({{"L1", "1"}, {"L2", std::to_string(L2)}, {"g0", "0.25"}, {"v0", "1.5"}});
    const double v0 = 1.5, m1 = p.bar_mass(1), c = p.wave_speed(), tc = p.contact_start();
    const double end = p.contact_end(), opens = tc + 2.0 * L2 / c;
    CHECK(end - tc == Approx(2.0));
    for (double t : {0.0, 0.1, 0.3, 0.9, 1.4, 1.9, 2.2, 2.5, 3.7, 4.6, 6.1, 9.3}) {
      CAPTURE(L2, t);
      const TwoBarsIntegrals b1 = integrate_two_bars_exact(p, 1, t), b2 = integrate_two_bars_exact(p, 2, t);
      const double tol = 4.0 * 2.0 / 20000;  // 4 jumps x one cell, relative
      CHECK(b1.momentum + b2.momentum == Approx(m1 * v0).epsilon(tol));
      CHECK(b1.energy + b2.energy == Approx(p.exact_energy()).epsilon(tol));
      CHECK(b1.momentum / m1 == Approx(p.exact_mean_velocity(1, t)).margin(tol * v0));
      CHECK(b2.momentum / p.bar_mass(2) == Approx(p.exact_mean_velocity(2, t)).margin(tol * v0));
      // Closed while the force acts and until bar 2's pulse returns, open afterwards.
      const double g = exact_gap(p, t);
      if (t < tc) CHECK(g == Approx(0.25 - v0 * t));
      else if (t <= opens) CHECK(g == Approx(0.0).margin(1e-12));
      else CHECK(g > 0.0);
      CHECK(p.exact_contact_force(t) == (t > tc && t < end ? p.contact_force_level() : 0.0));
    }
    // Bar 1 leaves at rest, unstrained, at u = g0 + v0 L1 / c; bar 2 carries the momentum.
    for (double x : {0.0, 0.4, 1.0}) {
      CHECK(p.exact_velocity(1, x, end + 0.5) == 0.0);
      CHECK(p.exact_displacement(1, x, end + 0.5) == Approx(0.25 + v0 * 1.0 / c));
    }
    CHECK(p.exact_mean_velocity(1, end + 1.0) == Approx(0.0).margin(1e-15));
    CHECK(p.exact_mean_velocity(2, end + 1.0) * p.bar_mass(2) == Approx(m1 * v0));
    CHECK(p.contact_force_level() * (end - tc) == Approx(m1 * v0));
  }
  // Equal bars: bar 2 leaves as a rigid body at v0.
  const auto eq = bars({{"L1", "1"}, {"L2", "1"}});
  for (double x : {0.0, 0.3, 1.0}) CHECK(eq.exact_velocity(2, x, 2.5) == Approx(1.0));
}

TEST_CASE("two bars: discrete operators, mass models, contact row on both bodies, stable step",
          "[problems][two-bars]") {
  for (std::string mass : {"lumped", "consistent", "singular"}) {
    CAPTURE(mass);
    const auto p = bars({{"N1", "6"}, {"N2", "9"}, {"L2", "1.2"}, {"E", "4"}, {"mass", mass}});
    REQUIRE(p.ndof() == 17);
    const Eigen::MatrixXd M = Eigen::MatrixXd(p.mass_matrix());
    nsb::SpMat Ks;
    p.tangent_stiffness(nsb::Vec::Zero(p.ndof()), Ks);
    const Eigen::MatrixXd K = Eigen::MatrixXd(Ks);
    // Each bar keeps its mass; no coupling between the bars' blocks.
    CHECK(M.topLeftCorner(7, 7).sum() == Approx(p.bar_mass(1)));
    CHECK(M.bottomRightCorner(10, 10).sum() == Approx(p.bar_mass(2)));
    CHECK(M.topRightCorner(7, 10).norm() == 0.0);
    CHECK(K.topRightCorner(7, 10).norm() == 0.0);
    if (mass == "singular") {
      CHECK(M(p.dof(1, 6), p.dof(1, 6)) == 0.0);
      CHECK(M(p.dof(2, 0), p.dof(2, 0)) == 0.0);
    }
    // Rigid motions of each bar carry no force; F_int = K u; strain energy u^T K u / 2.
    nsb::Vec u = nsb::Vec::Zero(p.ndof()), f(p.ndof());
    u.head(7).setConstant(0.3);
    u.tail(10).setConstant(-0.2);
    p.internal_force(u, f);
    CHECK(f.norm() == Approx(0.0).margin(1e-13));
    u = nsb::Vec::LinSpaced(p.ndof(), 0.1, 1.7).array().sin();
    p.internal_force(u, f);
    CHECK((f - K * u).norm() == Approx(0.0).margin(1e-12));
    CHECK(p.strain_energy(u) == Approx(0.5 * u.dot(K * u)));
    // g = g0 + u_2,first - u_1,last.
    const nsb::SpMat& L = p.gap_operator();
    CHECK(L.nonZeros() == 2);
    CHECK(L.coeff(0, p.dof(1, 6)) == -1.0);
    CHECK(L.coeff(0, p.dof(2, 0)) == 1.0);
    if (mass != "singular") {
      Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
      // h2 = 1.2/9 < h1 = 1/6 sets the step; the free-free lumped chain reaches 2c/h.
      const double bound = 2.0 / std::sqrt(es.eigenvalues().maxCoeff());
      CHECK(bound >= p.stable_step() * (1 - 1e-12));
      CHECK(bound <= p.stable_step() * 1.05);
    }
  }
  const auto p = bars();
  const auto s = p.initial_state();
  CHECK(p.mean_velocity(1, s.v) == Approx(1.0));
  CHECK(p.mean_velocity(2, s.v) == 0.0);
  CHECK(p.momentum(s.v) == Approx(p.exact_momentum()));
  CHECK(p.impact_times(10.0) == std::vector<double>{0.0});
  CHECK(bars({{"g0", "0.5"}, {"v0", "2"}}).impact_times(0.2).empty());
  const auto e = p.state(0.7);
  REQUIRE(e);
  CHECK(e->u.size() == p.ndof());
  CHECK(e->v[p.dof(1, 0)] == Approx(1.0));  // the front has not reached bar 1's far end
  CHECK(e->v[p.dof(2, 0)] == Approx(0.5));
}

TEST_CASE("two bars: registry, observables and bad input", "[problems][two-bars]") {
  const auto p = nsb::make_problem("two-bars");
  CHECK(p->name() == "two-bars");
  const auto names = p->observable_names();
  for (std::string n : {"v1_mean", "v2_mean", "contact_force", "contact_force_exact", "momentum", "momentum_exact"})
    CHECK(std::find(names.begin(), names.end(), n) != names.end());
  std::vector<double> out(names.size());
  nsb::Vec impulse = nsb::Vec::Constant(1, 0.05);
  p->observe(p->initial_state(), impulse, 0.1, out);
  CHECK(out[2] == Approx(0.5));
  try {
    nsb::make_problem("two-bars", {{"L1", "2"}, {"L2", "1"}});
    FAIL("L2 < L1 accepted");
  } catch (const nsb::InputError& e) {
    const std::string what = e.what();
    CHECK(what.find("L2") != std::string::npos);
    CHECK(what.find("L1") != std::string::npos);
  }
  try {
    nsb::make_problem("two-bars", {{"g0", "-0.1"}});
    FAIL("negative gap accepted");
  } catch (const nsb::InputError& e) {
    CHECK(std::string(e.what()).find("g0") != std::string::npos);
  }
  CHECK_THROWS_AS(nsb::make_problem("two-bars", {{"v0", "0"}}), nsb::InputError);
  CHECK_THROWS_AS(nsb::make_problem("two-bars", {{"N2", "0"}}), nsb::InputError);
  CHECK_THROWS_AS(nsb::make_problem("two-bars", {{"mass", "diagonal"}}), nsb::InputError);
}

TEST_CASE("two bars: field mesh (two bodies) and element stress against the exact field", "[problems][two-bars][field-mesh]") {
  const TwoBars p = bars({{"g0", "0.05"}, {"N1", "20"}, {"N2", "40"}});
  const auto mesh = p.field_mesh();
  REQUIRE(mesh.has_value());
  REQUIRE(mesh->npoints() == p.ndof());
  REQUIRE(mesh->ncells() == 60);
  for (nsb::Index i = 0; i <= 20; ++i) CHECK(mesh->point_dofs(i, 0) == p.dof(1, i));
  for (nsb::Index j = 0; j <= 40; ++j) {
    CHECK(mesh->point_dofs(21 + j, 0) == p.dof(2, j));
    CHECK(mesh->points(21 + j, 0) == Approx(1.05 + j * p.element_size(2)));
  }
  CHECK(mesh->cell_body[19] == 0);
  CHECK(mesh->cell_body[20] == 1);
  // Between the fronts the exact u is linear: the element stress is the exact one.
  Eigen::MatrixXd sigma(mesh->ncells(), 1);
  const double t = p.contact_start() + 0.73, h = p.element_size(1), c = p.wave_speed();
  const auto s = p.state(t);
  REQUIRE(s.has_value());
  p.cell_stress(s->u, sigma);
  int compared = 0, loaded = 0;
  for (nsb::Index e = 0; e < 60; ++e) {
    const int b = e < 20 ? 1 : 2;
    const double x0 = b == 1 ? 0.0 : 1.05, mid = x0 + ((b == 1 ? e : e - 20) + 0.5) * h;
    // Fronts: bar 1's at L1 - c s and its reflection, bar 2's at L1 + g0 + c s.
    const double s_in = t - p.contact_start();
    const double fronts[] = {1.0 - c * s_in, c * s_in - 1.0, 1.05 + c * s_in};
    bool near = false;
    for (const double f : fronts) near = near || std::abs(mid - f) < h;
    if (near) continue;
    // exact_stress takes bar 2's abscissa from its own left end.
    const double exact = p.exact_stress(b, b == 1 ? mid : mid - 1.05, t);
    CHECK(sigma(e, 0) == Approx(exact).margin(1e-12));
    ++compared;
    loaded += exact < 0.0;
  }
  CHECK(compared >= 50);
  CHECK(loaded >= 20);
}

// Issue 30, finding 6: N1 = N2 = 1e8 was OOM-killed after 142 s; refused before allocating.
TEST_CASE("two bars: sizes that cannot fit in memory are refused before allocating", "[problems][two-bars]") {
  ::setenv("NSBENCH_MEMORY_LIMIT", "1G", 1);
  CHECK_THROWS_WITH(nsb::make_problem("two-bars", {{"N1", "100000000"}, {"N2", "100000000"}}),
                    "two-bars: N1 + N2 = 100000000 + 100000000 needs about 37.3 GiB, more than the 1 GiB available "
                    "(NSBENCH_MEMORY_LIMIT); valid: N1 + N2 <= 5368709");
  CHECK(nsb::make_problem("two-bars", {{"N1", "100"}, {"N2", "200"}})->ndof() > 300);
  ::unsetenv("NSBENCH_MEMORY_LIMIT");
}
