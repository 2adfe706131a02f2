#include "problems/rigid_problem.hpp"

namespace nsb {

SpMat RigidProblem::mass_matrix() const {
  SpMat M(ndof(), ndof());
  for (Index i = 0; i < ndof(); ++i) M.insert(i, i) = mass_[i];
  M.makeCompressed();
  return M;
}

void RigidProblem::tangent_stiffness(ConstVecRef, SpMat& K) const {
  if (K.rows() != ndof() || K.cols() != ndof()) K.resize(ndof(), ndof());
  K.setZero();
}

}  // namespace nsb
