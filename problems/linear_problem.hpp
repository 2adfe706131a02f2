#pragma once
// Linear elastic problems: what the bars and the spring chain share (signorini-bar and
// bouncing-bar, two-bars, mass-on-bar, spring-chain):
//
//     M U'' + K U = F_ext(t) + L^T lambda,    M and K constant, assembled once,
//     F_int(U) = K U, dF_int/dU = K (is_linear: a scheme may factorise once).
//
// A derived problem fills M_ (n x n), K_ (n x n, compressed) and contacts_ in its constructor;
// the rest of Problem is its own: the load, the strain energy (summed element by element,
// V_int = U^T K U / 2 in exact arithmetic: its own sum keeps its energies' bits), the stable
// step (its closed form 2 / omega_max), the initial state, the output and the exact solution.
// A problem with a faster F_int than the sparse product (an element loop over threads)
// overrides internal_force with the same K.
#include "problems/problem.hpp"

namespace nsb {

// K = from, into K's storage (values only, no allocation) when K already holds from's pattern.
void copy_stiffness(const SpMat& from, SpMat& K);

class LinearProblem : public Problem {
 public:
  SpMat mass_matrix() const override { return M_; }
  void internal_force(ConstVecRef u, VecRef f) const override { f.noalias() = K_ * u; }
  void tangent_stiffness(ConstVecRef, SpMat& K) const override { copy_stiffness(K_, K); }
  bool is_linear() const override { return true; }
  const Contacts& contacts() const override { return contacts_; }

 protected:
  SpMat M_, K_;
  Contacts contacts_;
};

}  // namespace nsb
