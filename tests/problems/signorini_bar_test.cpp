#include <Eigen/Dense>
#include <algorithm>
#include <bit>
#include <cstdint>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>

#include "problems/registry.hpp"
#include "problems/signorini_bar.hpp"

using Catch::Detail::Approx;
using nsb::Params;
using nsb::SignoriniBar;

namespace {

SignoriniBar bar(const std::map<std::string, std::string>& set = {}) {
  return SignoriniBar(Params(SignoriniBar::parameters_spec(), set));
}

// Energy and momentum of the exact field by integrating over the pieces between the fronts,
// where the integrand is constant: exact up to round-off.
struct Integrals {
  double energy, momentum;
};
Integrals integrate_exact(const SignoriniBar& p, double t) {
  const auto& prm = p.parameters();
  const double L = prm.real("L"), E = prm.real("E"), rho = prm.real("rho"), A = prm.real("A");
  const double s = t - p.contact_start(), c = p.wave_speed();
  std::vector<double> cuts = {0.0, L, std::clamp(c * s, 0.0, L), std::clamp(2 * L - c * s, 0.0, L)};
  std::sort(cuts.begin(), cuts.end());
  Integrals r{0.0, 0.0};
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = cuts[i], b = cuts[i + 1], x = 0.5 * (a + b);
    const double v = p.exact_velocity(x, t), sig = p.exact_stress(x, t);
    r.energy += (b - a) * A * (0.5 * rho * v * v + 0.5 * sig * sig / E);
    r.momentum += (b - a) * rho * A * v;
  }
  return r;
}

}  // namespace

TEST_CASE("signorini bar exact: displacement continuous across both fronts, jumps obey rho c [v] = -[sigma]",
          "[problems][exact][signorini-bar]") {
  for (double g0 : {0.0, 0.3}) {
    const auto p = bar({{"g0", std::to_string(g0)}, {"E", "4"}, {"L", "2"}, {"v0", "0.5"}});
    const double c = p.wave_speed(), t0 = p.contact_start(), rho = 1.0, v0 = 0.5, eps = 1e-9;
    for (double s : {0.1, 0.5, 0.9, 1.3, 1.7}) {
      const double t = t0 + s;
      // Incoming front x = c s (s < L/c), reflected front x = 2L - c s (s > L/c).
      const double x = (c * s < 2.0) ? c * s : 4.0 - c * s;
      CAPTURE(g0, s, x);
      CHECK(p.exact_displacement(x - eps, t) == Approx(p.exact_displacement(x + eps, t)).margin(1e-8));
      const double dv = p.exact_velocity(x + eps, t) - p.exact_velocity(x - eps, t);
      const double dsig = p.exact_stress(x + eps, t) - p.exact_stress(x - eps, t);
      CHECK(std::abs(dv) == Approx(v0));
      // Front moving towards +x (incoming) has speed +c, the reflected one -c.
      const double speed = (c * s < 2.0) ? c : -c;
      CHECK(rho * speed * dv == Approx(-dsig));
    }
    // The contact point: on the wall during contact, leaves it with +v0.
    CHECK(p.exact_displacement(0.0, t0 + 0.5 * p.contact_duration()) == Approx(-g0).margin(1e-15));
    CHECK(p.exact_velocity(0.0, t0 + p.contact_duration() + 0.1) == Approx(v0));
    CHECK(p.exact_displacement(0.0, t0 + p.contact_duration() + 0.1) == Approx(-g0 + 0.1 * v0));
    // Continuity in time at the start and the end of contact, at every node.
    for (double te : {t0, t0 + p.contact_duration()})
      for (double x : {0.0, 0.5, 1.0, 2.0})
        CHECK(p.exact_displacement(x, te - eps) == Approx(p.exact_displacement(x, te + eps)).margin(1e-8));
  }
}

TEST_CASE("signorini bar exact: energy constant, momentum and contact force consistent",
          "[problems][exact][signorini-bar]") {
  for (double g0 : {0.0, 0.25}) {
    const auto p = bar({{"g0", std::to_string(g0)}, {"rho", "3"}, {"A", "0.5"}, {"v0", "2"}});
    const double T = p.contact_duration(), t0 = p.contact_start();
    for (double t : {0.0, 0.5 * t0, t0 + 0.1 * T, t0 + 0.5 * T, t0 + 0.8 * T, t0 + 1.2 * T}) {
      CAPTURE(g0, t);
      const Integrals I = integrate_exact(p, t);
      CHECK(I.energy == Approx(p.exact_energy()).epsilon(1e-13));
      CHECK(I.momentum == Approx(p.exact_momentum(t)).margin(1e-12));
      // The wall's force is the bar's compressive end stress times the section.
      CHECK(p.exact_contact_force(t) == Approx(-0.5 * p.exact_stress(0.0, t)).margin(1e-12));
    }
    // Total impulse A rho c v0 T = 2 M v0: the momentum reverses.
    CHECK(p.exact_momentum(t0 + T) == Approx(-p.exact_momentum(0.0)));
  }
}

TEST_CASE("signorini bar: tangent stiffness and strain energy match finite differences of F_int",
          "[problems][signorini-bar]") {
  for (std::string mass : {"lumped", "singular", "consistent"}) {
    const auto p = bar({{"N", "7"}, {"E", "3"}, {"A", "2"}, {"mass", mass}});
    const nsb::Index n = p.ndof();
    nsb::Vec u = nsb::Vec::LinSpaced(n, 0.1, -0.4);
    u[3] += 0.2;
    nsb::SpMat K;
    p.tangent_stiffness(u, K);
    nsb::Vec f0(n), f1(n), fm(n);
    p.internal_force(u, f0);
    // Central differences are exact for a linear force up to round-off: O(eps |f| / h).
    const double h = 1e-6;
    for (nsb::Index j = 0; j < n; ++j) {
      nsb::Vec up = u, um = u;
      up[j] += h;
      um[j] -= h;
      p.internal_force(up, f1);
      p.internal_force(um, fm);
      const nsb::Vec col = (f1 - fm) / (2 * h);
      CHECK((col - nsb::Vec(K.col(j))).norm() <= 1e-8 * K.norm());
      CHECK((p.strain_energy(up) - p.strain_energy(um)) / (2 * h) == Approx(f0[j]).margin(1e-8));
    }
    // Refilling an existing pattern keeps the values.
    p.tangent_stiffness(u, K);
    CHECK((nsb::Vec(K * u) - f0).norm() <= 1e-14 * f0.norm() + 1e-14);
    // Rigid motions carry no force.
    p.internal_force(nsb::Vec::Constant(n, 0.7), f1);
    CHECK(f1.norm() <= 1e-14);
  }
}

TEST_CASE("signorini bar: mass models keep the total mass; the singular one has a massless contact node",
          "[problems][signorini-bar]") {
  for (std::string mass : {"lumped", "singular", "consistent"}) {
    const auto p = bar({{"N", "10"}, {"rho", "2"}, {"A", "3"}, {"L", "5"}, {"mass", mass}});
    const nsb::SpMat M = p.mass_matrix();
    const nsb::Vec one = nsb::Vec::Ones(p.ndof());
    CHECK(one.dot(M * one) == Approx(30.0));
    CHECK(p.momentum(one) == Approx(30.0));
    CHECK(bool(nsb::diagonal_mass(M)) == (mass != "consistent"));
    if (mass == "singular") {
      CHECK(M.coeff(0, 0) == 0.0);
      CHECK(M.coeff(1, 1) == Approx(1.5 * 2 * 3 * 0.5));
    }
  }
}

TEST_CASE("signorini bar: stable step is 2 / omega_max of the discrete bar", "[problems][signorini-bar]") {
  const int N = 20;
  for (std::string mass : {"lumped", "consistent", "singular"}) {
    CAPTURE(mass);
    const auto p = bar({{"N", std::to_string(N)}, {"E", "4"}, {"mass", mass}});
    nsb::SpMat Ks;
    p.tangent_stiffness(nsb::Vec::Zero(p.ndof()), Ks);
    const Eigen::MatrixXd K = Eigen::MatrixXd(Ks), M = Eigen::MatrixXd(p.mass_matrix());
    double lambda_max = 0.0;
    if (mass != "singular") {
      Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
      lambda_max = es.eigenvalues().maxCoeff();
      CHECK(2.0 / std::sqrt(lambda_max) == Approx(p.stable_step()).epsilon(1e-10));
    } else {
      // Massless node 0 condensed out: free (Schur complement) or held on the wall (removed).
      const Eigen::MatrixXd Kmm = K.bottomRightCorner(N, N), Mmm = M.bottomRightCorner(N, N);
      const Eigen::MatrixXd free = Kmm - K.bottomLeftCorner(N, 1) * K.topRightCorner(1, N) / K(0, 0);
      for (const Eigen::MatrixXd& Kc : {free, Kmm}) {
        Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kc, Mmm);
        lambda_max = std::max(lambda_max, es.eigenvalues().maxCoeff());
      }
      CHECK(2.0 / std::sqrt(lambda_max) >= p.stable_step());
    }
  }
}

TEST_CASE("signorini bar: registry, steel preset and bad input", "[problems][signorini-bar]") {
  const auto steel = nsb::make_problem("signorini-bar-steel");
  CHECK(steel->name() == "signorini-bar-steel");
  const auto& s = dynamic_cast<const SignoriniBar&>(*steel);
  CHECK(s.wave_speed() == Approx(std::sqrt(210e9 / 7800)));
  CHECK(s.contact_start() == Approx(5e-4));
  CHECK(s.contact_force_level() == Approx(3.14e-4 * 7800 * std::sqrt(210e9 / 7800) * 0.1));
  CHECK(nsb::make_problem("signorini-bar")->name() == "signorini-bar");
  CHECK_THROWS_AS(nsb::make_problem("signorini-bar", {{"N", "0"}}), nsb::InputError);
  CHECK_THROWS_AS(nsb::make_problem("signorini-bar", {{"mass", "diagonal"}}), nsb::InputError);
  CHECK_THROWS_AS(nsb::make_problem("signorini-bar", {{"v0", "-1"}}), nsb::InputError);
  // v0 = 0 is a bar at rest (a drop under gravity: bouncing-bar); without gravity it stays put.
  const auto rest = nsb::make_problem("signorini-bar", {{"v0", "0"}});
  const auto& r = dynamic_cast<const SignoriniBar&>(*rest);
  CHECK(r.exact_displacement(0.5, 1.0) == 0.0);
  CHECK(r.exact_contact_force(1.0) == 0.0);
  CHECK_THROWS_AS(nsb::make_problem("signorini-bar", {{"g0", "-1"}}), nsb::InputError);
}

TEST_CASE("signorini bar: an N that cannot fit in memory is refused before allocating", "[problems][signorini-bar]") {
  ::setenv("NSBENCH_MEMORY_LIMIT", "1G", 1);
  // 1e8 elements would need ~20 GB (issue 20: bad_alloc under a memory limit).
  CHECK_THROWS_WITH(nsb::make_problem("signorini-bar", {{"N", "100000000"}}),
                    Catch::StartsWith("signorini-bar: N = 100000000 needs about 18.6 GiB, more than the 1 GiB available "
                                      "(NSBENCH_MEMORY_LIMIT); valid: N <= 5368709"));
  CHECK(nsb::make_problem("signorini-bar", {{"N", "1000"}})->ndof() == 1001);
  ::unsetenv("NSBENCH_MEMORY_LIMIT");
}

TEST_CASE("signorini bar: parameters whose products overflow are refused, not run to -inf", "[problems][signorini-bar]") {
  // Issue 20: signorini-bar-steel with L = 1e308 ran with momentum_exact = -inf, status ok.
  CHECK_THROWS_WITH(nsb::make_problem("signorini-bar-steel", {{"L", "1e308"}}),
                    Catch::StartsWith("signorini-bar-steel: these parameters make the mass rho A L = inf"));
  CHECK_THROWS_WITH(nsb::make_problem("signorini-bar", {{"rho", "1e-200"}, {"A", "1e-200"}}),
                    Catch::Contains("the mass rho A L = 0"));
  CHECK(nsb::make_problem("signorini-bar-steel", {{"L", "1e3"}})->ndof() == 101);
}

TEST_CASE("signorini bar under gravity: F_ext = -grad V_load, weight rho A L g on every mass model",
          "[problems][signorini-bar]") {
  for (std::string mass : {"lumped", "singular", "consistent"}) {
    CAPTURE(mass);
    const auto p = bar({{"N", "6"}, {"rho", "2"}, {"A", "3"}, {"L", "1.5"}, {"g", "0.7"}, {"mass", mass}});
    const nsb::Index n = p.ndof();
    nsb::Vec f(n);
    p.external_force(0.0, f);
    // Total weight rho A L g towards the wall (-x), whatever the mass model.
    CHECK(f.sum() == Approx(-2 * 3 * 1.5 * 0.7));
    // The massless node carries no load, so its static contact equation is unchanged.
    if (mass == "singular") CHECK(f[0] == 0.0);
    // V_load is linear: central differences are exact up to round-off, O(eps |V| / h).
    const nsb::Vec u = nsb::Vec::LinSpaced(n, 0.3, -0.2);
    const double h = 1e-6;
    for (nsb::Index j = 0; j < n; ++j) {
      nsb::Vec up = u, um = u;
      up[j] += h;
      um[j] -= h;
      CHECK((p.load_potential(up) - p.load_potential(um)) / (2 * h) == Approx(-f[j]).margin(1e-8));
    }
    CHECK(p.load_potential(nsb::Vec::Zero(n)) == 0.0);
    // The exact solution is the bouncing bar's (tests/problems/bouncing_bar_test.cpp).
    CHECK(p.state(0.5).has_value());
  }
  // g = 0 (the default) keeps the load-free problem and its exact solution.
  const auto p0 = bar({{"N", "6"}});
  nsb::Vec f(p0.ndof());
  p0.external_force(0.0, f);
  CHECK(f.isZero(0.0));
  CHECK(p0.state(0.5).has_value());
  CHECK_THROWS_AS(nsb::make_problem("signorini-bar", {{"g", "-1"}}), nsb::InputError);
}

TEST_CASE("signorini bar: stiff_ratio stiffens the half at the wall; the stable step bounds the true one; no exact solution",
          "[problems][signorini-bar]") {
  const int N = 10;
  for (double r : {1e6, 1e-3}) {
    for (std::string mass : {"lumped", "consistent", "singular"}) {
      CAPTURE(r, mass);
      const auto p = bar({{"N", std::to_string(N)}, {"E", "4"}, {"stiff_ratio", std::to_string(r)}, {"mass", mass}});
      nsb::SpMat Ks;
      p.tangent_stiffness(nsb::Vec::Zero(p.ndof()), Ks);
      const Eigen::MatrixXd K = Eigen::MatrixXd(Ks), M = Eigen::MatrixXd(p.mass_matrix());
      // Element e spans nodes e, e+1: 4 r / h for the five at the wall, 4 / h for the others.
      for (int e = 0; e < N; ++e) CHECK(-K(e, e + 1) == Approx((e < N / 2 ? r : 1.0) * 4.0 * N));
      const nsb::Vec u = nsb::Vec::LinSpaced(p.ndof(), 0.3, -0.2).array().square();
      nsb::Vec f(p.ndof());
      p.internal_force(u, f);
      CHECK((f - K * u).norm() <= 1e-12 * (K * u).norm());
      CHECK(p.strain_energy(u) == Approx(0.5 * u.dot(K * u)).epsilon(1e-12));
      // A bound (stable), and not a loose one: within a factor 2 of 2 / omega_max.
      double lambda_max = 0.0;
      if (mass != "singular") {
        Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
        lambda_max = es.eigenvalues().maxCoeff();
      } else {  // massless node 0 condensed out: free (Schur complement) or held on the wall
        const Eigen::MatrixXd Kmm = K.bottomRightCorner(N, N), Mmm = M.bottomRightCorner(N, N);
        const Eigen::MatrixXd free = Kmm - K.bottomLeftCorner(N, 1) * K.topRightCorner(1, N) / K(0, 0);
        for (const Eigen::MatrixXd& Kc : {free, Kmm}) {
          Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kc, Mmm);
          lambda_max = std::max(lambda_max, es.eigenvalues().maxCoeff());
        }
      }
      const double exact_limit = 2.0 / std::sqrt(lambda_max);
      CHECK(p.stable_step() <= exact_limit * (1 + 1e-12));
      CHECK(p.stable_step() >= 0.5 * exact_limit);
      CHECK_FALSE(p.state(0.5).has_value());
      std::vector<double> obs(p.observable_names().size());
      p.observe(p.initial_state(), nsb::Vec(), 0.0, obs);
      CHECK(std::isnan(obs[3]));
      CHECK(obs[6] == Approx(-1.0));  // momentum -rho A L v0, still measured
    }
  }
  CHECK(bar({{"stiff_ratio", "1"}}).state(0.5).has_value());
}

TEST_CASE("signorini bar: field mesh and element stress (uniform strain, the exact field between fronts)",
          "[problems][signorini-bar][field-mesh]") {
  for (const char* mass : {"lumped", "consistent", "singular"}) {
    INFO(mass);
    // A uniform strain eps gives E_e eps in every element: r E in the half at the wall.
    const SignoriniBar p = bar({{"E", "2"}, {"stiff_ratio", "3"}, {"N", "10"}, {"mass", mass}});
    const auto mesh = p.field_mesh();
    REQUIRE(mesh.has_value());
    REQUIRE(mesh->npoints() == p.ndof());
    const double eps = 1e-3, h = p.element_size();
    nsb::Vec u(p.ndof());
    for (nsb::Index i = 0; i < p.ndof(); ++i) {
      CHECK(mesh->point_dofs(i, 0) == i);
      CHECK(mesh->points(i, 0) == Approx(i * h));
      u[i] = eps * mesh->points(i, 0);
    }
    Eigen::MatrixXd sigma(mesh->ncells(), 1);
    p.cell_stress(u, sigma);
    for (nsb::Index e = 0; e < mesh->ncells(); ++e) CHECK(sigma(e, 0) == Approx((e < 5 ? 3.0 : 1.0) * 2.0 * eps));
  }
  // The exact field's nodal values: the element's stress is the exact one away from the
  // fronts (x = c s and 2L - c s, s = t - t0), where the exact u is linear.
  const SignoriniBar p = bar({{"N", "20"}, {"g0", "0.1"}});
  const auto mesh = p.field_mesh();
  Eigen::MatrixXd sigma(mesh->ncells(), 1);
  for (const double t : {0.41, 1.52}) {
    const auto s = p.state(t);
    REQUIRE(s.has_value());
    p.cell_stress(s->u, sigma);
    const double front1 = t - p.contact_start(), front2 = 2.0 - front1, h = p.element_size();
    int compared = 0, loaded = 0;
    for (nsb::Index e = 0; e < mesh->ncells(); ++e) {
      const double mid = (e + 0.5) * h;
      if (std::abs(mid - front1) < h || std::abs(mid - front2) < h) continue;
      CHECK(sigma(e, 0) == Approx(p.exact_stress(mid, t)).margin(1e-12));
      ++compared;
      loaded += p.exact_stress(mid, t) < 0.0;
    }
    CHECK(compared >= 17);
    CHECK(loaded >= 5);
  }
}

TEST_CASE("signorini bar exact: observable(name, t) is observe() on state(t), bit for bit", "[problems][signorini-bar]") {
  for (const char* problem : {"signorini-bar", "bouncing-bar"}) {
    for (const char* mass : {"lumped", "singular"}) {
      const auto p = nsb::make_problem(problem, {{"N", "40"}, {"mass", mass}});
      const nsb::ExactSolution& exact = *p->exact();
      const auto names = p->observable_names();
      std::vector<double> out(names.size());
      for (double t = 0.0; t <= 4.0; t += 0.0137) {  // across the contact and the flights after it
        p->observe(*exact.state(t), Eigen::VectorXd::Zero(p->ncontacts()), 0.0, out);
        std::size_t offered = 0;
        for (std::size_t k = 0; k < names.size(); ++k) {
          if (const auto value = exact.observable(names[k], t)) {
            CAPTURE(problem, mass, t, names[k]);
            CHECK(std::bit_cast<std::uint64_t>(*value) == std::bit_cast<std::uint64_t>(out[k]));
            ++offered;
          }
        }
        CHECK(offered == 5);  // u, v and the contact force, exact, at the contact end; momentum is a sum over nodes
      }
    }
  }
  const auto stiffened = nsb::make_problem("signorini-bar", {{"stiff_ratio", "4"}});  // no exact solution
  CHECK_FALSE(stiffened->exact()->state(1.0));
  CHECK_FALSE(stiffened->exact()->observable("u_contact", 1.0));
}
