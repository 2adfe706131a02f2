#include "integrators/nsga.hpp"
#include "integrators/registry.hpp"

#include <limits>

namespace nsb {

ParamSpecs Nsga::parameters_spec() {
  ParamSpecs specs = {
      ParamSpec::real("rho_inf", 1.0, 0.0, 1.0, "spectral radius at infinity (1: no numerical dissipation)"),
  };
  add_implicit_contact_specs(specs);
  return specs;
}

Nsga::Nsga(const Params& params) : Integrator(params) {
  const double rho = params.real("rho_inf");
  alpha_m_ = (2.0 * rho - 1.0) / (rho + 1.0);
  alpha_f_ = rho / (rho + 1.0);
  gamma_ = 0.5 + alpha_f_ - alpha_m_;
  beta_ = 0.25 * (gamma_ + 0.5) * (gamma_ + 0.5);
}

void Nsga::init(const Problem& problem, const State& initial) {
  bind(problem, initial);
  a_ = initial_acceleration(problem, state_, mass_, "nsga");
  ++work_.force_evaluations;
  abar_ = a_;
  newton_ = newton_options(params_);
  implicit_.bind(problem, mass_, state_.u, work_, lcp_options(params_), newton_, "nsga");
  moving_ = problem.contacts_move();
  f_ext_ = Vec::Zero(problem.ndof());
  problem.external_force(state_.t, f_ext_);  // kept as is when constant
}

StepInfo Nsga::advance(double h) {
  StepInfo info;
  info.dt = h;
  const double e = problem_->restitution();
  if (moving_ && e != 0.0) {  // e L(U_k) V_k: the restitution term at the step's start rows
    implicit_.evaluate_contacts_at(state_.u);
    restitution_rate_.noalias() = e * (implicit_.normal_rows() * state_.v);
  }
  const double bh2 = beta_ * h * h;
  const double c = bh2 * (1.0 - alpha_f_) / (1.0 - alpha_m_);
  // Smooth step: M (Q - U_hat) + c (F_int(Q) - F_ext) = 0, the equation of motion at t_{k+1}
  // multiplied by c, with a_{k+1} and abar_{k+1} eliminated through Q.
  u_pred_ = state_.u + h * state_.v + (h * h * (0.5 - beta_)) * abar_;
  u_hat_ = u_pred_ - (bh2 / (1.0 - alpha_m_)) * (alpha_m_ * abar_ - alpha_f_ * a_);
  if (!problem_->external_force_is_constant()) problem_->external_force(state_.t + h, f_ext_);
  implicit_.solve_step(u_hat_, f_ext_, c, false, q_, nu_, info);
  abar_next_ = (q_ - u_pred_) / bh2;
  a_ = ((1.0 - alpha_m_) * abar_next_ + alpha_m_ * abar_ - alpha_f_ * a_) / (1.0 - alpha_f_);
  w_ = state_.v + h * ((1.0 - gamma_) * abar_ + gamma_ * abar_next_);
  std::swap(abar_, abar_next_);

  // Contacts the smooth step closes, before the position correction opens them.
  if (moving_) {
    b_ = implicit_.evaluate_contacts_at(q_);
  } else {
    b_.noalias() = problem_->gap_operator() * q_;
    b_ += problem_->gap_offset();
  }
  closing_.clear();
  for (Index i = 0; i < b_.size(); ++i)
    if (b_[i] <= 0.0) closing_.push_back(i);

  if (moving_) {
    correct_positions_on_moving_rows(info);
  } else {
    const LcpResult pos = implicit_.correct(problem_->gap_offset(), q_, nu_, {}, true);
    info.iterations += pos.iterations;
    if (!pos.converged) info.converged = false;
  }
  if (closing_.empty()) {
    impulses_.setZero();
    tangential_impulses_.setZero();
    tangential_impulses2_.setZero();
  } else {
    if (moving_) {
      implicit_.evaluate_contacts_at(q_);  // the rows at U_{k+1}
      if (e != 0.0) b_ = restitution_rate_;
      else b_.setZero();
    } else {
      b_.noalias() = e * (problem_->gap_operator() * state_.v);
    }
    const LcpResult vel = problem_->contacts().has_friction()
                              ? implicit_.correct_with_friction(b_, w_, impulses_, tangential_impulses_, tangential_impulses2_, closing_)
                              : implicit_.correct(b_, w_, impulses_, closing_, false);
    info.iterations += vel.iterations;
    if (!vel.converged) info.converged = false;
  }
  std::swap(state_.u, q_);
  std::swap(state_.v, w_);
  return info;
}

void Nsga::correct_positions_on_moving_rows(StepInfo& info) {
  q_smooth_ = q_;
  const double eps = std::numeric_limits<double>::epsilon();
  for (long it = 0; it < newton_.max_iterations; ++it) {
    // Rows and gap at the iterate x_j = q_: 0 <= nu _|_ g(x_j) + L(x_j) (U - x_j) >= 0,
    // U = Q + S^{-1} L(x_j)^T nu.
    const Vec& g = implicit_.evaluate_contacts_at(q_);
    offset_.noalias() = g - implicit_.normal_rows() * q_;
    std::swap(q_previous_, q_);
    q_ = q_smooth_;
    const LcpResult pos = implicit_.correct(offset_, q_, nu_, {}, true);
    info.iterations += pos.iterations;
    if (!pos.converged) info.converged = false;
    const double change = (q_ - q_previous_).cwiseAbs().maxCoeff();
    if (change <= newton_.tolerance * (q_ - q_smooth_).cwiseAbs().maxCoeff() + 100.0 * eps * q_.cwiseAbs().maxCoeff()) return;
  }
  info.converged = false;
  ++work_.extra["position_newton_unconverged"];
}

NSBENCH_INTEGRATOR({"nsga", "nonsmooth generalised-alpha (Bruls-Acary-Cardona 2014): position correction and velocity impact law, rho_inf", &Nsga::parameters_spec, &make_from_params<Integrator, Nsga>, false, false, {.friction = true, .moving_contacts = true, .friction_cone = true}});

}  // namespace nsb
