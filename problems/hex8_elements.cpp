#include "problems/hex8_elements.hpp"
#include "core/deterministic_math.hpp"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

#include "problems/input_check.hpp"

namespace nsb {

namespace {

constexpr int kCorner[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                               {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
// Voigt order of the symmetric index pairs (engineering shear).
constexpr int kVoigtI[6] = {0, 1, 2, 1, 0, 0};
constexpr int kVoigtJ[6] = {0, 1, 2, 2, 2, 1};

}  // namespace

double hex8_material_response(const Eigen::Matrix3d& F, const Hex8Material& mat, Eigen::Matrix3d& S,
                         Eigen::Matrix<double, 6, 6>* D) {
  const Eigen::Matrix3d C = F.transpose() * F;
  Eigen::Matrix3d A;
  double m, W;
  if (mat.law == Hex8Law::neo_hookean) {
    const double J = F.determinant();
    if (!(J > 0.0)) throw std::runtime_error("hex8: inverted element (det F <= 0) in the neo-Hookean law");
    const double lnJ = nsb::dmath::log(J);
    A = C.inverse();
    S = mat.mu * (Eigen::Matrix3d::Identity() - A) + mat.lambda * lnJ * A;
    m = mat.mu - mat.lambda * lnJ;
    W = 0.5 * mat.mu * (C.trace() - 3.0) - mat.mu * lnJ + 0.5 * mat.lambda * lnJ * lnJ;
  } else {
    const Eigen::Matrix3d E = 0.5 * (C - Eigen::Matrix3d::Identity());
    const double trE = E.trace();
    A.setIdentity();
    S = mat.lambda * trE * A + 2.0 * mat.mu * E;
    m = mat.mu;
    W = 0.5 * mat.lambda * trE * trE + mat.mu * E.squaredNorm();
  }
  if (D)
    for (int p = 0; p < 6; ++p)
      for (int q = 0; q < 6; ++q)
        (*D)(p, q) = mat.lambda * A(kVoigtI[p], kVoigtJ[p]) * A(kVoigtI[q], kVoigtJ[q]) +
                     m * (A(kVoigtI[p], kVoigtI[q]) * A(kVoigtJ[p], kVoigtJ[q]) + A(kVoigtI[p], kVoigtJ[q]) * A(kVoigtJ[p], kVoigtI[q]));
  return W;
}

Hex8Material Hex8Material::from_young(Hex8Law law, double E, double nu) {
  require_input(E > 0.0 && std::isfinite(E), "hex8", "E", E, "(0, inf)");
  require_input(nu >= 0.0 && nu < 0.5, "hex8", "nu", nu, "[0, 0.5)");
  return {law, E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))};
}

Hex8Element::Hex8Element(const Hex8Nodes& reference) {
  const double g = 1.0 / std::sqrt(3.0);
  for (int q = 0; q < 8; ++q) {
    const double xi[3] = {kCorner[q][0] * g, kCorner[q][1] * g, kCorner[q][2] * g};
    Eigen::Matrix<double, 8, 3> dxi;  // dN_a / dxi_j
    Gauss& G = gauss_[q];
    for (int a = 0; a < 8; ++a) {
      double f[3];
      for (int j = 0; j < 3; ++j) f[j] = 1.0 + xi[j] * kCorner[a][j];
      G.N(a) = f[0] * f[1] * f[2] / 8.0;
      dxi(a, 0) = kCorner[a][0] * f[1] * f[2] / 8.0;
      dxi(a, 1) = f[0] * kCorner[a][1] * f[2] / 8.0;
      dxi(a, 2) = f[0] * f[1] * kCorner[a][2] / 8.0;
    }
    const Eigen::Matrix3d J0 = reference * dxi;  // dX_i / dxi_j
    G.wj = J0.determinant();
    if (!(G.wj > 0.0)) throw std::invalid_argument("hex8: reference element inverted or degenerate (det J0 <= 0)");
    G.dN = dxi * J0.inverse();  // rows: (J0^{-T} dN/dxi)^T
  }
}

double Hex8Element::volume() const {
  double v = 0.0;
  for (const Gauss& G : gauss_) v += G.wj;
  return v;
}

double Hex8Element::energy(const Hex8Nodes& x, const Hex8Material& material) const {
  double total = 0.0;
  Eigen::Matrix3d S;
  for (const Gauss& G : gauss_) total += G.wj * hex8_material_response(x * G.dN, material, S, nullptr);
  return total;
}

void Hex8Element::internal_force(const Hex8Nodes& x, const Hex8Material& material, Hex8Vector& f) const {
  f.setZero();
  Eigen::Matrix3d S;
  for (const Gauss& G : gauss_) {
    const Eigen::Matrix3d F = x * G.dN;
    hex8_material_response(F, material, S, nullptr);
    const Eigen::Matrix<double, 3, 8> nodal = G.wj * (F * S) * G.dN.transpose();  // P grad N_a
    f += Eigen::Map<const Hex8Vector>(nodal.data());
  }
}

void Hex8Element::tangent(const Hex8Nodes& x, const Hex8Material& material, Hex8Matrix& K) const {
  K.setZero();
  Eigen::Matrix3d S;
  Eigen::Matrix<double, 6, 6> D;
  Eigen::Matrix<double, 6, 24> B;
  for (const Gauss& G : gauss_) {
    const Eigen::Matrix3d F = x * G.dN;
    hex8_material_response(F, material, S, &D);
    // dE_IJ (Voigt) = sym(F^T dF)_IJ, dF = sum_b dx_b grad N_b^T.
    for (int b = 0; b < 8; ++b)
      for (int i = 0; i < 3; ++i)
        for (int p = 0; p < 6; ++p) {
          const int I = kVoigtI[p], J = kVoigtJ[p];
          B(p, 3 * b + i) = I == J ? F(i, I) * G.dN(b, I) : F(i, I) * G.dN(b, J) + F(i, J) * G.dN(b, I);
        }
    K.noalias() += G.wj * B.transpose() * D * B;
    const Eigen::Matrix<double, 8, 8> geometric = G.wj * G.dN * S * G.dN.transpose();  // grad N_a . S grad N_b
    for (int a = 0; a < 8; ++a)
      for (int b = 0; b < 8; ++b)
        for (int i = 0; i < 3; ++i) K(3 * a + i, 3 * b + i) += geometric(a, b);
  }
}

void Hex8Element::consistent_mass(double rho, Eigen::Matrix<double, 8, 8>& M) const {
  require_input(rho > 0.0 && std::isfinite(rho), "hex8", "rho", rho, "(0, inf)");
  M.setZero();
  for (const Gauss& G : gauss_) M.noalias() += rho * G.wj * G.N * G.N.transpose();
}

void Hex8Element::lumped_mass(double rho, Eigen::Matrix<double, 8, 1>& m) const {
  Eigen::Matrix<double, 8, 8> M;
  consistent_mass(rho, M);
  m = M.rowwise().sum();
}

}  // namespace nsb
