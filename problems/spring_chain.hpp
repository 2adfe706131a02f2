#pragma once
// Spring chain: n point masses in a line joined by n - 1 linear springs, no external force,
// optionally rigid walls: left of the first mass, or also right of the last one.
//
//     M U'' + K U = L^T lambda,     K = stiffness of the free chain (singular: rigid motion)
//     masses alternate m, r m (r = mass_ratio), springs all k
//     wall = left:  g(U) = gap + U_0 >= 0   (one contact);  wall = none: no contact
//     wall = both:  also g(U) = gap - U_{n-1} >= 0  (the chain rattles between the walls)
//
// Initial state: U = 0, velocity -v0 + a (-1)^i on mass i (a rigid drift towards the wall
// plus a vibration). A small stiff system with the momentum identities of a continuum:
// F_int has zero resultant, so with no wall the total linear momentum sum_i m_i U'_i is
// constant, and with walls it changes by exactly the wall impulses (sum of L^T Lambda). It is the test bed
// of the variable-step integrators (momentum under any step sequence, energy balance);
// it is not a discretised bar (no element masses, no exact solution).
//
// Field output (`--fields`): along x, mass i a point with a vertex cell at x = i (1 m apart:
// the model has no rest length, only the springs' elongations), dof i; spring i a line from
// mass i to mass i + 1 with cell array spring_force = k (U_{i+1} - U_i) [N], positive in
// tension. One body (id 0). The walls (x = -gap, and n - 1 + gap) are not drawn.
//
// Stable step of the central difference scheme: 2 / omega_max, omega_max^2 the largest
// eigenvalue of M^{-1} K (computed once, dense, hence n <= 200).
#include "problems/linear_problem.hpp"

namespace nsb {

class SpringChain final : public LinearProblem {
 public:
  explicit SpringChain(const Params& params);
  static ParamSpecs parameters_spec();

  std::string name() const override { return "spring-chain"; }
  const Params& parameters() const override { return params_; }
  Index ndof() const override { return n_; }
  void external_force(double, VecRef f) const override { f.setZero(); }
  double strain_energy(ConstVecRef u) const override;
  double load_potential(ConstVecRef) const override { return 0.0; }
  State initial_state() const override;
  double stable_step() const override { return stable_step_; }
  // momentum (below) and v_first, the velocity of the first mass (dof 0: the one at the left
  // wall, whose graph jumps at each of its impacts).
  std::vector<std::string> observable_names() const override { return {"momentum", "v_first"}; }
  void observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const override;
  std::optional<FieldMesh> field_mesh() const override;
  void cell_stress(ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> out) const override;

  // Total linear momentum sum_i m_i v_i.
  double momentum(ConstVecRef v) const { return m_.dot(v); }

 private:
  Params params_;
  Index n_;
  double k_, e_, v0_, a_;
  Vec m_;
  double stable_step_;
};

}  // namespace nsb
