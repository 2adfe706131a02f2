#include <catch2/catch.hpp>
#include <cstdlib>
#include <cmath>

#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/mass_on_bar.hpp"
#include "problems/registry.hpp"

using Catch::Detail::Approx;
using nsb::MassOnBar;
using nsb::Params;

namespace {

MassOnBar striker(const std::map<std::string, std::string>& set = {}) {
  return MassOnBar(Params(MassOnBar::parameters_spec(), set));
}

// int_a^b F by composite 3-point Gauss-Legendre (never at the ends, where F may jump).
double integrate_force(const MassOnBar& p, double a, double b, int n = 4000) {
  const double h = (b - a) / n, r = std::sqrt(0.6) / 2;
  double s = 0.0;
  for (int i = 0; i < n; ++i) {
    const double m = a + (i + 0.5) * h;
    s += h * (5.0 * p.exact_contact_force(m - r * h) + 8.0 * p.exact_contact_force(m) + 5.0 * p.exact_contact_force(m + r * h)) / 18.0;
  }
  return s;
}

// The three regimes of the header: M = bar mass / 4, = bar mass (default), = 4 bar masses.
const std::vector<double> masses = {0.25, 1.0, 4.0};

}  // namespace

TEST_CASE("mass on bar exact: Saint-Venant's first interval, +2 Z v0 jumps at each return, M V' = -F",
          "[problems][exact][mass-on-bar]") {
  for (double M : masses) {
    const auto p = striker({{"M", std::to_string(M)}, {"v0", "0.7"}, {"E", "4"}, {"L", "1.5"}});
    const double v0 = 0.7, Z = p.impedance(), T = p.round_trip(), ts = p.first_separation();
    CAPTURE(M, ts);
    REQUIRE(T == Approx(1.5));
    REQUIRE(Z == Approx(2.0));
    for (double t : {0.0, 0.2, 0.7, 1.3, 1.49})
      CHECK(p.exact_contact_force(t) == Approx(Z * v0 * std::exp(-Z * t / M)));
    // The jumps, while in contact.
    int jumps = 0;
    for (int n = 1; n * T < ts; ++n, ++jumps) {
      const double eps = 1e-9;
      CHECK(p.exact_contact_force(n * T + eps) - p.exact_contact_force(n * T - eps) == Approx(2 * Z * v0).epsilon(1e-6));
      CHECK(p.exact_mass_velocity(n * T + eps) == Approx(p.exact_mass_velocity(n * T - eps)).margin(1e-6 * v0));
    }
    CHECK(jumps >= 1);
    // The mass's equation, by central differences between the jumps.
    for (double t = 0.0137; t < ts; t += 0.0731) {
      const double d = 1e-6;
      if (std::abs(std::remainder(t, T)) < 2 * d) continue;
      CHECK(-M * (p.exact_mass_velocity(t + d) - p.exact_mass_velocity(t - d)) / (2 * d) ==
            Approx(p.exact_contact_force(t)).margin(1e-6 * Z * v0));
    }
  }
}

TEST_CASE("mass on bar exact: momentum M v0 = M V(t) + int_0^t F through every contact; F > 0 in contact",
          "[problems][exact][mass-on-bar]") {
  for (double M : masses) {
    const auto p = striker({{"M", std::to_string(M)}});
    const double T = p.round_trip(), v0 = 1.0, end = p.contact_end();
    const auto impacts = p.impact_times(1e9);
    CAPTURE(M, end, impacts.size());
    // With M >= the bar's mass the end, thrown back by the returning front, catches the mass
    // again; the light mass (M = bar mass / 4) leaves fast enough to escape.
    CHECK(impacts.size() == (M >= 1.0 ? 2u : 1u));
    // Integrate between every time where F may jump or vanish: the returns n T, the impacts
    // and the separations (found as the zeros of F after each impact).
    std::vector<double> cuts;
    for (double t = T; t < end + T; t += T) cuts.push_back(t);
    for (double t : impacts) cuts.push_back(t);
    for (double t = 1e-4; t < end + T; t += 1e-4)
      if (p.exact_contact_force(t) == 0.0 && p.exact_contact_force(t - 1e-4) > 0.0) {
        double a = t - 1e-4, b = t;
        for (int k = 0; k < 60; ++k) (p.exact_contact_force(0.5 * (a + b)) > 0.0 ? a : b) = 0.5 * (a + b);
        cuts.push_back(b);
      }
    cuts.push_back(end + T);
    std::sort(cuts.begin(), cuts.end());
    double impulse = 0.0, a = 0.0;
    for (double b : cuts) {
      if (b - a < 1e-12) continue;
      impulse += integrate_force(p, a, b);
      a = b;
      CHECK(M * v0 == Approx(M * p.exact_mass_velocity(a) + impulse).epsilon(1e-9));
    }
    CHECK(p.exact_contact_force(end + 0.1) == 0.0);
    CHECK(p.exact_mass_velocity(end + 5.0) == p.exact_mass_velocity(end));
    // The mass leaves no faster than it came (the bar keeps some energy).
    CHECK(p.exact_mass_velocity(end) < 0.0);
    CHECK(p.exact_mass_velocity(end) > -v0);
    CHECK(p.first_separation() <= end);
  }
}

TEST_CASE("mass on bar exact: second-interval separation in closed form and the M = 1.728 rho A L threshold",
          "[problems][exact][mass-on-bar]") {
  // alpha = rho A L / M = 1: F = Z v0 e^{-tau} (e^{-2} + 2 - 2 tau) after T, zero at tau = 1 + e^{-2}/2.
  const auto p = striker();
  const double tau = 1.0 + std::exp(-2.0) / 2.0;
  CHECK(p.first_separation() == Approx(p.round_trip() + tau).epsilon(1e-12));
  CHECK(p.exact_mass_velocity(p.first_separation()) == Approx(std::exp(-tau) * (std::exp(-2.0) - 2.0 * tau)).epsilon(1e-10));
  CHECK(striker({{"M", "1.72"}}).first_separation() < 2.0 * p.round_trip());
  CHECK(striker({{"M", "1.74"}}).first_separation() > 2.0 * p.round_trip());
  // Long contacts: a heavy mass stays about half a period of the mass on the bar's static
  // spring E A / L, pi sqrt(M L / (E A)) (the limit M >> rho A L).
  const auto heavy = striker({{"M", "100"}});
  CHECK(heavy.first_separation() == Approx(M_PI * 10.0).epsilon(0.05));
}

TEST_CASE("mass on bar: a fine CD-Lagrange run follows the exact mass velocity and contacts",
          "[problems][mass-on-bar]") {
  const int N = 400;
  for (double M : masses) {
    const auto p = striker({{"M", std::to_string(M)}, {"N", std::to_string(N)}});
    auto integ = nsb::make_integrator("cd-lagrange");
    integ->init(p, p.initial_state());
    const double dt = 0.9 * p.stable_step(), t_end = p.contact_end() + p.round_trip();
    double max_v_error = 0.0, last_contact = -1.0;
    // Steps with an impulse after 10 without: the lumped contact node chatters for a few steps
    // at a release (contact opens and closes while F is about 0), which is not a new contact.
    std::vector<double> starts;
    const auto r = nsb::run(p, *integ, {dt, t_end, 1, false}, [&](const nsb::Integrator& it, const nsb::StepInfo&) {
      const auto& s = it.state();
      max_v_error = std::max(max_v_error, std::abs(s.v[p.mass_dof()] - p.exact_mass_velocity(s.t)));
      if (it.impulses()[0] > 0.0) {
        if (s.t - last_contact > 10.5 * dt) starts.push_back(s.t);
        last_contact = s.t;
      }
    });
    REQUIRE(r.status == nsb::RunStatus::Ok);
    const auto impacts = p.impact_times(t_end);
    CAPTURE(M, p.contact_end(), last_contact, max_v_error, starts.size());
    // The velocity is an integral of F: its error is the impulse of a few steps of mistimed
    // force (F jumps by 2 Z v0 at the fronts), a few times Z v0 dt / M (measured: 2.3 to 3.1).
    CHECK(max_v_error <= 5.0 * p.impedance() * dt / M);
    // The same contacts, each starting and the last ending within 10 steps (the discrete
    // fronts spread over several elements; measured: up to 7 steps).
    REQUIRE(starts.size() == impacts.size());
    for (std::size_t i = 0; i < starts.size(); ++i) CHECK(std::abs(starts[i] - impacts[i]) <= 10.0 * dt);
    CHECK(std::abs(last_contact - p.contact_end()) <= 10.0 * dt);
    // Energy: the lumped contact node (rho A h / 2) meets the mass plastically, losing about
    // its share h / (2 L) (times M v0^2 / 2 times rho A L / M) at each impact: O(h).
    const double loss = (p.exact_energy() - r.final_energy) / p.exact_energy();
    CHECK(loss >= 0.0);
    CHECK(loss <= 2.0 * impacts.size() * p.bar_mass() / M / (2.0 * N));
  }
}

TEST_CASE("mass on bar: operators, contact row on both bodies, registry and bad input", "[problems][mass-on-bar]") {
  for (std::string mass : {"lumped", "consistent", "singular"}) {
    CAPTURE(mass);
    const auto p = striker({{"N", "8"}, {"M", "3"}, {"mass", mass}});
    REQUIRE(p.ndof() == 9);
    const nsb::SpMat M = p.mass_matrix();
    // The bar's mass without the clamped node's row (h / 2; consistent: and its coupling
    // h / 6 to node N - 1), plus M.
    const double removed = mass == "consistent" ? 1.0 / 16 + 1.0 / 48 : 1.0 / 16;
    CHECK(nsb::Vec(M * nsb::Vec::Ones(9)).head(8).sum() == Approx(p.bar_mass() * (1.0 - removed)));
    CHECK(M.coeff(8, 8) == 3.0);
    if (mass == "singular") CHECK(M.coeff(0, 0) == 0.0);
    nsb::SpMat K;
    p.tangent_stiffness(nsb::Vec::Zero(9), K);
    CHECK(nsb::Vec(K.col(8)).norm() == 0.0);  // the mass is rigid
    const nsb::Vec u = nsb::Vec::LinSpaced(9, 0.3, -0.4).array().cos();
    nsb::Vec f(9);
    p.internal_force(u, f);
    CHECK((f - K * u).norm() == Approx(0.0).margin(1e-12));
    CHECK(p.strain_energy(u) == Approx(0.5 * u.dot(K * u)));
    CHECK(p.gap_operator().coeff(0, 0) == 1.0);
    CHECK(p.gap_operator().coeff(0, 8) == -1.0);
    CHECK(p.gap_operator().nonZeros() == 2);
  }
  const auto p = nsb::make_problem("mass-on-bar");
  CHECK(p->name() == "mass-on-bar");
  CHECK(p->observable_names() == std::vector<std::string>{"contact_force", "v_mass", "contact_force_exact", "v_mass_exact"});
  CHECK(p->initial_state().v[100] == 1.0);
  CHECK_THROWS_AS(nsb::make_problem("mass-on-bar", {{"M", "0"}}), nsb::InputError);
  CHECK_THROWS_AS(nsb::make_problem("mass-on-bar", {{"N", "1"}}), nsb::InputError);
  CHECK_THROWS_AS(nsb::make_problem("mass-on-bar", {{"v0", "-1"}}), nsb::InputError);
  // M within [0.01, 100] bar masses (the exact sweep's range); the ends work.
  CHECK_NOTHROW(nsb::make_problem("mass-on-bar", {{"M", "0.01"}}));
  CHECK_NOTHROW(nsb::make_problem("mass-on-bar", {{"M", "100"}, {"L", "1"}}));
  for (std::string M : {"0.009", "101"}) {
    try {
      nsb::make_problem("mass-on-bar", {{"M", M}});
      FAIL("M = " << M << " accepted");
    } catch (const nsb::InputError& e) {
      CHECK(std::string(e.what()).find("M = ") != std::string::npos);
    }
  }
}

TEST_CASE("mass on bar: field mesh of the bar (clamped node without dof) and element stress; the striker a vertex",
          "[problems][mass-on-bar][field-mesh]") {
  for (const char* mass : {"lumped", "consistent", "singular"}) {
    INFO(mass);
    const MassOnBar p = MassOnBar(Params(MassOnBar::parameters_spec(), {{"N", "8"}, {"E", "3"}, {"mass", mass}}));
    const auto mesh = p.field_mesh();
    REQUIRE(mesh.has_value());
    REQUIRE(mesh->npoints() == 10);
    REQUIRE(mesh->ncells() == 9);
    REQUIRE(mesh->nelements() == 8);
    for (nsb::Index i = 0; i < 8; ++i) CHECK(mesh->point_dofs(i, 0) == i);
    CHECK(mesh->point_dofs(8, 0) == -1);  // the clamp
    // The striker: a vertex (body 1) at the free end x = 0, on its dof.
    CHECK(mesh->cell_size(8) == 1);
    CHECK(mesh->cells(8, 0) == 9);
    CHECK(mesh->cells(8, 1) == -1);
    CHECK(mesh->points.row(9) == Eigen::RowVector2d(0.0, 0.0));
    CHECK(mesh->point_dofs(9, 0) == p.mass_dof());
    CHECK(mesh->cell_body[8] == 1);
    // u = eps (x - L): uniform strain, u = 0 at the clamp; the striker's dof is not read.
    const double eps = -2e-3;
    nsb::Vec u(p.ndof());
    for (nsb::Index i = 0; i < 8; ++i) u[i] = eps * (mesh->points(i, 0) - 1.0);
    u[p.mass_dof()] = 1e6;
    Eigen::MatrixXd sigma(8, 1);
    p.cell_stress(u, sigma);
    for (nsb::Index e = 0; e < 8; ++e) CHECK(sigma(e, 0) == Approx(3.0 * eps));
  }
}

// Issue 30, finding 6: a size that cannot fit is refused before allocating, as for the other bars.
TEST_CASE("mass on bar: an N that cannot fit in memory is refused before allocating", "[problems][mass-on-bar]") {
  ::setenv("NSBENCH_MEMORY_LIMIT", "1G", 1);
  CHECK_THROWS_WITH(nsb::make_problem("mass-on-bar", {{"N", "100000000"}}),
                    "mass-on-bar: N = 100000000 needs about 18.6 GiB, more than the 1 GiB available "
                    "(NSBENCH_MEMORY_LIMIT); valid: N <= 5368709");
  ::unsetenv("NSBENCH_MEMORY_LIMIT");
}
