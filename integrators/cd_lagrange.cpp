#include "integrators/cd_lagrange.hpp"

#include <fmt/format.h>


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
  contact_ = ImpulseContact(problem, minv_, lcp_);
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

  info.iterations = contact_.apply(state_.u, v_prev_, state_.v, impulses_, info, work_);
  work_.lcp_iterations += info.iterations;
  ++work_.steps;
  return info;
}

Energy CdLagrange::energy() const {
  if (!started_) return Integrator::energy();
  return {0.5 * v_prev_.dot(m_.cwiseProduct(v_prev_)),
          0.5 * (problem_->potential(u_prev_) + problem_->potential(state_.u))};
}

}  // namespace nsb
