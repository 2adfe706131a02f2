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
  closed_.reserve(static_cast<std::size_t>(problem.ncontacts()));

  const Contacts& c = problem.contacts();
  friction_ = c.has_friction();
  if (!friction_) return;
  T_ = c.tangent;
  mu_ = c.mu;
  w_ = c.tangent_velocity;
  const Index p = c.size();
  // Interleaved rows N_1, T_1, N_2, T_2, ...: W = C M^{-1} C^T.
  SpMat C(2 * p, problem.ndof());
  std::vector<Eigen::Triplet<double>> entries;
  for (Index i = 0; i < p; ++i) {
    for (decltype(L_)::InnerIterator it(L_, i); it; ++it) entries.emplace_back(2 * i, it.col(), it.value());
    for (decltype(T_)::InnerIterator it(T_, i); it; ++it) entries.emplace_back(2 * i + 1, it.col(), it.value());
  }
  C.setFromTriplets(entries.begin(), entries.end());
  const SpMat W = SpMat(C * minv.asDiagonal() * C.transpose());
  w_nt_ = Vec::Zero(p);
  w_tt_ = Vec::Zero(p);
  for (Index j = 0; j < W.outerSize(); ++j)
    for (SpMat::InnerIterator it(W, j); it; ++it) {
      if (it.row() / 2 != it.col() / 2) {
        friction_coupled_ = friction_coupled_ || it.value() != 0.0;
      } else if (it.row() == 2 * (j / 2) && it.col() == it.row() + 1) {
        w_nt_[j / 2] = it.value();
      } else if (it.row() == it.col() && it.row() % 2 == 1) {
        w_tt_[j / 2] = it.value();
      }
    }
  if (friction_coupled_) w_full_ = Eigen::MatrixXd(W);
  mu_closed_ = Vec::Zero(p);
}

void ImpulseContact::add_impulse(Index i, double n, double t, VecRef v) const {
  for (decltype(L_)::InnerIterator it(L_, i); it; ++it) v[it.col()] += minv_[it.col()] * it.value() * n;
  if (t != 0.0)
    for (decltype(T_)::InnerIterator it(T_, i); it; ++it) v[it.col()] += minv_[it.col()] * it.value() * t;
}

Index ImpulseContact::collect_closed(const Vec& g0) {
  closed_.clear();
  for (Index i = 0; i < L_.rows(); ++i)
    if (is_closed(i, g0)) closed_.push_back(i);
  return static_cast<Index>(closed_.size());
}

long ImpulseContact::apply_with_friction(ConstVecRef v_prev, VecRef v, VecRef impulses, VecRef tangential,
                                         StepInfo& info, WorkCounters& work, double e) {
  const Vec& g0 = problem_->gap_offset();
  const auto normal_rate = [&](Index i, ConstVecRef x) {
    double r = 0.0;
    for (decltype(L_)::InnerIterator it(L_, i); it; ++it) r += it.value() * x[it.col()];
    return r;
  };
  const auto slip_rate = [&](Index i) {
    double r = -w_[i];
    for (decltype(T_)::InnerIterator it(T_, i); it; ++it) r += it.value() * v[it.col()];
    return r;
  };
  if (!friction_coupled_) {
    for (Index i = 0; i < L_.rows(); ++i) {
      if (!is_closed(i, g0)) continue;
      const CoulombImpulse r = solve_coulomb_local(h_diag_[i], w_nt_[i], w_tt_[i],
                                                   normal_rate(i, v) + e * normal_rate(i, v_prev), slip_rate(i), mu_[i]);
      if (r.normal == 0.0) continue;
      impulses[i] = r.normal;
      tangential[i] = r.tangential;
      add_impulse(i, r.normal, r.tangential, v);
    }
    return 0;
  }
  const Index a = collect_closed(g0);
  if (a == 0) return 0;
  auto& [D, q, x] = storage_.of_size(2 * a);
  for (Index r = 0; r < 2 * a; ++r)
    for (Index c = 0; c < 2 * a; ++c) D(r, c) = w_full_(2 * closed_[r / 2] + r % 2, 2 * closed_[c / 2] + c % 2);
  for (Index k = 0; k < a; ++k) {
    const Index i = closed_[k];
    q[2 * k] = normal_rate(i, v) + e * normal_rate(i, v_prev);
    q[2 * k + 1] = slip_rate(i);
    mu_closed_[k] = mu_[i];
  }
  const LcpResult res = solve_coulomb(D, q, mu_closed_.head(a), x, lcp_);
  if (!res.converged) {
    info.converged = false;
    ++work.lcp_unconverged;
  }
  for (Index k = 0; k < a; ++k) {
    impulses[closed_[k]] = x[2 * k];
    tangential[closed_[k]] = x[2 * k + 1];
    add_impulse(closed_[k], x[2 * k], x[2 * k + 1], v);
  }
  return res.iterations;
}

long ImpulseContact::apply(ConstVecRef u, ConstVecRef v_prev, VecRef v, VecRef impulses, VecRef tangential,
                           StepInfo& info, WorkCounters& work) {
  return apply(u, v_prev, v, impulses, tangential, info, work, problem_->restitution());
}

long ImpulseContact::apply(ConstVecRef u, ConstVecRef v_prev, VecRef v, VecRef impulses, VecRef tangential,
                           StepInfo& info, WorkCounters& work, double e) {
  const Vec& g0 = problem_->gap_offset();
  gap_.noalias() = L_ * u;
  impulses.setZero();
  if (friction_) {
    tangential.setZero();
    return apply_with_friction(v_prev, v, impulses, tangential, info, work, e);
  }
  if (h_is_diagonal_) {
    for (Index i = 0; i < L_.rows(); ++i) {
      if (!is_closed(i, g0)) continue;
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
  const Index a = collect_closed(g0);
  if (a == 0) return 0;
  auto& [D, q, x] = storage_.of_size(a);
  for (Index r = 0; r < a; ++r) {
    for (Index c = 0; c < a; ++c) D(r, c) = h_full_(closed_[r], closed_[c]);
    q[r] = L_.row(closed_[r]).dot(v) + e * L_.row(closed_[r]).dot(v_prev);
  }
  const LcpResult res = solve_lcp(D, q, x, lcp_);
  if (!res.converged) {
    info.converged = false;
    ++work.lcp_unconverged;
  }
  for (Index r = 0; r < a; ++r) {
    impulses[closed_[r]] = x[r];
    for (decltype(L_)::InnerIterator it(L_, closed_[r]); it; ++it) v[it.col()] += minv_[it.col()] * it.value() * x[r];
  }
  return res.iterations;
}

}  // namespace nsb
