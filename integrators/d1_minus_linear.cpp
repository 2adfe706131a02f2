#include "integrators/d1_minus_linear.hpp"
#include "integrators/registry.hpp"

#include <fmt/format.h>

namespace nsb {

ParamSpecs D1MinusLinear::parameters_spec() { return lcp_parameter_specs(); }

D1MinusLinear::D1MinusLinear(const Params& params) : Integrator(params), lcp_(lcp_options(params)) {}

void D1MinusLinear::init(const Problem& problem, const State& initial) {
  bind(problem, initial);
  minv_ = mass_.diagonal().cwiseInverse();
  L_ = problem.gap_operator();
  friction_ = problem.contacts().has_friction();
  if (friction_) T_ = problem.contacts().tangent;
  contact_ = ImpulseContact(problem, minv_, lcp_);
  const Index n = problem.ndof(), p = L_.rows();
  for (Vec* x : {&f_ext_, &a_now_, &a_next_, &f_int_, &v1_, &v_minus_, &u_start_}) *x = Vec::Zero(n);
  for (Vec* x : {&p1_, &p2_, &impact_, &gap_, &p1_t_, &p2_t_, &impact_t_}) *x = Vec::Zero(p);
  problem.external_force(state_.t, f_ext_);
  started_ = false;
}

void D1MinusLinear::add_impulses(const Vec& normal, const Vec& tangential, double scale, VecRef v) const {
  for (Index i = 0; i < L_.rows(); ++i) {
    if (normal[i] != 0.0)
      for (decltype(L_)::InnerIterator it(L_, i); it; ++it) v[it.col()] += scale * minv_[it.col()] * it.value() * normal[i];
    if (friction_ && tangential[i] != 0.0)
      for (decltype(T_)::InnerIterator it(T_, i); it; ++it) v[it.col()] += scale * minv_[it.col()] * it.value() * tangential[i];
  }
}

StepInfo D1MinusLinear::advance(double h) {
  StepInfo info;
  info.dt = h;
  if (!started_) {
    problem_->internal_force(state_.u, f_int_);
    ++work_.force_evaluations;
    a_now_ = minv_.cwiseProduct(f_ext_ - f_int_);
    gap_.noalias() = L_ * state_.u;
    gap_ += problem_->gap_offset();
    closed_start_ = (gap_.array() <= 0.0).any();
    started_ = true;
  }
  // Left: V_{k,1} = V_k + h A_k, needed in full only on the contacts' dofs (the contact
  // solves read and write nothing else); U_{k+1} = U_k + h V_k + h^2/2 A_k + h/2 M^{-1} L^T P_1.
  for_contact_dofs([&](Index j) { v1_[j] = state_.v[j] + h * a_now_[j]; });
  long iterations = 0;
  p1_.setZero();
  p1_t_.setZero();
  if (closed_start_) iterations += contact_.apply(state_.u, v1_, v1_, p1_, p1_t_, info, work_, 0.0);  // e = 0: v_prev unused
  std::swap(u_start_, state_.u);
  state_.u.noalias() = u_start_ + h * state_.v + (0.5 * h * h) * a_now_;
  add_impulses(p1_, p1_t_, 0.5 * h, state_.u);

  // Right: A_{k+1}, V^- = V_k + h/2 (A_k + A_{k+1}).
  if (!problem_->external_force_is_constant()) problem_->external_force(state_.t + h, f_ext_);
  problem_->internal_force(state_.u, f_int_);
  ++work_.force_evaluations;
  a_next_.noalias() = minv_.cwiseProduct(f_ext_ - f_int_);
  v_minus_.noalias() = state_.v + (0.5 * h) * (a_now_ + a_next_);

  gap_.noalias() = L_ * state_.u;
  gap_ += problem_->gap_offset();
  bool impact = false, closed_end = false;
  for (Index i = 0; i < L_.rows(); ++i) {
    if (gap_[i] > 0.0) continue;
    closed_end = true;
    double gdot = 0.0;
    for (decltype(L_)::InnerIterator it(L_, i); it; ++it) gdot += it.value() * v1_[it.col()];
    impact = impact || gdot < 0.0;
  }
  p2_.setZero();
  p2_t_.setZero();
  if (impact) {
    p1_.setZero();
    p1_t_.setZero();
  } else if (closed_start_) {
    add_impulses(p1_, p1_t_, 0.5, v_minus_);
    iterations += contact_.apply(u_start_, v_minus_, v_minus_, p2_, p2_t_, info, work_, 0.0);
  }
  // Impact at t_{k+1}, Newton's law against V^-.
  impact_.setZero();
  impact_t_.setZero();
  std::swap(state_.v, v_minus_);
  if (closed_end) {
    // V^- on the contacts' dofs (all the impact law reads of it) into v1_, no longer needed.
    for_contact_dofs([&](Index j) { v1_[j] = state_.v[j]; });
    iterations += contact_.apply(state_.u, v1_, state_.v, impact_, impact_t_, info, work_, problem_->restitution());
  }
  impulses_ = impact_ + 0.5 * p1_ + p2_;
  if (friction_) tangential_impulses_ = impact_t_ + 0.5 * p1_t_ + p2_t_;

  std::swap(a_now_, a_next_);
  closed_start_ = closed_end;
  info.iterations = iterations;
  work_.lcp_iterations += iterations;
  return info;
}

NSBENCH_INTEGRATOR({"d1-minus-linear", "Schindler-Acary D1MinusLinear, half-explicit velocity level, impacts at the step's end", &D1MinusLinear::parameters_spec, &make_from_params<Integrator, D1MinusLinear>, false, false,
                    {.friction = true, .explicit_step = true, .mass = MassNeed::DiagonalPositive}});

}  // namespace nsb
