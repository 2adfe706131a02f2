#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "problems/rocking_block_exact.hpp"
#include "tests/support/input_error.hpp"

using Catch::Detail::Approx;
using nsb::CornerImpact;
using nsb::RockingBlockExact;
using nsb::RockingBlockSpec;
using nsb::RockingImpactLaw;

namespace {

constexpr double kPiRad = std::numbers::pi;

// Gauss–Legendre nodes and weights on [-1, 1] (Newton on P_n from Chebyshev guesses).
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(n, 0.0), w.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPiRad * (i + 0.75) / (n + 0.5)), dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1, p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1.0);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    x[i] = z;
    w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
}

// The energy quadrature, independent of the closed form: time from the turning point psi_m to
// psi, t = int dpsi / (p sqrt(2 (cos psi_m - cos psi))), with psi = psi_m + v^2 (smooth in v:
// cos psi_m - cos psi = 2 sin(psi_m + v^2 / 2) sin(v^2 / 2)).
double quadrature_time(double p, double psi_m, double psi) {
  std::vector<double> x, w;
  gauss_legendre(80, x, w);
  const double top = std::sqrt(psi - psi_m);
  double sum = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double v = 0.5 * top * (x[i] + 1.0);
    const double half = 0.5 * v * v;
    const double sinc = v == 0.0 ? 0.5 : std::sin(half) / (v * v);
    sum += w[i] / (p * std::sqrt(std::sin(psi_m + half) * sinc));
  }
  return 0.5 * top * sum;
}

RockingBlockExact make_exact_block(double b, double h, double theta0, double omega0,
                        RockingImpactLaw law = RockingImpactLaw::housner, double e = 0.0, double mu = 1e308) {
  RockingBlockSpec spec;
  spec.b = b, spec.h = h, spec.theta0 = theta0, spec.omega0 = omega0, spec.law = law, spec.e = e, spec.mu = mu;
  return RockingBlockExact(spec);
}

// Angular momentum about the floor point (px, 0), counter-clockwise (I_c = m R^2 / 3, m = 1).
double momentum_about(double b, double h, double px, double x, double y, double vx, double vy, double omega) {
  return (b * b + h * h) / 3.0 * omega + ((x - px) * vy - y * vx);
}

}  // namespace

TEST_CASE("rocking block: corner gaps, normal and tangent rows against finite differences", "[rocking_block_exact]") {
  std::mt19937 rng(32);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double d = 1e-6;
  for (int trial = 0; trial < 20; ++trial) {
    const double b = 0.1 + std::abs(u(rng)), h = 0.1 + std::abs(u(rng));
    const Eigen::Vector3d U(u(rng), 2.0 * u(rng), 1.5 * u(rng));
    const auto corners = nsb::block_corners(b, h, U);
    for (int side = 0; side < 2; ++side) {
      const double px = side == 0 ? b : -b, py = -h;
      const auto& k = side == 0 ? corners.right : corners.left;
      // World position of the corner, from the definition.
      const auto world = [&](const Eigen::Vector3d& V) {
        return Eigen::Vector2d(V(0) + px * std::cos(V(2)) - py * std::sin(V(2)),
                               V(1) + px * std::sin(V(2)) + py * std::cos(V(2)));
      };
      CHECK(k.gap == Approx(world(U)(1)).margin(1e-15));
      for (int j = 0; j < 3; ++j) {
        Eigen::Vector3d plus = U, minus = U;
        plus(j) += d, minus(j) -= d;
        const Eigen::Vector2d slope = (world(plus) - world(minus)) / (2.0 * d);
        const double gap_slope = (nsb::block_corners(b, h, plus).right.gap - nsb::block_corners(b, h, minus).right.gap) / (2.0 * d);
        CHECK(k.normal_row(j) == Approx(slope(1)).margin(1e-9));
        CHECK(k.tangent_row(j) == Approx(slope(0)).margin(1e-9));
        if (side == 0) CHECK(k.normal_row(j) == Approx(gap_slope).margin(1e-9));
      }
    }
  }
}

TEST_CASE("rocking block: energy constant between impacts, contact held, impact times against the quadrature",
          "[rocking_block_exact]") {
  for (const double b : {0.1, 0.2, 0.45}) {
    const auto ex = make_exact_block(b, 1.0, 0.6 * std::atan(b), 0.0);
    REQUIRE(ex.impacts().size() > 5);
    const double p = ex.p(), alpha = ex.alpha();
    // The first impact, located on the integrated solution, and the closed-form phases, both
    // against the quadrature of the energy: theta0 is a turning point (omega0 = 0).
    const double psi0 = alpha - 0.6 * std::atan(b);
    CHECK(ex.impacts()[0].t == Approx(quadrature_time(p, psi0, alpha)).epsilon(1e-13));
    for (std::size_t k = 0; k + 1 < 6; ++k) {
      const double w = std::abs(ex.impacts()[k].omega_after);
      const double psi_m = alpha - ex.amplitude(w);
      CHECK(ex.impacts()[k + 1].t - ex.impacts()[k].t == Approx(2.0 * quadrature_time(p, psi_m, alpha)).epsilon(1e-13));
      // Energy in the phase: (1/2) I_O w^2 + m g h at theta = 0, the same at 40 points.
      const double E = 0.5 * ex.pivot_inertia() * w * w + 9.81 * 1.0;
      const double t0 = ex.impacts()[k].t, t1 = ex.impacts()[k + 1].t;
      for (int i = 0; i < 40; ++i) {
        const auto s = *ex.state(t0 + (t1 - t0) * (i + 0.5) / 40.0);
        CHECK(ex.energy(s) == Approx(E).epsilon(1e-13));
        // The pivot stays on the floor at its place, the other corner above it.
        const auto corners = nsb::block_corners(b, 1.0, {s.x, s.y, s.theta});
        const auto& pivot = s.theta > 0 ? corners.left : corners.right;
        const auto& other = s.theta > 0 ? corners.right : corners.left;
        CHECK(std::abs(pivot.gap) < 1e-14);
        CHECK(other.gap > 0.0);
        CHECK(std::abs(pivot.tangent_row.dot(Eigen::Vector3d(s.vx, s.vy, s.omega))) < 1e-14);
        CHECK(std::abs(pivot.normal_row.dot(Eigen::Vector3d(s.vx, s.vy, s.omega))) < 1e-14);
      }
      // The pivot's force against the momentum's rate (fourth-order central differences).
      const double tm = t0 + 0.3 * (t1 - t0), d = 1e-4;
      const auto a2 = *ex.state(tm - 2 * d), a1 = *ex.state(tm - d), b1 = *ex.state(tm + d), b2 = *ex.state(tm + 2 * d);
      const auto mid = *ex.state(tm);
      const auto force = ex.pivot_force(mid.theta, mid.omega);
      CHECK((a2.vx - 8 * a1.vx + 8 * b1.vx - b2.vx) / (12 * d) == Approx(force(0)).margin(1e-9));
      CHECK((a2.vy - 8 * a1.vy + 8 * b1.vy - b2.vy) / (12 * d) + 9.81 == Approx(force(1)).margin(1e-9));
      CHECK(force(1) > 0.0);
      // The turning point: |theta| = amplitude, omega = 0, half-way through the phase.
      const auto top = *ex.state(t0 + ex.rise_time(w));
      CHECK(std::abs(top.theta) == Approx(ex.amplitude(w)).epsilon(1e-12));
      CHECK(std::abs(top.omega) < 1e-12);
    }
  }
}

TEST_CASE("rocking block: Housner's impacts keep the angular momentum about the new corner", "[rocking_block_exact]") {
  for (const double b : {0.1, 0.3, 0.6}) {
    const double h = 1.0;
    const auto ex = make_exact_block(b, h, -0.5 * std::atan(b), 0.05);
    CHECK(ex.impact_ratio() == Approx(1.0 - 1.5 * std::pow(std::sin(std::atan(b / h)), 2)).epsilon(1e-15));
    for (std::size_t k = 0; k < 4; ++k) {
      const auto& im = ex.impacts()[k];
      // After: the new phase at theta = 0. Before: rotation about the old pivot, at -sigma' b.
      const auto after = *ex.state(im.t);
      const double new_pivot = im.omega_after > 0 ? -b : b;  // omega > 0 turns about the left corner
      const double old_pivot = -new_pivot;
      const double vx = -h * im.omega_before, vy = (old_pivot < 0 ? b : -b) * im.omega_before;
      const double before = momentum_about(b, h, after.x + new_pivot, after.x, h, vx, vy, im.omega_before);
      CHECK(std::abs(after.theta) < 1e-12);
      CHECK(momentum_about(b, h, after.x + new_pivot, after.x, after.y, after.vx, after.vy, after.omega) ==
            Approx(before).epsilon(1e-13));
      CHECK(im.omega_after / im.omega_before == Approx(ex.impact_ratio()).epsilon(1e-14));
    }
    // The impacts accumulate: times increase to the rest time, amplitudes fall.
    const auto& all = ex.impacts();
    for (std::size_t k = 1; k < all.size(); ++k) {
      REQUIRE(all[k].t > all[k - 1].t);
      REQUIRE(all[k].amplitude_after < all[k - 1].amplitude_after);
    }
    CHECK(ex.ending() == RockingBlockExact::Ending::rest);
    CHECK(ex.rest_time() >= all.back().t);
    CHECK(ex.rest_time() - all.back().t < 1e-12);
    // The rest time against the series summed in long double far past round-off (no tail).
    long double series = all.front().t;
    for (double w = std::abs(all.front().omega_after); w > 1e-300; w *= ex.impact_ratio())
      series += 2.0L * ex.rise_time(w);
    CHECK(ex.rest_time() == Approx(static_cast<double>(series)).epsilon(4e-16));
    const auto rest = *ex.state(ex.rest_time() + 1.0);
    CHECK(rest.theta == 0.0);
    CHECK(rest.omega == 0.0);
  }
}

TEST_CASE("rocking block: Moreau's law with e = 0 and enough friction is Housner's", "[rocking_block_exact]") {
  for (const double alpha_deg : {5.0, 15.0, 30.0, 45.0, 54.0}) {
    const double alpha = alpha_deg * kPiRad / 180.0, b = std::sin(alpha), h = std::cos(alpha);
    const double mu_H = 3.0 * b * h / (1.0 + 3.0 * h * h);
    for (const int pivot : {1, -1}) {
      const auto out = nsb::moreau_impact(b, h, 1.0, 0.0, mu_H * 1.0001, pivot, -pivot * 0.7);
      CHECK(out.solutions == 1);
      CHECK(out.kind == CornerImpact::Kind::rocks_on_new_corner);
      CHECK(out.ratio == Approx(nsb::housner_ratio(alpha)).margin(1e-15));
      CHECK(std::abs(out.Lambda_old) < 1e-15);
      CHECK(out.normal_velocity_after(1) > 0.0);  // the old corner lifts
      // Closed forms: Lambda_new = b |omega-| m (1 + 3 cos^2 alpha) / 2, |Lambda_T| = mu_H Lambda_new.
      CHECK(out.Lambda_new == Approx(b * 0.7 * (1.0 + 3.0 * h * h) / 2.0).epsilon(1e-14));
      CHECK(std::abs(out.Lambda_T) == Approx(mu_H * out.Lambda_new).epsilon(1e-13));
    }
    // Just below mu_H the new corner slips, with the ratio in closed form while the old corner
    // lifts (1 - 3 sin^2 + 3 mu sin cos >= 0); else both corners slide on the floor, omega+ = 0.
    const double mu = 0.9 * mu_H;
    const auto slip = nsb::moreau_impact(b, h, 1.0, 0.0, mu, 1, -1.0);
    CHECK(slip.kind == CornerImpact::Kind::slip);
    if (1.0 - 3.0 * b * b + 3.0 * mu * b * h >= 0.0) {
      CHECK(slip.normal_velocity_after(1) >= 0.0);
      CHECK(slip.ratio ==
            Approx(1.0 - 6.0 * b * (b - mu * h) / (1.0 + 3.0 * b * b - 3.0 * mu * b * h)).epsilon(1e-13));
    } else {
      CHECK(std::abs(slip.normal_velocity_after(1)) < 1e-15);
      CHECK(std::abs(slip.ratio) < 1e-15);
    }
  }
}

TEST_CASE("rocking block: Moreau's impulses satisfy the complementarity and Coulomb's law", "[rocking_block_exact]") {
  for (const double alpha_deg : {10.0, 40.0, 60.0, 80.0}) {
    const double alpha = alpha_deg * kPiRad / 180.0, b = std::sin(alpha), h = std::cos(alpha);
    for (const double e : {0.0, 0.3, 1.0}) {
      for (const double mu : {0.0, 0.05, 0.3, 1.0, 10.0}) {
        const auto out = nsb::moreau_impact(b, h, 2.0, e, mu, 1, -1.3);
        INFO("alpha " << alpha_deg << " e " << e << " mu " << mu);
        REQUIRE(out.solutions == 1);
        const auto& c = out.normal_velocity_after;  // new, old, slip
        const double c_new_minus = 2.0 * b * -1.3, tol = 1e-13;
        const double U_new = c(0) + e * c_new_minus, U_old = c(1);
        CHECK(out.Lambda_new >= -tol);
        CHECK(out.Lambda_old >= -tol);
        CHECK(U_new >= -tol);
        CHECK(U_old >= -tol);
        CHECK(std::abs(out.Lambda_new * U_new) < tol);
        CHECK(std::abs(out.Lambda_old * U_old) < tol);
        const double bound = mu * (out.Lambda_new + out.Lambda_old);
        CHECK(std::abs(out.Lambda_T) <= bound + tol);
        if (std::abs(c(2)) > tol) {
          CHECK(std::abs(out.Lambda_T) == Approx(bound).margin(tol));
          CHECK(out.Lambda_T * c(2) <= tol);
        }
        // No energy gained: kinetic energy with M = diag(m, m, m R^2 / 3), m = 2, R = 1.
        const auto kinetic = [](const Eigen::Vector3d& v) { return v(0) * v(0) + v(1) * v(1) + v(2) * v(2) / 3.0; };
        CHECK(kinetic(out.velocity_after) <= kinetic(out.velocity_before) * (1.0 + 1e-14));
      }
    }
    // Wide blocks (alpha above 54.7 degrees) rebound about the old corner: omega+ = -e omega-.
    if (alpha_deg > 55.0) {
      const auto out = nsb::moreau_impact(b, h, 1.0, 0.5, 1.01 * h / b, -1, 2.0);
      CHECK(out.kind == CornerImpact::Kind::rocks_on_old_corner);
      CHECK(out.ratio == Approx(-0.5).epsilon(1e-14));
    }
  }
}

TEST_CASE("rocking block: the impact laws in a sequence", "[rocking_block_exact]") {
  // Moreau, e = 0, no slip: the same sequence as Housner's.
  const auto housner = make_exact_block(0.25, 1.0, 0.15, 0.0);
  const auto moreau = make_exact_block(0.25, 1.0, 0.15, 0.0, RockingImpactLaw::moreau, 0.0, 1.0);
  REQUIRE(housner.impacts().size() == moreau.impacts().size());
  CHECK(moreau.impact_ratio() == Approx(housner.impact_ratio()).epsilon(1e-14));
  CHECK(moreau.rest_time() == Approx(housner.rest_time()).epsilon(1e-13));
  // Moreau with e > 0 on a slender block: flight; the exact solution stops at the impact.
  const auto bounce = make_exact_block(0.25, 1.0, 0.15, 0.0, RockingImpactLaw::moreau, 0.5, 1.0);
  CHECK(bounce.ending() == RockingBlockExact::Ending::leaves_rocking);
  CHECK(bounce.first_impact_outcome()->kind == CornerImpact::Kind::flight);
  CHECK(bounce.end_time() == bounce.impacts()[0].t);
  CHECK_FALSE(bounce.state(bounce.end_time() + 1e-9).has_value());
  // A wide block under Housner's law stops at the first impact (r <= 0).
  const auto wide = make_exact_block(2.0, 1.0, 0.3, 0.0);
  CHECK(wide.impacts().size() == 1);
  CHECK(wide.rest_time() == wide.impacts()[0].t);
  // Launched hard enough, or tilted beyond alpha, it topples: ends on its side.
  for (const auto& topple : {make_exact_block(0.2, 1.0, 0.0, 3.0), make_exact_block(0.2, 1.0, -0.25, 0.0)}) {
    CHECK(topple.ending() == RockingBlockExact::Ending::topples);
    CHECK(topple.impacts().empty());
    CHECK(std::abs(topple.state(topple.end_time())->theta) == Approx(kPiRad / 2).epsilon(1e-13));
  }
  // A wide block with e > 0 under Moreau's law rebounds about the same corner: theta keeps its
  // sign, the speed falls by e at each impact, the energy above rest by e^2.
  const auto rebound = make_exact_block(2.0, 1.0, -0.3, 0.0, RockingImpactLaw::moreau, 0.5, 1.0);
  CHECK(rebound.impact_ratio() == Approx(-0.5).epsilon(1e-14));
  REQUIRE(rebound.impacts().size() > 3);
  CHECK(rebound.ending() == RockingBlockExact::Ending::rest);
  for (std::size_t k = 0; k < 3; ++k) {
    const auto& im = rebound.impacts()[k];
    const double t_mid = 0.5 * (im.t + rebound.impacts()[k + 1].t);
    CHECK(rebound.state(t_mid)->theta < 0.0);
    CHECK(im.omega_after == Approx(-0.5 * im.omega_before).epsilon(1e-14));
  }
  CHECK_THROWS_AS(nsb::moreau_impact(0.2, 1.0, 1.0, 0.0, 1.0, 1, 0.5), std::invalid_argument);
}

TEST_CASE("rocking block: bad input is one line naming the parameter and its range", "[rocking_block_exact]") {
  struct Case {
    const char* name;
    void (*set)(RockingBlockSpec&);
    const char* range;
  };
  const Case cases[] = {
      {"b", [](RockingBlockSpec& s) { s.b = 0.0; }, "(0, 90) degrees"},
      {"h", [](RockingBlockSpec& s) { s.h = -1.0; }, "(0, 90) degrees"},
      {"mu", [](RockingBlockSpec& s) { s.mu = -0.1; }, "[0, inf)"},
      {"e", [](RockingBlockSpec& s) { s.e = 1.5; }, "[0, 1]"},
      {"theta0", [](RockingBlockSpec& s) { s.theta0 = 1.6; }, "(-pi/2, pi/2)"},
      {"m", [](RockingBlockSpec& s) { s.m = 0.0; }, "(0, inf)"},
  };
  for (const auto& c : cases) {
    RockingBlockSpec spec;
    c.set(spec);
    const std::string text = nsb::test::input_error_text<RockingBlockExact>(spec);
    INFO(text);
    CHECK(text.find(std::string(c.name) + " = ") != std::string::npos);
    CHECK(text.find(c.range) != std::string::npos);
    CHECK(text.find('\n') == std::string::npos);
  }
}

// Not a check: prints the numbers docs/rigid_bodies.md quotes. Hidden; run it by its tag:
// build/tests/nsbench_tests "[rigid_numbers]"
TEST_CASE("rocking block: the numbers of docs/rigid_bodies.md", "[.][rigid_numbers]") {
  std::printf("alpha_deg  housner_ratio  mu_H  moreau_e0_mu_inf  moreau_e0_mu_H/2 (kind)  moreau_e0.5_mu_inf (kind)\n");
  for (const double alpha_deg : {5.0, 10.0, 15.0, 20.0, 30.0, 45.0, 60.0}) {
    const double alpha = alpha_deg * kPiRad / 180.0, b = std::sin(alpha), h = std::cos(alpha);
    const double mu_H = 3.0 * b * h / (1.0 + 3.0 * h * h);
    const auto stick = nsb::moreau_impact(b, h, 1.0, 0.0, 1e308, 1, -1.0);
    const auto slip = nsb::moreau_impact(b, h, 1.0, 0.0, 0.5 * mu_H, 1, -1.0);
    const auto bounce = nsb::moreau_impact(b, h, 1.0, 0.5, 1e308, 1, -1.0);
    std::printf("%4.0f  %.16f  %.6f  %.16f  %.6f (%d)  %.6f (%d)\n", alpha_deg, nsb::housner_ratio(alpha), mu_H,
                stick.ratio, slip.ratio, static_cast<int>(slip.kind), bounce.ratio, static_cast<int>(bounce.kind));
  }
  const auto ex = make_exact_block(0.2, 1.0, 0.1, 0.0);
  std::printf("block b 0.2 h 1 m 1 g 9.81 theta0 0.1 (Housner): first impact %.15f s, %zu impacts, rest at %.15f s, "
              "amplitude after impacts 1..3: %.12f %.12f %.12f rad\n",
              ex.impacts()[0].t, ex.impacts().size(), ex.rest_time(), ex.impacts()[0].amplitude_after,
              ex.impacts()[1].amplitude_after, ex.impacts()[2].amplitude_after);
}
