#include "integrators/cone_contact.hpp"

namespace nsb {

ConeContact::ConeContact(const Problem& problem, const Vec& minv, LcpOptions lcp)
    : problem_(&problem),
      minv_(minv),
      lcp_(lcp),
      moving_(problem.contacts_move()),
      e_(problem.restitution()),
      rows_(problem.contact_geometry()),
      offset_(moving_ ? Vec::Zero(problem.ncontacts()) : problem.gap_offset()) {
  const Contacts& c = problem.contacts();
  mu_ = c.mu;
  w1_ = c.tangent_velocity;
  w2_ = c.tangent2_velocity;
  // Which contacts share a (massive) dof, from the stored pattern of all three rows.
  std::vector<Index> owner(static_cast<std::size_t>(problem.ndof()), -1);
  for (Index i = 0; i < c.size() && !coupled_; ++i)
    for (int k = 0; k < 3; ++k)
      for (RowSpMat::InnerIterator it(rows_of(k), i); it; ++it) {
        if (minv_[it.col()] == 0.0) continue;
        Index& o = owner[static_cast<std::size_t>(it.col())];
        if (o >= 0 && o != i) coupled_ = true;
        o = i;
      }
  closed_.reserve(static_cast<std::size_t>(c.size()));
  mu_closed_ = Vec::Zero(c.size());
}

double ConeContact::row_dot(int k, Index i, ConstVecRef x) const {
  double r = 0.0;
  for (RowSpMat::InnerIterator it(rows_of(k), i); it; ++it) r += it.value() * x[it.col()];
  return r;
}

double ConeContact::weighted_dot(int k, Index i, int l, Index j) const {
  return weighted_row_dot(rows_of(k), i, rows_of(l), j, minv_);
}

Eigen::Matrix3d ConeContact::block(Index i, Index j) const {
  Eigen::Matrix3d W;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) W(k, l) = weighted_dot(k, i, l, j);
  return W;
}

Eigen::Vector3d ConeContact::free_velocity(Index i, ConstVecRef v_prev, ConstVecRef v, double e) const {
  return {row_dot(0, i, v) + e * row_dot(0, i, v_prev), row_dot(1, i, v) - w1_[i], row_dot(2, i, v) - w2_[i]};
}

void ConeContact::add_impulse(Index i, const Eigen::Vector3d& lambda, VecRef v) const {
  for (int k = 0; k < 3; ++k)
    if (lambda[k] != 0.0)
      for (RowSpMat::InnerIterator it(rows_of(k), i); it; ++it) v[it.col()] += minv_[it.col()] * it.value() * lambda[k];
}

long ConeContact::apply(ConstVecRef u, ConstVecRef v_prev, VecRef v, VecRef normal, VecRef tangential,
                        VecRef tangential2, StepInfo& info, WorkCounters& work) {
  return apply(u, v_prev, v, normal, tangential, tangential2, info, work, e_);
}

long ConeContact::apply(ConstVecRef u, ConstVecRef v_prev, VecRef v, VecRef normal, VecRef tangential,
                        VecRef tangential2, StepInfo& info, WorkCounters& work, double e) {
  if (moving_) {
    problem_->evaluate_contacts(u, rows_);
  } else {
    rows_.gap.noalias() = rows_.normal * u;
  }
  normal.setZero();
  tangential.setZero();
  tangential2.setZero();
  closed_.clear();
  for (Index i = 0; i < rows_.normal.rows(); ++i)
    if (offset_[i] + rows_.gap[i] <= 0.0 && weighted_dot(0, i, 0, i) != 0.0) closed_.push_back(i);
  const Index a = static_cast<Index>(closed_.size());
  if (a == 0) return 0;
  const auto record = [&](Index i, const Eigen::Vector3d& lambda) {
    normal[i] = lambda[0];
    tangential[i] = lambda[1];
    tangential2[i] = lambda[2];
    add_impulse(i, lambda, v);
  };
  if (!coupled_) {
    for (const Index i : closed_) {
      const ConeSolve r = solve_cone(block(i, i), free_velocity(i, v_prev, v, e), mu_[i]);
      if (!r.converged) {
        info.converged = false;
        ++work.lcp_unconverged;
      }
      record(i, {r.impulse.normal, r.impulse.tangential.x(), r.impulse.tangential.y()});
    }
    return 0;
  }
  auto& [D, q, x] = storage_.of_size(3 * a);
  for (Index r = 0; r < a; ++r) {
    for (Index c = 0; c < a; ++c) D.block<3, 3>(3 * r, 3 * c) = block(closed_[r], closed_[c]);
    q.segment<3>(3 * r) = free_velocity(closed_[r], v_prev, v, e);
  }
  for (Index r = 0; r < a; ++r) mu_closed_[r] = mu_[closed_[r]];
  const LcpResult res = solve_coulomb_cone(D, q, mu_closed_.head(a), x, lcp_);
  if (!res.converged) {
    info.converged = false;
    ++work.lcp_unconverged;
  }
  for (Index r = 0; r < a; ++r) record(closed_[r], x.segment<3>(3 * r));
  return res.iterations;
}

}  // namespace nsb
