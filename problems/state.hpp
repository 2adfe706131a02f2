#pragma once
// The vector types every part of a problem speaks in, and a state of its dofs: what the
// model (problems/problem.hpp), its exact solution (problems/exact_solution.hpp) and its
// output (problems/problem_output.hpp) share.
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace nsb {

using Vec = Eigen::VectorXd;
using SpMat = Eigen::SparseMatrix<double>;
using Index = Eigen::Index;
using VecRef = Eigen::Ref<Vec>;
using ConstVecRef = Eigen::Ref<const Vec>;

// Displacement and velocity at time t. Staggered schemes document what their `v` means.
struct State {
  double t = 0.0;
  Vec u;
  Vec v;
};

}  // namespace nsb
