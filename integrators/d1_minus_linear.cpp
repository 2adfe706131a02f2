#include "integrators/d1_minus_linear.hpp"
#include "integrators/registry.hpp"

#include <fmt/format.h>

namespace nsb {

ParamSpecs D1MinusLinear::parameters_spec() { return lcp_parameter_specs(); }

D1MinusLinear::D1MinusLinear(const Params& params) : Integrator(params), lcp_(lcp_options(params)) {}

void D1MinusLinear::init(const Problem& problem, const State& initial) {
  bind(problem, initial);
  minv_ = mass_.diagonal().cwiseInverse();
  moving_ = problem.contacts_move();
  rows_ = problem.contact_geometry();
  rows_next_ = rows_;
  friction_ = problem.contacts().has_friction();
  cone_ = problem.contacts().has_cone();
  if (cone_) {
    cone_contact_ = ConeContact(problem, minv_, lcp_);
  } else {
    contact_ = ImpulseContact(problem, minv_, lcp_);
  }
  const Index n = problem.ndof(), p = rows_.normal.rows();
  for (Vec* x : {&f_ext_, &a_now_, &a_next_, &f_int_, &v1_, &v_minus_, &u_start_}) *x = Vec::Zero(n);
  gap_ = Vec::Zero(p);
  for (StageImpulses* x : {&p1_, &p2_, &impact_}) x->reset(p);
  problem.external_force(state_.t, f_ext_);
  started_ = false;
}

void D1MinusLinear::StageImpulses::reset(Index p) {
  normal.setZero(p);
  tangential.setZero(p);
  tangential2.setZero(p);
}

void D1MinusLinear::add_impulses(const StageImpulses& p, double scale, VecRef v) const {
  const auto add_row = [&](const Eigen::SparseMatrix<double, Eigen::RowMajor>& rows, Index i, double impulse) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, i); it; ++it)
      v[it.col()] += scale * minv_[it.col()] * it.value() * impulse;
  };
  for (Index i = 0; i < rows_.normal.rows(); ++i) {
    if (p.normal[i] != 0.0) add_row(rows_.normal, i, p.normal[i]);
    if (friction_ && p.tangential[i] != 0.0) add_row(rows_.tangent, i, p.tangential[i]);
    if (cone_ && p.tangential2[i] != 0.0) add_row(rows_.tangent2, i, p.tangential2[i]);
  }
}

long D1MinusLinear::solve_stage(ConstVecRef u, ConstVecRef v_prev, VecRef v, StageImpulses& p, StepInfo& info, double e) {
  if (cone_) return cone_contact_.apply(u, v_prev, v, p.normal, p.tangential, p.tangential2, info, work_, e);
  return contact_.apply(u, v_prev, v, p.normal, p.tangential, info, work_, e);
}

void D1MinusLinear::evaluate_gaps(ConstVecRef u, ContactGeometry& rows) {
  if (moving_) {
    problem_->evaluate_contacts(u, rows);
    gap_ = rows.gap;
    return;
  }
  gap_.noalias() = rows.normal * u;
  gap_ += problem_->gap_offset();
}

StepInfo D1MinusLinear::advance(double h) {
  StepInfo info;
  info.dt = h;
  if (!started_) {
    problem_->internal_force(state_.u, f_int_);
    ++work_.force_evaluations;
    a_now_ = minv_.cwiseProduct(f_ext_ - f_int_);
    evaluate_gaps(state_.u, rows_);
    closed_start_ = (gap_.array() <= 0.0).any();
    started_ = true;
  }
  // Left: V_{k,1} = V_k + h A_k, needed in full only on the contacts' dofs (the contact
  // solves read and write nothing else); U_{k+1} = U_k + h V_k + h^2/2 A_k + h/2 M^{-1} L^T P_1.
  for_contact_dofs([&](Index j) { v1_[j] = state_.v[j] + h * a_now_[j]; });
  long iterations = 0;
  const Index p = rows_.normal.rows();
  p1_.reset(p);
  if (closed_start_) iterations += solve_stage(state_.u, v1_, v1_, p1_, info, 0.0);  // e = 0: v_prev unused
  std::swap(u_start_, state_.u);
  state_.u.noalias() = u_start_ + h * state_.v + (0.5 * h * h) * a_now_;
  add_impulses(p1_, 0.5 * h, state_.u);

  // Right: A_{k+1}, V^- = V_k + h/2 (A_k + A_{k+1}).
  if (!problem_->external_force_is_constant()) problem_->external_force(state_.t + h, f_ext_);
  problem_->internal_force(state_.u, f_int_);
  ++work_.force_evaluations;
  a_next_.noalias() = minv_.cwiseProduct(f_ext_ - f_int_);
  v_minus_.noalias() = state_.v + (0.5 * h) * (a_now_ + a_next_);

  evaluate_gaps(state_.u, rows_next_);
  bool impact = false, closed_end = false;
  for (Index i = 0; i < p; ++i) {
    if (gap_[i] > 0.0) continue;
    closed_end = true;
    double gdot = 0.0;
    for (RowSpMat::InnerIterator it(rows_next_.normal, i); it; ++it) gdot += it.value() * v1_[it.col()];
    impact = impact || gdot < 0.0;
  }
  p2_.reset(p);
  if (impact) {
    p1_.reset(p);
  } else if (closed_start_) {
    add_impulses(p1_, 0.5, v_minus_);
    iterations += solve_stage(u_start_, v_minus_, v_minus_, p2_, info, 0.0);
  }
  // Impact at t_{k+1}, Newton's law against V^-.
  impact_.reset(p);
  std::swap(state_.v, v_minus_);
  if (closed_end) {
    // V^- on the contacts' dofs (all the impact law reads of it) into v1_, no longer needed.
    for_contact_dofs([&](Index j) { v1_[j] = state_.v[j]; });
    iterations += solve_stage(state_.u, v1_, state_.v, impact_, info, problem_->restitution());
  }
  impulses_ = impact_.normal + 0.5 * p1_.normal + p2_.normal;
  if (friction_) tangential_impulses_ = impact_.tangential + 0.5 * p1_.tangential + p2_.tangential;
  if (cone_) tangential_impulses2_ = impact_.tangential2 + 0.5 * p1_.tangential2 + p2_.tangential2;

  std::swap(a_now_, a_next_);
  if (moving_) {  // the rows at U_{k+1} are the next step's at U_k (swapped, no copy)
    rows_.gap.swap(rows_next_.gap);
    rows_.normal.swap(rows_next_.normal);
    rows_.tangent.swap(rows_next_.tangent);
    rows_.tangent2.swap(rows_next_.tangent2);
  }
  closed_start_ = closed_end;
  info.iterations = iterations;
  work_.lcp_iterations += iterations;
  return info;
}

NSBENCH_INTEGRATOR({"d1-minus-linear", "Schindler-Acary D1MinusLinear, half-explicit velocity level, impacts at the step's end", &D1MinusLinear::parameters_spec, &make_from_params<Integrator, D1MinusLinear>, false, false,
                    {.friction = true, .moving_contacts = true, .friction_cone = true, .explicit_step = true, .mass = MassNeed::DiagonalPositive}});

}  // namespace nsb
