// ball-chain: the two outcomes of the header, each checked on its own. The simultaneous one
// against an exact enumeration of the LCP's active sets; the sequential march against the
// hand-derived collisions (e = 1; n = 2 and n = 3 with e < 1); both for momentum and, at
// e = 1, kinetic energy; the contact rows, the exact state and the bad input.
#include <Eigen/LU>
#include <catch2/catch.hpp>
#include <cmath>

#include "problems/ball_chain.hpp"
#include "problems/registry.hpp"

using Catch::Detail::Approx;

namespace {

nsb::BallChain make_balls(std::map<std::string, std::string> overrides) {
  return nsb::BallChain(nsb::Params(nsb::BallChain::parameters_spec(), overrides));
}

// Round-off of a few operations on O(v0) numbers.
constexpr double kEps = 1e-14;

// The LCP 0 <= x _|_ D x + q >= 0 solved by trying every active set exactly (LU on the
// active block): the solutions found, one per feasible set.
std::vector<nsb::Vec> enumerate_lcp(const Eigen::MatrixXd& D, const nsb::Vec& q) {
  const nsb::Index p = q.size();
  std::vector<nsb::Vec> solutions;
  for (unsigned mask = 0; mask < (1u << p); ++mask) {
    std::vector<nsb::Index> active;
    for (nsb::Index i = 0; i < p; ++i)
      if (mask & (1u << i)) active.push_back(i);
    nsb::Vec x = nsb::Vec::Zero(p);
    if (!active.empty()) {
      const auto a = static_cast<nsb::Index>(active.size());
      Eigen::MatrixXd Da(a, a);
      nsb::Vec qa(a);
      for (nsb::Index r = 0; r < a; ++r) {
        qa[r] = q[active[r]];
        for (nsb::Index c = 0; c < a; ++c) Da(r, c) = D(active[r], active[c]);
      }
      const nsb::Vec xa = Da.partialPivLu().solve(-qa);
      for (nsb::Index r = 0; r < a; ++r) x[active[r]] = xa[r];
    }
    const nsb::Vec w = D * x + q;
    const double tol = 1e-12 * q.cwiseAbs().maxCoeff();
    bool feasible = true;
    for (nsb::Index i = 0; i < p; ++i)
      feasible = feasible && x[i] >= -tol && w[i] >= -tol && std::abs(x[i] * w[i]) <= tol * (1 + std::abs(x[i]));
    if (feasible) solutions.push_back(x);
  }
  return solutions;
}

}  // namespace

TEST_CASE("ball-chain: contact rows are node-to-node, H = L M^-1 L^T tridiagonal", "[problems][ball-chain]") {
  const auto c = make_balls({{"n", "4"}, {"gap", "0.1"}, {"m", "2"}});
  REQUIRE(c.ncontacts() == 3);
  const Eigen::MatrixXd L(c.gap_operator());
  Eigen::MatrixXd expected(3, 4);
  expected << -1, 1, 0, 0, 0, -1, 1, 0, 0, 0, -1, 1;
  CHECK(L == expected);
  CHECK(c.gap_offset().isApproxToConstant(0.1));
  const Eigen::MatrixXd H = L * Eigen::MatrixXd(c.mass_matrix()).inverse() * L.transpose();
  CHECK(H(0, 1) == Approx(-0.5));
  CHECK(H(0, 0) == Approx(1.0));
  CHECK(H(0, 2) == 0.0);
}

TEST_CASE("ball-chain: the simultaneous outcome is the unique solution of Moreau's LCP (every active set tried)",
          "[problems][ball-chain]") {
  for (const double e : {0.0, 0.4, 1.0})
    for (int n = 2; n <= 7; ++n) {
      INFO("n = " << n << ", e = " << e);
      const auto c = make_balls({{"n", std::to_string(n)}, {"gap", "0"}, {"e", std::to_string(e)}, {"v0", "1.5"}, {"m", "0.7"}});
      const Eigen::MatrixXd L(c.gap_operator());
      const Eigen::MatrixXd H = L * Eigen::MatrixXd(c.mass_matrix()).inverse() * L.transpose();
      const nsb::Vec q = (1.0 + e) * L * c.initial_state().v;
      const auto solutions = enumerate_lcp(H, q);
      REQUIRE(solutions.size() == 1);
      CHECK((solutions[0] - c.simultaneous_impulses()).cwiseAbs().maxCoeff() <= kEps * 1.5);
      const nsb::Vec v = c.initial_state().v + Eigen::MatrixXd(c.mass_matrix()).inverse() * L.transpose() * solutions[0];
      CHECK((v - c.simultaneous_outcome()).cwiseAbs().maxCoeff() <= kEps * 1.5);
      // Closed form of the header.
      CHECK(c.simultaneous_outcome()[0] == Approx(1.5 * (1 - (1 + e) * (n - 1) / n)).margin(kEps));
      for (int j = 1; j < n; ++j) CHECK(c.simultaneous_outcome()[j] == Approx(1.5 * (1 + e) / n).margin(kEps));
    }
}

TEST_CASE("ball-chain: n = 3, e = 1 simultaneous outcome is (-1/3, 2/3, 2/3) v0", "[problems][ball-chain]") {
  const auto c = make_balls({{"n", "3"}, {"gap", "0"}, {"e", "1"}, {"v0", "3"}});
  CHECK(c.simultaneous_outcome()[0] == Approx(-1.0).margin(kEps));
  CHECK(c.simultaneous_outcome()[1] == Approx(2.0).margin(kEps));
  CHECK(c.simultaneous_outcome()[2] == Approx(2.0).margin(kEps));
  // The sequential outcome is not that: the last ball takes all.
  CHECK(c.sequential_outcome()[0] == 0.0);
  CHECK(c.sequential_outcome()[2] == 3.0);
}

TEST_CASE("ball-chain: both outcomes conserve momentum, and kinetic energy at e = 1", "[problems][ball-chain]") {
  for (const double e : {0.0, 0.3, 0.8, 1.0})
    for (int n : {2, 3, 5, 8}) {
      INFO("n = " << n << ", e = " << e);
      const auto c = make_balls({{"n", std::to_string(n)}, {"gap", "0.02"}, {"e", std::to_string(e)}, {"v0", "2"}});
      const double p0 = c.momentum(c.initial_state().v), k0 = c.kinetic_energy(c.initial_state().v);
      for (const nsb::Vec& v : {c.sequential_outcome(), c.simultaneous_outcome()}) {
        CHECK(c.momentum(v) == Approx(p0).epsilon(1e-13));
        if (e == 1.0) CHECK(c.kinetic_energy(v) == Approx(k0).epsilon(1e-13));
        if (e < 1.0) CHECK(c.kinetic_energy(v) < k0);
        for (nsb::Index i = 0; i + 1 < n; ++i) CHECK(v[i] <= v[i + 1] + 1e-13);  // no pair approaches
      }
    }
}

TEST_CASE("ball-chain: e = 1 sequential march is n - 1 collisions at k gap / v0 ending in (0, ..., 0, v0)",
          "[problems][ball-chain]") {
  const auto c = make_balls({{"n", "5"}, {"gap", "0.1"}, {"e", "1"}, {"v0", "2"}});
  const auto times = c.impact_times(1e9);
  REQUIRE(times.size() == 4);
  for (int k = 0; k < 4; ++k) CHECK(times[k] == Approx((k + 1) * 0.05).epsilon(1e-14));
  nsb::Vec expected = nsb::Vec::Zero(5);
  expected[4] = 2.0;
  CHECK(c.sequential_outcome() == expected);
  // Exact state: ball 3 moves only between t = 0.1 and 0.15, by 0.1 (it closes the gap to 4).
  CHECK(c.state(0.12)->v[2] == 2.0);
  CHECK(c.state(0.12)->u[2] == Approx(0.04).epsilon(1e-14));
  CHECK(c.state(1.0)->u[2] == Approx(0.1).epsilon(1e-14));
  CHECK(c.state(1.0)->u[4] == Approx(2.0 * (1.0 - 0.2)).epsilon(1e-14));
}

TEST_CASE("ball-chain: e < 1 sequential march: n = 2 and n = 3 by hand, later collisions included",
          "[problems][ball-chain]") {
  const double e = 0.5, v0 = 1.0;
  {
    const auto c = make_balls({{"n", "2"}, {"gap", "0.1"}, {"e", "0.5"}});
    CHECK(c.sequential_outcome()[0] == Approx((1 - e) / 2 * v0).epsilon(1e-15));
    CHECK(c.sequential_outcome()[1] == Approx((1 + e) / 2 * v0).epsilon(1e-15));
    CHECK(c.impact_times(1e9).size() == 1);
  }
  const auto c = make_balls({{"n", "3"}, {"gap", "0.1"}, {"e", "0.5"}});
  // First pass 1-2, 2-3, then 1 (at (1-e)/2) catches 2 (at (1-e^2)/4): a third collision.
  const auto times = c.impact_times(1e9);
  REQUIRE(times.size() == 3);
  const double v1 = (1 - e) / 2, v2 = (1 - e * e) / 4, v3 = (1 + e) * (1 + e) / 4;
  CHECK(times[0] == Approx(0.1 / v0));
  CHECK(times[1] == Approx(times[0] + 0.1 / ((1 + e) / 2)));
  // At times[1] ball 1 is (v2' - v1) (times[1] - times[0]) behind ball 2: it closes at v1 - v2.
  const double behind = ((1 + e) / 2 - v1) * (times[1] - times[0]);
  CHECK(times[2] == Approx(times[1] + behind / (v1 - v2)));
  const double w = (1 - e) * (1 - e) / 4;
  CHECK(w == Approx(v1 - v2));
  CHECK(c.sequential_outcome()[0] == Approx(v1 - (1 + e) * w / 2).epsilon(1e-15));
  CHECK(c.sequential_outcome()[1] == Approx(v2 + (1 + e) * w / 2).epsilon(1e-15));
  CHECK(c.sequential_outcome()[2] == Approx(v3).epsilon(1e-15));
  CHECK(c.sequential_outcome()[0] == Approx(0.203125));  // e = 1/2 in numbers
  // The outcome does not depend on the gap (the march scales with it).
  const auto wide = make_balls({{"n", "3"}, {"gap", "7"}, {"e", "0.5"}});
  CHECK((wide.sequential_outcome() - c.sequential_outcome()).cwiseAbs().maxCoeff() <= kEps);
  // Exact state is continuous in position across the collisions.
  for (const double t : times) {
    const nsb::Vec before = c.state(t * (1 - 1e-12))->u, after = c.state(t)->u;
    CHECK((before - after).cwiseAbs().maxCoeff() <= 1e-11);
  }
}

TEST_CASE("ball-chain: e = 0 touching cascade of the sequential law tends to the plastic v0 / n",
          "[problems][ball-chain]") {
  const auto c = make_balls({{"n", "4"}, {"gap", "0"}, {"e", "0"}, {"v0", "1"}});
  for (nsb::Index i = 0; i < 4; ++i) CHECK(c.sequential_outcome()[i] == Approx(0.25).margin(1e-13));
  CHECK(!c.state(0.5).has_value());
  CHECK(c.impact_times(1.0) == std::vector<double>{0.0});
}

TEST_CASE("ball-chain: observables and bad input", "[problems][ball-chain]") {
  auto p = nsb::make_problem("ball-chain", {{"n", "3"}, {"gap", "0"}});
  CHECK(p->observable_names() == std::vector<std::string>{"v1", "v2", "v3", "v1_exact", "v2_exact", "v3_exact"});
  std::vector<double> out(6);
  nsb::State s = p->initial_state();
  s.t = 0.1;
  p->observe(s, nsb::Vec(), 0.0, out);
  CHECK(out[3] == Approx(-1.0 / 3));
  CHECK_THROWS_WITH(nsb::make_problem("ball-chain", {{"n", "1"}}), Catch::Contains("n"));
  CHECK_THROWS_AS(nsb::make_problem("ball-chain", {{"gap", "-0.1"}}), nsb::InputError);
  CHECK_THROWS_AS(nsb::make_problem("ball-chain", {{"e", "1.5"}}), nsb::InputError);
  CHECK_THROWS_AS(nsb::make_problem("ball-chain", {{"m", "0"}}), nsb::InputError);
}

TEST_CASE("ball chain: field mesh, a vertex per ball at (i - 1) gap, one body each", "[problems][field-mesh]") {
  const auto p = make_balls({{"n", "3"}, {"gap", "0.25"}});
  const auto mesh = p.field_mesh();
  REQUIRE(mesh.has_value());
  CHECK(mesh->dimension == 1);
  REQUIRE(mesh->npoints() == 3);
  REQUIRE(mesh->nbodies() == 3);
  CHECK(mesh->nelements() == 0);
  CHECK(mesh->cell_body == std::vector<int>{0, 1, 2});
  for (nsb::Index i = 0; i < 3; ++i) {
    CHECK(mesh->points(i, 0) == 0.25 * static_cast<double>(i));
    CHECK(mesh->point_dofs(i, 0) == i);
    CHECK(mesh->cells(i, 0) == i);
  }
  // The gaps of the reference are the distances between the points.
  for (nsb::Index i = 0; i < 2; ++i) CHECK(p.gap_offset()[i] == mesh->points(i + 1, 0) - mesh->points(i, 0));
}
