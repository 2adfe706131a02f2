// block-2d: the internal force is the gradient of the strain energy and the tangent the
// gradient of the force (central differences), both laws are objective (a rigid motion
// gives no force and no energy; a rotated deformed state gives the rotated forces), the
// internal forces have no net force or torque, the mass and contact operators are what the
// header says, and the stable step bounds the true one.
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

#include "problems/block_2d.hpp"

using Catch::Detail::Approx;

namespace {

nsb::Block2d block(std::map<std::string, std::string> overrides = {}) {
  return nsb::Block2d(nsb::Params(nsb::Block2d::parameters_spec(), overrides));
}

// A smooth, clearly non-rigid deformation plus noise: strains of a few percent.
nsb::Vec deformed(const nsb::Block2d& b, double amplitude, unsigned seed) {
  std::srand(seed);
  nsb::Vec u = amplitude * nsb::Vec::Random(b.ndof());
  for (nsb::Index a = 0; a < b.nodes(); ++a) {
    const Eigen::Vector2d X = b.reference_position(a);
    u[2 * a] += 0.03 * X.y();
    u[2 * a + 1] += -0.02 * X.y() + 0.01 * X.x() * X.x();
  }
  return u;
}

// Rigid motion x -> R x + c applied to the current configuration X + u.
nsb::Vec rigidly_moved(const nsb::Block2d& b, const nsb::Vec& u, double angle, Eigen::Vector2d c) {
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(angle).toRotationMatrix();
  nsb::Vec w(b.ndof());
  for (nsb::Index a = 0; a < b.nodes(); ++a) {
    const Eigen::Vector2d X = b.reference_position(a);
    w.segment<2>(2 * a) = R * (X + u.segment<2>(2 * a)) + c - X;
  }
  return w;
}

const char* kMaterials[] = {"svk", "neo-hookean"};

}  // namespace

TEST_CASE("block-2d: internal force is the gradient of the strain energy", "[problems][block-2d]") {
  for (const char* material : kMaterials) {
    SECTION(material) {
      const auto b = block({{"material", material}, {"nx", "4"}, {"ny", "3"}});
      const nsb::Vec u = deformed(b, 4e-3, 1);
      nsb::Vec f(b.ndof());
      b.internal_force(u, f);
      // Central differences: truncation eps^2 W'''/6 ~ (eps/l)^2 |f| with l ~ 0.1 m the
      // element size, i.e. 1e-10 |f|; rounding eps_mach W / eps ~ 1e-16 * 1e2 J / 1e-6 m
      // = 1e-8 N against |f| ~ 1e4 N. 1e-6 |f| leaves room for both and is far below the
      // O(|f|) error of any wrong term.
      const double eps = 1e-6, scale = f.cwiseAbs().maxCoeff();
      REQUIRE(scale > 1e3);
      double worst = 0.0;
      for (nsb::Index i = 0; i < b.ndof(); ++i) {
        nsb::Vec up = u, um = u;
        up[i] += eps;
        um[i] -= eps;
        const double fd = (b.strain_energy(up) - b.strain_energy(um)) / (2 * eps);
        worst = std::max(worst, std::abs(fd - f[i]));
      }
      CHECK(worst <= 1e-6 * scale);
    }
  }
}

TEST_CASE("block-2d: tangent stiffness is the gradient of the internal force, refilled in place",
          "[problems][block-2d]") {
  for (const char* material : kMaterials) {
    SECTION(material) {
      const auto b = block({{"material", material}, {"nx", "4"}, {"ny", "3"}});
      const nsb::Vec u = deformed(b, 4e-3, 2);
      nsb::SpMat K;
      b.tangent_stiffness(nsb::Vec::Zero(b.ndof()), K);
      const double* values = K.valuePtr();
      b.tangent_stiffness(u, K);
      CHECK(K.valuePtr() == values);  // same pattern: values refilled, nothing reallocated
      std::srand(3);
      const double eps = 1e-6;
      for (int trial = 0; trial < 3; ++trial) {
        const nsb::Vec d = nsb::Vec::Random(b.ndof());
        nsb::Vec fp(b.ndof()), fm(b.ndof());
        b.internal_force(u + eps * d, fp);
        b.internal_force(u - eps * d, fm);
        const nsb::Vec fd = (fp - fm) / (2 * eps);
        const nsb::Vec Kd = K * d;
        // Same error budget as the force check, one derivative up.
        CHECK((fd - Kd).cwiseAbs().maxCoeff() <= 1e-6 * Kd.cwiseAbs().maxCoeff());
      }
      // Hyperelastic: K is symmetric.
      const nsb::SpMat Kt = K.transpose();
      CHECK((K - Kt).norm() <= 1e-12 * K.norm());
    }
  }
}

TEST_CASE("block-2d: rigid motions give zero internal force and zero strain energy, deformations do not",
          "[problems][block-2d]") {
  for (const char* material : kMaterials) {
    SECTION(material) {
      const auto b = block({{"material", material}});
      const double E = 1e6, H = 0.5, area = 0.5;
      nsb::Vec f(b.ndof());
      // Rounding: F = I + U grad N carries |U| |grad N| eps_mach ~ 1 m * 10/m * 1e-16 = 1e-15
      // of strain, i.e. stresses ~ E 1e-15 and forces ~ E H 1e-15. 1e-12 E H (= 5e-7 N)
      // resolves a strain of 1e-12; the deformed state below has strains of 1e-2. The energy:
      // SVK is quadratic in E (rounding squared), but the neo-Hookean form mu/2 (tr C - 2) -
      // mu ln J cancels terms linear in C - I, so rounding enters at first order, ~ E 1e-15
      // per unit area: 1e-12 E area for both.
      for (double angle : {0.3, 2.0, -1.1}) {
        const nsb::Vec u = rigidly_moved(b, nsb::Vec::Zero(b.ndof()), angle, {0.7, -0.2});
        b.internal_force(u, f);
        CHECK(f.cwiseAbs().maxCoeff() <= 1e-12 * E * H);
        CHECK(std::abs(b.strain_energy(u)) <= 1e-12 * E * area);
      }
      const nsb::Vec u = deformed(b, 0.0, 4);
      b.internal_force(u, f);
      CHECK(f.cwiseAbs().maxCoeff() > 1e-4 * E * H);
      CHECK(b.strain_energy(u) > 1e-6 * E * area);

      // Objectivity: the forces of a rotated deformed state are the rotated forces.
      const double angle = 0.9;
      const Eigen::Matrix2d R = Eigen::Rotation2Dd(angle).toRotationMatrix();
      nsb::Vec fr(b.ndof());
      b.internal_force(rigidly_moved(b, u, angle, {-0.3, 1.0}), fr);
      double worst = 0.0;
      for (nsb::Index a = 0; a < b.nodes(); ++a)
        worst = std::max(worst, (fr.segment<2>(2 * a) - R * f.segment<2>(2 * a)).cwiseAbs().maxCoeff());
      CHECK(worst <= 1e-10 * f.cwiseAbs().maxCoeff());
      CHECK(b.strain_energy(rigidly_moved(b, u, angle, {-0.3, 1.0})) == Approx(b.strain_energy(u)).epsilon(1e-10));
    }
  }
}

TEST_CASE("block-2d: internal forces have no net force and no net torque", "[problems][block-2d]") {
  for (const char* material : kMaterials) {
    SECTION(material) {
      const auto b = block({{"material", material}});
      const nsb::Vec u = deformed(b, 4e-3, 5);
      nsb::Vec f(b.ndof());
      b.internal_force(u, f);
      Eigen::Vector2d net = Eigen::Vector2d::Zero();
      double torque = 0.0, scale = 0.0;
      for (nsb::Index a = 0; a < b.nodes(); ++a) {
        const Eigen::Vector2d x = b.reference_position(a) + u.segment<2>(2 * a);
        net += f.segment<2>(2 * a);
        torque += x.x() * f[2 * a + 1] - x.y() * f[2 * a];
        scale += x.norm() * f.segment<2>(2 * a).norm();
      }
      // Sums of O(n) terms of size |f|: a few hundred eps_mach of the sum of magnitudes.
      CHECK(net.norm() <= 1e-13 * scale);
      CHECK(std::abs(torque) <= 1e-13 * scale);
    }
  }
}

TEST_CASE("block-2d: lumped mass, one contact per boundary node, diagonal Delassus operator",
          "[problems][block-2d]") {
  const auto b = block({{"nx", "6"}, {"ny", "3"}});
  CHECK(b.lumped_mass().sum() == Approx(2 * 1000.0 * 1.0 * 0.5).epsilon(1e-13));
  CHECK(b.ncontacts() == 2 * (6 + 3));
  const nsb::SpMat Hd = b.gap_operator() * b.lumped_mass().cwiseInverse().asDiagonal() * b.gap_operator().transpose();
  CHECK(Hd.nonZeros() == b.ncontacts());
  // Gaps start at the nodes' heights; the lowest corner at `height`.
  CHECK(b.gap_offset().minCoeff() == Approx(0.1).epsilon(1e-14));
  // Initial velocity: translation plus spin about the centre.
  const auto s = block({{"vx", "0.5"}, {"vy", "-1"}, {"spin", "2"}, {"tilt", "0"}}).initial_state();
  const auto bs = block({{"vx", "0.5"}, {"vy", "-1"}, {"spin", "2"}, {"tilt", "0"}});
  const Eigen::Vector2d p = bs.linear_momentum(s.v);
  CHECK(p.x() == Approx(0.5 * 500.0).epsilon(1e-13));
  CHECK(p.y() == Approx(-1.0 * 500.0).epsilon(1e-13));
  // J about the origin = J about the centre (I omega, lumped) + centre x M v; centre at (0, 0.35).
  double I = 0.0;
  for (nsb::Index a = 0; a < bs.nodes(); ++a)
    I += bs.lumped_mass()[2 * a] * (bs.reference_position(a) - Eigen::Vector2d(0.0, 0.35)).squaredNorm();
  CHECK(bs.angular_momentum(s.u, s.v) == Approx(2.0 * I - 0.35 * 0.5 * 500.0).epsilon(1e-12));
}

TEST_CASE("block-2d: the element bound gives a stable step below the true central-difference limit",
          "[problems][block-2d]") {
  const auto b = block({{"nx", "6"}, {"ny", "3"}});
  nsb::SpMat K;
  b.tangent_stiffness(nsb::Vec::Zero(b.ndof()), K);
  const nsb::Vec s = b.lumped_mass().cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd A = s.asDiagonal() * Eigen::MatrixXd(K) * s.asDiagonal();
  const double omega_max = std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A).eigenvalues().maxCoeff());
  const double exact_limit = 2.0 / omega_max;
  CHECK(b.stable_step() <= exact_limit);
  CHECK(b.stable_step() >= 0.5 * exact_limit);  // and not uselessly pessimistic
}

TEST_CASE("block-2d: bad parameters name the parameter and its range", "[problems][block-2d]") {
  CHECK_THROWS_WITH(block({{"nu", "0.5"}}), Catch::Contains("nu") && Catch::Contains("[0, 0.5)"));
  CHECK_THROWS_WITH(block({{"nx", "0"}}), Catch::Contains("nx"));
  CHECK_THROWS_WITH(block({{"material", "rubber"}}), Catch::Contains("material"));
}

TEST_CASE("block-2d: field mesh and Cauchy cell stress (rotation, finite stretch, linearised limit)",
          "[problems][block-2d][field-mesh]") {
  const double E = 1e6, nu = 0.3, lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  for (const char* material : kMaterials) {
    INFO(material);
    const auto b = block({{"material", material}, {"nx", "4"}, {"ny", "3"}, {"tilt", "20"}});
    const auto mesh = b.field_mesh();
    REQUIRE(mesh.has_value());
    REQUIRE(mesh->npoints() == b.nodes());
    REQUIRE(mesh->ncells() == 12);
    for (nsb::Index a = 0; a < b.nodes(); ++a) {
      CHECK(mesh->points.row(a).transpose() == b.reference_position(a));
      CHECK(mesh->point_dofs(a, 0) == 2 * a);
      CHECK(mesh->point_dofs(a, 1) == 2 * a + 1);
    }
    // u = G X (a uniform displacement gradient G), X from the mesh's own points.
    const auto uniform = [&](const Eigen::Matrix2d& G) {
      nsb::Vec u(b.ndof());
      for (nsb::Index a = 0; a < b.nodes(); ++a) u.segment<2>(2 * a) = G * mesh->points.row(a).transpose();
      return u;
    };
    Eigen::MatrixXd sigma(12, 3);
    // A rigid rotation: no stress (Cauchy and PK2 alike).
    b.cell_stress(uniform(Eigen::Rotation2Dd(0.7).toRotationMatrix() - Eigen::Matrix2d::Identity()), sigma);
    CHECK(sigma.cwiseAbs().maxCoeff() <= 1e-9 * E);
    // A small strain eps: sigma = lambda tr(eps) I + 2 mu eps + O(|eps|^2).
    for (const double scale : {1e-3, 1e-4}) {
      Eigen::Matrix2d G;
      G << 0.7, 0.4, -0.2, -0.5;
      G *= scale;
      const Eigen::Matrix2d eps = 0.5 * (G + G.transpose());
      const Eigen::Matrix2d lin = lambda * eps.trace() * Eigen::Matrix2d::Identity() + 2 * mu * eps;
      b.cell_stress(uniform(G), sigma);
      for (nsb::Index e = 0; e < 12; ++e) {
        CHECK(std::abs(sigma(e, 0) - lin(0, 0)) <= 5 * E * scale * scale);
        CHECK(std::abs(sigma(e, 1) - lin(1, 1)) <= 5 * E * scale * scale);
        CHECK(std::abs(sigma(e, 2) - lin(0, 1)) <= 5 * E * scale * scale);
      }
      CHECK(std::abs(sigma(0, 0) - lin(0, 0)) >= 1e-3 * E * scale * scale);  // not the linear law itself
    }
  }
  // A finite stretch F = diag(1 + a, 1) of the untilted SVK block, Cauchy sigma = F S F^T / J:
  //     S_11 = (lambda + 2 mu) E_11, S_22 = lambda E_11, E_11 = a + a^2/2;
  //     sigma_xx = (1 + a) S_11, sigma_yy = S_22 / (1 + a), sigma_xy = 0.
  const auto b = block({{"tilt", "0"}, {"nx", "3"}, {"ny", "2"}});
  const double a = 0.2, E11 = a + 0.5 * a * a;
  nsb::Vec u = nsb::Vec::Zero(b.ndof());
  for (nsb::Index n = 0; n < b.nodes(); ++n) u[2 * n] = a * b.reference_position(n).x();
  Eigen::MatrixXd sigma(6, 3);
  b.cell_stress(u, sigma);
  for (nsb::Index e = 0; e < 6; ++e) {
    CHECK(sigma(e, 0) == Approx((1 + a) * (lambda + 2 * mu) * E11).epsilon(1e-12));
    CHECK(sigma(e, 1) == Approx(lambda * E11 / (1 + a)).epsilon(1e-12));
    CHECK(std::abs(sigma(e, 2)) <= 1e-12 * E);
  }
}
