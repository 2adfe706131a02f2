#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "core/parameters.hpp"
#include "problems/hex8_elements.hpp"
#include "tests/support/input_error.hpp"
#include "tests/support/allocation_counter.hpp"

using Catch::Detail::Approx;
using nsb::Hex8Element;
using nsb::Hex8Law;
using nsb::Hex8Material;
using nsb::Hex8Nodes;

namespace {

constexpr int kCorner[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                               {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

// A distorted reference brick: the box [0, a] x [0, b] x [0, c] with its nodes moved by up to `shake`.
Hex8Nodes brick(double a, double b, double c, double shake, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-shake, shake);
  Hex8Nodes X;
  for (int n = 0; n < 8; ++n)
    X.col(n) << 0.5 * a * (1 + kCorner[n][0]) + u(rng), 0.5 * b * (1 + kCorner[n][1]) + u(rng),
        0.5 * c * (1 + kCorner[n][2]) + u(rng);
  return X;
}

Hex8Nodes deformed_hex(const Hex8Nodes& X, double amount, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-amount, amount);
  Hex8Nodes x = X;
  for (int i = 0; i < 24; ++i) x.data()[i] += u(rng);
  return x;
}

Eigen::Matrix3d rotation(double ax, double ay, double az) {
  return (Eigen::AngleAxisd(az, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(ay, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(ax, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

const Hex8Law kLaws[] = {Hex8Law::svk, Hex8Law::neo_hookean};

}  // namespace

TEST_CASE("hex8: the force is the energy's gradient and the tangent the force's", "[hex8]") {
  std::mt19937 rng(8);
  for (const Hex8Law law : kLaws) {
    const Hex8Material mat = Hex8Material::from_young(law, 200.0, 0.3);
    const Hex8Nodes X = brick(1.0, 0.7, 1.3, 0.1, rng);
    const Hex8Element element(X);
    const Hex8Nodes x = deformed_hex(X, 0.15, rng);
    nsb::Hex8Vector f, fp, fm;
    nsb::Hex8Matrix K;
    element.internal_force(x, mat, f);
    element.tangent(x, mat, K);
    const double h = 1e-6;
    nsb::Hex8Vector grad;
    nsb::Hex8Matrix dK;
    for (int r = 0; r < 24; ++r) {
      Hex8Nodes xp = x, xm = x;
      xp.data()[r] += h;
      xm.data()[r] -= h;
      grad(r) = (element.energy(xp, mat) - element.energy(xm, mat)) / (2.0 * h);
      element.internal_force(xp, mat, fp);
      element.internal_force(xm, mat, fm);
      dK.col(r) = (fp - fm) / (2.0 * h);
    }
    INFO("law " << static_cast<int>(law));
    CHECK((grad - f).norm() < 1e-7 * f.norm());
    CHECK((dK - K).norm() < 1e-7 * K.norm());
    CHECK((K - K.transpose()).norm() < 1e-13 * K.norm());  // hyperelastic: symmetric
  }
}

TEST_CASE("hex8: patch test, a uniform strain gives no force on the interior node", "[hex8]") {
  // A 2x2x2 patch of distorted elements on 27 nodes, the middle one moved off its place.
  std::mt19937 rng(27);
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  Eigen::Matrix<double, 3, 27> nodes;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        const bool boundary = i != 1 || j != 1 || k != 1;
        nodes.col(i + 3 * j + 9 * k) << i + (boundary ? 0.0 : u(rng)), j + (boundary ? 0.0 : u(rng)),
            k + (boundary ? 0.0 : u(rng));
      }
  Eigen::Matrix3d F0;
  F0 << 1.05, 0.02, -0.03, 0.01, 0.97, 0.04, -0.02, 0.03, 1.02;
  const Eigen::Vector3d shift(0.3, -0.2, 0.1);
  for (const Hex8Law law : kLaws) {
    const Hex8Material mat = Hex8Material::from_young(law, 100.0, 0.25);
    Eigen::Vector3d middle = Eigen::Vector3d::Zero();
    double scale = 0.0;
    for (int ek = 0; ek < 2; ++ek)
      for (int ej = 0; ej < 2; ++ej)
        for (int ei = 0; ei < 2; ++ei) {
          Hex8Nodes X;
          int ids[8];
          for (int n = 0; n < 8; ++n) {
            ids[n] = (ei + (kCorner[n][0] + 1) / 2) + 3 * (ej + (kCorner[n][1] + 1) / 2) + 9 * (ek + (kCorner[n][2] + 1) / 2);
            X.col(n) = nodes.col(ids[n]);
          }
          const Hex8Element element(X);
          const Hex8Nodes x = (F0 * X).colwise() + shift;
          nsb::Hex8Vector f;
          element.internal_force(x, mat, f);
          scale = std::max(scale, f.cwiseAbs().maxCoeff());
          for (int n = 0; n < 8; ++n)
            if (ids[n] == 13) middle += f.segment<3>(3 * n);
        }
    INFO("law " << static_cast<int>(law) << " scale " << scale);
    REQUIRE(scale > 1.0);  // the strain does load the elements
    CHECK(middle.norm() < 1e-13 * scale);
  }
}

TEST_CASE("hex8: a rigid motion gives no energy and no force", "[hex8]") {
  std::mt19937 rng(3);
  const Hex8Nodes X = brick(2.0, 1.0, 0.5, 0.1, rng);
  const Hex8Element element(X);
  const Hex8Nodes x = (rotation(0.7, -1.1, 2.3) * X).colwise() + Eigen::Vector3d(1.0, 2.0, -3.0);
  for (const Hex8Law law : kLaws) {
    const Hex8Material mat = Hex8Material::from_young(law, 1e3, 0.45);
    nsb::Hex8Vector f;
    element.internal_force(x, mat, f);
    nsb::Hex8Vector stretched_force;
    const Hex8Nodes stretched = 1.01 * x;
    element.internal_force(stretched, mat, stretched_force);
    CHECK(std::abs(element.energy(x, mat)) < 1e-12 * mat.mu * element.volume());
    CHECK(f.norm() < 1e-12 * stretched_force.norm());
  }
}

TEST_CASE("hex8: the masses sum to rho times the volume", "[hex8]") {
  std::mt19937 rng(5);
  const double rho = 7800.0;
  // A sheared parallelepiped: volume det of its edge vectors.
  Eigen::Matrix3d edges;
  edges << 1.0, 0.3, 0.1, 0.0, 0.8, 0.2, 0.0, 0.0, 1.2;
  Hex8Nodes X;
  for (int n = 0; n < 8; ++n) X.col(n) = edges * Eigen::Vector3d((1 + kCorner[n][0]) / 2, (1 + kCorner[n][1]) / 2, (1 + kCorner[n][2]) / 2);
  const Hex8Element element(X);
  CHECK(element.volume() == Approx(edges.determinant()).epsilon(1e-15));
  Eigen::Matrix<double, 8, 1> lumped;
  Eigen::Matrix<double, 8, 8> consistent;
  element.lumped_mass(rho, lumped);
  element.consistent_mass(rho, consistent);
  CHECK(lumped.sum() == Approx(rho * edges.determinant()).epsilon(1e-14));
  CHECK(consistent.sum() == Approx(rho * edges.determinant()).epsilon(1e-14));
  for (int a = 0; a < 8; ++a) CHECK(lumped(a) == Approx(rho * edges.determinant() / 8.0).epsilon(1e-14));
  // The unit cube's consistent mass in closed form: the product over the three directions of the
  // 1D element's (2, 1; 1, 2) / 6, M_ab = prod_j (2 if a and b share coordinate j, else 1) / 216.
  Hex8Nodes box;
  for (int n = 0; n < 8; ++n) box.col(n) << (1 + kCorner[n][0]) / 2, (1 + kCorner[n][1]) / 2, (1 + kCorner[n][2]) / 2;
  Eigen::Matrix<double, 8, 8> Mbox;
  Hex8Element(box).consistent_mass(1.0, Mbox);
  for (int a = 0; a < 8; ++a)
    for (int b = 0; b < 8; ++b) {
      double expected = 1.0 / 216.0;
      for (int j = 0; j < 3; ++j) expected *= kCorner[a][j] == kCorner[b][j] ? 2.0 : 1.0;
      CHECK(Mbox(a, b) == Approx(expected).epsilon(1e-14));
    }
  // Any distorted brick: the lumped masses still sum to rho V.
  const Hex8Element distorted(brick(1.0, 1.0, 1.0, 0.2, rng));
  distorted.lumped_mass(rho, lumped);
  CHECK(lumped.sum() == Approx(rho * distorted.volume()).epsilon(1e-14));
}

TEST_CASE("hex8: the linear elastic limit, allocation-free, bad input", "[hex8]") {
  // A unit cube stretched by a small eps along x, its lateral positions held (oedometric strain):
  // the force on the x = 1 face is the oedometric modulus lambda + 2 mu
  // = E (1 - nu) / ((1 + nu)(1 - 2 nu)) times eps, to O(eps) (the 3D bar's modulus).
  Hex8Nodes X;
  for (int n = 0; n < 8; ++n) X.col(n) << (1 + kCorner[n][0]) / 2, (1 + kCorner[n][1]) / 2, (1 + kCorner[n][2]) / 2;
  const Hex8Element cube(X);
  const double E = 210.0, nu = 0.3, eps = 1e-7;
  Hex8Nodes x = X;
  x.row(0) *= 1.0 + eps;
  for (const Hex8Law law : kLaws) {
    const Hex8Material mat = Hex8Material::from_young(law, E, nu);
    nsb::Hex8Vector f;
    nsb::Hex8Matrix K;
    long allocations = 0;
    {
      const nsb::test::CountAllocations count;
      cube.internal_force(x, mat, f);
      cube.tangent(x, mat, K);
      allocations = count.count();
    }
    CHECK(allocations == 0);
    double face = 0.0;
    for (int n = 0; n < 8; ++n)
      if (kCorner[n][0] > 0) face += f(3 * n);
    CHECK(face == Approx(E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) * eps).epsilon(1e-6));
  }
  // Bad input: one line naming the parameter and its range.
  const std::string bad_nu = nsb::test::input_error_text_of([] { Hex8Material::from_young(Hex8Law::svk, 1.0, 0.5); });
  CHECK(bad_nu.find("nu = ") != std::string::npos);
  CHECK(bad_nu.find("[0, 0.5)") != std::string::npos);
  const std::string bad_E = nsb::test::input_error_text_of([] { Hex8Material::from_young(Hex8Law::svk, 0.0, 0.3); });
  CHECK(bad_E.find("E = ") != std::string::npos);
  Eigen::Matrix<double, 8, 1> m;
  const std::string bad_rho = nsb::test::input_error_text_of([&] { cube.lumped_mass(-1.0, m); });
  CHECK(bad_rho.find("rho = ") != std::string::npos);
  Hex8Nodes inverted = X;
  inverted.row(2) *= -1.0;  // mirrored: det J0 < 0
  CHECK_THROWS_AS(Hex8Element(inverted), std::invalid_argument);
  Hex8Nodes crushed = X;
  crushed.row(0) *= -0.5;  // det F < 0
  nsb::Hex8Vector f;
  CHECK_THROWS_AS(cube.internal_force(crushed, Hex8Material::from_young(Hex8Law::neo_hookean, 1.0, 0.3), f),
                  std::runtime_error);
}
