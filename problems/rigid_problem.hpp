#pragma once
// Rigid bodies under a constant load: what the problems whose bodies do not deform share
// (bouncing-mass, sliding-mass, rolling-disk):
//
//     M U'' = F + L^T lambda_N + T^T lambda_T,    M diagonal and constant, F constant
//     F_int = 0, K = 0, V_load(U) = -F^T U (F = -grad V_load: gravity),
//     no stiffness, so the explicit stable step is unbounded.
//
// A derived problem fills mass_ (the diagonal of M), load_ (F) and contacts_ in its
// constructor; the rest of Problem (name, parameters, initial state, observables, exact
// solution) is its own.
#include <limits>

#include "problems/problem.hpp"

namespace nsb {

class RigidProblem : public Problem {
 public:
  Index ndof() const override { return mass_.size(); }
  SpMat mass_matrix() const override;
  void internal_force(ConstVecRef, VecRef f) const override { f.setZero(); }
  void tangent_stiffness(ConstVecRef u, SpMat& K) const override;
  bool is_linear() const override { return true; }
  void external_force(double, VecRef f) const override { f = load_; }
  double strain_energy(ConstVecRef) const override { return 0.0; }
  double load_potential(ConstVecRef u) const override { return -load_.dot(u); }
  const Contacts& contacts() const override { return contacts_; }
  double stable_step() const override { return std::numeric_limits<double>::infinity(); }

 protected:
  Vec mass_, load_;
  Contacts contacts_;
};

}  // namespace nsb
