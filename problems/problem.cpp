#include "problems/problem.hpp"

namespace nsb {

std::optional<Vec> diagonal_mass(const SpMat& M) {
  Vec d = Vec::Zero(M.rows());
  for (Index j = 0; j < M.outerSize(); ++j)
    for (SpMat::InnerIterator it(M, j); it; ++it) {
      if (it.row() != it.col()) {
        if (it.value() != 0.0) return std::nullopt;
      } else {
        d[it.row()] = it.value();
      }
    }
  return d;
}

}  // namespace nsb
