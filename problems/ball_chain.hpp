#pragma once
// Ball chain (Newton's cradle): n equal point masses m on a line, no external force, ball 1
// launched at v0 towards the others at rest, the same gap between neighbours, Newton
// restitution e between neighbours. Contacts between bodies: the Delassus operator is not
// diagonal, and with gap = 0 the impacts are simultaneous, where impact laws differ.
//
//     m U_i'' = (L^T lambda)_i,    g_i = gap + U_{i+1} - U_i >= 0   (i = 1 .. n-1)
//     H = L M^{-1} L^T = tridiag(-1, 2, -1) / m
//
// Unknowns: the displacements U_i (U(0) = 0, ball i at (i - 1) gap in the reference).
// Parameters: n >= 2, gap >= 0, e in [0, 1], v0 (initial velocity of ball 1, positive
// towards the others), m > 0.
//
// Sequential outcome (binary collisions). A collision of the pair (i, i+1) approaching at
// w = v_i - v_{i+1} > 0 exchanges, for equal masses,
//     v_i <- v_i - (1 + e) w / 2,    v_{i+1} <- v_{i+1} + (1 + e) w / 2.
// With gap > 0 the motion is an event-driven march: between collisions every ball moves
// uniformly; the next collision is the smallest g_i / (v_i - v_{i+1}) over approaching
// pairs (ties, i.e. touching balls colliding at one instant: in cyclic order after the last
// pair that collided, sweeps along the chain); it ends when no pair approaches (v_i - v_{i+1} <=
// 1e-14 |v0|, the cut-off of the geometric cascades of gap-0 pairs when e < 1). For e = 1
// the march is n - 1 collisions, t_k = k gap / v0, ending in (0, ..., 0, v0). For e < 1 the
// first pass leaves ball 1 faster than ball 2 and later collisions follow; for n = 3:
//     pass:  ((1-e)/2, (1-e^2)/4, (1+e)^2/4) v0,   then 1-2 again (w = (1-e)^2 v0 / 4):
//     final: ((1-e)/2 - (1+e)(1-e)^2/8,  (1-e^2)/4 + (1+e)(1-e)^2/8,  (1+e)^2/4) v0.
// The march is invariant under scaling gap and time together, so the sequential outcome
// does not depend on gap > 0; for gap = 0 it is the limit gap -> 0+ (marched with gap 1).
//
// Simultaneous outcome (Moreau's impact law, gap = 0): one LCP with the full Delassus
// matrix, g'(-) = (-v0, 0, ..., 0):
//     0 <= Lambda  _|_  H Lambda + (1 + e) g'(-) >= 0.
// With Lambda = m (1 + e) v0 y (v0 > 0) it reads 0 <= y _|_ T y - e_1 >= 0, T = tridiag(-1, 2,
// -1) of size n - 1, whose inverse (T^{-1})_ij = min(i, j) (n - max(i, j)) / n is positive:
// y = T^{-1} e_1, y_i = (n - i) / n > 0, all contacts active and the unique solution (T is
// positive definite). Hence
//     Lambda_i = m (1 + e) v0 (n - i) / n,
//     v_1 = v0 (1 - (1 + e)(n - 1) / n),   v_j = (1 + e) v0 / n  (j >= 2).
// n = 3, e = 1: (-1/3, 2/3, 2/3) v0; e = 0: every ball at v0 / n. Both outcomes conserve
// momentum, and for e = 1 the kinetic energy. (v0 <= 0: no contact closes, no impulse.)
//
// Exact state (gap > 0): the march's piecewise-linear motion. Observables: the velocities
// v1 .. vn and v1_exact .. vn_exact: for gap > 0 the march's velocities at t (the sequential
// outcome once it ends), for gap = 0 Moreau's outcome for t > 0 (the law, not a unique
// answer: the exact state() is then empty).
//
// Field output (`--fields`): along x, ball i a vertex at its reference position (i - 1) gap,
// dof i - 1, body i - 1. The balls are points (the model has no radii): with gap = 0 they
// start at one point and the displacements separate them.
//
// References: J. J. Moreau, "Unilateral contact and dry friction in finite freedom
// dynamics", CISM Courses and Lectures 302, 1988; V. Acary and B. Brogliato, "Numerical
// Methods for Nonsmooth Dynamical Systems", Springer 2008 (multiple impacts, Newton's
// cradle); F. Herrmann and P. Schmälzle, "Simple explanation of a well-known
// collision experiment", Am. J. Phys. 49 (1981).
#include "problems/problem.hpp"

namespace nsb {

class BallChain final : public Problem, public ExactSolution {
 public:
  explicit BallChain(const Params& params);
  static ParamSpecs parameters_spec();

  std::string name() const override { return "ball-chain"; }
  const Params& parameters() const override { return params_; }
  Index ndof() const override { return n_; }
  SpMat mass_matrix() const override;
  void internal_force(ConstVecRef, VecRef f) const override { f.setZero(); }
  void tangent_stiffness(ConstVecRef u, SpMat& K) const override;
  bool is_linear() const override { return true; }
  void external_force(double, VecRef f) const override { f.setZero(); }
  double strain_energy(ConstVecRef) const override { return 0.0; }
  double load_potential(ConstVecRef) const override { return 0.0; }
  const Contacts& contacts() const override { return contacts_; }
  State initial_state() const override;
  double stable_step() const override;  // no stiffness: unbounded
  std::vector<std::string> observable_names() const override;
  void observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const override;
  const ExactSolution* exact() const override { return this; }
  std::optional<State> state(double t) const override;
  std::vector<double> impact_times(double t_end) const override;
  std::optional<FieldMesh> field_mesh() const override;

  // Final velocities of the binary-collision march (see above); any gap.
  const Vec& sequential_outcome() const { return sequential_; }
  // Final velocities of Moreau's law with every contact closed at once (gap = 0).
  const Vec& simultaneous_outcome() const { return simultaneous_; }
  // Moreau's impulses Lambda_i (size n - 1) of the simultaneous outcome.
  const Vec& simultaneous_impulses() const { return simultaneous_impulses_; }
  double momentum(ConstVecRef v) const { return m_ * v.sum(); }
  double kinetic_energy(ConstVecRef v) const { return 0.5 * m_ * v.squaredNorm(); }

 private:
  // The state after each collision of the march with gaps `gap`, in order.
  static std::vector<State> march(Index n, double gap, double e, double v0);

  Params params_;
  Index n_;
  double gap_, e_, v0_, m_;
  Contacts contacts_;
  std::vector<State> events_;  // the march (gap > 0), starting with the initial state
  Vec sequential_, simultaneous_, simultaneous_impulses_;
};

}  // namespace nsb
