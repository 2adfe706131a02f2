#include "integrators/moreau_jean.hpp"
#include "integrators/registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace nsb {

ParamSpecs MoreauJean::parameters_spec() {
  ParamSpecs specs = {
      ParamSpec::real("theta", 0.5, 0.5, 1.0, "theta of the theta-method"),
      ParamSpec::choice("projection", "none", {"none", "position"}, "position: project U_{k+1} onto g >= 0 after the step (Acary 2013)"),
  };
  const ParamSpecs lcp = lcp_parameter_specs();
  specs.insert(specs.end(), lcp.begin(), lcp.end());
  return specs;
}

MoreauJean::MoreauJean(const Params& params)
    : Integrator(params), theta_(params.real("theta")), project_positions_(params.choice("projection") == "position") {
  lcp_ = lcp_options(params);
}

void MoreauJean::init(const Problem& problem, const State& initial) {
  bind(problem, initial);
  const Index n = problem.ndof();
  problem.tangent_stiffness(state_.u, K_);
  ++work_.tangent_evaluations;
  L_ = problem.gap_operator();
  response_.assign(L_.rows(), Vec());
  f_int_ = Vec::Zero(n);
  f_ext_now_ = Vec::Zero(n);
  f_ext_next_ = Vec::Zero(n);
  rhs_ = Vec::Zero(n);
  v_free_ = Vec::Zero(n);
  gap_ = Vec::Zero(L_.rows());
  gdot_ = Vec::Zero(L_.rows());
  problem.external_force(state_.t, f_ext_now_);
  f_ext_next_ = f_ext_now_;
  pattern_analyzed_ = false;
  h_factored_ = 0.0;
  solver_.setMode(Eigen::CholmodSimplicialLLt);  // no BLAS: see the header
  solver_.cholmod().print = 1;  // errors only: "not positive definite" is handled by the LU fallback
}

void MoreauJean::factorize(double h) {
  W_ = mass_ + (h * h * theta_ * theta_) * K_;
  if (!pattern_analyzed_) {
    solver_.analyzePattern(W_);
    pattern_analyzed_ = true;
  }
  solver_.factorize(W_);
  ++work_.factorizations;
  use_lu_ = solver_.info() != Eigen::Success;
  if (use_lu_) {
    lu_.compute(W_);
    ++work_.extra["lu_fallbacks"];
    if (lu_.info() != Eigen::Success)
      throw std::runtime_error("moreau-jean: iteration matrix M + h^2 theta^2 K is singular");
  }
  h_factored_ = h;
  for (auto& r : response_) r.resize(0);
}

Vec MoreauJean::solve(const Vec& rhs) { return use_lu_ ? Vec(lu_.solve(rhs)) : Vec(solver_.solve(rhs)); }

const Vec& MoreauJean::contact_response(Index i) {
  Vec& r = response_[i];
  if (r.size() == 0) {
    Vec li = Vec::Zero(problem_->ndof());
    for (decltype(L_)::InnerIterator it(L_, i); it; ++it) li[it.col()] = it.value();
    r = solve(li);
    ++work_.linear_solves;
  }
  return r;
}

StepInfo MoreauJean::step(double h) {
  StepInfo info;
  info.dt = h;
  if (problem_->is_linear()) {
    if (h != h_factored_) factorize(h);
  } else {
    problem_->tangent_stiffness(state_.u, K_);
    ++work_.tangent_evaluations;
    factorize(h);
  }
  problem_->internal_force(state_.u, f_int_);
  ++work_.force_evaluations;
  if (!problem_->external_force_is_constant()) problem_->external_force(state_.t + h, f_ext_next_);

  rhs_.noalias() = h * (theta_ * f_ext_next_ + (1.0 - theta_) * f_ext_now_ - f_int_);
  rhs_.noalias() -= (h * h * theta_) * (K_ * state_.v);
  v_free_ = solve(rhs_);
  v_free_ += state_.v;
  ++work_.linear_solves;

  // Active set from the predicted gap.
  const Vec& g0 = problem_->gap_offset();
  const double e = problem_->restitution();
  gap_.noalias() = L_ * state_.u;
  gap_ += g0;
  gdot_.noalias() = L_ * state_.v;
  active_.clear();
  for (Index i = 0; i < L_.rows(); ++i)
    if (gap_[i] + h * (1.0 - theta_) * gdot_[i] <= 0.0) active_.push_back(i);

  impulses_.setZero();
  v_next_ = v_free_;
  if (!active_.empty()) {
    const Index a = static_cast<Index>(active_.size());
    Eigen::MatrixXd D(a, a);
    Vec q(a), x = Vec::Zero(a);
    for (Index c = 0; c < a; ++c) {
      const Vec& r = contact_response(active_[c]);
      for (Index row = 0; row < a; ++row) D(row, c) = L_.row(active_[row]).dot(r);
    }
    for (Index row = 0; row < a; ++row)
      q[row] = L_.row(active_[row]).dot(v_free_) + e * gdot_[active_[row]];
    const LcpResult res = solve_lcp(D, q, x, lcp_);
    info.iterations = res.iterations;
    work_.lcp_iterations += res.iterations;
    double& max_residual = work_.extra["lcp_max_residual"];
    max_residual = std::max(max_residual, res.residual);
    if (!res.converged) {
      info.converged = false;
      ++work_.lcp_unconverged;
    }
    for (Index c = 0; c < a; ++c) {
      if (x[c] == 0.0) continue;
      impulses_[active_[c]] = x[c];
      v_next_.noalias() += x[c] * contact_response(active_[c]);
    }
  }
  state_.u.noalias() += h * (theta_ * v_next_ + (1.0 - theta_) * state_.v);
  if (project_positions_) {
    const LcpResult res = contact_correction(L_, g0, state_.u, nu_, {}, true,
                                             [this](Index i) -> const Vec& { return contact_response(i); }, lcp_, work_);
    info.iterations += res.iterations;
    if (!res.converged) info.converged = false;
  }
  std::swap(state_.v, v_next_);
  state_.t += h;
  std::swap(f_ext_now_, f_ext_next_);
  if (problem_->external_force_is_constant()) f_ext_next_ = f_ext_now_;
  ++work_.steps;
  return info;
}

NSBENCH_INTEGRATOR({"moreau-jean", "Moreau-Jean theta-method, velocity-level LCP with Newton restitution", &MoreauJean::parameters_spec, &make_from_params<Integrator, MoreauJean>, false});

}  // namespace nsb
