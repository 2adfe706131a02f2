#include "integrators/newmark_lm.hpp"
#include "integrators/registry.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace nsb {

ParamSpecs NewmarkLm::parameters_spec() {
  ParamSpecs specs = {
      ParamSpec::real("beta", 0.25, 0.0, 0.5, "Newmark beta", true),
      ParamSpec::real("gamma", 0.5, 0.5, 1.0, "Newmark gamma"),
  };
  add_implicit_contact_specs(specs);
  return specs;
}

NewmarkLm::NewmarkLm(const Params& params)
    : Integrator(params), beta_(params.real("beta")), gamma_(params.real("gamma")) {}

void NewmarkLm::init(const Problem& problem, const State& initial) {
  bind(problem, initial);
  a_ = initial_acceleration(problem, state_, mass_, "newmark-lm");
  ++work_.force_evaluations;
  implicit_.bind(problem, mass_, state_.u, work_, lcp_options(params_), newton_options(params_), "newmark-lm");
  lambda_ = Vec::Zero(problem.ncontacts());
  f_ext_ = Vec::Zero(problem.ndof());
  problem.external_force(state_.t, f_ext_);  // kept as is when constant
}

StepInfo NewmarkLm::advance(double h) {
  StepInfo info;
  info.dt = h;
  const double c = beta_ * h * h;
  u_pred_ = state_.u + h * state_.v + (h * h * (0.5 - beta_)) * a_;
  if (!problem_->external_force_is_constant()) problem_->external_force(state_.t + h, f_ext_);
  implicit_.solve_step(u_pred_, f_ext_, c, true, u_next_, mu_, info);
  a_next_ = (u_next_ - u_pred_) / c;
  state_.v += h * ((1.0 - gamma_) * a_ + gamma_ * a_next_);
  std::swap(state_.u, u_next_);
  std::swap(a_, a_next_);
  mu_ /= c;  // lambda_{k+1}
  impulses_ = h * ((1.0 - gamma_) * lambda_ + gamma_ * mu_);
  std::swap(lambda_, mu_);
  return info;
}

NSBENCH_INTEGRATOR({"newmark-lm", "Newmark (beta, gamma) with position-level Lagrange multipliers; mass redistribution with a singular mass", &NewmarkLm::parameters_spec, &make_from_params<Integrator, NewmarkLm>, false, false, {.inelastic_only = true}});

}  // namespace nsb
