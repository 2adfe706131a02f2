#pragma once
// The sparse symmetric solver every implicit scheme factorises its iteration matrix with
// (moreau-jean's W = M + h^2 theta^2 K, nsga's and newmark-lm's S = M + c K,
// schatzman-paoli's W = M + theta h^2 K):
//
//     A = P^T L L^T P     CHOLMOD's simplicial LL^T (T. A. Davis, CHOLMOD user guide), with
//                         its default fill-reducing ordering P (AMD; METIS if AMD fills badly)
//
// configured as Eigen's CholmodDecomposition in CholmodSimplicialLLt mode (final_asis = 0,
// final_ll = 1): no BLAS, see moreau_jean.hpp. analyze() once per pattern, factorize() per
// matrix (keeps the analysis), solve() per right-hand side. Neither allocates after its
// first call: factorize() runs cholmod_factorize's simplicial steps itself, with the permuted
// copy of A kept (cholmod_factorize allocates and frees it each time), and solve() calls
// cholmod_solve2 with its workspace kept (Eigen's wrapper allocates the result and the
// workspace on every solve).
// With lu_fallback, an A that is not positive definite (indefinite W of a compressed
// hyperelastic material, moreau_jean.hpp) is factorised by Eigen's SparseLU instead (its
// solves allocate; counted by the schemes as "lu_fallbacks").
//
// analyze() refuses (InputError) an A whose factor would not fit in memory: CHOLMOD's
// symbolic analysis gives nnz(L) exactly, and the packed simplicial factor takes a double and
// an int per entry plus 6 ints per column, 12 nnz(L) + 24 n bytes (docs/measurements.md); with CHOLMOD's permuted copy of A and the scheme's A (a double
// and an int per entry, an int per column, each) and CHOLMOD's workspace (about 5 doubles per
// column), the estimate is 12 nnz(L) + 24 nnz(A) + 72 n bytes, against MemAvailable
// (/proc/meminfo) or NSBENCH_MEMORY_LIMIT (bytes, or with a K, M or G suffix: powers of 1024).
#include "core/environment.hpp"  // memory_available
#include <Eigen/SparseLU>
#include <cholmod.h>

#include <string>
#include <vector>

#include "problems/problem.hpp"

namespace nsb {

class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // Symbolic analysis of A's pattern (its lower triangle is read). `who` and `matrix` name the
  // scheme and the matrix in the out-of-memory message ("integrator moreau-jean", "W").
  void analyze(const SpMat& A, const std::string& who, const std::string& matrix);
  // Numeric factorisation of A (the analysed pattern). Returns false when A is not positive
  // definite and lu_fallback is off; with lu_fallback an LU replaces the Cholesky factor, and
  // a singular A throws std::runtime_error.
  bool factorize(const SpMat& A, bool lu_fallback);
  bool uses_lu() const { return use_lu_; }
  // x = A^{-1} b (x is resized to n if needed; b and x may be the same vector).
  void solve(const Vec& b, Vec& x);

  // The estimate above, in bytes, of the last analysis (0 before one).
  double estimated_bytes() const { return estimated_bytes_; }

 private:
  cholmod_common common_;
  cholmod_factor* factor_ = nullptr;
  cholmod_sparse* permuted_ = nullptr;  // triu(A(p,p)'), the matrix CHOLMOD's rowfac reads
  cholmod_dense *x_ = nullptr, *y_ = nullptr, *e_ = nullptr;  // cholmod_solve2's workspace
  Eigen::SparseLU<SpMat> lu_;
  bool use_lu_ = false;
  double estimated_bytes_ = 0.0;
  std::string who_, matrix_;
};

// A = M + s K in the fixed pattern of M + K, refilled in place (no allocation once bound),
// rounded as Eigen's M + s * K (m + s k where both are present). M and K keep their patterns.
class SparseSum {
 public:
  void bind(const SpMat& M, const SpMat& K);
  const SpMat& assemble(const SpMat& M, double s, const SpMat& K);
  const SpMat& matrix() const { return A_; }

 private:
  SpMat A_;
  std::vector<Index> from_m_, from_k_;  // position in A_ of each stored entry of M, of K
};

}  // namespace nsb
