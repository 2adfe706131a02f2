#include "problems/block_2d.hpp"
#include "problems/registry.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace nsb {

namespace {
// Q4 node coordinates in the parent square and the 2x2 Gauss abscissae.
constexpr double kXi[4] = {-1.0, 1.0, 1.0, -1.0};
constexpr double kEta[4] = {-1.0, -1.0, 1.0, 1.0};
const double kGp = 1.0 / std::sqrt(3.0);
// Voigt index pairs (11, 22, 12).
constexpr int kI[3] = {0, 1, 0};
constexpr int kJ[3] = {0, 1, 1};
}  // namespace

ParamSpecs Block2d::parameters_spec() {
  return {
      ParamSpec::real("W", 1.0, 0.0, 1e308, "block width [m]", true),
      ParamSpec::real("H", 0.5, 0.0, 1e308, "block height [m]", true),
      ParamSpec::integer("nx", 8, 1, 1024, "elements along the width"),
      ParamSpec::integer("ny", 4, 1, 1024, "elements along the height"),
      ParamSpec::real("E", 1e6, 0.0, 1e308, "Young's modulus [Pa]", true),
      ParamSpec::real("nu", 0.3, 0.0, 0.5, "Poisson's ratio", false, true),
      ParamSpec::real("rho", 1000.0, 0.0, 1e308, "density [kg/m^3]", true),
      ParamSpec::choice("material", "svk", {"svk", "neo-hookean"}, "hyperelastic law"),
      ParamSpec::real("height", 0.1, 0.0, 1e308, "initial height of the lowest corner [m]"),
      ParamSpec::real("tilt", 15.0, -90.0, 90.0, "initial tilt, counter-clockwise [deg]"),
      ParamSpec::real("vx", 0.0, -1e308, 1e308, "initial horizontal velocity [m/s]"),
      ParamSpec::real("vy", -1.0, -1e308, 1e308, "initial vertical velocity, positive upwards [m/s]"),
      ParamSpec::real("spin", 0.0, -1e308, 1e308, "initial angular velocity about the centre [rad/s]"),
      ParamSpec::real("g", 9.81, 0.0, 1e308, "gravity [m/s^2] (0: off)"),
      ParamSpec::real("e", 0.0, 0.0, 1.0, "Newton restitution coefficient"),
  };
}

Block2d::Block2d(const Params& p)
    : params_(p),
      nx_(p.integer("nx")),
      ny_(p.integer("ny")),
      rho_(p.real("rho")),
      g_(p.real("g")),
      e_(p.real("e")),
      neo_hookean_(p.choice("material") == "neo-hookean"),
      v0_(p.real("vx"), p.real("vy")),
      spin_(p.real("spin")) {
  const double E = p.real("E"), nu = p.real("nu"), W = p.real("W"), H = p.real("H");
  lambda_ = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));  // plane strain uses the 3D Lame constants
  mu_ = E / (2.0 * (1.0 + nu));

  // Reference configuration: the rectangle rotated by the tilt about its centre, centred
  // on x = 0, lowest corner at `height`.
  const double a = p.real("tilt") * std::numbers::pi / 180.0;
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(a).toRotationMatrix();
  X_.resize(2, nodes());
  for (Index j = 0; j <= ny_; ++j)
    for (Index i = 0; i <= nx_; ++i)
      X_.col(i + (nx_ + 1) * j) = R * Eigen::Vector2d(W * (double(i) / nx_ - 0.5), H * (double(j) / ny_ - 0.5));
  const double lift = p.real("height") - X_.row(1).minCoeff();
  X_.row(1).array() += lift;
  centre_ = Eigen::Vector2d(0.0, lift);

  // Elements, Gauss data, lumped mass.
  const Index ne = nx_ * ny_;
  conn_.resize(ne);
  gauss_.resize(4 * ne);
  m_ = Vec::Zero(ndof());
  for (Index j = 0; j < ny_; ++j)
    for (Index i = 0; i < nx_; ++i) {
      const Index e = i + nx_ * j, n0 = i + (nx_ + 1) * j;
      conn_[e] = {n0, n0 + 1, n0 + nx_ + 2, n0 + nx_ + 1};
      Eigen::Matrix<double, 2, 4> Xe;
      for (int k = 0; k < 4; ++k) Xe.col(k) = X_.col(conn_[e][k]);
      for (int q = 0; q < 4; ++q) {
        const double xi = kXi[q] * kGp, eta = kEta[q] * kGp;
        Mat42 dxi;
        Eigen::Vector4d N;
        for (int k = 0; k < 4; ++k) {
          N[k] = 0.25 * (1 + kXi[k] * xi) * (1 + kEta[k] * eta);
          dxi(k, 0) = 0.25 * kXi[k] * (1 + kEta[k] * eta);
          dxi(k, 1) = 0.25 * kEta[k] * (1 + kXi[k] * xi);
        }
        const Eigen::Matrix2d Jac = Xe * dxi;  // dX/dxi
        Gauss& G = gauss_[4 * e + q];
        G.dN = dxi * Jac.inverse();
        G.wj = Jac.determinant();
        for (int k = 0; k < 4; ++k) m_.segment<2>(2 * conn_[e][k]).array() += rho_ * G.wj * N[k];
      }
    }

  // Sparsity pattern of K and, per element, the position of each entry in K's values.
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(64 * ne);
  for (Index e = 0; e < ne; ++e)
    for (int r = 0; r < 8; ++r)
      for (int c = 0; c < 8; ++c) triplets.emplace_back(2 * conn_[e][r / 2] + r % 2, 2 * conn_[e][c / 2] + c % 2, 0.0);
  pattern_.resize(ndof(), ndof());
  pattern_.setFromTriplets(triplets.begin(), triplets.end());
  pattern_.makeCompressed();
  slot_.resize(ne);
  for (Index e = 0; e < ne; ++e)
    for (int r = 0; r < 8; ++r)
      for (int c = 0; c < 8; ++c) {
        const Index row = 2 * conn_[e][r / 2] + r % 2, col = 2 * conn_[e][c / 2] + c % 2;
        const auto* begin = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[col];
        const auto* end = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[col + 1];
        slot_[e][8 * r + c] = std::lower_bound(begin, end, row) - pattern_.innerIndexPtr();
      }

  // Contacts: every boundary node, on its y dof.
  for (Index j = 0; j <= ny_; ++j)
    for (Index i = 0; i <= nx_; ++i)
      if (i == 0 || i == nx_ || j == 0 || j == ny_) boundary_.push_back(i + (nx_ + 1) * j);
  L_.resize(static_cast<Index>(boundary_.size()), ndof());
  g0_.resize(L_.rows());
  for (Index r = 0; r < L_.rows(); ++r) {
    L_.insert(r, 2 * boundary_[r] + 1) = 1.0;
    g0_[r] = X_(1, boundary_[r]);
  }
  L_.makeCompressed();

  // Element eigenvalue bound at U = 0: omega_max^2 <= max_e lambda_max(M_e^{-1/2} K_e M_e^{-1/2}).
  double w2 = 0.0;
  const Vec u0 = Vec::Zero(ndof());
  Mat8 Ke;
  for (Index e = 0; e < ne; ++e) {
    element_tangent(e, u0, Ke);
    Eigen::Matrix<double, 8, 1> s;
    for (int r = 0; r < 8; ++r) {
      double me = 0.0;
      for (int q = 0; q < 4; ++q) {
        const Gauss& G = gauss_[4 * e + q];
        const double xi = kXi[q] * kGp, eta = kEta[q] * kGp;
        me += rho_ * G.wj * 0.25 * (1 + kXi[r / 2] * xi) * (1 + kEta[r / 2] * eta);
      }
      s[r] = 1.0 / std::sqrt(me);
    }
    const Mat8 A = s.asDiagonal() * Ke * s.asDiagonal();
    w2 = std::max(w2, Eigen::SelfAdjointEigenSolver<Mat8>(A, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff());
  }
  stable_step_ = 2.0 / std::sqrt(w2);
}

double Block2d::material(const Eigen::Matrix2d& F, Eigen::Vector3d& S, Eigen::Matrix3d* D) const {
  const Eigen::Matrix2d C = F.transpose() * F;
  Eigen::Matrix2d A, Sm;
  double m, W;
  if (neo_hookean_) {
    const double J = F.determinant();
    if (!(J > 0.0)) throw std::runtime_error("block-2d: inverted element (det F <= 0) in the neo-Hookean law");
    const double lnJ = std::log(J);
    A = C.inverse();
    Sm = mu_ * (Eigen::Matrix2d::Identity() - A) + lambda_ * lnJ * A;
    m = mu_ - lambda_ * lnJ;
    W = 0.5 * mu_ * (C.trace() - 2.0) - mu_ * lnJ + 0.5 * lambda_ * lnJ * lnJ;
  } else {
    const Eigen::Matrix2d E = 0.5 * (C - Eigen::Matrix2d::Identity());
    const double trE = E.trace();
    A.setIdentity();
    Sm = lambda_ * trE * A + 2.0 * mu_ * E;
    m = mu_;
    W = 0.5 * lambda_ * trE * trE + mu_ * E.squaredNorm();
  }
  S << Sm(0, 0), Sm(1, 1), Sm(0, 1);
  if (D)
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q)
        (*D)(p, q) = lambda_ * A(kI[p], kJ[p]) * A(kI[q], kJ[q]) +
                     m * (A(kI[p], kI[q]) * A(kJ[p], kJ[q]) + A(kI[p], kJ[q]) * A(kJ[p], kI[q]));
  return W;
}

Eigen::Matrix<double, 8, 1> Block2d::element_dofs(Index e, ConstVecRef u) const {
  Eigen::Matrix<double, 8, 1> ue;
  for (int k = 0; k < 4; ++k) ue.segment<2>(2 * k) = u.segment<2>(2 * conn_[e][k]);
  return ue;
}

namespace {
// F = I + U_e grad N, and B with delta E (Voigt, engineering shear) = B delta u_e.
template <class Mat42>
void kinematics(const Eigen::Matrix<double, 8, 1>& ue, const Mat42& dN, Eigen::Matrix2d& F,
                Eigen::Matrix<double, 3, 8>& B) {
  F = Eigen::Matrix2d::Identity() + Eigen::Map<const Eigen::Matrix<double, 2, 4>>(ue.data()) * dN;
  for (int a = 0; a < 4; ++a)
    for (int k = 0; k < 2; ++k) {
      B(0, 2 * a + k) = F(k, 0) * dN(a, 0);
      B(1, 2 * a + k) = F(k, 1) * dN(a, 1);
      B(2, 2 * a + k) = F(k, 0) * dN(a, 1) + F(k, 1) * dN(a, 0);
    }
}
}  // namespace

void Block2d::internal_force(ConstVecRef u, VecRef f) const {
  f.setZero();
  Eigen::Matrix2d F;
  Eigen::Matrix<double, 3, 8> B;
  Eigen::Vector3d S;
  for (Index e = 0; e < static_cast<Index>(conn_.size()); ++e) {
    const auto ue = element_dofs(e, u);
    Eigen::Matrix<double, 8, 1> fe = Eigen::Matrix<double, 8, 1>::Zero();
    for (int q = 0; q < 4; ++q) {
      const Gauss& G = gauss_[4 * e + q];
      kinematics(ue, G.dN, F, B);
      material(F, S, nullptr);
      fe.noalias() += G.wj * B.transpose() * S;
    }
    for (int k = 0; k < 4; ++k) f.segment<2>(2 * conn_[e][k]) += fe.segment<2>(2 * k);
  }
}

void Block2d::element_tangent(Index e, ConstVecRef u, Mat8& Ke) const {
  const auto ue = element_dofs(e, u);
  Eigen::Matrix2d F;
  Eigen::Matrix<double, 3, 8> B;
  Eigen::Vector3d S;
  Eigen::Matrix3d D;
  Ke.setZero();
  for (int q = 0; q < 4; ++q) {
    const Gauss& G = gauss_[4 * e + q];
    kinematics(ue, G.dN, F, B);
    material(F, S, &D);
    Ke.noalias() += G.wj * B.transpose() * D * B;
    Eigen::Matrix2d Sm;
    Sm << S[0], S[2], S[2], S[1];
    const Eigen::Matrix4d geo = G.wj * G.dN * Sm * G.dN.transpose();  // grad N_a . S grad N_b
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        Ke(2 * a, 2 * b) += geo(a, b);
        Ke(2 * a + 1, 2 * b + 1) += geo(a, b);
      }
  }
}

void Block2d::tangent_stiffness(ConstVecRef u, SpMat& K) const {
  const bool same_pattern =
      K.rows() == pattern_.rows() && K.cols() == pattern_.cols() && K.isCompressed() &&
      K.nonZeros() == pattern_.nonZeros() &&
      std::equal(K.outerIndexPtr(), K.outerIndexPtr() + K.cols() + 1, pattern_.outerIndexPtr()) &&
      std::equal(K.innerIndexPtr(), K.innerIndexPtr() + K.nonZeros(), pattern_.innerIndexPtr());
  if (same_pattern)
    K.coeffs().setZero();
  else
    K = pattern_;
  Mat8 Ke;
  double* values = K.valuePtr();
  for (Index e = 0; e < static_cast<Index>(conn_.size()); ++e) {
    element_tangent(e, u, Ke);
    for (int r = 0; r < 8; ++r)
      for (int c = 0; c < 8; ++c) values[slot_[e][8 * r + c]] += Ke(r, c);
  }
}

double Block2d::strain_energy(ConstVecRef u) const {
  double W = 0.0;
  Eigen::Matrix2d F;
  Eigen::Matrix<double, 3, 8> B;
  Eigen::Vector3d S;
  for (Index e = 0; e < static_cast<Index>(conn_.size()); ++e) {
    const auto ue = element_dofs(e, u);
    for (int q = 0; q < 4; ++q) {
      const Gauss& G = gauss_[4 * e + q];
      kinematics(ue, G.dN, F, B);
      W += G.wj * material(F, S, nullptr);
    }
  }
  return W;
}

SpMat Block2d::mass_matrix() const {
  SpMat M(ndof(), ndof());
  M.reserve(Eigen::VectorXi::Ones(ndof()));
  for (Index i = 0; i < ndof(); ++i) M.insert(i, i) = m_[i];
  M.makeCompressed();
  return M;
}

void Block2d::external_force(double, VecRef f) const {
  f.setZero();
  for (Index a = 0; a < nodes(); ++a) f[2 * a + 1] = -m_[2 * a + 1] * g_;
}

double Block2d::load_potential(ConstVecRef u) const {
  double V = 0.0;
  for (Index a = 0; a < nodes(); ++a) V += m_[2 * a + 1] * g_ * (X_(1, a) + u[2 * a + 1]);
  return V;
}

State Block2d::initial_state() const {
  State s;
  s.u = Vec::Zero(ndof());
  s.v.resize(ndof());
  for (Index a = 0; a < nodes(); ++a) {
    const Eigen::Vector2d r = X_.col(a) - centre_;
    s.v.segment<2>(2 * a) = v0_ + spin_ * Eigen::Vector2d(-r.y(), r.x());
  }
  return s;
}

Eigen::Vector2d Block2d::linear_momentum(ConstVecRef v) const {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  for (Index a = 0; a < nodes(); ++a) p += m_[2 * a] * v.segment<2>(2 * a);
  return p;
}

double Block2d::angular_momentum(ConstVecRef u, ConstVecRef v) const {
  double J = 0.0;
  for (Index a = 0; a < nodes(); ++a) {
    const double x = X_(0, a) + u[2 * a], y = X_(1, a) + u[2 * a + 1];
    J += m_[2 * a] * (x * v[2 * a + 1] - y * v[2 * a]);
  }
  return J;
}

std::vector<std::string> Block2d::observable_names() const {
  return {"strain_energy", "gravity_energy", "px", "py", "angular_momentum", "closed_contacts"};
}

void Block2d::observe(const State& s, std::span<double> out) const {
  const Eigen::Vector2d p = linear_momentum(s.v);
  long closed = 0;
  for (Index r = 0; r < L_.rows(); ++r) closed += (g0_[r] + s.u[2 * boundary_[r] + 1] <= 0.0);
  out[0] = strain_energy(s.u);
  out[1] = load_potential(s.u);
  out[2] = p.x();
  out[3] = p.y();
  out[4] = angular_momentum(s.u, s.v);
  out[5] = static_cast<double>(closed);
}

NSBENCH_PROBLEM({"block-2d", "hyperelastic Q4 block (plane strain) dropped tilted on a rigid frictionless floor", &Block2d::parameters_spec, &make_from_params<Problem, Block2d>});

}  // namespace nsb
