#pragma once
// The trilinear hexahedron (hex8) for hyperelastic solids in 3D: one element's strain energy,
// internal force, tangent stiffness and mass from its 8 node positions (derivations in
// docs/three_d.md; the 3D form of block_2d's Q4 element).
//
// Nodes in the parent cube [-1, 1]^3, numbered (-,-,-), (+,-,-), (+,+,-), (-,+,-), then the same
// at zeta = +1; N_a = (1 + xi xi_a)(1 + eta eta_a)(1 + zeta zeta_a) / 8. Total Lagrangian: the
// reference positions X (3 x 8, one column per node) fix, at each of the 2x2x2 Gauss points
// (+-1/sqrt(3), weights 1), grad_X N_a = J0^{-T} dN_a/dxi and w j = det J0 (J0 = dX/dxi > 0);
// the current positions x give
//     F = sum_a x_a (grad_X N_a)^T,   C = F^T F,   E = (C - I) / 2,   J = det F.
// Energy per unit reference volume (lambda, mu the Lamé constants):
//     Saint Venant–Kirchhoff   W = lambda/2 (tr E)^2 + mu E:E,      S = lambda tr(E) I + 2 mu E
//     neo-Hookean (compressible, Ciarlet's / Simo's form)
//                              W = mu/2 (tr C - 3) - mu ln J + lambda/2 (ln J)^2,
//                              S = mu (I - C^{-1}) + lambda ln J C^{-1}
// (both with the linear elastic limit at F = I; the neo-Hookean energy is infinite as J -> 0+,
// undefined for J <= 0: std::runtime_error). Then, summed over the Gauss points,
//     energy = sum w j W,   f_a = sum w j F S grad_X N_a   (f = dEnergy/dx, the internal force),
//     K = df/dx = sum w j (B^T D B + (grad N_a . S grad N_b) I_3),
// B the 6 x 24 Green strain-displacement matrix (Voigt order 11, 22, 33, 23, 13, 12, shear
// engineering), D = dS/dE: D_IJKL = lambda A_IJ A_KL + m (A_IK A_JL + A_IL A_JK) with A = I,
// m = mu (SVK) or A = C^{-1}, m = mu - lambda ln J (neo-Hookean).
// W depends on x only through C: a rigid motion x = Q X + c gives zero energy and force.
// Mass (density rho): consistent M_ab = rho sum w j N_a N_b (per direction; exact on a
// parallelepiped), lumped m_a = sum_b M_ab (row sums, summing to rho times the volume,
// sum w j, exact for any hex8).
// Fixed-size Eigen throughout; no allocation.
//
// Bad input (InputError, one line): E not > 0, nu outside [0, 0.5), rho not > 0;
// std::invalid_argument for reference nodes with det J0 <= 0 at a Gauss point.
#include <Eigen/Core>

namespace nsb {

using Hex8Nodes = Eigen::Matrix<double, 3, 8>;     // one column per node
using Hex8Vector = Eigen::Matrix<double, 24, 1>;   // node-major: (x_1, y_1, z_1, x_2, ...)
using Hex8Matrix = Eigen::Matrix<double, 24, 24>;

enum class Hex8Law { svk, neo_hookean };

struct Hex8Material {
  Hex8Law law = Hex8Law::svk;
  double lambda = 0.0, mu = 0.0;
  // From Young's modulus and Poisson's ratio (InputError on E <= 0 or nu outside [0, 0.5)).
  static Hex8Material from_young(Hex8Law law, double E, double nu);
};

// Second Piola–Kirchhoff stress S and energy density W (returned) at the deformation gradient F;
// D = dS/dE (Voigt) when D is not null. std::runtime_error for J <= 0 in the neo-Hookean law.
double hex8_material_response(const Eigen::Matrix3d& F, const Hex8Material& material, Eigen::Matrix3d& S,
                              Eigen::Matrix<double, 6, 6>* D);

class Hex8Element {
 public:
  explicit Hex8Element(const Hex8Nodes& reference);  // std::invalid_argument if inverted

  double volume() const;
  double energy(const Hex8Nodes& x, const Hex8Material& material) const;
  void internal_force(const Hex8Nodes& x, const Hex8Material& material, Hex8Vector& f) const;
  void tangent(const Hex8Nodes& x, const Hex8Material& material, Hex8Matrix& K) const;
  void consistent_mass(double rho, Eigen::Matrix<double, 8, 8>& M) const;  // per direction
  void lumped_mass(double rho, Eigen::Matrix<double, 8, 1>& m) const;

 private:
  struct Gauss {
    Eigen::Matrix<double, 8, 3> dN;  // grad_X N_a, one row per node
    Eigen::Matrix<double, 8, 1> N;
    double wj = 0.0;
  };
  Gauss gauss_[8];
};

}  // namespace nsb
