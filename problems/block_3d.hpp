#pragma once
// block-3d: a hyperelastic hex8 block dropped, tilted, on a rigid floor z = 0, with an optional
// spin about the vertical, a sideways velocity and Coulomb friction on the cone (the 3D form of
// block_2d.hpp; docs/three_d.md).
//
// PDE, total Lagrangian, reference configuration Omega_0 = the block as placed at t = 0:
//     rho u_tt = Div P - rho g e_z,   P = F S(E),   F = I + Grad u,   E = (F^T F - I) / 2
//     on every surface point:  gap g = z = Z + u_z >= 0,  t_N >= 0,  g t_N = 0,
//                              |t_T| <= mu t_N, the slip opposing t_T where |t_T| = mu t_N
// with S of Saint Venant–Kirchhoff or the compressible neo-Hookean law (`material`;
// problems/hex8_elements.hpp has both, their forces and tangents). Lamé constants of E, nu.
//
// Mesh: a W x D x H box (x, y, z) of nx x ny x nz hex8 elements, rotated by `tilt` about the
// y axis through its centre (x -> x cos a + z sin a: the +x end rises for a > 0), centred on
// x = y = 0, its lowest point at `height`. Node (i, j, k) has index
//     n = i + (nx + 1) (j + (ny + 1) k),   dofs 3n, 3n + 1, 3n + 2 (u_x, u_y, u_z).
// Every element is the same rotated box, so one Hex8Element (its Gauss data) serves them all.
// Threads (core/threads.hpp): element layers (fixed k) of one parity at a time, which share
// no node, so each node's sum follows the mesh whatever the thread count.
// Mass: lumped, m_a = sum_e rho int N_a dV (row sums of the consistent mass; diagonal, so
// CD-Lagrange's contact blocks are w_n, w_t I: its closed-form disk projection).
// Gravity g (0: off) along -z: F_ext = -m_a g on the z dofs, V_load = sum_a m_a g z_a.
// Initial velocity v_a = (vx, vy, vz) + spin e_z x (X_a - c), c the block's centre.
//
// Contacts: every surface node is a candidate (the tilted, spinning block may land on any
// face), one contact per node with rows on its own dofs, constant:
//     normal L: +1 on u_z (gap g0 = Z_a),   T1: +1 on u_x,   T2: +1 on u_y   (mu > 0 only)
// so the cone law holds per node with the slip (v_a,x, v_a,y). mu = 0 (the default, as
// block-2d's) gives the frictionless block, without tangent rows. Restitution e.
//
// What is exact (the identities a study measures; docs/three_d.md):
//   - linear momentum P = sum_a m_a v_a changes only by gravity and the contact impulses:
//         P(t1) - P(t0) = -M g e_z (t1 - t0) + sum_i (Lambda_T1,i, Lambda_T2,i, Lambda_N,i)
//     (sum F_int = 0: the energy depends on u only through C, invariant under translations);
//   - angular momentum about the centre of mass, J_c = sum_a m_a (x_a - x_c) x v_a, changes
//     only by the moments (x_a - x_c) x Lambda_a of the contact impulses (the internal forces
//     have no net torque, invariance under rotations; uniform gravity none about x_c);
//   - energy: kinetic + strain + gravity is constant in free flight; contacts with e <= 1
//     and friction never add to it.
// Observables: strain and gravity energy; P (px, py, pz); the centre of mass (xc, yc, zc);
// J_c (jx, jy, jz); the number of closed contacts (g <= 0). The generic columns add kinetic
// and total energy, the smallest gap, impulse sums and active contacts.
//
// Parameters: W, D, H (size [m]), nx, ny, nz (elements, >= 1), E [Pa], nu in [0, 0.5),
// rho [kg/m^3], material {svk, neo-hookean}, height (lowest point above the floor [m], >= 0:
// the block never starts in penetration), tilt [deg], vx, vy, vz [m/s], spin [rad/s, about
// the vertical through the centre], g [m/s^2], e, mu (>= 0).
// Bad input (InputError, one line, exit 2): the ranges above; a mesh whose memory (about
// kBlock3dBytesPerElement per element, the assembled tangent included) exceeds the machine's,
// refused before anything of its size is allocated. The estimate covers the problem and the
// explicit schemes' runs; an implicit scheme's sparse factorisation of K grows faster than
// the mesh (fill-in of a 3D mesh: docs/three_d.md has measured figures), which it does not bound.
//
// Stable step: 2 / omega_max with omega_max^2 <= lambda_max(M_e^{-1} K_e) (the element
// eigenvalue bound, Irons & Treharne 1971), K_e the tangent at U = 0: the undeformed block's.
#include <Eigen/Core>
#include <vector>

#include "problems/hex8_elements.hpp"
#include "problems/problem.hpp"

namespace nsb {

// Bytes per element of a block-3d mesh with its tangent assembled: K's 81 x 27 / 8 entries
// per node (value and row index) and a run's state and work vectors, rounded up.
inline constexpr double kBlock3dBytesPerElement = 4096.0;

class Block3d final : public Problem {
 public:
  explicit Block3d(const Params& params);
  static ParamSpecs parameters_spec();

  std::string name() const override { return "block-3d"; }
  const Params& parameters() const override { return params_; }
  Index ndof() const override { return 3 * nodes(); }
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
  // Field output: the nodes at their reference positions, the hexahedra in hex8 (VTK) order;
  // stress: the Cauchy stress sigma = F S F^T / J at the element's centre, components xx, yy,
  // zz, yz, xz, xy.
  std::optional<FieldMesh> field_mesh() const override;
  void cell_stress(ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> out) const override;

  Index nodes() const { return (nx_ + 1) * (ny_ + 1) * (nz_ + 1); }
  Index elements() const { return nx_ * ny_ * nz_; }
  double total_mass() const { return m_.sum() / 3.0; }
  const Vec& lumped_mass() const { return m_; }  // per dof
  Eigen::Vector3d reference_position(Index a) const { return X_.col(a); }
  // The surface node of each contact row.
  const std::vector<Index>& contact_nodes() const { return surface_; }
  Eigen::Vector3d linear_momentum(ConstVecRef v) const;
  Eigen::Vector3d centre_of_mass(ConstVecRef u) const;
  // J_c = sum_a m_a (x_a - x_c) x v_a.
  Eigen::Vector3d angular_momentum(ConstVecRef u, ConstVecRef v) const;

 private:
  Index node(Index i, Index j, Index k) const { return i + (nx_ + 1) * (j + (ny_ + 1) * k); }
  // The 8 nodes of element (i, j, k), in hex8 order.
  void element_nodes(Index i, Index j, Index k, Index out[8]) const;
  // The current positions X + U of the element's nodes.
  Hex8Nodes positions(const Index nodes_e[8], ConstVecRef u) const;
  // visit(nodes) for every element of element layer k, its 8 nodes in hex8 order.
  template <class Visit>
  void for_each_in_layer(Index k, Visit&& visit) const;
  // Runs layer(k) over the element layers, one parity at a time; false when a layer threw
  // (an inverted element in the neo-Hookean law).
  template <class Layer>
  bool for_layers_by_parity(Layer&& layer) const;
  // K's sparsity pattern: column c's rows, in increasing order, passed to visit(c, row).
  template <class Visit>
  void for_each_pattern_entry(Visit&& visit) const;

  Params params_;
  Index nx_, ny_, nz_;
  Hex8Material material_;
  double g_;
  Eigen::Matrix3Xd X_;                 // reference positions
  Eigen::Matrix3d rotation_;           // the tilt
  Eigen::Vector3d element_size_;       // W / nx, D / ny, H / nz
  Hex8Element element_;
  Vec m_;                              // lumped mass per dof
  Contacts contacts_;
  std::vector<Index> surface_;         // node of each contact row
  Eigen::Vector3d v0_, centre_;
  double spin_;
  double stable_step_ = 0.0;
};

}  // namespace nsb
