#include "integrators/impulse_contact.hpp"

#include <algorithm>

namespace nsb {

ImpulseContact::ImpulseContact(const Problem& problem, const Vec& minv, LcpOptions lcp)
    : problem_(&problem), minv_(minv), lcp_(lcp), L_(problem.gap_operator()), gap_(Vec::Zero(problem.ncontacts())) {
  const SpMat H = SpMat(problem.gap_operator() * minv.asDiagonal() * problem.gap_operator().transpose());
  h_diag_ = H.diagonal();
  for (Index j = 0; j < H.outerSize(); ++j)
    for (SpMat::InnerIterator it(H, j); it; ++it)
      if (it.row() != it.col() && it.value() != 0.0) h_is_diagonal_ = false;
  if (!h_is_diagonal_) h_full_ = Eigen::MatrixXd(H);
}

long ImpulseContact::apply(ConstVecRef u, ConstVecRef v_prev, VecRef v, VecRef impulses, StepInfo& info,
                           WorkCounters& work) {
  return apply(u, v_prev, v, impulses, info, work, problem_->restitution());
}

long ImpulseContact::apply(ConstVecRef u, ConstVecRef v_prev, VecRef v, VecRef impulses, StepInfo& info,
                           WorkCounters& work, double e) {
  const Vec& g0 = problem_->gap_offset();
  gap_.noalias() = L_ * u;
  impulses.setZero();
  if (h_is_diagonal_) {
    for (Index i = 0; i < L_.rows(); ++i) {
      if (g0[i] + gap_[i] > 0.0 || h_diag_[i] == 0.0) continue;
      double gdot_free = 0.0, gdot_prev = 0.0;
      for (decltype(L_)::InnerIterator it(L_, i); it; ++it) {
        gdot_free += it.value() * v[it.col()];
        gdot_prev += it.value() * v_prev[it.col()];
      }
      const double lambda = std::max(0.0, -(gdot_free + e * gdot_prev) / h_diag_[i]);
      if (lambda == 0.0) continue;
      impulses[i] = lambda;
      for (decltype(L_)::InnerIterator it(L_, i); it; ++it) v[it.col()] += minv_[it.col()] * it.value() * lambda;
    }
    return 0;
  }
  std::vector<Index> closed;
  for (Index i = 0; i < L_.rows(); ++i)
    if (g0[i] + gap_[i] <= 0.0 && h_diag_[i] != 0.0) closed.push_back(i);
  if (closed.empty()) return 0;
  const Index a = static_cast<Index>(closed.size());
  Eigen::MatrixXd D(a, a);
  Vec q(a), x = Vec::Zero(a);
  for (Index r = 0; r < a; ++r) {
    for (Index c = 0; c < a; ++c) D(r, c) = h_full_(closed[r], closed[c]);
    q[r] = L_.row(closed[r]).dot(v) + e * L_.row(closed[r]).dot(v_prev);
  }
  const LcpResult res = solve_lcp(D, q, x, lcp_);
  if (!res.converged) {
    info.converged = false;
    ++work.lcp_unconverged;
  }
  for (Index r = 0; r < a; ++r) {
    impulses[closed[r]] = x[r];
    for (decltype(L_)::InnerIterator it(L_, closed[r]); it; ++it) v[it.col()] += minv_[it.col()] * it.value() * x[r];
  }
  return res.iterations;
}

}  // namespace nsb
