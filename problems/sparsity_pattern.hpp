#pragma once
// A tangent's sparsity pattern written straight into a compressed column-major K (no
// triplets, no sort): the pattern is given as for_each(visit), which calls visit(col, row)
// for every entry, columns in increasing order and each column's rows in increasing order
// (the structured meshes of block_2d.hpp and block_3d.hpp list their node neighbourhoods so).
// When K already holds exactly this pattern (a scheme's earlier call) nothing is allocated:
// only its values are zeroed.
#include "problems/problem.hpp"

namespace nsb {

template <class ForEachEntry>
void prepare_sparsity_pattern(SpMat& K, Index n, ForEachEntry&& for_each) {
  Index nnz = 0;
  for_each([&](Index, Index) { ++nnz; });
  bool same = K.rows() == n && K.cols() == n && K.isCompressed() && K.nonZeros() == nnz;
  if (same) {
    Index k = 0;
    for_each([&](Index col, Index row) {
      same = same && K.innerIndexPtr()[k] == row && K.outerIndexPtr()[col] <= k && k < K.outerIndexPtr()[col + 1];
      ++k;
    });
  }
  if (!same) {
    K.resize(n, n);
    K.resizeNonZeros(nnz);
    Index k = 0;
    for_each([&](Index col, Index row) {
      K.innerIndexPtr()[k] = row;
      K.outerIndexPtr()[col + 1] = ++k;
    });
    K.outerIndexPtr()[0] = 0;
  }
  K.coeffs().setZero();
}

}  // namespace nsb
