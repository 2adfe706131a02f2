#include <catch2/catch.hpp>
#include <random>

#include "solvers/lcp.hpp"

TEST_CASE("LCP: diagonal Delassus is solved in closed form", "[integrators][lcp]") {
  Eigen::MatrixXd D = Eigen::Vector3d(2.0, 1.0, 4.0).asDiagonal();
  Eigen::VectorXd q(3), x;
  q << -4.0, 3.0, 0.0;
  const auto r = nsb::solve_lcp(D, q, x, {});
  CHECK(r.iterations == 1);
  CHECK(x[0] == 2.0);
  CHECK(x[1] == 0.0);
  CHECK(x[2] == 0.0);
}

TEST_CASE("LCP: projected Gauss-Seidel meets complementarity on coupled SPD problems", "[integrators][lcp]") {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 2 + trial % 9;
    Eigen::MatrixXd A(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = normal(rng);
    const Eigen::MatrixXd D = A * A.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    Eigen::VectorXd q(n), x;
    for (int i = 0; i < n; ++i) q[i] = normal(rng);
    const auto r = nsb::solve_lcp(D, q, x, {1e-12, 100000});
    REQUIRE(r.converged);
    const Eigen::VectorXd w = D * x + q;
    const double scale = q.cwiseAbs().maxCoeff();
    CHECK(x.minCoeff() >= 0.0);
    CHECK(w.minCoeff() >= -1e-10 * scale);
    CHECK(std::abs(x.dot(w)) <= 1e-9 * scale * (1.0 + x.cwiseAbs().sum()));
  }
}

TEST_CASE("LCP: a non-positive diagonal is refused", "[integrators][lcp][bad-input]") {
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(2, 2);
  Eigen::VectorXd q = Eigen::VectorXd::Ones(2), x;
  CHECK_THROWS_WITH(nsb::solve_lcp(D, q, x, {}), Catch::Contains("non-positive diagonal"));
}
