#include "problems/linear_problem.hpp"

#include <algorithm>

namespace nsb {

void copy_stiffness(const SpMat& from, SpMat& K) {
  if (K.rows() == from.rows() && K.cols() == from.cols() && K.isCompressed() && K.nonZeros() == from.nonZeros())
    std::copy(from.valuePtr(), from.valuePtr() + from.nonZeros(), K.valuePtr());
  else
    K = from;
}

}  // namespace nsb
