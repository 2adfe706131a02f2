#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "solvers/coulomb.hpp"
#include "solvers/coulomb_cone.hpp"
#include "tests/support/allocation_counter.hpp"

using Catch::Detail::Approx;
using nsb::ConeImpulse;

namespace {

Eigen::Vector3d velocity_after(const Eigen::Matrix3d& W, const Eigen::Vector3d& q, const ConeImpulse& r) {
  return q + W * Eigen::Vector3d(r.normal, r.tangential.x(), r.tangential.y());
}

// A random SPD 3x3 block: B B^T + shift I, eigenvalues spread by a few orders.
Eigen::Matrix3d random_spd(std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Matrix3d B;
  for (int i = 0; i < 9; ++i) B(i / 3, i % 3) = normal(rng);
  return B * B.transpose() + 1e-2 * Eigen::Matrix3d::Identity();
}

// The kinetic energy change of the impulse, Lambda . (u- + u+) / 2 in local terms (e = 0: u- = q).
double energy_change(const Eigen::Matrix3d& W, const Eigen::Vector3d& q, const ConeImpulse& r) {
  const Eigen::Vector3d lambda(r.normal, r.tangential.x(), r.tangential.y());
  return lambda.dot(q + 0.5 * W * lambda);
}

}  // namespace

TEST_CASE("coulomb cone: isotropic block, stick inside the cone and slip on its boundary", "[coulomb_cone]") {
  const double w = 0.5, mu = 0.4;
  // Small tangential velocity: stick, U = 0.
  const Eigen::Vector3d q_stick(-2.0, 0.3, -0.4);
  const auto stick = nsb::solve_cone_isotropic(w, q_stick, mu);
  CHECK(stick.normal == Approx(4.0).epsilon(1e-15));
  CHECK(stick.tangential.norm() < mu * stick.normal);
  CHECK(velocity_after(w * Eigen::Matrix3d::Identity(), q_stick, stick).norm() < 1e-15);
  // Large: slip, |Lambda_T| = mu Lambda_N, Lambda_T opposite to the slip after the impulse.
  const Eigen::Vector3d q_slip(-2.0, 3.0, -4.0);
  const auto slip = nsb::solve_cone_isotropic(w, q_slip, mu);
  const Eigen::Vector3d U = velocity_after(w * Eigen::Matrix3d::Identity(), q_slip, slip);
  CHECK(slip.tangential.norm() == Approx(mu * slip.normal).epsilon(1e-15));
  CHECK(U.x() == Approx(0.0).margin(1e-15));
  CHECK(U.tail<2>().norm() > 0.0);
  CHECK((slip.tangential / slip.tangential.norm() + U.tail<2>() / U.tail<2>().norm()).norm() < 1e-15);
  // Separating: no impulse.
  const auto open = nsb::solve_cone_isotropic(w, Eigen::Vector3d(0.1, 3.0, 1.0), mu);
  CHECK(open.normal == 0.0);
  CHECK(open.tangential.isZero());
}

TEST_CASE("coulomb cone: the general solver equals the closed form on an isotropic block", "[coulomb_cone]") {
  std::mt19937 rng(33);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int i = 0; i < 200; ++i) {
    const double w = 0.1 + std::abs(u(rng)), mu = 0.5 * std::abs(u(rng));
    const Eigen::Vector3d q(-std::abs(u(rng)), u(rng), u(rng));
    const auto closed = nsb::solve_cone_isotropic(w, q, mu);
    const auto general = nsb::solve_cone_local(w * Eigen::Matrix3d::Identity(), q, mu);
    REQUIRE(general.converged);
    CHECK(general.impulse.normal == Approx(closed.normal).epsilon(1e-14));
    CHECK((general.impulse.tangential - closed.tangential).norm() <= 1e-14 * closed.normal * (1.0 + mu));
  }
}

TEST_CASE("coulomb cone: the 2D law when one tangent direction is absent", "[coulomb_cone]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    // A 2x2 SPD block (N, T) with the second tangent row decoupled and no velocity along it.
    const double w_nn = 1.0 + std::abs(u(rng)), w_tt = 0.5 + std::abs(u(rng));
    const double w_nt = 0.8 * u(rng) * std::sqrt(w_nn * w_tt), mu = 0.6 * std::abs(u(rng));
    const double q_n = -std::abs(u(rng)), q_t = 2.0 * u(rng);
    Eigen::Matrix3d W;
    W << w_nn, w_nt, 0.0, w_nt, w_tt, 0.0, 0.0, 0.0, 1.0 + std::abs(u(rng));
    const auto plane = nsb::solve_coulomb_local(w_nn, w_nt, w_tt, q_n, q_t, mu);
    const auto cone = nsb::solve_cone_local(W, Eigen::Vector3d(q_n, q_t, 0.0), mu);
    INFO("W_NT " << w_nt << " mu " << mu << " q " << q_n << " " << q_t);
    REQUIRE(cone.converged);
    CHECK(cone.impulse.normal == Approx(plane.normal).epsilon(1e-13));
    CHECK(cone.impulse.tangential.x() == Approx(plane.tangential).margin(1e-13 * plane.normal));
    CHECK(cone.impulse.tangential.y() == 0.0);
  }
}

TEST_CASE("coulomb cone: random SPD blocks satisfy the law, no energy gain", "[coulomb_cone]") {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int sticks = 0, slips = 0;
  for (int i = 0; i < 500; ++i) {
    const Eigen::Matrix3d W = random_spd(rng);
    const Eigen::Vector3d q(-std::abs(u(rng)), 0.2 * u(rng), 0.2 * u(rng));
    // mu below W_NN / |W_NT|: a solution exists (h grows from h(0) < 0).
    const double mu = std::min(1.0, 0.9 * W(0, 0) / W.block<1, 2>(0, 1).norm()) * std::abs(u(rng));
    const auto solve = nsb::solve_cone_local(W, q, mu);
    INFO("case " << i << " mu " << mu);
    REQUIRE(solve.converged);
    const ConeImpulse& r = solve.impulse;
    CHECK(nsb::cone_law_residual(W, q, mu, r) < 1e-12);
    CHECK(r.normal >= 0.0);
    CHECK(r.tangential.norm() <= mu * r.normal * (1.0 + 1e-14));
    const Eigen::Vector3d U = velocity_after(W, q, r);
    const double scale = q.cwiseAbs().maxCoeff();
    CHECK(std::abs(U.x()) < 1e-12 * scale);  // q_N < 0: the contact stays closed
    if (r.tangential.norm() < mu * r.normal * (1.0 - 1e-9)) {
      ++sticks;
      CHECK(U.tail<2>().norm() < 1e-12 * scale);
    } else if (U.tail<2>().norm() > 1e-9 * scale) {
      ++slips;
      CHECK(r.tangential.dot(U.tail<2>()) <= 0.0);
      CHECK((r.tangential.normalized() + U.tail<2>().normalized()).norm() < 1e-9);
    }
    CHECK(energy_change(W, q, r) <= 1e-14 * scale * r.normal * (1.0 + mu));
  }
  INFO("sticks " << sticks << " slips " << slips);
  CHECK(sticks > 25);  // both regimes are exercised
  CHECK(slips > 25);
}

TEST_CASE("coulomb cone: the local solves allocate nothing", "[coulomb_cone]") {
  Eigen::Matrix3d W;
  W << 2.0, 0.3, -0.2, 0.3, 1.0, 0.1, -0.2, 0.1, 0.7;
  const Eigen::Vector3d q(-1.0, 2.0, -1.5);
  double sum = 0.0;
  long allocations = 0;
  {
    const nsb::test::CountAllocations count;
    const auto general = nsb::solve_cone_local(W, q, 0.4);
    const auto closed = nsb::solve_cone_isotropic(0.5, q, 0.4);
    sum = general.impulse.normal + closed.normal + nsb::cone_law_residual(W, q, 0.4, general.impulse);
    allocations = count.count();
  }
  CHECK(sum > 0.0);
  CHECK(allocations == 0);
}

TEST_CASE("coulomb cone: the residual detects a violated law", "[coulomb_cone]") {
  const Eigen::Matrix3d W = Eigen::Vector3d(1.0, 2.0, 0.5).asDiagonal();
  const Eigen::Vector3d q(-1.0, 3.0, 0.0);
  const auto solve = nsb::solve_cone_local(W, q, 0.3);
  CHECK(nsb::cone_law_residual(W, q, 0.3, solve.impulse) < 1e-14);
  ConeImpulse along = solve.impulse;  // friction pushing along the slip: not the law
  along.tangential = -along.tangential;
  CHECK(nsb::cone_law_residual(W, q, 0.3, along) > 0.1);
  ConeImpulse outside = solve.impulse;  // outside the cone
  outside.tangential *= 2.0;
  CHECK(nsb::cone_law_residual(W, q, 0.3, outside) > 0.1);
}

TEST_CASE("coulomb cone: a diagonal block with equal tangent entries in closed form (a sphere's)", "[coulomb_cone]") {
  const double m = 2.0;
  const Eigen::Matrix3d W = Eigen::Vector3d(1.0 / m, 3.5 / m, 3.5 / m).asDiagonal();
  for (const Eigen::Vector3d& q : {Eigen::Vector3d(-1.0, 0.02, -0.01), Eigen::Vector3d(-1.0, 3.0, -4.0)}) {
    const ConeImpulse closed = nsb::solve_cone_decoupled(1.0 / m, 3.5 / m, q, 0.3);
    const auto dispatched = nsb::solve_cone(W, q, 0.3);
    CHECK(dispatched.iterations == 0);  // the closed form, not the local solve
    CHECK(dispatched.impulse.normal == closed.normal);
    CHECK(dispatched.impulse.tangential == closed.tangential);
    CHECK(closed.normal == Approx(m));
    CHECK(nsb::cone_law_residual(W, q, 0.3, closed) < 1e-15);
    const auto general = nsb::solve_cone_local(W, q, 0.3);
    CHECK((general.impulse.tangential - closed.tangential).norm() < 1e-14);
  }
  // Inside the disk the slip stops; outside, |Lambda_T| = mu Lambda_N against the slip.
  const Eigen::Vector3d stick(-1.0, 0.02, -0.01), slip(-1.0, 3.0, -4.0);
  CHECK(velocity_after(W, stick, nsb::solve_cone_decoupled(1.0 / m, 3.5 / m, stick, 0.3)).tail<2>().norm() < 1e-16);
  const ConeImpulse r = nsb::solve_cone_decoupled(1.0 / m, 3.5 / m, slip, 0.3);
  CHECK(r.tangential.norm() == Approx(0.3 * r.normal));
  CHECK(r.tangential.normalized().dot(slip.tail<2>().normalized()) == Approx(-1.0));
}

TEST_CASE("coulomb cone: Gauss-Seidel over coupled contacts satisfies every contact's law", "[coulomb_cone]") {
  std::mt19937 rng(33);
  std::normal_distribution<double> normal(0.0, 1.0);
  // Three contacts sharing dofs: D = C M^{-1} C^T with C (9 x 6) of random rows, M = I.
  Eigen::MatrixXd C(9, 6);
  for (int i = 0; i < C.size(); ++i) C(i / 6, i % 6) = normal(rng);
  const Eigen::MatrixXd D = C * C.transpose() + 0.5 * Eigen::MatrixXd::Identity(9, 9);
  Eigen::VectorXd q(9);
  q << -1.0, 0.5, -0.3, -0.4, 2.0, 1.0, -2.0, -0.1, 0.05;
  const Eigen::Vector3d mu(0.3, 0.5, 0.8);
  Eigen::VectorXd x;
  const nsb::LcpResult res = nsb::solve_coulomb_cone(D, q, mu, x, {1e-13, 100000});
  REQUIRE(res.converged);
  CHECK(res.iterations > 1);
  for (int i = 0; i < 3; ++i) {
    // Contact i's law against the others' impulses: its local free velocity shifted by them.
    Eigen::VectorXd others = x;
    others.segment<3>(3 * i).setZero();
    const Eigen::Vector3d local = q.segment<3>(3 * i) + D.middleRows<3>(3 * i) * others;
    const ConeImpulse r{x[3 * i], {x[3 * i + 1], x[3 * i + 2]}};
    CHECK(nsb::cone_law_residual(D.block<3, 3>(3 * i, 3 * i), local, mu[i], r) < 1e-10);
  }
  // No energy gain (e = 0): Lambda . (q + U) / 2 = Lambda . q + Lambda . D Lambda / 2 <= 0.
  CHECK(x.dot(q) + 0.5 * x.dot(D * x) <= 1e-14);
}

// Not a check: prints the numbers docs/three_d.md quotes. Hidden; run it by its tag:
// build/tests/nsbench_tests "[three_d_numbers]"
TEST_CASE("coulomb cone: the numbers of docs/three_d.md", "[.][three_d_numbers]") {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int most = 0;
  long total = 0;
  double worst = 0.0;
  const int cases = 10000;
  for (int i = 0; i < cases; ++i) {
    const Eigen::Matrix3d W = random_spd(rng);
    const Eigen::Vector3d q(-std::abs(u(rng)), 2.0 * u(rng), 2.0 * u(rng));
    const double mu = std::min(1.0, 0.9 * W(0, 0) / W.block<1, 2>(0, 1).norm()) * std::abs(u(rng));
    const auto solve = nsb::solve_cone_local(W, q, mu);
    most = std::max(most, solve.iterations);
    total += solve.iterations;
    worst = std::max(worst, nsb::cone_law_residual(W, q, mu, solve.impulse));
  }
  std::printf("solve_cone_local on %d random SPD blocks: outer iterations mean %.1f, max %d; worst residual %.2e\n",
              cases, static_cast<double>(total) / cases, most, worst);
}
