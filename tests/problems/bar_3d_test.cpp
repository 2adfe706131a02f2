// bar-3d (problems/bar_3d.hpp): the assembled hex8 force and tangent against finite
// differences, the patch test, the held bar against the 1D oedometric bar and the exact
// solution (CD-Lagrange), field stresses, bad input.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "integrators/registry.hpp"
#include "problems/bar3d_exact.hpp"
#include "problems/bar_3d.hpp"
#include "problems/signorini_bar.hpp"
#include "run/run.hpp"

namespace {

nsb::Bar3d make_bar3d(std::map<std::string, std::string> overrides) { return nsb::Bar3d(nsb::Params(nsb::Bar3d::parameters_spec(), overrides)); }

nsb::Vec wavy(nsb::Index n, double scale) {
  nsb::Vec u(n);
  for (nsb::Index i = 0; i < n; ++i) u[i] = scale * std::sin(0.37 * static_cast<double>(i) + 0.1 * static_cast<double>(i * i % 7));
  return u;
}

// The reference position of dof q's node, and its direction (0 x, 1 y, 2 z).
struct DofPlace {
  Eigen::Vector3d X;
  int direction = 0;
};

DofPlace place(const nsb::Bar3d& p, const nsb::FieldMesh& mesh, nsb::Index q) {
  for (nsb::Index a = 0; a < mesh.npoints(); ++a)
    for (int d = 0; d < 3; ++d)
      if (mesh.point_dofs(a, d) == q) return {mesh.points.row(a).transpose(), d};
  FAIL("dof " << q << " of " << p.ndof() << " on no point");
  return {};
}

}  // namespace

TEST_CASE("bar-3d: F_int = dV/du and K = dF_int/du by central differences; F_int = K u", "[problems][bar-3d]") {
  for (const char* lateral : {"held", "free"}) {
    CAPTURE(lateral);
    const auto p = make_bar3d({{"N", "3"}, {"N_side", "2"}, {"lateral", lateral}, {"nu", "0.27"}, {"L", "2"}, {"A", "0.3"}});
    const nsb::Index n = p.ndof();
    const nsb::Vec u = wavy(n, 1e-2);
    nsb::Vec f(n), fp(n), fm(n);
    p.internal_force(u, f);
    nsb::SpMat K;
    p.tangent_stiffness(u, K);
    REQUIRE(K.rows() == n);
    CHECK((nsb::Vec(K * u) - f).norm() <= 1e-13 * f.norm());
    CHECK(nsb::SpMat(K - nsb::SpMat(K.transpose())).norm() <= 1e-14 * K.norm());
    const double eps = 1e-6;
    double force_err = 0.0, tangent_err = 0.0;
    nsb::Vec du = nsb::Vec::Zero(n);
    for (nsb::Index q = 0; q < n; ++q) {
      du[q] = eps;
      force_err = std::max(force_err, std::abs((p.strain_energy(u + du) - p.strain_energy(u - du)) / (2 * eps) - f[q]));
      p.internal_force(u + du, fp);
      p.internal_force(u - du, fm);
      tangent_err = std::max(tangent_err, (nsb::Vec((fp - fm) / (2 * eps)) - nsb::Vec(K.col(q))).cwiseAbs().maxCoeff());
      du[q] = 0.0;
    }
    const double scale = f.cwiseAbs().maxCoeff(), kscale = nsb::Vec(K.diagonal()).cwiseAbs().maxCoeff();
    CHECK(force_err <= 1e-7 * scale);
    CHECK(tangent_err <= 1e-7 * kscale);
    // A refilled K keeps its pattern and values.
    nsb::SpMat again = K;
    again.coeffs().setZero();
    p.tangent_stiffness(u, again);
    CHECK(nsb::SpMat(again - K).norm() == 0.0);
  }
}

TEST_CASE("bar-3d: patch test, a uniform strain leaves the interior nodes unloaded; rigid translation none at all",
          "[problems][bar-3d]") {
  const auto p = make_bar3d({{"N", "4"}, {"N_side", "3"}, {"lateral", "free"}, {"L", "1.5"}, {"A", "0.8"}});
  const auto mesh = p.field_mesh();
  REQUIRE(mesh);
  Eigen::Matrix3d G;
  G << 1e-3, 2e-4, -3e-4, 5e-4, -7e-4, 1e-4, -2e-4, 3e-4, 4e-4;
  const nsb::Index n = p.ndof();
  nsb::Vec u(n), f(n);
  for (nsb::Index q = 0; q < n; ++q) {
    const DofPlace d = place(p, *mesh, q);
    u[q] = G.row(d.direction).dot(d.X);
  }
  p.internal_force(u, f);
  const double L = 1.5, a = std::sqrt(0.8);
  double interior = 0.0, boundary = 0.0;
  for (nsb::Index q = 0; q < n; ++q) {
    const DofPlace d = place(p, *mesh, q);
    const bool inside = d.X.x() > 1e-12 && d.X.x() < L - 1e-12 && d.X.y() > 1e-12 && d.X.y() < a - 1e-12 &&
                        d.X.z() > 1e-12 && d.X.z() < a - 1e-12;
    (inside ? interior : boundary) = std::max(inside ? interior : boundary, std::abs(f[q]));
  }
  CHECK(boundary > 1e-5);  // the faces carry the traction
  CHECK(interior <= 1e-13 * boundary);
  p.internal_force(nsb::Vec::Constant(n, 0.3), f);
  CHECK(f.cwiseAbs().maxCoeff() <= 1e-14);
}

TEST_CASE("bar-3d: a uniform axial stretch, held sides: sigma_xx = M eps, sigma_yy = sigma_zz = lambda eps",
          "[problems][bar-3d]") {
  const double E = 3.0, nu = 0.25, eps = 1e-3;
  const auto p = make_bar3d({{"N", "5"}, {"N_side", "2"}, {"E", "3"}, {"nu", "0.25"}});
  const auto mesh = p.field_mesh();
  nsb::Vec u(p.ndof());
  for (nsb::Index a = 0; a < mesh->npoints(); ++a) u[mesh->point_dofs(a, 0)] = eps * mesh->points(a, 0);
  Eigen::MatrixXd sigma(mesh->nelements(), 6);
  p.cell_stress(u, sigma);
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  for (nsb::Index e = 0; e < sigma.rows(); ++e) {
    CHECK(sigma(e, 0) == Approx(nsb::oedometric_modulus(E, nu) * eps).epsilon(1e-13));
    CHECK(sigma(e, 1) == Approx(lambda * eps).epsilon(1e-13));
    CHECK(sigma(e, 2) == Approx(lambda * eps).epsilon(1e-13));
    CHECK(sigma.row(e).tail<3>().cwiseAbs().maxCoeff() <= 1e-15);
  }
  // The strain energy of the stretch: M eps^2 / 2 times the volume L A = 1.
  CHECK(p.strain_energy(u) == Approx(0.5 * nsb::oedometric_modulus(E, nu) * eps * eps).epsilon(1e-12));
}

TEST_CASE("bar-3d, held, lumped: CD-Lagrange's run is the 1D oedometric bar's, node for node", "[problems][bar-3d]") {
  for (const char* side : {"1", "2"}) {
    CAPTURE(side);
    const auto p = make_bar3d({{"N", "20"}, {"N_side", side}, {"g0", "0.05"}});
    const auto& line = p.exact_bar();  // the 1D bar with E -> M: its own semi-discrete system
    const double dt = 0.8 * 0.05 / p.p_wave_speed();  // 0.8 h / c_p
    auto a = nsb::make_integrator("cd-lagrange"), b = nsb::make_integrator("cd-lagrange");
    a->init(p, p.initial_state());
    b->init(line, line.initial_state());
    double worst = 0.0;
    for (int k = 0; k < 300; ++k) {
      a->step(dt);
      b->step(dt);
      for (nsb::Index kk = 0; kk <= p.side_elements(); ++kk)
        for (nsb::Index j = 0; j <= p.side_elements(); ++j)
          for (nsb::Index i = 0; i <= 20; ++i) {
            const nsb::Index q = p.x_dof(i, j, kk);
            worst = std::max({worst, std::abs(a->state().u[q] - b->state().u[i]), std::abs(a->state().v[q] - b->state().v[i])});
          }
    }
    // Round-off only: the face nodes' sums differ from the 1D bar's in the last bits, and 300
    // steps accumulate it (measured 3e-12 with N_side 1, 8e-12 with 2; v0 = 1, u = O(0.1)).
    INFO("largest difference " << worst);
    CHECK(worst <= 1e-10);
  }
}

namespace {

struct HeldRun {
  double first_contact = NAN, last_contact = NAN;  // the first and last step with an impulse
  double displacement_error = 0.0;                 // max over nodes and steps of |u - u_exact| / (v0 T)
  double force_level = 0.0;                        // mean contact force over the steps in contact
};

// CD-Lagrange on the held bar of N elements at dt = 0.5 h / c_p, to 1.5 contact durations.
HeldRun run_held(int N, const std::string& mass = "lumped") {
  const auto p = make_bar3d({{"N", std::to_string(N)}, {"mass", mass}, {"g0", "0.1"}, {"nu", "0.3"}});
  const double c = p.p_wave_speed(), T = nsb::bar3d_contact_duration(1.0, 1.0, 0.3, 1.0);
  const double dt = 0.5 / (N * c);
  auto integ = nsb::make_integrator("cd-lagrange");
  integ->init(p, p.initial_state());
  HeldRun r;
  double force_sum = 0.0;
  long force_steps = 0;
  while (integ->state().t < 0.1 + 1.5 * T) {
    integ->step(dt);
    const double t = integ->state().t, impulse = integ->impulses().sum();
    if (impulse > 0.0) {
      if (std::isnan(r.first_contact)) r.first_contact = t;
      r.last_contact = t;
      force_sum += impulse / dt;
      ++force_steps;
    }
    const auto exact = p.state(t);
    REQUIRE(exact);
    r.displacement_error = std::max(r.displacement_error, (integ->state().u - exact->u).cwiseAbs().maxCoeff() / T);
  }
  r.force_level = force_sum / static_cast<double>(force_steps);
  return r;
}

}  // namespace

TEST_CASE("bar-3d, held: CD-Lagrange against the exact solution, contact 2 L / c_p within O(dt), u converging",
          "[problems][bar-3d]") {
  const double c = nsb::p_wave_speed(1.0, 0.3, 1.0), T = 2.0 / c, t0 = 0.1;
  double previous = INFINITY;
  for (int N : {20, 40, 80}) {
    CAPTURE(N);
    const HeldRun r = run_held(N);
    const double dt = 0.5 / (N * c);
    // Contact from g0 / v0 for 2 L / c_p (the first step after the gap closes, the last one
    // before the release): both ends within a couple of steps.
    CHECK(std::abs(r.first_contact - t0) <= 2 * dt);
    CHECK(std::abs(r.last_contact - (t0 + T)) <= 3 * dt);
    CHECK(r.force_level == Approx(c * 1.0).epsilon(0.05));  // A rho c_p v0
    CHECK(r.displacement_error < previous);
    if (N > 20) {
      INFO("order " << std::log2(previous / r.displacement_error));
      CHECK(r.displacement_error <= 0.75 * previous);
    }
    previous = r.displacement_error;
  }
}

TEST_CASE("bar-3d: exact state at 0 is the initial one; free sides: no exact solution", "[problems][bar-3d]") {
  const auto held = make_bar3d({{"N", "6"}, {"N_side", "2"}});
  const auto s0 = held.state(0.0);
  REQUIRE(s0);
  CHECK(s0->u == held.initial_state().u);
  CHECK(s0->v == held.initial_state().v);
  const auto free = make_bar3d({{"N", "6"}, {"lateral", "free"}});
  CHECK_FALSE(free.state(0.1));
  std::vector<double> out(free.observable_names().size());
  free.observe(free.initial_state(), nsb::Vec(), 0.0, out);
  CHECK(std::isnan(out[5]));  // contact_force_exact
  CHECK(out[1] == -1.0);      // v_contact
  CHECK(out[6] == Approx(-1.0).epsilon(1e-14));  // momentum rho A L (-v0)
}

TEST_CASE("bar-3d: every mass model keeps the total x mass; singular moves the wall face's to the next layer",
          "[problems][bar-3d]") {
  for (const char* mass : {"lumped", "consistent", "singular"}) {
    CAPTURE(mass);
    const auto p = make_bar3d({{"N", "4"}, {"N_side", "2"}, {"mass", mass}, {"lateral", "free"}, {"A", "0.5"}});
    const nsb::SpMat M = p.mass_matrix();
    const nsb::Vec rows = M * nsb::Vec::Ones(p.ndof());
    double x_mass = 0.0;
    for (nsb::Index q = 0; q < p.ndof(); q += 3) x_mass += rows[q];
    CHECK(x_mass == Approx(0.5).epsilon(1e-14));  // rho A L
    if (std::string(mass) == "singular") CHECK(M.coeff(p.x_dof(0, 1, 1), p.x_dof(0, 1, 1)) == 0.0);
  }
}

TEST_CASE("bar-3d: bad input, one line naming the parameter and its range", "[problems][bar-3d][bad-input]") {
  for (const char* nu : {"0.5", "-0.1", "0.7"}) {
    CAPTURE(nu);
    CHECK_THROWS_MATCHES(make_bar3d({{"nu", nu}}), nsb::InputError,
                         Catch::Matchers::Predicate<nsb::InputError>([](const nsb::InputError& e) {
                           const std::string w = e.what();
                           return w.find("nu") != std::string::npos && w.find("[0, 0.5)") != std::string::npos &&
                                  w.find('\n') == std::string::npos;
                         }));
  }
  // 1e8 x 1024^2 elements: far beyond any machine's memory, refused before allocating.
  CHECK_THROWS_MATCHES(make_bar3d({{"N", "100000000"}, {"N_side", "1024"}}), nsb::InputError,
                       Catch::Matchers::Predicate<nsb::InputError>([](const nsb::InputError& e) {
                         const std::string w = e.what();
                         return w.find("bar-3d: N = 100000000, N_side = 1024") != std::string::npos &&
                                w.find("GiB") != std::string::npos && w.find("valid: N * N_side^2 <= ") != std::string::npos;
                       }));
  CHECK_THROWS_AS(make_bar3d({{"lateral", "sideways"}}), nsb::InputError);
  CHECK_THROWS_AS(make_bar3d({{"N_side", "0"}}), nsb::InputError);
}
