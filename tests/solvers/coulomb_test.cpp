// The 2D Moreau–Coulomb solves of solvers/coulomb.hpp against the law itself: every
// case of random local problems is enumerated by brute force (separate, stick, slip+,
// slip-), and the solver's answer must be the one consistent case; the Gauss–Seidel over
// coupled contacts must satisfy the law on every contact; friction must never add energy.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "solvers/coulomb.hpp"

namespace {

struct Local {
  double w_nn, w_nt, w_tt, q_n, q_t, mu;
};

// How far (n, t) is from the law, in velocity units (0: it holds).
double law_violation(const Local& c, double n, double t) {
  const double u_n = c.q_n + c.w_nn * n + c.w_nt * t;
  const double u_t = c.q_t + c.w_nt * n + c.w_tt * t;
  const double scale = std::max({std::abs(c.q_n), std::abs(c.q_t), 1e-300});
  double v = std::max({0.0, -n * c.w_nn, -u_n});                     // n >= 0, U_N >= 0
  v = std::max(v, std::min(std::abs(n * c.w_nn), std::abs(u_n)));     // n U_N = 0
  v = std::max(v, (std::abs(t) - c.mu * n) * c.w_tt);                  // in the cone
  if (std::abs(t) < c.mu * n * (1 - 1e-9)) v = std::max(v, std::abs(u_t));  // inside: stick
  else v = std::max(v, t * u_t > 0.0 ? std::min(std::abs(u_t), std::abs(t) * c.w_tt) : 0.0);  // on it: slip opposes
  return v / scale;
}

// Every candidate of the four cases that satisfies the law.
std::vector<std::pair<double, double>> brute_force(const Local& c) {
  std::vector<std::pair<double, double>> candidates = {{0.0, 0.0}};
  const double det = c.w_nn * c.w_tt - c.w_nt * c.w_nt;
  candidates.emplace_back((-c.q_n * c.w_tt + c.q_t * c.w_nt) / det, (-c.q_t * c.w_nn + c.q_n * c.w_nt) / det);
  for (const double s : {-1.0, 1.0}) {
    const double n = -c.q_n / (c.w_nn + s * c.mu * c.w_nt);
    candidates.emplace_back(n, s * c.mu * n);
  }
  std::vector<std::pair<double, double>> valid;
  for (const auto& [n, t] : candidates)
    if (std::isfinite(n) && law_violation(c, n, t) <= 1e-12) valid.emplace_back(n, t);
  return valid;
}

Local random_local(std::mt19937_64& rng, bool coupled) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.1, 2.0), mu(0.0, 1.5);
  // W = A A^T with A random: symmetric positive definite.
  const double a = pos(rng), b = coupled ? u(rng) : 0.0, d = pos(rng);
  return {a * a, a * b, b * b + d * d, u(rng), u(rng), mu(rng)};
}

}  // namespace

TEST_CASE("Coulomb local solve: the one case of the law that holds, on random 2x2 problems",
          "[integrators][coulomb][friction]") {
  std::mt19937_64 rng(20261123);
  int stick = 0, slip = 0, open = 0;
  for (int k = 0; k < 20000; ++k) {
    const Local c = random_local(rng, k % 2 == 0);
    const auto r = nsb::solve_coulomb_local(c.w_nn, c.w_nt, c.w_tt, c.q_n, c.q_t, c.mu);
    INFO("case " << k << ": W = [" << c.w_nn << ", " << c.w_nt << "; " << c.w_tt << "], q = (" << c.q_n << ", "
                 << c.q_t << "), mu " << c.mu << " -> (" << r.normal << ", " << r.tangential << ")");
    REQUIRE(law_violation(c, r.normal, r.tangential) <= 1e-12);
    const auto valid = brute_force(c);
    REQUIRE(!valid.empty());
    // Below mu |W_NT| < W_NN the law has one solution: every valid candidate is ours.
    if (c.mu * std::abs(c.w_nt) < c.w_nn)
      for (const auto& [n, t] : valid) {
        CHECK(n == Approx(r.normal).margin(1e-12));
        CHECK(t == Approx(r.tangential).margin(1e-12));
      }
    if (r.normal == 0.0) ++open;
    else if (std::abs(r.tangential) < c.mu * r.normal) ++stick;
    else ++slip;
  }
  // The random set visits every case.
  CHECK(open > 1000);
  CHECK(stick > 1000);
  CHECK(slip > 1000);
}

TEST_CASE("Coulomb local solve: decoupled, the closed form; mu = 0, the frictionless impulse",
          "[integrators][coulomb][friction]") {
  const auto r = nsb::solve_coulomb_local(2.0, 0.0, 3.0, -4.0, 9.0, 0.5);
  CHECK(r.normal == 2.0);
  CHECK(r.tangential == -1.0);  // -q_t / W_TT = -3 clamped to -mu Lambda_N
  const auto s = nsb::solve_coulomb_local(2.0, 0.0, 3.0, -4.0, 1.5, 0.5);
  CHECK(s.tangential == -0.5);  // stick: -q_t / W_TT inside the cone
  const auto f = nsb::solve_coulomb_local(2.0, 0.0, 3.0, -4.0, 1.5, 0.0);
  CHECK(f.normal == std::max(0.0, 4.0 / 2.0));
  CHECK(f.tangential == 0.0);
}

TEST_CASE("Coulomb impulses never add energy: kinetic change Lambda.(q + W Lambda / 2) <= 0 for e = 0",
          "[integrators][coulomb][friction]") {
  // With e = 0 and a fixed obstacle, q is the free local velocity and the impulse changes the
  // kinetic energy by Lambda.(v- + v+)/2 = Lambda.q + Lambda.W Lambda / 2 (docs/method.md section 6).
  std::mt19937_64 rng(7);
  for (int k = 0; k < 20000; ++k) {
    const Local c = random_local(rng, true);
    const auto r = nsb::solve_coulomb_local(c.w_nn, c.w_nt, c.w_tt, c.q_n, c.q_t, c.mu);
    const double n = r.normal, t = r.tangential;
    const double change = n * c.q_n + t * c.q_t + 0.5 * (c.w_nn * n * n + 2 * c.w_nt * n * t + c.w_tt * t * t);
    INFO("case " << k);
    CHECK(change <= 1e-12 * (c.q_n * c.q_n / c.w_nn + c.q_t * c.q_t / c.w_tt));
  }
}

TEST_CASE("Coulomb Gauss-Seidel over coupled contacts: the law on every contact, tolerance reported",
          "[integrators][coulomb][friction]") {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1.0, 1.0), mu(0.0, 0.8);
  for (int trial = 0; trial < 200; ++trial) {
    const int a = 2 + trial % 5, n = 2 * a;
    // D = C C^T + diagonal shift: a Delassus matrix of contacts sharing dofs.
    Eigen::MatrixXd C(n, n + 3);
    for (int i = 0; i < C.size(); ++i) C.data()[i] = u(rng);
    const Eigen::MatrixXd D = C * C.transpose() + 0.5 * Eigen::MatrixXd::Identity(n, n);
    Eigen::VectorXd q(n), m(a), x = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) q[i] = u(rng);
    for (int i = 0; i < a; ++i) m[i] = mu(rng);
    const nsb::LcpResult res = nsb::solve_coulomb(D, q, m, x, {1e-13, 100000});
    INFO("trial " << trial << ", " << res.iterations << " iterations, residual " << res.residual);
    REQUIRE(res.converged);
    const Eigen::VectorXd w = D * x + q;
    for (int i = 0; i < a; ++i) {
      // Contact i's own law, with the others' impulses folded into its free velocities.
      const Local c{D(2 * i, 2 * i), D(2 * i, 2 * i + 1), D(2 * i + 1, 2 * i + 1),
                    w[2 * i] - D(2 * i, 2 * i) * x[2 * i] - D(2 * i, 2 * i + 1) * x[2 * i + 1],
                    w[2 * i + 1] - D(2 * i + 1, 2 * i) * x[2 * i] - D(2 * i + 1, 2 * i + 1) * x[2 * i + 1], m[i]};
      CHECK(law_violation(c, x[2 * i], x[2 * i + 1]) <= 1e-9);
    }
  }
}

TEST_CASE("Coulomb Gauss-Seidel: uncoupled contacts take one sweep, exact", "[integrators][coulomb][friction]") {
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(4, 4);
  D << 2, 0.3, 0, 0,  //
      0.3, 1, 0, 0,   //
      0, 0, 1, 0,     //
      0, 0, 0, 4;
  const Eigen::VectorXd q = (Eigen::VectorXd(4) << -1, 2, -3, 1).finished();
  const Eigen::VectorXd mu = (Eigen::VectorXd(2) << 0.4, 0.2).finished();
  Eigen::VectorXd x;
  const nsb::LcpResult res = nsb::solve_coulomb(D, q, mu, x, {1e-12, 10});
  CHECK(res.iterations == 1);
  CHECK(res.residual == 0.0);
  const auto first = nsb::solve_coulomb_local(2, 0.3, 1, -1, 2, 0.4);
  CHECK(x[0] == first.normal);
  CHECK(x[1] == first.tangential);
  CHECK(x[2] == 3.0);
  CHECK(x[3] == -0.25);  // -q_t / W_TT = -0.25, inside mu Lambda_N = 0.6
}
