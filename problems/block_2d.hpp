#pragma once
// 2D block impact: a hyperelastic block (plane strain, thickness 1 m) dropped, tilted and
// spinning, on a rigid floor y = 0, frictionless or with Coulomb friction mu (docs/method.md section 3; the benchmark family
// of J. Di Stasio, D. Dureisseix, A. Gravouil et al., "Benchmark cases for robust explicit
// time integrators in non-smooth transient dynamics", Advanced Modeling and Simulation in
// Engineering Sciences (AMSES), 2019).
//
// Kinematics, total Lagrangian. The reference configuration is the block as placed at
// t = 0 (tilted, lifted), so U(0) = 0 and node a sits at x_a = X_a + U_a. Bilinear Q4
// elements on a structured nx x ny mesh, 2x2 Gauss points, shape functions N_a(X):
//     F = I + sum_a U_a (grad_X N_a)^T,   C = F^T F,   E = (C - I) / 2,   J = det F
// Energy per unit reference area (plane strain: F_33 = 1, C_33 = 1):
//     Saint-Venant-Kirchhoff  W = lambda/2 (tr E)^2 + mu E:E,         S = lambda tr(E) I + 2 mu E
//     neo-Hookean (compr.)    W = mu/2 (tr C - 2) - mu ln J + lambda/2 (ln J)^2,
//                             S = mu (I - C^{-1}) + lambda ln J C^{-1}
// Both depend on U only through C, so a rigid motion gives W = 0 and F_int = 0 exactly
// (to round-off) and the internal forces have no net force or torque: the discrete
// linear and angular momenta are changed only by gravity and the floor.
//     F_int,a = sum_gp w_gp j_gp  F S grad_X N_a
//     K = sum_gp w_gp j_gp (B^T D B + (grad N_a . S grad N_b) I),   D = dS/dE (Voigt, engineering shear)
//     D_IJKL = lambda A_IJ A_KL + m (A_IK A_JL + A_IL A_JK)
//              SVK: A = I, m = mu;   neo-Hookean: A = C^{-1}, m = mu - lambda ln J
// K's pattern (node neighbours on the structured mesh) is built when K does not hold it yet;
// refilling it allocates nothing. The mesh is regular, so the Gauss data (grad_X N_a, w j)
// are computed once for all elements; the force kernel runs the four Gauss points as SIMD
// lanes and works with H = grad U (E = (H + H^T + H^T H) / 2, no cancellation of I).
// Threads (core/threads.hpp): element rows of one parity at a time, so no two rows in
// flight share a node: the sums into each node follow the mesh, not the thread count.
//
// Mass: lumped by row sums of the consistent mass, m_a = sum_e int rho N_a (diagonal, so
// CD-Lagrange's Delassus operator L M^{-1} L^T is diagonal: one contact per y dof).
// Gravity g (0: off) along -y: V_load = sum_a m_a g y_a, F_ext = -m_a g on the y dofs.
// Contact: every boundary node is a candidate, gap g_a = y_a = X_a,y + U_a,y >= 0 (one row
// of L per boundary node, on its y dof, g0 = X_a,y). Frictionless (mu = 0, the default):
// horizontal momentum P_x = sum m_a v_a,x is conserved exactly; Newton restitution e (0 by
// default, the usual choice for a deformable body: the rebound comes from the elastic
// energy). With mu > 0 each contact has the tangent row on its x dof, slip rate
// u_T = v_a,x - w (w = floor_velocity, a belt), and docs/method.md section 6's identities hold:
// P_x changes by sum Lambda_T exactly; while every closed contact slides the same way
// (u_T > 0, say) Delta P_x = -mu sum Lambda_N; the energy never increases (e <= 1, w = 0).
//
// Observables: strain and gravity energy, P_x, P_y, angular momentum about the origin
// J = sum_a m_a (x_a v_a,y - y_a v_a,x), contacts closed (g <= 0). The generic columns add
// kinetic and total energy, impulse sums and active contacts. J of CD-Lagrange's reported
// pair (U_{k+1}, P_{k+3/2}) is its exact discrete invariant in free flight (derivation in
// tests/integrators/block_momentum_test.cpp).
//
// Parameters: W, H (size [m]), nx, ny (elements), E [Pa], nu, rho [kg/m^3], material
// {svk, neo-hookean}, height (lowest corner above the floor [m]), tilt [deg, about the
// centre, counter-clockwise], vx, vy [m/s], spin [rad/s, about the centre], g [m/s^2], e,
// mu (>= 0), floor_velocity [m/s].
//
// Stable step: 2 / omega_max with omega_max^2 <= max_e lambda_max(M_e^{-1} K_e) (the
// element eigenvalue bound, Irons & Treharne 1971; Hughes, The Finite Element Method,
// 1987, sec. 9.3), K_e the tangent at U = 0. It bounds the undeformed system only:
// the SVK material stiffens in tension, so large strains lower the true limit.
#include <Eigen/Core>
#include <array>

#include "problems/problem.hpp"

namespace nsb {

class Block2d final : public Problem {
 public:
  explicit Block2d(const Params& params);
  static ParamSpecs parameters_spec();

  std::string name() const override { return "block-2d"; }
  const Params& parameters() const override { return params_; }
  Index ndof() const override { return 2 * nodes(); }
  SpMat mass_matrix() const override;
  void internal_force(ConstVecRef u, VecRef f) const override;
  void tangent_stiffness(ConstVecRef u, SpMat& K) const override;
  bool is_linear() const override { return false; }
  void external_force(double t, VecRef f) const override;
  double strain_energy(ConstVecRef u) const override;
  double load_potential(ConstVecRef u) const override;
  const Contacts& contacts() const override { return contacts_; }
  State initial_state() const override;
  double stable_step() const override { return stable_step_; }
  std::vector<std::string> observable_names() const override;
  void observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const override;
  // Field output: the nodes at their reference positions (node a on dofs 2a, 2a + 1), the
  // Q4 elements counter-clockwise; stress: the Cauchy stress sigma = F S F^T / J (plane
  // strain, in-plane components xx, yy, xy) averaged over the element's 2x2 Gauss points.
  std::optional<FieldMesh> field_mesh() const override;
  void cell_stress(ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> out) const override;

  Index nodes() const { return (nx_ + 1) * (ny_ + 1); }
  const Vec& lumped_mass() const { return m_; }
  // Reference (t = 0) position of node a.
  Eigen::Vector2d reference_position(Index a) const { return X_.col(a); }
  // Linear momentum (x, y) and angular momentum about the origin of a state (u, v).
  Eigen::Vector2d linear_momentum(ConstVecRef v) const;
  double angular_momentum(ConstVecRef u, ConstVecRef v) const;

 private:
  using Mat42 = Eigen::Matrix<double, 4, 2>;
  using Mat8 = Eigen::Matrix<double, 8, 8>;
  struct Gauss {
    Mat42 dN;   // grad_X N_a at the Gauss point, one row per element node
    double wj;  // Gauss weight times det dX/dxi
  };
  // Second Piola-Kirchhoff stress (Voigt 11, 22, 12), energy density and D = dS/dE at C.
  double material(const Eigen::Matrix2d& F, Eigen::Vector3d& S, Eigen::Matrix3d* D) const;
  void element_tangent(Index e, ConstVecRef u, Mat8& Ke) const;
  // Nodes of element e, counter-clockwise from its lower-left corner.
  std::array<Index, 4> element_nodes(Index e) const;
  Eigen::Matrix<double, 8, 1> element_dofs(Index e, ConstVecRef u) const;
  // F_int of element row j added into f; false when an element inverted (neo-Hookean).
  template <bool kNeoHookean>
  bool add_row_forces(Index j, const double* u, double* f) const;
  // K's sparsity pattern: column c's rows, in increasing order, passed to visit(c, row).
  template <class Visit>
  void for_each_pattern_entry(Visit&& visit) const;

  Params params_;
  Index nx_, ny_;
  double lambda_, mu_, rho_, g_, e_;
  bool neo_hookean_;
  Eigen::Matrix2Xd X_;                     // reference positions
  // The mesh is regular: every element is the same rectangle, rotated by the tilt, so one
  // set of Gauss data serves all of them.
  std::array<Gauss, 4> gauss_;
  // The same gradients for the force kernel, laid out [node a][Gauss point q] (the four
  // Gauss points are the SIMD lanes), times w j.
  struct alignas(32) KernelGradients {
    double x[4][4], y[4][4];
  } wgrad_;
  Vec m_;                                  // lumped mass per dof
  Contacts contacts_;
  std::vector<Index> boundary_;            // node of each contact row
  Eigen::Vector2d v0_;
  double spin_;
  Eigen::Vector2d centre_;
  double stable_step_;
};

}  // namespace nsb
