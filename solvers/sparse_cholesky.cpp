#include "solvers/sparse_cholesky.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "core/parameters.hpp"

namespace nsb {

namespace {

// A's lower triangle as CHOLMOD reads it (no copy; as Eigen's viewAsCholmod of a Lower
// selfadjoint view).
cholmod_sparse view(const SpMat& A) {
  cholmod_sparse s{};
  s.nrow = static_cast<std::size_t>(A.rows());
  s.ncol = static_cast<std::size_t>(A.cols());
  s.nzmax = static_cast<std::size_t>(A.nonZeros());
  s.p = const_cast<int*>(A.outerIndexPtr());
  s.i = const_cast<int*>(A.innerIndexPtr());
  s.x = const_cast<double*>(A.valuePtr());
  s.nz = A.isCompressed() ? nullptr : const_cast<int*>(A.innerNonZeroPtr());
  s.packed = A.isCompressed() ? 1 : 0;
  s.sorted = 1;
  s.stype = -1;
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  return s;
}

double gib(double bytes) { return bytes / (1024.0 * 1024.0 * 1024.0); }

}  // namespace

SparseCholesky::SparseCholesky() {
  cholmod_start(&common_);
  common_.final_asis = 0;  // as Eigen's CholmodSimplicialLLt mode
  common_.supernodal = CHOLMOD_SIMPLICIAL;
  common_.final_ll = 1;
  // Silent: CHOLMOD prints "not positive definite" as an error, but that is the LU fallback's
  // case, reported through factorize() and counted by the schemes (lu_fallbacks).
  common_.print = 0;
}

SparseCholesky::~SparseCholesky() {
  cholmod_free_dense(&x_, &common_);
  cholmod_free_dense(&y_, &common_);
  cholmod_free_dense(&e_, &common_);
  if (factor_) cholmod_free_factor(&factor_, &common_);
  if (permuted_) cholmod_free_sparse(&permuted_, &common_);
  cholmod_finish(&common_);
}

void SparseCholesky::analyze(const SpMat& A, const std::string& who, const std::string& matrix) {
  if (factor_) cholmod_free_factor(&factor_, &common_);
  if (permuted_) cholmod_free_sparse(&permuted_, &common_);
  cholmod_sparse a = view(A);
  factor_ = cholmod_analyze(&a, &common_);
  if (!factor_) throw std::runtime_error(fmt::format("{}: CHOLMOD's analysis of {} failed (status {})", who, matrix, common_.status));
  use_lu_ = false;
  who_ = who;
  matrix_ = matrix;
  const double n = static_cast<double>(A.rows()), lnz = common_.lnz;
  const double entry = sizeof(double) + sizeof(int), anz = static_cast<double>(A.nonZeros());
  estimated_bytes_ = lnz * entry + 6.0 * n * sizeof(int)  // the factor
                     + 2.0 * (anz * entry + n * sizeof(int))  // CHOLMOD's permuted copy of A, the scheme's A
                     + 5.0 * n * sizeof(double);              // CHOLMOD's workspace
  std::string source;
  const double available = memory_available(source);
  if (estimated_bytes_ > available)
    throw InputError(fmt::format("{}: the factorisation of {} ({} dofs) needs about {:.3g} GiB, more than the {:.3g} GiB "
                                 "available ({})",
                                 who, matrix, A.rows(), gib(estimated_bytes_), gib(available), source));
}

bool SparseCholesky::factorize(const SpMat& A, bool lu_fallback) {
  // cholmod_factorize's simplicial path for a lower-stored A, step by step, so that its
  // permuted copy triu(A(p,p)') is refilled in place instead of allocated on every call:
  // transpose into it, rowfac (LL^T as final_ll asks), change_factor to the final form.
  cholmod_sparse a = view(A);
  const std::size_t n = a.nrow;
  if (!permuted_) permuted_ = cholmod_allocate_sparse(n, n, a.nzmax, 1, 1, 1, CHOLMOD_REAL, &common_);
  common_.status = CHOLMOD_OK;
  cholmod_allocate_work(n, 2 * n, 0, &common_);  // nothing once allocated
  int* perm = factor_->ordering == CHOLMOD_NATURAL ? nullptr : static_cast<int*>(factor_->Perm);
  if (!permuted_ || common_.status < CHOLMOD_OK || !cholmod_transpose_sym(&a, 2, perm, permuted_, &common_))
    throw std::runtime_error(fmt::format("{}: CHOLMOD could not permute {} (status {})", who_, matrix_, common_.status));
  const std::size_t grow2 = common_.grow2;
  factor_->is_ll = common_.final_ll;
  if (factor_->xtype == CHOLMOD_PATTERN && common_.final_pack) common_.grow2 = 0;  // the exact space
  double zero[2] = {0.0, 0.0};
  cholmod_rowfac(permuted_, nullptr, zero, 0, n, factor_, &common_);
  common_.grow2 = grow2;
  if (common_.status >= CHOLMOD_OK)
    cholmod_change_factor(factor_->xtype, factor_->is_ll, 0, common_.final_pack, common_.final_monotonic, factor_, &common_);
  use_lu_ = factor_->minor != factor_->n;
  if (!use_lu_) return true;
  if (!lu_fallback) return false;
  lu_.compute(A);
  if (lu_.info() != Eigen::Success) throw std::runtime_error(fmt::format("{}: iteration matrix {} is singular", who_, matrix_));
  return true;
}

void SparseCholesky::solve(const Vec& b, Vec& x) {
  if (use_lu_) {
    x = lu_.solve(b);
    return;
  }
  cholmod_dense rhs{};
  rhs.nrow = static_cast<std::size_t>(b.size());
  rhs.ncol = 1;
  rhs.nzmax = rhs.nrow;
  rhs.d = rhs.nrow;
  rhs.x = const_cast<double*>(b.data());
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  // The simplicial solve leaves its workspace Y shaped 1 x n, and the next call reallocates
  // it unless it is 4 x n again (cholmod_ensure_dense checks the shape, not the room):
  // restore the shape it was allocated with.
  if (y_ && y_->nzmax >= 4 * rhs.nrow) {
    y_->nrow = y_->d = 4;
    y_->ncol = rhs.nrow;
  }
  if (!cholmod_solve2(CHOLMOD_A, factor_, &rhs, nullptr, &x_, nullptr, &y_, &e_, &common_))
    throw std::runtime_error(fmt::format("{}: CHOLMOD's solve with {} failed (status {})", who_, matrix_, common_.status));
  x.resize(b.size());
  std::memcpy(x.data(), x_->x, static_cast<std::size_t>(b.size()) * sizeof(double));
}

namespace {

// Where each stored entry of B (a sub-pattern of A) sits in A's value array.
std::vector<Index> positions(const SpMat& A, const SpMat& B) {
  std::vector<Index> pos;
  pos.reserve(static_cast<std::size_t>(B.nonZeros()));
  for (Index j = 0; j < B.outerSize(); ++j) {
    SpMat::InnerIterator a(A, j);
    for (SpMat::InnerIterator b(B, j); b; ++b) {
      while (a && a.row() < b.row()) ++a;
      if (!a || a.row() != b.row()) throw std::logic_error("SparseSum: an entry of M or K is not in M + K");
      pos.push_back(static_cast<Index>(&a.value() - A.valuePtr()));
    }
  }
  return pos;
}

}  // namespace

void SparseSum::bind(const SpMat& M, const SpMat& K) {
  A_ = M + K;
  A_.makeCompressed();
  from_m_ = positions(A_, M);
  from_k_ = positions(A_, K);
}

const SpMat& SparseSum::assemble(const SpMat& M, double s, const SpMat& K) {
  if (static_cast<std::size_t>(M.nonZeros()) != from_m_.size() || static_cast<std::size_t>(K.nonZeros()) != from_k_.size() ||
      !M.isCompressed() || !K.isCompressed())
    throw std::logic_error("SparseSum: M or K changed pattern since bind()");
  double* a = A_.valuePtr();
  std::fill(a, a + A_.nonZeros(), 0.0);
  const double* m = M.valuePtr();
  for (std::size_t i = 0; i < from_m_.size(); ++i) a[from_m_[i]] = m[i];
  const double* k = K.valuePtr();
  for (std::size_t i = 0; i < from_k_.size(); ++i) a[from_k_[i]] += s * k[i];
  return A_;
}

}  // namespace nsb
