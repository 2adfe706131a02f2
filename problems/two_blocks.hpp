#pragma once
// Two blocks: two hyperelastic Q4 blocks (block_2d.hpp, untilted) on a rigid floor y = 0,
// a lower block resting on it and an upper block dropped onto the lower one, their meshes
// not matching. Contacts between bodies: the inter-body rows share dofs with each other and
// with the floor rows, so H = L M^{-1} L^T is not diagonal.
//
//     U = (U_lower, U_upper),  M = diag(M_lower, M_upper),  F_int, K, energies: the blocks'
//     floor:  g = y_a >= 0 for every boundary node a of either block (as block-2d)
//     node-to-segment: for each bottom node a of the upper block, the segment [b0, b1] of the
//     lower block's top edge holding its reference abscissa X_a, xi = (X_a - X_b0) / (X_b1 - X_b0):
//         g = y_a - ((1 - xi) y_b0 + xi y_b1) >= 0,    y = Y + U_y
//     one row with +1 on a's y dof, -(1 - xi) on b0's and -xi on b1's.
//
// Small sliding: the segment and xi are fixed in the reference configuration (the blocks as
// placed at t = 0), so the row is linear in U and exact while the upper node slides along
// its segment by little against the segment's length and the top edge stays nearly flat.
// The upper block's bottom is the slave side and must be at least as finely meshed as the
// lower block's top edge (upper_W / upper_nx <= lower_W / lower_nx): one-pass node-to-
// segment stops only the slave nodes, so a coarser slave side would let the lower block's
// top nodes pass between them. Both blocks are centred on x = 0, the upper no wider than the
// lower, so every slave node has a segment.
//
// Friction (mu > 0, the same on every contact): the floor rows get block-2d's tangent rows
// (the x dof), the node-to-segment rows the x components with the same weights (the slip
// rate of the node against the interpolated segment point). The node-to-segment weights sum
// to zero, so the inter-body impulses (normal and tangential) change no total momentum:
//     sum_a m_a v_a(+) - sum_a m_a v_a(-) = dt F_ext + (floor impulses: Lambda_T along x,
//                                                   Lambda_N along y)
// and, without gravity, the total momentum changes by the floor's impulses only.
//
// Parameters: lower_ and upper_ + block-2d's W, H, nx, ny, E, nu, rho, material, vx, vy,
// spin; lower_height (the lower block's bottom above the floor, >= 0) and upper_gap (the
// upper block's bottom above the lower block's top, >= 0: no overlap at t = 0); g, e, mu.
// Observables: block-2d's, totalled over both blocks (strain_energy, gravity_energy, px,
// py, angular_momentum, closed_contacts: floor and node-to-segment contacts with g <= 0),
// and closed_between (node-to-segment contacts with g <= 0).
//
// References: P. Wriggers, "Computational Contact Mechanics", 2nd ed., Springer 2006,
// ch. 4 and 9 (node-to-segment discretisation, small sliding); T. A. Laursen,
// "Computational Contact and Impact Mechanics", Springer 2002.
#include <memory>

#include "problems/block_2d.hpp"

namespace nsb {

class TwoBlocks final : public Problem {
 public:
  explicit TwoBlocks(const Params& params);
  static ParamSpecs parameters_spec();

  std::string name() const override { return "two-blocks"; }
  const Params& parameters() const override { return params_; }
  Index ndof() const override { return nl_ + upper_->ndof(); }
  SpMat mass_matrix() const override;
  void internal_force(ConstVecRef u, VecRef f) const override;
  void tangent_stiffness(ConstVecRef u, SpMat& K) const override;
  bool is_linear() const override { return false; }
  void external_force(double t, VecRef f) const override;
  double strain_energy(ConstVecRef u) const override;
  double load_potential(ConstVecRef u) const override;
  const Contacts& contacts() const override { return contacts_; }
  State initial_state() const override;
  double stable_step() const override;
  std::vector<std::string> observable_names() const override;
  void observe(const State& s, std::span<double> out) const override;
  // Field output: the lower block's mesh (body 0), then the upper block's (body 1, dofs
  // shifted by lower_dofs()); stress as block-2d's (Cauchy, Gauss-point mean).
  std::optional<FieldMesh> field_mesh() const override;
  void cell_stress(ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> out) const override;

  const Block2d& lower() const { return *lower_; }
  const Block2d& upper() const { return *upper_; }
  // Dofs of the lower block come first: U = (U_lower, U_upper), lower_dofs() of them.
  Index lower_dofs() const { return nl_; }
  // Contacts: the lower block's floor rows, the upper block's floor rows, then the
  // node-to-segment rows (floor_contacts() of the first kind).
  Index floor_contacts() const { return floor_contacts_; }
  Eigen::Vector2d linear_momentum(ConstVecRef v) const;

 private:
  Params params_;
  std::unique_ptr<Block2d> lower_, upper_;
  Index nl_;
  Index floor_contacts_;
  Contacts contacts_;
};

}  // namespace nsb
