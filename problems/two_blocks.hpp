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
// Large sliding (sliding = large; Wriggers 2006 section 9.1, Laursen 2002 chapter 5): the
// contacts move with the configuration (contacts_move(), docs/contacts.md). At every
// evaluation each bottom node a of the upper block finds its segment [b0, b1] of the lower
// block's top edge from the current positions x = X + U:
//     e = x_b1 - x_b0,  l = |e|,  t = e / l,  n = (-t_y, t_x)   (upward for e along +x)
//     xi = (x_a - x_b0) . t / l,   g = (x_a - x_seg(xi)) . n = (x_a - x_b0) . n
//     L(U):  +n on a,  -(1 - xi) n on b0,  -xi n on b1   (exactly dg/dU: the terms of dn and
//            dxi cancel, dn = -t (n . de) / l)
// Segment choice: segment i holds the nodes on its side of the line through the shared vertex
// b along n_i + n_i+1 (the bisector): there (x_a - x_b) . n_i = (x_a - x_b) . n_i+1, so the gap
// is continuous where a node changes segment, while its row changes pattern (b0, b1 shift by
// one node). On a straight edge the bisector is the normal through the vertex and xi lies in
// [0, 1]; at a kink it may pass 0 or 1 by the kink's angle times the gap. Past the edge's ends
// (xi < 0 on the first segment, xi > 1 on the last) the node is off the lower block: its gap
// is the distance to the end vertex b, g = |x_a - x_b|, L = +d on a, -d on b, d the unit vector
// from b to a: continuous with the segment's at xi = 0 (1) when g >= 0, and open. One-pass
// node-to-segment does not see the upper block's bottom edge meet the lower block's corner.
// Tangent rows, the convected slip (Laursen's frictional slip is the rate of the convected
// coordinate xi): T = ds/dU with s = X_b0 + h xi, h = X_b1 - X_b0 the segment's reference
// length, i.e. the reference abscissa of the lower block's material point under the node:
//     T(U) = (h / l) [t . (dx_a - (1 - xi) dx_b0 - xi dx_b1) + (g / l) n . (dx_b1 - dx_b0)]
// Stick (T V = 0) keeps the node over the same material point; at g = 0 this is the relative
// tangential velocity scaled by h / l (1 up to the top edge's stretch), so the friction force's
// bound is mu h / l times the normal one. Both rows' weights sum to zero per component (as in
// small sliding: the identities below hold). Storage for the worst case, allocated once:
// each node-to-segment row holds the node's and every top-edge node's x and y entries
// (2 (lower_nx + 2)), zero off its current segment; contacts() holds the rows at U0 in that
// pattern and g0 = g(U0) - L(U0) U0.
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
// upper block's bottom above the lower block's top, >= 0: no overlap at t = 0); g, e, mu;
// sliding (small: the pairing frozen in the reference configuration, the default; large: the
// pairing found at every evaluation).
// Observables: block-2d's, totalled over both blocks (strain_energy, gravity_energy, px,
// py, angular_momentum, closed_contacts: floor and node-to-segment contacts with g <= 0),
// and closed_between (node-to-segment contacts with g <= 0).
//
// References: P. Wriggers, "Computational Contact Mechanics", 2nd ed., Springer 2006,
// ch. 4 and 9 (node-to-segment discretisation, small and large sliding); T. A. Laursen,
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
  bool contacts_move() const override { return large_sliding_; }
  void evaluate_contacts(ConstVecRef u, ContactGeometry& out) const override;
  // The floor rows' T u; the node-to-segment rows' convected slide X_b0 + h xi (large sliding).
  void contact_slide(ConstVecRef u, VecRef s) const override;
  State initial_state() const override;
  double stable_step() const override;
  std::vector<std::string> observable_names() const override;
  void observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const override;
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

  // Where the upper block's bottom node k (0 .. upper_nx) meets the lower block's top edge at
  // u, found from the current positions (the large-sliding rule above, whatever `sliding`).
  struct SegmentContact {
    Index segment = 0;        // i: the segment [top node i, top node i + 1]
    double xi = 0.0;          // local coordinate on it (unclamped)
    double gap = 0.0;         // g
    double slide = 0.0;       // s = X_b0 + h xi
    // dofs of g and s: a (x, y), b0 (x, y), b1 (x, y), and their weights in L and T
    Index dofs[6] = {};
    double normal[6] = {};
    double tangent[6] = {};
  };
  SegmentContact segment_contact(ConstVecRef u, Index k) const;

 private:
  // The node-to-segment contacts' rows and gaps at U0 (large sliding), in the worst-case
  // pattern, appended to `normal` and `tangent`.
  void add_large_sliding_rows(std::vector<Eigen::Triplet<double>>& normal, std::vector<Eigen::Triplet<double>>& tangent);
  // Current position of lower-block node b.
  Eigen::Vector2d lower_position(ConstVecRef u, Index b) const;

  Params params_;
  std::unique_ptr<Block2d> lower_, upper_;
  Index nl_;
  Index floor_contacts_;
  Contacts contacts_;
  bool large_sliding_ = false;
  Index top0_ = 0;      // first node of the lower block's top edge
  Index segments_ = 0;  // lower_nx: segments of that edge
  Index slaves_ = 0;    // upper_nx + 1: bottom nodes of the upper block
};

}  // namespace nsb
