#pragma once
// bar-3d: a hex8 bar hitting a rigid wall, the 3D form of signorini-bar (signorini_bar.hpp;
// derivations in docs/three_d.md; Code_Aster's SDNV100 benchmark uses this bar).
//
// A linear elastic bar (Young's modulus E, Poisson's ratio nu, density rho) along x, length L,
// square cross-section of area A (side a = sqrt(A)), occupying [0, L] x [0, a] x [0, a],
// moving with -v0 e_x towards the rigid wall x = -g0 (frictionless), gravity g along -x:
//     rho u_tt = div sigma - rho g e_x,   sigma = lambda tr(eps) I + 2 mu eps,   eps = sym grad u
//     on the face x = 0:  g = g0 + u_x >= 0,  t_x >= 0,  g t_x = 0,  t_y = t_z = 0
//     lateral = held: u_y = u_z = 0 everywhere (oedometric: the bar's sides slide along fixed
//                     frictionless walls); lateral = free: the sides are traction-free.
// Small strains (the problem is linear, as signorini-bar is): lambda, mu the Lamé constants of
// E, nu (problems/hex8_elements.hpp, Hex8Material).
//
// Exact solution (lateral = held only; problems/bar3d_exact.hpp): u = (u(x, t), 0, 0) with
// u the Signorini bar's d'Alembert solution (g = 0) or the bouncing bar's (g > 0) for the
// oedometric modulus M = E (1 - nu) / ((1 + nu)(1 - 2 nu)), c_p = sqrt(M / rho): contact force
// A rho c_p v0 for 2 L / c_p from t0 = g0 / v0, the bar leaving the wall with +v0. With the
// sides free the bar bulges under the impact (a Pochhammer–Chree wave), no closed form: the
// exact columns are NaN and the exact state() gives nothing.
//
// Discretisation: N x N_side x N_side trilinear hexahedra (hex8_elements.hpp), h = L / N
// along x, a / N_side across; node (i, j, k) at (i h, j a / N_side, k a / N_side) has index
//     n = i + (N + 1) (j + (N_side + 1) k);
// its dofs: held, u_x only (dof n); free, (u_x, u_y, u_z) on dofs 3n, 3n + 1, 3n + 2. Every
// element is the same box, so one element stiffness K_e serves all of them: the hex8 tangent
// at the reference configuration, which for either hyperelastic law is the linear elastic
// stiffness (K_e = int B^T D B dV, D of lambda, mu; held: its 8 x 8 block of the x
// components). F_int = K U, evaluated element by element without assembling K (the
// explicit schemes' kernel: gather u_e, f_e = K_e u_e, scatter); K itself is assembled on
// the first tangent_stiffness() call. Threads: element layers (fixed i) of one parity at a
// time, which share no node, so each node's sum follows the mesh whatever the thread count.
// Mass (`mass`, per direction):
//     lumped      m_a = sum_e rho int N_a dV (row sums of the consistent mass)
//     consistent  M_ab = rho int N_a N_b dV
//     singular    lumped, then the x mass of each wall-face node (0, j, k) moved to (1, j, k)
//                 (as signorini-bar's; the total mass and momentum of rigid motions are kept).
//                 The face nodes' x dofs are coupled by K, so CD-Lagrange's quasi-static
//                 treatment of massless dofs (cd_lagrange.hpp) refuses it.
// With lumped mass and the sides held, each face x = ih moves as a whole in the d'Alembert
// solution and the semi-discrete system of the face sums is the 1D bar's (docs/three_d.md):
// the held bar's discrete solution is signorini-bar's with E -> M, to round-off.
// Gravity acts on the x masses, F_ext = -g M 1 on the x dofs (V_load = g (M 1)^T U).
// Contacts: one per wall-face node (i = 0), on its x dof, gap g0 + u_x, restitution e.
// Stable step: the element eigenvalue bound 2 / omega_max, omega_max^2 <= max eigenvalue of
// K_e v = omega^2 M_e v (Irons & Treharne 1971) with the element's lumped (lumped, singular)
// or consistent mass; the singular model moves mass onto the layer next to the wall, so its
// step is the lumped one, as signorini-bar's h / c.
//
// Parameters (signorini-bar's nondimensional defaults): L = E = rho = A = v0 = 1, g0 = 0,
// g = 0, N = 100, mass = lumped | consistent | singular, e = 0; nu = 0.3 in [0, 0.5),
// lateral = held | free, N_side = 1 (elements along each side of the cross-section).
// Observables: u_contact, v_contact (the wall face's mean x displacement and velocity),
// contact_force (the step's impulses summed, over dt), their exact values, momentum (x,
// sum of M's row sums times v_x) and its exact value. Summary: contact_end_exact.
//
// Bad input (InputError, one line, exit 2): nu outside [0, 0.5); a mesh whose memory (about
// kBar3dBytesPerElementFree or ...Held per element, the assembled tangent included) exceeds the
// machine's, refused before anything of its size is allocated; products of parameters beyond
// the doubles (as signorini-bar).
#include <Eigen/Core>
#include <memory>
#include <mutex>
#include <vector>

#include "problems/bar_elements.hpp"
#include "problems/problem.hpp"

namespace nsb {

class SignoriniBar;

// Bytes per element of a bar-3d mesh with its tangent assembled (the triplets of K_e, K and M,
// and a run's vectors): 3 dofs per node (free) and 1 (held).
inline constexpr double kBar3dBytesPerElementFree = 20480.0, kBar3dBytesPerElementHeld = 3072.0;

class Bar3d final : public Problem, public ExactSolution {
 public:
  // The exact solution's impact times, not 0.1.0's Problem::impact_times (kept for plugins).
  using ExactSolution::impact_times;
  explicit Bar3d(const Params& params);
  ~Bar3d() override;
  static ParamSpecs parameters_spec();

  std::string name() const override { return "bar-3d"; }
  const Params& parameters() const override { return params_; }
  Index ndof() const override { return dofs_per_node_ * nodes(); }
  SpMat mass_matrix() const override { return M_; }
  void internal_force(ConstVecRef u, VecRef f) const override;
  void tangent_stiffness(ConstVecRef u, SpMat& K) const override;
  bool is_linear() const override { return true; }
  void external_force(double, VecRef f) const override { f = -gravity_ * x_mass_; }
  double strain_energy(ConstVecRef u) const override;
  double load_potential(ConstVecRef u) const override { return gravity_ * x_mass_.dot(u); }
  double energy_scale() const override;
  std::string energy_scale_text() const override { return "kinetic energy at the first impact, rho A L (v0^2 + 2 g g0) / 2"; }
  const Contacts& contacts() const override { return contacts_; }
  State initial_state() const override;
  double stable_step() const override { return stable_step_; }
  std::vector<std::string> observable_names() const override;
  void observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const override;
  // Held: node (i, j, k)'s u_x from the 1D exact solution at x = i h. Free: nothing.
  const ExactSolution* exact() const override { return this; }
  std::optional<State> state(double t) const override;
  // contact_end_exact: when the wall face leaves the wall for good, t0 + 2 L / c_p (held, g = 0,
  // v0 > 0: the d'Alembert solution's one contact phase); NaN otherwise (free sides, or g > 0).
  std::vector<std::pair<std::string, double>> summary_values() const override;
  // Field output: the nodes at their reference positions, the hexahedra in hex8 order (VTK's
  // hexahedron order); stress: the linear elastic Cauchy stress at the element's centre,
  // components xx, yy, zz, yz, xz, xy.
  std::optional<FieldMesh> field_mesh() const override;
  void cell_stress(ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> out) const override;

  Index nodes() const { return (n_ + 1) * (side_ + 1) * (side_ + 1); }
  Index elements() const { return n_ * side_ * side_; }
  Index side_elements() const { return side_; }  // N_side
  bool lateral_held() const { return dofs_per_node_ == 1; }
  // The x dof of node (i, j, k).
  Index x_dof(Index i, Index j, Index k) const { return dofs_per_node_ * node(i, j, k); }
  // The 1D bar (E -> M) whose d'Alembert / bouncing solution is the held bar's.
  const SignoriniBar& exact_bar() const { return *exact_; }
  double momentum(ConstVecRef v) const { return x_mass_.dot(v); }
  double p_wave_speed() const { return c_p_; }

 private:
  Index node(Index i, Index j, Index k) const { return i + (n_ + 1) * (j + (side_ + 1) * k); }
  // The 8 nodes of element (i, j, k), in hex8 order.
  void element_nodes(Index i, Index j, Index k, Index out[8]) const;
  // visit(e, nodes) for every element e (i fastest, then j, then k: the cells' order).
  template <class Visit>
  void for_each_element(Visit&& visit) const;
  template <int D>
  void add_layer_forces(Index i, const double* u, double* f) const;
  SpMat assemble_stiffness() const;
  void build_mass(const Eigen::Matrix<double, 8, 8>& Me, const Eigen::Matrix<double, 8, 1>& me, BarMassModel model);
  void set_stable_step(const Eigen::Matrix<double, 8, 8>& Me, const Eigen::Matrix<double, 8, 1>& me, BarMassModel model);

  Params params_;
  Index n_, side_;
  int dofs_per_node_;
  double h_, a_, gravity_, v0_, lambda_, mu_, c_p_;
  Eigen::Matrix<double, 24, 24> Ke_;  // element stiffness, free (node-major x, y, z)
  Eigen::Matrix<double, 8, 8> Kx_;    // its x-x block, held
  SpMat M_;
  Vec x_mass_;  // M's row sums on the x dofs, 0 on the others
  Contacts contacts_;
  double stable_step_ = 0.0;
  std::unique_ptr<SignoriniBar> exact_;
  mutable std::once_flag k_once_;
  mutable SpMat K_;  // assembled on first use
};

}  // namespace nsb
