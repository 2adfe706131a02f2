#include "integrators/cd_lagrange.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace nsb {

ParamSpecs CdLagrange::parameters_spec() {
  return {
      ParamSpec::real("lcp_tol", 1e-12, 0.0, 1e-2, "LCP tolerance when H is not diagonal", true),
      ParamSpec::integer("lcp_max_iter", 10000, 1, 100000000, "LCP iteration cap when H is not diagonal"),
  };
}

CdLagrange::CdLagrange(const Params& params) : Integrator(params) {
  lcp_.tolerance = params.real("lcp_tol");
  lcp_.max_iterations = params.integer("lcp_max_iter");
}

void CdLagrange::init(const Problem& problem, const State& initial) {
  bind(problem, initial);
  const auto diag = diagonal_mass(mass_);
  if (!diag)
    throw InputError(fmt::format("integrator cd-lagrange needs a diagonal mass matrix; problem {} has a non-diagonal one", problem.name()));
  m_ = *diag;
  if ((m_.array() <= 0.0).any())
    throw InputError(fmt::format("integrator cd-lagrange needs positive masses; problem {} has massless dofs", problem.name()));
  minv_ = m_.cwiseInverse();

  const Index n = problem.ndof();
  u_prev_ = state_.u;
  v_prev_ = state_.v;
  f_int_ = Vec::Zero(n);
  f_ext_ = Vec::Zero(n);
  problem.external_force(state_.t, f_ext_);
  L_ = problem.gap_operator();
  gap_ = Vec::Zero(L_.rows());

  const SpMat H = SpMat(problem.gap_operator() * minv_.asDiagonal() * problem.gap_operator().transpose());
  h_diag_ = H.diagonal();
  h_is_diagonal_ = true;
  for (Index j = 0; j < H.outerSize(); ++j)
    for (SpMat::InnerIterator it(H, j); it; ++it)
      if (it.row() != it.col() && it.value() != 0.0) h_is_diagonal_ = false;
  if (!h_is_diagonal_) h_full_ = Eigen::MatrixXd(H);
  started_ = false;
}

StepInfo CdLagrange::step(double tau) {
  StepInfo info;
  info.dt = tau;
  if (!started_) {
    problem_->internal_force(state_.u, f_int_);
    ++work_.force_evaluations;
    state_.v += 0.5 * tau * minv_.cwiseProduct(f_ext_ - f_int_);
    started_ = true;
  }
  std::swap(u_prev_, state_.u);
  state_.u.noalias() = u_prev_ + tau * state_.v;
  state_.t += tau;

  problem_->internal_force(state_.u, f_int_);
  ++work_.force_evaluations;
  if (!problem_->external_force_is_constant()) problem_->external_force(state_.t, f_ext_);

  std::swap(v_prev_, state_.v);
  state_.v.noalias() = v_prev_ + tau * minv_.cwiseProduct(f_ext_ - f_int_);  // v_free

  info.iterations = solve_contacts(info);
  work_.lcp_iterations += info.iterations;
  ++work_.steps;
  return info;
}

long CdLagrange::solve_contacts(StepInfo& info) {
  const Vec& g0 = problem_->gap_offset();
  const double e = problem_->restitution();
  gap_.noalias() = L_ * state_.u;
  impulses_.setZero();
  if (h_is_diagonal_) {
    for (Index i = 0; i < L_.rows(); ++i) {
      if (g0[i] + gap_[i] > 0.0) continue;
      double gdot_free = 0.0, gdot_prev = 0.0;
      for (decltype(L_)::InnerIterator it(L_, i); it; ++it) {
        gdot_free += it.value() * state_.v[it.col()];
        gdot_prev += it.value() * v_prev_[it.col()];
      }
      const double lambda = std::max(0.0, -(gdot_free + e * gdot_prev) / h_diag_[i]);
      if (lambda == 0.0) continue;
      impulses_[i] = lambda;
      for (decltype(L_)::InnerIterator it(L_, i); it; ++it)
        state_.v[it.col()] += minv_[it.col()] * it.value() * lambda;
    }
    return 0;
  }
  // Coupled contacts (H not diagonal): LCP on the closed ones.
  std::vector<Index> closed;
  for (Index i = 0; i < L_.rows(); ++i)
    if (g0[i] + gap_[i] <= 0.0) closed.push_back(i);
  if (closed.empty()) return 0;
  const Index a = static_cast<Index>(closed.size());
  Eigen::MatrixXd D(a, a);
  Vec q(a), x = Vec::Zero(a);
  for (Index r = 0; r < a; ++r) {
    for (Index c = 0; c < a; ++c) D(r, c) = h_full_(closed[r], closed[c]);
    q[r] = L_.row(closed[r]).dot(state_.v) + e * L_.row(closed[r]).dot(v_prev_);
  }
  const LcpResult res = solve_lcp(D, q, x, lcp_);
  if (!res.converged) {
    info.converged = false;
    ++work_.lcp_unconverged;
  }
  for (Index r = 0; r < a; ++r) {
    impulses_[closed[r]] = x[r];
    for (decltype(L_)::InnerIterator it(L_, closed[r]); it; ++it)
      state_.v[it.col()] += minv_[it.col()] * it.value() * x[r];
  }
  return res.iterations;
}

Energy CdLagrange::energy() const {
  if (!started_) return Integrator::energy();
  return {0.5 * v_prev_.dot(m_.cwiseProduct(v_prev_)),
          0.5 * (problem_->potential(u_prev_) + problem_->potential(state_.u))};
}

}  // namespace nsb
