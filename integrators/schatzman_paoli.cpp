#include "integrators/schatzman_paoli.hpp"
#include "integrators/registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace nsb {

ParamSpecs SchatzmanPaoli::parameters_spec() {
  ParamSpecs specs = {
      ParamSpec::real("theta", 0.0, 0.0, 0.5, "stiffness weight: 0 explicit (diagonal mass), 1/4 or 1/2 implicit (linear K)"),
  };
  const ParamSpecs lcp = lcp_parameter_specs();
  specs.insert(specs.end(), lcp.begin(), lcp.end());
  return specs;
}

SchatzmanPaoli::SchatzmanPaoli(const Params& params) : Integrator(params), theta_(params.real("theta")) {
  lcp_ = lcp_options(params);
}

void SchatzmanPaoli::init(const Problem& problem, const State& initial) {
  bind(problem, initial);
  const Index n = problem.ndof();
  L_ = problem.gap_operator();
  d_diagonal_ = false;
  if (explicit_()) {
    minv_ = mass_.diagonal().cwiseInverse();
    const SpMat H = SpMat(problem.gap_operator() * minv_.asDiagonal() * problem.gap_operator().transpose());
    d_diagonal_ = true;
    for (Index j = 0; j < H.outerSize(); ++j)
      for (SpMat::InnerIterator it(H, j); it; ++it)
        if (it.row() != it.col() && it.value() != 0.0) d_diagonal_ = false;
    h_diag_ = H.diagonal();
    if (d_diagonal_ && (h_diag_.array() <= 0.0).any())
      throw InputError(fmt::format("integrator schatzman-paoli: problem {} has a contact with an empty row of L", problem.name()));
  } else {
    problem.tangent_stiffness(state_.u, K_);
    ++work_.tangent_evaluations;
    W_.bind(mass_, K_);  // W's pattern, analysed now: a factor too large is refused up front
    chol_.analyze(W_.matrix(), "integrator schatzman-paoli", "W");
  }
  responses_.bind(L_.rows());
  h_factored_ = 0.0;
  f_int_ = Vec::Zero(n);
  f_ext_ = Vec::Zero(n);
  rhs_ = Vec::Zero(n);
  u_next_ = Vec::Zero(n);
  problem.external_force(state_.t, f_ext_);
  started_ = false;
  impulse_before_ = false;
}

void SchatzmanPaoli::factorize(double h) {
  const bool positive = chol_.factorize(W_.assemble(mass_, theta_ * h * h, K_), false);
  ++work_.factorizations;
  if (!positive) throw std::runtime_error("schatzman-paoli: M + theta h^2 K is not positive definite");
  h_factored_ = h;
  responses_.invalidate();
}

void SchatzmanPaoli::solve_in_place(Vec& x) {
  if (explicit_()) {
    x.array() *= minv_.array();
  } else {
    chol_.solve(x, x);
    ++work_.linear_solves;
  }
}

const Vec& SchatzmanPaoli::contact_response(Index i) {
  return responses_.get(L_, i, [this](Vec& r) { solve_in_place(r); });
}

StepInfo SchatzmanPaoli::advance(double h) {
  StepInfo info;
  info.dt = h;
  if (!explicit_() && h != h_factored_) factorize(h);
  if (!problem_->external_force_is_constant()) problem_->external_force(state_.t, f_ext_);
  problem_->internal_force(state_.u, f_int_);
  ++work_.force_evaluations;

  // U_free = 2 U_k - U_{k-1} + s W^{-1} (F_ext,k - F_int(U_k)); the first step takes
  // U_{-1} = U_0 - h v_0 and s = h^2 / 2 (the Taylor start, see the header).
  if (!started_) u_prev_ = state_.u - h * state_.v;
  const double s = started_ ? h * h : 0.5 * h * h;
  if (explicit_()) {
    u_next_.noalias() = 2.0 * state_.u - u_prev_ + s * minv_.cwiseProduct(f_ext_ - f_int_);  // one pass
  } else {
    rhs_ = s * (f_ext_ - f_int_);
    solve_in_place(rhs_);
    u_next_.noalias() = 2.0 * state_.u - u_prev_ + rhs_;
  }

  solve_contacts(h, info);

  // v_{k+1}: second-order backward difference (trapezoidal on the first step); in and just
  // after a step with an impulse the last difference alone (BDF2 would extrapolate the jump).
  const bool impulse = impulses_.size() > 0 && impulses_.maxCoeff() > 0.0;
  const double rh = 1.0 / h;
  if (impulse || impulse_before_) state_.v.noalias() = rh * (u_next_ - state_.u);
  else if (started_) state_.v.noalias() = (1.5 * rh) * u_next_ - (2.0 * rh) * state_.u + (0.5 * rh) * u_prev_;
  else state_.v = 2.0 * (u_next_ - state_.u) / h - state_.v;
  impulse_before_ = impulse;
  std::swap(u_prev_, state_.u);
  std::swap(state_.u, u_next_);
  started_ = true;
  return info;
}

void SchatzmanPaoli::solve_contacts(double h, StepInfo& info) {
  const Vec& g0 = problem_->gap_offset();
  const double e = problem_->restitution();
  impulses_.setZero();
  // q_i = (1 + e) g0_i + L_i (U_free + e U_{k-1}): the constraint of the step times 1 + e.
  const auto q_of = [&](Index i) {
    double q = (1.0 + e) * g0[i];
    for (decltype(L_)::InnerIterator it(L_, i); it; ++it) q += it.value() * (u_next_[it.col()] + e * u_prev_[it.col()]);
    return q;
  };
  if (d_diagonal_) {
    for (Index i = 0; i < L_.rows(); ++i) {
      const double R = std::max(0.0, -q_of(i) / h_diag_[i]);
      if (R == 0.0) continue;
      impulses_[i] = R / h;
      for (decltype(L_)::InnerIterator it(L_, i); it; ++it) u_next_[it.col()] += minv_[it.col()] * it.value() * R;
    }
    return;
  }
  active_.clear();
  for (Index i = 0; i < L_.rows(); ++i)
    if (q_of(i) <= 0.0) active_.push_back(i);
  if (active_.empty()) return;
  const Index a = static_cast<Index>(active_.size());
  auto& [D, q, R] = lcp_storage_.of_size(a);
  for (Index c = 0; c < a; ++c) {
    const Vec& r = contact_response(active_[c]);
    for (Index row = 0; row < a; ++row) D(row, c) = L_.row(active_[row]).dot(r);
    q[c] = q_of(active_[c]);
  }
  const LcpResult res = solve_lcp(D, q, R, lcp_);
  info.iterations = res.iterations;
  work_.lcp_iterations += res.iterations;
  if (!res.converged) {
    info.converged = false;
    ++work_.lcp_unconverged;
  }
  for (Index c = 0; c < a; ++c) {
    if (R[c] == 0.0) continue;
    impulses_[active_[c]] = R[c] / h;
    u_next_.noalias() += R[c] * contact_response(active_[c]);
  }
}

NSBENCH_INTEGRATOR({"schatzman-paoli", "Schatzman-Paoli two-step scheme, position-level impact law (theta = 0: explicit, Carpenter-Taylor-Katona for e = 0)", &SchatzmanPaoli::parameters_spec, &make_from_params<Integrator, SchatzmanPaoli>, false, false,
                    {.linear_only = true}, {"theta", 0.0, {.explicit_step = true, .mass = MassNeed::DiagonalPositive}}});

}  // namespace nsb
