#include "integrators/d1_minus_linear.hpp"

#include <fmt/format.h>

namespace nsb {

ParamSpecs D1MinusLinear::parameters_spec() {
  return {
      ParamSpec::real("lcp_tol", 1e-12, 0.0, 1e-2, "LCP tolerance when H is not diagonal", true),
      ParamSpec::integer("lcp_max_iter", 10000, 1, 100000000, "LCP iteration cap when H is not diagonal"),
  };
}

D1MinusLinear::D1MinusLinear(const Params& params) : Integrator(params) {
  lcp_.tolerance = params.real("lcp_tol");
  lcp_.max_iterations = params.integer("lcp_max_iter");
}

void D1MinusLinear::init(const Problem& problem, const State& initial) {
  bind(problem, initial);
  const auto m = diagonal_mass(mass_);
  if (!m || !(m->minCoeff() > 0.0))
    throw InputError(fmt::format("integrator d1-minus-linear needs a diagonal mass with positive entries (M^{{-1}} in every stage); problem {} has {}",
                                 problem.name(), m ? "a massless dof" : "a non-diagonal mass"));
  minv_ = m->cwiseInverse();
  L_ = problem.gap_operator();
  contact_ = ImpulseContact(problem, minv_, lcp_);
  const Index n = problem.ndof(), p = L_.rows();
  for (Vec* x : {&f_ext_, &f_now_, &f_next_, &f_int_, &v1_, &v_minus_, &u_start_}) *x = Vec::Zero(n);
  for (Vec* x : {&p1_, &p2_, &impact_, &gap_}) *x = Vec::Zero(p);
  problem.external_force(state_.t, f_ext_);
  started_ = false;
}

void D1MinusLinear::add_impulses(const Vec& impulse, double scale, VecRef v) const {
  for (Index i = 0; i < L_.rows(); ++i)
    if (impulse[i] != 0.0)
      for (decltype(L_)::InnerIterator it(L_, i); it; ++it) v[it.col()] += scale * minv_[it.col()] * it.value() * impulse[i];
}

StepInfo D1MinusLinear::step(double h) {
  StepInfo info;
  info.dt = h;
  if (!started_) {
    problem_->internal_force(state_.u, f_int_);
    ++work_.force_evaluations;
    f_now_ = f_ext_ - f_int_;
    started_ = true;
  }
  // Left: Euler predictor with the contact forces of the contacts closed at U_k.
  v1_.noalias() = state_.v + h * minv_.cwiseProduct(f_now_);
  // (e = 0: v_prev does not enter.)
  long iterations = contact_.apply(state_.u, v1_, v1_, p1_, info, work_, 0.0);
  u_start_ = state_.u;
  state_.u.noalias() += 0.5 * h * (state_.v + v1_);
  state_.t += h;

  if (!problem_->external_force_is_constant()) problem_->external_force(state_.t, f_ext_);
  problem_->internal_force(state_.u, f_int_);
  ++work_.force_evaluations;
  f_next_ = f_ext_ - f_int_;

  gap_.noalias() = L_ * state_.u;
  gap_ += problem_->gap_offset();
  bool impact = false;
  for (Index i = 0; i < L_.rows() && !impact; ++i)
    impact = gap_[i] <= 0.0 && L_.row(i).dot(v1_) < 0.0;

  v_minus_.noalias() = state_.v + 0.5 * h * minv_.cwiseProduct(f_now_ + f_next_);
  if (impact) {
    p1_.setZero();
    p2_.setZero();
  } else {
    add_impulses(p1_, 0.5, v_minus_);
    iterations += contact_.apply(u_start_, v_minus_, v_minus_, p2_, info, work_, 0.0);
  }
  state_.v = v_minus_;
  iterations += contact_.apply(state_.u, v_minus_, state_.v, impact_, info, work_, problem_->restitution());
  impulses_ = impact_ + 0.5 * p1_ + p2_;

  std::swap(f_now_, f_next_);
  info.iterations = iterations;
  work_.lcp_iterations += iterations;
  ++work_.steps;
  return info;
}

}  // namespace nsb
