#include "integrators/impulse_contact.hpp"

#include <algorithm>

namespace nsb {

namespace {

// A with every stored entry 1: for moving contacts, which contacts share a dof depends on
// the pattern, not on the values at one configuration (a product can vanish at U0 only).
SpMat pattern_of(SpMat A) {
  A.coeffs().setOnes();
  return A;
}

}  // namespace

ImpulseContact::ImpulseContact(const Problem& problem, const Vec& minv, LcpOptions lcp)
    : problem_(&problem),
      minv_(minv),
      lcp_(lcp),
      moving_(problem.contacts_move()),
      rows_(problem.contact_geometry()),
      offset_(moving_ ? Vec::Zero(problem.ncontacts()) : problem.gap_offset()) {
  const SpMat L = moving_ ? pattern_of(problem.gap_operator()) : problem.gap_operator();
  const SpMat H = SpMat(L * minv.asDiagonal() * L.transpose());
  h_diag_ = H.diagonal();
  for (Index j = 0; j < H.outerSize(); ++j)
    for (SpMat::InnerIterator it(H, j); it; ++it)
      if (it.row() != it.col() && it.value() != 0.0) h_is_diagonal_ = false;
  if (!h_is_diagonal_) h_full_ = Eigen::MatrixXd(H);
  closed_.reserve(static_cast<std::size_t>(problem.ncontacts()));
  if (moving_) {
    const Index p = problem.ncontacts();
    entries_begin_.assign(static_cast<std::size_t>(p + 1), 0);
    entries_end_.assign(static_cast<std::size_t>(p), 0);
    for (Index i = 0; i < p; ++i) {
      const Index capacity = rows_.normal.row(i).nonZeros() + (rows_.tangent.rows() > 0 ? rows_.tangent.row(i).nonZeros() : 0);
      entries_begin_[static_cast<std::size_t>(i + 1)] = entries_begin_[static_cast<std::size_t>(i)] + capacity;
    }
    entries_.resize(static_cast<std::size_t>(entries_begin_.back()));
  }

  const Contacts& c = problem.contacts();
  friction_ = c.has_friction();
  if (!friction_) return;
  mu_ = c.mu;
  w_ = c.tangent_velocity;
  const Index p = c.size();
  // Interleaved rows N_1, T_1, N_2, T_2, ...: W = C M^{-1} C^T.
  SpMat C(2 * p, problem.ndof());
  std::vector<Eigen::Triplet<double>> entries;
  for (Index i = 0; i < p; ++i) {
    for (RowSpMat::InnerIterator it(rows_.normal, i); it; ++it) entries.emplace_back(2 * i, it.col(), moving_ ? 1.0 : it.value());
    for (RowSpMat::InnerIterator it(rows_.tangent, i); it; ++it) entries.emplace_back(2 * i + 1, it.col(), moving_ ? 1.0 : it.value());
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

void ImpulseContact::gather(Index i) {
  auto k = static_cast<std::size_t>(entries_begin_[static_cast<std::size_t>(i)]);
  const auto keep = [&](Index col, double l, double t) {
    if (l != 0.0 || t != 0.0) entries_[k++] = {col, l, t};
  };
  RowSpMat::InnerIterator l(rows_.normal, i);
  if (!friction_) {
    for (; l; ++l) keep(l.col(), l.value(), 0.0);
  } else {
    for (RowSpMat::InnerIterator t(rows_.tangent, i); l || t;) {
      if (t && (!l || t.col() < l.col())) {
        keep(t.col(), 0.0, t.value());
        ++t;
      } else if (!t || l.col() < t.col()) {
        keep(l.col(), l.value(), 0.0);
        ++l;
      } else {
        keep(l.col(), l.value(), t.value());
        ++l;
        ++t;
      }
    }
  }
  entries_end_[static_cast<std::size_t>(i)] = static_cast<Index>(k);
}

ImpulseContact::Products ImpulseContact::products(Index i, Index j) const {
  Products s;
  const RowEntry *a = gathered_begin(i), *a_end = gathered_end(i), *b = gathered_begin(j), *b_end = gathered_end(j);
  if (a == a_end || b == b_end || a->col > (b_end - 1)->col || b->col > (a_end - 1)->col) return s;  // no shared dof
  while (a != a_end && b != b_end) {
    if (a->col < b->col) {
      ++a;
    } else if (b->col < a->col) {
      ++b;
    } else {
      const double m = minv_[a->col];
      s.nn += a->l * m * b->l;
      s.nt += a->l * m * b->t;
      s.tn += a->t * m * b->l;
      s.tt += a->t * m * b->t;
      ++a;
      ++b;
    }
  }
  return s;
}

double weighted_row_dot(const RowSpMat& A, Index i, const RowSpMat& B, Index j, const Vec& minv) {
  RowSpMat::InnerIterator a(A, i), b(B, j);
  double sum = 0.0;
  while (a && b) {
    if (a.col() < b.col()) {
      ++a;
    } else if (b.col() < a.col()) {
      ++b;
    } else {
      sum += a.value() * minv[a.col()] * b.value();
      ++a;
      ++b;
    }
  }
  return sum;
}

void ImpulseContact::evaluate_at(ConstVecRef u) {
  problem_->evaluate_contacts(u, rows_);
  for (Index i = 0; i < rows_.normal.rows(); ++i) {
    if (!(rows_.gap[i] <= 0.0)) continue;  // open at u: nothing of it is read this step
    gather(i);
    const Products s = products(i, i);
    h_diag_[i] = s.nn;
    if (!friction_) continue;
    w_nt_[i] = s.nt;
    w_tt_[i] = s.tt;
  }
}

void ImpulseContact::couple_closed() {
  const auto a = static_cast<Index>(closed_.size());
  for (Index r = 0; r < a; ++r)
    for (Index c = r; c < a; ++c) {
      const Index i = closed_[r], j = closed_[c];
      const Products s = products(i, j);
      if (!friction_) {
        h_full_(i, j) = h_full_(j, i) = s.nn;
        continue;
      }
      w_full_(2 * i, 2 * j) = w_full_(2 * j, 2 * i) = s.nn;
      w_full_(2 * i, 2 * j + 1) = w_full_(2 * j + 1, 2 * i) = s.nt;
      w_full_(2 * i + 1, 2 * j) = w_full_(2 * j, 2 * i + 1) = s.tn;
      w_full_(2 * i + 1, 2 * j + 1) = w_full_(2 * j + 1, 2 * i + 1) = s.tt;
    }
}

void ImpulseContact::add_impulse(Index i, double n, double t, VecRef v) const {
  if (moving_) {  // the closed contact's gathered nonzeros, not its worst-case pattern
    for (const RowEntry* e = gathered_begin(i); e != gathered_end(i); ++e) v[e->col] += minv_[e->col] * (e->l * n + e->t * t);
    return;
  }
  for (RowSpMat::InnerIterator it(rows_.normal, i); it; ++it) v[it.col()] += minv_[it.col()] * it.value() * n;
  if (t != 0.0)
    for (RowSpMat::InnerIterator it(rows_.tangent, i); it; ++it) v[it.col()] += minv_[it.col()] * it.value() * t;
}

Index ImpulseContact::collect_closed() {
  closed_.clear();
  for (Index i = 0; i < rows_.normal.rows(); ++i)
    if (is_closed(i)) closed_.push_back(i);
  return static_cast<Index>(closed_.size());
}

long ImpulseContact::apply_with_friction(ConstVecRef v_prev, VecRef v, VecRef impulses, VecRef tangential,
                                         StepInfo& info, WorkCounters& work, double e) {
  // Called for closed contacts only: with moving contacts their gathered nonzeros.
  const auto normal_rate = [&](Index i, ConstVecRef x) {
    double r = 0.0;
    if (moving_)
      for (const RowEntry* e = gathered_begin(i); e != gathered_end(i); ++e) r += e->l * x[e->col];
    else
      for (RowSpMat::InnerIterator it(rows_.normal, i); it; ++it) r += it.value() * x[it.col()];
    return r;
  };
  const auto slip_rate = [&](Index i) {
    double r = -w_[i];
    if (moving_)
      for (const RowEntry* e = gathered_begin(i); e != gathered_end(i); ++e) r += e->t * v[e->col];
    else
      for (RowSpMat::InnerIterator it(rows_.tangent, i); it; ++it) r += it.value() * v[it.col()];
    return r;
  };
  if (!friction_coupled_) {
    for (Index i = 0; i < rows_.normal.rows(); ++i) {
      if (!is_closed(i)) continue;
      const CoulombImpulse r = solve_coulomb_local(h_diag_[i], w_nt_[i], w_tt_[i],
                                                   normal_rate(i, v) + e * normal_rate(i, v_prev), slip_rate(i), mu_[i]);
      if (r.normal == 0.0) continue;
      impulses[i] = r.normal;
      tangential[i] = r.tangential;
      add_impulse(i, r.normal, r.tangential, v);
    }
    return 0;
  }
  const Index a = collect_closed();
  if (a == 0) return 0;
  if (moving_) couple_closed();
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
  if (moving_) {
    evaluate_at(u);
  } else {
    rows_.gap.noalias() = rows_.normal * u;
  }
  impulses.setZero();
  if (friction_) {
    tangential.setZero();
    return apply_with_friction(v_prev, v, impulses, tangential, info, work, e);
  }
  if (h_is_diagonal_) {
    for (Index i = 0; i < rows_.normal.rows(); ++i) {
      if (!is_closed(i)) continue;
      double gdot_free = 0.0, gdot_prev = 0.0;
      for (RowSpMat::InnerIterator it(rows_.normal, i); it; ++it) {
        gdot_free += it.value() * v[it.col()];
        gdot_prev += it.value() * v_prev[it.col()];
      }
      const double lambda = std::max(0.0, -(gdot_free + e * gdot_prev) / h_diag_[i]);
      if (lambda == 0.0) continue;
      impulses[i] = lambda;
      for (RowSpMat::InnerIterator it(rows_.normal, i); it; ++it) v[it.col()] += minv_[it.col()] * it.value() * lambda;
    }
    return 0;
  }
  const Index a = collect_closed();
  if (a == 0) return 0;
  if (moving_) couple_closed();
  auto& [D, q, x] = storage_.of_size(a);
  for (Index r = 0; r < a; ++r) {
    for (Index c = 0; c < a; ++c) D(r, c) = h_full_(closed_[r], closed_[c]);
    q[r] = rows_.normal.row(closed_[r]).dot(v) + e * rows_.normal.row(closed_[r]).dot(v_prev);
  }
  const LcpResult res = solve_lcp(D, q, x, lcp_);
  if (!res.converged) {
    info.converged = false;
    ++work.lcp_unconverged;
  }
  for (Index r = 0; r < a; ++r) {
    impulses[closed_[r]] = x[r];
    for (RowSpMat::InnerIterator it(rows_.normal, closed_[r]); it; ++it) v[it.col()] += minv_[it.col()] * it.value() * x[r];
  }
  return res.iterations;
}

}  // namespace nsb
